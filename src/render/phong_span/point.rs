//! One point light, local viewer, Phong: the 32-bit span loop.
//!
//! With `l = Lp - p` and `v = -p` linear along the span (eye position `p`)
//! and the normal `n` linear, every scalar the colour needs is a
//! quadratic in the pixel index: `A = |n|²`, `B = |l|²`, `C = |v|²`,
//! `D = n·l`, `E = n·v`, `F = l·v`. Then
//!
//! ```text
//! N·L = D / (|n| |l|)
//! 1 - R·V = w,   w·A = A + G (F·A - 2 D E),   G = 1 / (|l| |v|)
//! ```
//!
//! (`R·V = 2 (N·L)(N·V) - L·V`; per pixel as `w·A = A (1 + L̂·V̂) - 2
//! (n·L̂)(n·V̂)`). The specular table takes `m·w = m·(w·A)/A` as the
//! directional loop takes `Q/|n|²`: `1/A` from the table
//! [`RS`](super::RS) only scales `w` (a relative error), but `1/|l|` and
//! `1/|v|` enter `w` absolutely (an error `ε` of either moves `w` by
//! `ε·R·V`), so they come from one step of the series of `(1 -
//! e)^(-1/2)` per pixel ([`newton`]) seeded by the linear extrapolation of
//! the two previous pixels' values: with steps of at most `|l|/16` the
//! seed is within `3·2^-8` (the second difference of `1/|l|` is below
//! `3 (|dl|/|l|)²` of it), `e = 1 - b s²` within `2^-5.4`, the step within
//! `0.28 e⁴ = 2^-23.4`, plus truncations of `2^-23`.
//!
//! The span is cut into chunks of [`PCHUNK`] pixels; at each chunk's first
//! pixel the six quadratics are computed exactly in 64 bits from the
//! pixel's vectors (`l` and `v` scaled by powers of two per chunk so that
//! `|l̃|²` and `|ṽ|²` start in `[1/2, 2)`), rounded to 32-bit forward
//! differences (after 31 steps within `0.5 + 15.5 + 232` units of `2^-29`:
//! `2^-21` relative), and the first two seeds come from the table
//! [`RS`](super::RS) (`2^-11.4`; the step takes them to `2^-30`). The
//! error of `w` is then within `2^-19` (forward differences of `D`, `E`,
//! `F` `3·2^-21`, `1/|l|` and `1/|v|` `2^-22`, products `2^-24` each),
//! which times the shininess `m < 256` moves the table position by less
//! than `2^-11` of the specular range: the loop runs for `m < 256` (the
//! table's scale `K·2^19` below `2^31`), higher shininesses take the
//! 64-bit per-pixel path. Measured against `f64` in this module's tests
//! (`random_spans_against_f64`, `highlight_peak_set`, `point_loop_runs`).
//!
//! A span of more than one chunk takes its 64-bit triples once, at its
//! first pixel, with its ranges proven over the whole span ([`Plan`],
//! `PhongKernel::point_plan`), and steps them exactly from chunk to chunk
//! by shifts and adds (`f(t + 32) = f + 32 f' + 496 f''`): each chunk
//! then rounds them and takes its seeds, without products or range tests
//! (the same 32-bit state as its own set-up when its scales are the
//! span's: `point_plan_equals_chunk_setup`). A single-chunk span keeps
//! the set-up from its vectors (`point_setup`); spans and chunks below
//! [`SHORT_SPAN`] pixels take their pixels one by one, each by the
//! loop's arithmetic at that pixel alone (`PhongKernel::point_one`: exact
//! values, table seed and one series step; else the 64-bit path).
//! Measured on the firmware (span sweep of 200-pixel spans less 1-pixel
//! ones, a pixel; dodecahedron Phong raster): M4 191.05 -> 176.38 and
//! 2 010 978 -> 1 892 522, M0 763.10 -> 698.56 and 6 699 059 ->
//! 6 261 194 (the plan, `point_one` and its threshold, a cheaper
//! per-span range check and step test, the packed `1/|n|` table and, on
//! the M0, `F̃·G` in the last pass); frames unchanged on the firmware.
//! Then [`newton`]'s `e²` term from two 32-bit products (`MULS` on the
//! M0) and one group of passes a chunk ([`GROUP`]): M4 167.75 -> 163.52
//! and 1 700 554 -> 1 678 691, M0 661.65 -> 559.69 and 5 470 644 ->
//! 4 792 322; frames unchanged on the firmware and in the reference
//! images. Then the specular table's scale kept to its top 16 bits
//! ([`KScale`]: the position within one unit of its Q7 segments of the
//! whole scale's; two `MULS` on the M0) and, on the M0, the loop's
//! high-half products in the carry form now `wide::mulhi_split`'s (the same values, three
//! instructions fewer each): M4 163.52 -> 163.18 and 1 678 691 ->
//! 1 684 470 (`point_one`'s scale without a stack slot: 163.09 and
//! 1 688 572 with it), M0 559.69 -> 547.04 -> 502.41 and 4 792 322 ->
//! 4 774 038 -> 4 476 543; frames unchanged on the firmware and in the
//! reference images. Then [`Plan::chunk_hi`] inlined on the M0, the
//! plan's constant second differences set once a row set-up
//! (`TriQuad::set_row`) and [`TRI_SHORT_SPAN`] 2 on the M0: M4 1 684 470
//! -> 1 667 249 and 161.91 -> 161.72, M0 4 476 543 -> 4 388 305 and
//! 501.48 -> 497.06; frames unchanged. Measured and not kept: the
//! colours written by the loop's last pass itself (the depth mask
//! first, then each passing pixel's channels and encoding in that pass,
//! no buffer of terms and no separate colour loop): M4 161.91 -> 171.44
//! and 1 684 470 -> 1 699 895, M0 501.48 -> 503.71 and 4 476 543 ->
//! 4 524 192 (the colour constants and the row spilled in the last
//! pass, which already holds the state of `|n|²`, the tables and the
//! scale); `F̃·G` in the pass of `1/|ṽ|` on the M4 (no pass of its own):
//! 161.91 -> 164.98 and 1 684 470 -> 1 697 859.
//!
//! # Fine chunks
//! Where the steps of `l̃` and `ṽ` are at most `1/64` of their lengths
//! over the whole chunk (a span's plan or set-up, or a triangle's
//! quadratics, prove it with the ranges: [`Chunk::fine`]; the light and
//! the eye at least ~64 pixels' steps from the surface), the linear
//! extrapolation of the two previous values is within `2 r² (1 + 4r)`
//! of `1/|l|` (`r` the step's ratio, the second derivative of `1/|l +
//! t·d|` lying in `[-r², 2r²]` of it): `2^-10.8`, and one first-order
//! step ([`newton_lin`], `s (1 + e/2)`: three high halves and three
//! instructions, no `e²` term) takes it within `0.38 e² + 2^-23 <
//! 2^-20.8`, so the error of `w` stays within `2^-18.7` (`m < 256`: the
//! table position within `2^-10.7` of the specular range). The chunk's
//! first value is one such step from the table ([`seeds_fine`]: within
//! `2^-22`), its second seed the table's. The chunk functions are made
//! per kind (fine or not: each its seeds and two loops). Frames
//! unchanged on the firmware (every CRC) and in the reference images.
//! Measured (span sweep phong-kpoint, a pixel; dodecahedron Phong
//! raster, whose triangles are mostly not fine, its light being close:
//! 6 set-ups of 36): M4 161.72 -> 154.02 and 1 665 656 -> 1 660 949, M0
//! 497.06 -> 490.37 and 4 385 013 -> 4 378 217. Measured and not kept
//! (the same order: M4 sweep and frame, M0 sweep and frame): the fine
//! flag in the plan (`Plan`, inside [`TriQuad`]: its buffers' offsets
//! moved, M0 `TriQuad::plan` +27 000) with one chunk function for both
//! kinds (four loops) and `y1` a full series step from `y0`, 152.48,
//! 1 659 900, 496.66, 4 461 682; so with two first-order steps, 151.56,
//! 1 655 406, 493.10, 4 469 164; the flag beside the plan, one chunk
//! function, 152.97, 1 668 216, 493.44, 4 436 700; a chunk function per
//! kind, two first-order steps, 152.89, 1 657 873, 496.33, 4 401 329.
//!
//! A triangle whose viewer alone is fine (the eye far, the light close:
//! most of the dodecahedron Phong frame's set-ups) takes the fine seeds
//! and step for `1/|ṽ|` only ([`SPLIT_FINE`]; `1/|l̃|` keeps the series
//! step): a chunk function of its own. Frames unchanged (every CRC, the
//! reference images); tested against `f64` (`tri_quad_close_light_against_f64`:
//! 54 such triangles within 0.654 levels). Measured (dodecahedron Phong
//! raster; span sweep phong-kpoint, a pixel): M4 1 617 338 -> 1 593 035
//! and 151.74 -> 151.78, M0 4 229 401 -> 4 243 027 and 486.11 -> 483.14
//! (the M0 with one span driver choosing the chunk function a chunk; with
//! a driver per function as the M4, 4 251 961; the M0's per-pixel step
//! gains ~9 instructions where its chunk's fine seed costs ~55).
//!
//! # The viewer's quadratic
//! A triangle whose view vector steps by at most `r` of its length a
//! pixel, with `m·3152·r³ <= 2^-10` (`m` bounded by the table scale:
//! [`view_quad_min`]; `r <= 1/407` at `m = 20`, `1/689` at `m = 100`),
//! takes `1/|ṽ|` as a quadratic a chunk ([`view_quad`]: through its
//! values at the chunk's pixels 0, 16 and 32, within `3152 r³ + 2^-19`,
//! relative) by forward differences, two additions a pixel for the
//! extrapolation, the first-order step and its moves ([`TriQuad`]'s
//! `fine_v` 2; chunk functions of their own, the light fine or not).
//! `w` moves by as much (`ε·R·V`), the specular factor by at most
//! `m·ε`: a quarter level. Tested against `f64` (`view_quad_error`:
//! within 0.60 of the bound) and against the series step on the same
//! chunks (`point_view_quad_against_series`). Measured (span sweep
//! phong-kpoint, a pixel; its viewer `r` = 1/510): M4 151.78 -> 146.28,
//! M0 483.14 -> 426.11 (`F̃·G` in the quadratic's pass on both). The
//! dodecahedron Phong frame's triangles are outside the bound (`m` =
//! 100, a 40° field over 160 pixels: `r` >= 1/229): its frame
//! unchanged but for the code's layout and the chunk functions' choice
//! (M4 1 626 703 -> 1 630 515, M0 4 300 909 -> 4 306 635). Measured and
//! not kept: `F̃·G` in its own pass after the quadratic's (M4 146.29 ->
//! 152.66, [`VQ_FG`]); `1/|n|` a quadratic a chunk too ([`NORMAL_QUAD`],
//! off: M4 146.32 -> 151.25).
//!
//! In the renderers a span's plan comes from its triangle's quadratics
//! instead ([`TriQuad`], module `tri`: set up once a triangle, the row
//! stepped in y), already in the loop's units times `2^32`, so that a
//! chunk's state is the plan's high words ([`Plan::hi`], read by the
//! loop where they lie; on ARMv6-M built first, [`Plan::chunk_hi`]); spans
//! below [`TRI_SHORT_SPAN`] pixels keep `point_one`. The loop is the same.
//!
//! Per pixel (three passes over the chunk, few live values each, all
//! 32-bit): `1/|l̃|` and `n·L̂`; `1/|ṽ|`, `n·V̂` and `L̂·V̂`; `A`, `w·A`,
//! then the light terms as the directional loop ([`PhongKernel::terms`]),
//! whose channels the span driver computes per passing pixel.
//! Chunks outside the proven ranges (`A` in `[1/4, 5/4)`, `|l̃|²` and
//! `|ṽ|²` in `(1/4, 4)`, steps of at most 1/16 of `|l|` and `|v|`, every
//! value within `i32`) take the 64-bit per-pixel path
//! (`PhongKernel::general_px`).
//!
//! # The floor (issue 15: 90 instructions a pixel on the M4)
//! Counted on the firmware's span sweep phong-kpoint (M4, 151.78 a
//! pixel; its chunks fine: `tri_chunk::<true, true>`), from the executed
//! instructions of each pass (the disassembly's counts over the 3 200
//! pixels of its long spans) against the fewest instructions each term
//! needs at its stated error, registers allowing (`floor`):
//!
//! ```text
//! term (per pixel)                          now    floor
//! pass 1: 1/|l̃| (B step 2, seed 1, step 4),
//!         n·L̂ (D step 2, SMMUL, LSL), stores 19.25  13
//! pass 2: 1/|ṽ| (as 1/|l̃|), (n·L̂)(n·V̂) 3,
//!         G = 1/(|l̃||ṽ|) 2, loads, stores   23.0   18
//! pass 3: F̃·G (F step 2, SMMUL, LSL, ld/st)  8.1    6
//! pass 4: A step 2, 1/|n| packed table 8,
//!         w·A 3, clamp and K 3, 1/|n|² 3,
//!         position 3, table 6 (two LDRH), N·L 3,
//!         n·L > 0 test 2, pack 2, store 1    49.0   38
//! colour (`paint`): 6 SMLA, 3 USAT, 3 ORR/LSL,
//!         REV, STRH, load, EOR               22.0   15
//! depth test (`mask_in_range`)                8.6    6
//! chunk set-up (plan step 172, seeds ~90,
//!         driver ~350 a chunk of 32)         21.8    5
//! total                                     151.8  101
//! ```
//!
//! Above their floor: the passes' spills (16.75 stack loads and stores a
//! pixel: pass 1 3.5, pass 2 2, pass 3 0.75, pass 4 5.5, colour 5: the
//! colour's six channel constants and the loops' states do not fit the
//! twelve free registers), the loop control of four passes and the
//! values handed between them (seven words a pixel stored and loaded
//! again: `1/|l̃|`, `n·L̂`, `G`, `(n·L̂)(n·V̂)`, `F̃·G`, the terms), and
//! the chunk's set-up (`Plan::step_chunk` steps six 64-bit triples, 5.4
//! a pixel, where the loop reads the high words only). Even at every
//! floor the present formulation costs ~101: the sum is above 90. What
//! the error bounds allow cheaper:
//! - `1/|ṽ|` (the eye far: `|dṽ|/|ṽ| = r` ~1/300 a pixel for a 60°
//!   field of 320 pixels, 1/500 in the sweep) by forward differences of
//!   a quadratic through its exact values at the chunk's pixels 0, 16
//!   and 32: within `r³·1576·(1 + 4r)` of it relative (the Taylor
//!   coefficients of `1/|v + t·d|` are below `r^k/|v|`, Legendre's
//!   bound, and `|t(t - 16)(t - 32)| <= 1576` on `[0, 32]`), `2^-16.3`
//!   at `r = 1/500`; `w` moves by as much (`ε·R·V`), the table position
//!   by `m` times it. Per pixel 2 additions for the 5 of the step and the
//!   seed and the state's moves: floor 96; the set-up three exact values
//!   a chunk (~75, 2.3 a pixel).
//! - `n·V̂` and `l̃·V̂` (`E/|ṽ|`, `F̃/|ṽ|`) as quadratics of their own
//!   (the interpolation error then has the normal's step in it: `2|n|(r³
//!   + ν r²)·1576`, `ν` the normal's relative step, ~0.003 in the sweep:
//!   `2^-13.9`, too large for `m` = 256 within `2^-11` of the table):
//!   `w·A = A + A·(ŷ_l·l̃·V̂) - 2 (n·L̂)(n·V̂)`, three products for five,
//!   steps 4 for 6: floor 89, for small `m·r²ν` only.
//! - The series step on `|l̃|²·|ṽ|²` for `G` (a product and a step for
//!   the step of `1/|ṽ|` and a product): no gain while `N·L` needs
//!   `1/|l̃|` alone; the diffuse and specular terms already share it.
//! - `1/|n|` by the first-order step from the extrapolated seed (as
//!   `1/|l̃|`, `|dn|/|n|` at most 1/64): 2 + 5 for 10, but `1/|n|²`
//!   then takes its own product: floor −2.
//!
//! Built: the first of these ([`VIEW_QUAD`], [`view_quad`], below), the
//! viewer's pass then `F̃·G` too: passes 2 and 3 31.1 -> 23.5 a pixel
//! (4.5 of it spills: the quadratic's three words, `E`'s and `F̃`'s
//! beside the pointers), its set-up three first-order steps a chunk.
//!
//! So the floor of the stated bounds is ~89 on the M4 with every term at
//! its floor and no spill, which four passes of twelve registers do not
//! give (each value handed between passes costs a store and a load).
//! The M0 (483.14, 2.5 × 90 = 225): `wide::mulhi_split` alone is 218
//! a pixel (its eleven high halves ~20 instructions each), the specular
//! table 27, the channels 22, the encoding 20: its floor is that of the
//! high halves; each one the formulation drops saves ~20 there.

