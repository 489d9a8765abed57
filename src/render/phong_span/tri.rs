//! One point light, local viewer, Phong: the six quadratics set up once a
//! triangle.
//!
//! Over a triangle the normal `n`, the light vector `l = Lp - p` and the
//! view vector `v = -p` are linear in the pixel's `(x, y)` (planar
//! interpolation of the vertex normals; `p` on the triangle's position
//! plane), so the six scalars of the point loop (module `point`: `A =
//! |n|²`, `B = |l̃|²`, `C = |ṽ|²`, `D = n·l̃`, `E = n·ṽ`, `F = l̃·ṽ`, with
//! `l̃`, `ṽ` scaled by powers of two chosen once a triangle) are
//! quadratics `f + d·x + e·y + a·x² + b·x·y + c·y²` of the offset `(x,
//! y)` from the triangle's anchor pixel. [`TriQuad::new`] rounds the
//! three planes to integer coefficients (the normal in raw `Q30` a pixel,
//! `l̃` and `ṽ` in their scaled units) and multiplies them out exactly in
//! 64 bits; per span [`TriQuad::plan`] evaluates each quadratic and its
//! first two differences along the row at the span's first pixel,
//! exactly (wrapping `i64`: the true values are within `i64`), which is
//! the 32-bit loop's plan (`point::Plan`): no products of vectors, no
//! scaling and no range test a span.
//!
//! The span's plan is stepped from the last span's of the triangle
//! (`TriQuad::plan`, [`STEPPED`]): with each quadratic's first
//! difference in y at the last span's start kept beside the plan, the
//! next row's plan starting within [`DX_STEP`] pixels takes additions
//! only (three a quadratic for the row, three a pixel of the offset), one
//! farther four products a quadratic, other spans (a triangle's first in
//! a band, a row skipped) six from the quadratics. Measured against the
//! row's values stepped and two products a span (dodecahedron Phong
//! raster; span sweep phong-kpoint, a pixel): M4 1 611 934 -> 1 617 338
//! and 151.45 -> 151.74, M0 4 359 846 -> 4 229 401 and 486.57 -> 486.11
//! (frames unchanged): the M4's 64-bit products cost about what the
//! state's loads and stores cost (the plan ~100 a stepped span, ~180
//! before), the M0's products (three 32-bit ones each) much more.
//!
//! # Ranges, proven once a triangle
//! `A`, `B` and `C` are convex (squared lengths of affine functions), so
//! over the triangle their largest value is at a vertex, and the tangent
//! plane at the vertices' centroid bounds them from below: with `S` the
//! sum of the three vertex vectors, `9 |u|² >= 6 S·u_j - |S|²` at the
//! vertex `j` minimising it (exact for two of the vertices' vectors
//! apart by any angle along an edge). The loop's ranges (`A` in `[1/4,
//! 5/4)`, `B` and `C` in `(1/6, 4)`, steps along x at most `1/16` of
//! `|l̃|` and `|ṽ|`) are checked on these bounds with a relative margin
//! of `2^-8`, which covers the rounding of the planes' coefficients (at
//! most `½ + ½|x| + ½|y|` units, `x` and `y` within `2^12` pixels of the
//! anchor: `2^-17` of `A`, `B`, `C`) and the 32-bit loop's drift within a
//! chunk (248 units of `2^-29`). A triangle that fails them (vertex
//! normals far apart (`|n|²` near 1/4: ~120°), a light or the eye near the triangle
//! compared with its size, a triangle wider than `2^12` pixels, positions
//! or light offsets beyond `±2^29` raw, as the per-span loop) keeps the
//! per-span path; every span also passes the per-span loop's range test
//! (`PhongKernel::fill`), else the 64-bit path. A triangle whose steps
//! along x are at most `1/64` of `|l̃|` and `|ṽ|` on the same bounds
//! (`|dx|² · 2^12 <= |u|²`) is fine: its chunks take the point loop's
//! first-order step a pixel (module `point`).
//!
//! # Kept from band to band
//! The band renderer sets a triangle up in every band it reaches; its
//! quadratics are the same in each. A [`QuadSlot`] of the pool keeps
//! them (keyed by the triangle's prepared vertices, face and the light's
//! position: the very values [`TriQuad::make`] would make again), so a
//! triangle crossing bands is set up once a frame while slots last, else
//! again (tested with 0, 1, 2 and 64 slots: the same bytes).
//!
//! # Error
//! The quadratics are exact for the rounded planes: the normal within
//! `½ + ½|x| + ½|y|` raw `Q30` units of the exact plane through the
//! vertex normals, `l̃`, `ṽ` within as many of their units (below
//! `2^-17` relative over a triangle of `2^12` pixels), against the
//! rasterizer's walked values (their steps rounded to raw units: the same
//! order a pixel, accumulated along the span). The rest is the point
//! loop's error (module `point`), unchanged. Tested against `f64` on
//! random and extreme triangles (`tri_quad_*` in this module's tests).

use super::point::{view_quad_min, Plan, Px, GROUP, NORMAL_QUAD, VIEW_QUAD};
use super::CHUNK;
use super::{raw, KLight, PhongKernel};
use crate::num::wide::wmul;
use crate::num::{InvArea, Real, SubpixelBits};

/// Extra fraction bits of the planes before they are rounded.
const EXTRA: u32 = 12;
/// Largest offset of a vertex from the anchor pixel, in pixels.
const EXTENT: i32 = 1 << 12;
/// A span's plan stepped from the last span's ([`TriQuad::plan`]), else
/// made from the row's values.
const STEPPED: bool = true;
/// Quadratics of the rows' values kept (`TriQuad::plan_rows`): none with
/// [`STEPPED`] (the triangle's state 192 bytes smaller).
const ROWS: usize = if STEPPED { 0 } else { 6 };
/// Largest offset along the row from the last span's start that the
/// stepped plan takes by additions. Measured with 3 (dodecahedron Phong
/// raster): M4 1 593 035 -> 1 593 322, M0 4 243 027 -> 4 257 613.
const DX_STEP: u32 = 2;
/// The next row's plan from the last span's by products
/// ([`TriQuad::step_far`]) when its start is farther than [`DX_STEP`].
const FAR: bool = true;

