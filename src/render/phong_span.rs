//! The Phong span kernel: per-span set-up, per-pixel table lookups.
//!
//! [`PhongKernel`] is made per object (the band renderer: once a band)
//! from a [`Shade`] (material and lights in eye space) of the `Q16`
//! profiles, its specular table taken from a [`SpecCache`] when one of
//! the same shininess is at hand (the band renderer keeps one a frame:
//! measured on the dodecahedron Phong frame's 10 bands, 52 972
//! instructions less on the M4, 145 435 on the M0); per span,
//! [`PhongKernel::begin`] takes the interpolated normal (`Q30` raw, the
//! layout's [`UNIT_FRAC_BITS`](crate::num::UNIT_FRAC_BITS)) and eye
//! position (`Q16` raw) at the span's first pixel and their steps per
//! pixel, and [`PhongSpan::next`] gives one pixel after another.
//!
//! # Interpolation of the normal
//! Planar, as the rest of the crate: the normal is the screen-linear
//! interpolation of the vertex normals, `n(i) = n0 + i·dn`, *not*
//! renormalised before it is interpolated (the seed's "normalise the span
//! ends, then interpolate" weighs the ends differently, see
//! `tests/seed_phong.rs`). It is the `f64` twin's model, so the kernel is
//! compared with its twin on the same quantity, and it is what makes
//! Duff's formulation possible: every dot product of `n` with a constant
//! vector is linear in `i` and `|n|²` is quadratic.
//!
//! # Directional lights, viewer at infinity (Duff)
//! With `L` and `V` constant the specular base is written as a quadratic
//! over `|n|²`, so that it needs no precise normalisation at all:
//!
//! ```text
//! Phong:  1 - R·V   = ( |n × (L+V)|² + (n·(L-V))² ) / (2 |n|²)       x^n = (1 - w)^n
//! Blinn:  1 - (N·H)² = |n × H|² / |n|²                                x^n = (1 - w)^(n/2)
//! ```
//!
//! (`|n × S|² = |n|²|S|² - (n·S)²` and `(n·S)² - (n·D)² = 4 (n·L)(n·V)`
//! give the first; `N·H > 0` is checked on the linear `n·H`). The
//! numerator `Q` is a sum of squares of linear functions of `i`, each
//! vanishing at the highlight's peak, so the rounding of their linear
//! coefficients (`2^-31` per step) enters `Q` multiplied by their small
//! values there: `w = Q/|n|²` keeps its *relative* accuracy where `x^n`
//! needs it (`n = 10 000`), and `1/|n|²` needs only ~12 bits. Per span:
//! `|n|²` and `Q` as exact `u64` forward differences, `n·L` linear. With
//! one light ([`PhongKernel::fill`], the renderer's loop) they become
//! 32-bit forward differences re-seeded exactly every 32 pixels (module
//! `one`: `|n|²` in Q30, `K·Q` in Q20 table segments, both within their
//! proven range per chunk, chunks whose `Q` is provably past the table
//! skip the specular term, the rest per pixel in 64 bits; a full
//! chunk's set-up with its length a constant, so that the products by it
//! fold into shifts; a span of more than one chunk and at most
//! `one::WHOLE_MAX` pixels whose whole length is proven as a chunk is
//! runs with that single plan, its 32-bit state stepped on from chunk to
//! chunk without re-seeding: `2^-15` of `|n|²` and `2^-5` of a table
//! segment at most, tested); measured on the firmware's span sweep, 81.91
//! instructions a pixel on the M4 (148.94 on the M0; before the single
//! plan 86.52 and 169.72; was 167, 106.97, 104.88, 94.63 with
//! the channels in the loop of the depth test, then 92.23, 90.95, 89.31;
//! then `1/|n|` from one load of a packed table, `one::RS_PACKED`, whose
//! address stays in a register, `|n|²` stepped less `1/4`, and no `n·L`
//! test a pixel in chunks where `n·L` is positive at both ends) and
//! 169.25 on the M0 (was 207.96, 198.87, 184.50, 169.37, 174.93, 175.22,
//! 175.71 with the row fill out of line; the sweep's figure is
//! the 200-pixel spans less the 1-pixel ones, and the latter now cost 570
//! instructions less on the M4 and 2 318 less on the M0: the 200-pixel
//! spans alone went from 96.8 to 92.7 a pixel on the M4 and from 186.2
//! to 180.1 on the M0). Spans shorter than 4 pixels (`one::SHORT_SPAN`)
//! skip the span and chunk set-up: the depth test of each pixel, then the
//! 64-bit path for the passing ones. A span with a single plan, and
//! each chunk of the others, runs as one loop a pixel (`Out::fused`, one
//! per pixel and depth format): the depth test (without the depth clamp
//! on spans of 8 pixels or more whose depths are in range), for a
//! passing pixel its light terms (`N·L` and the specular factor, packed;
//! on the M4 each channel two `SMLABB`/`SMLATT` of the packed terms,
//! flipped to signed halves, by the packed coefficients, see
//! `one::Colour`) and the sums encoded straight from Q19 by
//! [`PixelFormat::encode_q19`] (for RGB565 one `USAT` a channel), then
//! the state stepped: 77.54 instructions a pixel on the M4 and 141.48 on
//! the M0 (81.38 and 148.99 with a pass for the terms into a buffer, a
//! pass of depth tests into a bit mask and a pass of colours). The loop
//! holds ~25 values (the 32-bit state and its steps, 8; the depth, its
//! step and the two slices' positions, 5; the tables, 2; the colour
//! constants, 6; temporaries) in 14 registers: ~56 instructions of
//! arithmetic a pixel, the rest reloads. (Measured and not kept: the
//! colour constants read from memory at each pixel, 83.41 and 86.46;
//! the depth loop alone out of line, 90.66; the channels as `MLA`s without packing,
//! 81.34; `1/|n|`'s packed entries in the other order, 80.52; the
//! terms into a buffer and one loop of depth test and colour, 83.52.)
//! Per pixel: `1/|n|` from a 65-entry
//! table over `|n|² ∈ [1/4, 5/4)` ([`RSQRT_N`]), `N·L = n·L / |n|`, the
//! table position `m·w` and the specular table ([`SPEC_SEGMENTS`]
//! segments of `(1 - u/m)^m` for `u ∈ [0, min(m, 8)]`, built when the
//! kernel is made for that shininess, so `n = 10 000` keeps its peak).
//! The one-light loop (module `one`, and its 64-bit per-pixel path, so
//! that both give the same values) reads `1/|n|` and `1/|n|²` instead
//! from one load of a 2048-entry table without interpolation
//! (`one::RN`, 8 KB of flash: `2^14/|n|` and `2^13/|n|²` as the 16-bit
//! halves of a word, at the middle of each segment): no interpolation
//! and no square a pixel; measured on the span sweep 71.30 -> 65.74
//! instructions a pixel on the M4 and 141.32 -> 129.38 on the M0 (at
//! 1024 entries, 4 KB, 66.25 on the M4, but the bunny's mean error
//! against its `f64` twin in `tests/profiles_vs_twin.rs` rose from 0.0237
//! to 0.0275 level, past its bound 0.025; 0.0246 at 2048, 0.0239 at 4096;
//! every firmware CRC and reference image unchanged). On the M4 the
//! one-light loop now holds only its stepped values in registers and
//! reloads its invariants (tables' addresses, steps, colour constants)
//! from one block of the frame behind an opaque address (`one::Inv`):
//! 62.80 -> 57.97 instructions a pixel on the span sweep.
//!
//! Two to eight directional lights (viewer at infinity) run the same
//! chunks and per-light arithmetic (module `multi`): each light's exact
//! state and chunk plan as one light's, `1/|n|` once a pixel, then light
//! after light its terms added to the pixel's channel sums (two signed
//! 16-bit multiply-adds a channel on the M4), the offsets of the packed
//! form in the sums' start. Taken when every channel sum stays below
//! `2^31` with each light at its largest terms (eight white lights of
//! `Ip·kd = Ip·ks = 0.9`; beyond, the per-pixel path of
//! [`PhongKernel::begin`]); a span whose lights all have a single plan
//! (as one light's above) steps their 32-bit states on from chunk to
//! chunk. Measured on the firmware's span sweep, per pixel with 1, 2 and
//! 4 lights: 81.91, 181.58 and 289.49 instructions on the M4, 148.94,
//! 326.58 and 544.72 on the M0 (with a plan a chunk: 86.52, 196.49 and
//! 316.20 on the M4, 169.72, 356.07 and 592.59 on the M0; the per-pixel
//! path before: 280.33 and 434.96 with 2 and 4 on the M4, 392.94 and
//! 643.29 on the M0): each
//! light beyond the second adds 54.0 a pixel on the M4 and 109.1 on the
//! M0 (its terms and its channel sums; 59.9 and 118.3 with its share of
//! the chunk plans).
//! (The test-free lit chunks of one light made this loop slower, 201.13
//! and 324.98 on the M4 with 2 and 4 lights, 203.40 and 329.11 with the
//! packed `1/|n|` table too, 198.43 and 319.67 with the table alone: not
//! taken here.)
//!
//! # Point lights, local viewer
//! `l = Lp - p` and `v = -p` are linear per pixel and `|l|²`, `|v|²`
//! quadratic (exact forward differences in `u64`); their reciprocal square
//! roots come from the table of [`approx16::rsqrt_newton`] (one Newton
//! step: `2^-29` relative), which makes unit `L` and `V` in `Q30` with
//! three products each; the specular base is then the same sum of squares
//! (`L + V` and `L - V` per pixel). No general normalisation. One point
//! light with a local viewer and the Phong model at shininess below 256
//! ([`PhongKernel::fill`], the renderer's loop) runs the 32-bit loop of
//! module `point` instead: the six quadratics `|n|²`, `|l|²`, `|v|²`,
//! `n·l`, `n·v`, `l·v` as per-chunk forward differences, `1/|l|` and
//! `1/|v|` by a series step seeded from the two previous pixels; measured
//! on the firmware's span sweep, 176.38 instructions a pixel on the M4
//! (was 517, 219.06, 205.85 with the channels in the loop of the depth
//! test, then 203.69, 192.15, 191.05 with a set-up a chunk) and 698.56 on
//! the M0 (was 1 357, 797.56, 776.22, then 772.15, 765.99, 763.10), a
//! span of more than one chunk set up once and stepped from chunk to
//! chunk by shifts (module `point`'s plan), a single chunk's set-up
//! (`point_setup`, ~900 instructions on the M4) a function of its own,
//! spans below 8 pixels a pixel at a time by the same arithmetic
//! (`point_one`, ~280 instructions a pixel on the M4);
//! its buffers (256 bytes) live in
//! its own frames, zeroed once a span and a chunk, so that the other
//! shaders' span stages do not carry them (the 640 bytes kept by the
//! shader before cost 8 a pixel less on the M4 and 19 more on the M0).
//!
//! In the renderers (the position layout) the six quadratics are set up
//! once a triangle instead ([`TriQuad`], module `tri`): `n`, `l = Lp -
//! p` and `v = -p` are affine in the pixel's `(x, y)` over a triangle
//! (the normal's and the position's planes through its vertices), so
//! `|n|²`, `|l̃|²`, `|ṽ|²`, `n·l̃`, `n·ṽ`, `l̃·ṽ` are quadratics of `(x,
//! y)`, multiplied out exactly in 64 bits from the planes rounded to
//! integer coefficients, their ranges proven once over the triangle
//! (convexity: the largest value at a vertex, the tangent plane at the
//! centroid below), `l̃` and `ṽ` scaled by powers of two chosen a
//! triangle. Per span: each quadratic's row start stepped by forward
//! differences in y from the span of the row above (three 64-bit
//! additions), its value and differences at the span's first pixel (two
//! products by the offset along the row), in the loop's units times
//! `2^32` (the 32-bit state is their high words): no vectors, scaling or
//! range test a span. Spans below 4 pixels keep `point_one`; a set-up
//! is made at a triangle's first longer span in the band. Measured
//! (dodecahedron Phong raster, M4 and M0; span sweep phong-kpoint):
//! 1 886 263 -> 1 848 422 and 6 256 609 -> 5 911 473; 176.38 -> 169.48 and
//! 698.55 -> 661.69 a pixel. Where the steps of `l̃` and `ṽ` are at
//! most 1/64 of their lengths (a triangle's or span's chunks "fine",
//! module `point`) each pixel takes a first-order step instead of the
//! series: 161.72 -> 154.02 a pixel on the M4, 497.06 -> 490.37 on the
//! M0, frames unchanged. The loop itself (~93 instructions a pixel
//! on the M4, ~570 on the M0) is unchanged and now the floor: with the
//! channels (~24), the row and band walk and the set-ups (~4 800 a
//! triangle and band on the M4) the frame stays above its budget.
//!
//! # Positions
//! The position layout's eye positions come walked by the rasterizer,
//! whose steps are rounded to a raw `Q16` unit; at shininess
//! [`PLANE_MIN_SHININESS`] or more the renderers give each span's start
//! from the triangle's exact position plane instead ([`PosPlane`], made
//! once a triangle, exact at the span's middle pixel): measured on the
//! highlight-peak set, `fast` 3 levels from its twin -> 1 at shininess
//! 10 000, no cost in the span loop (the start is set before it).
//!
//! # Accuracy (tests in this module)
//! Against the same model in `f64` on the same inputs, per channel: within
//! 1 level for shininess 1 to 10 000, peaks and grazing lights included
//! (the table interpolation `2^-11` at 128 segments, `1/|n|` `2^-11.4`
//! relative at `|n|² = 1/4`, `2^-15.4` at 1, the coefficients' rounding
//! `1/128` level). The one-light loop's `1/|n|` ([`crate::num::rsqrt_pair_table`]
//! at 2048 entries) is within `2^-10.97` relative over the range and
//! `2^-12.38` for `|n|² >= 3/4`, its `1/|n|²` within `2^-9.98` and
//! `2^-11.40` (tested: `one::tests::rn_table_within_bound`); measured
//! within 1 level of `f64` on the same sets.
//!
//! # Limits
//! Coefficients `Ip·Lc·kd·C` and `Ip·Lc·ks` up to 4 and shininess from 1
//! to [`MAX_SHININESS`](crate::illum::MAX_SHININESS): outside those,
//! [`PhongKernel::new`] gives [`KernelError`] and the caller keeps the
//! generic path. Pixels whose `|n|²` lies outside `[1/4, 5/4)` (vertex
//! normals more than 120° apart within a triangle) take the generic
//! per-pixel path (`Shade::at_q16`), as do spans whose positions leave
//! `±2^30` raw.

