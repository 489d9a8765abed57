//! [`Real`] for the float twins `f32` and `f64`.
//!
//! `f64` uses `libm` throughout (correctly rounded `sqrt`, <= 1 ulp
//! elsewhere); its `rsqrt` is `1 / sqrt(x)`, two correctly rounded
//! operations, within 1.5 ulp (measured 1.47 ulp). `f32` takes the
//! `1/sqrt` *seed* from `micromath::F32Ext`
//! (the bit trick, measured 3.4% relative error) and refines it with three
//! Newton-Raphson steps (multiplications only, cheap on a Cortex-M4F FPU);
//! `sqrt` adds one Heron correction. micromath's own `sqrt`, `powf`,
//! `sin`/`cos` were measured too coarse for shading (5% for `sqrt`, 0.46
//! absolute for `powf` at large `n`, 1.1e-3 for `sin`/`cos`), so `f32`
//! `powf` and `sin_cos` use `libm` (`powf`, `sincosf`).
//!
//! Each bound is a constant next to its function (`F32_RSQRT_MAX_ERROR`,
//! …), which the tests at the bottom of this file check against `f64`.

use micromath::F32Ext;

use super::real::{GenericKernels, Real};

/// [`rsqrt_f32`]'s largest relative error: `2^-22` (measured `2^-22.44`).
#[cfg_attr(not(test), allow(dead_code))]
const F32_RSQRT_MAX_ERROR: f64 = 1.0 / 4_194_304.0;

/// [`sqrt_f32`]'s largest relative error: `2^-22` (measured `2^-22.6`).
#[cfg_attr(not(test), allow(dead_code))]
const F32_SQRT_MAX_ERROR: f64 = 1.0 / 4_194_304.0;

/// [`rsqrt_f64`]'s largest error in ulps of the result: 1.5 (measured
/// 1.47).
#[cfg_attr(not(test), allow(dead_code))]
const F64_RSQRT_MAX_ULPS: f64 = 1.5;

/// `f32` `powf` (`libm`)'s largest absolute error for `x` in `[0, 1]`:
/// `2^-23` (measured `2^-24.3`).
#[cfg_attr(not(test), allow(dead_code))]
const F32_POW_MAX_ERROR: f64 = 1.0 / 8_388_608.0;

/// `f64` `powf` (`libm`)'s largest absolute error for `x` in `[0, 1]`:
/// `2^-51` (measured `2^-53`).
#[cfg_attr(not(test), allow(dead_code))]
const F64_POW_MAX_ERROR: f64 = 1.0 / 2_251_799_813_685_248.0;

/// `f32` `sin_cos` (`libm` `sincosf`)'s largest absolute error: `2^-24`
/// (measured `2^-25`).
#[cfg_attr(not(test), allow(dead_code))]
const F32_SIN_COS_MAX_ERROR: f64 = 1.0 / 16_777_216.0;

/// `f64` `sin_cos` (`libm`)'s largest absolute error: `2^-52`.
#[cfg_attr(not(test), allow(dead_code))]
const F64_SIN_COS_MAX_ERROR: f64 = 1.0 / 4_503_599_627_370_496.0;

/// `1/sqrt(x)` for `f32` within [`F32_RSQRT_MAX_ERROR`], see the module
/// docs. `x <= 0`, NaN, `+inf` give 0.
fn rsqrt_f32(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 || x == f32::INFINITY {
        return 0.0;
    }
    if x < f32::MIN_POSITIVE {
        // Subnormal: the bit-trick seed needs a normal exponent.
        return rsqrt_f32(x * 18_446_744_073_709_551_616.0) * 4_294_967_296.0;
    }
    let mut y = F32Ext::invsqrt(x);
    for _ in 0..3 {
        y *= 1.5 - 0.5 * x * y * y;
    }
    y
}

/// `sqrt(x)` for `f32`: `x * rsqrt(x)` plus one Heron correction, within
/// [`F32_SQRT_MAX_ERROR`].
fn sqrt_f32(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if x == f32::INFINITY {
        return x;
    }
    let y = rsqrt_f32(x);
    let s = x * y;
    s + 0.5 * y * (x - s * s)
}

/// `1/sqrt(x)` for `f64`, within [`F64_RSQRT_MAX_ULPS`] ulp (see the
/// module docs). `x <= 0`,
/// NaN, `+inf` give 0.
fn rsqrt_f64(x: f64) -> f64 {
    if x > 0.0 {
        1.0 / libm::sqrt(x)
    } else {
        0.0
    }
}