/// The six quadratics of one triangle (see the module docs).
///
/// `repr(C)` on ARMv6-M (the fields in this order; dodecahedron Phong
/// raster M0 4 241 007 -> 4 239 939, cubes-and-sphere 9 041 842 ->
/// 9 040 747). Measured and not kept: the plan's state first and `q`
/// after it (`repr(C)` on both targets: M0 4 236 524, M4 1 595 984 ->
/// 1 606 060; the M4's own layout of that order 1 607 001), with `start`
/// or `fine` moved on ARMv6-M only (4 240 725, 4 242 580); a
/// [`QuadSlot`]'s quadratics read in place by the plan instead of copied
/// by `TriQuad::load` (32 copies of 288 bytes a frame; the slice or the
/// slot's pointer passed down `row_fill`): M4 1 592 731 / 1 599 167 and
/// cubes-and-sphere 3 876 649 -> 3 888 373 / 3 879 173 (the span
/// filler's argument more), M0 4 244 665 / 4 250 804.
#[derive(Clone, Copy, Debug)]
#[cfg_attr(armv6m, repr(C))]
pub struct TriQuad {
    /// The anchor pixel (vertex 0's).
    at: [i32; 2],
    /// Per quadratic (`A`, `B`, `C`, `D`, `E`, `F`): `[f, d, e, a, b, c]`
    /// of `f + d·x + e·y + a·x² + b·x·y + c·y²` (wrapping).
    q: [[i64; 6]; 6],
    /// Per quadratic, at row `ry`: its value at `x = 0`, the value's
    /// first difference to the next row, the coefficient of `x` and the
    /// first difference's step (`f + e·y + c·y²`, `e + c·(2y + 1)`, `d +
    /// b·y`, `2c`: set by `set_row`, not doubled a span: dodecahedron
    /// Phong raster M4 1 620 399 -> 1 612 194, M0 4 361 338 -> 4 359 840,
    /// cubes-and-sphere 156 more on both, 48 bytes more stack).
    row: [[i64; 4]; ROWS],
    /// The row of `row`, or of the last span's plan with [`STEPPED`]
    /// (`None`: not set).
    ry: Option<i32>,
    /// With [`STEPPED`]: the column of the last span's plan (`span`) and
    /// each quadratic's first difference in y there.
    cx: i32,
    g: [i64; 6],
    /// The plan at the start of a span of more than one chunk, kept
    /// ([`TriQuad::plan`]).
    start: [[i64; 2]; 6],
    kept: bool,
    /// The last span's plan ([`TriQuad::plan`]).
    pub(super) span: Plan,
    /// The point loop's buffers (the span driver's and the values
    /// between passes), kept here: not zeroed a span.
    pub(super) buf: [u32; CHUNK],
    pub(super) px: [Px; GROUP],
    /// The vertices (screen position in subpixels, normal raw `Q30`
    /// flipped for back faces, eye position raw `Q16`) and subpixel bits
    /// of a set-up not yet made ([`TriQuad::ready`]).
    verts: [([i32; 2], [i32; 3], [i32; 3]); 3],
    sub: SubpixelBits,
    pending: bool,
    /// Made (else the spans take the per-span path).
    ok: bool,
    /// The triangle's prepared vertex indices and face (the key of its
    /// [`QuadSlot`], [`key_of`]; 0: a triangle given by its vertices).
    key: u64,
    /// Made here (not loaded from a [`QuadSlot`]): to be kept.
    made: bool,
    /// Steps along x of `l̃` and `ṽ` of at most `1/64` of their length
    /// over the triangle: its chunks take the point loop's fine steps
    /// (module `point`).
    fine: bool,
    /// Steps along x of `ṽ` of at most `1/64` of its length over the
    /// triangle (its `1/|ṽ|` takes the fine steps, `fine` or not): 1; so
    /// small that its `1/|ṽ|` is a quadratic a chunk ([`view_quad_min`],
    /// module `point`): 2; else 0. Plus 4 when the normal's steps along
    /// x are at most `2^-8` of its length as well (its `1/|n|` a
    /// quadratic a chunk, with the viewer's).
    fine_v: u8,
}

#[cfg(test)]
extern crate std;

#[cfg(test)]
std::thread_local! {
    /// Set-ups made ([`TriQuad::make`]) on this thread (tests count them).
    pub(crate) static MAKES: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
    /// Set-ups made fine on this thread (tests count them).
    pub(crate) static FINES: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
    /// Set-ups made with the viewer alone fine on this thread (tests
    /// count them).
    pub(crate) static FINES_V: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
    /// Set-ups made with the viewer's `1/|ṽ|` a quadratic a chunk on this
    /// thread (tests count them).
    pub(crate) static QUADS_V: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
    /// Set-ups made with `1/|n|` a quadratic a chunk too on this thread
    /// (tests count them).
    pub(crate) static QUADS_N: core::cell::Cell<u32> = const { core::cell::Cell::new(0) };
}

/// One triangle's quadratics kept from one band to the next (the band
/// renderer's [`Pool`](crate::render::Pool) holds a few): a triangle
/// crossing bands is set up once a frame instead of once a band.
///
/// Keyed by the triangle's prepared vertices, its face and the light's
/// position: a slot found holds the very values [`TriQuad`] would make
/// again (the same inputs), so a frame is the same with any number of
/// slots. A triangle is kept when it continues below the band; a slot is
/// free again once the bands are past its triangle's last row. When every
/// slot is taken, the triangle is set up again in the next band.
#[derive(Clone, Copy, Debug)]
pub struct QuadSlot {
    /// The triangle's key ([`key_of`]; 0: free).
    key: u64,
    light: [i32; 3],
    /// The last pixel row the triangle may cover.
    last: i32,
    ok: bool,
    at: [i32; 2],
    q: [[i64; 6]; 6],
    fine: bool,
    fine_v: u8,
}

impl QuadSlot {
    /// A free slot (`const`: in a `static` pool).
    pub const EMPTY: Self = Self {
        key: 0,
        light: [0; 3],
        last: 0,
        ok: false,
        at: [0; 2],
        q: [[0; 6]; 6],
        fine: false,
        fine_v: 0,
    };

    /// Bytes of one slot (the RAM per kept triangle).
    pub const BYTES: usize = core::mem::size_of::<Self>();