use crate::illum::{RawTerm, Shade, Specular, Viewer, MAX_LIGHTS};
use crate::num::approx16;
use crate::num::wide::{clz32, wmul};
use crate::num::{light_halves, scale255, unit30, Raw16, Real};
use crate::raster::{Lerp, RasterError, Span, Spans};
use crate::target::{level_q19, DepthBuffer, DepthFormat, PixelFormat, Rgb8, Target};
use core::fmt;

/// Segments of the specular table (`SPEC_SEGMENTS + 1` entries of `u16`):
/// chosen from the sweep in this module's tests (`spec_table_sweep`).
pub const SPEC_SEGMENTS: usize = 128;
/// Segments of the `1/|n|` table over `|n|² ∈ [1/4, 5/4)`.
pub const RSQRT_N: usize = 64;
/// Fraction bits of a specular table position.
const POS_FRAC: u32 = 20;
/// Largest table argument `u = m·w` (Q16): `e^-8 < 2^-11`.
const U_MAX: u32 = 8 << 16;

/// `1/sqrt(f)` in Q16 for `f = 1/4 + j/64`, `j` in `0..=64`: `2^19 /
/// sqrt(16 + j)`, floor of the square root of the floor (within `2^-16`
/// absolute): [`crate::num::rsqrt_quarter_table`] at 65 entries.
const RS: [u32; RSQRT_N + 1] = crate::num::rsqrt_quarter_table::<{ RSQRT_N + 1 }>();

/// Why a kernel could not be made (the caller keeps the generic path).
/// The kernel exists for `Q16` shades only, by type: [`PhongKernel::new`]
/// takes a `Shade<Q16>`, [`PhongKernel::new_cached`] the `Raw16` access
/// that only [`Q16`](crate::num::Q16)'s kernels hand out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum KernelError {
    /// A coefficient above 4, or a shininess below 1.
    Range,
}

impl fmt::Display for KernelError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Range => write!(
                f,
                "a light coefficient above 4 or a shininess below 1 (Phong span kernel)"
            ),
        }
    }
}

impl core::error::Error for KernelError {}

/// A span's planes at its first pixel and their steps a pixel, as the
/// kernel's loops take them: the normal `n` and its step `dn`, the
/// position `p` and its step `dp`.
type Planes = ([i32; 3], [i32; 3], [i32; 3], [i32; 3]);

/// One light folded for the kernel.
#[derive(Clone, Copy, Debug)]
struct KLight {
    /// Directional: unit direction (Q30). Point: position (Q16).
    at: [i32; 3],
    point: bool,
    /// Directional lights, viewer at infinity: `P1` (Phong `(L+V)/√2`,
    /// Blinn `H`) and `P2` (Phong `(L-V)/√2`), Q30.
    p1: [i32; 3],
    p2: [i32; 3],
    /// `255 · 2^6 ·` the diffuse and specular coefficients per channel
    /// (below 2^16).
    d: [u32; 3],
    s: [u32; 3],
    /// `255 · 2^4 ·` the same (below 2^14): the 32-bit loop's (narrow:
    /// the kernel lives in the renderer's frame).
    d4: [i16; 3],
    s4: [i16; 3],
}

/// Material, lights and tables of one object for one frame (see the
/// module docs).
#[derive(Clone, Debug)]
pub struct PhongKernel<'s, R> {
    shade: &'s Shade<R>,
    lights: heapless::Vec<KLight, MAX_LIGHTS>,
    /// `255 · 2^13 ·` ambient per channel.
    amb: [u32; 3],
    spec: bool,
    blinn: bool,
    /// All lights directional and the viewer at infinity.
    duff: bool,
    local: bool,
    /// Specular table, Q15; the two entries past the last segment are 0
    /// (positions beyond the table give no specular term).
    table: [u16; SPEC_SEGMENTS + 2],
    /// Table position per `Q` (Q8): `K = m · SPEC_SEGMENTS / min(m, 8)`
    /// times 2^8, below 2^26 (`m <= 10 000`).
    kf: u32,
    /// Spans take their start position from the triangle's
    /// [`PosPlane`]: a specular term at shininess [`PLANE_MIN_SHININESS`]
    /// or more, and positions interpolated (a point light or a local
    /// viewer).
    plane: bool,
    /// `255 · 2^19 ·` ambient per channel plus `2^18` (rounding), for the
    /// 32-bit loop of one directional light ([`PhongKernel::fill`]).
    amb19: [i32; 3],
    /// Two or more directional lights, viewer at infinity, whose channel
    /// sums stay below `2^31` (module `multi`): the sums' start, the
    /// ambient term (as `amb19`) plus `2^15 (d + s)` of every light.
    multi: Option<[i32; 3]>,
    /// `Q` (Q28) at or above `2^(15 + sq)`: no specular term.
    sq: u32,
    /// Table position per `Q · 1/|n|²`: `(rr14 · c16) >> cb`.
    c16: u32,
    cb: u32,
    /// The colour constants of the first light (`one::Colour::of`),
    /// made once a kernel for the point loop's triangle spans
    /// (`PhongKernel::fill_point_tri`) instead of once a span: dodecahedron
    /// Phong raster M4 1 660 949 -> 1 651 911. Not on ARMv6-M: the 64
    /// bytes more in the kernel cost it elsewhere (cubes-and-sphere raster
    /// 9 045 264 -> 9 062 195, span sweep phong-kpoint 490.37 -> 494.81 a
    /// pixel) more than the 1 003 they saved in the dodecahedron's.
    #[cfg(not(armv6m))]
    colour: Option<one::Colour>,
    /// The specular table for the one-light loop other than on ARMv6-M
    /// ([`one::pack_table`]; all zero for other kernels): entry `j` is
    /// `table[j] | (table[j] - table[j + 1]) << 16`, one load a pixel for
    /// both values.
    #[cfg(not(armv6m))]
    packed: [u32; SPEC_SEGMENTS + 1],
}

/// A specular table kept from one kernel to the next of the same
/// shininess ([`PhongKernel::new_cached`]): the renderer keeps one per
/// frame, so that its bands do not rebuild it (128 entries from
/// `approx16::spec_entry_q` per kernel).
#[derive(Clone, Debug)]
pub struct SpecCache {
    /// The table's `m` (Q16: the shininess, halved for Blinn) as its
    /// high and low halves: 2-byte alignment, so that the renderer's
    /// state keeps its other fields where they were (a 4-byte field
    /// moved them on the M0, beyond its short load offsets).
    m: [u16; 2],
    table: [u16; SPEC_SEGMENTS + 2],
}

impl SpecCache {
    /// The key of `m`.
    #[allow(clippy::cast_possible_truncation)]
    fn key(m: u32) -> [u16; 2] {
        [(m >> 16) as u16, m as u16]
    }
}

/// The specular table of `m` (Q16, `>= 1`; see [`PhongKernel`]'s
/// `table`).
#[allow(clippy::cast_possible_truncation)]
fn spec_table(m: u32) -> [u16; SPEC_SEGMENTS + 2] {
    let t_eff = m.min(U_MAX);
    let mut table = [0u16; SPEC_SEGMENTS + 2];
    // The last entry (u = min(m, 8)) is 0: exactly for m <= 8,
    // and e^-8 < 2^-11 dropped for larger m.
    // u = t_eff · j / SEGMENTS, floored (a power of two: a shift);
    // for m >= 8, u = 2^12 j and q = floor(u · 2^16 / m) steps by
    // the quotient and remainder of 2^28 / m (one division).
    let step = (m >= U_MAX).then(|| (((1u32 << 28) / m), (1u32 << 28) % m));
    let (mut q, mut rem) = (0u32, 0u32);
    for (j, e) in table.iter_mut().enumerate().take(SPEC_SEGMENTS) {
        let u = ((u64::from(t_eff) * j as u64) >> SPEC_SEGMENTS.trailing_zeros()) as u32;
        *e = match step {
            Some((sq_, sr)) => {
                let v = approx16::spec_entry_q(u, m, Some(u64::from(q)));
                q += sq_;
                rem += sr;
                if rem >= m {
                    q += 1;
                    rem -= m;
                }
                v
            }
            None => approx16::spec_entry(u, m),
        };
    }
    table
}

impl<'s> PhongKernel<'s, crate::num::Q16> {
    /// The kernel of `shade`.
    ///
    /// # Errors
    /// [`KernelError::Range`] for a coefficient above 4 or a shininess
    /// below 1 with a specular term.
    pub fn new(shade: &'s Shade<crate::num::Q16>) -> Result<Self, KernelError> {
        Self::new_cached(Raw16::Q16, shade, &mut None)
    }
}

