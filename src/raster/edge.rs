//! The edge walker: an exact integer DDA (Bresenham's method).

use super::SubpixelBits;
use crate::num::wide::{small_floor_divmod, wmul, NO_DIVIDE};

/// Walks one triangle edge downwards, one scanline at a time, giving for
/// each row the first column whose pixel centre lies at or to the right of
/// the edge (see the [module docs](super) for the formula).
///
/// The column is the exact ceiling of a rational on every row: the walker
/// keeps the integer column and an error term `e` with `numerator =
/// column · D - e`, `0 <= e < D`, and steps both by an integer quotient and
/// remainder. No rounding, no drift, whatever the length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// The current column (first pixel at or right of the edge).
    pub x: i32,
    pub(super) e: i32,
    pub(super) q: i32,
    pub(super) r: i32,
    pub(super) d: i32,
}

impl Edge {
    /// An edge that never moves (a placeholder).
    pub(crate) const EMPTY: Self = Self {
        x: 0,
        e: 0,
        q: 0,
        r: 0,
        d: 1,
    };

    /// The edge from `(x0, y0)` down to `(x1, y1)` (subpixels, `y1 > y0`,
    /// coordinates within the limits of the [module](super)), positioned at
    /// row `j`.
    #[inline(always)]
    pub fn new(x0: i32, y0: i32, x1: i32, y1: i32, j: i32, sub: SubpixelBits) -> Self {
        let s = sub.scale();
        let dx = x1 - x0;
        let dy = (y1 - y0).max(1);
        // In [1, 2^30].
        let d = (s * dy).max(1);
        // One division per edge: dx = q·dy + rem, 0 <= rem < dy. On
        // ARMv6-M (no divider) the usual slopes, |dx/dy| up to 4, take a
        // few subtractions instead of a library division (also in test
        // builds, so that the host tests check the division-free paths).
        let (q, rem) = slope_divmod::<{ NO_DIVIDE || cfg!(test) }>(dx, dy);
        let r = s * rem;
        let t = j as i64 * s as i64 + (s / 2) as i64 - y0 as i64; // yc - y0
        let (x, e) = if (0..s as i64).contains(&t) {
            // The edge's first row (t < S): with A = x0 - S/2 + t·q = S·a + b
            // the numerator is d·a + N', N' = b·dy + t·rem in [0, 2d), so
            // ceil(N'/d) is 0, 1 or 2: no second division, all in 32 bits
            // (|t·q| <= |dx| < 2^22·2^8; b·dy, t·rem < 2^30).
            let t = t as i32;
            let a_full = x0 - s / 2 + t * q;
            let (a, b) = (a_full >> sub.get(), a_full & (s - 1));
            let np = b * dy + t * rem;
            if np == 0 {
                (a, 0)
            } else if np <= d {
                (a + 1, d - np)
            } else {
                (a + 2, 2 * d - np)
            }
        } else if let Some(xe) = (NO_DIVIDE || cfg!(test))
            .then(|| later_row_small(x0, t, q, rem, dy, d, sub))
            .flatten()
        {
            xe
        } else {
            // Any other row (a band starting inside the triangle): the
            // numerator in 64 bits, divided in 32 bits when it fits.
            // |t| < 2^22 + 2^8 for rows and vertices within the limits.
            let n = match i32::try_from(t) {
                Ok(t) => wmul(x0 - s / 2, dy) + wmul(t, dx),
                Err(_) => (x0 - s / 2) as i64 * dy as i64 + t * dx as i64,
            };
            match i32::try_from(n) {
                Ok(n) => {
                    let (k, m) = floor_divmod(n, d);
                    if m == 0 {
                        (k, 0)
                    } else {
                        (k + 1, d - m)
                    }
                }
                Err(_) => {
                    let (k, m) = (n.div_euclid(d as i64), n.rem_euclid(d as i64));
                    if m == 0 {
                        (k as i32, 0)
                    } else {
                        (k as i32 + 1, d - m as i32)
                    }
                }
            }
        };
        Self { x, e, q, r, d }
    }

