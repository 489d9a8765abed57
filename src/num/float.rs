//! [`Real`] for the float twins `f32` and `f64`.
//!
//! `f64` uses `libm` throughout (correctly rounded `sqrt`, <= 1 ulp
//! elsewhere); its `rsqrt` is `1 / sqrt(x)`, two correctly rounded
//! operations, within 1.5 ulp (measured 1.47 ulp, see
//! `accuracy::rsqrt_f64_within_one_and_a_half_ulp`). `f32` takes the `1/sqrt` *seed* from `micromath::F32Ext`
//! (the bit trick, measured 3.4% relative error) and refines it with three
//! Newton-Raphson steps (multiplications only, cheap on a Cortex-M4F FPU);
//! `sqrt` adds one Heron correction. micromath's own `sqrt`, `powf`,
//! `sin`/`cos` were measured too coarse for shading (5% for `sqrt`, 0.46
//! absolute for `powf` at large `n`, 1.1e-3 for `sin`/`cos`), so `f32`
//! `powf` and `sin_cos` use `libm` (`powf`, `sincosf`).

use micromath::F32Ext;

use super::real::Real;

/// `1/sqrt(x)` for `f32`, see the module docs. `x <= 0`, NaN, `+inf` give 0.
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

/// `sqrt(x)` for `f32`: `x * rsqrt(x)` plus one Heron correction.
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

/// `1/sqrt(x)` for `f64`, within 1.5 ulp (see the module docs). `x <= 0`,
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