impl<'s, R: Real> PhongKernel<'s, R> {
    /// [`PhongKernel::new`] for a shade of any real that has the integer
    /// kernels (`q`, handed out by [`Kernels::pick`](crate::num::Kernels::pick)
    /// for `Q16` only), taking its specular table from `cache` when that
    /// holds the table of the same shininess, else building it and keeping
    /// it there (the same kernel either way).
    ///
    /// # Errors
    /// As [`PhongKernel::new`].
    pub fn new_cached(
        q: Raw16<R>,
        shade: &'s Shade<R>,
        cache: &mut Option<SpecCache>,
    ) -> Result<Self, KernelError> {
        let (ambient, terms, shin, spec, model, viewer) = shade.raw_q16(q);
        let blinn = model == Specular::Blinn;
        let local = viewer == Viewer::Local;
        if spec && shin < 1 << 16 {
            return Err(KernelError::Range);
        }
        let amb = ambient.map(|a| scale255(a, 13) as u32);
        let mut lights = heapless::Vec::new();
        for t in &terms {
            let RawTerm {
                at,
                point,
                diffuse,
                specular,
            } = *t;
            let conv = |c: [i32; 3]| -> Result<[u32; 3], KernelError> {
                let mut o = [0u32; 3];
                for (o, &c) in o.iter_mut().zip(c.iter()) {
                    let v = scale255(c, 6);
                    *o = u16::try_from(v).map_err(|_| KernelError::Range)?.into();
                }
                Ok(o)
            };
            let d = conv(diffuse)?;
            let s = conv(specular)?;
            let (at, p1, p2) = if point {
                (at, [0; 3], [0; 3])
            } else {
                let l = unit30(at.map(i64::from));
                let (p1, p2) = light_halves(l, blinn);
                (l, p1, p2)
            };
            // scale255(c, 4) <= scale255(c, 6) / 4 + 1 < 2^14.
            let d4 = diffuse.map(|c| scale255(c, 4) as i16);
            let s4 = specular.map(|c| scale255(c, 4) as i16);
            let _ = lights.push(KLight {
                at,
                point,
                p1,
                p2,
                d,
                s,
                d4,
                s4,
            });
        }
        let duff = !local && lights.iter().all(|l| !l.point);
        // Specular table and its position scale.
        let m = if blinn {
            (shin as u32) / 2
        } else {
            shin as u32
        }
        .max(1);
        let t_eff = m.min(U_MAX);
        let table = match cache {
            _ if !spec => [0u16; SPEC_SEGMENTS + 2],
            Some(c) if c.m == SpecCache::key(m) => c.table,
            _ => {
                let c = cache.insert(SpecCache {
                    m: SpecCache::key(m),
                    table: spec_table(m),
                });
                c.table
            }
        };
        // K · 2^8 = m · SEGMENTS · 2^8 / t_eff (m, t_eff Q16): <= 2^7 · 2^8
        // for m <= 8, m / 2^19 · 2^7 · 2^8 <= 10 000 · 2^4 · 2^8 < 2^26 above.
        let kf = u32::try_from(
            (u64::from(m) * ((SPEC_SEGMENTS as u64) << 8))
                .checked_div(u64::from(t_eff))
                .unwrap_or(0),
        )
        .ok()
        .filter(|&k| k < 1 << 26)
        .ok_or(KernelError::Range)?;
        let amb19 = ambient.map(|a| (scale255(a, 19) as i32).saturating_add(1 << 18));
        let multi = (duff && lights.len() > 1)
            .then(|| multi::start(amb19, &lights))
            .flatten();
        // qs (Q28 of Q) below 2^(15 + sq) covers every w·nn < 1.25 · t_eff / m.
        let qlim = (u64::from(t_eff) * (5 << 28) / 4)
            .checked_div(u64::from(m))
            .unwrap_or(0)
            + 1;
        let mut sq = 0u32;
        while (1u64 << (15 + sq)) < qlim {
            sq += 1;
        }
        // pos = qs_s · rr14 · X, X = m K / t_eff · 2^(POS_FRAC + sq - 42)
        // = c16 · 2^-cb with c16 < 2^16 and c16 <= 2^cb, so that
        // g = (rr14 · c16) >> cb <= 2^16 and pos = qs_s · g <= 2^31.
        let num = u64::from(m) * SPEC_SEGMENTS as u64; // < 2^38
                                                       // floor(num · 2^e / t_eff) for e <= 24 from one division:
                                                       // floor(floor(x / d) / 2^k) = floor(x / (d · 2^k)).
        let top = (num << 24).checked_div(u64::from(t_eff));
        let mut c16 = 0u32;
        let mut cb = 0u32;
        let mut found = false;
        for b in (0..48u32).rev() {
            let e = i64::from(POS_FRAC + sq + b) - 42;
            if e > 24 {
                continue;
            }
            let v = top.map_or(u64::MAX, |t| t.checked_shr((24 - e) as u32).unwrap_or(0));
            if v < 1 << 16 {
                c16 = v as u32;
                cb = b;
                found = v <= 1 << b;
                break;
            }
        }
        if spec && !found {
            return Err(KernelError::Range);
        }
        #[cfg(not(armv6m))]
        let one_light = duff && spec && lights.len() == 1;
        #[cfg_attr(armv6m, allow(unused_mut))]
        let mut k = Self {
            shade,
            lights,
            amb,
            spec,
            blinn,
            duff,
            local,
            table,
            kf,
            plane: spec && !duff && i64::from(shin) >= i64::from(PLANE_MIN_SHININESS) << 16,
            amb19,
            multi,
            sq,
            c16,
            cb,
            #[cfg(not(armv6m))]
            colour: None,
            #[cfg(not(armv6m))]
            packed: if one_light {
                one::pack_table(&table)
            } else {
                [0; SPEC_SEGMENTS + 1]
            },
        };
        #[cfg(not(armv6m))]
        {
            k.colour = k.lights.first().map(|l| one::Colour::of(&k, l));
        }
        Ok(k)
    }

    /// The light of the point loop (module `point`): one point light, a
    /// local viewer and the Phong model at a shininess below 256 (`None`
    /// for other kernels). The renderers set a triangle's quadratics
    /// ([`TriQuad`]) for this kernel.
    fn point_loop_light(&self) -> Option<&KLight> {
        match &self.lights[..] {
            [l] if l.point && self.local && !self.blinn && self.kf < point::KF_MAX => Some(l),
            _ => None,
        }
    }

    /// `true` when the renderers set a triangle's quadratics
    /// ([`TriQuad`]) for this kernel: one point light, a local viewer
    /// and the Phong model at a shininess below 256.
    pub fn wants_tri(&self) -> bool {
        self.point_loop_light().is_some()
    }

    /// `true` when the renderers set the triangle's exact position plane
    /// per triangle for this kernel: a specular term of shininess 512 or
    /// more in the position-walking kernel, where the walked Q16
    /// position's rounding shows in the highlight.
    pub fn wants_plane(&self) -> bool {
        self.plane
    }

    /// Per-span set-up from the interpolated values at the span's first
    /// pixel and their steps per pixel: normal `n`, `dn` (Q30 raw) and,
    /// for the position layout, eye position `p`, `dp` (Q16 raw; zeros for
    /// the normal-only layout); `back` flips the normal.
    #[inline(always)]
    pub fn begin(
        &self,
        n: [i32; 3],
        dn: [i32; 3],
        p: [i32; 3],
        dp: [i32; 3],
        back: bool,
    ) -> PhongSpan<'_, 's, R> {
        let (n, dn) = if back {
            (n.map(i32::wrapping_neg), dn.map(i32::wrapping_neg))
        } else {
            (n, dn)
        };
        let mut ls = [LightSpan::default(); MAX_LIGHTS];
        let (nn, nn_d1, nn_d2) = quad(&[(n, dn)]);
        let (v, dv, vv, vv_d1, vv_d2, slow) = if self.duff {
            for (s, l) in ls.iter_mut().zip(self.lights.iter()) {
                s.nl = lin(n, l.at);
                s.dnl = lin(dn, l.at);
                if self.spec {
                    let c0 = cross(n, l.p1);
                    let c1 = cross(dn, l.p1);
                    let k0 = lin(n, l.p2);
                    let k1 = lin(dn, l.p2);
                    let f = [
                        ([c0[0], 0, 0], [c1[0], 0, 0]),
                        ([c0[1], 0, 0], [c1[1], 0, 0]),
                        ([c0[2], 0, 0], [c1[2], 0, 0]),
                        ([k0, 0, 0], [k1, 0, 0]),
                    ];
                    let (q, d1, d2) = quad(&f);
                    s.q = q;
                    s.q_d1 = d1;
                    s.q_d2 = d2;
                    if self.blinn {
                        s.nh = lin(n, l.p1);
                        s.dnh = lin(dn, l.p1);
                    }
                }
            }
            ([0; 3], [0; 3], 0, 0, 0, false)
        } else {
            let v0 = p.map(i32::wrapping_neg);
            let dv = dp.map(i32::wrapping_neg);
            // `l = Lp - p` stays within ±2^31 along any span of up to
            // 4096 pixels when it starts within ±2^30 and steps by at most
            // 2^18 (4 eye units) a pixel; else (a light near the edge of
            // the coordinate range) the span takes the generic path.
            let far = |v: i64| v.unsigned_abs() > 1 << 30;
            let mut slow = dp.iter().any(|&d| d.unsigned_abs() > 1 << 18)
                || p.iter().any(|&c| far(i64::from(c)));
            for (s, l) in ls.iter_mut().zip(self.lights.iter()) {
                if l.point {
                    slow |= (0..3).any(|a| far(i64::from(l.at[a]) - i64::from(p[a])));
                    s.l = [0, 1, 2].map(|a| l.at[a].wrapping_sub(p[a]));
                    s.dl = dv;
                    let (q, d1, d2) = quad(&[(s.l, s.dl)]);
                    s.q = q;
                    s.q_d1 = d1;
                    s.q_d2 = d2;
                }
            }
            let (vv, vv_d1, vv_d2) = quad(&[(v0, dv)]);
            (v0, dv, vv, vv_d1, vv_d2, slow)
        };
        PhongSpan {
            k: self,
            n0: n,
            dn,
            p0: p,
            dp,
            i: 0,
            n,
            nn,
            nn_d1,
            nn_d2,
            v,
            dv,
            vv,
            vv_d1,
            vv_d2,
            l0: ls[0],
            rest: [ls[1], ls[2], ls[3], ls[4], ls[5], ls[6], ls[7]],
            slow,
        }
    }

    /// A whole span of `len` pixels: for each pixel `i` for which
    /// `test(i)` holds (a depth test), `write(i, colour)`; returns how many
    /// pixels passed. The same colours
    /// as [`PhongKernel::begin`] and [`PhongSpan::next`]/[`PhongSpan::skip`];
    /// one directional light with the viewer at infinity runs a loop whose
    /// state stays in registers (the span-stage hook the kernel is made
    /// for).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn fill(
        &self,
        n: [i32; 3],
        dn: [i32; 3],
        p: [i32; 3],
        dp: [i32; 3],
        back: bool,
        len: u32,
        test: impl FnMut(u32) -> bool,
        write: impl FnMut(u32, Rgb8),
    ) -> u32 {
        self.fill_with(n, dn, p, dp, back, len, FnOut { test, write }, None)
    }

    /// [`PhongKernel::fill`] (the span stages' entry).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn fill_with(
        &self,
        n: [i32; 3],
        dn: [i32; 3],
        p: [i32; 3],
        dp: [i32; 3],
        back: bool,
        len: u32,
        mut out: impl Out,
        tri: Option<(&mut TriQuad, i32, i32)>,
    ) -> u32 {
        if let (true, [l]) = (self.duff, &self.lights[..]) {
            let (n, dn) = if back {
                (n.map(i32::wrapping_neg), dn.map(i32::wrapping_neg))
            } else {
                (n, dn)
            };
            return self.fill_one(l, n, dn, len, out);
        }
        if let Some(start) = self.multi {
            let (n, dn) = if back {
                (n.map(i32::wrapping_neg), dn.map(i32::wrapping_neg))
            } else {
                (n, dn)
            };
            return self.fill_multi(start, n, dn, len, out);
        }
        if let [l] = &self.lights[..] {
            // The triangle's quadratics (`TriQuad`) for spans of
            // `TRI_SHORT_SPAN` pixels or more, where it has them (made at
            // its first such span; its ranges proven over the whole
            // triangle, so no test a span); the walked values' paths
            // otherwise.
            if let (Some((t, x, y)), Some(l)) = (tri, self.point_loop_light()) {
                if len >= point::TRI_SHORT_SPAN && t.wants() && t.ready(l, self.kf) {
                    let (n, dn) = if back {
                        (n.map(i32::wrapping_neg), dn.map(i32::wrapping_neg))
                    } else {
                        (n, dn)
                    };
                    return self.fill_point_tri(l, t, (x, y), (n, dn, p, dp), len, out);
                }
            }
            if l.point && self.local && !self.blinn && self.kf < point::KF_MAX {
                // Positions and light offsets within ±2^29 over the span,
                // steps within 2^18 (the point loop's 64-bit set-up), for
                // spans below 2^13 pixels: `d·len` below 2^31, the sums
                // below 2^32 in i64 (no 64-bit multiply: on ARMv6-M the
                // check was a call of ~370 instructions a span).
                #[inline(always)]
                #[allow(clippy::cast_possible_wrap)]
                fn comp(c: i32, d: i32, lp: i32, len: u32) -> bool {
                    let near = |v: i64| v.unsigned_abs() < 1 << 29;
                    let (c, lp) = (i64::from(c), i64::from(lp));
                    let p1 = c + i64::from(d.wrapping_mul(len as i32));
                    d.unsigned_abs() <= 1 << 18
                        && near(c)
                        && near(p1)
                        && near(lp - c)
                        && near(lp - p1)
                }
                let ok = len < 1 << 13
                    && comp(p[0], dp[0], l.at[0], len)
                    && comp(p[1], dp[1], l.at[1], len)
                    && comp(p[2], dp[2], l.at[2], len);
                if ok {
                    let (n, dn) = if back {
                        (n.map(i32::wrapping_neg), dn.map(i32::wrapping_neg))
                    } else {
                        (n, dn)
                    };
                    return self.fill_point(l, (n, dn, p, dp), len, out);
                }
            }
            return self.fill_general_one(l, n, dn, p, dp, back, len, out);
        }
        let mut s = self.begin(n, dn, p, dp, back);
        let mut passed = 0;
        for i in 0..len {
            if out.test(i) {
                out.write(i, s.next());
                passed += 1;
            } else {
                s.skip();
            }
        }
        passed
    }

    /// [`PhongKernel::fill`] for one light, point or with a local viewer:
    /// the state of [`PhongKernel::begin`] for that light alone, in
    /// locals (no per-span copy of the eight lights' state). Not inlined:
    /// in the renderer's row loop its locals would share a stack frame of
    /// over 1 KB, which ARMv6-M addresses with three instructions a load
    /// (dodecahedron frame 11.3 M -> 9.9 M instructions there), and a copy
    /// per pixel and depth format costs flash (inlined, the M4 frame is 5 %
    /// faster).
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn fill_general_one(
        &self,
        l: &KLight,
        n: [i32; 3],
        dn: [i32; 3],
        p: [i32; 3],
        dp: [i32; 3],
        back: bool,
        len: u32,
        mut out: impl Out,
    ) -> u32 {
        let (n, dn) = if back {
            (n.map(i32::wrapping_neg), dn.map(i32::wrapping_neg))
        } else {
            (n, dn)
        };
        let (mut nn, mut nn_d1, nn_d2) = quad(&[(n, dn)]);
        let mut v = p.map(i32::wrapping_neg);
        let dv = dp.map(i32::wrapping_neg);
        let (mut vv, mut vv_d1, vv_d2) = quad(&[(v, dv)]);
        // As in `begin`: positions and light offsets within ±2^30, steps
        // within 2^18, else the generic path.
        let far = |v: i64| v.unsigned_abs() > 1 << 30;
        let mut slow =
            dp.iter().any(|&d| d.unsigned_abs() > 1 << 18) || p.iter().any(|&c| far(i64::from(c)));
        let mut s = LightSpan::default();
        if l.point {
            slow |= (0..3).any(|a| far(i64::from(l.at[a]) - i64::from(p[a])));
            s.l = [0, 1, 2].map(|a| l.at[a].wrapping_sub(p[a]));
            s.dl = dv;
            (s.q, s.q_d1, s.q_d2) = quad(&[(s.l, s.dl)]);
        }
        let mut nc = n;
        let mut passed = 0;
        for i in 0..len {
            if out.test(i) {
                passed += 1;
                let c = if slow {
                    None
                } else {
                    self.general_px(&s, l, nc, v, vv, nn)
                };
                out.write(
                    i,
                    c.unwrap_or_else(|| fallback(self.shade, n, dn, p, dp, i)),
                );
            }
            step(&mut nn, &mut nn_d1, nn_d2);
            step(&mut vv, &mut vv_d1, vv_d2);
            for a in 0..3 {
                nc[a] = nc[a].wrapping_add(dn[a]);
                v[a] = v[a].wrapping_add(dv[a]);
            }
            general_step(&mut s, l);
        }
        passed
    }

    /// One pixel of one light, point or with a local viewer (`None`:
    /// `|n|²` outside the table, the generic path's).
    #[inline(never)]
    #[allow(clippy::cast_possible_truncation)]
    fn general_px(
        &self,
        s: &LightSpan,
        l: &KLight,
        n: [i32; 3],
        v: [i32; 3],
        vv: u64,
        nn: u64,
    ) -> Option<Rgb8> {
        let r = rsqrt_n((nn >> 32) as i32)?;
        let r14 = r >> 2;
        let rr14 = (r14 * r14) >> 14;
        let vh = if self.local {
            unit_of(v, vv)
        } else {
            [0, 0, 1 << 30]
        };
        let mut acc = self.amb;
        general_light(self, s, l, n, vh, r, rr14, &mut acc);
        Some(Self::level(acc))
    }

    /// The colour for the accumulated channels (units `255 · 2^13`).
    #[inline(always)]
    fn level(acc: [u32; 3]) -> Rgb8 {
        // acc < 2^28 (ambient 2^21, at most 8 lights of 2^24 each).
        let l = |a: u32| ((a as i32).wrapping_add(1 << 12) >> 13).clamp(0, 255) as u8;
        Rgb8::new(l(acc[0]), l(acc[1]), l(acc[2]))
    }

    /// The specular factor (Q15) for `qs` (Q28 of `Q`, with `w = qs / |n|²`)
    /// and `rr14 = 2^14 / |n|²`.
    #[inline(always)]
    fn spec_of(&self, qs: i32, rr14: u32) -> u32 {
        let qs = qs.max(0) as u32 >> self.sq;
        if qs >= 1 << 15 {
            return 0;
        }
        let g = (rr14.wrapping_mul(self.c16)) >> self.cb;
        let pos = qs.wrapping_mul(g);
        let idx = (pos >> POS_FRAC) as usize;
        match (self.table.get(idx), self.table.get(idx + 1)) {
            (Some(&a), Some(&b)) => {
                let f = (pos >> (POS_FRAC - 16)) & 0xFFFF;
                let (a, b) = (u32::from(a), u32::from(b));
                a - ((a.saturating_sub(b) * f) >> 16)
            }
            _ => 0,
        }
    }
}