    /// [`Edge::new`] for an edge positioned at its own first row (`0 <= t
    /// < S` for `t = j·S + S/2 - y0`, the case of every edge a triangle
    /// starts with, and of its lower short edge), in 32-bit arithmetic
    /// (with the module's limits `|j·S| < 2^22` and `|y0| <= 2^21`, `t`
    /// fits an `i32`); other rows take [`Edge::new`]. The same walker.
    #[inline(always)]
    pub(crate) fn new_first(x0: i32, y0: i32, x1: i32, y1: i32, j: i32, sub: SubpixelBits) -> Self {
        let s = sub.scale();
        let t = j.wrapping_mul(s).wrapping_add(s / 2).wrapping_sub(y0);
        if !(0..s).contains(&t) {
            return Self::new_cold(x0, y0, x1, y1, j, sub);
        }
        Self::at_step(x0, y0, x1, y1, t, sub)
    }

    /// [`Edge::new_first`] at the edge's own first row `first_row(y0)`
    /// (`y1 > y0`, coordinates within the module's limits): there `t =
    /// j·S + S/2 - y0` is `(S/2 - y0) mod S` (the step from `y0 - S/2` up
    /// to the next multiple of `S`), so neither the row nor a range test
    /// is needed. The same walker (tested equal to [`Edge::new`]).
    #[inline(always)]
    pub(crate) fn at_first_row(x0: i32, y0: i32, x1: i32, y1: i32, sub: SubpixelBits) -> Self {
        let s = sub.scale();
        Self::at_step(x0, y0, x1, y1, (s / 2).wrapping_sub(y0) & (s - 1), sub)
    }

    /// [`Edge::at_first_row`] for a short edge: `|x1 - x0| < 2^16` and `0 <
    /// y1 - y0 < 2^15` (the small-triangle kernel's edges; other edges get
    /// a wrong walker, never a panic). With a hardware divider the floored
    /// quotient and remainder by one unsigned division of the numerator
    /// biased by `2^16·dy` (in `(0, 2^31)`: `dx + 2^16·dy = (q + 2^16)·dy +
    /// rem`, `0 <= rem < dy`), without [`Edge::new`]'s sign fix-up; on
    /// ARMv6-M [`Edge::at_first_row`]. The same walker (tested equal).
    #[inline(always)]
    pub(crate) fn at_first_row_short(
        x0: i32,
        y0: i32,
        x1: i32,
        y1: i32,
        sub: SubpixelBits,
    ) -> Self {
        if NO_DIVIDE {
            return Self::at_first_row(x0, y0, x1, y1, sub);
        }
        let s = sub.scale();
        let t = (s / 2).wrapping_sub(y0) & (s - 1);
        let dx = x1 - x0;
        let dy = (y1 - y0).max(1);
        let d = s * dy;
        let n = (dx.wrapping_add(dy << 16)) as u32;
        let qb = n / dy as u32;
        let rem = n.wrapping_sub(qb.wrapping_mul(dy as u32)) as i32;
        let q = (qb as i32).wrapping_sub(1 << 16);
        Self::at_quot(x0, [dy, d], q, rem, t, sub)
    }

    /// The walker of [`Edge::new_first`] and [`Edge::at_first_row`]: the
    /// edge at the row whose centre lies `t` subpixels below `y0`, `0 <= t
    /// < S` (the first-row case of [`Edge::new`], in 32-bit arithmetic:
    /// within the module's limits `S·dy <= 2^30`, so `d >= 1` without
    /// [`Edge::new`]'s guard).
    #[inline(always)]
    fn at_step(x0: i32, y0: i32, x1: i32, y1: i32, t: i32, sub: SubpixelBits) -> Self {
        let s = sub.scale();
        let dx = x1 - x0;
        let dy = (y1 - y0).max(1);
        let d = s * dy;
        let (q, rem) = slope_divmod::<NO_DIVIDE>(dx, dy);
        Self::at_quot(x0, [dy, d], q, rem, t, sub)
    }

    /// [`Edge::at_step`] from the slope's floored quotient `q` and
    /// remainder `rem` by `dy >= 1` (`d = S·dy`).
    #[inline(always)]
    fn at_quot(x0: i32, [dy, d]: [i32; 2], q: i32, rem: i32, t: i32, sub: SubpixelBits) -> Self {
        let s = sub.scale();
        let r = s * rem;
        let a_full = x0 - s / 2 + t * q;
        let (a, b) = (a_full >> sub.get(), a_full & (s - 1));
        let np = b * dy + t * rem;
        let (x, e) = first_column::<{ !cfg!(target_arch = "arm") }>(a, np, d);
        Self { x, e, q, r, d }
    }