    /// Frees every slot of `slots` (a new frame).
    pub(crate) fn clear(slots: &mut [Self]) {
        for s in slots {
            s.key = 0;
        }
    }
}

/// The key of the triangle of prepared vertices `v`, back face or not
/// (never 0).
#[inline(always)]
pub(super) fn key_of(v: [u16; 3], back: bool) -> u64 {
    (1 << 63)
        | u64::from(back) << 48
        | u64::from(v[2]) << 32
        | u64::from(v[1]) << 16
        | u64::from(v[0])
}

/// `x · y` modulo `2^64` for `|y| < 2^15` (ARMv6-M: three 32-bit
/// products, no 64-bit multiply call).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn mul_small(x: i64, y: i32) -> i64 {
    if cfg!(armv6m) {
        mul_small_split(x, y)
    } else {
        x.wrapping_mul(i64::from(y))
    }
}

/// [`mul_small`] on ARMv6-M (compiled everywhere: tested on the host).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn mul_small_split(x: i64, y: i32) -> i64 {
    let (hi, lo) = ((x >> 32) as i32, x as u32);
    // lo = 2^16 lh + ll: each product within i32 for |y| < 2^15.
    let (lh, ll) = ((lo >> 16) as i32, (lo & 0xFFFF) as i32);
    (i64::from(hi.wrapping_mul(y)) << 32)
        .wrapping_add(i64::from(lh * y) << 16)
        .wrapping_add(i64::from(ll * y))
}

/// `x · y` modulo `2^64` (ARMv6-M: from 32-bit halves, no 64-bit
/// multiply call).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn mul_wide(x: i64, y: i32) -> i64 {
    if cfg!(armv6m) {
        mul_wide_split(x, y)
    } else {
        x.wrapping_mul(i64::from(y))
    }
}

/// [`mul_wide`] on ARMv6-M (compiled everywhere: tested on the host).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn mul_wide_split(x: i64, y: i32) -> i64 {
    let (hi, lo) = ((x >> 32) as i32, x as u32);
    // lo · y = lo · (y mod 2^32) - lo · 2^32 when y < 0.
    let mut p = crate::num::wide::wmul_u32(lo, y as u32) as i64;
    if y < 0 {
        p = p.wrapping_sub(i64::from(lo) << 32);
    }
    (i64::from(hi.wrapping_mul(y)) << 32).wrapping_add(p)
}

/// `round(x / 2^s)` for `s >= 1`, `x · 2^-s` for `s <= 0`, within
/// `i32` (`None` beyond).
#[inline(always)]
fn shift_round(x: i64, s: i32) -> Option<i32> {
    if s >= 1 {
        i32::try_from(x.checked_shr((s - 1) as u32)?.wrapping_add(1) >> 1).ok()
    } else {
        let k = s.unsigned_abs();
        let y = x.checked_shl(k)?;
        (y >> k == x).then_some(())?;
        i32::try_from(y).ok()
    }
}

/// The product of two affine vector functions `u0 + ux·x + uy·y` and
/// `w0 + wx·x + wy·y` as `[f, d, e, a, b, c]` (wrapping `i64`). Not
/// inlined (nor [`square`]): one at a time, few values live.
#[inline(never)]
fn quad2(u: &[[i32; 3]; 3], w: &[[i32; 3]; 3]) -> [i64; 6] {
    let mut q = [0i64; 6];
    for k in 0..3 {
        let (u0, ux, uy) = (u[0][k], u[1][k], u[2][k]);
        let (w0, wx, wy) = (w[0][k], w[1][k], w[2][k]);
        let t = [
            wmul(u0, w0),
            wmul(u0, wx).wrapping_add(wmul(ux, w0)),
            wmul(u0, wy).wrapping_add(wmul(uy, w0)),
            wmul(ux, wx),
            wmul(ux, wy).wrapping_add(wmul(uy, wx)),
            wmul(uy, wy),
        ];
        for (q, t) in q.iter_mut().zip(t) {
            *q = q.wrapping_add(t);
        }
    }
    q
}

/// The quadratic `q` times `2^k`, its value biased by `2^31` (wrapping:
/// the values over the triangle stay within `i64`, below `2^63` by the
/// ranges checked).
#[inline(always)]
fn loop_units(o: &mut [i64; 6], q: [i64; 6], k: u32) {
    for (o, q) in o.iter_mut().zip(q) {
        *o = q.wrapping_shl(k);
    }
    o[0] = o[0].wrapping_add(1 << 31);
}

/// [`quad2`] of `u` with itself (six products a component).
#[inline(never)]
#[allow(clippy::needless_range_loop)]
fn square(u: &[[i32; 3]; 3]) -> [i64; 6] {
    let mut q = [0i64; 6];
    for k in 0..3 {
        let (u0, ux, uy) = (u[0][k], u[1][k], u[2][k]);
        let t = [
            wmul(u0, u0),
            wmul(u0, ux).wrapping_mul(2),
            wmul(u0, uy).wrapping_mul(2),
            wmul(ux, ux),
            wmul(ux, uy).wrapping_mul(2),
            wmul(uy, uy),
        ];
        for (q, t) in q.iter_mut().zip(t) {
            *q = q.wrapping_add(t);
        }
    }
    q
}

/// Bounds of `|u|²` over the triangle of the three vertex vectors `u`
/// (components below `2^28`): `9 ·` the lower bound (tangent plane at the
/// centroid) and the upper bound (the largest vertex).
#[inline(always)]
fn range(u: &[[i32; 3]; 3]) -> (i64, i64) {
    let [u0, u1, u2] = u;
    let s = [
        u0[0] + u1[0] + u2[0],
        u0[1] + u1[1] + u2[1],
        u0[2] + u1[2] + u2[2],
    ];
    let dot = |a: [i32; 3], b: [i32; 3]| wmul(a[0], b[0]) + wmul(a[1], b[1]) + wmul(a[2], b[2]);
    let ss = dot(s, s);
    let mut lo = i64::MAX;
    let mut hi = 0;
    for &uj in u {
        let t = dot(s, uj);
        lo = lo.min((t << 2) + (t << 1) - ss);
        hi = hi.max(dot(uj, uj));
    }
    (lo, hi)
}

