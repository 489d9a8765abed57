//! The fixed affine fast path of the band renderer: `i32` values stepped
//! without perspective (the `fast` profile and its affine relatives), one
//! fused row kernel per (pixel format, depth format, value count).
//!
//! The generic walker ([`Walk::rows`]) hands each span to a sink that
//! slices the band, checks the depth plane flag and dispatches to the span
//! stage; here the row loop owns the band buffers:
//!
//! - per triangle visit: the clipping and depth-range decisions (made once
//!   at setup, [`Walk::inside`], [`Walk::z16`]) select one of four loops,
//!   and the values at column 0 of the first row are one multiply-add per
//!   value away from the values at pixel (0, 0);
//! - per row: two edge steps, the `x0 < x1` test, one multiply-add per
//!   value for the span start, the row offset advanced by the width and
//!   the column-0 values by their y steps;
//! - per span: the colour and depth slices (one range check each) and the
//!   span stage's own pixel loops: [`inr_span`] for a triangle whose
//!   depths are all in range (the kernel [`Fill`](super::Fill) runs too,
//!   so the firmware's span-loop figures are this loop's), [`depth_loop`]
//!   with the clamping test otherwise; so the bytes are those of the
//!   generic path.
//!
//! Values are the same modulo 2^32 as the generic walker's `row + sx·x0 +
//! sy·j` (wrapping sums of the same whole steps), hence the same pixels.

use super::span::{clamp_test, depth_loop, in_range_test, inr_span};
use super::triangle::{first_row, row_range};
use super::walk::{setup, Vals, Walk};
use super::{Edge, InvArea, Lerp, SubpixelBits, Vertex};
use crate::num::wide::{clz32, mul_i32_i16_soft, NO_LONG_MUL};
use crate::target::{Depth16, DepthFormat};

/// A band's memory as the fused row kernel sees it: colour and depth
/// slices of `width`-pixel rows starting at screen row `y0`.
pub(crate) struct BandMem<'k, 'b, R, Z> {
    /// Colour, row-major.
    pub px: &'k mut &'b mut [R],
    /// Depth, the same layout.
    pub z: &'k mut Option<&'b mut [Z]>,
    /// First screen row of the band.
    pub y0: i32,
    /// Pixels per row.
    pub width: i32,
}

/// The row loop of [`Walk::fused`] and [`Walk::fused_nodepth`]: from the
/// next row down to `until` (excluded) or the triangle's last row, `$body`
/// once per row with the edges `$l`, `$r`, the values `$v` at column 0 of
/// the row, its offset `$base` in the band and the pixel count `$drawn`
/// in scope; between rows two edge steps, the values' y step and the
/// offset's advance. Evaluates to the pixel count. A macro, not a function
/// taking the body as a closure: that form cost bunny-gouraud raster
/// thumbv7em 1 642 158 -> 1 660 698 and bunny-flat thumbv6m 2 197 727 ->
/// 2 235 398.
macro_rules! each_row {
    ($w:ident, $row:expr, $sy:expr, $until:expr, $y0:expr, $width:expr,
     |$l:ident, $r:ident, $v:ident, $base:ident, $drawn:ident| $body:block) => {{
        let Some((stop, mut $v, mut $base)) = $w.open_rows($row, $sy, $until, $y0, $width) else {
            return 0;
        };
        let mut $drawn = 0u32;
        while $w.j < stop {
            let r1 = $w.half_end(stop);
            let (mut $l, mut $r) = ($w.left, $w.right);
            for _ in $w.j..r1 {
                $body
                $l.step();
                $r.step();
                $v = $v.add_n($sy, 1);
                $base = $base.wrapping_add($width as usize);
            }
            $w.left = $l;
            $w.right = $r;
            $w.j = r1;
        }
        $drawn
    }};
}

impl Walk {
    /// Walks rows from the next one down to `until` (excluded) or the
    /// triangle's last row, drawing each span into `mem` with `color`
    /// (values at the pixel centre); returns the pixels written. `vals`
    /// holds the values at pixel (0, 0) and their steps ([`pack_vals`]).
    #[inline(always)]
    pub(crate) fn rows_fused<const N: usize, const V: usize, R: Copy, D: DepthFormat>(
        &mut self,
        vals: &[[i32; 3]; V],
        until: i32,
        mem: &mut BandMem<'_, '_, R, D::Raw>,
        color: impl Fn(&[i32; N]) -> R,
    ) -> u32 {
        let [row, sx, sy] = unpack_fixed::<N, V>(vals);
        let (row, sx, sy) = (&row, &sx, &sy);
        let (y0, width) = (mem.y0, mem.width);
        let px = &mut **mem.px;
        match mem.z.as_deref_mut() {
            Some(z) => {
                let (px, z) = same_len(px, z);
                let inr = D::plane_in_range(self.z16);
                match (self.inside, inr) {
                    (true, true) => self.fused::<N, R, D, false, true>(
                        row, sx, sy, until, px, z, y0, width, &color,
                    ),
                    (true, false) => self.fused::<N, R, D, false, false>(
                        row, sx, sy, until, px, z, y0, width, &color,
                    ),
                    (false, true) => self
                        .fused::<N, R, D, true, true>(row, sx, sy, until, px, z, y0, width, &color),
                    (false, false) => self.fused::<N, R, D, true, false>(
                        row, sx, sy, until, px, z, y0, width, &color,
                    ),
                }
            }
            None => self.fused_nodepth::<N, R>(row, sx, sy, until, px, y0, width, &color),
        }
    }

    /// The depth-tested row loop: `CLIP` clamps spans to the width, `INR`
    /// takes the depth test without clamps (every depth of the triangle in
    /// range).
    #[allow(clippy::too_many_arguments)]
    #[cfg_attr(armv6m, inline(always))]
    #[cfg_attr(not(armv6m), inline(never))]
    fn fused<const N: usize, R: Copy, D: DepthFormat, const CLIP: bool, const INR: bool>(
        &mut self,
        row: &Vals<i32, N>,
        sx: &Vals<i32, N>,
        sy: &Vals<i32, N>,
        until: i32,
        px: &mut [R],
        z: &mut [D::Raw],
        y0: i32,
        width: i32,
        color: &impl Fn(&[i32; N]) -> R,
    ) -> u32 {
        each_row!(self, row, sy, until, y0, width, |l, r, v, base, drawn| {
            let (x0, x1) = if CLIP {
                (l.x.max(0), r.x.min(width))
            } else {
                (l.x, r.x)
            };
            if x0 < x1 {
                let s = v.add_n(sx, x0);
                let span = base.wrapping_add(x0 as usize)..base.wrapping_add(x1 as usize);
                if let (Some(p), Some(d)) = (px.get_mut(span.clone()), z.get_mut(span)) {
                    drawn += if INR {
                        inr_span::<i32, N, R, D>(p, d, s.z, s.a, sx, color)
                    } else {
                        p.len() as u32
                            - depth_loop(p, d, s.z, sx.z, s.a, &sx.a, color, clamp_test::<i32, D>)
                    };
                }
            }
        })
    }

    /// The row loop without depth: every covered pixel written.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn fused_nodepth<const N: usize, R: Copy>(
        &mut self,
        row: &Vals<i32, N>,
        sx: &Vals<i32, N>,
        sy: &Vals<i32, N>,
        until: i32,
        px: &mut [R],
        y0: i32,
        width: i32,
        color: &impl Fn(&[i32; N]) -> R,
    ) -> u32 {
        each_row!(self, row, sy, until, y0, width, |l, r, v, base, drawn| {
            let (x0, x1) = (l.x.max(0), r.x.min(width));
            if x0 < x1 {
                let mut a = v.add_n(sx, x0).a;
                let span = base.wrapping_add(x0 as usize)..base.wrapping_add(x1 as usize);
                if let Some(p) = px.get_mut(span) {
                    drawn += p.len() as u32;
                    for q in p.iter_mut() {
                        *q = color(&a);
                        for (x, d) in a.iter_mut().zip(sx.a.iter()) {
                            *x = x.wrapping_add(*d);
                        }
                    }
                }
            }
        })
    }

    /// What both row loops start from: the row after the last they walk
    /// (`until` or the triangle's end), the values at column 0 of the next
    /// row and that row's offset in the band; `None` when no row is left.
    #[inline(always)]
    fn open_rows<const N: usize>(
        &self,
        row: &Vals<i32, N>,
        sy: &Vals<i32, N>,
        until: i32,
        y0: i32,
        width: i32,
    ) -> Option<(i32, Vals<i32, N>, usize)> {
        let stop = until.min(self.end);
        if self.j >= stop {
            return None;
        }
        let v = row.add_n(sy, self.j);
        let base = (self.j - y0).wrapping_mul(width) as usize;
        Some((stop, v, base))
    }
}

impl Walk {
    /// [`Walk::rows_fused`] for a resumed triangle (a pool slot's walk
    /// and values, walked in place): with a depth plane, the triangle
    /// inside the window and every depth in range (every triangle
    /// [`draw_small`] hands on, most of the others), the rows down to
    /// `until` through the resume kernel [`resume_rows`]; the others
    /// through [`Walk::rows_fused`]. The same pixels, walk and values.
    #[inline(always)]
    pub(crate) fn rows_resumed<const N: usize, const V: usize, R: Copy, D: DepthFormat>(
        &mut self,
        vals: &[[i32; 3]; V],
        until: i32,
        mem: &mut BandMem<'_, '_, R, D::Raw>,
        color: impl Fn(&[i32; N]) -> R,
    ) -> u32 {
        if RESUME_KERNEL && N > 0 && !cfg!(armv6m) && self.inside && D::plane_in_range(self.z16) {
            if let Some(z) = mem.z.as_deref_mut() {
                let stop = until.min(self.end);
                if self.j >= stop {
                    return 0;
                }
                let (px, z) = same_len(mem.px, z);
                let band = [stop, mem.y0, mem.width];
                return resume_rows::<N, V, R, D>(self, vals, band, px, z, &color);
            }
        }
        self.rows_fused::<N, V, R, D>(vals, until, mem, color)
    }
}

/// Resumed triangles through [`resume_rows`] (else [`Walk::rows_fused`]):
/// those with values (`N > 0`) off ARMv6-M. Exact QEMU counts,
/// bunny-gouraud raster thumbv7em (every CRC unchanged): without it
/// 1 628 965, with it 1 622 563 (first 1 657 797 before the resumed
/// triangles skipped their fetch in `render::active`; `resume_rows`
/// 136 420 against [`Walk::fused`] and the span stage's `in_range_loop`
/// 126 630 at the slot arm, whose call costs 16 K more), with the x
/// steps in registers (not through `core::hint::black_box` as in
/// [`draw_small`]) 1 615 109; the host's bunny frame (callgrind,
/// `examples/bunny_frame.rs`) 2 168 864 -> 2 149 425. Not for flat
/// triangles (`N = 0`: bunny-flat raster thumbv7em 1 456 821 ->
/// 1 483 489) nor on ARMv6-M (bunny-gouraud raster thumbv6m 2 370 412 ->
/// 2 376 517; there [`Walk::fused`] is inlined already).
///
/// Measured and not kept (thumbv7em bunny-gouraud raster, from
/// 1 615 109): the edges packed in one word each (`x·2^20 + e`, stepped
/// by `p += q·2^20 - r` and `p += 2^20 + d` when bit 19 is set, exact for
/// `d <= 2^19` and columns below `2^11`), the values at column 0 of the
/// row stepped by their y steps with the levels' rounding offset in, the
/// rows counted by offset: 22 instructions a row instead of 36, but 19 a
/// passing pixel instead of 18 and 27 a span start instead of 22, the
/// edges packed at each call and stored back: 1 621 783 (the failed
/// tests counted in memory; in a register 1 622 696, the spans through
/// the span stage's [`inr_span`] 1 625 602, the rows in a closure that
/// the compiler called out of line 1 646 422). In this kernel, only the
/// edges' columns and error terms stored back (their steps unchanged but
/// at the lower half's first row): 1 622 459.
const RESUME_KERNEL: bool = true;

