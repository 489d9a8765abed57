//! Edge-case tests for all four [`Real`] types: saturation, bad inputs,
//! conversions and the constant constructors. Runs in debug, so any integer
//! overflow would panic here.

extern crate std;

use super::{Real, Q16, Q32};

/// Checks shared by all implementations.
fn common<R: Real>() {
    let f = R::from_f64;
    let close = |a: R, b: f64| (a.to_f64() - b).abs() <= 1e-4 * b.abs().max(1.0);
    assert_eq!(R::from_f32(f32::NAN), R::ZERO);
    assert_eq!(R::from_f64(f64::NAN), R::ZERO);
    assert_eq!(R::from_f64(f64::INFINITY), R::MAX);
    assert_eq!(R::from_f64(f64::NEG_INFINITY), R::MIN);
    assert_eq!(R::from_f32(f32::INFINITY), R::MAX);
    assert!(close(R::from_i32(-7), -7.0));
    assert!(close(R::from_ratio(1, 3), 1.0 / 3.0));
    assert!(close(R::from_ratio(-2, 3), -2.0 / 3.0));
    assert_eq!(R::from_ratio(5, 0), R::MAX);
    assert_eq!(R::from_ratio(-5, 0), R::MIN);
    assert_eq!(R::from_ratio(0, 0), R::ZERO);
    assert_eq!(f(2.0).div(R::ZERO), R::MAX);
    assert_eq!(f(-2.0).div(R::ZERO), R::MIN);
    assert_eq!(R::ZERO.div(R::ZERO), R::ZERO);
    assert_eq!(R::ZERO.recip(), R::MAX);
    assert!(close(f(3.0).div(f(-4.0)), -0.75));
    assert!(close(f(4.0).recip(), 0.25));
    assert_eq!(R::MAX.div(R::EPSILON), R::MAX);
    assert_eq!(R::MIN.div(R::EPSILON), R::MIN);
    // Roots of bad inputs are defined.
    assert_eq!(R::ZERO.rsqrt(), R::ZERO);
    assert_eq!(f(-1.0).rsqrt(), R::ZERO);
    assert_eq!(R::MIN.rsqrt(), R::ZERO);
    assert_eq!(f(-4.0).sqrt(), R::ZERO);
    assert_eq!(R::ZERO.sqrt(), R::ZERO);
    assert!(close(f(4.0).rsqrt(), 0.5));
    assert!(close(f(2.0).sqrt(), core::f64::consts::SQRT_2));
    assert!(R::MAX.rsqrt() > R::ZERO);
    assert!(R::EPSILON.rsqrt() > R::ONE);
    // powf domain edges.
    assert_eq!(R::ZERO.powf(R::ZERO), R::ONE);
    assert_eq!(R::ZERO.powf(f(2.0)), R::ZERO);
    assert_eq!(f(-0.5).powf(f(2.0)), R::ZERO);
    assert_eq!(R::ONE.powf(f(1e4)), R::ONE);
    assert_eq!(f(3.0).powf(f(2.0)), R::ONE);
    assert_eq!(f(0.5).powf(f(-2.0)), R::ONE);
    assert_eq!(f(0.5).powf(R::MAX), R::ZERO);
    assert!(close(f(0.5).powf(R::ONE), 0.5));
    assert!(close(f(0.25).powf(f(0.5)), 0.5));
    assert!(R::EPSILON.powf(R::EPSILON) > f(0.99));
    // Saturating and elementary operations.
    assert!(close(f(1.5) * f(-2.0), -3.0));
    assert!(close(f(1.5).mul_i32(-3), -4.5));
    assert!(close(f(-3.0).half(), -1.5));
    assert_eq!(f(-3.0).abs(), f(3.0));
    assert_eq!(f(2.0).clamp(R::ZERO, R::ONE), R::ONE);
    assert_eq!(f(-2.0).clamp(R::ZERO, R::ONE), R::ZERO);
    assert_eq!(f(0.5).clamp(R::ONE, R::ZERO), R::ZERO);
    assert_eq!(f(0.5).min(R::ONE), f(0.5));
    assert_eq!(f(0.5).max(R::ONE), R::ONE);
    let mut a = R::ONE;
    a += R::ONE;
    a *= f(3.0);
    a -= f(0.5);
    assert!(close(a, 5.5));
    // Levels.
    assert_eq!(f(-1.0).to_level(), 0);
    assert_eq!(f(2.0).to_level(), 255);
    assert_eq!(f(0.5).to_level(), 128);
    assert_eq!(R::ONE.to_level(), 255);
    assert_eq!(R::MIN.to_level(), 0);
    assert_eq!(R::MAX.to_level(), 255);
    // Fixed-point raw conversions.
    assert_eq!(f(1.5).to_fixed_i32(4), 24);
    assert_eq!(f(-1.75).to_fixed_i32(0), -2);
    assert_eq!(f(-1.25).to_fixed_i32(0), -1);
    assert_eq!(f(0.75).to_fixed_i32(30), 3 << 28);
    assert_eq!(f(0.75).to_fixed_i32(99), 3 << 28);
    assert_eq!(R::MAX.to_fixed_i32(30), i32::MAX);
    assert_eq!(R::MIN.to_fixed_i32(30), i32::MIN);
    assert_eq!(R::from_fixed_i32(24, 4), f(1.5));
    assert_eq!(R::from_fixed_i32(3 << 28, 30), f(0.75));
    assert!(
        close(R::from_fixed_i32(i32::MAX, 0), f64::from(i32::MAX))
            || R::from_fixed_i32(i32::MAX, 0) == R::MAX
    );
    // sin/cos at special angles.
    let (s, c) = f(core::f64::consts::FRAC_PI_2).sin_cos();
    assert!(close(s, 1.0) && close(c, 0.0));
    let (s, c) = f(-core::f64::consts::PI).sin_cos();
    assert!(close(s, 0.0) && close(c, -1.0));
    let _ = R::MAX.sin_cos();
    let _ = R::MIN.sin_cos();
}