use super::one::{rsq_biased, Colour, RS_PACKED};
use super::tri::TriQuad;
use super::{
    drive, drive_in, fallback, pack, rsqrt_n, sq3, KLight, LightSpan, Out, PhongKernel, Planes,
    CHUNK,
};
use crate::num::wide::{clz32, mulhi, wmul};
use crate::num::Real;
use crate::target::{level_q19, Rgb8};

/// Spans and chunks below this many pixels take their pixels one by one
/// (after the depth test; [`PhongKernel::point_one`], else the 64-bit
/// path): below it that costs less than a chunk's set-up (`point_setup`,
/// ~900 instructions on the M4). Measured on the dodecahedron Phong
/// frame, raster (M4, M0), with the 64-bit path alone: 4 pixels
/// 2 020 376, 6 638 466; 2 pixels 2 080 579, 6 769 434; 6 pixels
/// 2 008 015, 6 605 652; 8 pixels 2 040 850 on the M4; later, against 6
/// pixels' 1 974 841 and 6 415 672, 7 pixels 1 988 909 and 6 444 635.
/// With `point_one`: 6 pixels 1 894 107 and 6 274 357, 8 pixels
/// 1 892 522 and 6 261 194, 12 pixels 1 951 815 and 6 417 166.
const SHORT_SPAN: u32 = 8;
/// Spans below this many pixels of a triangle with quadratics
/// ([`TriQuad`]) take their pixels one by one as below [`SHORT_SPAN`].
/// Measured on the dodecahedron Phong raster after the plan's second
/// differences moved to `TriQuad::set_row`: M4 with 3 pixels 1 667 249
/// -> 1 671 187 (4 kept); M0 with 3, 2 and 1 pixels 4 419 572 ->
/// 4 395 340, 4 388 305 and 4 407 939 (2 kept); frames unchanged.
pub(super) const TRI_SHORT_SPAN: u32 = if cfg!(armv6m) { 2 } else { 4 };
/// Pixels per chunk (the span driver's).
pub(super) const PCHUNK: usize = CHUNK;
/// Largest specular table scale `K·2^8` ([`PhongKernel`]'s `kf`) the
/// loop runs (`m < 256`, see the module docs).
pub(super) const KF_MAX: u32 = 1 << 20;

/// A triangle whose view vector steps by at most `r` of its length a
/// pixel with `m·3152·r³ <= 2^-10` ([`view_quad_min`]) takes `1/|ṽ|`
/// as a quadratic a chunk ([`view_quad`]: forward differences, two
/// additions a pixel) instead of the series step a pixel.
pub(super) const VIEW_QUAD: bool = true;

/// A triangle whose `1/|ṽ|` is a quadratic ([`VIEW_QUAD`]) and whose
/// normal steps by at most `2^-7.5` of its length a pixel would take
/// `1/|n|` as a quadratic a chunk too ([`view_quad`] of `|n|²`: within
/// `3152·2^-22.5 + 2^-19 < 2^-10.8`, relative) instead of the table
/// [`RS`](super::RS) (`2^-11.4`) a pixel: `N·L` moves by as much
/// (relative), the table position `K·w·A/|n|²` by twice that (relative:
/// the specular factor by less than `2^-9.8 · max x·e^-x`). Other than on
/// ARMv6-M. Measured worse and off: span sweep phong-kpoint M4 146.32 ->
/// 151.25 a pixel (the last pass, which already spills, holding three
/// more values; the table's nine instructions a pixel gone), with the
/// bound `2^-8` (the sweep's normal steps just above it: no triangle
/// took it) 146.29 -> 146.32; stepped in a pass of its own into the
/// [`Px`]s (the last pass loading it), 146.28 -> 152.00.
pub(super) const NORMAL_QUAD: bool = false;

/// `F̃·G` in the pass of the quadratic `1/|ṽ|` ([`VIEW_QUAD`]) other than
/// on ARMv6-M (whose loop takes it in the last pass, [`FUSED_FG`]), else
/// in a pass of its own as the series step's. Measured (span sweep
/// phong-kpoint, M4): its own pass 146.29 -> 152.66 a pixel.
const VQ_FG: bool = true;

/// [`VQ_FG`] on ARMv6-M too (not in the last pass, [`FUSED_FG`]: the
/// same values). Measured (span sweep phong-kpoint, M0): 428.64 ->
/// 426.11 a pixel.
const VQ_FG_M0: bool = true;

/// The smallest `M` with `M³ >= (3152·m·2^10)²` and `M >= 2^16`, for `m`
/// in `0..=256`: steps of the view vector of at most `r` of its length
/// with `r² <= 1/M` keep [`view_quad`]'s error `3152 r³` within
/// `2^-10/m` (and `r <= 2^-8`).
const VQ_MIN: [u32; 257] = {
    let mut t = [0u32; 257];
    let mut m = 0;
    while m <= 256 {
        let p = 3152 * 1024 * m as u64;
        let p2 = p * p;
        let (mut lo, mut hi) = (1u64 << 16, 1u64 << 21);
        // The smallest x in [lo, hi] with x³ >= p² (hi³ = 2^63 > p²).
        while lo < hi {
            let mid = (lo + hi) / 2;
            if mid * mid * mid >= p2 {
                hi = mid;
            } else {
                lo = mid + 1;
            }
        }
        t[m] = lo as u32;
        m += 1;
    }
    t
};

/// [`VQ_MIN`] of the shininess bound of the table scale `kf` (`K·2^8 =
/// 4096 m` for `m >= 8`, `2^15` below: `m <= kf/2^12 + 1`).
#[inline(always)]
pub(super) fn view_quad_min(kf: u32) -> i64 {
    let m = ((kf >> 12) + 1).min(256) as usize;
    i64::from(VQ_MIN.get(m).copied().unwrap_or(u32::MAX))
}