/// The rows `$j..$stop` of a small triangle ([`draw_small`],
/// [`resume_rows`]): a span a row between the edges `$l` and `$r`, both
/// stepped after it, the rows counted by their offset (reaching `$end`,
/// that of row `$stop`) unless [`SmallRows::LAZY`]. A macro, not a method:
/// as an `#[inline(always)]` method taking the edges by value and the
/// end as an argument it cost bunny-flat raster thumbv6m 2 055 671 ->
/// 2 098 737 and thumbv7em 1 456 821 -> 1 475 421 (exact QEMU counts).
/// The [`SmallRows`] of [`draw_small`] and [`resume_rows`] from row `$j`
/// (band's first row `$y0`, rows `$width` pixels apart): `$row` the values
/// at pixel (0, 0), stepped to row `$j` by `$sy` unless
/// [`SmallRows::LAZY`]; the failed tests counted apart in `$fail_count`.
/// ARMv7-M without values: the count in memory the optimiser cannot
/// follow, so that no register holds it across the rows (bunny-flat
/// raster thumbv7em 1 501 529 -> 1 473 507; the values' count, `drawn`,
/// gained nothing that way). A macro: as an `#[inline(always)]`
/// constructor it measured bunny-gouraud raster thumbv7em 1 615 109 ->
/// 1 616 676 (bunny-flat 1 456 821 -> 1 454 673), the counts moving with
/// the functions' inlining order.
macro_rules! small_rows_at {
    ($row:ident, $sy:ident, $j:ident, $y0:ident, $width:ident, $fail_count:ident) => {{
        let fails = if NO_LONG_MUL || N > 0 {
            &mut $fail_count
        } else {
            core::hint::black_box(&mut $fail_count)
        };
        let v_first = if SmallRows::<'_, N>::LAZY {
            $row
        } else {
            $row.add_n(&$sy, $j)
        };
        SmallRows {
            vz: v_first.z,
            va: v_first.a,
            base: ($j - $y0).wrapping_mul($width) as usize,
            width: $width as usize,
            drawn: 0,
            fails,
        }
    }};
}

macro_rules! small_rows_to {
    ($rows:ident, $j:ident, $stop:expr, $end:expr, $l:ident, $r:ident, $levels:tt, ($px:ident, $z:ident, $sx:ident, $sy:ident, $color:expr)) => {
        let end = $end;
        while if !SmallRows::<'_, N>::LAZY {
            $rows.base != end
        } else {
            $j < $stop
        } {
            $rows.span::<R, D, $levels>($j, $l.x, $r.x, $px, $z, $sx, $sy, $color);
            $l.step();
            $r.step();
            $j += 1;
        }
    };
}

/// The resume kernel: walks the record `w` (a pool slot's walk, its
/// values `vals` at pixel (0, 0) with their steps, [`pack_vals`]) in place
/// from its next row down to `band[0]` (excluded, below the triangle's
/// end and the walk's next row; `band[1]` the band's first row,
/// `band[2]` its width), the lower short edge swapped in at the middle
/// row as [`Walk::half_end`] does, and leaves its edges and next row for
/// the next band. The triangle lies inside the window, its every depth
/// in range (the caller's test): the rows and spans of [`draw_small`]
/// ([`SmallRows`], no clamp, no call per span). Returns the pixels
/// written. Out of line: every register free for the rows (see
/// [`RESUME_KERNEL`] for what it measured). Tested against
/// [`Walk::rows_fused`] band by band.
#[inline(never)]
fn resume_rows<const N: usize, const V: usize, R: Copy, D: DepthFormat>(
    w: &mut Walk,
    vals: &[[i32; 3]; V],
    band: [i32; 3],
    px: &mut [R],
    z: &mut [D::Raw],
    color: &impl Fn(&[i32; N]) -> R,
) -> u32 {
    let [stop, y0, width] = band;
    let [row, sx, sy] = unpack_fixed::<N, V>(vals);
    let mut fail_count = 0u32;
    let mut j = w.j;
    let mid = w.mid;
    let mut rows = small_rows_at!(row, sy, j, y0, width, fail_count);
    let (sx, sy) = (&sx, &sy);
    let off = |j: i32| (j - y0).wrapping_mul(width) as usize;
    let (mut l, mut r) = (w.left, w.right);
    if j < mid {
        let stop_upper = mid.min(stop);
        small_rows_to!(
            rows,
            j,
            stop_upper,
            off(stop_upper),
            l,
            r,
            false,
            (px, z, sx, sy, color)
        );
        j = stop_upper;
    }
    if j == mid && j < stop {
        if w.long_left {
            r = w.low;
        } else {
            l = w.low;
        }
    }
    if j < stop {
        small_rows_to!(
            rows,
            j,
            stop,
            off(stop),
            l,
            r,
            false,
            (px, z, sx, sy, color)
        );
        j = stop;
    }
    w.left = l;
    w.right = r;
    w.j = j;
    rows.drawn()
}

/// [`setup`] for `i32` values: the same walk and values, bit for bit.
///
/// The usual triangle takes a straight 32-bit path ([`setup32`], on
/// ARMv6-M with 16 × 32-bit products from two `MULS` and the reciprocal
/// without a division); the others take [`setup`] itself.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn setup_fast<const N: usize, const V: usize>(
    a: &Vertex<i32, N>,
    b: &Vertex<i32, N>,
    c: &Vertex<i32, N>,
    sub: SubpixelBits,
    j0: i32,
    width: i32,
    walk: &mut Walk,
    vals: &mut [[i32; 3]; V],
) -> bool {
    match setup32(a, b, c, sub, j0, width, walk, vals) {
        Ok(drawn) => drawn,
        // The vertices by value: their copy is made on this rare path
        // only (by reference they would live in memory on every path).
        Err(()) => setup_slow([*a, *b, *c], sub, j0, width, walk, vals),
    }
}

/// Stores row values and steps in a slot's values: entry 0 the depth,
/// entry `k + 1` attribute `k`, each `[value at pixel (0, 0), x step, y
/// step]` (entries beyond `N + 1` untouched).
#[inline(always)]
pub(crate) fn pack_vals<L: Lerp, const N: usize, const V: usize>(
    v: &mut [[L; 3]; V],
    row: &Vals<L, N>,
    sx: &Vals<L, N>,
    sy: &Vals<L, N>,
) {
    if let Some(x) = v.get_mut(0) {
        *x = [row.z, sx.z, sy.z];
    }
    for k in 0..N {
        if let Some(x) = v.get_mut(k + 1) {
            *x = [row.a[k], sx.a[k], sy.a[k]];
        }
    }
}

/// A slot's values (see [`pack_vals`]) as row values and steps.
#[inline(always)]
pub(crate) fn unpack_fixed<const N: usize, const V: usize>(v: &[[i32; 3]; V]) -> [Vals<i32, N>; 3] {
    let get = |k: usize, c: usize| v.get(k).map_or(0, |x| x[c]);
    let f = |c: usize| Vals {
        z: get(0, c),
        a: core::array::from_fn(|k| get(k + 1, c)),
    };
    [f(0), f(1), f(2)]
}

/// [`setup`] out of line: the rare triangles [`setup32`] leaves.
#[inline(never)]
#[cold]
#[allow(clippy::too_many_arguments)]
fn setup_slow<const N: usize, const V: usize>(
    v: [Vertex<i32, N>; 3],
    sub: SubpixelBits,
    j0: i32,
    width: i32,
    walk: &mut Walk,
    vals: &mut [[i32; 3]; V],
) -> bool {
    let [a, b, c] = &v;
    match setup::<i32, N>(a, b, c, sub, j0, width) {
        Some((w, r, sx, sy)) => {
            *walk = w;
            pack_vals(vals, &r, &sx, &sy);
            true
        }
        None => false,
    }
}

/// What [`setup32`] computes a value's plane from: the vertex offsets
/// `[dx1, dy1, dx2, dy2]`, the reciprocal of the doubled area and its
/// high-word shift `k`, the subpixel bits `s`, and the offsets `o = (h -
/// x0, h - y0)` of the centre of pixel (0, 0) from vertex 0 (`h = S/2`).
#[derive(Clone, Copy)]
struct Grad {
    d: [i32; 4],
    inv: InvArea,
    k: u32,
    s: u32,
    o: [i32; 2],
}

impl Grad {
    /// One value's gradients (x, y), its value at the centre of pixel (0,
    /// 0) and whether the bounds of [`setup32`] hold (else the three
    /// values mean nothing).
    #[inline(always)]
    fn plane(&self, v0: i32, v1: i32, v2: i32) -> (i32, i32, i32, bool) {
        self.plane_diff::<true>(v0, v1, v2)
    }

    /// [`Grad::plane`]; without `WRAPS` for values whose differences are
    /// known not to wrap (then not tested).
    #[inline(always)]
    fn plane_diff<const WRAPS: bool>(&self, v0: i32, v1: i32, v2: i32) -> (i32, i32, i32, bool) {
        let [dx1, dy1, dx2, dy2] = self.d;
        let (d1, o1) = sub_wrap::<WRAPS>(v1, v0);
        let (d2, o2) = sub_wrap::<WRAPS>(v2, v0);
        let nx = wide(d1, dy2) - wide(d2, dy1);
        let ny = wide(d2, dx1) - wide(d1, dx2);
        let ok = !(o1 | o2) & fits(nx) & fits(ny);
        let (gx, gy) = (
            self.inv.quot_high(nx as i32, self.k),
            self.inv.quot_high(ny as i32, self.k),
        );
        let h = 1i64 << (self.s - 1);
        let t = wide(gx, self.o[0]) + wide(gy, self.o[1]) + h;
        (gx, gy, v0.wrapping_add((t >> self.s) as i32), ok)
    }
}

impl Grad {
    /// [`Grad::plane`] with the gradient numerators in 32 bits (ARMv6-M:
    /// no 64-bit products for them), for `lim = 2^(30 - bxy)` where the
    /// coordinate offsets lie below `2^bxy`: when the value differences do
    /// not wrap and lie below `lim` in magnitude, each product of a
    /// numerator is below `2^30`, the numerator below `2^31`, the very
    /// `i32` of [`Grad::plane`]. Otherwise the flag is `false` (and the
    /// values mean nothing).
    #[inline(always)]
    fn plane_short<const WRAPS: bool>(
        &self,
        v0: i32,
        v1: i32,
        v2: i32,
        lim: u32,
    ) -> (i32, i32, i32, bool) {
        let [dx1, dy1, dx2, dy2] = self.d;
        let (d1, o1) = sub_wrap::<WRAPS>(v1, v0);
        let (d2, o2) = sub_wrap::<WRAPS>(v2, v0);
        let ok = !(o1 | o2) & ((d1.unsigned_abs() | d2.unsigned_abs()) < lim);
        let nx = d1.wrapping_mul(dy2).wrapping_sub(d2.wrapping_mul(dy1));
        let ny = d2.wrapping_mul(dx1).wrapping_sub(d1.wrapping_mul(dx2));
        let (gx, gy) = (
            self.inv.quot_high(nx, self.k),
            self.inv.quot_high(ny, self.k),
        );
        (gx, gy, v0.wrapping_add(self.origin_short(gx, gy)), ok)
    }

    /// `(gx·ox + gy·oy + h) >> s` modulo 2^32 ([`Grad::plane`]'s row
    /// origin, the offsets `o` below `2^15` in magnitude as [`wide`] asks)
    /// in 32-bit arithmetic: with `g = 2^15·gh + gl` (`gh = g >> 15`, `gl`
    /// in `0..2^15`) the sum is `2^15·A + B` for `A = gxh·ox + gyh·oy`
    /// and `B = gxl·ox + gyl·oy + h`, `|B| <= 2·(2^15 - 1)^2 + 2^(s-1) <
    /// 2^31` (an exact `i32`); for `s <= 8` its floor by `2^s` is
    /// `A·2^(15-s) + (B >> s)`, for which `A` is needed modulo `2^32`
    /// only (the wrapping products). Exact, the very bits. It replaced
    /// `g = 2^16·gh + gl` with `gl` in `0..2^16` (`B` in two parts below
    /// `2^31` and the carry of their low `s` bits): exact QEMU counts,
    /// bunny-gouraud raster thumbv6m 2 455 763 -> 2 451 396, bunny-flat
    /// 2 130 680 -> 2 126 401. Measured and not kept: the signed low half
    /// (`SXTH`, `gh = (g >> 16) - (gl >> 31)`), 2 455 763 -> 2 462 806
    /// (bunny-flat 2 130 835); later the low half as `g - (gh << 15)`
    /// instead of the mask, 2 391 960 -> 2 400 876.
    #[inline(always)]
    fn origin_short(&self, gx: i32, gy: i32) -> i32 {
        origin_short_at(self.s, self.o, gx, gy)
    }