    /// [`Edge::new`] out of line (a band starting inside a triangle).
    #[inline(never)]
    #[cold]
    fn new_cold(x0: i32, y0: i32, x1: i32, y1: i32, j: i32, sub: SubpixelBits) -> Self {
        Self::new(x0, y0, x1, y1, j, sub)
    }

    /// Advances one row; returns `true` when the column moved one further
    /// than the quotient (the error term wrapped). On ARM by the error
    /// term's sign (a conditional add, the sign bit added to the column).
    #[cfg(target_arch = "arm")]
    #[inline(always)]
    pub fn step(&mut self) -> bool {
        self.step_by_sign()
    }

    /// [`Edge::step`]'s ARM form, by the error term's sign (on the hosts
    /// compiled for its test against the other form only).
    #[cfg(any(test, target_arch = "arm"))]
    #[inline(always)]
    fn step_by_sign(&mut self) -> bool {
        self.e -= self.r;
        self.x += self.q;
        if self.e < 0 {
            self.e += self.d;
            self.x += 1;
            true
        } else {
            false
        }
    }

    /// Advances one row; returns `true` when the column moved one further
    /// than the quotient (the error term wrapped). On the hosts by the
    /// borrow of the unsigned `e - r` (`0 <= e, r < d`: it borrows exactly
    /// when `e - r < 0`): one `SUB`, its carry added to the column by
    /// `ADC`, the error term's fix-up a `CMOV` (callgrind,
    /// `examples/bunny_frame.rs`, the bunny's Gouraud frame 2 199 488 ->
    /// 2 178 374; on ARM it cost the row loops registers, bunny-gouraud
    /// raster thumbv7em 1 631 831 -> 1 698 055). The same walker (tested
    /// equal to the ARM form). Chosen by `cfg` attributes: the ARM builds
    /// compile the very code they did.
    #[cfg(not(target_arch = "arm"))]
    #[inline(always)]
    pub fn step(&mut self) -> bool {
        let (e, wrap) = (self.e as u32).overflowing_sub(self.r as u32);
        self.x = self.x.wrapping_add(self.q).wrapping_add(wrap as i32);
        self.e = if wrap {
            e.wrapping_add(self.d as u32)
        } else {
            e
        } as i32;
        wrap
    }

    /// The whole-column part of a step, `⌊DX/DY⌋`.
    pub fn quotient(&self) -> i32 {
        self.q
    }
}

/// The column and error term at a row `t` subpixels below the first
/// vertex (`t >= 0`) of a short edge, without a division (for ARMv6-M, a
/// band starting a few rows into a triangle): as on the first row, with
/// `A = x0 - S/2 + t·q = S·a + b` the numerator is `d·a + N'` with
/// `N' = b·dy + t·rem >= 0`, whose quotient by `d` is below `2 + t/S`, taken by at
/// most four subtractions. `None` (the caller divides) beyond that or
/// outside the bounds that keep it all in 32 bits: `t < 2^12`, `dy <
/// 2^16`, `|q| < 2^16` (then `|t·q| < 2^28`, `N' < 2^29`).
#[inline]
fn later_row_small(
    x0: i32,
    t: i64,
    q: i32,
    rem: i32,
    dy: i32,
    d: i32,
    sub: SubpixelBits,
) -> Option<(i32, i32)> {
    if !(0..1 << 12).contains(&t) || dy >= 1 << 16 || q.unsigned_abs() >= 1 << 16 {
        return None;
    }
    let (t, s) = (t as i32, sub.scale());
    let a_full = x0 - s / 2 + t * q;
    let (a, b) = (a_full >> sub.get(), a_full & (s - 1));
    let (k, m) = small_floor_divmod(b * dy + t * rem, d)?;
    Some(if m == 0 {
        (a + k, 0)
    } else {
        (a + k + 1, d - m)
    })
}

