//! Interpolated quantities: fixed point (`i32`) and the float twins.
//!
//! An attribute `A` over a triangle is the plane through its three vertex
//! values. With `(dx1, dy1)`, `(dx2, dy2)` the subpixel offsets of vertices
//! 1 and 2 from vertex 0, `d1`, `d2` their value differences and
//! `a = dx1·dy2 - dx2·dy1` the doubled area, the gradients per *pixel* are
//!
//! ```text
//! gx = S·(d1·dy2 - d2·dy1) / a        gy = S·(d2·dx1 - d1·dx2) / a
//! ```
//!
//! One reciprocal of `a` per triangle ([`Recip`]) turns the divisions into
//! multiplications, so the Cortex-M0, which has no divide instruction,
//! pays for one division per triangle, none per scanline or pixel.

use super::recip::InvArea;
use super::wide::{fits_i16, mul_i32_i16, shr64, wmul, NO_LONG_MUL};
use super::SubpixelBits;
use core::fmt::Debug;

/// Largest magnitude of a fixed-point (`i32`) attribute value: 2^30.
pub const ATTR_LIMIT: i32 = 1 << 30;

/// Fraction bits of a fixed-point colour level: a level `l` in `0..=255` is
/// the raw value `l · 2^16`.
pub const LEVEL_FRAC_BITS: u32 = 16;

/// Fixed-point depth: `d` in `[0, 1]` is the raw value `d · 2^30`.
pub const DEPTH_ONE: i32 = 1 << 30;

/// A quantity the rasterizer interpolates: an `i32` fixed-point raw value,
/// or `f32`/`f64` for the float twins (same algorithm, no quantization).
pub trait Lerp: Copy + Debug + PartialEq + Default {
    /// A gradient per pixel, kept at full precision for pre-stepping.
    type Grad: Copy + Debug;

    /// `true` when `a + n·s` equals `n` additions of `s` exactly (integer
    /// arithmetic): the scanline loop then steps the values at column 0
    /// row by row and starts each span one multiply-add from them. Floats round differently depending on where the sum
    /// started, so for them each row's start value is computed afresh from
    /// the anchor, and a band renders the very bytes of a full frame.
    const EXACT_STEPS: bool;
    /// Zero (for pools of values in `static`s: `Default` is not `const`).
    const ZERO: Self;
    /// Per-triangle constants: the reciprocal of the doubled area.
    type Setup: Copy + Debug;

    /// The per-triangle constants for doubled area `area2` (non-zero).
    fn setup(area2: i64) -> Self::Setup;

    /// Gradients per pixel along x and y, from the vertex values and the
    /// subpixel offsets `[dx1, dy1, dx2, dy2]` of vertices 1 and 2 from
    /// vertex 0.
    fn gradients(
        a: [Self; 3],
        d: [i32; 4],
        setup: &Self::Setup,
        sub: SubpixelBits,
    ) -> (Self::Grad, Self::Grad);

    /// The value at subpixel offset `(ox, oy)` from vertex 0, whose value
    /// is `a0`.
    fn anchor(
        a0: Self,
        gx: Self::Grad,
        gy: Self::Grad,
        ox: i32,
        oy: i32,
        sub: SubpixelBits,
    ) -> Self;

    /// A gradient as a per-step increment.
    fn step(g: Self::Grad) -> Self;

    /// For [`Lerp::EXACT_STEPS`] types, the walker's row origin: the value
    /// at the centre of pixel (0, 0) of the plane through `a0` at subpixel
    /// `(x0, y0)` with gradients `gx`, `gy` per pixel, as the anchor at the
    /// pixel centre nearest `(x0, y0)` ([`Lerp::anchor`]) stepped back by
    /// whole steps (wrapping). Types may compute the same value another
    /// way.
    #[inline(always)]
    fn origin(
        a0: Self,
        gx: Self::Grad,
        gy: Self::Grad,
        x0: i32,
        y0: i32,
        sub: SubpixelBits,
    ) -> Self {
        let s = sub.scale();
        let (ia, ja) = (x0 >> sub.get(), y0 >> sub.get());
        let (ox, oy) = (ia * s + s / 2 - x0, ja * s + s / 2 - y0);
        Self::anchor(a0, gx, gy, ox, oy, sub)
            .add_n(Self::step(gx), ia.wrapping_neg())
            .add_n(Self::step(gy), ja.wrapping_neg())
    }

    /// `self + n · step` (whole steps).
    fn add_n(self, step: Self, n: i32) -> Self;