/// `round(a·b / 2^30)` summed over three components (wrapping: callers
/// keep it within `i32`, unit vectors and normals of length <= 1.25).
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn lin(a: [i32; 3], b: [i32; 3]) -> i32 {
    let s = wmul(a[0], b[0])
        .wrapping_add(wmul(a[1], b[1]))
        .wrapping_add(wmul(a[2], b[2]));
    (s.wrapping_add(1 << 29) >> 30) as i32
}

/// `a × b` in Q30 (rounded) for Q30 `a` and `b`.
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn cross(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    let c = |x: i64| (x.wrapping_add(1 << 29) >> 30) as i32;
    [
        c(wmul(a[1], b[2]) - wmul(a[2], b[1])),
        c(wmul(a[2], b[0]) - wmul(a[0], b[2])),
        c(wmul(a[0], b[1]) - wmul(a[1], b[0])),
    ]
}

/// The sum of squares `Σ |f0 + i·df|²` of linear vector functions as a
/// forward-difference triple `(value, first difference, second
/// difference)`, exact modulo 2^64 (every true value below 2^64 is exact).
#[allow(clippy::cast_sign_loss)]
fn quad(f: &[([i32; 3], [i32; 3])]) -> (u64, u64, u64) {
    let (mut c0, mut c1, mut c2) = (0u64, 0u64, 0u64);
    for (a, d) in f {
        for k in 0..3 {
            c0 = c0.wrapping_add(wmul(a[k], a[k]) as u64);
            c1 = c1.wrapping_add((wmul(a[k], d[k]) as u64).wrapping_mul(2));
            c2 = c2.wrapping_add(wmul(d[k], d[k]) as u64);
        }
    }
    (c0, c1.wrapping_add(c2), c2.wrapping_mul(2))
}

/// Per-light state of a span.
#[derive(Clone, Copy, Debug, Default)]
struct LightSpan {
    nl: i32,
    dnl: i32,
    nh: i32,
    dnh: i32,
    /// Directional: `Q` (Q60). Point: `|l|²` (Q32).
    q: u64,
    q_d1: u64,
    q_d2: u64,
    /// Point: `l = Lp - p` (Q16) and its step.
    l: [i32; 3],
    dl: [i32; 3],
}

/// One span in progress (see [`PhongKernel::begin`]).
#[derive(Debug)]
pub struct PhongSpan<'k, 's, R> {
    k: &'k PhongKernel<'s, R>,
    n0: [i32; 3],
    dn: [i32; 3],
    p0: [i32; 3],
    dp: [i32; 3],
    i: u32,
    n: [i32; 3],
    nn: u64,
    nn_d1: u64,
    nn_d2: u64,
    v: [i32; 3],
    dv: [i32; 3],
    vv: u64,
    vv_d1: u64,
    vv_d2: u64,
    l0: LightSpan,
    rest: [LightSpan; MAX_LIGHTS - 1],
    /// Every pixel by the generic path (positions near the range's edge).
    slow: bool,
}

/// `2^16 / |n|` (Q16) from `|n|²` in Q28 in `[1/4, 5/4)`, else `None`.
#[inline(always)]
fn rsqrt_n(f: i32) -> Option<u32> {
    let j = ((f.wrapping_sub(1 << 26)) >> 22) as u32 as usize;
    let (a, b) = (*RS.get(j)?, *RS.get(j + 1)?);
    let t = ((f >> 6) & 0xFFFF) as u32;
    Some(a - (((a - b) * t) >> 16))
}

/// `1 / sqrt(x)` for `x > 0` as `(y, e)`: `y · 2^-e`, `y` in `[2^29,
/// 2^30]`, within [`RSQRT64_MAX_ERROR`] = `2^-28.5 + 2^-29` relative:
/// [`approx16::rsqrt_newton`]'s `2^-28.5` of the top 32 bits of `x`
/// (the dropped low bits, below `2^-30` of `x`, move the root by less
/// than `2^-31`, inside that bound's margin) plus `2^-29`, the truncation
/// of its result to `y`. Tested over every even shift and random `x`
/// (`rsqrt64_within_max_error`): measured `2^-28.75`.
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn rsqrt64(x: u64) -> (i32, u32) {
    // The top 32 bits of `x << lz` from 32-bit shifts and the crate's
    // `clz32` (ARMv6-M: no 64-bit shift or count-leading-zeros calls).
    let (hi, lo) = ((x >> 32) as u32, x as u32);
    let (lz, m) = if hi != 0 {
        let lz = clz32(hi) & !1; // 0..=30
        let m = if lz == 0 {
            hi
        } else {
            (hi << lz) | (lo >> (32 - lz))
        };
        (lz, m)
    } else {
        let lz = clz32(lo) & !1; // 0..=30 for lo >= 2
        (32 + lz, lo << lz)
    };
    let y = approx16::rsqrt_newton(m) >> 1;
    (y as i32, 61 - lz / 2)
}

/// The largest relative error of [`rsqrt64`]: `2^-28.5 + 2^-29`.
#[cfg_attr(not(test), allow(dead_code))]
const RSQRT64_MAX_ERROR: f64 = 4.496_823_181_161_834e-9;

/// The low 32 bits of `x >> s` for `s` in `0..32` (32-bit shifts only).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn shr_low(x: i64, s: u32) -> i32 {
    let (hi, lo) = ((x >> 32) as u32, x as u32);
    if s == 0 {
        lo as i32
    } else {
        ((lo >> s) | (hi << (32 - s))) as i32
    }
}

/// `v / |v|` in Q30 from `v` and `|v|²` (any common scale).
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn unit_of(v: [i32; 3], vv: u64) -> [i32; 3] {
    if vv == 0 {
        return [0; 3];
    }
    let (y, e) = rsqrt64(vv);
    let s = (e - 30).min(31); // e >= 30
    let f = |c: i32| shr_low(wmul(c, y), s);
    [f(v[0]), f(v[1]), f(v[2])]
}

/// The generic per-pixel path (`Shade::at_q16` on the normalised normal)
/// at pixel `i` of a span (values passed by copy: the span's state stays
/// in registers).
#[cold]
#[inline(never)]
fn fallback<R: Real>(
    shade: &Shade<R>,
    n0: [i32; 3],
    dn: [i32; 3],
    p0: [i32; 3],
    dp: [i32; 3],
    i: u32,
) -> Rgb8 {
    let i = i as i32;
    let n = [0, 1, 2].map(|a| n0[a].wrapping_add(dn[a].wrapping_mul(i)));
    let p = [0, 1, 2].map(|a| p0[a].wrapping_add(dp[a].wrapping_mul(i)));
    // Q30 -> Q16 (as `Profile::unit_back`, rounded), then normalised.
    let n16 = n.map(|c| ((i64::from(c) + (1 << 13)) >> 14) as i32);
    let u = approx16::unit(n16);
    let c = shade.at_q16(u, p);
    let level = |c: i32| R::from_fixed_i32(c, 16).to_level();
    Rgb8::new(level(c[0]), level(c[1]), level(c[2]))
}

/// Adds one light's diffuse and specular terms (factors Q15) to `acc`.
#[inline(always)]
fn add_light(acc: &mut [u32; 3], l: &KLight, nl15: u32, sp: u32) {
    for ((a, d), s) in acc.iter_mut().zip(l.d).zip(l.s) {
        *a = a.wrapping_add((d * nl15).wrapping_add(s * sp) >> 8);
    }
}

/// `N·L` in Q15 from `n·L` (Q30, > 0) and `2^16/|n|`.
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
fn nl15(nl: i32, r: u32) -> u32 {
    ((nl as u32 >> 15).wrapping_mul(r) >> 16).min(1 << 15)
}

/// One directional light at one pixel (viewer at infinity), then its
/// state stepped.
#[inline(always)]
fn duff_light<R: Real>(
    k: &PhongKernel<'_, R>,
    s: &mut LightSpan,
    l: &KLight,
    r: u32,
    rr14: u32,
    acc: &mut [u32; 3],
) {
    let nl = s.nl;
    if nl > 0 {
        let sp = if k.spec && (!k.blinn || s.nh > 0) {
            k.spec_of((s.q >> 32) as i32, rr14)
        } else {
            0
        };
        add_light(acc, l, nl15(nl, r), sp);
    }
    duff_step(s);
}

#[inline(always)]
fn duff_step(s: &mut LightSpan) {
    s.nl = s.nl.wrapping_add(s.dnl);
    s.nh = s.nh.wrapping_add(s.dnh);
    step(&mut s.q, &mut s.q_d1, s.q_d2);
}