/// The column and error term `(a + k, k·d - np)` of [`Edge::at_quot`]
/// for `np` in `[0, 2d)`, `k = ⌈np / d⌉` (0, 1 or 2): with `BRANCHLESS`
/// from two comparisons, `k = [np > 0] + [np > d]`, otherwise by
/// branches (the form [`Edge::at_quot`] keeps on ARM, inline; on ARMv7-M
/// the branchless one measured bunny-gouraud raster thumbv7em
/// 1 642 170 -> 1 655 745). The same values (tested). The hosts take it
/// branchless (callgrind, `examples/bunny_frame.rs`, 2 178 374 ->
/// 2 170 967).
#[inline(always)]
fn first_column<const BRANCHLESS: bool>(a: i32, np: i32, d: i32) -> (i32, i32) {
    if BRANCHLESS {
        let k = (np > 0) as i32 + (np > d) as i32;
        (a + k, k * d - np)
    } else if np == 0 {
        (a, 0)
    } else if np <= d {
        (a + 1, d - np)
    } else {
        (a + 2, 2 * d - np)
    }
}

/// Quotient bits of [`binary_floor_divmod`].
const DIV_BITS: u32 = 5;

/// `(⌊n/d⌋, n mod d)` for `d > 0` without a division (ARMv6-M: a
/// library call of about 100 instructions), for the steeper slopes
/// [`small_floor_divmod`] declines: restoring binary division of `|n|` in
/// [`DIV_BITS`] steps (one shift, one comparison and at most one
/// subtraction each), when `|n| < d·2^DIV_BITS` and `d < 2^(31 -
/// DIV_BITS)` (so that `d·2^k` fits for every step); `None` otherwise
/// (the caller divides). Exact: each step keeps `|n| = q·d + m` with `0
/// <= m < d·2^k`; the floor of a negative quotient follows from the
/// magnitude's. Tested against `div_euclid` and `rem_euclid`. Exact QEMU
/// counts on thumbv6m (every division of the bunny's edges gone):
/// bunny-gouraud raster 2 838 011 -> 2 814 970, bunny-flat 2 406 527 ->
/// 2 387 698 (with 4 quotient bits 2 813 776 and 2 389 322, with 6
/// 2 819 305 and 2 395 886, with 8 2 828 691 and 2 414 206).
#[inline(always)]
#[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)]
fn binary_floor_divmod(n: i32, d: i32) -> Option<(i32, i32)> {
    let du = d as u32;
    let mag = n.unsigned_abs();
    if d <= 0 || du >= 1 << (31 - DIV_BITS) || mag >= du << DIV_BITS {
        return None;
    }
    let (mut m, mut q) = (mag, 0u32);
    for k in (0..DIV_BITS).rev() {
        let t = du << k;
        if m >= t {
            m -= t;
            q |= 1 << k;
        }
    }
    let (q, m) = (q as i32, m as i32);
    Some(if n >= 0 {
        (q, m)
    } else if m == 0 {
        (-q, 0)
    } else {
        (-q - 1, d - m)
    })
}

/// `(⌊dx/dy⌋, dx mod dy)` for `dy >= 1`, the edge's slope: with
/// `NO_DIV` (ARMv6-M, which has no divider) the usual
/// slopes take [`small_floor_divmod`] or [`binary_floor_divmod`]'s few
/// subtractions instead of a library division, which remains for the
/// rest ([`floor_divmod`]). The choice a const parameter: as a `bool`
/// argument thumbv6m raster took bunny-gouraud 2 580 811 -> 2 583 018,
/// bunny-flat 2 197 727 -> 2 199 288; as a parameter the counts are
/// unchanged.
#[inline(always)]
fn slope_divmod<const NO_DIV: bool>(dx: i32, dy: i32) -> (i32, i32) {
    let small = if NO_DIV {
        small_floor_divmod(dx, dy).or_else(|| binary_floor_divmod(dx, dy))
    } else {
        None
    };
    match small {
        Some(qr) => qr,
        None => floor_divmod(dx, dy),
    }
}

