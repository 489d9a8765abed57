//! Saturating fixed-point newtypes [`Q16`] and [`Q32`] implementing
//! [`Real`].
//!
//! The `fixed` crate's operators panic on overflow in debug builds; these
//! wrappers saturate instead, round products to nearest, and route the
//! transcendental functions to the integer kernels in `approx16` and
//! `approx32`.

use core::ops::{Add, AddAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use fixed::types::{I16F16, I32F32};

use super::real::{GenericKernels, Q16Kernels, Real};
use super::wide::{wmul, wmul64};
use super::{approx16, approx32};

macro_rules! fixed_real {
    (
        $(#[$doc:meta])*
        $name:ident, $fixed:ty, $raw:ty, $wide:ty, $frac:expr, $approx:ident, $wmul:path, $kern:ty
    ) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
        pub struct $name($fixed);

        impl $name {
            /// Number of fraction bits.
            pub const FRAC_BITS: u32 = $frac;

            /// Value with the given raw bits (`bits / 2^FRAC_BITS`).
            pub const fn from_bits(bits: $raw) -> Self {
                Self(<$fixed>::from_bits(bits))
            }

            /// Raw bits (`value * 2^FRAC_BITS`).
            pub const fn to_bits(self) -> $raw {
                self.0.to_bits()
            }

            /// Wraps a `fixed` value.
            pub const fn from_fixed(v: $fixed) -> Self {
                Self(v)
            }

            /// The wrapped `fixed` value.
            pub const fn to_fixed(self) -> $fixed {
                self.0
            }

            /// Saturates a wide intermediate to the raw range.
            const fn sat(w: $wide) -> Self {
                if w > <$raw>::MAX as $wide {
                    Self::from_bits(<$raw>::MAX)
                } else if w < <$raw>::MIN as $wide {
                    Self::from_bits(<$raw>::MIN)
                } else {
                    Self::from_bits(w as $raw)
                }
            }

            /// `n / d` for a pre-scaled numerator, rounded to nearest (ties
            /// away from zero), saturated; `d == 0` saturates by the sign of
            /// `n` (`0/0 = 0`).
            #[allow(clippy::cast_possible_wrap)] // q <= |n| fits in $wide
            const fn div_round(n: $wide, d: $wide) -> Self {
                if d == 0 {
                    return Self::sat(if n > 0 { <$wide>::MAX } else if n < 0 { <$wide>::MIN } else { 0 });
                }
                let (nu, du) = (n.unsigned_abs(), d.unsigned_abs());
                let mut q = nu / du;
                if nu % du >= du - du / 2 {
                    q += 1;
                }
                let q = q as $wide;
                Self::sat(if (n < 0) != (d < 0) { -q } else { q })
            }

            /// Saturating conversion from an integer, usable in constants.
            pub const fn from_int_const(v: i32) -> Self {
                Self::sat((v as $wide) << $frac)
            }

            /// `num / den` rounded to nearest, usable in constants (same
            /// rules as [`Real::from_ratio`]).
            pub const fn from_ratio_const(num: i32, den: i32) -> Self {
                Self::div_round((num as $wide) << $frac, den as $wide)
            }

            /// A product `w` of two raw values rounded to nearest (ties up)
            /// and saturated: `sat(shr_round(w, FRAC_BITS))`, decided from
            /// the top bits. With `w' = w + 2^(FRAC-1)` (no overflow: `|w| <=
            /// 2^(2 BITS - 2)`), `floor(w' / 2^FRAC)` fits the raw type
            /// exactly when `w' >> (FRAC + BITS - 1)` is 0 or -1 (`w'` in
            /// `[-2^(BITS-1+FRAC), 2^(BITS-1+FRAC))`); one arithmetic shift
            /// of the high word instead of two wide comparisons.
            #[inline(always)]
            #[allow(clippy::cast_possible_truncation)] // |top| <= 2^(BITS/2 - 1)
            fn round_product(w: $wide) -> Self {
                let w = w + (1 << ($frac - 1));
                let top = (w >> ($frac + <$raw>::BITS - 1)) as $raw;
                if top == 0 || top == -1 {
                    Self::from_bits((w >> $frac) as $raw)
                } else if w < 0 {
                    Self::from_bits(<$raw>::MIN)
                } else {
                    Self::from_bits(<$raw>::MAX)
                }
            }

            /// Round-to-nearest right shift of a wide value (`s` in 1..=62).
            const fn shr_round(w: $wide, s: u32) -> $wide {
                ((w >> (s - 1)) + 1) >> 1
            }

            /// Saturating conversion from `f64` (NaN -> 0).
            fn from_float(v: f64) -> Self {
                let t = v * (1u64 << $frac) as f64;
                if t.is_nan() {
                    Self::from_bits(0)
                } else if t >= <$raw>::MAX as f64 {
                    Self::from_bits(<$raw>::MAX)
                } else if t <= <$raw>::MIN as f64 {
                    Self::from_bits(<$raw>::MIN)
                } else {
                    Self::from_bits(libm::round(t) as $raw)
                }
            }
        }

        impl Add for $name {
            type Output = Self;
            #[inline(always)]
            fn add(self, o: Self) -> Self {
                Self(self.0.saturating_add(o.0))
            }
        }
        impl Sub for $name {
            type Output = Self;
            #[inline(always)]
            fn sub(self, o: Self) -> Self {
                Self(self.0.saturating_sub(o.0))
            }
        }
        impl Mul for $name {
            type Output = Self;
            /// Product rounded to nearest (ties up), saturating.
            #[inline(always)]
            fn mul(self, o: Self) -> Self {
                Self::round_product($wmul(self.to_bits(), o.to_bits()))
            }
        }
        impl Neg for $name {
            type Output = Self;
            #[inline(always)]
            fn neg(self) -> Self {
                Self(self.0.saturating_neg())
            }
        }
        impl AddAssign for $name {
            fn add_assign(&mut self, o: Self) {
                *self = *self + o;
            }
        }
        impl SubAssign for $name {
            fn sub_assign(&mut self, o: Self) {
                *self = *self - o;
            }
        }
        impl MulAssign for $name {
            fn mul_assign(&mut self, o: Self) {
                *self = *self * o;
            }
        }

        impl Real for $name {
            const ZERO: Self = Self::from_bits(0);
            const ONE: Self = Self::from_bits(1 << $frac);
            const MAX: Self = Self::from_bits(<$raw>::MAX);
            const MIN: Self = Self::from_bits(<$raw>::MIN);
            const EPSILON: Self = Self::from_bits(1);
            type Kernels = $kern;

            fn from_f32(v: f32) -> Self {
                Self::from_float(f64::from(v))
            }
            fn from_f64(v: f64) -> Self {
                Self::from_float(v)
            }
            fn from_i32(v: i32) -> Self {
                Self::from_int_const(v)
            }
            fn from_ratio(num: i32, den: i32) -> Self {
                Self::from_ratio_const(num, den)
            }
            fn to_f32(self) -> f32 {
                self.to_bits() as f32 * (1.0 / (1u64 << $frac) as f32)
            }
            fn to_f64(self) -> f64 {
                self.to_bits() as f64 * (1.0 / (1u64 << $frac) as f64)
            }
            #[inline(always)]
            fn to_fixed_i32(self, frac: u32) -> i32 {
                let frac = if frac > 30 { 30 } else { frac };
                let w = self.to_bits() as $wide;
                let v = if frac >= $frac {
                    w << (frac - $frac)
                } else {
                    Self::shr_round(w, $frac - frac)
                };
                v.clamp(i32::MIN as $wide, i32::MAX as $wide) as i32
            }
            #[inline(always)]
            fn from_fixed_i32(raw: i32, frac: u32) -> Self {
                let frac = if frac > 30 { 30 } else { frac };
                let w = raw as $wide;
                if frac <= $frac {
                    Self::sat(w << ($frac - frac))
                } else {
                    Self::sat(Self::shr_round(w, frac - $frac))
                }
            }
            #[inline(always)]
            fn abs(self) -> Self {
                Self(self.0.saturating_abs())
            }
            #[inline(always)]
            fn min(self, o: Self) -> Self {
                Ord::min(self, o)
            }
            #[inline(always)]
            fn max(self, o: Self) -> Self {
                Ord::max(self, o)
            }
            #[inline(always)]
            fn clamp(self, lo: Self, hi: Self) -> Self {
                Ord::min(Ord::max(self, lo), hi)
            }
            #[inline(always)]
            fn mul_i32(self, k: i32) -> Self {
                Self::sat($wmul(self.to_bits(), k as $raw))
            }
            #[inline(always)]
            fn half(self) -> Self {
                Self::from_bits(self.to_bits() / 2)
            }
            fn div(self, d: Self) -> Self {
                Self::div_round((self.to_bits() as $wide) << $frac, d.to_bits() as $wide)
            }
            fn recip(self) -> Self {
                Self::ONE.div(self)
            }
            fn sqrt(self) -> Self {
                Self::from_bits($approx::sqrt(self.to_bits()))
            }
            fn rsqrt(self) -> Self {
                Self::from_bits($approx::rsqrt(self.to_bits()))
            }
            fn powf(self, n: Self) -> Self {
                Self::from_bits($approx::pow(self.to_bits(), n.to_bits()))
            }
            fn sin_cos(self) -> (Self, Self) {
                let (s, c) = $approx::sin_cos(self.to_bits());
                (Self::from_bits(s), Self::from_bits(c))
            }
            #[inline(always)]
            fn to_level(self) -> u8 {
                let v = self.to_bits().clamp(0, 1 << $frac) as $wide;
                ((v * 255 + (1 << ($frac - 1))) >> $frac) as u8
            }
        }
    };
}

fixed_real!(
    /// Q16.16 fixed point (`fixed::types::I16F16`), the `fast` profile for
    /// Cortex-M0: range `[-32768, 32768)`, resolution 2^-16. Operators
    /// saturate; per-pixel kernels stay mostly in 32-bit integers.
    Q16, I16F16, i32, i64, 16, approx16, wmul, Q16Kernels
);

fixed_real!(
    /// Q32.32 fixed point (`fixed::types::I32F32`), the `precise` profile:
    /// range `[-2^31, 2^31)`, resolution 2^-32. Operators saturate.
    Q32, I32F32, i64, i128, 32, approx32, wmul64, GenericKernels
);

#[cfg(test)]
mod tests {
    use super::{Q16, Q32};

    fn check16(a: i32, b: i32) {
        let w = i64::from(a) * i64::from(b);
        let want = Q16::sat(Q16::shr_round(w, 16));
        assert_eq!(Q16::round_product(w), want, "{a} * {b}");
        assert_eq!(Q16::from_bits(a) * Q16::from_bits(b), want, "{a} * {b}");
    }

    fn check32(a: i64, b: i64) {
        let w = i128::from(a) * i128::from(b);
        let want = Q32::sat(Q32::shr_round(w, 32));
        assert_eq!(Q32::round_product(w), want, "{a} * {b}");
        assert_eq!(Q32::from_bits(a) * Q32::from_bits(b), want, "{a} * {b}");
    }

    /// `round_product` (the operator `*`) equals the two-step
    /// `sat(shr_round(w))` on edge and random products, for both widths:
    /// around the rounding ties, the saturation thresholds (`|a b|` near
    /// `2^47` resp. `2^95`) and the extreme operands.
    #[test]
    fn round_product_matches_shift_then_saturate() {
        let edges32 = crate::num::testkit::EDGES_I32;
        for &a in &edges32 {
            for &b in &edges32 {
                check16(a, b);
            }
        }
        let edges64 = [
            0,
            1,
            -1,
            0x7FFF_FFFF,
            0x8000_0000,
            0xFFFF_FFFF,
            0x1_0000_0000,
            -0x1_0000_0000,
            i64::MAX,
            i64::MIN,
            i64::MIN + 1,
            0xB504_F333_F9DE,
            -0xB504_F333_F9DF,
        ];
        for &a in &edges64 {
            for &b in &edges64 {
                check32(a, b);
            }
        }
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        for _ in 0..200_000 {
            // Shifted by 0..=31 (resp. 63): small and large magnitudes.
            let (r, t) = (next(), next());
            check16(
                (r as i32) >> (t % 32),
                ((r >> 32) as i32) >> ((t >> 8) % 32),
            );
            check32(
                (r as i64) >> ((t >> 16) % 64),
                (t as i64) >> ((r >> 58) % 64),
            );
            // Products straddling the Q16 saturation threshold 2^47.
            let a = 0x00B5_0000 + (r % 0x2_0000) as i32;
            check16(a, a);
            check16(a, -a);
        }
    }
}