    /// [`Grad::origin_short`]'s low `32 - s` bits (the others mean
    /// nothing) from the sum modulo 2^32: `⌊t / 2^s⌋ mod 2^(32-s)` is bits
    /// `s..32` of `t`, which the wrapping sum holds. Two `MULS` and no
    /// carries, for a value of which only those bits are used (the grey
    /// level of [`draw_small`] with `LEVELS`, shifted left by 8). Exact in
    /// those bits; tested.
    #[inline(always)]
    fn origin_low(&self, gx: i32, gy: i32) -> i32 {
        let [ox, oy] = self.o;
        let t = gx
            .wrapping_mul(ox)
            .wrapping_add(gy.wrapping_mul(oy))
            .wrapping_add(1 << (self.s - 1));
        ((t as u32) >> self.s) as i32
    }

    /// [`Grad::plane`] on ARMv6-M (and in test builds, which check it)
    /// with [`Grad::plane_short`]'s bound, elsewhere [`Grad::plane`].
    #[inline(always)]
    fn plane_small<const WRAPS: bool>(
        &self,
        v0: i32,
        v1: i32,
        v2: i32,
        lim: u32,
    ) -> (i32, i32, i32, bool) {
        if SHORT_NUMERATORS {
            self.plane_short::<WRAPS>(v0, v1, v2, lim)
        } else {
            self.plane_diff::<WRAPS>(v0, v1, v2)
        }
    }
}

impl Grad {
    /// [`Grad::plane_diff`] without the wrap test, out of line (on ARMv6-M,
    /// for the depths [`Grad::plane_short`] refuses where the fields do
    /// not apply: [`WIDE_RESCUE`]).
    #[inline(never)]
    #[cold]
    fn plane_wide_cold(&self, v0: i32, v1: i32, v2: i32) -> (i32, i32, i32, bool) {
        self.plane_diff::<false>(v0, v1, v2)
    }

    /// [`Grad::plane_fields`] out of line (on ARMv6-M, for the values
    /// [`Grad::plane_short`] refuses: inlined there, it cost the kernel's
    /// other paths more than it saved). The planes' inputs by value: a
    /// copy made on this path only, where by reference they were stored
    /// to the stack for every triangle (bunny-gouraud raster thumbv6m
    /// 2 605 128 -> 2 588 049; [`Grad::plane_wide_cold`] so, bunny-flat
    /// raster 2 197 471 -> 2 211 335: kept by reference). The plane in
    /// `out` as `[gx, gy, origin, ok]` ([`Grad::fields_rescue`]).
    #[inline(never)]
    #[cold]
    fn plane_fields_cold(self, f: [i32; 3], v0: i32, sh: u32, out: &mut [i32; 4]) {
        let (gx, gy, o, ok) = self.plane_fields::<false, false>(f, v0, sh, true);
        *out = [gx, gy, o, i32::from(ok)];
    }

    /// [`Grad::plane_fields_cold`]'s plane: its result through a slot of
    /// its own, written on this path only (returned, it shared its slot
    /// with the inlined planes, which then stored theirs to it for every
    /// triangle: bunny-gouraud raster thumbv6m 2 588 049 -> 2 580 761).
    #[inline(always)]
    fn fields_rescue(self, f: [i32; 3], v0: i32, sh: u32) -> (i32, i32, i32, bool) {
        let mut out = [0; 4];
        self.plane_fields_cold(f, v0, sh, &mut out);
        (out[0], out[1], out[2], out[3] != 0)
    }

    /// The plane of packed values ([`crate::num::Profile::PACKED_GREY`]:
    /// each vertex value `v_i = f_i · 2^sh + c` with a 16-bit field
    /// `f_i = v_i >> sh` and the same low part `c < 2^sh`, the depths at
    /// `sh = 14` and the grey levels at `sh = 8`), from the fields `f` and
    /// the value `v0` at vertex 0, for coordinate offsets below `2^14`:
    /// the value differences are `2^sh` times the field differences (below
    /// `2^16`), so each product of a gradient numerator is below `2^30`
    /// and the numerator (the full one without its `sh` zero low bits) an
    /// exact `i32`, whatever the size of the value differences (which the
    /// 32-bit numerators of [`Grad::plane_short`] bound by `2^(30 -
    /// bxy)`). The gradients by [`InvArea::quot_scaled`], the flag `false`
    /// where it declines (a gradient then reaches `2^29`, and the values
    /// mean nothing). The very gradients and row
    /// origin of [`Grad::plane`] and of the general setup ([`setup`]).
    /// With `UP` the caller promises `k <= sh`: the gradients by
    /// [`InvArea::quot_up`] (the same values, the shifts not selected).
    ///
    /// Measured and not kept (exact QEMU counts, bunny-gouraud raster
    /// thumbv7em, the kernel-fit bit in): the depth plane's quotients in
    /// their exact 64-bit form `⌊(n·m + 2^(32−u)) / 2^(33−u)⌋` (one
    /// `SMULL`, the rounding and the shift; no `n << u` overflow flags),
    /// the range test on the high words: 1 567 929 -> 1 562 561 alone,
    /// but with the band list's stream 1 573 620 -> 1 579 895 (and a
    /// gradient of exactly `-2^24` then admitted where the general set-up
    /// declines it); the level plane the same way 1 608 227 (64-bit
    /// shift) and 1 614 182 (halved 32-bit form).
    #[inline(always)]
    fn plane_fields<const UP: bool, const SHORT: bool>(
        &self,
        f: [i32; 3],
        v0: i32,
        sh: u32,
        origin: bool,
    ) -> (i32, i32, i32, bool) {
        let [dx1, dy1, dx2, dy2] = self.d;
        let (f1, f2) = (f[1].wrapping_sub(f[0]), f[2].wrapping_sub(f[0]));
        let nx = f1.wrapping_mul(dy2).wrapping_sub(f2.wrapping_mul(dy1));
        let ny = f2.wrapping_mul(dx1).wrapping_sub(f1.wrapping_mul(dx2));
        // `k <= sh` by the caller's bound: the shifts known per triangle.
        let (gx, gy, ok) = if UP {
            let u = sh.wrapping_sub(self.k);
            // Both numerators in `-2^16..2^16` (and `u <= 14`): two
            // products each.
            let short =
                SHORT && SHORT_QUOTIENTS && ((nx ^ (nx >> 31)) | (ny ^ (ny >> 31))) < 1 << 16;
            if short {
                let q = (self.inv.quot_up_short(nx, u), self.inv.quot_up_short(ny, u));
                (q.0, q.1, true)
            } else {
                let ((gx, okx), (gy, oky)) = (self.inv.quot_up(nx, u), self.inv.quot_up(ny, u));
                (gx, gy, okx & oky)
            }
        } else {
            let (gx, gy) = (
                self.inv.quot_scaled(nx, self.k, sh),
                self.inv.quot_scaled(ny, self.k, sh),
            );
            (
                gx.unwrap_or(0),
                gy.unwrap_or(0),
                gx.is_some() & gy.is_some(),
            )
        };
        let o = if !origin {
            0
        } else if SHORT_NUMERATORS {
            self.origin_short(gx, gy)
        } else {
            let h = 1i64 << (self.s - 1);
            ((wide(gx, self.o[0]) + wide(gy, self.o[1]) + h) >> self.s) as i32
        };
        (gx, gy, v0.wrapping_add(o), ok)
    }
}

/// `true` when every triangle [`draw_small`] admits in a band of rows
/// `y0..until` of a window `width` columns wide (at `s` subpixel bits,
/// `S = 2^s`, `h = S/2`) has its offsets `h - x0`, `h - y0'` of pixel (0,
/// 0)'s centre from vertex 0 (`x0`, `y0'`) below `2^15` in magnitude, the
/// factors [`wide`] asks: decided per band, not per triangle. With `y0`,
/// `until`, `width` in `0..W` for `W = 2^(15 - s)`: the kernel's tests
/// leave `0 <= x0 <= width·S` and `(y0 - 1)·S + h < y0' <= (until -
/// 1)·S + h` (no `i32` wraps there for such bands), so `h - x0` lies in
/// `[h - (W - 1)·S, h]` and `h - y0'` in `[-(W - 2)·S, S)`, both within
/// `(-2^15, 2^15)`. A band outside these (wider than 2047 columns, or
/// rows past 2047, at 4 subpixel bits) sends its triangles to the general
/// path (the same pixels).
#[inline(always)]
fn offsets_near(s: u32, y0: i32, until: i32, width: i32) -> bool {
    ((y0 | until | width) as u32) < (1u32 << 15) >> s
}

/// [`Grad::origin_short`] for `s` subpixel bits and the offsets `o`.
#[inline(always)]
fn origin_short_at(s: u32, o: [i32; 2], gx: i32, gy: i32) -> i32 {
    let [ox, oy] = o;
    let a = (gx >> 15)
        .wrapping_mul(ox)
        .wrapping_add((gy >> 15).wrapping_mul(oy));
    let b = (gx & 0x7fff)
        .wrapping_mul(ox)
        .wrapping_add((gy & 0x7fff).wrapping_mul(oy))
        .wrapping_add(1 << (s - 1));
    (a << (15 - s)).wrapping_add(b >> s)
}

/// [`draw_small`] takes [`Grad::plane_fields`] for packed values: on
/// ARMv7-M (bunny-gouraud raster thumbv7em 2 019 909 -> 1 954 376), in
/// test builds, and on ARMv6-M since the kernel takes the packed words
/// (the fields without unpacking; thumbv6m 2 690 337 -> 2 665 621; with
/// the unpacked values it cost more than it saved there, 3 005 292 ->
/// 3 118 241); not on the 64-bit hosts (callgrind,
/// `examples/bunny_frame.rs`: 2 840 474 -> 2 974 717).
const PACKED_FIELDS: bool = cfg!(target_arch = "arm") || cfg!(test);

/// On ARMv6-M [`draw_small`] takes [`Grad::plane_fields`] for packed
/// values, where the shifts are not known per triangle (`k > 8`), only
/// where [`Grad::plane_short`] refuses them, out of line
/// ([`Grad::plane_fields_cold`]): bunny-gouraud raster thumbv6m 3 005 292
/// -> 2 980 115 (inlined there: 3 016 457).
const FIELDS_RESCUE: bool = NO_LONG_MUL;

/// On ARMv6-M [`draw_small`] takes the depth plane by [`Grad::plane_diff`]
/// (64-bit numerators from [`wide`]'s two `MULS`, out of line:
/// [`Grad::plane_wide_cold`]) where [`Grad::plane_short`] refuses it and
/// the value is the depth alone (flat objects, `N = 0`: their depths
/// are not packed, and their differences reach its bound), rather than
/// handing the triangle to the general path; also in test builds, which
/// check it against the general path.
const WIDE_RESCUE: bool = NO_LONG_MUL || cfg!(test);

/// [`draw_small`] takes [`Grad::plane_short`]: on ARMv6-M, and in test
/// builds (on ARMv7-M the 64-bit numerators cost less than the bound's
/// test).
const SHORT_NUMERATORS: bool = NO_LONG_MUL || cfg!(test);

/// [`Grad::plane_fields`] takes [`InvArea::quot_up_short`] (two `MULS` a
/// gradient instead of four) where both numerators of a plane lie in
/// `-2^16..2^16` (with `SHORT`: the depth plane of [`draw_small`]): on
/// ARMv6-M, and in test builds, which check it (on ARMv7-M a gradient is
/// one `SMMUL`). Exact QEMU counts, bunny-gouraud raster thumbv6m
/// 2 580 811 -> 2 556 014 for `i16` numerators (81% of the bunny's depth
/// planes), later 2 520 390 -> 2 509 937 for the wider range; for the
/// level plane as well 2 618 573 (`i16`; its numerators mostly wider, the
/// compiler computed both forms and selected), 2 594 161 (the wider
/// range), with the level's long form out of line 2 583 084 (called for
/// nearly every triangle). Also measured and
/// not kept on ARMv6-M: both overflow flags of [`InvArea::quot_up`] in one
/// test, `(|nx ^ nx >> 31| | |ny ^ ny >> 31|) >> (31 - u) == 0`
/// (2 520 390 -> 2 525 721; again later, 2 394 260 -> 2 397 232; with
/// the bound `>> (29 - u)`, which keeps the level's gradients within
/// `2^27`, and [`levels_in_range`]'s gradient test then left out for
/// those planes, 2 391 960 -> 2 391 896: not kept).
const SHORT_QUOTIENTS: bool = NO_LONG_MUL || cfg!(test);