/// Checks for the saturating fixed-point operators.
fn saturating<R: Real>() {
    assert_eq!(R::MAX + R::ONE, R::MAX);
    assert_eq!(R::MIN - R::ONE, R::MIN);
    assert_eq!(R::MAX * R::MAX, R::MAX);
    assert_eq!(R::MIN * R::MAX, R::MIN);
    assert_eq!(R::MIN * R::MIN, R::MAX);
    assert_eq!(-R::MIN, R::MAX);
    assert_eq!(R::MIN.abs(), R::MAX);
    assert_eq!(R::MAX.mul_i32(i32::MAX), R::MAX);
    assert_eq!(R::MAX.mul_i32(i32::MIN), R::MIN);
    assert_eq!(R::MAX.div(R::EPSILON), R::MAX);
    assert_eq!(R::EPSILON.recip(), R::MAX);
    assert_eq!(R::from_f64(1e300), R::MAX);
    assert_eq!(
        R::from_fixed_i32(i32::MIN, 0).to_f64(),
        R::from_i32(i32::MIN).to_f64()
    );
    // One ulp: the smallest positive value.
    assert_eq!(R::EPSILON.half(), R::ZERO);
    assert_eq!((-R::EPSILON).half(), R::ZERO);
    assert_eq!(R::EPSILON * R::EPSILON, R::ZERO);
    assert_eq!(R::EPSILON.sqrt() * R::EPSILON.sqrt(), R::EPSILON);
}

#[test]
fn q16_edges() {
    common::<Q16>();
    saturating::<Q16>();
    assert_eq!(Q16::EPSILON.rsqrt(), Q16::from_i32(256));
    assert_eq!(Q16::from_f64(0.5 / 65536.0), Q16::EPSILON);
    assert_eq!(Q16::from_f32(-1.5 / 65536.0), Q16::from_bits(-2));
    assert_eq!(Q16::from_i32(40_000), Q16::MAX);
    assert_eq!(Q16::from_i32(i32::MIN), Q16::MIN);
    assert_eq!(Q16::from_ratio(2, 3).to_bits(), 43_691);
    assert_eq!(Q16::from_ratio(-2, 3).to_bits(), -43_691);
    assert_eq!(Q16::from_fixed_i32(3, 17).to_bits(), 2);
    assert_eq!(Q16::MAX.to_fixed_i32(16), i32::MAX);
}

#[test]
fn q32_edges() {
    common::<Q32>();
    saturating::<Q32>();
    assert_eq!(Q32::EPSILON.rsqrt(), Q32::from_i32(65_536));
    assert_eq!(Q32::from_ratio(2, 3).to_bits(), 2_863_311_531);
    assert_eq!(
        Q32::from_fixed_i32(i32::MAX, 0),
        Q32::from_bits(i64::from(i32::MAX) << 32)
    );
}