/// `1/|ṽ|` over a chunk as a quadratic: its value, first and second
/// differences (Q29) from the exact values (one first-order step from
/// the table, [`newton_lin`]: `|e| < 2^-10.4`, within `2^-21.6`) at the
/// chunk's pixels 0, 16 and 32, `C = |ṽ|²` stepped from its 32-bit
/// forward difference `c` (`None`: a value out of the table). Within
/// `3152 r³ + 2^-19` of `1/|ṽ|` (relative) over
/// the chunk's 32 pixels, `r <= 2^-8` the view vector's step over its
/// length: the Taylor coefficients of `1/|v + t·d|` are below
/// `r^k/|v|` (Legendre's generating function), `|t (t - 16) (t - 32)|
/// <= 1576` on `[0, 32]`, `(1 - 32 r)^-4 < 2`; the nodes' `2^-21.6`
/// times 1.25, the roundings of the differences 264 units of `2^-29`
/// (`1/|ṽ| > 1/2`). Measured with [`newton`]'s series step for the
/// nodes (within `2^-22`): span sweep phong-kpoint M4 147.14, M0 430.86.
#[inline(always)]
fn view_quad((c0, c1, c2): (i32, i32, i32)) -> Option<(i32, i32, i32)> {
    let c16 = c0.wrapping_add(c1 << 4).wrapping_add(c2.wrapping_mul(120));
    let c32 = c0.wrapping_add(c1 << 5).wrapping_add(c2.wrapping_mul(496));
    let u0 = newton_lin(seed(c0)?, c0);
    let u16 = newton_lin(seed(c16)?, c16);
    let u32 = newton_lin(seed(c32)?, c32);
    // f(t) = u0 + t·a + t(t - 1)/2 · b through the three values.
    let b = (u0
        .wrapping_sub(u16.wrapping_mul(2))
        .wrapping_add(u32)
        .wrapping_add(128))
        >> 8;
    let a = (u16
        .wrapping_sub(u0)
        .wrapping_sub(b.wrapping_mul(120))
        .wrapping_add(8))
        >> 4;
    Some((u0, a, b))
}

/// `round(x / 2^s)` for `s` in `1..64`, `x·2^-s` (exact) for `s` in
/// `-31..=0`; `None` past `i32`.
#[inline(always)]
fn shr_round(x: i64, s: i32) -> Option<i32> {
    if s >= 1 {
        i32::try_from((x >> (s - 1)).wrapping_add(1) >> 1).ok()
    } else {
        let y = i32::try_from(x).ok()?;
        let k = s.unsigned_abs();
        let z = y.checked_shl(k)?;
        (z >> k == y).then_some(z)
    }
}

/// `x / 2^s` as [`shr_round`], modulo `2^32` (no range check).
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn shr_wrap(x: i64, s: i32) -> i32 {
    if s >= 1 {
        ((x >> (s - 1)).wrapping_add(1) >> 1) as i32
    } else {
        (x as i32).wrapping_shl(s.unsigned_abs())
    }
}

/// `(f(0), f(1) - f(0), f(2) - 2 f(1) + f(0))` of `f(i) = (a + i·da)·(b
/// + i·db)`, exact (wrapping: callers keep the true values within `i64`).
#[inline(always)]
fn prod(a: [i32; 3], da: [i32; 3], b: [i32; 3], db: [i32; 3]) -> [i64; 3] {
    let mut c = [0i64; 3];
    for k in 0..3 {
        let ab = wmul(a[k], b[k]);
        let cross = wmul(a[k], db[k]).wrapping_add(wmul(da[k], b[k]));
        let dd = wmul(da[k], db[k]);
        c[0] = c[0].wrapping_add(ab);
        c[1] = c[1].wrapping_add(cross).wrapping_add(dd);
        c[2] = c[2].wrapping_add(dd.wrapping_mul(2));
    }
    c
}

/// The exact difference triple `c` divided by `2^s` (rounded) as a 32-bit
/// forward difference over `k` steps, with bounds of its values over them
/// (`None`: a value may leave `i32`).
#[inline(always)]
fn fwd32(c: [i64; 3], s: i32, k: usize) -> Option<((i32, i32, i32), i64, i64)> {
    let x0 = shr_round(c[0], s)?;
    let x1 = shr_round(c[1], s)?;
    let x2 = shr_round(c[2], s)?;
    // t <= 31: every product below 2^41 (`wmul`: no 64-bit multiply
    // call on ARMv6-M).
    let t = k.saturating_sub(1).min(PCHUNK) as i32;
    let w0 = i64::from(x0);
    let xe = w0 + wmul(x1, t) + wmul(x2, t * (t - 1) / 2);
    // A quadratic leaves its chord by at most |x2|·t²/8.
    let bow = wmul(x2, t * t).abs() >> 3;
    let lo = w0.min(xe) - bow;
    let hi = w0.max(xe) + bow;
    if lo <= i64::from(i32::MIN) || hi >= i64::from(i32::MAX) {
        return None;
    }
    Some(((x0, x1, x2), lo, hi))
}

/// Bounds of the values over `t` steps of the exact quadratic whose
/// difference triple is `c` divided by `2^s`, and its second difference
/// so rounded (`None`: a value may leave `i32`). From the triple rounded
/// to 32 bits: stepped, its values leave the exact ones by at most `½ +
/// ½·t + ¼·t(t - 1)` units (the roundings of the first and the second
/// difference), which the bounds add.
#[inline(always)]
fn span_bounds(c: [i64; 3], s: i32, t: i32) -> Option<(i32, i64, i64)> {
    let x0 = shr_round(c[0], s)?;
    let x1 = shr_round(c[1], s)?;
    let x2 = shr_round(c[2], s)?;
    // t < 2^12: every product below 2^56 (`wmul`: no 64-bit multiply
    // call on ARMv6-M).
    let w0 = i64::from(x0);
    let xe = w0 + wmul(x1, t) + wmul(x2, t * (t - 1) / 2);
    // A quadratic leaves its chord by at most |x2|·t²/8.
    let bow = (wmul(x2, t * t).abs() >> 3) + i64::from((t * t + t) / 4 + 1);
    let lo = w0.min(xe) - bow;
    let hi = w0.max(xe) + bow;
    if lo <= i64::from(i32::MIN) || hi >= i64::from(i32::MAX) {
        return None;
    }
    Some((x2, lo, hi))
}

/// `1/sqrt(b)` (`b` Q29, result Q29) from the seed `s` within `2^-6`
/// (relative): `s (1 + e/2 + 3e²/8 + 5e³/16)` with `e = 1 - b s²` (the
/// series of `(1 - e)^(-1/2)` to its fourth term: within `0.28 e⁴`, plus
/// the truncations' `2^-22.5`). `e` (`|e| < 2^-4.9`) and `b s²` take
/// products of operands of unknown sign (one `SMMUL` each on the M4); the
/// term `e² (3/8 + 5e/16)` only `2^-23` absolute, so it comes from `e` in
/// `Q20` (below `2^15.1`) by two 32-bit products (one `MULS` each on the
/// M0, instead of two split high halves): `e` floored to `2^-20` (`e²` by
/// `2^-24.4`), `e²` to `2^-24`, `3/8 + 5e/16` to `2^-14` (checked by
/// `newton_error`).
#[inline(always)]
fn newton(s: i32, b: i32) -> i32 {
    let sb = mulhi(s, b); // Q26 of s·b (<= 2^28.5)
    let e31 = ((1 << 23) - mulhi(sb, s)) << 8; // e · 2^31 (|e| < 1)
    let e20 = e31 >> 11;
    // e² (Q24, below 2^14.2) times 3/8 + 5e/16 (Q15): Q39, as Q32.
    let inner = 12_288i32.wrapping_add(e20 >> 7).wrapping_add(e20 >> 9);
    let e2 = (e20.wrapping_mul(e20) >> 16).wrapping_mul(inner) >> 7;
    s.wrapping_add(mulhi(s, e31.wrapping_add(e2)))
}

/// `1/sqrt(b)` (`b` Q29, result Q29) from a seed `s` within `2^-10.8`
/// (relative) by the series' first two terms: `s (1 + e/2)`, `e = 1 - b
/// s²` (`|e| < 2^-9.7`): within `0.38 e² < 2^-20.8` of it, plus the
/// truncations' `2^-23` (`e` floored to `2^-23`, three high halves):
/// the loop's step where its seeds are that close ([`Chunk::fine`]), three
/// high-half products and three instructions (the `e²` term of
/// [`newton`] costs ~8 more). Checked by `newton_lin_error`.
#[inline(always)]
fn newton_lin(s: i32, b: i32) -> i32 {
    let sb = mulhi(s, b); // Q26 of s·b (<= 2^28.5)
    let e31 = ((1 << 23) - mulhi(sb, s)) << 8; // e · 2^31 (|e| < 1)
    s.wrapping_add(mulhi(s, e31))
}

/// A chunk's 32-bit state.
#[cfg_attr(test, derive(Debug, PartialEq, Eq))]
struct Chunk {
    a: (i32, i32, i32),
    b: (i32, i32, i32),
    c: (i32, i32, i32),
    d: (i32, i32, i32),
    e: (i32, i32, i32),
    f: (i32, i32, i32),
    /// Newton states `(y(-2), y(-1))` of `1/|l̃|` and `1/|ṽ|` (Q29; the
    /// latter's third word 0), or `1/|ṽ|`'s quadratic ([`view_quad`]).
    yl: (i32, i32),
    yv: (i32, i32, i32),
    /// Steps of `l̃` and `ṽ` of at most `1/64` of their length over the
    /// chunk: the seeds from [`seeds_fine`], each pixel by
    /// [`newton_lin`] (the linear extrapolation within `2^-10.8`).
    fine: bool,
}

/// A span's plan: the six quadratics' exact difference triples ([`prod`]
/// of the span's scaled vectors: `A = |n|²`, `B = |l̃|²`, `C = |ṽ|²`, `D
/// = n·l̃`, `E = n·ṽ`, `F = l̃·ṽ`) at the first pixel of the chunk to come,
/// made once a span ([`PhongKernel::point_plan`], which proves the
/// ranges over the whole span) and stepped a chunk at a time by shifts
/// and adds ([`Plan::step_chunk`]). Wrapping `i64` arithmetic is exact
/// modulo `2^64` and every true value is within `i64` (`|n|² < 2^62.6`,
/// `|l̃|²`, `|ṽ|² < 2^60`, the others between), so a chunk starts from the
/// very products of its first pixel's vectors scaled by the span's powers
/// of two: the state of the chunk's own set-up (`point_setup`) whenever
/// its first pixel's scales are the span's (`point_plan_equals_chunk_setup`
/// checks it), else the same quantities at another scale, within the
/// same proven ranges.
#[derive(Clone, Copy, Debug)]
pub(super) struct Plan {
    pub(super) q: [[i64; 3]; 6],
}

impl Plan {
    /// The triples [`PCHUNK`] pixels on: `f(t + 32) = f + 32 f' + 496 f''`,
    /// `f'(t + 32) = f' + 32 f''`. Not inlined: inlined, its shifts of
    /// the plan were hoisted to every span's start, planned or not.
    #[inline(never)]
    pub(super) fn step_chunk(&mut self) {
        const { assert!(PCHUNK == 32) };
        for c in &mut self.q {
            let d2 = c[2];
            c[0] = c[0]
                .wrapping_add(c[1] << 5)
                .wrapping_add(d2 << 9)
                .wrapping_sub(d2 << 4);
            c[1] = c[1].wrapping_add(d2 << 5);
        }
    }

    /// The chunk's 32-bit state: the triples rounded (`A`, `D`, `E` Q30 of
    /// their product units, `B`, `C` Q29, `F` Q28: [`shr_wrap`] by 30, 29,
    /// 30), within `i32` by the plan's ranges, and the Newton seeds from
    /// the table (`None`: a seed out of the table). Not inlined (as
    /// `point_setup`).
    /// `fine`: steps of `l̃` and `ṽ` of at most `1/64` of their length
    /// over the whole span (or triangle), the chunk [`Chunk::fine`] (kept
    /// beside the plan, not in it: a field more in the triangle's
    /// [`TriQuad`] moved its buffers' offsets past the M0's immediate
    /// loads, 27 000 instructions more in `TriQuad::plan`).
    #[inline(never)]
    fn chunk(&self, fine: bool) -> Option<Chunk> {
        let r = |c: [i64; 3], s: i32| (shr_wrap(c[0], s), shr_wrap(c[1], s), shr_wrap(c[2], s));
        let [qa, qb, qc, qd, qe, qf] = self.q;
        let b = r(qb, 29);
        let c = r(qc, 29);
        Some(Chunk {
            a: r(qa, 30),
            b,
            c,
            d: r(qd, 30),
            e: r(qe, 30),
            f: r(qf, 30),
            yl: seeds_of(b.0, b.1, fine)?,
            yv: tri(seeds_of(c.0, c.1, fine)?),
            fine,
        })
    }