/// `a - b` and whether it wraps; without `WRAPS` (a difference known not
/// to wrap) the wrapping difference and `false`.
#[inline(always)]
fn sub_wrap<const WRAPS: bool>(a: i32, b: i32) -> (i32, bool) {
    if WRAPS {
        a.overflowing_sub(b)
    } else {
        (a.wrapping_sub(b), false)
    }
}

/// `true` when `v` fits an `i32`.
#[inline(always)]
fn fits(v: i64) -> bool {
    v as i32 as i64 == v
}

/// `a · b` in 64 bits for `|b| < 2^15` (a coordinate offset of
/// [`setup32`]): one `SMULL` on ARMv7-M and the hosts, two `MULS` on
/// ARMv6-M ([`mul_i32_i16_soft`], exact for such `b`; also in test builds,
/// so that the host tests check the ARMv6-M path).
#[inline(always)]
fn wide(a: i32, b: i32) -> i64 {
    if SHORT_PRODUCTS {
        mul_i32_i16_soft(a, b)
    } else {
        a as i64 * b as i64
    }
}

/// [`setup32`] takes the ARMv6-M products ([`wide`]): on ARMv6-M, and in
/// test builds.
const SHORT_PRODUCTS: bool = NO_LONG_MUL || cfg!(test);

/// The 32-bit setup: `Err(())` when a bound below fails (the caller then
/// takes [`setup`]), else exactly [`setup`]'s result. The bounds:
///
/// - the subpixel offsets of vertices 1 and 2 from vertex 0 lie below
///   `2^bxy` in magnitude with `bxy <= 15` (triangles under 2048 pixels a
///   side at 4 subpixel bits): the doubled area `dx1·dy2 - dx2·dy1` is
///   below `2·2^30` in magnitude, an `i32`;
/// - for each value, its differences `v1 - v0`, `v2 - v0` do not wrap and
///   lie below `2^bv` with `bv + bxy <= 30`: each product of a gradient
///   numerator `d1·dy2 - d2·dy1`, `d2·dx1 - d1·dx2` is below 2^30, the
///   numerator below 2^31, an exact `i32`, so [`InvArea::quot`] takes no
///   normalisation;
/// - the reciprocal takes [`InvArea::quot`]'s high-word case
///   ([`InvArea::high_shift`]), and a numerator's quotient is
///   [`InvArea::quot_high`]'s (within ±2^30);
/// - the row origin `a0 + ((gx·(h - x0) + gy·(h - y0) + h) >> s)` (`h =
///   S/2`) is `origin64`'s sum of the same `i64`s (the gradients are
///   `i32`s, sign-extended), formed by `SMULL`/`SMLAL`; on ARMv6-M (and in
///   test builds) by [`wide`]'s two `MULS` each, which asks `|h - x0|`,
///   `|h - y0| < 2^15` (vertex 0 within 2047 pixels of the origin at 4
///   subpixel bits) and the coordinate offsets below `2^15` (above);
/// - the reciprocal on ARMv6-M by [`InvArea::new`] (a table and Newton
///   steps, no division call), elsewhere by [`InvArea::new_small`] where
///   it applies (two `UDIV`): the same value.
///
/// Tested equal to [`setup`] on random and extreme triangles.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn setup32<const N: usize, const V: usize>(
    a: &Vertex<i32, N>,
    b: &Vertex<i32, N>,
    c: &Vertex<i32, N>,
    sub: SubpixelBits,
    j0: i32,
    width: i32,
    w: &mut Walk,
    vals: &mut [[i32; 3]; V],
) -> Result<bool, ()> {
    let [dx1, dy1, dx2, dy2] = [b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y];
    let mxy = dx1.unsigned_abs() | dy1.unsigned_abs() | dx2.unsigned_abs() | dy2.unsigned_abs();
    let bxy = 32 - mxy.leading_zeros();
    if bxy > 15 {
        return Err(());
    }
    let area2 = dx1 * dy2 - dx2 * dy1;
    if area2 == 0 {
        return Ok(false);
    }
    let Some([js, j_mid, j_bot]) = row_range([a.y, b.y, c.y], sub, j0) else {
        return Ok(false);
    };
    walk_edges(
        w,
        &[[a.x, a.y], [b.x, b.y], [c.x, c.y]],
        [js, j_mid, j_bot],
        area2,
        width,
        sub,
    );
    let inv = InvArea::new_fast(area2);
    let s = sub.get();
    let k = inv.high_shift(s).ok_or(())?;
    let h = 1i32 << (s - 1);
    // The offsets of pixel (0, 0)'s centre from vertex 0 are factors of
    // [`wide`]: below 2^15 in magnitude (vertex 0 within 2047 pixels of
    // the origin at 4 subpixel bits).
    if SHORT_PRODUCTS && ((h - a.x).unsigned_abs() | (h - a.y).unsigned_abs()) >= 1 << 15 {
        return Err(());
    }
    let g = Grad {
        d: [dx1, dy1, dx2, dy2],
        inv,
        k,
        s,
        o: [h - a.x, h - a.y],
    };
    let (gx, gy, z0, okz) = g.plane(a.z, b.z, c.z);
    let z16 = Depth16::plane_in_range32([a.z, b.z, c.z], gx, gy);
    if let Some(v) = vals.get_mut(0) {
        *v = [z0, gx, gy];
    }
    let mut ok = okz;
    for k in 0..N {
        let (gx, gy, o, oka) = g.plane(a.attrs[k], b.attrs[k], c.attrs[k]);
        ok &= oka;
        if let Some(v) = vals.get_mut(k + 1) {
            *v = [o, gx, gy];
        }
    }
    if !ok {
        return Err(());
    }
    w.z16 = z16;
    Ok(true)
}

/// The walk of a sorted triangle (vertices `p[0..3]`, `x`, `y` in
/// subpixels; its doubled area `area2 != 0`) from row `js`: [`setup32`]'s
/// edges, rows and flags (but [`Walk::z16`]), computed before the value
/// planes (out of line it cost thumbv7em bunny-gouraud raster 2.328 ->
/// 2.379 M).
#[inline(always)]
fn walk_edges(
    w: &mut Walk,
    p: &[[i32; 2]; 3],
    rows: [i32; 3],
    area2: i32,
    width: i32,
    sub: SubpixelBits,
) {
    let [[ax, ay], [bx, by], [cx, cy]] = *p;
    let [js, j_mid, j_bot] = rows;
    // The edges from their selected end points (selecting the four
    // coordinates costs less than selecting two walkers of five fields).
    let long_left = area2 > 0;
    let lowp = (bx, by, j_mid.max(js));
    let (sx0, sy0, sj) = if js < j_mid { (ax, ay, js) } else { lowp };
    let (sx1, sy1) = if js < j_mid { (bx, by) } else { (cx, cy) };
    let (lp, rp) = if long_left {
        ((ax, ay, cx, cy, js), (sx0, sy0, sx1, sy1, sj))
    } else {
        ((sx0, sy0, sx1, sy1, sj), (ax, ay, cx, cy, js))
    };
    w.left = Edge::new_first(lp.0, lp.1, lp.2, lp.3, lp.4, sub);
    w.right = Edge::new_first(rp.0, rp.1, rp.2, rp.3, rp.4, sub);
    w.low = if j_mid < j_bot {
        Edge::new_first(bx, by, cx, cy, lowp.2, sub)
    } else {
        Edge::EMPTY
    };
    let sc = sub.scale();
    let (xmin, xmax) = (ax.min(bx).min(cx), ax.max(bx).max(cx));
    w.inside = xmin >= 0 && xmax <= width.saturating_mul(sc);
    w.j = js;
    w.mid = j_mid;
    w.end = j_bot;
    w.ia = ax >> sub.get();
    w.ja = ay >> sub.get();
    w.long_left = long_left;
}

/// `true` when every pixel a triangle draws from the planes of
/// [`draw_small`] has its level attribute (fixed, `2^16` a level) rounded
/// into `0..=255`, from the vertex values `l` and the attribute's
/// gradients `gx`, `gy` (per pixel). A pixel centre drawn lies in the
/// closed triangle, within `2^15` subpixels of vertex 0 on each axis
/// (the kernel's bound on the offsets), where the exact plane lies between
/// the least and the greatest vertex value; the kernel's value there is
/// `v0 + (gx·dx + gy·dy + S/2) / S` floored (`dx`, `dy` the centre's
/// subpixel offsets from vertex 0, `S = 2^s`, `s >= 1`), so it differs from
/// the exact plane by less than `(|gx - Gx|·|dx| + |gy - Gy|·|dy|) / S +
/// 1`;
/// [`InvArea`]'s gradients are within `½ + |G|·2^-28` of the exact `G`,
/// below 2 for `g` in `[-2^28, 2^28)` (`|g - G| <= 1.5 / (1 - 2^-28)`):
/// the error stays below `2·2·2^15 / S + 1 = 2^(17 - s) + 1`, below `m =
/// 2^(18 - s)` (`s` in `1..=8`). Hence with
/// every vertex value in `[-2^15 + m, 2^24 - 2^15 - m)` (at 4 subpixel
/// bits `m = 2^14`, a quarter of a level: levels 0 and 255 pass) the
/// value lies in `[-2^15, 2^24 - 2^15)`: rounded (`+ 2^15`, then `>> 16`)
/// into `0..=255`, with no `i32` wrap on the way (the kernel's wrapping
/// sums equal the true ones there). Conservative: `false` only sends the
/// triangle to the clamping path. The gradients' range tested on
/// `g ^ (g >> 31)` (`g` or `-g - 1`) rather than on magnitudes: two
/// instructions a triangle less, bunny-gouraud raster thumbv6m 2 397 232
/// to 2 394 260 (thumbv7em unchanged).
#[inline(always)]
fn levels_in_range(l: [i32; 3], gx: i32, gy: i32, s: u32) -> bool {
    let m = 1i32 << (18 - s);
    let (lo_lim, hi_lim) = (m - (1 << 15), (1 << 24) - (1 << 15) - m);
    let (lo, hi) = (l[0].min(l[1]).min(l[2]), l[0].max(l[1]).max(l[2]));
    (lo >= lo_lim) & (hi < hi_lim) & (((gx ^ (gx >> 31)) | (gy ^ (gy >> 31))) >> 28 == 0)
}