/// One light at one pixel, point lights or a local viewer (`vh`: unit `V`).
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
#[allow(clippy::too_many_arguments)]
fn general_light<R: Real>(
    k: &PhongKernel<'_, R>,
    s: &LightSpan,
    l: &KLight,
    n: [i32; 3],
    vh: [i32; 3],
    r: u32,
    rr14: u32,
    acc: &mut [u32; 3],
) {
    let lh = if l.point { unit_of(s.l, s.q) } else { l.at };
    let nl = lin(n, lh);
    if nl <= 0 {
        return;
    }
    let sp = if k.spec {
        // Halves: |l̂ ± v̂| / 2 <= 1 keeps them in Q30.
        let a = [0, 1, 2].map(|c| (lh[c] >> 1) + (vh[c] >> 1));
        if k.blinn {
            let h = unit_of(a, sq3(a));
            if lin(n, h) > 0 {
                let q = sq3(cross(n, h));
                k.spec_of((q >> 32) as i32, rr14)
            } else {
                0
            }
        } else {
            let d = [0, 1, 2].map(|c| (lh[c] >> 1) - (vh[c] >> 1));
            let kd = lin(n, d);
            // Q/2 = |n × a|² + (n·d)² with the halves; w = 2 (Q/2) / |n|².
            let q = sq3(cross(n, a)).wrapping_add(wmul(kd, kd) as u64);
            k.spec_of(((q >> 31) as i32).max(0), rr14)
        }
    } else {
        0
    };
    add_light(acc, l, nl15(nl, r), sp);
}

#[inline(always)]
fn general_step(s: &mut LightSpan, l: &KLight) {
    if l.point {
        for a in 0..3 {
            s.l[a] = s.l[a].wrapping_add(s.dl[a]);
        }
        step(&mut s.q, &mut s.q_d1, s.q_d2);
    }
}

impl<R: Real> PhongSpan<'_, '_, R> {
    /// The next pixel's colour (then steps to the following pixel).
    // Not an `Iterator`: the span never ends by itself, and an `Option`
    // per pixel would cost in the loop.
    #[allow(clippy::should_implement_trait)]
    #[inline(always)]
    pub fn next(&mut self) -> Rgb8 {
        // One light, the common case, in a copy of its own whose state
        // the compiler keeps in registers (`l0`, no array indexing).
        let c = match (self.k.duff, self.k.lights.len()) {
            _ if self.slow => self.slow(),
            (true, 1) => self.duff::<true>(),
            (true, _) => self.duff::<false>(),
            (false, 1) => self.general::<true>(),
            (false, _) => self.general::<false>(),
        };
        self.i = self.i.wrapping_add(1);
        c
    }

    /// Steps over a pixel without shading it (a failed depth test).
    #[inline(always)]
    pub fn skip(&mut self) {
        self.step_all();
        self.i = self.i.wrapping_add(1);
    }

    #[inline(always)]
    fn step_all(&mut self) {
        let k = self.k;
        step(&mut self.nn, &mut self.nn_d1, self.nn_d2);
        let rest = k.lights.len().saturating_sub(1);
        if k.duff {
            duff_step(&mut self.l0);
            for s in self.rest.iter_mut().take(rest) {
                duff_step(s);
            }
        } else {
            self.step_general(rest);
        }
    }

    #[inline(always)]
    fn step_general(&mut self, rest: usize) {
        let k = self.k;
        for a in 0..3 {
            self.n[a] = self.n[a].wrapping_add(self.dn[a]);
            self.v[a] = self.v[a].wrapping_add(self.dv[a]);
        }
        step(&mut self.vv, &mut self.vv_d1, self.vv_d2);
        if let Some(l) = k.lights.first() {
            general_step(&mut self.l0, l);
        }
        for (s, l) in self.rest.iter_mut().zip(k.lights.iter().skip(1)).take(rest) {
            general_step(s, l);
        }
    }

    /// The generic path at this pixel, then a step.
    #[cold]
    fn slow(&mut self) -> Rgb8 {
        let c = fallback(self.k.shade, self.n0, self.dn, self.p0, self.dp, self.i);
        self.step_all();
        c
    }

    /// The pixel's `1/|n|` from `|n|²` ([`rsqrt_n`]) and its square in
    /// Q14; `None` beyond the table's range (then [`PhongSpan::slow`]).
    #[inline(always)]
    fn inv_len(&self) -> Option<(u32, u32)> {
        let r = rsqrt_n((self.nn >> 32) as i32)?;
        let r14 = r >> 2;
        Some((r, (r14 * r14) >> 14))
    }

    /// Directional lights, viewer at infinity (`ONE`: exactly one light).
    #[inline(always)]
    fn duff<const ONE: bool>(&mut self) -> Rgb8 {
        let k = self.k;
        let Some((r, rr14)) = self.inv_len() else {
            return self.slow();
        };
        let mut acc = k.amb;
        if let Some(l) = k.lights.first() {
            duff_light(k, &mut self.l0, l, r, rr14, &mut acc);
        }
        if !ONE {
            for (s, l) in self.rest.iter_mut().zip(k.lights.iter().skip(1)) {
                duff_light(k, s, l, r, rr14, &mut acc);
            }
        }
        step(&mut self.nn, &mut self.nn_d1, self.nn_d2);
        PhongKernel::<R>::level(acc)
    }

    /// Point lights or a local viewer (`ONE`: exactly one light). Not
    /// inlined: its ~400 instructions a pixel dwarf a call, and inlined
    /// into every span loop it added 60 KB of code.
    #[inline(never)]
    fn general<const ONE: bool>(&mut self) -> Rgb8 {
        let k = self.k;
        let Some((r, rr14)) = self.inv_len() else {
            return self.slow();
        };
        let n = self.n;
        let vh = if k.local {
            unit_of(self.v, self.vv)
        } else {
            [0, 0, 1 << 30]
        };
        let mut acc = k.amb;
        if let Some(l) = k.lights.first() {
            general_light(k, &self.l0, l, n, vh, r, rr14, &mut acc);
        }
        if !ONE {
            for (s, l) in self.rest.iter().zip(k.lights.iter().skip(1)) {
                general_light(k, s, l, n, vh, r, rr14, &mut acc);
            }
        }
        step(&mut self.nn, &mut self.nn_d1, self.nn_d2);
        let rest = if ONE {
            0
        } else {
            k.lights.len().saturating_sub(1)
        };
        self.step_general(rest);
        PhongKernel::<R>::level(acc)
    }
}

/// `|v|²` exactly (`u64`, wrapping only beyond `3 · 2^62`).
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
fn sq3(v: [i32; 3]) -> u64 {
    (wmul(v[0], v[0]) as u64)
        .wrapping_add(wmul(v[1], v[1]) as u64)
        .wrapping_add(wmul(v[2], v[2]) as u64)
}

/// One forward-difference step.
#[inline(always)]
fn step(v: &mut u64, d1: &mut u64, d2: u64) {
    *v = v.wrapping_add(*d1);
    *d1 = d1.wrapping_add(d2);
}

/// Today's span stage for the kernel (glue until the span stage gives
/// shaders a per-span hook): depth test and write as
/// [`Fill`](crate::raster::Fill), the kernel's colour per passing pixel,
/// the kernel stepped over failing ones.
#[derive(Debug)]
pub struct PhongFill<'t, 'd, 'b, 'k, 's, T, D: DepthFormat, R> {
    target: &'t mut T,
    depth: Option<&'d mut DepthBuffer<'b, D>>,
    kernel: &'k PhongKernel<'s, R>,
    /// The next triangles are back faces (normal flipped).
    pub back: bool,
    /// The next triangle's position plane (the `PhongPosition` layout).
    pub plane: PosPlane,
    /// The next triangle's quadratics (the `PhongPosition` layout, one
    /// point light: [`PhongKernel::wants_tri`]).
    pub tri: TriQuad,
    drawn: u32,
}

impl<'t, 'd, 'b, 'k, 's, T: Target, D: DepthFormat, R: Real>
    PhongFill<'t, 'd, 'b, 'k, 's, T, D, R>
{
    /// The span stage over `target` and `depth`.
    ///
    /// # Errors
    /// [`RasterError::DepthWindowMismatch`] when the depth buffer holds
    /// other rows or another width than the target (as
    /// [`Fill::new`](crate::raster::Fill::new)).
    pub fn new(
        target: &'t mut T,
        depth: Option<&'d mut DepthBuffer<'b, D>>,
        kernel: &'k PhongKernel<'s, R>,
    ) -> Result<Self, RasterError> {
        if let Some(d) = &depth {
            if d.window() != target.window() {
                return Err(RasterError::DepthWindowMismatch);
            }
        }
        Ok(Self {
            target,
            depth,
            kernel,
            back: false,
            plane: PosPlane::NONE,
            tri: TriQuad::NONE,
            drawn: 0,
        })
    }

    /// Pixels written so far.
    pub fn drawn(&self) -> u32 {
        self.drawn
    }

    /// The target's window.
    pub fn window(&self) -> crate::target::Window {
        self.target.window()
    }

    #[inline(always)]
    fn run<L: Lerp, const N: usize>(&mut self, s: &Span<L, N>, pp: Option<([i32; 3], [i32; 3])>) {
        // The triangle's quadratics for the position layout.
        let tri =
            (pp.is_some() && self.tri.wants()).then_some((&mut self.tri, s.x0 as i32, s.y as i32));
        let n = [raw(s.a[0]), raw(s.a[1]), raw(s.a[2])];
        let dn = [raw(s.da[0]), raw(s.da[1]), raw(s.da[2])];
        let (p, dp) = pp.unwrap_or(([0; 3], [0; 3]));
        let (y, x0, x1) = (s.y, s.x0, s.x1);
        let len = x1.saturating_sub(x0);
        let enc = <T::Format as PixelFormat>::encode;
        let k = self.kernel;
        let back = self.back;
        let span = (n, dn, p, dp);
        let drow = match self.depth.as_deref_mut() {
            Some(d) => match d.span_mut(y, x0, x1) {
                Some(drow) => Some(drow),
                None => return,
            },
            None => None,
        };
        let count = if let Some(row) = self.target.span_mut(y, x0, x1) {
            row_fill::<L, T::Format, D, R>(k, row, drow, s.z, s.dz, span, back, tri)
        } else {
            let t = &mut *self.target;
            let write = move |i: u32, c| t.write_pixel(x0 + i, y, enc(c));
            match drow {
                Some(drow) => {
                    let mut d = DepthTest::<L, D> {
                        drow,
                        z: s.z,
                        dz: s.dz,
                        in_range: false,
                    };
                    let test = move |i| d.test(i);
                    k.fill_with(n, dn, p, dp, back, len, FnOut { test, write }, tri)
                }
                None => k.fill_with(
                    n,
                    dn,
                    p,
                    dp,
                    back,
                    len,
                    FnOut {
                        test: |_| true,
                        write,
                    },
                    tri,
                ),
            }
        };
        self.drawn += count;
    }
}

/// The kernel as a [`Shader`](crate::raster::Shader) of the band
/// renderer: its own span loop ([`Shader::span_kernel`](crate::raster::Shader::span_kernel)) runs
/// [`PhongKernel::fill`] with the span stage's depth test, so the
/// forward differences stay in registers; attributes are the normal (3) or
/// the normal and the eye position (6), as for [`super::PhongShader`].
#[derive(Debug)]
pub struct PhongKernelShader<'k, 's, R> {
    kernel: &'k PhongKernel<'s, R>,
    /// The next triangles are back faces (normal flipped).
    pub back: bool,
    /// The next triangle's position plane (the `PhongPosition` layout).
    pub plane: PosPlane,
    /// The next triangle's quadratics (the `PhongPosition` layout, one
    /// point light: [`PhongKernel::wants_tri`]).
    pub tri: TriQuad,
    /// The quadratics kept from band to band ([`QuadSlot`]), the point
    /// light's position and the band's rows.
    slots: &'k mut [QuadSlot],
    light: [i32; 3],
    rows: (i32, i32),
}

impl<'k, 's, R: Real> PhongKernelShader<'k, 's, R> {
    /// A shader running `kernel`, front faces first.
    pub fn new(kernel: &'k PhongKernel<'s, R>) -> Self {
        Self {
            kernel,
            back: false,
            plane: PosPlane::NONE,
            tri: TriQuad::NONE,
            slots: &mut [],
            light: [0; 3],
            rows: (0, 0),
        }
    }

    /// The shader keeping the triangles' quadratics in `slots` from one
    /// band to the next (this band: rows `y0..y1`).
    pub(crate) fn keep_in(&mut self, slots: &'k mut [QuadSlot], (y0, y1): (u32, u32)) {
        if let Some(l) = self.kernel.point_loop_light() {
            self.slots = slots;
            self.light = l.at;
            self.rows = (y0 as i32, y1 as i32);
        }
    }