    /// `self + step`: the inner-loop operation.
    fn add(self, step: Self) -> Self;

    /// Depth as a 30-bit fraction (`0..=2^30`), saturating; the value is
    /// a fixed raw `d·2^30` or a float `d`.
    fn depth30(self) -> u32;

    /// The raw `i64` of a fixed-point gradient (`Some` for `i32`'s, as
    /// [`Lerp::fixed_raw`] for values); `None` for the float twins.
    #[inline(always)]
    fn fixed_grad(g: Self::Grad) -> Option<i64> {
        let _ = g;
        None
    }

    /// Rounded to the nearest integer after removing `frac` fraction bits
    /// (fixed), or rounded (float); saturating.
    fn round_int(self, frac: u32) -> i32;

    /// What undoes a perspective weight `q` in `(0, 1]` (a unit value:
    /// fixed `q · 2^30`): see [`Lerp::unweight`].
    type Unweight: Copy;

    /// The factor for `q` (one division per pixel: the price of
    /// perspective-correct interpolation). Fixed: `q` is clamped to at
    /// least 2^-20 (`w` at most 2^20 times the near distance).
    fn unweight_factor(q: Self) -> Self::Unweight;

    /// `self / q`, for an attribute interpolated as `a · q`.
    fn unweight(self, f: Self::Unweight) -> Self;

    /// The raw `i32` of a fixed-point value (`Some` for `i32`: the band
    /// renderer's fixed affine fast path, `raster::fast`, works on raw
    /// values); `None` for the float twins, which take the generic path.
    #[inline(always)]
    fn fixed_raw(self) -> Option<i32> {
        None
    }

    /// The value whose [`Lerp::fixed_raw`] is `v` (`i32`: `v` itself;
    /// floats, which never take the fast path: `v` as a number).
    fn from_fixed_raw(v: i32) -> Self;

    /// The band pool's value storage as raw `i32`s (`Some` for `i32`, the
    /// very array: the fast path keeps a triangle's values there and
    /// walks a resumed one from there, no copy); `None` for the float
    /// twins.
    #[inline(always)]
    fn fixed_slots<const V: usize>(_v: &mut [[Self; 3]; V]) -> Option<&mut [[i32; 3]; V]> {
        None
    }
}

/// The gradient numerators `(d1·dy2 - d2·dy1, d2·dx1 - d1·dx2)` in `i64`.
#[inline(always)]
fn numerators64(a: [i32; 3], d: [i32; 4]) -> (i64, i64) {
    let d1 = a[1] as i64 - a[0] as i64;
    let d2 = a[2] as i64 - a[0] as i64;
    let [dx1, dy1, dx2, dy2] = d.map(|v| v as i64);
    (d1 * dy2 - d2 * dy1, d2 * dx1 - d1 * dx2)
}

/// [`numerators64`] from 32 × 32 → 64-bit products when the differences
/// fit an `i32` (always, for values within the attribute limit): the same
/// values, on every target.
#[inline(always)]
fn numerators32(a: [i32; 3], d: [i32; 4]) -> (i64, i64) {
    let [dx1, dy1, dx2, dy2] = d;
    let (d1, o1) = a[1].overflowing_sub(a[0]);
    let (d2, o2) = a[2].overflowing_sub(a[0]);
    if o1 | o2 {
        return numerators64(a, d);
    }
    // Each product below 2^31·2^22: the differences fit an i64. Offsets
    // within an i16 (triangles under 2048 pixels at 4 subpixel bits) take
    // the cheaper exact product on ARMv6-M (elsewhere a long multiply is
    // one instruction: no check).
    if NO_LONG_MUL && fits_i16(dx1) && fits_i16(dy1) && fits_i16(dx2) && fits_i16(dy2) {
        return (
            mul_i32_i16(d1, dy2) - mul_i32_i16(d2, dy1),
            mul_i32_i16(d2, dx1) - mul_i32_i16(d1, dx2),
        );
    }
    (wmul(d1, dy2) - wmul(d2, dy1), wmul(d2, dx1) - wmul(d1, dx2))
}

/// `a0 + round((gx·ox + gy·oy) / S)` from the 64-bit sum, wrapping.
#[inline(always)]
fn anchor64(a0: i32, gx: i64, gy: i64, ox: i32, oy: i32, sub: SubpixelBits) -> i32 {
    // The sum fits i64 (see the module limits); wrapping arithmetic
    // computes it exactly even when a product alone would not fit.
    let t = gx
        .wrapping_mul(ox as i64)
        .wrapping_add(gy.wrapping_mul(oy as i64));
    let s = sub.get();
    a0.wrapping_add((t.wrapping_add(1 << (s - 1)) >> s) as i32)
}