    /// [`Plan::chunk`] of a plan whose triples are already in the loop's
    /// units times `2^32` (a triangle's, [`TriQuad`]: the values biased
    /// by `2^31`, so that their high words are rounded, the differences'
    /// floored): the high words. The ARMv6-M's (inlined: the state
    /// straight into the loop's frame: dodecahedron Phong raster 4 476 543
    /// -> 4 427 143, span sweep 501.48 -> 497.13 a pixel; the loop reading
    /// the plan's words itself, [`Plan::hi`], measured 4 378 217 ->
    /// 4 404 551 and 490.37 -> 495.65; this form, built from
    /// [`Plan::hi`] with the other targets' [`Plan::seeds_hi`] beside it,
    /// 4 378 217 -> 4 361 338 and 490.37 -> 488.40).
    /// `fv`: the seeds of `1/|ṽ|` fine ([`TriQuad`]'s fineness of the
    /// viewer, apart from the light's `fine`).
    #[inline(always)]
    fn chunk_hi(&self, fine: bool, fv: bool, vq: bool) -> Option<Chunk> {
        let [a, b, c, d, e, f] = self.hi();
        Some(Chunk {
            a,
            b,
            c,
            d,
            e,
            f,
            yl: seeds_of(b.0, b.1, fine)?,
            yv: if vq {
                view_quad(c)?
            } else {
                tri(seeds_of(c.0, c.1, fv)?)
            },
            fine: fine && fv,
        })
    }

    /// The chunk's triples of [`Plan::chunk_hi`], read by the loop
    /// straight from the plan other than on ARMv6-M: no [`Chunk`] built
    /// and copied into the loop's frame (`chunk_hi` not inlined there:
    /// inlined, the M4 had measured 1 684 470 -> 1 695 544). Dodecahedron
    /// Phong raster M4 1 651 911 -> 1 620 399, span sweep phong-kpoint
    /// 153.92 -> 151.54 a pixel.
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    fn hi(&self) -> [(i32, i32, i32); 6] {
        self.q.map(|c| {
            (
                (c[0] >> 32) as i32,
                (c[1] >> 32) as i32,
                (c[2] >> 32) as i32,
            )
        })
    }

    /// [`Plan::seeds_hi`] and, when `nq`, `2^13/|n|` (Q29: `2^16/|n|`
    /// times `2^13`) as a quadratic ([`view_quad`] of `|n|²`, Q29); else
    /// zeros.
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    fn seeds_hi_n(
        &self,
        fine: bool,
        fv: bool,
        vq: bool,
        nq: bool,
    ) -> Option<(Seeds, (i32, i32, i32))> {
        let yn = if nq {
            let c = self.q[0];
            let h = |x: i64| ((x >> 32) as i32) >> 1;
            view_quad((h(c[0]), h(c[1]), h(c[2])))?
        } else {
            (0, 0, 0)
        };
        Some((self.seeds_hi(fine, fv, vq)?, yn))
    }

    /// The Newton seeds of `1/|l̃|` and `1/|ṽ|` ([`Chunk::yl`], [`Chunk::yv`])
    /// of the chunk of [`Plan::hi`] (`None`: a seed out of the table),
    /// each fine or not (`fine`, `fv`).
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    fn seeds_hi(&self, fine: bool, fv: bool, vq: bool) -> Option<Seeds> {
        let hi = |c: [i64; 3]| ((c[0] >> 32) as i32, (c[1] >> 32) as i32);
        let (b0, b1) = hi(self.q[1]);
        let yl = seeds_of(b0, b1, fine)?;
        let yv = if vq {
            let c = self.q[2];
            view_quad((
                (c[0] >> 32) as i32,
                (c[1] >> 32) as i32,
                (c[2] >> 32) as i32,
            ))?
        } else {
            let (c0, c1) = hi(self.q[2]);
            tri(seeds_of(c0, c1, fv)?)
        };
        Some((yl, yv))
    }
}

/// Newton states of `1/|l̃|` and `1/|ṽ|` ([`Chunk::yl`], [`Chunk::yv`]).
type Seeds = ((i32, i32), (i32, i32, i32));

/// A Newton state `(y(-2), y(-1))` as [`Chunk::yv`] (third word 0).
#[inline(always)]
fn tri((a, b): (i32, i32)) -> (i32, i32, i32) {
    (a, b, 0)
}

/// `v` and its step `d` times `2^s`, `s` making the largest component
/// of `v` lie in `[2^28, 2^29)`, each component of the scaled step below
/// `2^26` (`None`: `v` zero or above `2^29`, or a larger step). One test
/// of the step's components ORed (they are all below `2^(26 - s)` when
/// their OR is).
#[inline(always)]
fn scale(v: [i32; 3], d: [i32; 3]) -> Option<([i32; 3], [i32; 3])> {
    let m = v[0].unsigned_abs() | v[1].unsigned_abs() | v[2].unsigned_abs();
    if m == 0 || m >= 1 << 29 {
        return None;
    }
    let s = clz32(m) - 3;
    let md = d[0].unsigned_abs() | d[1].unsigned_abs() | d[2].unsigned_abs();
    if u64::from(md) << s >= 1 << 26 {
        return None;
    }
    Some((v.map(|x| x << s), d.map(|x| x << s)))
}

/// Newton states `(y0 - 2δ, y0 - δ)` from table estimates `y0`, `y1` of
/// `1/sqrt` at a chunk's first two pixels (`x`: Q29 in `(1/6, 4)` and the
/// next value's difference), `δ = y1 - y0`: the loop's first two seeds are
/// `y0` and about `y1` (within `3 · 2^-11.4`).
#[inline(always)]
fn seeds(x0: i32, x1: i32) -> Option<(i32, i32)> {
    let y0 = seed(x0)?;
    let y1 = seed(x0.wrapping_add(x1))?;
    let dl = y1.wrapping_sub(y0);
    Some((y0.wrapping_sub(dl.wrapping_mul(2)), y0.wrapping_sub(dl)))
}

/// Newton states `(y0 - 2δ, y0 - δ)` as [`seeds`], `y0` the first-order
/// step ([`newton_lin`]) from the table at the chunk's first pixel
/// (`|e| < 2^-10.4`: within `2^-22`) and `y1` the table's at the next
/// (`2^-11.4`): the loop's first seed within `2^-22` of its value, the
/// second within `2^-11.3`, as close as [`newton_lin`] needs (the table
/// seeds of [`seeds`], `y0` not stepped, put the second within
/// `3·2^-11.4` and the step's error at `2^-19`).
#[inline(always)]
fn seeds_fine(x0: i32, x1: i32) -> Option<(i32, i32)> {
    let y0 = newton_lin(seed(x0)?, x0);
    let y1 = seed(x0.wrapping_add(x1))?;
    let dl = y1.wrapping_sub(y0);
    Some((y0.wrapping_sub(dl.wrapping_mul(2)), y0.wrapping_sub(dl)))
}

/// [`seeds_fine`] for a fine chunk ([`Chunk::fine`]), else [`seeds`].
#[inline(always)]
fn seeds_of(x0: i32, x1: i32, fine: bool) -> Option<(i32, i32)> {
    if fine {
        seeds_fine(x0, x1)
    } else {
        seeds(x0, x1)
    }
}

/// `1/sqrt(x)` (Q29) within `2^-11.4` relative for `x` (Q29) in `(1/6,
/// 4)`, from the table of [`rsqrt_n`] (`f = x/4`, `x` or `4x` in `[1/4,
/// 5/4)`, Q28). A function inlined (as a closure it was a call per seed).
#[inline(always)]
fn seed(x: i32) -> Option<i32> {
    let (f, s) = if x >= 1 << 29 {
        (x >> 3, 12)
    } else if x >= 1 << 27 {
        (x >> 1, 13)
    } else {
        (x << 1, 14)
    };
    let r = rsqrt_n(f)?;
    i32::try_from(r << s).ok()
}

/// The normal `n`, the view vector `-p` and the light vector `l - p` at
/// pixel `j` of a span (`v + j·d` of each, wrapping).
#[inline(always)]
#[allow(clippy::cast_possible_wrap)]
fn at_pixel(l: &KLight, (n, dn, p, dp): Planes, j: u32) -> ([i32; 3], [i32; 3], [i32; 3]) {
    let at = |v: [i32; 3], d: [i32; 3]| {
        [0, 1, 2].map(|a| v[a].wrapping_add(d[a].wrapping_mul(j as i32)))
    };
    let pj = at(p, dp);
    let lj = [0, 1, 2].map(|a| l.at[a].wrapping_sub(pj[a]));
    (at(n, dn), pj.map(i32::wrapping_neg), lj)
}

/// Per-pixel values between the passes of a chunk: `g`, first `1/|l̃|`
/// (Q29), then `G = 1/(|l̃| |ṽ|)` (Q28), then `L̂·V̂` (Q26); `nlnv`,
/// `(n·L̂)(n·V̂)` (Q28). (`n·L̂`, Q30, waits in the colour's place.)
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Px {
    g: i32,
    nlnv: i32,
}

impl Px {
    /// Zeros.
    pub(super) const ZERO: Self = Self { g: 0, nlnv: 0 };
}

/// `F̃·G` in the last pass of the point loop (ARMv6-M), else in a pass of
/// its own (ARMv7-M): the same values. Measured, fused: dodecahedron
/// Phong raster M0 6 605 652 -> 6 552 519, span sweep 695.81 -> 691.94
/// a pixel; M4 the frame unchanged (+47), the sweep 177.81 -> 179.82.
const FUSED_FG: bool = cfg!(armv6m);

/// A triangle whose viewer only is fine ([`TriQuad`]: the steps of `ṽ`
/// at most `1/64` of its length, not those of `l̃`) takes the fine
/// seeds and step for `1/|ṽ|` alone (its own chunk function).
const SPLIT_FINE: bool = true;

/// The specular table's scale `K·2^19` (`kf << 11`, below `2^31`) kept to
/// its top 16 bits: `kh · 2^t` (`kh < 2^16`, `t <= 15`), within `2^-15`
/// of it (relative), so that the table position `K·w·A` (Q7 segments,
/// below `2^15` within the table) moves by less than one unit of it
/// (`kscale_products`).
#[derive(Clone, Copy)]
struct KScale {
    kt: i32,
    kh: u32,
    t: u32,
}