/// `sqrt(x)` for `f64`; negative input and NaN give 0.
fn sqrt_f64(x: f64) -> f64 {
    if x > 0.0 {
        libm::sqrt(x)
    } else {
        0.0
    }
}

macro_rules! float_real {
    (
        $t:ident, $narrow:expr, $widen:expr, $to32:expr,
        $round:path, $abs:path, $sqrt:ident, $rsqrt:ident, $pow:path, $sincos:path
    ) => {
        impl Real for $t {
            type Kernels = GenericKernels;
            const ZERO: Self = 0.0;
            const ONE: Self = 1.0;
            const MAX: Self = $t::MAX;
            const MIN: Self = $t::MIN;
            const EPSILON: Self = $t::EPSILON;

            fn from_f32(v: f32) -> Self {
                Self::from_f64(f64::from(v))
            }
            fn from_f64(v: f64) -> Self {
                let v: $t = $narrow(v);
                if v.is_nan() {
                    0.0
                } else {
                    v.clamp($t::MIN, $t::MAX)
                }
            }
            fn from_i32(v: i32) -> Self {
                v as $t
            }
            fn from_ratio(num: i32, den: i32) -> Self {
                Self::from_f64(f64::from(num)).div(Self::from_f64(f64::from(den)))
            }
            fn to_f32(self) -> f32 {
                $to32(self)
            }
            fn to_f64(self) -> f64 {
                $widen(self)
            }
            fn to_fixed_i32(self, frac: u32) -> i32 {
                let frac = frac.min(30);
                $round(self * (1u32 << frac) as $t) as i32
            }
            fn from_fixed_i32(raw: i32, frac: u32) -> Self {
                let frac = frac.min(30);
                raw as $t * (1.0 / (1u32 << frac) as $t)
            }
            fn abs(self) -> Self {
                $abs(self)
            }
            fn min(self, o: Self) -> Self {
                $t::min(self, o)
            }
            fn max(self, o: Self) -> Self {
                $t::max(self, o)
            }
            fn clamp(self, lo: Self, hi: Self) -> Self {
                $t::min($t::max(self, lo), hi)
            }
            fn mul_i32(self, k: i32) -> Self {
                self * k as $t
            }
            fn half(self) -> Self {
                self * 0.5
            }
            fn div(self, d: Self) -> Self {
                if d == 0.0 {
                    return if self > 0.0 {
                        $t::MAX
                    } else if self < 0.0 {
                        $t::MIN
                    } else {
                        0.0
                    };
                }
                let q = self / d;
                if q.is_nan() {
                    0.0
                } else {
                    q.clamp($t::MIN, $t::MAX)
                }
            }
            fn recip(self) -> Self {
                Self::ONE.div(self)
            }
            fn sqrt(self) -> Self {
                $sqrt(self)
            }
            fn rsqrt(self) -> Self {
                $rsqrt(self)
            }
            fn powf(self, n: Self) -> Self {
                if n.is_nan() || n <= 0.0 || self >= 1.0 {
                    1.0
                } else if self.is_nan() || self <= 0.0 {
                    0.0
                } else {
                    $pow(self, n)
                }
            }
            fn sin_cos(self) -> (Self, Self) {
                if self.is_finite() {
                    $sincos(self)
                } else {
                    (0.0, 1.0)
                }
            }
            fn to_level(self) -> u8 {
                (Real::clamp(self, 0.0, 1.0) * 255.0 + 0.5) as u8
            }
        }
    };
}

/// `f64` to `f32`, rounding; out-of-range values become infinite.
fn narrow(v: f64) -> f32 {
    v as f32
}

float_real!(
    f32,
    narrow,
    f64::from,
    core::convert::identity,
    libm::roundf,
    libm::fabsf,
    sqrt_f32,
    rsqrt_f32,
    libm::powf,
    libm::sincosf
);
float_real!(
    f64,
    core::convert::identity,
    core::convert::identity,
    narrow,
    libm::round,
    libm::fabs,
    sqrt_f64,
    rsqrt_f64,
    libm::pow,
    libm::sincos
);

#[cfg(test)]
mod tests {
    extern crate std;

    use std::println;
    use std::vec::Vec;

    use super::super::testkit::{lg, near_one, pow_error, sin_cos_error, Rng};
    use super::*;