/// The small-triangle kernel: a triangle set up in 32 bits and walked
/// from its first row without clipping or depth clamps; a triangle that
/// continues below the band is handed back as the [`Walk`] and values of
/// [`setup_fast`] after [`Walk::rows_fused`] down to the band's end.
///
/// `v` holds the vertices sorted by `y` (subpixels, any `i32`: a
/// triangle the kernel takes lies within the window's columns, its first
/// row in the band, inside the module's limits). The kernel applies when
/// every condition below holds, decided before a pixel is written; `None`
/// otherwise (nothing written, the caller takes [`setup_fast`] and
/// [`Walk::rows_fused`]):
///
/// - a depth plane is present, the triangle's first row lies within the
///   band (`y0 <= first row < until`) and its last vertex within the
///   module's limits (`c.y <= coord_limit`);
/// - its columns lie within `0..=width` ([`Walk::inside`]): no clipping;
/// - [`setup32`]'s bounds (coordinate offsets below `2^15`, the
///   reciprocal's high-word case, no wrapping numerator); the offsets'
///   bound is taken as the column extent and the height below `2^15`
///   (which implies it), and on ARMv6-M (and in test builds) vertex 0's
///   offsets from pixel (0, 0) from the band's bounds ([`offsets_near`]);
/// - every depth converts to 16 bits without a clamp
///   ([`DepthFormat::plane_in_range`]);
/// - on ARMv6-M (and in test builds), the gradient numerators in 32 bits:
///   each value's differences below `2^(30 - bxy)` for a column extent
///   and height below `2^bxy` ([`Grad::plane_short`]);
/// - with `packed` (`N = 1`, the caller's promise that each vertex holds
///   its packed grey word, [`crate::num::Profile::PACKED_GREY`], as its
///   depth and as its value: the depth field `f` in the high half, the
///   level field in the low half, the values [`grey_z`] `f·2^14 + 2^13`
///   and [`grey_l`] taken from them where they are used, the depths'
///   range tested on the words), for offsets below `2^14` (and,
///   on ARMv7-M and in test builds, the reciprocal's shift `k <= 8`:
///   doubled areas below `2^15` subpixels² at 4 subpixel bits; both shifts of
///   [`InvArea::quot_up`] known per triangle): the
///   planes from the fields ([`Grad::plane_fields`], numerators in 32 bits
///   for any depth difference, the gradients below `2^29`) instead, on
///   ARMv7-M and in test builds ([`PACKED_FIELDS`]), and on ARMv6-M where
///   [`Grad::plane_short`] refuses the values ([`FIELDS_RESCUE`]).
///
/// Then it writes exactly the pixels of [`setup_fast`] and
/// [`Walk::rows_fused`] (the same edges from their first rows, the same
/// gradients and values, the same span stage) and returns their count
/// (`Some((0, false))` for a triangle without area or rows) and whether
/// the triangle continues below the band: then `carry` and `vals` hold
/// the very walk and values (entries `0..=N`) [`setup_fast`] and
/// [`Walk::rows_fused`] leave (but [`carry_over`]'s unused edge). Tested against the general path on random
/// and extreme triangles, pixel for pixel and walk for walk.
///
/// Inlined, set-up and rows in one piece. Measured on the Cortex-M4
/// (exact QEMU counts, bunny-gouraud raster 1 833 849 inlined): the
/// set-up split from the rows as an out-of-line stage writing a
/// `#[repr(C)]` record (one store a field, loaded by the rows) took about
/// 470 instructions a triangle by itself, as many as inline (the stage
/// alone keeps more than 14 values live: the three vertices, the offsets,
/// the reciprocal; and the level plane's high products left `SMMUL` for
/// `UMULL` and two `MLA`), and the rows reading the record cost more than
/// reading registers: 2 356 317 with the record made per triangle (a
/// `memcpy` each), 2 194 324 with it made once by the caller, 2 184 271
/// with the rows copying it out first, 2 162 038 with the rows out of
/// line too (their prologue copies the record into their frame, 75
/// instructions a triangle, and the swap at the lower half selects five
/// fields through the stack, 43). The kernel as it is out of line
/// (`draw_small`): 2 065 666; with the planes of one form computed in
/// one piece, inlined 1 857 615, out of line 1 996 973; out of line with
/// the reciprocal's factor through `core::hint::black_box` in
/// [`InvArea::quot_high`] (the products back to `SMMUL`) 2 033 963: the
/// call costs about 72 instructions a triangle (the vertices stored for
/// it, the band memory, the frame), the rows' start 29, each row 6.
///
/// Kept since (bunny-gouraud raster thumbv7em 1 749 614 -> 1 642 120,
/// thumbv6m 2 734 554 -> 2 665 621, steps in the doc comments where they
/// are): the packed grey words instead of six unpacked values
/// (`fetch_fixed` of `render::active`), the level's gradients as quotient and
/// flag ([`InvArea::quot_up`]), the edges' biased unsigned division
/// ([`Edge::at_first_row_short`]), the values by one offset, the columns'
/// test, the reciprocal halved in 32 bits, the mesh looked up once per
/// object, the field planes on ARMv6-M too ([`PACKED_FIELDS`]). Measured
/// and not kept: the row
/// origins from vertex 0's pixel in 32 bits (`v0 + ⌊(gx·ox + gy·oy + h) /
/// S⌋ - gx·i - gy·j` with `|ox|, |oy| <= S/2`, exact for gradients below
/// `2^(30 - s)`; thumbv7em 1 749 614 -> 1 919 424: the planes' gradients
/// alone, without their origins, made the compiler compute the field
/// and the general gradients both and select; with the general ones out
/// of line 1 848 801, with `packed` a constant 1 788 167; the 64-bit
/// origin is two `SMLAL` on ARMv7-M, as cheap; thumbv6m bunny-gouraud
/// −11 K but bunny-flat +26 K; later on ARMv6-M alone, for the field
/// planes, 2 665 621 -> 2 673 795); one overflow flag for both field
/// quotients of a plane (`(nx ^ nx >> 31 | ny ^ ny >> 31) >> (31 - u)`:
/// 1 651 052 -> 1 653 513, and 1 646 369 -> 1 648 830 later); the left
/// and right edges' end points selected before their set-up instead of
/// the edges (1 651 052 -> 1 683 848, thumbv6m bunny-flat +54 K); the
/// first row tested against the band in rows instead of the first
/// vertex in subpixels (1 658 600 -> 1 715 025); the three positions
/// through one bounds test of the greatest index (1 646 369 ->
/// 1 664 927, bunny-flat +25 K / +39 K on thumbv7em / thumbv6m).
///
/// Measured from 1 642 170 (bunny-flat 1 473 507; thumbv6m 2 580 811,
/// 2 197 727) and not kept, the rows in two phases (the edges walked
/// first, each row's `[x0, x1)` stored in a 16-row array the band owns,
/// then the rows drawn from it; a triangle with more rows in the band
/// declined): inline, 1 794 046 (per 16-row chunk), 1 804 368 (one
/// chunk; the span start `v + sy·j + sx·x0` instead of stepped rows
/// 1 798 786, thumbv6m 2 676 292): the edge walks spilled and unrolled
/// by four. The edges packed in three words (`x·2^20 + e`, `q·2^20 -
/// r`, `2^20 + d`: a step is an add, a test of bit 19 and a conditional
/// add, exact for `d <= 2^19` and columns below `2^11`) and one loop per
/// side of the long edge: the first phase at 15 a row, 1 749 257
/// (thumbv6m 2 702 250); with the second phase out of line and its
/// counters in memory the compiler cannot follow, the pixel loop at 14
/// (5 + 9 a passing pixel, from 17), the rows 10 and the spans 30, but
/// 1 774 000: the call 51 a triangle, the set-up about 70 more. The
/// packed edges in the one-phase loops: rows 23 instead of 30, the set-up
/// +61 a triangle, 1 693 692 (bunny-flat 1 518 614, thumbv6m 2 612 953,
/// 2 232 799); their quotients through memory 1 687 204 (bunny-flat
/// 1 536 155). The whole rows out of line (both phases): 1 940 101.
/// Here, [`small_loop`]'s steps copied to values before its loop:
/// 1 689 840 (bunny-flat 1 507 128; thumbv6m unchanged). Also from
/// 1 642 170, each alone: [`small_loop`] on ARMv7-M by one index into
/// both buffers, 1 741 791 (still two pointers, the pixel count then in
/// memory); the failed tests counted apart with values, 1 660 718; the
/// edges stepped before the span instead of after it, 1 691 872; the
/// short edges' division checked (`checked_div`) instead of `dy.max(1)`,
/// 1 664 741; their first column and error term without branches (`k =
/// [np > 0] + [np > d]`), 1 655 745. The kernel's registers are taken
/// across its rows (both edges, the row, the offset, the count), so each
/// of these moved the spills more than it saved.
///
/// Measured again from 1 631 491 (thumbv6m 2 370 412, host frame
/// 2 161 582 by callgrind) and not kept: the set-up filling a state of
/// 21 words (edges, lower edge, values at the first row, row offsets,
/// the side that swaps) for an `#[inline(never)]` row kernel walking both
/// halves, 1 819 659 (thumbv6m 2 549 134, host 2 383 688); its edges
/// packed in three words, 1 816 217; the same kernel inlined, 1 709 304;
/// the packed edges in the present inline rows, 1 673 193 (thumbv6m
/// 2 425 488). Out of line the state crosses memory twice (about 70 to
/// 120 instructions a triangle: four arguments travel in registers) and
/// the rows still hold about 18 values against 12 free registers (25 a
/// row, 13 a passing pixel, from 30 and 14 inline).
///
/// Measured from 1 615 109 (thumbv6m 2 369 374, host 2 154 477) and not
/// kept: the fresh triangles that end in their band with a bounding box
/// under 16 pixels (1 099 of the bunny's 1 146, ~4.7 rows and ~10 pixels
/// each) rasterised by edge functions instead of the walk, with the same
/// pixels (tested on 30 000 random and extreme triangles): three edge
/// values stepped over the box, 2 200 540 (thumbv6m 2 924 623; ~38 box
/// steps a triangle at ~10 instructions); the edges by side in 16-bit
/// lanes and each row's ends walked from the previous row's, 1 760 039;
/// from the top vertex's column, 1 744 737 (thumbv6m 2 456 352, host
/// 2 368 355); box bounds of 6 and 3 pixels, 1 669 797 and 1 638 758.
/// Its edge set-up is cheaper (~80 a triangle against ~135), but finding
/// a row's ends costs ~60 a row against the walk's ~20.
///
/// Measured from 1 615 109 (bunny-gouraud raster thumbv7em; thumbv6m
/// untouched) and not kept: the rows by pixel index (an edge steps its
/// index in the band by `q + width`, no row offset), the edges'
/// invariants and the values' steps in one block read through an opaque
/// address and reloaded every row, the span's values `c + syw·k + sx·p`:
/// rows 17 instructions instead of 28, spans 28 instead of 29, pixels 16
/// instead of 16.5, but about 75 more a triangle (the block's ~15 words
/// stored from spill slots, the start values per half): 1 646 504 at
/// best (first 1 813 109; the block built after the edges 1 688 395;
/// both halves in one loop 1 827 227; the slices outside the block
/// 1 658 849; the resume kernel through it 1 650 121). Even at that
/// form's floor (rows 12, spans 18, pixels 13: ~335 K for the fresh rows
/// against ~560 K) the block's cost a triangle repays less than it takes.
/// Its dead branch alone, kept off by a `const`, moved bunny-gouraud
/// +2 081 and bunny-flat +4 683: it is not in the tree.
///
/// Where the bunny's raster goes (thumbv7em, 1 573 608, exact QEMU
/// counts): with the fresh triangles' rows cut off after their set-up
/// (the set-up's results kept alive, nothing carried to the next band)
/// the raster measured 802 649, the band loop with the set-ups 713 398
/// of it, about 476 a triangle; the rows, spans and pixels with the
/// resumed triangles take the other 771 K. In the set-up's straight
/// line (377 instructions a triangle) 116 are loads and stores of the
/// stack, 33 branches and 175 arithmetic. The thumbv7em target keeps
/// `r7` as its frame pointer (its target specification); built without
/// it (a custom target, nightly, measured against the same build with
/// it) the raster took 1 585 284 -> 1 569 261 and bunny-flat 1 393 548
/// -> 1 402 174: one register more is worth about 1 %.
///
/// With `LEVELS`, for one grey level (`N = 1`; other `N` as
/// without `LEVELS`; fixed, `2^16` a level:
/// [`crate::raster::GouraudMono`]'s attribute) whose every pixel's rounded
/// level lies in `0..=255`, decided per triangle ([`levels_in_range`]):
/// `color` then receives the level in the form of
/// [`crate::raster::GouraudMono`]'s [`Shader::in_range_values`](super::Shader::in_range_values)
/// (`(v + 2^15) << 8`, the rounded level in the top 8 bits, stepped by
/// `s << 8`), so that the pixel needs no clamp (its
/// [`Shader::shade_raw_in_range`](super::Shader::shade_raw_in_range)).
/// `None` as well for a triangle that fails the test (the caller's
/// general path then clamps). The same pixels, walk and values as
/// without `LEVELS` otherwise (the walk and values left for the next band
/// in the original form). Tested against the general path.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn draw_small<
    const N: usize,
    const V: usize,
    R: Copy,
    D: DepthFormat,
    const LEVELS: bool,