impl KScale {
    /// The scale of `kf` (`< KF_MAX`).
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap)]
    fn of(kf: u32) -> Self {
        let kc = (kf << 11) & 0x7FFF_FFFF;
        let t = (32 - clz32(kc)).saturating_sub(16);
        let kh = kc >> t;
        Self {
            // Its sign hidden: one signed high-half product and the
            // position's saturation in one `USAT` on the M4.
            kt: core::hint::black_box((kh << t) as i32),
            kh,
            t,
        }
    }

    /// `kh·2^t` of the scale of `kf` as `kc & (0xFFFF_0000 >> clz(kc))`
    /// (`kc = kf·2^11`), the same value ([`PhongKernel::point_one`] other
    /// than on the M0).
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap)]
    #[cfg_attr(armv6m, allow(dead_code))]
    fn kt_of(kf: u32) -> i32 {
        let kc = kf << 11;
        (kc & (0xFFFF_0000 >> clz32(kc | 1))) as i32
    }

    /// `floor(w · kh · 2^t / 2^32)` for `0 <= w < 2^30`: `mulhi(w, kh·2^t)`;
    /// on the M0 from two 16-bit products ([`KScale::mul_split`]).
    #[inline(always)]
    fn mul(self, w: i32) -> i32 {
        if cfg!(armv6m) {
            self.mul_split(w)
        } else {
            mulhi(w, self.kt)
        }
    }

    /// [`KScale::mul`] from `w = 2^16 wh + wl`, nested floors: `(wh·kh +
    /// (wl·kh >> 16)) >> (16 - t)`, every product below `2^32` (compiled
    /// everywhere: tested on the host).
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)]
    #[cfg_attr(not(armv6m), allow(dead_code))]
    fn mul_split(self, w: i32) -> i32 {
        let w = w as u32;
        let hi = (w >> 16) * self.kh;
        let lo = ((w & 0xFFFF) * self.kh) >> 16;
        (hi.wrapping_add(lo) >> (16 - self.t)) as i32
    }
}

/// Pixels a group of the point loop's passes (the values between passes
/// of a group are kept in [`Px`]s: 256 bytes, on the stack zeroed once a
/// chunk, or kept in the triangle's [`TriQuad`]): a whole chunk, each
/// pass once a chunk. Measured against 16 (span sweep a pixel;
/// dodecahedron Phong raster): M4 167.75 -> 164.40 and 1 700 554 ->
/// 1 679 852, M0 561.17 -> 559.69 and 4 798 753 -> 4 792 322 (after
/// [`newton`]'s `e²` term in 32-bit products); 128 bytes more stack in
/// the Phong scenes (the [`TriQuad`] of the span filler).
pub(super) const GROUP: usize = 32;