/// [`Lerp::origin`] for `i32` from one 64-bit sum: `a0 + round((gx·(S/2 -
/// x0) + gy·(S/2 - y0)) / S)` (wrapping). The same value as the anchor
/// `anchor64(ox, oy)` at pixel `(ia, ja)` stepped back by `ia·gx + ja·gy`:
/// the two sums differ by `S·(ia·gx + ja·gy)` exactly, so their rounded
/// quotients by `S` differ by `ia·gx + ja·gy`; and the low 32 bits of
/// `t >> s` depend only on `t` modulo `2^(32 + s)`, which wrapping `i64`
/// arithmetic keeps (`32 + s <= 64`), whatever the magnitudes. Tested
/// equal on random and extreme values.
#[inline(always)]
fn origin64(a0: i32, gx: i64, gy: i64, x0: i32, y0: i32, sub: SubpixelBits) -> i32 {
    let s = sub.get();
    let h = 1i64 << (s - 1);
    let t = gx
        .wrapping_mul(h - x0 as i64)
        .wrapping_add(gy.wrapping_mul(h - y0 as i64))
        .wrapping_add(h);
    a0.wrapping_add((t >> s) as i32)
}

/// [`anchor64`] in 32-bit arithmetic for offsets within a pixel (`|o| <=
/// S`; others take [`anchor64`]): with `g = gh·S + gl` (`0 <= gl < S`),
/// `floor(t / S) = gh·ox + gyh·oy + floor((gl·ox + gyl·oy + S/2) / S)`
/// exactly, and of it only the low 32 bits are kept, for which the low 32
/// bits of `gh` (bits `s..s+31` of `g`) suffice. The same value, whatever
/// the magnitudes.
#[inline(always)]
fn anchor32(a0: i32, gx: i64, gy: i64, ox: i32, oy: i32, sub: SubpixelBits) -> i32 {
    let s = sub.get();
    let lim = sub.scale().unsigned_abs();
    if ox.unsigned_abs() > lim || oy.unsigned_abs() > lim {
        return anchor64(a0, gx, gy, ox, oy, sub);
    }
    let mask = (1u32 << s) - 1;
    let (gxh, gyh) = (
        shr64(gx as u64, s) as u32 as i32,
        shr64(gy as u64, s) as u32 as i32,
    );
    let (gxl, gyl) = ((gx as u32 & mask) as i32, (gy as u32 & mask) as i32);
    let low = (gxl * ox + gyl * oy + (1 << (s - 1))) >> s;
    a0.wrapping_add(gxh.wrapping_mul(ox))
        .wrapping_add(gyh.wrapping_mul(oy))
        .wrapping_add(low)
}

impl Lerp for i32 {
    const EXACT_STEPS: bool = true;
    const ZERO: i32 = 0;
    type Grad = i64;
    type Setup = InvArea;

    #[inline]
    fn setup(area2: i64) -> InvArea {
        InvArea::new(area2)
    }

    #[inline]
    fn gradients(a: [i32; 3], d: [i32; 4], r: &InvArea, sub: SubpixelBits) -> (i64, i64) {
        // On ARM 32 × 32 → 64-bit products (one `smull` each on ARMv7-M,
        // the exact 16-bit helper on ARMv6-M); 64-bit products on 64-bit
        // hosts. The same values.
        let (nx, ny) = if cfg!(target_arch = "arm") {
            numerators32(a, d)
        } else {
            numerators64(a, d)
        };
        let s = sub.get();
        (r.quot(nx, s), r.quot(ny, s))
    }

    #[inline]
    fn anchor(a0: i32, gx: i64, gy: i64, ox: i32, oy: i32, sub: SubpixelBits) -> i32 {
        if NO_LONG_MUL {
            anchor32(a0, gx, gy, ox, oy, sub)
        } else {
            anchor64(a0, gx, gy, ox, oy, sub)
        }
    }

    #[inline]
    fn step(g: i64) -> i32 {
        g as i32
    }