    /// Sets the next triangle's quadratics up (the `PhongPosition`
    /// layout, [`TriQuad::set_of_tri`]): the last triangle's kept when
    /// made and continuing below the band, this one's taken from the
    /// slots when there (its vertices then not fetched).
    #[inline(always)]
    pub(crate) fn set_tri<P: crate::num::Profile>(
        &mut self,
        frame: &super::Frame<'_, P>,
        po: &super::PreparedObject,
        tri: &super::PreparedTri,
    ) {
        self.tri.store(self.slots, self.light, self.rows);
        let key = tri::key_of(tri.v, tri.back);
        if !self.tri.load(key, self.slots, self.light, self.rows.1) {
            self.tri.set_of_tri(frame, po, tri);
        }
    }

    /// The kernel's colour at one pixel (a span of one pixel: the very
    /// value the span loop computes there, its forward differences being
    /// exact).
    fn at<L: Lerp>(&self, a: &[L], p: [i32; 3]) -> Rgb8 {
        let n = [raw(a[0]), raw(a[1]), raw(a[2])];
        self.kernel.begin(n, [0; 3], p, [0; 3], self.back).next()
    }

    /// The span loop: depth test as the span stage's, the kernel's colour
    /// per passing pixel.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn fill_row<L: Lerp, F: PixelFormat, D: DepthFormat>(
        &mut self,
        row: &mut [F::Raw],
        drow: Option<&mut [D::Raw]>,
        z: L,
        dz: L,
        a: &[L],
        da: &[L],
        pp: ([i32; 3], [i32; 3]),
        at: Option<(i32, i32)>,
    ) -> u32 {
        let n = [raw(a[0]), raw(a[1]), raw(a[2])];
        let dn = [raw(da[0]), raw(da[1]), raw(da[2])];
        let (p, dp) = pp;
        let tri = match at {
            Some((x, y)) if self.tri.wants() => Some((&mut self.tri, x, y)),
            _ => None,
        };
        let span = (n, dn, p, dp);
        row_fill::<L, F, D, R>(self.kernel, row, drow, z, dz, span, self.back, tri)
    }
}

impl<L: Lerp, R: Real> crate::raster::Shader<L, 3> for PhongKernelShader<'_, '_, R> {
    fn shade(&self, a: &[L; 3]) -> Rgb8 {
        self.at(a, [0; 3])
    }

    #[inline(always)]
    fn span_kernel<F: PixelFormat, D: DepthFormat>(
        &mut self,
        row: &mut [F::Raw],
        drow: Option<&mut [D::Raw]>,
        z: L,
        dz: L,
        a: &[L; 3],
        da: &[L; 3],
        _at: (i32, i32),
    ) -> Option<u32> {
        Some(self.fill_row::<L, F, D>(row, drow, z, dz, a, da, ([0; 3], [0; 3]), None))
    }
}

impl<L: Lerp, R: Real> crate::raster::Shader<L, 6> for PhongKernelShader<'_, '_, R> {
    fn shade(&self, a: &[L; 6]) -> Rgb8 {
        self.at(a, [raw(a[3]), raw(a[4]), raw(a[5])])
    }

    #[inline(always)]
    fn span_kernel<F: PixelFormat, D: DepthFormat>(
        &mut self,
        row: &mut [F::Raw],
        drow: Option<&mut [D::Raw]>,
        z: L,
        dz: L,
        a: &[L; 6],
        da: &[L; 6],
        (x0, y): (i32, i32),
    ) -> Option<u32> {
        let p = [raw(a[3]), raw(a[4]), raw(a[5])];
        let dp = [raw(da[3]), raw(da[4]), raw(da[5])];
        let pp = (self.plane.start(x0, y, row.len() as u32, p, dp), dp);
        Some(self.fill_row::<L, F, D>(row, drow, z, dz, a, da, pp, Some((x0, y))))
    }
}

impl<R> Drop for PhongKernelShader<'_, '_, R> {
    /// The last triangle's quadratics kept (as at the next triangle).
    fn drop(&mut self) {
        self.tri.store(self.slots, self.light, self.rows);
    }
}

/// The span stage's depth test over a row of the depth buffer, depths
/// `z + i·dz` ([`DepthFormat::from_lerp`], less-than, as
/// [`Fill`](crate::raster::Fill)). (The unclamped in-range form the span
/// stage also has doubled every span loop's code here: +64 KB of flash on
/// the M4, and no faster.)
struct DepthTest<'d, L, D: DepthFormat> {
    drow: &'d mut [D::Raw],
    z: L,
    dz: L,
    /// The span's depths are in range ([`DepthFormat::span_in_range`]):
    /// a chunk's loop runs without the depth clamp (the same values).
    in_range: bool,
}

impl<L: Lerp, D: DepthFormat> DepthTest<'_, L, D> {
    #[inline(always)]
    fn test(&mut self, i: u32) -> bool {
        let z = self.z;
        self.z = z.add(self.dz);
        match self.drow.get_mut(i as usize) {
            Some(zb) => {
                let zd = D::from_lerp(z);
                let pass = zd < *zb;
                if pass {
                    *zb = zd;
                }
                pass
            }
            None => false,
        }
    }

    /// The depth tests of the `k <= 32` pixels from `i` (over the depth
    /// slice alone, without the depth clamp when the span's depths are in
    /// range): the passing ones as a bit mask (pixel `j`: bit `j`) and how
    /// many failed; `None` when the pixels lie outside the depth slice.
    /// The failures come from the mask, counted only when not all passed:
    /// a passing pixel's store and bit predicated, without a branch
    /// (measured on the M4's span sweep, one light: 74.70 -> 73.48
    /// instructions a pixel; counted every piece 76.70 with one colour a
    /// loop iteration against 75.90).
    #[inline(always)]
    fn mask(&mut self, i: usize, k: usize) -> Option<(u32, u32)> {
        let drow = self.drow.get_mut(i..i + k)?;
        let (mut z, dz) = (self.z, self.dz);
        let (mut pass, mut bit) = (0u32, 1u32);
        if self.in_range {
            (pass, z) = mask_in_range::<L, D>(drow, z, dz);
        } else {
            for zb in drow.iter_mut() {
                let zd = D::from_lerp(z);
                if zd < *zb {
                    *zb = zd;
                    pass |= bit;
                }
                bit <<= 1;
                z = z.add(dz);
            }
        }
        self.z = z;
        // The failures from the mask, counted only when some failed (no
        // count in the loop: a passing pixel's store and bit without a
        // branch).
        // `k <= 32`: the shift masked to `0..32` (`k = 0`: no pixels, the
        // empty mask counted as 0 failed either way).
        #[allow(clippy::cast_possible_truncation)]
        let all = u32::MAX.wrapping_shr(32u32.wrapping_sub(k as u32));
        #[allow(clippy::cast_possible_truncation)]
        let failed = if pass == all {
            0
        } else {
            k as u32 - pass.count_ones()
        };
        Some((pass, failed))
    }
}

/// [`DepthTest::mask`] of a span whose depths are in range: the mask
/// of the passing pixels of `drow` (depths `z + j·dz`, `drow.len() <=
/// 32`) and the depth after them. Not inlined other than on ARMv6-M:
/// its loop keeps the depth and its step in registers, seven
/// instructions a pixel on the M4 (measured on the span sweep: one
/// light 73.48 -> 73.11 instructions a pixel, two 179.71 -> 178.92,
/// four 287.45 -> 286.65, the point light 162.97 -> 162.26).
#[cfg_attr(armv6m, inline(always))]
#[cfg_attr(not(armv6m), inline(never))]
fn mask_in_range<L: Lerp, D: DepthFormat>(drow: &mut [D::Raw], mut z: L, dz: L) -> (u32, L) {
    let (mut pass, mut bit) = (0u32, 1u32);
    for zb in drow.iter_mut() {
        let key = D::from_lerp_in_range(z);
        if key < D::to_key(*zb) {
            *zb = D::from_key(key);
            pass |= bit;
        }
        bit <<= 1;
        z = z.add(dz);
    }
    (pass, z)
}

/// Runs the kernel's `fill` over a span's row slice `row` and its depth
/// slice `drow` (the same length; depths `z + i·dz`, the test of
/// [`DepthTest`]) through [`RowOut`]; returns the pixels written.
///
/// Not inlined: one copy per pixel format, depth format and scalar
/// instead of one in each of the band renderer's Phong walks. On ARMv7-M
/// inlined, the firmware's `.text` was 428 680 B (its two Phong
/// `Bands::run` instances 65 + 74 KB), out of line 291 460 B, for 2.2 %
/// more instructions in the dodecahedron Phong frame (1 963 410 ->
/// 2 006 167 raster). On ARMv6-M out of line the firmware's `.text` went
/// from 705 760 to 446 008 B and the dodecahedron Phong frame from
/// 6 825 515 to 6 751 339 instructions (the span sweep's one light 175.22
/// -> 175.71 a pixel); the bounds check that kept it inlined there (the
/// point loop's range test, indexed) is gone. One row fill for the spans
/// with and without the triangle's quadratics (`tri`): a second copy for
/// the former cost 21.5 KB of `.text` on the M4 and 25.1 KB on the M0
/// (firmware 359 248 -> 337 712 B and 417 292 -> 392 236 B with one), for
/// 16 115 instructions more in the cubes-and-sphere frame on the M4 (of
/// 3.88 M; the dodecahedron Phong frame 5 331 fewer).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn row_fill<L: Lerp, F: PixelFormat, D: DepthFormat, R: Real>(
    k: &PhongKernel<'_, R>,
    row: &mut [F::Raw],
    drow: Option<&mut [D::Raw]>,
    z: L,
    dz: L,
    span: Planes,
    back: bool,
    tri: Option<(&mut TriQuad, i32, i32)>,
) -> u32 {
    row_out::<L, F, D, R>(k, row, drow, z, dz, span, back, tri)
}

/// The body of [`row_fill`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn row_out<L: Lerp, F: PixelFormat, D: DepthFormat, R: Real>(
    k: &PhongKernel<'_, R>,
    row: &mut [F::Raw],
    drow: Option<&mut [D::Raw]>,
    z: L,
    dz: L,
    (n, dn, p, dp): Planes,
    back: bool,
    tri: Option<(&mut TriQuad, i32, i32)>,
) -> u32 {
    let len = row.len() as u32;
    match drow {
        Some(drow) => {
            // Checked only for spans long enough to repay the check.
            let in_range = len >= IN_RANGE_SPAN && D::span_in_range(z, dz, len);
            let depth = DepthTest::<L, D> {
                drow,
                z,
                dz,
                in_range,
            };
            let out = RowOut::<F, _> { row, depth };
            k.fill_with(n, dn, p, dp, back, len, out, tri)
        }
        None => k.fill_with(
            n,
            dn,
            p,
            dp,
            back,
            len,
            RowOut::<F, _> {
                row,
                depth: NoDepth,
            },
            tri,
        ),
    }
}

/// Spans of at least this many pixels check whether their depths are in
/// range ([`DepthFormat::span_in_range`]) for [`RowOut`]'s loop without
/// the depth clamp.
const IN_RANGE_SPAN: u32 = 8;

/// Where the kernel's colours go: the depth test and the write of one
/// pixel after another (pixels in order, each tested once), and of a
/// chunk of packed colours (`r | g << 8 | b << 16`) at once.
trait Out {
    /// The depth test of pixel `i` (its depth stored when it passes).
    fn test(&mut self, i: u32) -> bool;
    /// Writes pixel `i`.
    fn write(&mut self, i: u32, c: Rgb8);
    /// Tests and writes the pixels of `cols` from pixel `i`, the colour
    /// of a passing pixel the channel sums `col(c)` (Q19,
    /// [`PixelFormat::encode_q19`]) for its entry `c`; returns how many
    /// failed.
    #[inline(always)]
    fn chunk(&mut self, i: u32, cols: &[u32], col: impl Fn(u32) -> [i32; 3] + Copy) -> u32 {
        let mut failed = 0;
        for (j, &c) in (i..).zip(cols.iter()) {
            if self.test(j) {
                self.write(j, level_q19(col(c)));
            } else {
                failed += 1;
            }
        }
        failed
    }

    /// The `k` pixels from pixel `i` in one loop over the state `s`: per
    /// pixel the depth test, for a passing one the channel sums `col(s)`
    /// (Q19, [`PixelFormat::encode_q19`]) encoded and written, then
    /// `step(s)` (every pixel); returns how many failed.
    #[inline(always)]
    fn fused<S>(
        &mut self,
        i: u32,
        k: u32,
        s: &mut S,
        col: impl Fn(&S) -> [i32; 3],
        step: impl Fn(&mut S),
    ) -> u32 {
        let mut failed = 0;
        for j in i..i + k {
            if self.test(j) {
                self.write(j, level_q19(col(s)));
            } else {
                failed += 1;
            }
            step(s);
        }
        failed
    }