/// Whether `dd9 · M <= lo` (`M` = [`view_quad_min`] of `kf`, in `[2^16,
/// 2^20)`; `dd9 < 2^54`, `0 <= lo < 2^60`): at once false when `dd9 >=
/// lo / 2^16` (most triangles: no 64-bit product on ARMv6-M), else by
/// the product of `dd9` rounded up to `2^4` against `lo / 2^4`
/// (below `2^62`; conservative: true only when `dd9 · M <= lo`).
#[inline(always)]
fn view_quad_ok(dd9: i64, lo: i64, kf: u32) -> bool {
    if dd9 >= lo >> 16 {
        return false;
    }
    ((dd9 + 15) >> 4) * view_quad_min(kf) <= lo >> 4
}

/// The shift `s` making `|u|² · 2^2s` (`q = |u|²`, `q > 0`) lie in
/// `[0.9 · 2^58, 3.6 · 2^58)`.
#[inline(always)]
fn scale_of(q: u64) -> i32 {
    let e = 63 - q.leading_zeros() as i32;
    let mut s = (59 - e).div_euclid(2);
    let x = if s >= 0 { q << (2 * s) } else { q >> (-2 * s) };
    // 0.9 · 2^60, rounded up.
    if x >= 1_037_629_354_146_162_279 {
        s -= 1;
    }
    s
}

/// `c · 2^sh` (an exact shift, or floored) in units of `2^-2` of it,
/// within `i32`.
#[inline(always)]
fn at_scale(c: i64, sh: i32) -> Option<i32> {
    let x = if sh >= 0 {
        c << sh.min(63)
    } else {
        c >> (-sh).min(63)
    };
    i32::try_from(x >> 2).ok()
}

/// The plane through the values `a` at the three vertices: the value at
/// the anchor pixel's centre and the gradients along x and y, in units
/// of `2^-EXTRA` of `a`'s (`None`: gradients of `2^40` units or more).
#[inline(always)]
fn plane(
    d: [i32; 4],
    inv: &InvArea,
    s: u32,
    (ox, oy): (i64, i64),
    a: [i32; 3],
) -> Option<[i64; 3]> {
    let (d1, d2) = (
        i64::from(a[1]) - i64::from(a[0]),
        i64::from(a[2]) - i64::from(a[0]),
    );
    let nx = mul_wide(d1, d[3]).wrapping_sub(mul_wide(d2, d[1]));
    let ny = mul_wide(d2, d[0]).wrapping_sub(mul_wide(d1, d[2]));
    let (gx, gy) = (inv.quot(nx, s + EXTRA), inv.quot(ny, s + EXTRA));
    if gx.unsigned_abs() >= 1 << 40 || gy.unsigned_abs() >= 1 << 40 {
        return None;
    }
    let t = mul_wide(gx, ox as i32)
        .wrapping_add(mul_wide(gy, oy as i32))
        .wrapping_add(1 << (s - 1))
        >> s;
    Some([(i64::from(a[0]) << EXTRA).wrapping_add(t), gx, gy])
}

impl TriQuad {
    /// No set-up: the spans take the per-span path.
    pub const NONE: Self = Self {
        at: [0; 2],
        q: [[0; 6]; 6],
        row: [[0; 4]; ROWS],
        ry: None,
        cx: 0,
        g: [0; 6],
        start: [[0; 2]; 6],
        kept: false,
        span: Plan { q: [[0; 3]; 6] },
        buf: [0; CHUNK],
        px: [Px::ZERO; GROUP],
        verts: [([0; 2], [0; 3], [0; 3]); 3],
        sub: SubpixelBits::DEFAULT,
        pending: false,
        ok: false,
        key: 0,
        made: false,
        fine: false,
        fine_v: 0,
    };

    /// Whether the triangle's chunks are fine (see the field).
    #[inline(always)]
    pub(super) fn fine(&self) -> bool {
        self.fine
    }

    /// Whether the triangle's view vector alone is fine (see the field).
    #[inline(always)]
    pub(super) fn fine_v(&self) -> bool {
        self.fine_v & 3 != 0
    }

    /// Whether the triangle's `1/|ṽ|` is a quadratic a chunk (see the
    /// field `fine_v`).
    #[inline(always)]
    pub(super) fn quad_v(&self) -> bool {
        self.fine_v & 2 != 0
    }

    /// Whether the triangle's `1/|n|` is a quadratic a chunk too (see the
    /// field `fine_v`).
    #[inline(always)]
    pub(super) fn quad_n(&self) -> bool {
        self.fine_v & 4 != 0
    }

    /// Whether the set-up was made.
    pub fn ok(&self) -> bool {
        self.ok
    }

    /// Whether the spans take the quadratics' path: a set-up made, or
    /// pending (made at the triangle's first span long enough,
    /// [`TriQuad::ready`]).
    #[inline(always)]
    pub(super) fn wants(&self) -> bool {
        self.ok | self.pending
    }

    /// Keeps the triangle of vertices `v` (as [`TriQuad::new`]) for a
    /// set-up at its first span that needs it (`TriQuad::ready`): a
    /// triangle whose spans in a band are all short costs no set-up there.
    #[inline(always)]
    pub fn set(&mut self, v: [([i32; 2], [i32; 3], [i32; 3]); 3], sub: SubpixelBits, back: bool) {
        self.verts = v;
        if back {
            for (_, n, _) in &mut self.verts {
                *n = n.map(i32::wrapping_neg);
            }
        }
        self.sub = sub;
        self.pending = true;
        self.ok = false;
        self.ry = None;
        self.key = 0;
        self.made = false;
    }

    /// Makes the pending set-up for light `l` (the kernel's point light);
    /// whether the quadratics are made.
    #[inline(always)]
    pub(super) fn ready(&mut self, l: &KLight, kf: u32) -> bool {
        if self.pending {
            self.pending = false;
            self.ok = self.make(l, kf).is_some();
            self.made = true;
            #[cfg(test)]
            MAKES.with(|c| c.set(c.get() + 1));
        }
        self.ok
    }