>(
    v: &[Vertex<i32, N>; 3],
    sub: SubpixelBits,
    until: i32,
    mem: &mut BandMem<'_, '_, R, D::Raw>,
    carry: &mut Walk,
    vals: &mut [[i32; 3]; V],
    packed: bool,
    fit: bool,
    color: impl Fn(&[i32; N]) -> R,
) -> Option<(u32, bool)> {
    // Without a depth plane the general path, decided first.
    let z = mem.z.as_deref_mut()?;
    let [a, b, c] = v;
    // With `packed` each vertex holds its packed grey word as its depth
    // and its value: the fields (`f`) and values (`val`) taken from it
    // where they are used (three live words rather than six values).
    let zf = |v: &Vertex<i32, N>| (v.z as u32 >> 16) as i32;
    let zval = |v: &Vertex<i32, N>| if packed { grey_z(v.z) } else { v.z };
    let lf = |v: &Vertex<i32, N>, k: usize| v.attrs[k] & 0xffff;
    let lval = |v: &Vertex<i32, N>, k: usize| {
        if packed {
            grey_l(v.attrs[k])
        } else {
            v.attrs[k]
        }
    };
    let (y0, width) = (mem.y0, mem.width);
    let (s, sc) = (sub.get(), sub.scale());
    let h = 1i32 << (s - 1);
    // `y0 <= first_row(a.y) < until` (`first_row(y) = ⌈(y - h) / S⌉`),
    // tested on the coordinates (the band's tests, kept with `fit`: a
    // triangle set up afresh below its first band fails them).
    if (a.y <= (y0 - 1) * sc + h) || (a.y > (until - 1) * sc + h) {
        return None;
    }
    let [dx1, dy1, dx2, dy2] = [b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y];
    // Every offset below 2^15 in magnitude, through the column extent and
    // the height (`0 <= dy1 <= dy2`, columns within `xmin..=xmax`): slightly
    // stricter than the offsets one by one, cheaper. Its bit length sets
    // `lim` below. On ARMv6-M the offsets one by one before (their
    // magnitudes, a tighter `lim`): with the extent, exact QEMU counts,
    // bunny-gouraud raster thumbv6m 2 415 422 -> 2 397 232, bunny-flat
    // 2 085 892 -> 2 063 406 (after [`offsets_near`]). Computed only where
    // used (with `fit`, only by the planes' `lim`).
    let mxy = || {
        let (xmin, xmax) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
        (xmax - xmin) as u32 | dy2 as u32
    };
    // ARMv6-M: vertex 0's offsets from pixel (0, 0) bounded per band
    // ([`offsets_near`]) instead of per triangle (their magnitudes):
    // bunny-gouraud raster thumbv6m 2 434 737 -> 2 415 422, bunny-flat
    // 2 087 542 -> 2 085 892. (Tested as `a.x < 2^15 + h` from `a.x >= 0`
    // and `a.y - h + 2^15 - 1` in `0..2^16 - 1`: bunny-gouraud raster
    // thumbv6m 2 535 961 -> 2 541 021, bunny-flat 2 180 230 -> 2 195 547;
    // not kept.) Its failure as bit 15 of the extent's word, one test for
    // both: bunny-gouraud 2 394 260 -> 2 391 960, bunny-flat 2 063 406 ->
    // 2 063 777.
    let far = u32::from(SHORT_PRODUCTS && !offsets_near(s, y0, until, width)) << 15;
    let (j_top, j_bot) = (first_row(a.y, sub), first_row(c.y, sub));
    let area2 = dx1 * dy2 - dx2 * dy1;
    // `fit`: prepare proved the triangle's object within the screen's box
    // with an area and a row for each triangle (`PreparedObject::kernel_fit`
    // of `render`, one bit of the object: no RAM per triangle; the
    // contract is [`crate::raster::kernel_fit_holds`]), so that the
    // frame-constant tests below hold: kept as assertions. Exact QEMU
    // counts (fwrun), raster: bunny-gouraud thumbv7em 1 615 109 ->
    // 1 578 408, thumbv6m 2 369 374 -> 2 359 238; bunny-flat thumbv7em
    // 1 456 821 -> 1 422 709, thumbv6m 2 055 671 -> 2 032 058. The empty
    // test is kept for triangles with values (`N > 0`): dropped there too,
    // bunny-gouraud 1 586 706 and 2 363 200; kept for flat ones too,
    // bunny-flat 1 426 339 and 2 056 440; dropped for every `N` after the
    // depths' test below, 1 567 929 -> 1 569 490 (thumbv6m 2 346 118 ->
    // 2 339 930). Measured and not kept: the kernel instantiated once per
    // value of `fit` (a constant in each), 1 758 548; the band's two tests
    // as one unsigned range, 1 567 929 -> 1 578 323 (thumbv6m 2 334 441,
    // bunny-flat 1 404 326 and 2 017 386).
    if fit {
        debug_assert!(c.y <= sub.coord_limit() && a.x.min(b.x).min(c.x) >= 0);
        debug_assert!(((a.x.max(b.x).max(c.x) + sc - 1) >> s) <= width);
        debug_assert!(mxy() < 1 << 14 && area2 != 0 && j_top < j_bot);
        if far != 0 {
            return None;
        }
    } else {
        // `c.y` within the limits, and the columns in `0..=width·S`, as
        // `⌈xmax / S⌉ <= width` (for `xmax >= 0` the unsigned sum does not
        // wrap; a negative `xmax` fails `xmin >= 0`): every coordinate
        // then lies within the module's limits, and nothing below wraps.
        // The columns' test instead of `xmax <= width·S` saturated (a
        // select between two values kept on the stack at every triangle):
        // exact QEMU counts, bunny-gouraud raster thumbv7em 1 658 600 ->
        // 1 651 052, thumbv6m 2 717 413 -> 2 694 098; bunny-flat thumbv7em
        // 1 510 721 -> 1 506 174, thumbv6m 2 281 745 -> 2 257 964. The
        // rows' test on the first row (`y0 <= j_top < until`, `j_top`
        // wrapping) as well cost thumbv7em bunny-gouraud 1 715 025.
        let (xmin, xmax) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
        let cols = ((xmax as u32).wrapping_add(sc as u32 - 1) >> s) as i32;
        if (c.y > sub.coord_limit()) || (xmin < 0) || (cols > width) {
            return None;
        }
        if (mxy() | far) >= 1 << 15 {
            return None;
        }
    }
    if (!fit || N > 0) && (area2 == 0 || j_top >= j_bot) {
        return Some((0, false));
    }
    // The kernel needs every depth in range (the vertex part of `z16`,
    // below): tested first, the depth differences then do not wrap. With
    // `fit` prepare tested every depth of the object where it projected
    // it (the kernel's test, kept as an assertion): exact QEMU counts,
    // raster bunny-gouraud thumbv7em 1 578 408 -> 1 567 929, thumbv6m
    // 2 359 238 -> 2 346 118, bunny-flat 1 422 709 -> 1 398 776, 2 032 058
    // -> 2 005 847 (geometry +1 461 and +8 192 on the Cortex-M4, +9 055
    // and +8 957 on the Cortex-M0). Written as `(fit || zv) & ...`
    // rather than skipped in a branch of its own it cost raster 1 586 706
    // -> 1 595 475.
    debug_assert!(!fit || words_in_range([a.z, b.z, c.z]) || !packed);
    debug_assert!(!fit || Depth16::vertices_in_range([a.z, b.z, c.z]) || packed);
    if !fit {
        let zv = if packed {
            words_in_range([a.z, b.z, c.z])
        } else {
            Depth16::vertices_in_range([a.z, b.z, c.z])
        };
        if !zv {
            return None;
        }
    }
    if !D::plane_in_range(true) {
        return None;
    }
    let inv = InvArea::new_fast(area2);
    let k = inv.high_shift(s)?;
    let g = Grad {
        d: [dx1, dy1, dx2, dy2],
        inv,
        k,
        s,
        o: [h - a.x, h - a.y],
    };
    // 2^(30 - bxy) for coordinate offsets below 2^bxy (bxy <= 15): only
    // where the planes take [`Grad::plane_short`], computed once on the
    // depth's path (as a value hoisted above the field planes it cost
    // every triangle its leading zeros on ARMv6-M; exact QEMU counts,
    // bunny-gouraud raster thumbv6m 2 478 334 -> 2 473 748 as a closure
    // called on both paths, -> 2 455 763 computed once).
    let lim = || (1u32 << 30) >> (32 - clz32(mxy()));
    // Packed values by their 16-bit fields where the offsets allow it.
    let fields = packed & (fit || mxy() < 1 << 14);
    // With `k <= 8` (doubled areas below 2^15 subpixels² at 4 subpixel
    // bits) both fields' shifts `sh - k` are known per triangle.
    let pk = PACKED_FIELDS & fields & (k <= 8);
    // ARMv6-M: the fields, out of line, where the 32-bit numerators of the
    // values refuse them.
    let rescue = FIELDS_RESCUE & fields;
    // The bound computed on the depth's path and kept for the values'.
    let mut lim_v = 0;
    let (gx, gy, z0, mut ok) = if pk {
        g.plane_fields::<true, true>([zf(a), zf(b), zf(c)], zval(a), 14, true)
    } else {
        lim_v = lim();
        match g.plane_small::<false>(zval(a), zval(b), zval(c), lim_v) {
            p if !p.3 & rescue => g.fields_rescue([zf(a), zf(b), zf(c)], zval(a), 14),
            p if !p.3 & (WIDE_RESCUE && N == 0) => g.plane_wide_cold(zval(a), zval(b), zval(c)),
            p => p,
        }
    };
    let z16 = Depth16::gradients_in_range(gx, gy);
    ok &= D::plane_in_range(z16);
    // With `LEVELS` on ARMv6-M (and in test builds) the level plane's
    // full origin only for a triangle that continues below the band
    // ([`Grad::origin_low`] for the rows).
    let lazy = LEVELS && N == 1 && SHORT_NUMERATORS && pk;
    let mut row = Vals { z: z0, a: [0; N] };
    let mut sx = Vals { z: gx, a: [0; N] };
    let mut sy = Vals { z: gy, a: [0; N] };
    for k in 0..N {
        let (gx, gy, o, oka) = if pk {
            g.plane_fields::<true, false>([lf(a, k), lf(b, k), lf(c, k)], lval(a, k), 8, !lazy)
        } else {
            match g.plane_small::<true>(lval(a, k), lval(b, k), lval(c, k), lim_v) {
                p if !p.3 & rescue => {
                    let f = [lf(a, k), lf(b, k), lf(c, k)];
                    g.fields_rescue(f, lval(a, k), 8)
                }
                p => p,
            }
        };
        ok &= oka;
        row.a[k] = o;
        sx.a[k] = gx;
        sy.a[k] = gy;
    }
    // One grey level: every pixel's level in range, else the general path.
    let (mut tx, mut ty) = (sx, sy);
    let mut t0 = row;
    if LEVELS && N == 1 {
        let l = [lval(a, 0), lval(b, 0), lval(c, 0)];
        ok &= levels_in_range(l, sx.a[0], sy.a[0], s);
        // Only the level's low 24 bits are kept: on ARMv6-M (and in test
        // builds) from [`Grad::origin_low`] (`s <= 8`), the full origin
        // then used only by a triangle that continues below the band.
        let o = if SHORT_NUMERATORS {
            lval(a, 0).wrapping_add(g.origin_low(sx.a[0], sy.a[0]))
        } else {
            row.a[0]
        };
        t0.a[0] = o.wrapping_add(1 << 15) << 8;
        tx.a[0] = sx.a[0] << 8;
        ty.a[0] = sy.a[0] << 8;
    }
    if !ok {
        return None;
    }
    let (px, z) = same_len(mem.px, z);
    let j_mid = first_row(b.y, sub);
    // The lower short edge from its first row: swapped in at `j_mid`, or
    // carried to the next band (every triangle with a lower half needs it).
    let low = if j_mid < j_bot {
        Edge::at_first_row_short(b.x, b.y, c.x, c.y, sub)
    } else {
        Edge::EMPTY
    };
    let long = Edge::at_first_row_short(a.x, a.y, c.x, c.y, sub);
    let upper = j_top < j_mid;
    let short = if upper {
        Edge::at_first_row_short(a.x, a.y, b.x, b.y, sub)
    } else {
        low
    };
    let long_left = area2 > 0;
    let (mut l, mut r) = if long_left {
        (long, short)
    } else {
        (short, long)
    };
    let anchor = [a.x >> s, a.y >> s];
    let mut fail_count = 0u32;
    let mut rows = small_rows_at!(t0, ty, j_top, y0, width, fail_count);
    let (sx0, sy0) = (&sx, &sy);
    // ARMv7-M: the x steps through memory, opaque to the optimiser (as
    // known stack values it reloaded them one by one at every pixel of
    // the inline pixel loop, now as one pair); bunny-gouraud raster
    // thumbv7em 1 886 889 -> 1 833 714. Not on ARMv6-M (its raster took
    // 2 838 011 -> 2 886 571), nor on the 64-bit hosts (callgrind,
    // `examples/bunny_frame.rs`: the steps then stay in registers, 2 233 321
    // -> 2 220 418; with the rows stepped, [`SmallRows::LAZY`], 2 259 273
    // -> 2 188 216). Measured on ARMv7-M again at 1 642 170 (bunny-gouraud
    // raster thumbv7em) without it: 1 733 664.
    let tx = if NO_LONG_MUL || !cfg!(target_arch = "arm") {
        tx
    } else {
        core::hint::black_box(tx)
    };
    let (sx, sy) = (&tx, &ty);
    let stop = j_bot.min(until);
    // The rows counted by their offset (no row number live in the loops;
    // bunny-gouraud raster thumbv6m 2 811 372 -> 2 794 166; bunny-flat
    // 2 389 601 -> 2 362 259, thumbv7em 1 546 420 -> 1 530 611), but
    // with values on ARMv7-M (by row: bunny-gouraud raster thumbv7em
    // 1 784 323 against 1 793 899 by offset):
    // row `k` ends where the offset reaches that of row `k`, `width`
    // (at least 1 here: a triangle with columns in `0..=width` has no
    // area when `width <= 0`) apart from row to row, and the loops start
    // below their ends (`j_top < stop`, and `j_top < j_mid` for the upper
    // half).
    let off = |j: i32| (j - y0).wrapping_mul(width) as usize;
    let mut j = j_top;
    if upper {
        let stop_upper = j_mid.min(stop);
        small_rows_to!(
            rows,
            j,
            stop_upper,
            off(stop_upper),
            l,
            r,
            LEVELS,
            (px, z, sx, sy, &color)
        );
        j = stop_upper;
        // At the lower half's first row (and not at the band's end, where
        // the resumed walk swaps the edges itself).
        if j < stop {
            if long_left {
                r = low;
            } else {
                l = low;
            }
        }
    }
    if j < stop {
        small_rows_to!(
            rows,
            j,
            stop,
            off(stop),
            l,
            r,
            LEVELS,
            (px, z, sx, sy, &color)
        );
        j = stop;
    }
    let more = j < j_bot;
    if more {
        carry_over(
            carry,
            [l, r, low],
            anchor,
            [j, j_mid, j_bot],
            [long_left, z16],
        );
        // The values at pixel (0, 0) in their original form: kept (with
        // `LEVELS`, and on ARMv6-M, where it cost bunny-flat raster 12 K
        // instructions less), or `rows.v` stepped back (the same values,
        // wrapping; on ARMv7-M the Gouraud bunny's raster 16 K less).
        let v00 = if LEVELS || NO_LONG_MUL {
            if lazy {
                let o = origin_short_at(s, [h - a.x, h - a.y], sx0.a[0], sy0.a[0]);
                row.a[0] = lval(a, 0).wrapping_add(o);
            }
            row
        } else {
            let v = Vals {
                z: rows.vz,
                a: rows.va,
            };
            if SmallRows::<'_, N>::LAZY {
                v
            } else {
                v.add_n(sy0, j.wrapping_neg())
            }
        };
        pack_vals(vals, &v00, sx0, sy0);
    }
    Some((rows.drawn(), more))
}