    /// [`Out::fused`] (the same pixels, values and result); for `k <=
    /// CHUNK` a depth buffer's tests may come first (a mask), then one
    /// loop of colours and steps ([`SpanDepth::masked`]).
    #[inline(always)]
    fn masked<S: Copy>(
        &mut self,
        i: u32,
        k: u32,
        s: &mut S,
        col: impl Fn(&S) -> [i32; 3],
        step: impl Fn(&mut S),
    ) -> u32 {
        self.fused(i, k, s, col, step)
    }
}

/// [`Out`] of a test and a write closure ([`PhongKernel::fill`]).
struct FnOut<T, W> {
    test: T,
    write: W,
}

impl<T: FnMut(u32) -> bool, W: FnMut(u32, Rgb8)> Out for FnOut<T, W> {
    #[inline(always)]
    fn test(&mut self, i: u32) -> bool {
        (self.test)(i)
    }

    #[inline(always)]
    fn write(&mut self, i: u32, c: Rgb8) {
        (self.write)(i, c);
    }
}

/// The depth part of [`RowOut`]: the depth test of one pixel, and a
/// chunk's loop over the row (the pixels of a chunk from its first).
trait SpanDepth {
    /// The depth test of pixel `i` (its depth stored when it passes).
    fn test(&mut self, i: u32) -> bool;
    /// Tests the `row.len()` pixels from pixel `i` and writes the passing
    /// ones, `px(c)` for their entries `c` of `cols`; returns how many
    /// failed.
    fn chunk<P>(
        &mut self,
        row: &mut [P],
        i: usize,
        cols: &[u32],
        px: impl Fn(u32) -> P + Copy,
    ) -> u32;
    /// Tests the `row.len()` pixels from pixel `i` and writes the passing
    /// ones, `px(s)`, stepping `s` after every pixel ([`Out::fused`]);
    /// returns how many failed.
    fn fused<P, S>(
        &mut self,
        row: &mut [P],
        i: usize,
        s: &mut S,
        px: impl Fn(&S) -> P,
        step: impl Fn(&mut S),
    ) -> u32;
    /// [`SpanDepth::fused`] (the same pixels, values and result): for
    /// `row.len() <= CHUNK` the depth tests first, then the colours
    /// ([`Out::masked`]).
    fn masked<P, S: Copy>(
        &mut self,
        row: &mut [P],
        i: usize,
        s: &mut S,
        px: impl Fn(&S) -> P,
        step: impl Fn(&mut S),
    ) -> u32;
}

/// No depth buffer: every pixel passes.
struct NoDepth;

impl SpanDepth for NoDepth {
    #[inline(always)]
    fn test(&mut self, _i: u32) -> bool {
        true
    }

    #[inline(always)]
    fn chunk<P>(
        &mut self,
        row: &mut [P],
        _i: usize,
        cols: &[u32],
        px: impl Fn(u32) -> P + Copy,
    ) -> u32 {
        paint(row, cols, None, px);
        0
    }

    #[inline(always)]
    fn fused<P, S>(
        &mut self,
        row: &mut [P],
        _i: usize,
        s: &mut S,
        px: impl Fn(&S) -> P,
        step: impl Fn(&mut S),
    ) -> u32 {
        for o in row.iter_mut() {
            *o = px(s);
            step(s);
        }
        0
    }

    #[inline(always)]
    fn masked<P, S: Copy>(
        &mut self,
        row: &mut [P],
        i: usize,
        s: &mut S,
        px: impl Fn(&S) -> P,
        step: impl Fn(&mut S),
    ) -> u32 {
        self.fused(row, i, s, px, step)
    }
}

impl<L: Lerp, D: DepthFormat> SpanDepth for DepthTest<'_, L, D> {
    #[inline(always)]
    fn test(&mut self, i: u32) -> bool {
        DepthTest::test(self, i)
    }

    /// Two loops: the depth test of the chunk's pixels (over the depth
    /// slice alone, without the depth clamp when the span's depths are in
    /// range), their results as a bit mask, then the colours of the
    /// passing pixels (one loop without a test when all passed, the
    /// common case). Measured on the M4's span sweep: one loop over the
    /// three slices kept 15 values live and reloaded the channel
    /// constants every pixel.
    #[inline(always)]
    fn chunk<P>(
        &mut self,
        row: &mut [P],
        i: usize,
        cols: &[u32],
        px: impl Fn(u32) -> P + Copy,
    ) -> u32 {
        const { assert!(CHUNK <= 32) };
        let k = row.len().min(CHUNK);
        let Some((pass, failed)) = self.mask(i, k) else {
            return k as u32;
        };
        paint(row, cols, (failed != 0).then_some(pass), px);
        failed
    }

    /// One loop over the row and depth slices: the depth test of a pixel
    /// (without the depth clamp when the span's depths are in range),
    /// its colour when it passes, the state stepped.
    #[inline(always)]
    fn fused<P, S>(
        &mut self,
        row: &mut [P],
        i: usize,
        s: &mut S,
        px: impl Fn(&S) -> P,
        step: impl Fn(&mut S),
    ) -> u32 {
        let k = row.len();
        let Some(drow) = self.drow.get_mut(i..i + k) else {
            return k as u32;
        };
        let (mut z, dz) = (self.z, self.dz);
        let mut failed = 0u32;
        if self.in_range {
            for (o, zb) in row.iter_mut().zip(drow.iter_mut()) {
                let key = D::from_lerp_in_range(z);
                if key < D::to_key(*zb) {
                    *zb = D::from_key(key);
                    *o = px(s);
                } else {
                    failed += 1;
                }
                step(s);
                z = z.add(dz);
            }
        } else {
            for (o, zb) in row.iter_mut().zip(drow.iter_mut()) {
                let zd = D::from_lerp(z);
                if zd < *zb {
                    *zb = zd;
                    *o = px(s);
                } else {
                    failed += 1;
                }
                step(s);
                z = z.add(dz);
            }
        }
        self.z = z;
        failed
    }

    /// The mask ([`DepthTest::mask`]), then the colours: when all passed,
    /// two pixels an iteration over a local copy of the state. Measured
    /// on the M4's span sweep (one light, the mask counting failures in
    /// its loop): 74.70 instructions a pixel against 75.90 one pixel an
    /// iteration through `s`, 75.03 two through `s`, 78.47 one over the
    /// local copy.
    #[inline(always)]
    fn masked<P, S: Copy>(
        &mut self,
        row: &mut [P],
        i: usize,
        s: &mut S,
        px: impl Fn(&S) -> P,
        step: impl Fn(&mut S),
    ) -> u32 {
        const { assert!(CHUNK <= 32) };
        let k = row.len();
        if k > CHUNK {
            return self.fused(row, i, s, px, step);
        }
        let Some((mut pass, failed)) = self.mask(i, k) else {
            return k as u32;
        };
        if failed == 0 {
            let mut st = *s;
            let mut pairs = row[..k].chunks_exact_mut(2);
            for o in &mut pairs {
                o[0] = px(&st);
                step(&mut st);
                o[1] = px(&st);
                step(&mut st);
            }
            for o in pairs.into_remainder() {
                *o = px(&st);
                step(&mut st);
            }
            *s = st;
        } else {
            for o in row[..k].iter_mut() {
                if pass & 1 != 0 {
                    *o = px(s);
                }
                pass >>= 1;
                step(s);
            }
        }
        failed
    }
}

/// The colours `px(c)` of the entries `c` of `cols` into `row`: every
/// pixel, or those whose bit is set in `pass` (pixel `j`: bit `j`).
/// Other than on ARMv6-M not inlined, `px` by value (the colour
/// constants in its frame, loaded in pairs, not spilled one by one in
/// the row fill's): measured on the M4, the dodecahedron Phong raster
/// 1 844 802 -> 1 822 957 and the span sweep's phong-kpoint 169.47 ->
/// 167.80, phong-k2 181.77 -> 179.81 a pixel; on the M0 it cost 45 108
/// instructions more in that frame (5 917 574 -> 5 962 682), so it stays
/// inlined there.
#[cfg_attr(armv6m, inline(always))]
#[cfg_attr(not(armv6m), inline(never))]
fn paint<P>(row: &mut [P], cols: &[u32], pass: Option<u32>, px: impl Fn(u32) -> P + Copy) {
    match pass {
        None => {
            for (o, &c) in row.iter_mut().zip(cols.iter()) {
                *o = px(c);
            }
        }
        Some(mut pass) => {
            for (o, &c) in row.iter_mut().zip(cols.iter()) {
                if pass & 1 != 0 {
                    *o = px(c);
                }
                pass >>= 1;
            }
        }
    }
}

/// [`Out`] of a span's row slice and its depth part ([`SpanDepth`]: a
/// depth slice, or none).
struct RowOut<'r, F: PixelFormat, Z> {
    row: &'r mut [F::Raw],
    depth: Z,
}

impl<F: PixelFormat, Z: SpanDepth> Out for RowOut<'_, F, Z> {
    #[inline(always)]
    fn test(&mut self, i: u32) -> bool {
        self.depth.test(i)
    }

    #[inline(always)]
    fn write(&mut self, i: u32, c: Rgb8) {
        if let Some(px) = self.row.get_mut(i as usize) {
            *px = F::encode(c);
        }
    }

    #[inline(always)]
    fn chunk(&mut self, i: u32, cols: &[u32], col: impl Fn(u32) -> [i32; 3] + Copy) -> u32 {
        let (i, k) = (i as usize, cols.len());
        let Some(row) = self.row.get_mut(i..i + k) else {
            return k as u32;
        };
        self.depth
            .chunk(row, i, cols, move |c| F::encode_q19(col(c)))
    }

    #[inline(always)]
    fn fused<S>(
        &mut self,
        i: u32,
        k: u32,
        s: &mut S,
        col: impl Fn(&S) -> [i32; 3],
        step: impl Fn(&mut S),
    ) -> u32 {
        let Some((row, i)) = pixels(self.row, i, k) else {
            return k;
        };
        self.depth.fused(row, i, s, |s| F::encode_q19(col(s)), step)
    }
    #[inline(always)]
    fn masked<S: Copy>(
        &mut self,
        i: u32,
        k: u32,
        s: &mut S,
        col: impl Fn(&S) -> [i32; 3],
        step: impl Fn(&mut S),
    ) -> u32 {
        let Some((row, i)) = pixels(self.row, i, k) else {
            return k;
        };
        self.depth
            .masked(row, i, s, |s| F::encode_q19(col(s)), step)
    }
}

/// The `k` pixels of `row` from `i` and that index, if they lie in it.
#[inline(always)]
fn pixels<P>(row: &mut [P], i: u32, k: u32) -> Option<(&mut [P], usize)> {
    let i = i as usize;
    Some((row.get_mut(i..i + k as usize)?, i))
}

/// Raw bits of a fixed-point interpolated value (`i32` profiles; the
/// kernel is never made for the float ones).
#[inline(always)]
fn raw<L: Lerp>(v: L) -> i32 {
    v.round_int(0)
}

impl<L: Lerp, T: Target, D: DepthFormat, R: Real> Spans<L, 3>
    for PhongFill<'_, '_, '_, '_, '_, T, D, R>
{
    fn span(&mut self, s: &Span<L, 3>) {
        self.run(s, None);
    }
}

impl<L: Lerp, T: Target, D: DepthFormat, R: Real> Spans<L, 6>
    for PhongFill<'_, '_, '_, '_, '_, T, D, R>
{
    fn span(&mut self, s: &Span<L, 6>) {
        let p = [raw(s.a[3]), raw(s.a[4]), raw(s.a[5])];
        let dp = [raw(s.da[3]), raw(s.da[4]), raw(s.da[5])];
        let len = s.x1.saturating_sub(s.x0);
        let p = self.plane.start(s.x0 as i32, s.y as i32, len, p, dp);
        self.run(s, Some((p, dp)));
    }
}

/// Extra fraction bits of [`PosPlane`]'s gradients and origin.
const PLANE_BITS: u32 = 12;

/// The least shininess at which the renderers give the kernel its spans'
/// start from the triangle's [`PosPlane`] ([`PhongKernel::wants_plane`]).
/// Below it the walked positions are kept (no set-up per triangle and
/// span): their error moves a highlight by at most `255·Ip·ks·0.61·√n`
/// levels per radian, and on the highlight-peak set every case below
/// shininess 1 000 measured within 1 level of the twin with them (the
/// plane took the dodecahedron Phong frame at shininess 100 from
/// 2 004 406 to 2 102 855 instructions on the M4 for no level).
pub const PLANE_MIN_SHININESS: u32 = 512;

