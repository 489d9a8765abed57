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

use super::SubpixelBits;
use core::fmt::Debug;

/// A quantity the rasterizer interpolates: an `i32` fixed-point raw value,
/// or `f32`/`f64` for the float twins (same algorithm, no quantization).
pub trait Lerp: Copy + Debug + PartialEq + Default {
    /// A gradient per pixel, kept at full precision for pre-stepping.
    type Grad: Copy + Debug;

    /// `true` when `a + n·s` equals `n` additions of `s` exactly (integer
    /// arithmetic): the scanline loop then steps the left-edge values row
    /// by row. Floats round differently depending on where the sum
    /// started, so for them each row's start value is computed afresh from
    /// the anchor, and a band renders the very bytes of a full frame.
    const EXACT_STEPS: bool;
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

    /// `self + n · step` (whole steps).
    fn add_n(self, step: Self, n: i32) -> Self;

    /// `self + step`: the inner-loop operation.
    fn add(self, step: Self) -> Self;

    /// Depth as a 30-bit fraction (`0..=2^30`), saturating; the value is
    /// a fixed raw `d·2^30` or a float `d`.
    fn depth30(self) -> u32;

    /// Depth as stored in a 16-bit buffer: `min(depth30 >> 14, 65534)`
    /// (65535 is the cleared value, farther than every fragment).
    #[inline(always)]
    fn depth16(self) -> u16 {
        (self.depth30() >> 14).min(u16::MAX as u32 - 1) as u16
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
}

/// The reciprocal of a doubled triangle area in fixed point:
/// `1/|a| ≈ m · 2^-k`, `m` rounded to 32 significant bits.
///
/// Error: `a` is first truncated to 32 significant bits (relative error
/// < 2^-31) and `m` rounded (< 2^-32), and a numerator it multiplies is
/// truncated to 31 significant bits (< 2^-31): a product is within a
/// relative 2^-30 of the exact quotient, plus ½ of its last place from the
/// final rounding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Recip {
    m: u64,
    k: u32,
    negative: bool,
}

impl Recip {
    /// The reciprocal of `a` (`a != 0`; zero gives a reciprocal of 1/1
    /// rather than a panic, and the rasterizer never asks for it).
    pub fn new(a: i64) -> Self {
        let negative = a < 0;
        let mag = a.unsigned_abs().max(1);
        let n = 63 - mag.leading_zeros(); // 2^n <= mag < 2^(n+1)
        let norm = if n >= 31 {
            mag >> (n - 31)
        } else {
            mag << (31 - n)
        }; // in [2^31, 2^32)
        let m = ((1u64 << 63) + norm / 2) / norm.max(1 << 31); // in (2^31, 2^32]
        Self {
            m,
            k: 32 + n,
            negative,
        }
    }

    /// `round(num · 2^s / a)` within the error stated on [`Recip`];
    /// saturates at `i64` bounds.
    pub fn mul_shift(&self, num: i64, s: u32) -> i64 {
        if num == 0 {
            return 0;
        }
        let neg = (num < 0) != self.negative;
        let mag = num.unsigned_abs();
        let bits = 64 - mag.leading_zeros();
        let t = bits.saturating_sub(31);
        let p = (mag >> t) * self.m; // < 2^31 · 2^32
                                     // result = p · 2^(t + s - k)
        let up = t as i32 + s as i32 - self.k as i32;
        let r: u64 = if up >= 0 {
            if up >= 63 || p.leading_zeros() <= up as u32 {
                i64::MAX as u64
            } else {
                p << up
            }
        } else {
            let sh = (-up) as u32;
            if sh >= 64 {
                0
            } else {
                (p >> sh) + ((p >> (sh - 1)) & 1)
            }
        };
        let r = r.min(i64::MAX as u64) as i64;
        if neg {
            -r
        } else {
            r
        }
    }
}

impl Lerp for i32 {
    const EXACT_STEPS: bool = true;
    type Grad = i64;
    type Setup = Recip;

    fn setup(area2: i64) -> Recip {
        Recip::new(area2)
    }

    #[inline]
    fn gradients(a: [i32; 3], d: [i32; 4], r: &Recip, sub: SubpixelBits) -> (i64, i64) {
        let d1 = a[1] as i64 - a[0] as i64;
        let d2 = a[2] as i64 - a[0] as i64;
        let [dx1, dy1, dx2, dy2] = d.map(|v| v as i64);
        let nx = d1 * dy2 - d2 * dy1;
        let ny = d2 * dx1 - d1 * dx2;
        (r.mul_shift(nx, sub.get()), r.mul_shift(ny, sub.get()))
    }

    #[inline]
    fn anchor(a0: i32, gx: i64, gy: i64, ox: i32, oy: i32, sub: SubpixelBits) -> i32 {
        // The sum fits i64 (see the module limits); wrapping arithmetic
        // computes it exactly even when a product alone would not fit.
        let t = gx
            .wrapping_mul(ox as i64)
            .wrapping_add(gy.wrapping_mul(oy as i64));
        let s = sub.get();
        let half = 1i64 << (s - 1);
        a0.wrapping_add((t.wrapping_add(half) >> s) as i32)
    }

    #[inline]
    fn step(g: i64) -> i32 {
        g as i32
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
        self.clamp(0, super::DEPTH_ONE) as u32
    }

    #[inline(always)]
    fn depth16(self) -> u16 {
        // The same value as the default, with one clamp instead of two.
        (self >> 14).clamp(0, u16::MAX as i32 - 1) as u16
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
    fn recip_products_within_stated_error() {
        let areas = [
            1i64,
            2,
            3,
            7,
            255,
            4096,
            99_991,
            1 << 31,
            (1 << 45) - 3,
            -5,
            -123_456_789,
        ];
        let nums = [
            1i64,
            -1,
            3,
            1000,
            -77_777,
            1 << 40,
            (1 << 54) - 1,
            -(1 << 53) + 17,
        ];
        for &a in &areas {
            let r = Recip::new(a);
            for &n in &nums {
                for s in [0u32, 4, 8] {
                    let exact = (n as f64) * (1u64 << s) as f64 / a as f64;
                    if exact.abs() > 9.0e18 {
                        continue;
                    }
                    let got = r.mul_shift(n, s) as f64;
                    let bound = 0.5 + exact.abs() * (1.0 / (1u64 << 30) as f64) + 1e-6;
                    assert!(
                        (got - exact).abs() <= bound,
                        "a={a} n={n} s={s}: got {got}, exact {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn recip_exact_on_small_values() {
        // Quotients that are exact small integers come out exact.
        let r = Recip::new(-12);
        assert_eq!(r.mul_shift(24, 4), -32);
        assert_eq!(Recip::new(3).mul_shift(9, 0), 3);
        assert_eq!(Recip::new(1).mul_shift(-(1 << 40), 8), -(1 << 48));
        assert_eq!(Recip::new(0).mul_shift(5, 0), 5);
    }

    #[test]
    fn fast_depth16_equals_the_general_conversion() {
        use crate::target::{Depth16, DepthFormat};
        let mut z = i32::MIN;
        for _ in 0..200_000 {
            assert_eq!(z.depth16(), Depth16::from_d30(z.depth30()), "{z}");
            z = z.wrapping_add(21_467 + (z as u32 % 977) as i32);
        }
        for z in [
            -1,
            0,
            1,
            (1 << 14) - 1,
            1 << 14,
            (1 << 30) - (1 << 14),
            (1 << 30) - 1,
            1 << 30,
            i32::MAX,
        ] {
            assert_eq!(z.depth16(), Depth16::from_d30(z.depth30()), "{z}");
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