/// The depth of a packed grey word ([`crate::num::Profile::PACKED_GREY`]:
/// the 16-bit depth field `f` in the high half, the level field in the
/// low half): `f·2^14 + 2^13`, as the renderer unpacks it.
#[inline(always)]
pub(crate) fn grey_z(w: i32) -> i32 {
    (((w as u32 >> 16) << 14) | (1 << 13)) as i32
}

/// The grey level of a packed grey word (see [`grey_z`]): `f·2^8` for its
/// low 16-bit field `f`.
#[inline(always)]
pub(crate) fn grey_l(w: i32) -> i32 {
    ((w as u32 & 0xffff) << 8) as i32
}

/// The least depth field whose depth [`grey_z`] passes
/// [`Depth16::vertices_in_range`] (depths in `[2^15, 65535·2^14 - 2^15)`),
/// and one past the greatest (checked against it on every field).
const WORD_FIELDS: (u32, u32) = {
    const M: u32 = 1 << 15;
    const DEPTH16_LIM: u32 = 65535 << 14;
    let mut f = 0u32;
    while !(((f << 14) | (1 << 13)).wrapping_sub(M) < DEPTH16_LIM - 2 * M) {
        f += 1;
    }
    let lo = f;
    while f < 1 << 16 && ((f << 14) | (1 << 13)).wrapping_sub(M) < DEPTH16_LIM - 2 * M {
        f += 1;
    }
    (lo, f)
};

/// [`Depth16::vertices_in_range`] of the depths of three packed grey
/// words ([`grey_z`]), on the words: a depth field `f` passes exactly when
/// it lies in `WORD_FIELDS`' range (the passing depths are one run of
/// fields), so that `w - lo·2^16` is below `(hi - lo)·2^16` as a `u32`
/// (the low half below `2^16`). Tested on every field.
#[inline(always)]
pub(super) fn words_in_range(w: [i32; 3]) -> bool {
    let (lo, hi) = WORD_FIELDS;
    let ok = |w: i32| (w as u32).wrapping_sub(lo << 16) < (hi - lo) << 16;
    ok(w[0]) & ok(w[1]) & ok(w[2])
}

/// [`draw_small`]'s walk of a triangle continuing below the band (its
/// edges `[left, right, lower short]`, the lower one at its first row
/// `rows[1]`, the walk at row `rows[0]`, its end row `rows[2]`, the
/// anchor pixel of its first vertex, `flags` the long edge's side and
/// [`Walk::z16`]): the fields [`setup32`] and [`Walk::rows_fused`] leave
/// (inside the window), but the lower short edge once the walk is past
/// its first row (then unused).
#[inline(always)]
fn carry_over(w: &mut Walk, e: [Edge; 3], anchor: [i32; 2], rows: [i32; 3], flags: [bool; 2]) {
    let [long_left, z16] = flags;
    let [j, j_mid, j_bot] = rows;
    let [l, r, low] = e;
    w.left = l;
    w.right = r;
    // The lower short edge while the walk has not swapped it in yet (`j
    // <= mid`); past that row the walk never reads it (the general walk
    // keeps it unused, here it is left empty).
    w.low = if j <= j_mid { low } else { Edge::EMPTY };
    w.j = j;
    w.mid = j_mid;
    w.end = j_bot;
    [w.ia, w.ja] = anchor;
    w.long_left = long_left;
    w.inside = true;
    w.z16 = z16;
}

/// The colour and depth slices cut to their common length: a span's
/// range checked on one then holds for the other (one test per span).
#[inline(always)]
fn same_len<'p, 'z, R, Z>(px: &'p mut [R], z: &'z mut [Z]) -> (&'p mut [R], &'z mut [Z]) {
    let n = px.len().min(z.len());
    let (px, _) = px.split_at_mut(n);
    let (z, _) = z.split_at_mut(n);
    (px, z)
}

/// The row state of [`draw_small`]: the values at column 0 of the row
/// (or at pixel (0, 0): [`SmallRows::LAZY`]),
/// the row's offset in the band, the pixels covered so far less those
/// that failed the depth test, or those failures apart
/// ([`SmallRows::fails_in`]; the pixels drawn the difference:
/// [`SmallRows::drawn`]). Each span's pixel loop inline ([`small_loop`]),
/// no call per span: on ARMv6-M (bunny-gouraud raster thumbv6m
/// 2 866 494 -> 2 838 685, bunny-flat 2 423 668 -> 2 407 693) and, with
/// the x steps opaque to the optimiser (see [`draw_small`]), on
/// ARMv7-M (bunny-gouraud raster thumbv7em 1 833 849 -> 1 833 714,
/// bunny-flat 1 561 380 -> 1 546 420; before, the span stage's loops,
/// the outlined [`in_range_loop`](super::span) for spans of two pixels
/// or more).
///
/// Measured from 1 573 608 (bunny-gouraud raster thumbv7em, every CRC
/// unchanged) and not kept: each span queued for the band instead of
/// drawn (its offset, count, values and steps, six words, in a queue of
/// 16 on the stack of [`Bands::run_fast`](crate::render), room for a
/// triangle's rows made before them, the queue drawn in order by an
/// out-of-line loop when full, before the general path draws and at the
/// object's end): 1 757 127, and 1 797 173 with the direct spans taken
/// out of the kernel's rows. The queue's loop took 380 859 (19 a span
/// and 14 a pixel, its palette address still rebuilt at every pixel);
/// the kernel's rows and spans gave back only 200 K of it: they still
/// hold the edges, the row and the values (26 to 29 a row, 25 a span
/// with the six stores).
struct SmallRows<'f, const N: usize> {
    /// The values' depth and attributes as two fields rather than one
    /// [`Vals`]: the host kept that pair packed in one 64-bit register,
    /// unpacked and repacked at every row (callgrind,
    /// `examples/bunny_frame.rs`, 2 208 123 -> 2 199 488, later
    /// 2 155 854 -> 2 150 035; the ARM counts unchanged).
    vz: i32,
    va: [i32; N],
    base: usize,
    width: usize,
    drawn: u32,
    fails: &'f mut u32,
}

impl<const N: usize> SmallRows<'_, N> {
    /// `v` holds the values at pixel (0, 0) and each span's start is two
    /// multiply-adds per value away (`v + sy·j + sx·x0`), instead of `v`
    /// at column 0 of the current row stepped by `sy` on every row (two
    /// values kept across the rows less): on ARMv7-M with values
    /// (bunny-gouraud raster thumbv7em 1 784 323 -> 1 766 646; again
    /// without it at 1 642 170: 1 685 618), and in test builds, which
    /// check it. Not on the 64-bit hosts, where the rows' values stepped
    /// cost less (the host's bunny frame, callgrind,
    /// `examples/bunny_frame.rs`, 2 220 418 -> 2 188 216; the rows then
    /// counted by row rather than by offset 2 205 047, the failed tests
    /// counted apart as on ARMv7-M without values 2 214 142).
    const LAZY: bool = !NO_LONG_MUL && N > 0 && cfg!(any(target_arch = "arm", test));

    /// The pixels drawn so far.
    #[inline(always)]
    fn drawn(&self) -> u32 {
        self.drawn.wrapping_sub(*self.fails)
    }

    /// Where a span's failed depth tests are counted, and by what step:
    /// [`SmallRows::drawn`] itself, one down per failure (one counter
    /// live in the pixel loop instead of two: bunny-gouraud raster
    /// thumbv6m 2 838 011 -> 2 811 372, thumbv7em 1 819 402 -> 1 789 976),
    /// but without values on ARMv7-M (bunny-flat raster thumbv7em
    /// 1 546 420 -> 1 558 184 that way): [`SmallRows::fails`], one up.
    #[inline(always)]
    fn fails_in(&mut self) -> (&mut u32, u32) {
        if NO_LONG_MUL || N > 0 {
            (&mut self.drawn, u32::MAX)
        } else {
            (&mut *self.fails, 1)
        }
    }

    /// Draws columns `x0..x1` of the current row (nothing when `x0 >=
    /// x1`) and moves to the next row; `LEVELS` as in [`draw_small`].
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn span<R: Copy, D: DepthFormat, const LEVELS: bool>(
        &mut self,
        j: i32,
        x0: i32,
        x1: i32,
        px: &mut [R],
        z: &mut [D::Raw],
        sx: &Vals<i32, N>,
        sy: &Vals<i32, N>,
        color: &impl Fn(&[i32; N]) -> R,
    ) {
        if x0 < x1 {
            let v = Vals {
                z: self.vz,
                a: self.va,
            };
            let s = if Self::LAZY {
                v.add_n(sy, j).add_n(sx, x0)
            } else {
                v.add_n(sx, x0)
            };
            // The slices from the span's start and pixel count `x1 - x0`
            // on the hosts (see [`span_by_count`]).
            #[cfg(not(target_arch = "arm"))]
            let (p, d) = span_by_count(px, z, self.base, x0, x1);
            #[cfg(target_arch = "arm")]
            let span = self.base.wrapping_add(x0 as usize)..self.base.wrapping_add(x1 as usize);
            #[cfg(target_arch = "arm")]
            let (p, d) = (px.get_mut(span.clone()), z.get_mut(span));
            if let (Some(p), Some(d)) = (p, d) {
                // The span's pixels covered here, its failed tests
                // counted on across the triangle's spans.
                self.drawn = self.drawn.wrapping_add(p.len() as u32);
                if NO_LONG_MUL || LEVELS {
                    // With `LEVELS` the rounding offset is in the values
                    // already ([`draw_small`]): the offset below would be
                    // taken off again at every pixel (an `LEA` a pixel on
                    // x86-64; the host's bunny frame, callgrind,
                    // `examples/bunny_frame.rs`, 2 246 494 -> 2 233 321;
                    // the ARM targets take `LEVELS` on ARMv6-M only, on
                    // the branch above anyway).
                    small_loop::<N, R, D>(p, d, s.z, s.a, sx, color, self.fails_in());
                } else {
                    // ARMv7-M: the values carried with the levels'
                    // rounding offset added, taken off again for the
                    // colour (the same values, wrapping): the offset of
                    // the level shaders' rounding then cancels instead of
                    // being added at every pixel (bunny-gouraud raster
                    // thumbv7em 1 833 714 -> 1 819 402).
                    const B: i32 = 1 << (super::LEVEL_FRAC_BITS - 1);
                    let a = s.a.map(|v| v.wrapping_add(B));
                    let color = |a: &[i32; N]| color(&a.map(|v| v.wrapping_sub(B)));
                    small_loop::<N, R, D>(p, d, s.z, a, sx, &color, self.fails_in());
                }
            }
        }
        if !Self::LAZY {
            self.vz = self.vz.wrapping_add(sy.z);
            for (v, d) in self.va.iter_mut().zip(sy.a.iter()) {
                *v = v.wrapping_add(*d);
            }
        }
        self.base = self.base.wrapping_add(self.width);
    }
}