impl<R: Real> PhongKernel<'_, R> {
    /// [`PhongKernel::fill`] for one point light, a local viewer and the
    /// Phong model with `kf < KF_MAX` (module docs); `n`, `dn` already
    /// flipped for back faces. Not inlined: its buffers (the driver's
    /// colours and [`Px`]s, 384 bytes) live in its own frame and
    /// `point_chunk`'s, not in the renderer's, whatever the layout drawn.
    #[inline(never)]
    #[allow(clippy::too_many_arguments, clippy::cast_possible_truncation)]
    pub(super) fn fill_point(&self, l: &KLight, span: Planes, len: u32, mut out: impl Out) -> u32 {
        if len < SHORT_SPAN {
            // The depth test first, then the passing pixels one by one
            // (`point_px`, as `point_chunk` for chunks this short).
            let c = Colour::of(self, l);
            let mut passed = 0;
            for i in 0..len {
                if out.test(i) {
                    out.write(i, self.point_px(l, &c, span, i));
                    passed += 1;
                }
            }
            return passed;
        }
        let c = Colour::of(self, l);
        // Spans of one chunk set it up from its vectors (`point_setup`),
        // longer ones from their plan stepped on (`point_plan`, else a
        // set-up a chunk).
        let mut plan = if len > PCHUNK as u32 {
            self.point_plan(l, span, len)
        } else {
            None
        };
        drive(
            len,
            |i, k, buf| self.point_chunk(l, &c, span, &mut plan, i, k as usize, buf),
            move |t| c.of_terms(t),
            &mut out,
        )
    }

    /// [`PhongKernel::fill`] for one point light, a local viewer and the
    /// Phong model from the triangle's quadratics ([`TriQuad`]) at the
    /// span's first pixel `(x, y)`: every chunk, the short ones too, from
    /// the plan so made ([`TriQuad::plan`]), no set-up of the span's
    /// vectors; the walked values `span` (normal flipped for back faces)
    /// serve only the 64-bit path of a chunk whose seeds leave the table.
    /// For spans of [`TRI_SHORT_SPAN`] pixels or more of a triangle whose
    /// set-up is made (`TriQuad::ready`: its ranges proven over the whole
    /// triangle); the shorter ones take [`PhongKernel::fill_point`].
    /// Not inlined, as [`PhongKernel::fill_point`].
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    pub(super) fn fill_point_tri(
        &self,
        l: &KLight,
        tri: &mut TriQuad,
        (x, y): (i32, i32),
        span: Planes,
        len: u32,
        mut out: impl Out,
    ) -> u32 {
        // The kernel's colour (of its only light, `l`): made once a kernel
        // (not on ARMv6-M: the kernel's `colour`).
        let own;
        #[cfg(not(armv6m))]
        let kept = self.colour.as_ref();
        #[cfg(armv6m)]
        let kept = None;
        let c = if let Some(c) = kept {
            c
        } else {
            own = Colour::of(self, l);
            &own
        };
        let planned = tri.plan(x, y, len);
        let (fine, fv, vq) = (tri.fine(), tri.fine_v(), tri.quad_v());
        let nq = NORMAL_QUAD && tri.quad_n() && !cfg!(armv6m);
        let TriQuad {
            span: pl, px, buf, ..
        } = tri;
        let mut plan = if planned { Some(pl) } else { None };
        // One chunk function for fine triangles, one for those whose
        // viewer only is fine ([`SPLIT_FINE`]), one for the others (each
        // with the two loops of its seeds and steps): a driver each, but
        // on ARMv6-M one driver choosing a chunk (the same values). Those
        // whose `1/|ṽ|` is a quadratic ([`VIEW_QUAD`]) have their own,
        // the light fine or not.
        let kind = match (fine, vq) {
            (true, true) if nq => 5,
            (false, true) if nq => 6,
            (true, true) => 3,
            (false, true) => 4,
            (true, false) => 0,
            _ if fv && SPLIT_FINE => 1,
            _ => 2,
        };
        if cfg!(armv6m) {
            return drive_in(
                buf,
                len,
                |i, k, buf| {
                    let k = k as usize;
                    let p = &mut plan;
                    match kind {
                        0 => {
                            self.tri_chunk::<true, true, false, false>(l, c, span, p, px, i, k, buf)
                        }
                        1 => self
                            .tri_chunk::<false, true, false, false>(l, c, span, p, px, i, k, buf),
                        3 => {
                            self.tri_chunk::<true, true, true, false>(l, c, span, p, px, i, k, buf)
                        }
                        4 => {
                            self.tri_chunk::<false, true, true, false>(l, c, span, p, px, i, k, buf)
                        }
                        _ => self
                            .tri_chunk::<false, false, false, false>(l, c, span, p, px, i, k, buf),
                    }
                },
                move |t| c.of_terms(t),
                &mut out,
            );
        }
        // A driver per chunk function (their const parameters).
        macro_rules! drive {
            ($fine:literal, $fv:literal, $vq:literal, $nq:literal) => {
                drive_in(
                    buf,
                    len,
                    |i, k, buf| {
                        self.tri_chunk::<$fine, $fv, $vq, $nq>(
                            l, c, span, &mut plan, px, i, k as usize, buf,
                        )
                    },
                    move |t| c.of_terms(t),
                    &mut out,
                )
            };
        }
        match kind {
            0 => drive!(true, true, false, false),
            1 => drive!(false, true, false, false),
            3 => drive!(true, true, true, false),
            4 => drive!(false, true, true, false),
            5 => drive!(true, true, true, true),
            6 => drive!(false, true, true, true),
            _ => drive!(false, false, false, false),
        }
    }

    /// [`PhongKernel::point_chunk`] of a span planned from its triangle:
    /// every chunk from the plan, stepped on.
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn tri_chunk<const FINE: bool, const FV: bool, const VQ: bool, const NQ: bool>(
        &self,
        l: &KLight,
        c: &Colour,
        span: Planes,
        plan: &mut Option<&mut Plan>,
        px: &mut [Px; GROUP],
        i: u32,
        k: usize,
        buf: &mut [u32; CHUNK],
    ) -> bool {
        if cfg!(armv6m) {
            // ARMv6-M: the chunk's state built (`Plan::chunk_hi`), the loop
            // reading it from there.
            let st = match plan {
                Some(pl) => {
                    if i > 0 {
                        pl.step_chunk();
                    }
                    pl.chunk_hi(FINE, FV, VQ)
                }
                None => None,
            };
            return match st {
                Some(st) if self.spec => {
                    self.point_run_in::<true, FINE, FV, VQ>(px, &st, k, buf);
                    true
                }
                Some(st) => {
                    self.point_run_in::<false, FINE, FV, VQ>(px, &st, k, buf);
                    true
                }
                None => {
                    for (j, o) in (i..i + k as u32).zip(buf.iter_mut()) {
                        *o = pack(self.point_px(l, c, span, j));
                    }
                    false
                }
            };
        }
        // Elsewhere the loop reads the plan's high words where they lie
        // (`Plan::hi`), only the seeds made first.
        let st = match plan {
            Some(pl) => {
                if i > 0 {
                    pl.step_chunk();
                }
                let pl: &Plan = pl;
                pl.seeds_hi_n(FINE, FV, VQ, NQ).map(|s| (pl, s))
            }
            None => None,
        };
        match st {
            Some((pl, (s, n))) if self.spec => {
                self.point_run_vals::<true, FINE, FV, VQ, NQ>(px, pl.hi(), s, n, k, buf);
                true
            }
            Some((pl, (s, n))) => {
                self.point_run_vals::<false, FINE, FV, VQ, NQ>(px, pl.hi(), s, n, k, buf);
                true
            }
            None => {
                for (j, o) in (i..i + k as u32).zip(buf.iter_mut()) {
                    *o = pack(self.point_px(l, c, span, j));
                }
                false
            }
        }
    }

    /// The light terms (`N·L | sp << 16`, [`PhongKernel::terms`]: returns
    /// `true`) or the colours (`r | g << 8 | b << 16`: `false`) of the `k`
    /// pixels from pixel `i` into `buf`.
    #[inline(never)]
    #[allow(clippy::type_complexity)]
    #[allow(clippy::too_many_arguments)]
    fn point_chunk(
        &self,
        l: &KLight,
        c: &Colour,
        span: Planes,
        plan: &mut Option<(Plan, bool)>,
        i: u32,
        k: usize,
        buf: &mut [u32; CHUNK],
    ) -> bool {
        // Below SHORT_SPAN pixels, pixel by pixel (`point_px`) costs
        // less than the set-up.
        let st = match plan {
            _ if k < SHORT_SPAN as usize => None,
            Some((pl, fine)) => {
                // The driver's chunks follow one another, PCHUNK pixels
                // apart.
                if i > 0 {
                    pl.step_chunk();
                }
                pl.chunk(*fine)
            }
            None => self.point_setup(l, span, i, k),
        };
        match st {
            Some(st) if self.spec && st.fine => {
                self.point_run::<true, true>(&st, k, buf);
                true
            }
            Some(st) if self.spec => {
                self.point_run::<true, false>(&st, k, buf);
                true
            }
            Some(st) if st.fine => {
                self.point_run::<false, true>(&st, k, buf);
                true
            }
            Some(st) => {
                self.point_run::<false, false>(&st, k, buf);
                true
            }
            None => {
                for (j, o) in (i..i + k as u32).zip(buf.iter_mut()) {
                    *o = pack(self.point_px(l, c, span, j));
                }
                false
            }
        }
    }

    /// The chunk's 32-bit state at pixel `i` (`None`: outside the proven
    /// ranges). Not inlined: its 64-bit set-up would share the loop's
    /// frame and registers.
    #[inline(never)]
    #[allow(
        clippy::cast_possible_wrap,
        clippy::cast_sign_loss,
        clippy::type_complexity
    )]
    fn point_setup(&self, l: &KLight, (n, dn, p, dp): Planes, i: u32, k: usize) -> Option<Chunk> {
        let at = |v: [i32; 3], d: [i32; 3]| {
            [0, 1, 2].map(|a| v[a].wrapping_add(d[a].wrapping_mul(i as i32)))
        };
        // Steps of the normal below 2^29 (1/2 a pixel), of l̃ and ṽ below
        // 2^26 (1/4 of their largest component): the products below stay
        // within i64 (|dn|² · 6 < 2^61).
        let small = |d: [i32; 3], b: u32| d.iter().all(|c| c.unsigned_abs() < 1 << b);
        if !small(dn, 29) {
            return None;
        }
        let nj = at(n, dn);
        let pj = at(p, dp);
        let vj = pj.map(i32::wrapping_neg);
        let dv = dp.map(i32::wrapping_neg);
        let lj = [0, 1, 2].map(|a| l.at[a].wrapping_sub(pj[a]));
        let (lt, dlt) = scale(lj, dv)?;
        let (vt, dvt) = scale(vj, dv)?;
        let (a32, alo, ahi) = fwd32(prod(nj, dn, nj, dn), 30, k)?;
        // The `1/|n|` table's range, with the drift (248 units) to spare.
        if alo < (1 << 28) + 256 || ahi >= (5 << 28) - 256 {
            return None;
        }
        // |l̃|², |ṽ|² (Q29, from [1/4, 3) at the first pixel) within (1/6,
        // 4), and steps of at most 1/16 of the length: |dl̃|² · 2^8 <= |l̃|²
        // (x.2 = 2 |dl̃|²).
        let (b32, blo, bhi) = fwd32(prod(lt, dlt, lt, dlt), 29, k)?;
        let (c32, clo, chi) = fwd32(prod(vt, dvt, vt, dvt), 29, k)?;
        // Fine (steps of at most 1/64: |dl̃|² · 2^12 <= |l̃|², the rounded
        // x.2 taken one unit up) when both are.
        let mut fine = true;
        for (x, lo, hi) in [(b32, blo, bhi), (c32, clo, chi)] {
            if lo <= (1 << 29) / 6 + 256 || hi >= (1 << 31) - 256 || i64::from(x.2) << 7 > lo - 256
            {
                return None;
            }
            fine &= (i64::from(x.2) + 1) << 11 <= lo - 256;
        }
        // |D̃| <= |n| |l̃| < 1.12 · 2 and |Ẽ| < 1.12 · 2 (Q29), |F̃| < 2 · 2
        // (Q28): within i32 over the chunk (the drift 248 units aside) by
        // the checks above; the first and second differences wrap
        // harmlessly (the values are exact modulo 2^32).
        let x32 = |c: [i64; 3]| -> (i32, i32, i32) {
            let r = |v: i64| ((v >> 29).wrapping_add(1) >> 1) as i32;
            (r(c[0]), r(c[1]), r(c[2]))
        };
        Some(Chunk {
            a: a32,
            b: b32,
            c: c32,
            d: x32(prod(nj, dn, lt, dlt)),
            e: x32(prod(nj, dn, vt, dvt)),
            f: x32(prod(lt, dlt, vt, dvt)),
            yl: seeds_of(b32.0, b32.1, fine)?,
            yv: tri(seeds_of(c32.0, c32.1, fine)?),
            fine,
        })
    }

    /// Whether the chunk of `k` pixels from pixel `i` runs the 32-bit loop
    /// from its own set-up (the tests' check that it is taken).
    #[cfg(test)]
    pub(super) fn point_loop_runs(&self, span: Planes, i: u32, k: usize) -> bool {
        self.lights
            .first()
            .is_some_and(|l| self.point_setup(l, span, i, k).is_some())
    }

    /// The span's plan (`None`: a value outside the proven ranges
    /// somewhere in the span of `len` pixels, `SHORT_SPAN..=4096`). Not
    /// inlined:
    /// its 64-bit set-up would share the loop's frame and registers.
    #[inline(never)]
    #[allow(clippy::cast_possible_wrap, clippy::type_complexity)]
    fn point_plan(&self, l: &KLight, (n, dn, p, dp): Planes, len: u32) -> Option<(Plan, bool)> {
        // Steps of the normal below 2^29 (1/2 a pixel), of l̃ and ṽ below
        // 2^26 (1/4 of their largest component): the products below stay
        // within i64 (|dn|² · 6 < 2^61).
        let small = |d: [i32; 3], b: u32| d.iter().all(|c| c.unsigned_abs() < 1 << b);
        if !small(dn, 29) || !(SHORT_SPAN..=4096).contains(&len) {
            return None;
        }
        let t = len as i32 - 1;
        let v = p.map(i32::wrapping_neg);
        let dv = dp.map(i32::wrapping_neg);
        let lv = [0, 1, 2].map(|a| l.at[a].wrapping_sub(p[a]));
        let (lt, dlt) = scale(lv, dv)?;
        let (vt, dvt) = scale(v, dv)?;
        let q = [
            prod(n, dn, n, dn),
            prod(lt, dlt, lt, dlt),
            prod(vt, dvt, vt, dvt),
            prod(n, dn, lt, dlt),
            prod(n, dn, vt, dvt),
            prod(lt, dlt, vt, dvt),
        ];
        let (_, alo, ahi) = span_bounds(q[0], 30, t)?;
        // The `1/|n|` table's range, with a chunk's drift (248 units) to
        // spare.
        if alo < (1 << 28) + 256 || ahi >= (5 << 28) - 256 {
            return None;
        }
        // |l̃|², |ṽ|² (Q29, from [1/4, 3) at the first pixel) within (1/6,
        // 4), and steps of at most 1/16 of the length: |dl̃|² · 2^8 <= |l̃|²
        // (x2 = 2 |dl̃|²).
        // Fine (steps of at most 1/64, as `point_setup`) when both are.
        let mut fine = true;
        for c in [q[1], q[2]] {
            let (x2, lo, hi) = span_bounds(c, 29, t)?;
            if lo <= (1 << 29) / 6 + 256 || hi >= (1 << 31) - 256 || i64::from(x2) << 7 > lo - 256 {
                return None;
            }
            fine &= (i64::from(x2) + 1) << 11 <= lo - 256;
        }
        // |D̃| <= |n| |l̃| < 1.12 · 2 and |Ẽ| < 1.12 · 2 (Q29), |F̃| < 2 · 2
        // (Q28): within i32 over the span (a chunk's drift aside) by the
        // checks above; the first and second differences wrap harmlessly
        // (the values are exact modulo 2^32).
        Some((Plan { q }, fine))
    }

    /// Whether a span of `len` pixels runs the 32-bit loop from its plan
    /// (the tests' check that it is taken).
    #[cfg(test)]
    pub(super) fn point_plan_runs(&self, span: Planes, len: u32) -> bool {
        self.lights
            .first()
            .is_some_and(|l| self.point_plan(l, span, len).is_some())
    }

    /// The chunks of a span of `len` pixels whose state the plan, stepped
    /// on, and the chunk's own set-up (`point_setup`) both give with the
    /// same scales: how many, and whether the two states are equal in
    /// each (the tests' check that the plan changes no value). `None`: no
    /// plan.
    #[cfg(test)]
    pub(super) fn plan_matches_setup(&self, span: Planes, len: u32) -> Option<(u32, bool)> {
        let l = self.lights.first()?;
        let (mut plan, fine) = self.point_plan(l, span, len)?;
        let (mut both, mut equal) = (0, true);
        let mut i = 0;
        while i < len {
            let k = (len - i).min(PCHUNK as u32) as usize;
            if i > 0 {
                plan.step_chunk();
            }
            // The powers of two of l and v at the chunk's first pixel.
            let sh = |j: u32| {
                let p = [0, 1, 2].map(|a| span.2[a].wrapping_add(span.3[a].wrapping_mul(j as i32)));
                let or = |v: [i32; 3]| v.iter().fold(0, |m, c| m | c.unsigned_abs());
                let lv = [0, 1, 2].map(|a| l.at[a].wrapping_sub(p[a]));
                (clz32(or(lv)), clz32(or(p)))
            };
            let same = sh(i) == sh(0);
            if let (true, Some(a), Some(b)) =
                (same, plan.chunk(fine), self.point_setup(l, span, i, k))
            {
                // The same seeds where both are fine or both not (the
                // plan's fine over the whole span, the set-up's over the
                // chunk).
                if a.fine == b.fine {
                    both += 1;
                    equal &= a == b;
                }
            }
            i += PCHUNK as u32;
        }
        Some((both, equal))
    }

    /// The span of `len` pixels by its plan's chunks run both ways, fine
    /// ([`seeds_fine`] and [`newton_lin`]) and not: whether the plan is
    /// fine, and the largest differences of the two loops' packed terms
    /// (`N·L` and the specular factor, Q15 each; the tests' check that
    /// the fine loop keeps the other's values within its bound). `None`:
    /// no plan.
    #[cfg(test)]
    pub(super) fn fine_against_coarse(&self, span: Planes, len: u32) -> Option<(bool, i32, i32)> {
        let l = self.lights.first()?;
        let (mut plan, fine) = self.point_plan(l, span, len)?;
        let (mut dnl, mut dsp) = (0, 0);
        let mut i = 0;
        while i < len {
            let k = (len - i).min(PCHUNK as u32) as usize;
            if i > 0 {
                plan.step_chunk();
            }
            let (a, b) = (plan.chunk(true)?, plan.chunk(false)?);
            let (mut ca, mut cb) = ([0u32; CHUNK], [0u32; CHUNK]);
            self.point_run::<true, true>(&a, k, &mut ca);
            self.point_run::<true, false>(&b, k, &mut cb);
            for (x, y) in ca[..k].iter().zip(&cb[..k]) {
                let d = |s: u32| (((x >> s) & 0xFFFF) as i32 - ((y >> s) & 0xFFFF) as i32).abs();
                dnl = dnl.max(d(0));
                dsp = dsp.max(d(16));
            }
            i += PCHUNK as u32;
        }
        Some((fine, dnl, dsp))
    }

    /// The span of `len` pixels by its plan's chunks run with `1/|ṽ|` by
    /// the series step a pixel and as the quadratic of [`view_quad`]
    /// ([`VIEW_QUAD`]): the largest differences of the two loops' packed
    /// terms (`N·L` and the specular factor, Q15 each; the tests' check
    /// that the quadratic keeps the other's values within its bound).
    /// `None`: no plan, or a chunk without the quadratic.
    #[cfg(test)]
    pub(super) fn quad_against_series(&self, span: Planes, len: u32) -> Option<(i32, i32)> {
        let l = self.lights.first()?;
        let (mut plan, fine) = self.point_plan(l, span, len)?;
        let (mut dnl, mut dsp) = (0, 0);
        let mut i = 0;
        while i < len {
            let k = (len - i).min(PCHUNK as u32) as usize;
            if i > 0 {
                plan.step_chunk();
            }
            let a = plan.chunk(fine)?;
            let b = Chunk {
                yv: view_quad(a.c)?,
                ..plan.chunk(fine)?
            };
            let (mut ca, mut cb) = ([0u32; CHUNK], [0u32; CHUNK]);
            let px = &mut [Px::default(); GROUP];
            if fine {
                self.point_run_in::<true, true, true, false>(px, &a, k, &mut ca);
                self.point_run_in::<true, true, true, true>(px, &b, k, &mut cb);
            } else {
                self.point_run_in::<true, false, false, false>(px, &a, k, &mut ca);
                self.point_run_in::<true, false, false, true>(px, &b, k, &mut cb);
            }
            for (x, y) in ca[..k].iter().zip(&cb[..k]) {
                let d = |s: u32| (((x >> s) & 0xFFFF) as i32 - ((y >> s) & 0xFFFF) as i32).abs();
                dnl = dnl.max(d(0));
                dsp = dsp.max(d(16));
            }
            i += PCHUNK as u32;
        }
        Some((dnl, dsp))
    }

    /// The chunk's colours (`r | g << 8 | b << 16`) from its state, in
    /// groups of [`GROUP`] pixels (four passes each, few live values a
    /// pass; the values between passes in a small array zeroed once a
    /// chunk, `n·L̂` in the colour's place).
    #[inline(always)]
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
    fn point_run<const SPEC: bool, const FINE: bool>(
        &self,
        st: &Chunk,
        k: usize,
        col: &mut [u32; CHUNK],
    ) {
        self.point_run_in::<SPEC, FINE, FINE, false>(&mut [Px::default(); GROUP], st, k, col);
    }

    /// [`PhongKernel::point_run`] with the values between passes in `px`
    /// (kept by the caller: no zeroing a chunk).
    #[inline(always)]
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
    fn point_run_in<const SPEC: bool, const FINE: bool, const FV: bool, const VQ: bool>(
        &self,
        px: &mut [Px; GROUP],
        st: &Chunk,
        k: usize,
        col: &mut [u32; CHUNK],
    ) {
        self.point_run_vals::<SPEC, FINE, FV, VQ, false>(
            px,
            [st.a, st.b, st.c, st.d, st.e, st.f],
            (st.yl, st.yv),
            (0, 0, 0),
            k,
            col,
        );
    }

    /// [`PhongKernel::point_run_in`] from the chunk's triples (`A`..`F`)
    /// and seeds given one by one (read where they lie: no [`Chunk`]
    /// built). `VQ`: `1/|ṽ|` the quadratic of [`view_quad`] (its value
    /// and differences in `yv`), `F̃·G` in its pass.
    #[inline(always)]
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
    fn point_run_vals<
        const SPEC: bool,
        const FINE: bool,
        const FV: bool,
        const VQ: bool,
        const NQ: bool,
    >(
        &self,
        px: &mut [Px; GROUP],
        [sa, sb, sc, sd, se, sf]: [(i32, i32, i32); 6],
        (yl, yv): Seeds,
        yn: (i32, i32, i32),
        k: usize,
        col: &mut [u32; CHUNK],
    ) {
        let k = k.min(PCHUNK);
        let (mut xb, mut xb1, xb2) = sb;
        let (mut d, mut d1, d2) = sd;
        let (mut la, mut lb) = yl;
        let (mut xc, mut xc1, xc2) = sc;
        let (mut e, mut e1, e2) = se;
        let (mut va, mut vb, vb2) = yv;
        let (mut f, mut f1, f2) = sf;
        let (mut a, mut a1, a2) = sa;
        let (mut rn, mut rn1, rn2) = yn;
        let kc = KScale::of(self.kf);
        // `1/|n|` from the packed table, its address in a register
        // (`one::rsq_biased`: the same values as `terms`).
        let rs = core::hint::black_box(&RS_PACKED);
        for cg in col.get_mut(..k).unwrap_or_default().chunks_mut(GROUP) {
            // 1/|l̃| and n·L̂.
            for (o, nl) in px.iter_mut().zip(cg.iter_mut()) {
                let s = lb.wrapping_mul(2).wrapping_sub(la);
                let y = if FINE {
                    newton_lin(s, xb)
                } else {
                    newton(s, xb)
                };
                o.g = y;
                *nl = (mulhi(d, y) << 4) as u32;
                (la, lb) = (lb, y);
                xb = xb.wrapping_add(xb1);
                xb1 = xb1.wrapping_add(xb2);
                d = d.wrapping_add(d1);
                d1 = d1.wrapping_add(d2);
            }
            // 1/|ṽ|, n·V̂ and L̂·V̂.
            if SPEC && VQ {
                // 1/|ṽ| by forward differences (va, vb, vb2: its value
                // and differences), F̃·G in the same pass ([`VQ_FG`]).
                let fg_here = VQ_FG && (!FUSED_FG || VQ_FG_M0);
                for (o, &nl) in px.iter_mut().zip(cg.iter()) {
                    let y = va;
                    o.nlnv = mulhi(nl as i32, mulhi(e, y) << 4);
                    let g = mulhi(o.g, y) << 2;
                    o.g = if fg_here { mulhi(f, g) << 2 } else { g };
                    va = va.wrapping_add(vb);
                    vb = vb.wrapping_add(vb2);
                    e = e.wrapping_add(e1);
                    e1 = e1.wrapping_add(e2);
                    if fg_here {
                        f = f.wrapping_add(f1);
                        f1 = f1.wrapping_add(f2);
                    }
                }
            } else if SPEC {
                for (o, &nl) in px.iter_mut().zip(cg.iter()) {
                    let s = vb.wrapping_mul(2).wrapping_sub(va);
                    let y = if FV { newton_lin(s, xc) } else { newton(s, xc) };
                    // (n·L̂)(n·V̂): Q30 · Q30 -> Q28.
                    o.nlnv = mulhi(nl as i32, mulhi(e, y) << 4);
                    // G = 1/(|l̃| |ṽ|) < 6 (Q28) in place of 1/|l̃|.
                    o.g = mulhi(o.g, y) << 2;
                    (va, vb) = (vb, y);
                    xc = xc.wrapping_add(xc1);
                    xc1 = xc1.wrapping_add(xc2);
                    e = e.wrapping_add(e1);
                    e1 = e1.wrapping_add(e2);
                }
            }
            if SPEC && !FUSED_FG && !(VQ && VQ_FG) {
                for o in px.iter_mut().take(cg.len()) {
                    // F̃ (Q28) · G (Q28): Q24, as Q26 (in place of G).
                    o.g = mulhi(f, o.g) << 2;
                    f = f.wrapping_add(f1);
                    f1 = f1.wrapping_add(f2);
                }
            }
            // w·A = A (1 + L̂·V̂) - 2 (n·L̂)(n·V̂) (Q24) and the light
            // terms (the channels are the driver's, per passing pixel).
            for (x, o) in px.iter().zip(cg.iter_mut()) {
                let nl = *o as i32;
                let q = if SPEC {
                    let fg = if FUSED_FG && !(VQ && VQ_FG && VQ_FG_M0) {
                        // F̃ (Q28) · G (Q28): Q24, as Q26.
                        let fg = mulhi(f, x.g) << 2;
                        f = f.wrapping_add(f1);
                        f1 = f1.wrapping_add(f2);
                        fg
                    } else {
                        x.g
                    };
                    let wa = (a >> 6)
                        .wrapping_add(mulhi(a, fg))
                        .wrapping_sub(x.nlnv >> 3);
                    // Within [0, 4) (Q24), as Q28: the position K·w·A in
                    // Q15 segments (saturated by `colour` beyond the
                    // table).
                    kc.mul(wa.clamp(0, (1 << 26) - 1) << 4)
                } else {
                    0
                };
                let r = if NQ {
                    // 2^16/|n| from its quadratic (Q29 of 1/|n|).
                    let r = (rn as u32) >> 13;
                    rn = rn.wrapping_add(rn1);
                    rn1 = rn1.wrapping_add(rn2);
                    r
                } else {
                    rsq_biased(rs, a.wrapping_sub(1 << 28))
                };
                let (nl15, sp) = self.terms_r::<SPEC>(r, nl, q >> 8);
                *o = (nl15 & 0xFFFF) | sp << 16;
                a = a.wrapping_add(a1);
                a1 = a1.wrapping_add(a2);
            }
        }
    }

    /// One pixel `j` of the span alone: the loop's arithmetic at that
    /// pixel ([`PhongKernel::point_one`]), else (outside its ranges) the
    /// 64-bit per-pixel path.
    #[inline(never)]
    fn point_px(&self, l: &KLight, c: &Colour, (n, dn, p, dp): Planes, j: u32) -> Rgb8 {
        self.point_one(l, c, (n, dn, p, dp), j)
            .unwrap_or_else(|| self.point_exact(l, n, dn, p, dp, j))
    }

    /// The loop's arithmetic ([`PhongKernel::point_run`]) at pixel `j`
    /// alone: the six quadratics' values at the pixel computed exactly
    /// (64-bit products of its vectors, scaled as a chunk's, rounded),
    /// `1/|l̃|` and `1/|ṽ|` by one series step ([`newton`]) from the table
    /// ([`seed`]: `2^-11.4`, the step takes it to `2^-30`); within the
    /// loop's error at its first pixel (no forward-difference drift).
    /// `None` outside the loop's ranges (`|n|²` in `[1/4, 5/4)`, `|l̃|²`
    /// and `|ṽ|²` in `(1/6, 4)`).
    #[inline(always)]
    #[allow(
        clippy::cast_possible_wrap,
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss
    )]
    fn point_one(&self, l: &KLight, c: &Colour, (n, dn, p, dp): Planes, j: u32) -> Option<Rgb8> {
        let (nj, vj, lj) = at_pixel(l, (n, dn, p, dp), j);
        let (lt, _) = scale(lj, [0; 3])?;
        let (vt, _) = scale(vj, [0; 3])?;
        // round(a·b / 2^s), wrapping (the ranges below checked in i64).
        let dot = |a: [i32; 3], b: [i32; 3], s: u32| -> i64 {
            wmul(a[0], b[0])
                .wrapping_add(wmul(a[1], b[1]))
                .wrapping_add(wmul(a[2], b[2]))
                .wrapping_add(1 << (s - 1))
                >> s
        };
        let a = dot(nj, nj, 30);
        if !((1 << 28)..(5 << 28)).contains(&a) {
            return None;
        }
        let b = dot(lt, lt, 29);
        let cc = dot(vt, vt, 29);
        let ok = |x: i64| x > (1 << 29) / 6 && x < (1 << 31) - 1;
        if !ok(b) || !ok(cc) {
            return None;
        }
        let (a, b) = (a as i32, b as i32);
        // n·L̂ (Q30), as the loop's first pass.
        let yl = newton(seed(b)?, b);
        let nl = mulhi(dot(nj, lt, 30) as i32, yl) << 4;
        let (nl15, sp) = if self.spec {
            let yv = newton(seed(cc as i32)?, cc as i32);
            let nlnv = mulhi(nl, mulhi(dot(nj, vt, 30) as i32, yv) << 4);
            let g = mulhi(yl, yv) << 2;
            let fg = mulhi(dot(lt, vt, 30) as i32, g) << 2;
            let wa = (a >> 6).wrapping_add(mulhi(a, fg)).wrapping_sub(nlnv >> 3);
            #[cfg(armv6m)]
            let q = KScale::of(self.kf).mul(wa.clamp(0, (1 << 26) - 1) << 4);
            // The same value, the scale in four instructions.
            #[cfg(not(armv6m))]
            let q = mulhi(wa.clamp(0, (1 << 26) - 1) << 4, KScale::kt_of(self.kf));
            self.terms::<true>(a, nl, q >> 8)
        } else {
            self.terms::<false>(a, nl, 0)
        };
        Some(level_q19(c.of_terms((nl15 & 0xFFFF) | sp << 16)))
    }

    /// Whether pixel `j` of the span takes [`PhongKernel::point_one`] (the
    /// tests' check that it is taken).
    #[cfg(test)]
    pub(super) fn point_one_runs(&self, span: Planes, j: u32) -> bool {
        self.lights
            .first()
            .is_some_and(|l| self.point_one(l, &Colour::of(self, l), span, j).is_some())
    }

    /// One pixel `j` of the span by the 64-bit per-pixel path.
    #[cold]
    #[inline(never)]
    #[allow(clippy::cast_possible_wrap)]
    #[allow(clippy::too_many_arguments)]
    fn point_exact(
        &self,
        l: &KLight,
        n: [i32; 3],
        dn: [i32; 3],
        p: [i32; 3],
        dp: [i32; 3],
        j: u32,
    ) -> Rgb8 {
        let (nj, vj, lj) = at_pixel(l, (n, dn, p, dp), j);
        let s = LightSpan {
            l: lj,
            q: sq3(lj),
            ..LightSpan::default()
        };
        self.general_px(&s, l, nj, vj, sq3(vj), sq3(nj))
            .unwrap_or_else(|| fallback(self.shade, n, dn, p, dp, j))
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// [`newton`] against `f64`: from seeds within `2^-6` (relative) of
    /// `1/sqrt(b)`, `b` (Q29) across `(1/6, 4)`, within `0.28 e⁴ +
    /// 2^-22.5`; from seeds within `3·2^-8` (the loop's, module docs)
    /// within `2^-22`.
    /// The ARMv6-M's chunk state ([`Plan::chunk_hi`]) holds the very
    /// words and seeds the other targets' loop reads ([`Plan::hi`],
    /// [`Plan::seeds_hi`]), for random plans, fine or not.
    #[test]
    fn chunk_hi_equals_hi_and_seeds() {
        let mut next = crate::geom::testkit::xorshift(0x9e37_79b9_7f4a_7c15);
        let mut some = 0;
        for i in 0..20_000u32 {
            let mut pl = Plan { q: [[0; 3]; 6] };
            for t in &mut pl.q {
                // B and C from the seeds' table range mostly (Q29 in (1/6,
                // 4) as high words), the others anything.
                *t = [next() as i64, next() as i64 >> 8, next() as i64 >> 16];
            }
            for t in &mut pl.q[1..3] {
                t[0] = ((next() % (3 << 29)) as i64 + (1 << 28)) << 32;
            }
            let fine = i % 2 == 0;
            let fv = fine || i % 3 == 0;
            let vq = i % 5 == 0;
            let want = pl.seeds_hi(fine, fv, vq).map(|(yl, yv)| (pl.hi(), yl, yv));
            let got = pl
                .chunk_hi(fine, fv, vq)
                .map(|c| ([c.a, c.b, c.c, c.d, c.e, c.f], c.yl, c.yv));
            assert_eq!(got, want, "{i}");
            some += usize::from(got.is_some());
        }
        assert!(some > 10_000, "{some}");
    }

    /// [`view_quad`] against `f64`: for view vectors stepping by `r` up to
    /// `2^-8` of their length a pixel (any direction), `|ṽ|²` (Q29) in
    /// `(1/6, 4)` over the chunk, its forward differences within `3152 r³
    /// + 2^-19` of `1/|ṽ|` (relative) at each of the 32 pixels; and
    /// [`VQ_MIN`] the smallest `M >= 2^16` with `M³ >= (3152·2^10·m)²`.
    #[test]
    fn view_quad_error() {
        let mut rng = crate::geom::testkit::xorshift(0x5151_2727_8383_9e9e);
        let mut u = move || (rng() >> 11) as f64 / (1u64 << 53) as f64;
        let q29 = f64::from(1u32 << 29);
        let (mut worst, mut n) = (0f64, 0);
        for i in 0..100_000 {
            let r = match i % 4 {
                0 => 2f64.powi(-8),
                _ => 2f64.powi(-8) * u().powf(0.5),
            };
            let len = (0.45 + 1.4 * u()).sqrt();
            let dir = |u: &mut dyn FnMut() -> f64| {
                let v = [2.0 * u() - 1.0, 2.0 * u() - 1.0, 2.0 * u() - 1.0];
                let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-9);
                v.map(|c| c / l)
            };
            let v = dir(&mut u).map(|c| c * len);
            let d = dir(&mut u).map(|c| c * len * r);
            let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
            let c0 = (dot(v, v) * q29).round() as i32;
            let c1 = ((2.0 * dot(v, d) + dot(d, d)) * q29).round() as i32;
            let c2 = (2.0 * dot(d, d) * q29).round() as i32;
            let Some((mut y, mut y1, y2)) = view_quad((c0, c1, c2)) else {
                continue;
            };
            n += 1;
            let bound = 3152.0 * r.powi(3) + 2f64.powi(-19);
            // The exact quadratic of the rounded triple.
            let (mut x, mut x1) = (f64::from(c0), f64::from(c1));
            for t in 0..32 {
                let exact = 1.0 / (x / q29).sqrt();
                let err = (f64::from(y) / q29 / exact - 1.0).abs();
                assert!(err <= bound, "r {r:e} t {t}: {err:e} > {bound:e}");
                worst = worst.max(err / bound);
                (y, y1) = (y.wrapping_add(y1), y1.wrapping_add(y2));
                (x, x1) = (x + x1, x1 + f64::from(c2));
            }
        }
        std::println!("view_quad: {n} chunks, worst {worst:.3} of the bound");
        assert!(n > 90_000, "{n}");
        for m in 0..=256u64 {
            let p2 = (3152 * 1024 * m).pow(2);
            let x = u64::from(VQ_MIN[m as usize]);
            assert!(x >= 1 << 16 && x * x * x >= p2, "{m}");
            assert!(x == 1 << 16 || (x - 1).pow(3) < p2, "{m}");
        }
    }

    #[test]
    fn newton_error() {
        let q29 = f64::from(1u32 << 29);
        let mut r = 0x9e37_79b9_7f4a_7c15u64;
        let mut worst = [0f64; 2];
        for i in 0..400_000 {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            let u = (r >> 11) as f64 / (1u64 << 53) as f64;
            let b = ((1.0 / 6.0 + (4.0 - 1.0 / 6.0) * u) * q29) as i32;
            let bx = f64::from(b) / q29;
            let exact = 1.0 / bx.sqrt();
            let (k, lim) = if i % 2 == 0 {
                (0, 1.0 / 64.0)
            } else {
                (1, 3.0 / 256.0)
            };
            // The seed's relative error: the extremes, then uniform.
            let d = match i % 8 {
                0 | 1 => lim,
                2 | 3 => -lim,
                _ => lim * (2.0 * ((r & 0xFFFF) as f64 / 65535.0) - 1.0),
            };
            let s = (exact * (1.0 + d) * q29).round() as i32;
            let sf = f64::from(s) / q29;
            let e = 1.0 - bx * sf * sf;
            let y = f64::from(newton(s, b)) / q29;
            let err = (y / exact - 1.0).abs();
            assert!(
                err <= 0.28 * e.powi(4) + 2f64.powf(-22.5),
                "b {bx} seed {d} e {e}: {err:e}"
            );
            worst[k] = worst[k].max(err);
        }
        std::println!("newton: {:.2} {:.2}", worst[0].log2(), worst[1].log2());
        assert!(worst[1] <= 2f64.powi(-22), "{}", worst[1].log2());
    }

    /// [`newton_lin`] against `f64`: from seeds within `2^-10.8`
    /// (relative) of `1/sqrt(b)`, `b` (Q29) across `(1/6, 4)`, within
    /// `0.38 e² + 2^-23` and below `2^-20.8`; [`seeds_fine`]'s first
    /// state within `2^-22`, the second's extrapolation within `2^-11.3`,
    /// for steps of up to `1/64` of the length.
    #[test]
    fn newton_lin_error() {
        let q29 = f64::from(1u32 << 29);
        let mut rng = crate::geom::testkit::xorshift(0x9e37_79b9_7f4a_7c15);
        let mut u = move || (rng() >> 11) as f64 / (1u64 << 53) as f64;
        let lim = 2f64.powf(-10.8);
        let mut worst = 0f64;
        for i in 0..400_000 {
            let b = ((1.0 / 6.0 + (4.0 - 1.0 / 6.0) * u()) * q29) as i32;
            let bx = f64::from(b) / q29;
            let exact = 1.0 / bx.sqrt();
            let d = match i % 8 {
                0 => lim,
                1 => -lim,
                _ => lim * (2.0 * u() - 1.0),
            };
            let s = (exact * (1.0 + d) * q29).round() as i32;
            let sf = f64::from(s) / q29;
            let e = 1.0 - bx * sf * sf;
            let y = f64::from(newton_lin(s, b)) / q29;
            let err = (y / exact - 1.0).abs();
            assert!(
                err <= 0.38 * e * e + 2f64.powi(-23),
                "b {bx} seed {d} e {e}: {err:e}"
            );
            worst = worst.max(err);
        }
        std::println!("newton_lin: {:.2}", worst.log2());
        assert!(worst <= 2f64.powf(-20.8), "{}", worst.log2());
        // The fine seeds: |l̃|² at the first two pixels of a chunk whose
        // step is up to 1/64 of the length (x1 = 2 l·dl + |dl|²).
        let mut worst = [0f64; 2];
        for _ in 0..200_000 {
            let x0 = (1.0 / 6.0 + (4.0 - 1.0 / 6.0) * u()) * 0.95;
            let r = u() / 64.0;
            let c = 2.0 * u() - 1.0;
            let x1 = x0 * (2.0 * r * c + r * r);
            let (b0, b1) = ((x0 * q29) as i32, (x1 * q29).round() as i32);
            let Some((ym2, ym1)) = seeds_fine(b0, b1) else {
                panic!("{x0} {x1}");
            };
            let (ym2, ym1) = (i64::from(ym2), i64::from(ym1));
            let y0 = (2 * ym1 - ym2) as f64 / q29;
            let e0 = 1.0 / (f64::from(b0) / q29).sqrt();
            let y1 = (2 * (2 * ym1 - ym2) - ym1) as f64 / q29;
            let e1 = 1.0 / (f64::from(b0 + b1) / q29).sqrt();
            worst[0] = worst[0].max((y0 / e0 - 1.0).abs());
            worst[1] = worst[1].max((y1 / e1 - 1.0).abs());
        }
        std::println!("seeds_fine: {:.2} {:.2}", worst[0].log2(), worst[1].log2());
        assert!(worst[0] <= 2f64.powi(-22) && worst[1] <= 2f64.powf(-11.3));
    }

    /// [`KScale`]: its two forms agree ([`KScale::mul_split`] is the
    /// M0's), its scale is within `2^-15` of `K·2^19` (relative), and the
    /// table position it gives (Q7 segments) within one unit of the
    /// position from the whole scale wherever it lies in the table.
    #[test]
    fn kscale_products() {
        let mut rng = crate::geom::testkit::xorshift(0x2545_f491_4f6c_dd1d);
        let mut worst = 0f64;
        let mut kfs = std::vec![0u32, 1, 31, 32, 33, 1 << 5, (1 << 5) + 1, KF_MAX - 1];
        for i in 0..20 {
            kfs.push((1 << i) + 1);
            kfs.push((1 << (i + 1)) - 1);
        }
        for i in 0..200_000u32 {
            let r = rng();
            let kf = if (i as usize) < kfs.len() {
                kfs[i as usize]
            } else {
                (r >> 40) as u32 % KF_MAX
            };
            let k = KScale::of(kf);
            let kc = kf << 11;
            assert_eq!(KScale::kt_of(kf), k.kt, "{kf}");
            assert!(k.kh < 1 << 16 && k.t <= 15 && (k.kt as u32) <= kc, "{kf}");
            if kc > 0 {
                let rel = f64::from(kc - k.kt as u32) / f64::from(kc);
                assert!(rel <= 2f64.powi(-15), "{kf}: {rel:e}");
                worst = worst.max(rel);
            }
            for w in [0, 1, (1 << 30) - 1, (r as u32 & ((1 << 30) - 1)) as i32] {
                let m = k.mul_split(w);
                assert_eq!(m, mulhi(w, k.kt), "{kf} {w}");
                assert_eq!(m, k.mul(w));
                // The position (Q7) within one unit of the whole scale's
                // where it is inside the table (below 2^15).
                let whole = mulhi(w, kc as i32) >> 8;
                if whole < 1 << 15 {
                    assert!(whole - (m >> 8) <= 1, "{kf} {w}: {whole} {}", m >> 8);
                }
            }
        }
        std::println!("kscale: worst relative {:.2}", worst.log2());
    }
}