    #[test]
    fn f32_sqrt_rsqrt_within_max_error() {
        let mut rng = Rng(3);
        let (mut ws, mut wr) = (0f64, 0f64);
        for i in 0..400_000u32 {
            // Random positive finite f32 (all exponents, subnormals included).
            let bits = if i < 1000 {
                i + 1
            } else {
                (rng.next() >> 33) as u32 % 0x7f80_0000
            };
            let x = f32::from_bits(bits.max(1));
            let xs = f64::from(x);
            ws = ws.max((f64::from(Real::sqrt(x)) - xs.sqrt()).abs() / xs.sqrt());
            wr = wr.max((f64::from(x.rsqrt()) - 1.0 / xs.sqrt()).abs() * xs.sqrt());
        }
        println!("f32 sqrt rel 2^{:.2}, rsqrt rel 2^{:.2}", lg(ws), lg(wr));
        assert!(ws <= F32_SQRT_MAX_ERROR);
        assert!(wr <= F32_RSQRT_MAX_ERROR);
    }

    #[test]
    fn pow_within_max_error() {
        let xs: Vec<f32> = (0..=100_000)
            .map(|i| i as f32 / 100_000.0)
            .chain(near_one().map(|v| v as f32))
            .collect();
        let worst = pow_error(&xs);
        println!("f32 powf: abs error 2^{:.2}", lg(worst));
        assert!(worst <= F32_POW_MAX_ERROR);
        let xs: Vec<f64> = (0..=100_000)
            .map(|i| f64::from(i) / 100_000.0)
            .chain(near_one())
            .collect();
        let worst = pow_error(&xs);
        println!("f64 powf: abs error 2^{:.2}", lg(worst));
        assert!(worst <= F64_POW_MAX_ERROR);
    }

    #[test]
    fn sin_cos_within_max_error() {
        let worst = sin_cos_error((-200_000..200_000).map(|i| i as f32 * 1e-3));
        println!("f32 sin_cos: abs error 2^{:.2}", lg(worst));
        assert!(worst <= F32_SIN_COS_MAX_ERROR);
        let worst = sin_cos_error((-200_000..200_000).map(|i| f64::from(i) * 1e-3));
        assert!(worst <= F64_SIN_COS_MAX_ERROR);
    }

    /// The `f64` reciprocal square root (`1 / sqrt(x)`, two correctly rounded
    /// operations) within 1.5 ulp of the exact value, as the module docs of
    /// `num::float` state (the division's ½ ulp plus the square root's
    /// relative 2^-53, which is up to 1 ulp of the result): checked against the residual `1 - x·y²` computed
    /// with exact products (fused multiply-adds), over random normal `x` of
    /// every exponent whose result stays normal.
    #[test]
    fn rsqrt_f64_within_one_and_a_half_ulp() {
        let mut rng = Rng(11);
        let mut worst = 0f64;
        for i in 0..400_000u32 {
            // Exponents -1000..1000, random mantissas; the first ones exact
            // powers of two and their neighbours.
            let x = if i < 64 {
                f64::from_bits((1023 + u64::from(i) - 32) << 52)
                    * if i % 2 == 0 { 1.0 } else { 1.0 + f64::EPSILON }
            } else {
                let e = (rng.next() % 2000) as i64 - 1000;
                let m = rng.next() >> 12;
                f64::from_bits((((1023 + e) as u64) << 52) | m)
            };
            let y = Real::rsqrt(x);
            // y² = a + a_lo and x·a = b + b_lo exactly, so 1 - x·y² = (1 - b) -
            // b_lo - x·a_lo, with 1 - b exact (b is within a few ulps of 1).
            let a = y * y;
            let a_lo = y.mul_add(y, -a);
            let b = x * a;
            let b_lo = x.mul_add(a, -b);
            let d = (1.0 - b) - b_lo - x * a_lo;
            // The exact r = y·(1 - d)^(-1/2) = y·(1 + d/2 + O(d²)).
            let ulp = f64::from_bits(y.to_bits() + 1) - y;
            let err = (y * d / 2.0).abs() / ulp;
            assert!(err <= F64_RSQRT_MAX_ULPS, "rsqrt({x:e}) = {y:e}: {err} ulp");
            worst = worst.max(err);
        }
        println!("f64 rsqrt: {worst:.3} ulp");
        // Measured 1.47 ulp: above 1, so "1 ulp" would be a wrong claim.
        assert!(worst > 1.0, "the check measures something: {worst}");
    }
}