    /// The quadratics of the triangle of vertices `v` (screen position in
    /// subpixels of `sub` bits, normal raw `Q30`, eye position raw
    /// `Q16`), the normal flipped when `back`, for kernel `k`;
    /// [`TriQuad::NONE`] when `k` is not one point light with a local
    /// viewer and the Phong model of the point loop, or outside the
    /// ranges of the module docs.
    #[inline(never)]
    pub fn new<R: Real>(
        k: &PhongKernel<'_, R>,
        v: [([i32; 2], [i32; 3], [i32; 3]); 3],
        sub: SubpixelBits,
        back: bool,
    ) -> Self {
        let mut t = Self::NONE;
        if let Some(l) = k.point_loop_light() {
            t.set(v, sub, back);
            t.ready(l, k.kf);
        }
        t
    }

    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::needless_range_loop
    )]
    #[inline(never)]
    fn make(&mut self, l: &KLight, kf: u32) -> Option<()> {
        // The vertices by reference (a copy was a `memcpy` a set-up).
        let (v, sub) = (&self.verts, self.sub);
        let ([x0, y0], _, _) = v[0];
        let ([x1, y1], _, _) = v[1];
        let ([x2, y2], _, _) = v[2];
        let d = [
            x1.checked_sub(x0)?,
            y1.checked_sub(y0)?,
            x2.checked_sub(x0)?,
            y2.checked_sub(y0)?,
        ];
        let area2 = wmul(d[0], d[3]).wrapping_sub(wmul(d[2], d[1]));
        if area2 == 0 {
            return None;
        }
        let inv = InvArea::new(area2);
        let s = sub.get();
        let sc = 1i32 << s;
        let (xa, ya) = (x0 >> s, y0 >> s);
        for ([x, y], _, _) in v {
            if ((x >> s) - xa).abs() >= EXTENT || ((y >> s) - ya).abs() >= EXTENT {
                return None;
            }
        }
        let o = (
            i64::from((xa << s) + sc / 2 - x0),
            i64::from((ya << s) + sc / 2 - y0),
        );
        // Vertex normals (flipped for back faces), light and view vectors
        // (raw Q16, within 2^30).
        let mut vn = [[0i32; 3]; 3];
        let mut lv = [[0i64; 3]; 3];
        let mut vv = [[0i64; 3]; 3];
        for j in 0..3 {
            for c in 0..3 {
                vn[j][c] = v[j].1[c];
                let pc = i64::from(v[j].2[c]);
                lv[j][c] = i64::from(l.at[c]) - pc;
                vv[j][c] = -pc;
                if lv[j][c].unsigned_abs() >= 1 << 29 || pc.unsigned_abs() >= 1 << 29 {
                    return None;
                }
            }
        }
        // The planes of the normal (rounded to raw Q30 units) and of the
        // position (2^-EXTRA raw Q16 units).
        let mut n = [[0i32; 3]; 3];
        let mut p = [[0i64; 3]; 3];
        for c in 0..3 {
            let pl = plane(d, &inv, s, o, [vn[0][c], vn[1][c], vn[2][c]])?;
            for r in 0..3 {
                n[r][c] = shift_round(pl[r], EXTRA as i32)?;
            }
            if n[1][c].unsigned_abs() >= 1 << 29 || n[2][c].unsigned_abs() >= 1 << 29 {
                return None;
            }
            let pl = plane(d, &inv, s, o, [v[0].2[c], v[1].2[c], v[2].2[c]])?;
            p[0][c] = (i64::from(l.at[c]) << EXTRA) - pl[0];
            p[1][c] = pl[1];
            p[2][c] = pl[2];
        }
        let mut bl = 0u64;
        let mut bv = 0u64;
        for j in 0..3 {
            let (mut ql, mut qv) = (0u64, 0u64);
            for c in 0..3 {
                // Within 2^30 (checked above).
                let (a, b) = (lv[j][c] as i32, vv[j][c] as i32);
                ql += wmul(a, a) as u64;
                qv += wmul(b, b) as u64;
            }
            bl = bl.max(ql);
            bv = bv.max(qv);
        }
        if bl == 0 || bv == 0 {
            return None;
        }
        let (sl, sv) = (scale_of(bl), scale_of(bv));
        // l̃ and ṽ: the planes scaled by 2^sl and 2^sv, rounded (the
        // gradients of l̃ the negated position's, as those of ṽ).
        let (el, ev) = (EXTRA as i32 - sl, EXTRA as i32 - sv);
        let mut lt = [[0i32; 3]; 3];
        let mut vt = [[0i32; 3]; 3];
        for c in 0..3 {
            lt[0][c] = shift_round(p[0][c], el)?;
            vt[0][c] = shift_round(p[0][c] - (i64::from(l.at[c]) << EXTRA), ev)?;
            for r in 1..3 {
                lt[r][c] = shift_round(-p[r][c], el)?;
                vt[r][c] = shift_round(-p[r][c], ev)?;
                if lt[r][c].unsigned_abs() >= 1 << 26 || vt[r][c].unsigned_abs() >= 1 << 26 {
                    return None;
                }
            }
        }
        // Ranges: every vector in units of 2^27 (1.0), squares 2^54.
        let mut na = [[0i32; 3]; 3];
        let mut la = [[0i32; 3]; 3];
        let mut va = [[0i32; 3]; 3];
        for j in 0..3 {
            for c in 0..3 {
                na[j][c] = vn[j][c] >> 3;
                la[j][c] = at_scale(lv[j][c], sl)?;
                va[j][c] = at_scale(vv[j][c], sv)?;
            }
        }
        const ONE: i64 = 1 << 54;
        const M: i64 = ONE >> 8;
        let (alo, ahi) = range(&na);
        if alo < 9 * (ONE / 4 + M) || ahi > 5 * ONE / 4 - 2 * M {
            return None;
        }
        // Fine (module `point`): steps along x of at most 1/64 of the
        // length, |dx|² · 2^12 <= |u|², for both.
        let mut fine = true;
        for (u, t) in [(&la, &lt), (&va, &vt)] {
            let (lo, hi) = range(u);
            if lo < 9 * (ONE / 6 + M) || hi > 4 * ONE - 4 * M {
                return None;
            }
            // The step along x at most 1/16 of the length: |dx|² · 2^8
            // <= |u|² (the step's components rounded up, in the same
            // units).
            let dx = t[1].map(|c| (c.unsigned_abs() >> 2) as i32 + 1);
            let dd = wmul(dx[0], dx[0]) + wmul(dx[1], dx[1]) + wmul(dx[2], dx[2]);
            if (dd << 11) + (dd << 8) > lo {
                return None;
            }
            let f = (dd << 15) + (dd << 12) <= lo;
            fine &= f;
            // The view vector's: quadratic (r² <= 1/M, M of the
            // shininess bound kf / 2^12) when fine and so small.
            self.fine_v = if !f {
                0
            } else if VIEW_QUAD && view_quad_ok(dd * 9, lo, kf) {
                2
            } else {
                1
            };
        }
        // The normal's steps along x at most 2^-7.5 of its length (|dn|² ·
        // 2^15 <= |n|², in the units of `na`, the steps rounded up).
        let dn = n[1].map(|c| (c.unsigned_abs() >> 3) as i32 + 1);
        let dd = wmul(dn[0], dn[0]) + wmul(dn[1], dn[1]) + wmul(dn[2], dn[2]);
        if NORMAL_QUAD && self.fine_v == 2 && (dd * 9).saturating_mul(1 << 15) <= alo {
            self.fine_v |= 4;
        }
        self.fine = fine;
        #[cfg(test)]
        FINES.with(|c| c.set(c.get() + u32::from(fine)));
        #[cfg(test)]
        FINES_V.with(|c| c.set(c.get() + u32::from(!fine && self.fine_v != 0)));
        #[cfg(test)]
        QUADS_V.with(|c| c.set(c.get() + u32::from(self.fine_v & 2 != 0)));
        #[cfg(test)]
        QUADS_N.with(|c| c.set(c.get() + u32::from(self.fine_v & 4 != 0)));
        // In the loop's units times 2^32 (A, D, E, F: 2^-30 of the
        // products, B, C: 2^-29), the values biased by 2^31.
        self.at = [xa, ya];
        let [qa, qb, qc, qd, qe, qf] = &mut self.q;
        loop_units(qa, square(&n), 2);
        loop_units(qb, square(&lt), 3);
        loop_units(qc, square(&vt), 3);
        loop_units(qd, quad2(&n, &lt), 2);
        loop_units(qe, quad2(&n, &vt), 2);
        loop_units(qf, quad2(&lt, &vt), 2);
        self.ry = None;
        Some(())
    }

    /// Keeps triangle `tri` of object `po` in `frame` (the
    /// `PhongPosition` layout) for its set-up ([`TriQuad::set`]); none
    /// when its vertices are not at hand.
    #[inline(never)]
    pub(crate) fn set_of_tri<P: crate::num::Profile>(
        &mut self,
        frame: &super::super::Frame<'_, P>,
        po: &super::super::PreparedObject,
        tri: &super::super::PreparedTri,
    ) {
        let mut v = [([0i32; 2], [0i32; 3], [0i32; 3]); 3];
        for (o, &i) in v.iter_mut().zip(tri.v.iter()) {
            let vx = frame
                .xy(usize::from(i))
                .and_then(|xy| Some((xy, frame.vertex::<6>(po, i, xy)?)));
            let Some((xy, vx)) = vx else {
                self.pending = false;
                self.ok = false;
                self.key = 0;
                self.made = false;
                return;
            };
            let a = |j: usize| raw::<P::Lerp>(vx.attrs[j]);
            *o = (xy, [a(0), a(1), a(2)], [a(3), a(4), a(5)]);
        }
        self.set(v, P::SUBPIXEL_BITS, tri.back);
        self.key = key_of(tri.v, tri.back);
    }

    /// Takes the set-up of the triangle of key `key` (its prepared
    /// vertices and face) from `slots` when one holds it for light
    /// position `light`: whether found (else nothing changed). The slot
    /// is freed when the triangle ends in this band (rows `..y1`).
    #[inline(never)]
    pub(super) fn load(
        &mut self,
        key: u64,
        slots: &mut [QuadSlot],
        light: [i32; 3],
        y1: i32,
    ) -> bool {
        let Some(s) = slots.iter_mut().find(|s| s.key == key && s.light == light) else {
            return false;
        };
        self.at = s.at;
        self.q = s.q;
        self.fine = s.fine;
        self.fine_v = s.fine_v;
        self.ok = s.ok;
        self.key = key;
        self.pending = false;
        self.made = false;
        self.ry = None;
        if s.last < y1 {
            s.key = 0;
        }
        true
    }

    /// Keeps the set-up made for the triangle in a free slot of `slots`
    /// (light position `light`) when the triangle continues below the
    /// band of rows `y0..y1`; a slot whose triangle ends above `y0` is
    /// free. None free: not kept (made again in the next band).
    #[inline(never)]
    pub(super) fn store(&mut self, slots: &mut [QuadSlot], light: [i32; 3], (y0, y1): (i32, i32)) {
        if !core::mem::take(&mut self.made) {
            return;
        }
        let key = self.key;
        if key == 0 {
            return;
        }
        // A pixel row `r` is covered only when its centre is not below
        // the lowest vertex: `(2r + 1) · 2^(s-1) <= ymax`.
        let ymax = self.verts.iter().map(|v| v.0[1]).max().unwrap_or(0);
        let last = ymax.saturating_mul(2).saturating_sub(1) >> (self.sub.get() + 1);
        if last < y1 {
            return;
        }
        if let Some(s) = slots.iter_mut().find(|s| s.key == 0 || s.last < y0) {
            // Field by field (a whole slot built first took its size of
            // stack).
            s.key = key;
            s.light = light;
            s.last = last;
            s.ok = self.ok;
            s.at = self.at;
            s.q = self.q;
            s.fine = self.fine;
            s.fine_v = self.fine_v;
        }
    }

    /// The point loop's plan of the span from pixel `(x, y)` (inside the
    /// triangle): each quadratic and its first and second differences
    /// along the row there, exactly. With [`STEPPED`], the last span's
    /// plan stepped (`TriQuad::plan_stepped`), else the row's values
    /// stepped (`TriQuad::plan_rows`).
    ///
    /// A span of `len` pixels, more than one chunk, steps the plan along
    /// the row ([`Plan`]'s chunk steps): with [`STEPPED`] its start is
    /// kept here and put back at the next span ([`TriQuad::restore`]),
    /// not followed (the differences in y stepped with the chunks, the
    /// next plan made from the quadratics when its start is not within
    /// [`DX_STEP`] of the last chunk's: span phong-kpoint M4 153.12 ->
    /// 151.76, M0 491.26 -> 483.59 a pixel).
    #[inline(never)]
    pub(super) fn plan(&mut self, x: i32, y: i32, len: u32) -> bool {
        let (x, y) = (x.wrapping_sub(self.at[0]), y.wrapping_sub(self.at[1]));
        if x.unsigned_abs() >= 1 << 15 || y.unsigned_abs() >= 1 << 15 {
            return false;
        }
        if STEPPED {
            if self.kept {
                self.restore();
            }
            self.plan_stepped(x, y);
            if len > CHUNK as u32 {
                self.kept = true;
                for (k, o) in self.start.iter_mut().zip(self.span.q.iter()) {
                    *k = [o[0], o[1]];
                }
            }
        } else {
            self.plan_rows(x, y);
        }
        true
    }

    /// [`TriQuad::plan`] from the last span's plan (at `(cx, ry)`, with
    /// each quadratic's first difference in y there, `g`): on the next
    /// row with a start at most [`DX_STEP`] pixels away, three additions
    /// a quadratic for the row (`f(x, y + 1) = f + g`, `f'` by `b`, `g` by
    /// `2c`) and three more a pixel of the offset (`f(x ± 1)`, `f'` by
    /// `2a`, `g` by `b`), no product; else made from the quadratics
    /// (`TriQuad::plan_direct`).
    #[inline(always)]
    fn plan_stepped(&mut self, x: i32, y: i32) {
        let dx = x.wrapping_sub(self.cx);
        match self.ry {
            Some(r) if r.wrapping_add(1) == y && dx.unsigned_abs() <= DX_STEP => match dx {
                0 => self.step_row::<0>(),
                1 => self.step_row::<1>(),
                -1 => self.step_row::<-1>(),
                2 => self.step_row::<2>(),
                _ => self.step_row::<-2>(),
            },
            Some(r) if FAR && r.wrapping_add(1) == y && dx.unsigned_abs() < 1 << 7 => {
                self.step_far(dx);
            }
            Some(r) if r == y && dx == 0 => {}
            _ => self.plan_direct(x, y),
        }
        self.ry = Some(y);
        self.cx = x;
    }

    /// The plan one row down and `DX` pixels along it (`|DX| <=`
    /// [`DX_STEP`]), by additions.
    #[inline(always)]
    fn step_row<const DX: i32>(&mut self) {
        for ((o, g), q) in self
            .span
            .q
            .iter_mut()
            .zip(self.g.iter_mut())
            .zip(self.q.iter())
        {
            let (b, c) = (q[4], q[5]);
            let mut v = o[0].wrapping_add(*g);
            let mut d1 = o[1].wrapping_add(b);
            let mut gy = g.wrapping_add(c.wrapping_add(c));
            let a2 = o[2];
            for _ in 0..DX.unsigned_abs() {
                if DX > 0 {
                    v = v.wrapping_add(d1);
                    d1 = d1.wrapping_add(a2);
                    gy = gy.wrapping_add(b);
                } else {
                    d1 = d1.wrapping_sub(a2);
                    v = v.wrapping_sub(d1);
                    gy = gy.wrapping_sub(b);
                }
            }
            o[0] = v;
            o[1] = d1;
            *g = gy;
        }
    }

    /// The plan one row down and `dx` pixels along it (`|dx| < 2^7`): the
    /// row by additions (as [`TriQuad::step_row`]), the offset by four
    /// products a quadratic (`f(x + t) = f + t f' + a t (t - 1)`, `f'` by
    /// `2a t`, `g` by `b t`), not six ([`TriQuad::plan_direct`]).
    #[inline(never)]
    fn step_far(&mut self, dx: i32) {
        for ((o, g), q) in self
            .span
            .q
            .iter_mut()
            .zip(self.g.iter_mut())
            .zip(self.q.iter())
        {
            let (a, b, c) = (q[3], q[4], q[5]);
            let d1 = o[1].wrapping_add(b);
            let at = mul_small(a, dx);
            o[0] = o[0]
                .wrapping_add(*g)
                .wrapping_add(mul_small(d1, dx))
                .wrapping_add(mul_small(at, dx.wrapping_sub(1)));
            o[1] = d1.wrapping_add(at.wrapping_add(at));
            *g = g
                .wrapping_add(c.wrapping_add(c))
                .wrapping_add(mul_small(b, dx));
        }
    }

    /// The plan at `(x, y)` (offsets from the anchor, below `2^15`) and
    /// each quadratic's first difference in y there, from the
    /// quadratics: `f + x (d + a x + b y) + y (e + c y)`, `d + a (2x + 1)
    /// + b y` and `e + b x + c (2y + 1)` (six products a quadratic).
    #[inline(never)]
    fn plan_direct(&mut self, x: i32, y: i32) {
        for ((o, g), &[f, d, e, a, b, c]) in self
            .span
            .q
            .iter_mut()
            .zip(self.g.iter_mut())
            .zip(self.q.iter())
        {
            let ax = mul_small(a, x);
            let cy = mul_small(c, y);
            let u = d.wrapping_add(ax).wrapping_add(mul_small(b, y));
            let ey = e.wrapping_add(cy);
            o[0] = f
                .wrapping_add(mul_small(u, x))
                .wrapping_add(mul_small(ey, y));
            o[1] = u.wrapping_add(ax).wrapping_add(a);
            o[2] = a.wrapping_add(a);
            *g = ey
                .wrapping_add(cy)
                .wrapping_add(c)
                .wrapping_add(mul_small(b, x));
        }
    }

    /// The plan's start kept by [`TriQuad::plan`] for a span of more than
    /// one chunk put back (the point loop stepped it along the row).
    #[inline(never)]
    fn restore(&mut self) {
        self.kept = false;
        for (k, o) in self.start.iter().zip(self.span.q.iter_mut()) {
            o[0] = k[0];
            o[1] = k[1];
        }
    }

    /// [`TriQuad::plan`] from the rows' values ([`STEPPED`] off). The
    /// row's values are stepped from the previous span's row when it is
    /// the row above (three additions a quadratic), else made from the
    /// quadratic; then two products by the offset along the row a
    /// quadratic. The second differences (`2a`, the same for every span)
    /// are `set_row`'s: measured (dodecahedron Phong raster, M4 and M0)
    /// 1 684 470 -> 1 667 249 and 4 427 143 -> 4 419 572, the span sweep
    /// 161.91 -> 161.72 and 497.13 -> 497.06 a pixel (`plan_equals_direct`
    /// checks the plans).
    #[inline(always)]
    fn plan_rows(&mut self, x: i32, y: i32) {
        let next = match self.ry {
            Some(r) if r == y => false,
            Some(r) if r.wrapping_add(1) == y => true,
            _ => {
                self.set_row(y);
                false
            }
        };
        self.ry = Some(y);
        // One quadratic at a time: its row stepped (the row below the
        // last span's), then its value and differences at x.
        for ((o, row), q) in self
            .span
            .q
            .iter_mut()
            .zip(self.row.iter_mut())
            .zip(self.q.iter())
        {
            let (a, b) = (q[3], q[4]);
            if next {
                row[0] = row[0].wrapping_add(row[1]);
                row[1] = row[1].wrapping_add(row[3]);
                row[2] = row[2].wrapping_add(b);
            }
            let ax = mul_small(a, x);
            let u = row[2].wrapping_add(ax);
            o[0] = row[0].wrapping_add(mul_small(u, x));
            o[1] = u.wrapping_add(ax).wrapping_add(a);
            // o[2] = 2a: set by `set_row`.
        }
    }

    /// The rows' values at row `y` from the quadratics (a span's first
    /// row in the band, or after a row without span), and the plan's
    /// second differences along the row, `2a` of each quadratic (the
    /// same for every span of the triangle: set here, where every new
    /// set-up of the quadratics comes first, `ry` being reset with them,
    /// not in each span's [`TriQuad::plan`]; [`Plan`]'s steps keep them).
    #[inline(never)]
    fn set_row(&mut self, y: i32) {
        for ((row, o), &[f, d, e, a, b, c]) in self
            .row
            .iter_mut()
            .zip(self.span.q.iter_mut())
            .zip(self.q.iter())
        {
            let cy = mul_small(c, y);
            row[0] = f.wrapping_add(mul_small(e.wrapping_add(cy), y));
            row[1] = e.wrapping_add(cy.wrapping_mul(2)).wrapping_add(c);
            row[2] = d.wrapping_add(mul_small(b, y));
            row[3] = c.wrapping_add(c);
            o[2] = a.wrapping_add(a);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`TriQuad::plan`] of spans in any order of rows (the same row, the
    /// next, a jump, a new set-up of the quadratics between them) equals
    /// each quadratic and its two differences along the row at the span's
    /// first pixel evaluated directly (wrapping `i64`): the second
    /// differences, set by `set_row` only, included.
    #[test]
    fn plan_equals_direct() {
        let mut next = crate::geom::testkit::xorshift(0x2545_f491_4f6c_dd1d);
        let mut t = TriQuad::NONE;
        let (mut x, mut y) = (0i32, 0i32);
        for i in 0..20_000u32 {
            if i % 97 == 0 {
                // A new set-up (`make`, `load`): new quadratics, no row.
                t.at = [(next() % 4000) as i32 - 2000, (next() % 4000) as i32 - 2000];
                for q in &mut t.q {
                    for c in q.iter_mut() {
                        *c = next() as i64 >> (next() % 40);
                    }
                }
                t.ry = None;
            }
            let u = next();
            y = match u % 4 {
                0 => y,
                1 | 2 => y + 1,
                _ => t.at[1] + (u >> 8) as i32 % 3000 - 1500,
            };
            // Starts near the last one's (stepped), or anywhere.
            x = if !(u >> 40).is_multiple_of(4) {
                x + ((u >> 44) % 7) as i32 - 3
            } else {
                t.at[0] + (u >> 24) as i32 % 3000 - 1500
            };
            let len = if (u >> 50).is_multiple_of(8) {
                33 + ((u >> 53) % 100) as u32
            } else {
                1 + ((u >> 53) % 32) as u32
            };
            assert!(t.plan(x, y, len));
            let (dx, dy) = (i64::from(x - t.at[0]), i64::from(y - t.at[1]));
            let f = |q: &[i64; 6], x: i64| {
                let [f, d, e, a, b, c] = *q;
                f.wrapping_add(d.wrapping_mul(x))
                    .wrapping_add(e.wrapping_mul(dy))
                    .wrapping_add(a.wrapping_mul(x).wrapping_mul(x))
                    .wrapping_add(b.wrapping_mul(x).wrapping_mul(dy))
                    .wrapping_add(c.wrapping_mul(dy).wrapping_mul(dy))
            };
            for (o, q) in t.span.q.iter().zip(t.q.iter()) {
                let (v0, v1, v2) = (f(q, dx), f(q, dx + 1), f(q, dx + 2));
                let d1 = v1.wrapping_sub(v0);
                let want = [v0, d1, v2.wrapping_sub(v1).wrapping_sub(d1)];
                assert_eq!(*o, want, "{i}: ({x}, {y})");
            }
            // Sometimes a long span: the plan stepped by the point
            // loop's chunks (the next plan starts from the span's start,
            // kept).
            if len > CHUNK as u32 {
                for _ in 0..(len - 1) / CHUNK as u32 {
                    t.span.step_chunk();
                }
                if (u >> 60).is_multiple_of(2) {
                    x += 1;
                }
            }
        }
    }

    /// The ARMv6-M products equal the 64-bit ones (modulo `2^64`).
    #[test]
    fn split_products() {
        let mut r = 0x9e37_79b9_7f4a_7c15u64;
        for i in 0..100_000 {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            let x = r as i64;
            let y = (r >> (i % 40)) as i32;
            assert_eq!(mul_wide_split(x, y), x.wrapping_mul(i64::from(y)));
            let ys = y % (1 << 15);
            assert_eq!(mul_small_split(x, ys), x.wrapping_mul(i64::from(ys)));
        }
        for (x, y) in [
            (i64::MIN, -1),
            (i64::MAX, i32::MIN),
            (-1, 32767),
            (1 << 62, -32767),
        ] {
            assert_eq!(mul_wide_split(x, y), x.wrapping_mul(i64::from(y)));
        }
    }
}