/// The colour and depth slices of columns `x0..x1` (`x0 < x1`) of the
/// row at offset `base`, cut from the span's start and its pixel count
/// `x1 - x0` rather than from its start and end (the same slices, or
/// `None` alike: `start + n` is the end): [`SmallRows::span`]'s on the
/// hosts, where the count then serves the slices and the pixel loop
/// (callgrind, `examples/bunny_frame.rs`, 2 170 967 -> 2 150 035; in
/// [`Walk::fused`] as well 2 159 493); not on ARM (bunny-gouraud raster
/// thumbv7em 1 631 831 -> 1 661 529), whose builds compile the code they
/// did (`cfg` attributes).
#[cfg(not(target_arch = "arm"))]
#[inline(always)]
fn span_by_count<'p, 'z, R, Z>(
    px: &'p mut [R],
    z: &'z mut [Z],
    base: usize,
    x0: i32,
    x1: i32,
) -> (Option<&'p mut [R]>, Option<&'z mut [Z]>) {
    let start = base.wrapping_add(x0 as usize);
    let n = x1.wrapping_sub(x0) as u32 as usize;
    (
        px.get_mut(start..).and_then(|p| p.get_mut(..n)),
        z.get_mut(start..).and_then(|d| d.get_mut(..n)),
    )
}

/// The pixels of a span of [`draw_small`] whose depths stay in range (no
/// clamp), one a step: each depth-tested ([`in_range_test`]) and, when
/// it passes, shaded by `color`; each other one adds `fails.1` to
/// `fails.0` (wrapping; see [`SmallRows::fails_in`]).
/// The same pixels, in the same order, as the span stage's
/// [`inr_span_inline`](super::span::inr_span_inline).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn small_loop<const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    mut z: i32,
    mut a: [i32; N],
    d: &Vals<i32, N>,
    color: &impl Fn(&[i32; N]) -> R,
    fails: (&mut u32, u32),
) {
    let mut it = row.iter_mut().zip(drow.iter_mut());
    while let Some((p, zb)) = it.next() {
        if in_range_test::<i32, D>(z, zb) {
            *p = color(&a);
        } else {
            *fails.0 = fails.0.wrapping_add(fails.1);
            // Never taken (a slice holds fewer than usize::MAX depths),
            // but a second loop exit keeps LLVM's runtime unroller off
            // this loop (as in the span stage's loop).
            if it.len() == usize::MAX {
                break;
            }
        }
        z = z.wrapping_add(d.z);
        for (v, s) in a.iter_mut().zip(d.a.iter()) {
            *v = v.wrapping_add(*s);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The resume kernel ([`Walk::rows_resumed`], [`resume_rows`]) against
    /// [`Walk::rows_fused`]: random triangles (inside the window, depths
    /// in range, and not: then both take the fused walk) set up at their
    /// first band ([`setup_fast`]) and walked band by band (band heights
    /// 1 to 16, random depth buffers so that tests fail too), each band
    /// from a copy of the same walk: the same pixels, depths, pixel counts
    /// and walk after every band.
    #[test]
    fn resumed_rows_equal_the_fused_walk() {
        let sub = SubpixelBits::DEFAULT;
        let mut rng = super::super::tests::xorshift(0x0005_eed0_f2e5_u64);
        let mut next = move |m: u32| (rng() % u64::from(m)) as i32;
        let width = 48;
        let color = |a: &[i32; 1]| a[0] as u32 ^ 0x5a5a_0000;
        let mut resumed = 0;
        for it in 0..6000 {
            let big = it % 3 == 0;
            let span = if big { 48 * 16 } else { 12 * 16 };
            let x0 = next(48 * 16 - span + 1);
            let y_top = next(40 * 16);
            let far = it % 7 == 0;
            let mut v: [Vertex<i32, 1>; 3] = core::array::from_fn(|_| Vertex {
                x: x0 + next(span + 1) - if far { 20 } else { 0 },
                y: y_top + next(span + 1),
                z: (1 << 16) + next(1 << 28),
                attrs: [next(1 << 24) - if it % 5 == 0 { 1 << 22 } else { 0 }],
            });
            v.sort_by_key(|p| p.y);
            let rows = 1 + next(16);
            let j0 = first_row(v[0].y, sub);
            let y_first = j0 - j0.rem_euclid(rows);
            let (mut walk, mut vals) = (Walk::EMPTY, [[0; 3]; 2]);
            if !setup_fast::<1, 2>(
                &v[0], &v[1], &v[2], sub, y_first, width, &mut walk, &mut vals,
            ) {
                continue;
            }
            let mut y0 = y_first;
            while !walk.done() {
                let n = (width * rows) as usize;
                let (mut px, mut z) = ([0u32; 48 * 16], [0u16; 48 * 16]);
                for (p, d) in px.iter_mut().zip(z.iter_mut()).take(n) {
                    *p = next(1 << 30) as u32;
                    *d = next(1 << 16) as u16;
                }
                let run = |resume: bool| {
                    let (mut p, mut d, mut w) = (px, z, walk);
                    let (mut pr, mut dr) = (&mut p[..n], Some(&mut d[..n]));
                    let mut mem = BandMem::<u32, u16> {
                        px: &mut pr,
                        z: &mut dr,
                        y0,
                        width,
                    };
                    let k = if resume {
                        w.rows_resumed::<1, 2, u32, Depth16>(&vals, y0 + rows, &mut mem, color)
                    } else {
                        w.rows_fused::<1, 2, u32, Depth16>(&vals, y0 + rows, &mut mem, color)
                    };
                    (k, p, d, w)
                };
                let (a, b) = (run(false), run(true));
                assert_eq!(a.0, b.0, "{v:?} band {y0}");
                assert!(a.1 == b.1 && a.2 == b.2, "{v:?} band {y0}");
                assert_eq!(a.3, b.3, "{v:?} band {y0}");
                resumed += u32::from(y0 > y_first && walk.inside && walk.z16);
                walk = a.3;
                y0 += rows;
            }
        }
        // The kernel's case is met often.
        assert!(resumed > 2000, "{resumed}");
    }

    /// [`Grad::origin_short`] against the 64-bit sum of [`Grad::plane`].
    #[test]
    fn short_origin_equals_the_wide_sum() {
        let mut rng = super::super::tests::xorshift(0x0123_4567_89ab_cdef);
        let mut next = || rng() as u32;
        let lim = (1 << 15) - 1;
        let ends = [0, 1, -1, lim, -lim, i32::MAX, i32::MIN, 0xffff, -0x10000];
        for i in 0..400_000u32 {
            let pick = |r: u32, k: u32| -> i32 {
                match k % 4 {
                    0 => ends[(r % ends.len() as u32) as usize],
                    1 => (r as i32) >> (r % 31),
                    _ => r as i32,
                }
            };
            let (gx, gy) = (pick(next(), i), pick(next(), i / 4));
            let o = |r: u32| ((r as i32) >> (r % 17)).clamp(-lim, lim);
            let (ox, oy) = (o(next()), o(next()));
            let s = 1 + i % 8;
            let grad = Grad {
                d: [0; 4],
                inv: InvArea::new(1),
                k: 0,
                s,
                o: [ox, oy],
            };
            let t = gx as i64 * ox as i64 + gy as i64 * oy as i64 + (1i64 << (s - 1));
            assert_eq!(
                grad.origin_short(gx, gy),
                (t >> s) as i32,
                "{gx} {gy} {ox} {oy} {s}"
            );
            let low = (1u32 << (32 - s)) - 1;
            assert_eq!(
                grad.origin_low(gx, gy) as u32 & low,
                (t >> s) as u32 & low,
                "{gx} {gy} {ox} {oy} {s}"
            );
        }
    }

    /// [`offsets_near`]: for every band it passes, the extreme first
    /// vertices [`draw_small`] admits (columns `0` and `width·S`, rows
    /// just below the band's first and at its last) have both offsets
    /// below `2^15` in magnitude; bands with a bound at `2^(15 - s)` or
    /// negative fail.
    #[test]
    fn offsets_near_bounds_the_offsets() {
        let mut rng = super::super::tests::xorshift(0x9e37_79b9_7f4a_7c15);
        let mut next = || rng() as u32;
        for s in 1..=8u32 {
            let (sc, h, w) = (1i32 << s, 1i32 << (s - 1), (1i32 << 15) >> s);
            let edge = [0, 1, 2, w - 2, w - 1];
            for i in 0..20_000u32 {
                let pick = |r: u32| {
                    if i % 2 == 0 {
                        edge[(r % 5) as usize]
                    } else {
                        (r % w as u32) as i32
                    }
                };
                let (y0, until, width) = (pick(next()), pick(next()), pick(next()));
                assert!(offsets_near(s, y0, until, width));
                let ys = [(y0 - 1) * sc + h + 1, (until - 1) * sc + h];
                for ax in [0, width * sc] {
                    for ay in ys {
                        if ys[0] > ys[1] {
                            continue;
                        }
                        let (ox, oy) = (h - ax, h - ay);
                        assert!(ox.unsigned_abs() < 1 << 15, "{s} {ax}");
                        assert!(oy.unsigned_abs() < 1 << 15, "{s} {ay}");
                    }
                }
            }
            for bad in [w, w + 1, i32::MAX, -1, i32::MIN] {
                assert!(!offsets_near(s, bad, 1, 1));
                assert!(!offsets_near(s, 0, bad, 1));
                assert!(!offsets_near(s, 0, 1, bad));
            }
        }
    }

    /// [`levels_in_range`]'s margins: `2^(18 - s)` at each end (at 4
    /// subpixel bits a quarter of a level), gradients in `[-2^28, 2^28)`.
    #[test]
    fn levels_in_range_bounds() {
        let top = 255 << 16;
        assert!(levels_in_range([0, 0, top], 0, 0, 4));
        assert!(levels_in_range([-(1 << 14), 5, 7], 0, 0, 4));
        assert!(!levels_in_range([-(1 << 14) - 1, 5, 7], 0, 0, 4));
        let hi = (1 << 24) - (1 << 15) - (1 << 14);
        assert!(levels_in_range([0, hi - 1, 7], 0, 0, 4));
        assert!(!levels_in_range([0, hi, 7], 0, 0, 4));
        assert!(levels_in_range(
            [0, 1, 2],
            (1 << 28) - 1,
            -((1 << 28) - 1),
            4
        ));
        assert!(!levels_in_range([0, 1, 2], 1 << 28, 0, 4));
        assert!(levels_in_range([0, 1, 2], -(1 << 28), -(1 << 28), 4));
        assert!(!levels_in_range([0, 1, 2], 0, -(1 << 28) - 1, 4));
        assert!(!levels_in_range([0, 1, 2], i32::MAX, 0, 4));
        assert!(!levels_in_range([0, 1, 2], 0, i32::MIN, 4));
        // One subpixel bit: margins of 2^17 (two levels).
        assert!(!levels_in_range([0, 1, 2], 0, 0, 1));
        assert!(levels_in_range(
            [(1 << 17) - (1 << 15), 1 << 20, 1 << 23],
            0,
            0,
            1
        ));
    }
}