/// The plane of one triangle's interpolated eye-space positions (`Q16`
/// raw, the `PhongPosition` layout's attributes 3 to 5) with
/// [`PLANE_BITS`] more fraction bits than the rasterizer's steps, made
/// once a triangle; per span [`PosPlane::start`] gives the kernel a start
/// position whose stepped values are exact (within half a raw unit) at
/// the span's middle pixel.
///
/// Why: the rasterizer steps an attribute by its gradient rounded to a
/// whole raw unit, so `k` pixels from the triangle's anchor a position is
/// off by up to `k/2` raw units (`k · 2^-17` eye units); the view and
/// light directions turn by that over the distance to the eye and the
/// light, and the peak of `x^n` amplifies it by up to `0.61·√n` a
/// radian. Measured on the highlight-peak set (a 108-pixel square face 3
/// units from the eye, light straight above, Phong, `n = 10 000`):
/// `fast` 3 levels from its `f64` twin with the walked positions, 1 with
/// this start.
///
/// Error (`plane_start_error` checks it): at pixel `i` of a span of `len`
/// the stepped position is within `½ + |i - h| · |dp - g| + 2^-5` raw
/// units of the exact plane through the three vertices (`h = ⌊(len -
/// 1)/2⌋`, `g` the exact gradient along x, `|dp - g| <= ½` for the
/// rasterizer's rounded step `dp`): the rounding at the middle, the step's
/// drift from there, and the plane's own error (`InvArea::quot`'s `½ +
/// |g|·2^-28` in units of `2^-12` raw per pixel, times offsets within
/// `2^14` pixels, with gradients below `2^28` raw).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PosPlane {
    /// The anchor pixel (nearest the first vertex).
    at: [i32; 2],
    /// Per component: the value at the anchor, whole raw units.
    base: [i32; 3],
    /// Per component: the rest of the value at the anchor, in `2^-12`
    /// raw units (`0..2^12`).
    rest: [i32; 3],
    /// Per component: the gradients along x and y, whole raw units
    /// (floor) and the rest in `2^-12` raw units (`0..2^12`).
    g: [[i32; 4]; 3],
    /// Made (else [`PosPlane::start`] keeps the walked values).
    ok: bool,
}

impl PosPlane {
    /// No plane: [`PosPlane::start`] keeps the walked values.
    pub const NONE: Self = Self {
        at: [0; 2],
        base: [0; 3],
        rest: [0; 3],
        g: [[0; 4]; 3],
        ok: false,
    };

    /// The plane through the three vertices `v` (screen position in
    /// subpixels of `sub` bits from the screen's top-left corner, eye
    /// position `Q16` raw); [`PosPlane::NONE`] for a degenerate triangle
    /// or gradients of `2^28` raw a pixel or more.
    pub fn new(v: [([i32; 2], [i32; 3]); 3], sub: crate::num::SubpixelBits) -> Self {
        let ([x0, y0], a0) = v[0];
        let ([x1, y1], a1) = v[1];
        let ([x2, y2], a2) = v[2];
        let d = [
            x1.wrapping_sub(x0),
            y1.wrapping_sub(y0),
            x2.wrapping_sub(x0),
            y2.wrapping_sub(y0),
        ];
        let area2 = wmul(d[0], d[3]).wrapping_sub(wmul(d[2], d[1]));
        if area2 == 0 {
            return Self::NONE;
        }
        let inv = crate::num::InvArea::new(area2);
        let s = sub.get();
        let sc = 1i32 << s;
        let (xa, ya) = (x0 >> s, y0 >> s);
        // Offsets of the anchor pixel's centre from vertex 0, within a
        // pixel.
        let (ox, oy) = (
            i64::from((xa << s).wrapping_add(sc / 2).wrapping_sub(x0)),
            i64::from((ya << s).wrapping_add(sc / 2).wrapping_sub(y0)),
        );
        let mut p = Self::NONE;
        p.at = [xa, ya];
        const MASK: i64 = (1 << PLANE_BITS) - 1;
        const LIM: u64 = 1 << (28 + PLANE_BITS);
        for k in 0..3 {
            let (d1, d2) = (a1[k].overflowing_sub(a0[k]), a2[k].overflowing_sub(a0[k]));
            let (nx, ny) = if d1.1 || d2.1 {
                let (d1, d2) = (
                    i64::from(a1[k]) - i64::from(a0[k]),
                    i64::from(a2[k]) - i64::from(a0[k]),
                );
                let [dx1, dy1, dx2, dy2] = d.map(i64::from);
                (
                    d1.wrapping_mul(dy2).wrapping_sub(d2.wrapping_mul(dy1)),
                    d2.wrapping_mul(dx1).wrapping_sub(d1.wrapping_mul(dx2)),
                )
            } else {
                let (d1, d2) = (d1.0, d2.0);
                (
                    wmul(d1, d[3]).wrapping_sub(wmul(d2, d[1])),
                    wmul(d2, d[0]).wrapping_sub(wmul(d1, d[2])),
                )
            };
            let (gx, gy) = (inv.quot(nx, s + PLANE_BITS), inv.quot(ny, s + PLANE_BITS));
            if gx.unsigned_abs() >= LIM || gy.unsigned_abs() >= LIM {
                return Self::NONE;
            }
            // The anchor's offset from vertex 0 in 2^-12 raw units
            // (|g·o| < 2^40 · 2^8).
            let t = gx
                .wrapping_mul(ox)
                .wrapping_add(gy.wrapping_mul(oy))
                .wrapping_add(1 << (s - 1))
                >> s;
            p.base[k] = a0[k].wrapping_add((t >> PLANE_BITS) as i32);
            p.rest[k] = (t & MASK) as i32;
            p.g[k] = [
                (gx >> PLANE_BITS) as i32,
                (gx & MASK) as i32,
                (gy >> PLANE_BITS) as i32,
                (gy & MASK) as i32,
            ];
        }
        p.ok = true;
        p
    }

    /// The plane of triangle `tri` of object `po` in `frame` (the
    /// `PhongPosition` layout: attributes 3 to 5 the eye position);
    /// [`PosPlane::NONE`] when its vertices are not at hand.
    pub(crate) fn of_tri<P: crate::num::Profile>(
        frame: &super::Frame<'_, P>,
        po: &super::PreparedObject,
        tri: &super::PreparedTri,
    ) -> Self {
        let mut v = [([0i32; 2], [0i32; 3]); 3];
        for (o, &i) in v.iter_mut().zip(tri.v.iter()) {
            let Some(xy) = frame.xy(usize::from(i)) else {
                return Self::NONE;
            };
            let Some(vx) = frame.vertex::<6>(po, i, xy) else {
                return Self::NONE;
            };
            *o = (xy, [raw(vx.attrs[3]), raw(vx.attrs[4]), raw(vx.attrs[5])]);
        }
        Self::new(v, P::SUBPIXEL_BITS)
    }

    /// The start position of the span of `len` pixels from pixel `(x0,
    /// y)` stepped by `dp`: the plane's value at its middle pixel `x0 +
    /// h` (`h = ⌊(len - 1)/2⌋`), rounded, less `h·dp` (wrapping); the
    /// walked start `p` without a plane. 32-bit arithmetic: pixels within
    /// `2^14` of the anchor keep the fractions' sum within `2^27`.
    #[inline(always)]
    pub fn start(&self, x0: i32, y: i32, len: u32, p: [i32; 3], dp: [i32; 3]) -> [i32; 3] {
        if !self.ok {
            return p;
        }
        let h = (len.saturating_sub(1) / 2) as i32;
        let dx = x0.wrapping_add(h).wrapping_sub(self.at[0]);
        let dy = y.wrapping_sub(self.at[1]);
        if dx.unsigned_abs() >= 1 << 14 || dy.unsigned_abs() >= 1 << 14 {
            return p;
        }
        let mut out = p;
        for (k, o) in out.iter_mut().enumerate() {
            let [gxi, gxf, gyi, gyf] = self.g[k];
            let whole = self.base[k]
                .wrapping_add(gxi.wrapping_mul(dx))
                .wrapping_add(gyi.wrapping_mul(dy));
            let frac = self.rest[k]
                .wrapping_add(gxf.wrapping_mul(dx))
                .wrapping_add(gyf.wrapping_mul(dy))
                .wrapping_add(1 << (PLANE_BITS - 1));
            *o = whole
                .wrapping_add(frac >> PLANE_BITS)
                .wrapping_sub(dp[k].wrapping_mul(h));
        }
        out
    }
}

/// Pixels per chunk of the 32-bit span loops (modules `one` and
/// `point`): their forward differences are re-seeded exactly at each
/// chunk's first pixel.
const CHUNK: usize = 32;

/// The span driver of the 32-bit loops: `chunk(i, k, buf)` puts the
/// colours (`r | g << 8 | b << 16`) of the `k <= CHUNK` pixels from pixel
/// `i` into `buf` and returns `false`, or their light terms, returning
/// `true`: then the colour of a passing pixel is `terms` of its entry
/// (the channels computed only for the pixels that pass, in the same loop
/// as the depth test and the write). The driver gives them to `out`
/// ([`Out::chunk`]: one short loop per pixel and depth format) and
/// returns how many pixels
/// passed. The buffer (128 bytes) is zeroed once a span; the point loop
/// calls the driver from a function of its own (not inlined), so that
/// its buffers stay off the renderer's frame.
#[inline(always)]
fn drive(
    len: u32,
    chunk: impl FnMut(u32, u32, &mut [u32; CHUNK]) -> bool,
    terms: impl Fn(u32) -> [i32; 3] + Copy,
    out: &mut impl Out,
) -> u32 {
    drive_in(&mut [0u32; CHUNK], len, chunk, terms, out)
}

/// [`drive`] with the buffer `buf` (kept by the caller: no zeroing a
/// span).
#[inline(always)]
fn drive_in(
    buf: &mut [u32; CHUNK],
    len: u32,
    mut chunk: impl FnMut(u32, u32, &mut [u32; CHUNK]) -> bool,
    terms: impl Fn(u32) -> [i32; 3] + Copy,
    out: &mut impl Out,
) -> u32 {
    // Failures counted (the rarer case in a frame), passes derived.
    let mut failed = 0;
    let mut i = 0u32;
    while i < len {
        let k = (len - i).min(CHUNK as u32);
        let t = chunk(i, k, buf);
        let b = buf.get(..k as usize).unwrap_or_default();
        failed += if t {
            out.chunk(i, b, terms)
        } else {
            out.chunk(i, b, unpack_q19)
        };
        i += k;
    }
    len - failed
}

/// `r | g << 8 | b << 16`.
#[inline(always)]
fn pack(c: Rgb8) -> u32 {
    u32::from(c.r) | u32::from(c.g) << 8 | u32::from(c.b) << 16
}

/// The colour of `r | g << 8 | b << 16`.
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn unpack(c: u32) -> Rgb8 {
    Rgb8::new(c as u8, (c >> 8) as u8, (c >> 16) as u8)
}

/// The channel sums (Q19) of the colour `r | g << 8 | b << 16`: its
/// levels, exactly ([`PixelFormat::encode_q19`]).
#[inline(always)]
#[allow(clippy::cast_possible_wrap)]
fn unpack_q19(c: u32) -> [i32; 3] {
    [
        ((c & 0xFF) << 19) as i32,
        ((c >> 8 & 0xFF) << 19) as i32,
        ((c >> 16 & 0xFF) << 19) as i32,
    ]
}

mod multi;
mod one;
mod point;
#[cfg(test)]
mod tests;
mod tri;

pub use tri::{QuadSlot, TriQuad};

/// Set-ups of the point light's quadratics made fine (module `point`) on
/// this thread so far.
#[cfg(test)]
pub(crate) fn tri_fines() -> u32 {
    tri::FINES.with(|c| c.get())
}

/// Set-ups of the point light's quadratics made with the viewer alone
/// fine (module `point`) on this thread so far.
#[cfg(test)]
pub(crate) fn tri_fines_v() -> u32 {
    tri::FINES_V.with(|c| c.get())
}

/// Set-ups of the point light's quadratics whose `1/|ṽ|` is a quadratic a
/// chunk (`point::VIEW_QUAD`) made on this thread so far.
#[cfg(test)]
pub(crate) fn tri_quads_v() -> u32 {
    tri::QUADS_V.with(|c| c.get())
}

/// Set-ups of the point light's quadratics whose `1/|n|` is a quadratic a
/// chunk too (`point::NORMAL_QUAD`) made on this thread so far.
#[cfg(test)]
pub(crate) fn tri_quads_n() -> u32 {
    tri::QUADS_N.with(|c| c.get())
}

/// Set-ups of the point light's quadratics made on this thread so far.
#[cfg(test)]
pub(crate) fn tri_makes() -> u32 {
    tri::MAKES.with(|c| c.get())
}