/// `(⌊n/d⌋, n mod d)` for `d > 0` with a single division.
#[inline]
fn floor_divmod(n: i32, d: i32) -> (i32, i32) {
    let d = d.max(1);
    let q = n / d;
    let m = n - q * d;
    if m < 0 {
        (q - 1, m + d)
    } else {
        (q, m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// [`Edge::step`] and its ARM form ([`Edge::step_by_sign`]) walk the very
    /// columns and error terms, on random and extreme walkers (`0 <= e, r
    /// < d <= 2^30`, any quotient), and on real edges from [`Edge::new`].
    #[test]
    fn step_forms_agree() {
        let mut next = super::super::tests::xorshift(0x9e37_79b9_7f4a_7c15);
        let ds = [1, 2, 3, 16, 255, (1 << 30) - 1, 1 << 30];
        for i in 0..20_000u32 {
            let d = if i % 4 == 0 {
                ds[(next() % ds.len() as u64) as usize]
            } else {
                1 + (next() % (1 << 30)) as i32
            };
            let pick = |v: u64| match v % 4 {
                0 => 0,
                1 => d - 1,
                _ => ((v >> 8) % d as u64) as i32,
            };
            let (e, r) = (pick(next()), pick(next()));
            let q = match i % 3 {
                0 => (next() % 64) as i32 - 32,
                1 => (next() >> 40) as i32 - (1 << 23),
                _ => 0,
            };
            let x = (next() % 8192) as i32 - 4096;
            let (mut a, mut b) = (Edge { x, e, q, r, d }, Edge { x, e, q, r, d });
            for _ in 0..40 {
                assert_eq!(a.step(), b.step_by_sign(), "{a:?}");
                assert_eq!(a, b);
                assert!((0..d).contains(&a.e));
            }
        }
        let sub = SubpixelBits::new(4).unwrap();
        for k in 0..2_000 {
            let c = |v: u64| (v % 4000) as i32 - 2000;
            let (x0, y0, x1) = (c(next()), c(next()), c(next()));
            let y1 = y0 + 1 + (next() % 3000) as i32 + k % 2;
            let j = (y0 + 7) >> 4;
            let (mut a, mut b) = (
                Edge::new(x0, y0, x1, y1, j, sub),
                Edge::new(x0, y0, x1, y1, j, sub),
            );
            for _ in 0..(y1 - y0) / 16 + 1 {
                assert_eq!(a.step(), b.step_by_sign());
                assert_eq!(a, b);
            }
        }
    }

    /// Both forms of [`first_column`] agree on every `np` in `[0, 2d)`
    /// for small `d` and at the ends for large ones (`2d` an `i32`).
    #[test]
    fn first_column_forms_agree() {
        for d in (1..200).chain([1 << 20, (1 << 29) + 3, (1 << 30) - 1]) {
            let nps: &mut dyn Iterator<Item = i32> = if d < 200 {
                &mut (0..2 * d)
            } else {
                &mut [0, 1, d - 1, d, d + 1, 2 * d - 1].into_iter()
            };
            for np in nps {
                for a in [-4096, 0, 77] {
                    let want = first_column::<false>(a, np, d);
                    assert_eq!(first_column::<true>(a, np, d), want, "{a} {np} {d}");
                    assert!((0..d).contains(&want.1));
                }
            }
        }
    }

    /// [`binary_floor_divmod`] is the Euclidean quotient and remainder
    /// wherever it answers, and answers for every quotient magnitude below
    /// `2^DIV_BITS` (small enough divisors).
    #[test]
    fn binary_floor_divmod_is_exact_or_declines() {
        let lim = 1i32 << DIV_BITS;
        for d in (1..300).chain([1000, 4095, (1 << 25) - 1, 1 << 25, i32::MAX]) {
            let span = (d.saturating_mul(lim + 2)).min(1 << 20);
            let step = (span / 2000).max(1);
            let mut n = -span;
            while n <= span {
                for n in [n, n.wrapping_add(1), n.wrapping_sub(1)] {
                    let want = (n.div_euclid(d), n.rem_euclid(d));
                    match binary_floor_divmod(n, d) {
                        Some(got) => assert_eq!(got, want, "{n} / {d}"),
                        None => assert!(
                            n.unsigned_abs() >= (d as u32) << DIV_BITS || d >= 1 << (31 - DIV_BITS),
                            "{n} / {d} declined"
                        ),
                    }
                }
                n += step;
            }
        }
        for n in [i32::MIN, i32::MAX, 0, -1, 1] {
            for d in [1, 2, 3, i32::MAX] {
                if let Some(got) = binary_floor_divmod(n, d) {
                    assert_eq!(got, (n.div_euclid(d), n.rem_euclid(d)), "{n} / {d}");
                }
            }
        }
        assert_eq!(binary_floor_divmod(5, 0), None);
        assert_eq!(binary_floor_divmod(5, -3), None);
    }
}