    #[inline(always)]
    fn origin(a0: i32, gx: i64, gy: i64, x0: i32, y0: i32, sub: SubpixelBits) -> i32 {
        if NO_LONG_MUL {
            // Two 64-bit products would be library calls: the anchor's
            // 32-bit form, stepped back.
            let s = sub.scale();
            let (ia, ja) = (x0 >> sub.get(), y0 >> sub.get());
            let (ox, oy) = (ia * s + s / 2 - x0, ja * s + s / 2 - y0);
            anchor32(a0, gx, gy, ox, oy, sub)
                .wrapping_sub((gx as i32).wrapping_mul(ia))
                .wrapping_sub((gy as i32).wrapping_mul(ja))
        } else {
            origin64(a0, gx, gy, x0, y0, sub)
        }
    }

    #[inline]
    fn add_n(self, step: i32, n: i32) -> i32 {
        self.wrapping_add(step.wrapping_mul(n))
    }

    #[inline(always)]
    fn add(self, step: i32) -> i32 {
        self.wrapping_add(step)
    }

    #[inline(always)]
    fn depth30(self) -> u32 {
        self.clamp(0, DEPTH_ONE) as u32
    }

    #[inline(always)]
    fn fixed_grad(g: i64) -> Option<i64> {
        Some(g)
    }

    #[inline(always)]
    fn round_int(self, frac: u32) -> i32 {
        if frac == 0 || frac > 31 {
            return self;
        }
        // 32-bit: values at covered pixels lie within ±2^30 (plus the
        // interpolation error), so adding half a unit cannot wrap; a
        // wrapped value elsewhere is never used (see the module docs).
        self.wrapping_add(1 << (frac - 1)) >> frac
    }

    type Unweight = i64;

    #[inline(always)]
    fn fixed_raw(self) -> Option<i32> {
        Some(self)
    }

    #[inline(always)]
    fn from_fixed_raw(v: i32) -> i32 {
        v
    }

    #[inline(always)]
    fn fixed_slots<const V: usize>(v: &mut [[i32; 3]; V]) -> Option<&mut [[i32; 3]; V]> {
        Some(v)
    }

    #[inline]
    fn unweight_factor(q: i32) -> i64 {
        // 2^60 / q, q >= 2^10: at most 2^50.
        (1i64 << 60) / q.max(1 << 10) as i64
    }

    #[inline]
    fn unweight(self, f: i64) -> i32 {
        // a·q/2^30 · 2^60/q / 2^30 = a; |a·q| <= 2^30·q keeps the product
        // within 2^60.
        let v = (self as i64).saturating_mul(f).saturating_add(1 << 29) >> 30;
        v.clamp(i32::MIN as i64, i32::MAX as i64) as i32
    }
}

macro_rules! float_lerp {
    ($t:ty) => {
        impl Lerp for $t {
            const EXACT_STEPS: bool = false;
            const ZERO: $t = 0.0;
            type Grad = $t;
            type Setup = $t;

            fn setup(area2: i64) -> $t {
                1.0 / (area2 as $t)
            }

            #[inline]
            fn gradients(a: [$t; 3], d: [i32; 4], inv: &$t, sub: SubpixelBits) -> ($t, $t) {
                let d1 = a[1] - a[0];
                let d2 = a[2] - a[0];
                let [dx1, dy1, dx2, dy2] = d.map(|v| v as $t);
                let s = sub.scale() as $t * *inv;
                ((d1 * dy2 - d2 * dy1) * s, (d2 * dx1 - d1 * dx2) * s)
            }

            #[inline]
            fn anchor(a0: $t, gx: $t, gy: $t, ox: i32, oy: i32, sub: SubpixelBits) -> $t {
                let inv_s = 1.0 / sub.scale() as $t;
                a0 + (gx * ox as $t + gy * oy as $t) * inv_s
            }

            #[inline]
            fn step(g: $t) -> $t {
                g
            }

            #[inline]
            fn add_n(self, step: $t, n: i32) -> $t {
                self + step * n as $t
            }

            #[inline(always)]
            fn add(self, step: $t) -> $t {
                self + step
            }

            #[inline]
            fn depth30(self) -> u32 {
                // `as` saturates and maps NaN to 0.
                let v = self * (1u32 << 30) as $t + 0.5;
                (v as u32).min(1 << 30)
            }

            type Unweight = $t;

            #[inline]
            fn from_fixed_raw(v: i32) -> $t {
                v as $t
            }

            #[inline]
            fn unweight_factor(q: $t) -> $t {
                if q > 0.0 {
                    1.0 / q
                } else {
                    0.0
                }
            }

            #[inline]
            fn unweight(self, f: $t) -> $t {
                self * f
            }

            #[inline]
            fn round_int(self, _frac: u32) -> i32 {
                // Round half up; `as` saturates and maps NaN to 0 (below
                // i32::MIN, `t` is already i32::MIN: saturate, no overflow).
                let v = self + 0.5;
                let t = v as i32;
                if (t as $t) > v {
                    t.saturating_sub(1)
                } else {
                    t
                }
            }
        }
    };
}