#[test]
fn float_edges() {
    common::<f32>();
    common::<f64>();
    assert_eq!(f32::from_f64(1e300), f32::MAX);
    assert_eq!(Real::sqrt(f32::INFINITY), f32::INFINITY);
    assert_eq!(f32::INFINITY.rsqrt(), 0.0);
    assert_eq!(f32::NAN.rsqrt(), 0.0);
    assert_eq!(Real::sqrt(f64::NAN), 0.0);
    assert_eq!(f32::NAN.to_level(), 0);
    assert_eq!(f32::NAN.to_fixed_i32(8), 0);
    assert_eq!(Real::powf(f32::NAN, 2.0), 0.0);
    assert_eq!(Real::powf(0.5f32, f32::NAN), 1.0);
    assert_eq!(Real::sin_cos(f32::NAN), (0.0, 1.0));
    assert_eq!(Real::sin_cos(f64::INFINITY), (0.0, 1.0));
    assert_eq!(f32::MAX.div(0.5), f32::MAX);
    assert_eq!(1.0f32.div(f32::NAN), 0.0);
    assert!(f32::from_bits(1).rsqrt() > 1e22);
}

/// Constants built with the `const fn` constructors.
const Q16_THIRD: Q16 = Q16::from_ratio_const(1, 3);
const Q16_SEVEN: Q16 = Q16::from_int_const(7);
const Q32_THIRD: Q32 = Q32::from_ratio_const(1, 3);
const Q32_SEVEN: Q32 = Q32::from_int_const(-7);

#[test]
fn const_constructors() {
    assert_eq!(Q16_THIRD.to_bits(), 21_845);
    assert_eq!(Q16_SEVEN.to_bits(), 7 << 16);
    assert_eq!(Q32_THIRD.to_bits(), 1_431_655_765);
    assert_eq!(Q32_SEVEN.to_bits(), -7 << 32);
    assert_eq!(Q16::from_bits(5).to_bits(), 5);
    assert_eq!(Q32::FRAC_BITS, 32);
    assert_eq!(Q16::from_fixed(Q16_SEVEN.to_fixed()), Q16_SEVEN);
}

/// Calls every method with `a` and `b`; results are only required to exist.
fn exercise<R: Real>(a: R, b: R) {
    let _ = (a + b, a - b, a * b, -a, a.abs(), a.min(b), a.max(b));
    let _ = (
        a.clamp(b, a),
        a.mul_i32(-77_777),
        a.half(),
        a.div(b),
        a.recip(),
    );
    let _ = (a.sqrt(), a.rsqrt(), a.powf(b), a.sin_cos(), a.to_level());
    let _ = (
        a.to_f32(),
        a.to_f64(),
        a.to_fixed_i32(0),
        a.to_fixed_i32(30),
    );
    let (s, c) = a.sin_cos();
    assert!(s.abs() <= R::ONE && c.abs() <= R::ONE);
    let p = a.powf(b);
    assert!(p >= R::ZERO && p <= R::ONE);
    assert!(a.rsqrt() >= R::ZERO && a.sqrt() >= R::ZERO);
}

#[test]
fn no_panic_on_any_bits() {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    let specials = [
        0u64,
        1,
        u64::MAX,
        1 << 63,
        (1 << 63) - 1,
        1 << 31,
        (1 << 31) - 1,
        1 << 32,
    ];
    for i in 0..100_000 {
        let (x, y) = if i < 64 {
            (specials[i % 8], specials[i / 8])
        } else {
            (next(), next())
        };
        let (x32, y32) = ((x >> 32) as u32, (y >> 32) as u32);
        let (ix, iy) = (
            i32::from_ne_bytes(x32.to_ne_bytes()),
            i32::from_ne_bytes(y32.to_ne_bytes()),
        );
        exercise(Q16::from_bits(ix), Q16::from_bits(iy));
        exercise(
            Q32::from_bits(i64::from_ne_bytes(x.to_ne_bytes())),
            Q32::from_bits(i64::from_ne_bytes(y.to_ne_bytes())),
        );
        let (fx, fy) = (f32::from_bits(x32), f32::from_bits(y32));
        let _ = (
            Q16::from_f32(fx),
            Q32::from_f32(fx),
            Q16::from_f64(f64::from_bits(x)),
        );
        let _ = (Q16::from_ratio(ix, iy), Q32::from_fixed_i32(iy, x32));
        if fx.is_finite() && fy.is_finite() {
            exercise(fx, fy);
            exercise(f64::from_bits(x), f64::from_bits(y));
        }
    }
}