float_lerp!(f32);
float_lerp!(f64);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn origin_from_one_sum_equals_the_anchor_stepped_back() {
        let mut g = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            g ^= g << 13;
            g ^= g >> 7;
            g ^= g << 17;
            g
        };
        let lim = 1i32 << 21;
        for s in 1..=8u32 {
            let sub = SubpixelBits::new(s).unwrap();
            for i in 0..20_000 {
                let r = next();
                let gx = (r as i64) >> (r % 60);
                let gy = (r.rotate_left(29) as i64) >> (r.rotate_left(7) % 60);
                let a0 = next() as i32;
                let (x0, y0) = match i % 4 {
                    0 => (lim, -lim),
                    1 => (-lim, lim - 1),
                    _ => ((next() as i32) % lim, (next() as i32) % lim),
                };
                let sc = sub.scale();
                let (ia, ja) = (x0 >> s, y0 >> s);
                let (ox, oy) = (ia * sc + sc / 2 - x0, ja * sc + sc / 2 - y0);
                let want = anchor64(a0, gx, gy, ox, oy, sub)
                    .wrapping_sub((gx as i32).wrapping_mul(ia))
                    .wrapping_sub((gy as i32).wrapping_mul(ja));
                assert_eq!(
                    origin64(a0, gx, gy, x0, y0, sub),
                    want,
                    "{gx} {gy} {x0} {y0} {s}"
                );
                assert_eq!(<i32 as Lerp>::origin(a0, gx, gy, x0, y0, sub), want);
            }
        }
    }

    #[test]
    fn anchor_in_32_bits_equals_the_64_bit_sum() {
        for s in 1..=8u32 {
            let sub = SubpixelBits::new(s).unwrap();
            let half = 1i64 << (s - 1);
            let sc = 1i32 << s;
            let mut g = 0x1234_5678_9abc_def1u64;
            for _ in 0..4000 {
                g ^= g << 13;
                g ^= g >> 7;
                g ^= g << 17;
                let gx = (g as i64) >> (g % 40);
                let gy = ((g.rotate_left(23)) as i64) >> (g % 50);
                let a0 = g.rotate_left(7) as i32;
                for (ox, oy) in [
                    (0, 0),
                    (sc / 2, -sc / 2 + 1),
                    (-sc, sc),
                    (3, -1),
                    (sc + 1, 2),
                ] {
                    let t = gx
                        .wrapping_mul(ox as i64)
                        .wrapping_add(gy.wrapping_mul(oy as i64));
                    let want = a0.wrapping_add((t.wrapping_add(half) >> s) as i32);
                    assert_eq!(anchor64(a0, gx, gy, ox, oy, sub), want);
                    assert_eq!(anchor32(a0, gx, gy, ox, oy, sub), want);
                }
            }
        }
    }

    #[test]
    fn float_rounding_and_depth_saturate() {
        assert_eq!(2.5f64.round_int(0), 3);
        assert_eq!((-2.5f64).round_int(0), -2);
        assert_eq!((-2.6f32).round_int(0), -3);
        assert_eq!(f64::NAN.round_int(0), 0);
        // Below i32::MIN: saturates (was an overflow, found by fuzzing).
        assert_eq!(f64::NEG_INFINITY.round_int(0), i32::MIN);
        assert_eq!((-3.0e9f32).round_int(0), i32::MIN);
        assert_eq!(f32::INFINITY.round_int(0), i32::MAX);
        assert_eq!(f64::NAN.depth30(), 0);
        assert_eq!(2.0f64.depth30(), 1 << 30);
        assert_eq!((-1.0f32).depth30(), 0);
        assert_eq!(0.5f64.depth30(), 1 << 29);
        assert_eq!((5i32 << 16).round_int(16), 5);
        assert_eq!(((5i32 << 16) + (1 << 15)).round_int(16), 6);
        assert_eq!((-7i32).depth30(), 0);
        assert_eq!(i32::MAX.depth30(), 1 << 30);
    }
}
