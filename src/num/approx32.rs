//! Integer kernels behind the [`Q32`](super::Q32) approximations.
//!
//! All functions take and return raw Q32.32 bit patterns (`i64`, value =
//! bits / 2^32) and use no floating point and no division. Internal values
//! are mostly Q.62 in `i128`/`u128` (on a Cortex-M0 a 64x64 product is a
//! library call; this is the `precise` profile).
//!
//! - `rsqrt`: the Q16 table interpolation as a seed (2^-15.4 relative),
//!   then one Newton-Raphson step `y (3 - f y^2) / 2` in 128-bit products:
//!   1.5 * (2^-15.4)^2 = 2^-30.2 relative, plus the final rounding.
//! - `sqrt`: exact digit-by-digit integer square root, correctly rounded.
//! - `pow`: as for Q16 (`2^(-n * L)`, exact table reduction for `L`), with
//!   a degree-5 series for `ln(1 + r)` (|r| <= 2^-7, truncation 2^-35
//!   relative) and a degree-4 series for `2^-y` on 1/64 steps.
//! - `sin_cos`: reduction by 2/pi in Q0.64, quarter-wave table, Taylor
//!   correction to degree 5 (|h| <= pi/256, truncation < 2^-46).
//!
//! Each function's bound is a constant next to it, which the tests at the
//! bottom of this file check against `f64`.

use super::approx16::rsqrt_mant;
use super::tables::{EXP2, LOG_INV, LOG_T, SIN};

/// Q32 one.
const ONE: i64 = 1 << 32;

/// [`rsqrt`]'s largest relative error beyond the half-ulp rounding of its
/// output: `2^-30` (measured `2^-30.28`).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const RSQRT_MAX_ERROR: f64 = 1.0 / 1_073_741_824.0;

/// [`sqrt`]'s largest absolute error: half an ulp, `2^-33` (correctly
/// rounded).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const SQRT_MAX_ERROR: f64 = 1.0 / 8_589_934_592.0;

/// [`pow`]'s largest absolute error for `x` in `[0, 1]`, `n` up to 32767:
/// `2^-31` (measured `2^-32.99`, the output rounding).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const POW_MAX_ERROR: f64 = 1.0 / 2_147_483_648.0;

/// [`sin_cos`]'s largest absolute error over every angle: `2^-32`
/// (measured `2^-32.97`).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const SIN_COS_MAX_ERROR: f64 = 1.0 / 4_294_967_296.0;
/// Q.62 one.
const ONE62: i128 = 1 << 62;
/// `ln 2` in Q.62.
const LN2: u128 = 0x2c5c_85fd_f473_de6b;
/// `1 / ln 2` in Q.62.
const INV_LN2: i128 = 0x5c55_1d94_ae0b_f85e;
/// `pi / 2` in Q.62.
const HALF_PI: i128 = 0x6487_ed51_10b4_611a;
/// `2 / pi` in Q0.64.
const TWO_OVER_PI: i128 = 0xa2f9_836e_4e44_152a;

/// `1/5, 1/4, 1/3, 1/2, 1` in Q.62 (series for `ln(1 + r)`).
const LN_COEF: [i128; 5] = [ONE62 / 5, ONE62 / 4, ONE62 / 3, ONE62 / 2, ONE62];
/// `1/24, 1/6, 1/2, 1` in Q.62 (series for `e^-t`).
const EXP_COEF: [i128; 4] = [ONE62 / 24, ONE62 / 6, ONE62 / 2, ONE62];
/// `1/2, 1/24` in Q.62 (cosine series).
const COS_COEF: [i128; 2] = [ONE62 / 2, ONE62 / 24];
/// `1/6, 1/120` in Q.62 (sine series).
const SIN_COEF: [i128; 2] = [ONE62 / 6, ONE62 / 120];

/// `a * b` in Q.62.
fn mul62(a: i128, b: i128) -> i128 {
    (a * b) >> 62
}

/// `1/sqrt(x)` on Q32 bits, within [`RSQRT_MAX_ERROR`] relative plus
/// half an ulp; `x <= 0` gives 0.
pub(crate) fn rsqrt(b: i64) -> i64 {
    if b <= 0 {
        return 0;
    }
    let u = b.unsigned_abs();
    // The leading-zero count (1..=63) rounded down to even: the MSB lands
    // on bit 62 or 63.
    let sh = u.leading_zeros() & !1;
    let m = u << sh; // f = m / 2^62 in [1, 4), x = f * 4^((30 - sh) / 2)
    let y0 = u64::from(rsqrt_mant((m >> 32) as u32)); // Q1.31
    let fy2 = (u128::from(m) * u128::from(y0 * y0)) >> 62; // ~1, Q.62
    let e = (3u128 << 62).saturating_sub(fy2); // ~2, Q.62
    let y1 = (u128::from(y0) * e) >> 32; // Q.62
    let s = 45 - sh / 2; // 14..=45
    let r = (y1 + (1 << (s - 1))) >> s;
    i64::try_from(r).unwrap_or(i64::MAX)
}

/// `sqrt(x)` on Q32 bits, correctly rounded (within [`SQRT_MAX_ERROR`]);
/// `x <= 0` gives 0.
pub(crate) fn sqrt(b: i64) -> i64 {
    if b <= 0 {
        return 0;
    }
    let (root, rem) = super::isqrt_rem_u128(u128::from(b.unsigned_abs()) << 32);
    let root = if rem > root { root + 1 } else { root };
    i64::try_from(root).unwrap_or(i64::MAX)
}

/// `-log2(x)` for Q32 bits `xb` in `[1, 2^32)`, as Q6.58.
fn neg_log2(xb: i64) -> u64 {
    let lz = xb.leading_zeros(); // 32..=63
    let k = i128::from(lz) - 31; // x = m * 2^-k, m in [1, 2)
    let m = xb << (lz - 32); // Q1.31
    let ji = ((m - (1 << 31) + (1 << 24)) >> 25).clamp(0, 64);
    let j = ji as usize;
    // Exact: m * inv < 2^45; |r| <= 2^-6.98 (units 2^-44).
    let r = i128::from(m * i64::from(LOG_INV[j]) - (1 << 44)) << 18; // Q.62
                                                                     // ln(1 + r) = r (1 - r (1/2 - r (1/3 - r (1/4 - r/5)))).
    let mut a = LN_COEF[0];
    for c in &LN_COEF[1..] {
        a = c - mul62(r, a);
    }
    let log2_1r = mul62(mul62(r, a), INV_LN2);
    let l62 = (k << 62) - i128::from(LOG_T[j]) - log2_1r;
    u64::try_from(l62 >> 4).unwrap_or(0)
}

/// `2^-y` for `y` in Q6.58 (`y < 33`), as Q32 bits, rounded.
fn exp2_neg(y: u64) -> i64 {
    let q = y >> 58;
    let g = y & ((1 << 58) - 1);
    let j = (g >> 52) as usize; // 64 segments
    let h = g & ((1 << 52) - 1); // units 2^-58, h < 1/64
    let t = i128::try_from((u128::from(h) * LN2) >> 58).unwrap_or(0); // Q.62
                                                                      // e^-t = 1 - t (1 - t (1/2 - t (1/6 - t/24))).
    let mut a = EXP_COEF[0];
    for c in &EXP_COEF[1..] {
        a = c - mul62(t, a);
    }
    let p = u128::try_from(ONE62 - mul62(t, a)).unwrap_or(0);
    let v = (u128::from(EXP2[j]) * p) >> 62; // Q.63
    let s = 31 + q; // <= 63
    let r = (v + (1 << (s - 1))) >> s;
    i64::try_from(r).unwrap_or(ONE)
}

/// `x^n` on Q32 bits for `x` in `[0, 1]`, `n >= 0` (see `Real::powf`),
/// within [`POW_MAX_ERROR`] absolute.
pub(crate) fn pow(xb: i64, nb: i64) -> i64 {
    if nb <= 0 || xb >= ONE {
        return ONE;
    }
    if xb <= 0 {
        return 0;
    }
    let l = neg_log2(xb);
    let y = (u128::from(l) * u128::from(nb.unsigned_abs())) >> 32;
    match u64::try_from(y) {
        Ok(y) if y < 33 << 58 => exp2_neg(y),
        _ => 0,
    }
}

/// `(sin, cos)` of an angle in Q32 bits, results in Q32 bits, within
/// [`SIN_COS_MAX_ERROR`] absolute.
pub(crate) fn sin_cos(b: i64) -> (i64, i64) {
    // Quarter turns in units of 2^-96.
    let u = i128::from(b) * TWO_OVER_PI;
    let quadrant = (u >> 96) & 3;
    let f = (u >> 32) & ((1 << 64) - 1); // fraction of a quarter turn, 2^-64
    let ji = ((f + (1 << 57)) >> 58).min(64);
    let j = ji as usize;
    let d = f - (ji << 58); // |d| <= 2^57
    let h = (d * HALF_PI) >> 64; // Q.62, |h| <= pi/256
    let h2 = mul62(h, h);
    // cos h = 1 - h^2/2 + h^4/24; sin h = h (1 - h^2/6 + h^4/120).
    let cos_h = ONE62 - mul62(h2, COS_COEF[0] - mul62(h2, COS_COEF[1]));
    let sin_h = h - mul62(h, mul62(h2, SIN_COEF[0] - mul62(h2, SIN_COEF[1])));
    let st = i128::from(SIN[j] >> 1); // Q.62
    let ct = i128::from(SIN[64 - j] >> 1);
    let s = mul62(st, cos_h) + mul62(ct, sin_h);
    let c = mul62(ct, cos_h) - mul62(st, sin_h);
    let (s, c) = match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    };
    let round = |v: i128| i64::try_from((v + (1 << 29)) >> 30).unwrap_or(0);
    (round(s), round(c))
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::println;
    use std::vec::Vec;

    use super::super::testkit::{
        lg, near_one, pow_error, q32_positive, rel_beyond_rounding, sin_cos_error, Rng,
    };
    use super::super::{Real, Q32};
    use super::*;

    #[test]
    fn rsqrt_within_max_error() {
        let mut worst = 0f64;
        for b in q32_positive() {
            let x = Q32::from_bits(b);
            let exact = 1.0 / x.to_f64().sqrt();
            let e = rel_beyond_rounding(x.rsqrt().to_f64(), exact, 2f64.powi(-32));
            worst = worst.max(e);
        }
        println!("Q32 rsqrt: rel error beyond 1/2 ulp = 2^{:.2}", lg(worst));
        assert!(worst <= RSQRT_MAX_ERROR);
    }

    #[test]
    fn sqrt_correctly_rounded() {
        for b in q32_positive() {
            let x = Q32::from_bits(b);
            let exact = x.to_f64().sqrt();
            let err = (x.sqrt().to_f64() - exact).abs();
            // f64 reference itself is only good to 2^-53 relative.
            assert!(
                err <= SQRT_MAX_ERROR + exact * 2f64.powi(-52),
                "Q32 sqrt {b}"
            );
        }
    }

    #[test]
    fn pow_within_max_error() {
        let mut rng = Rng(4);
        let mut xs: Vec<Q32> = (0..200_000)
            .map(|_| Q32::from_bits(rng.next_i64() & 0xFFFF_FFFF))
            .collect();
        xs.extend((0..5000).map(|k| Q32::from_bits((1 << 32) - k)));
        xs.extend((0..2000).map(Q32::from_bits));
        xs.extend(near_one().map(Q32::from_f64));
        let worst = pow_error(&xs);
        println!("Q32 powf: abs error 2^{:.2}", lg(worst));
        assert!(worst <= POW_MAX_ERROR);
        let x = Q32::from_f64(0.999);
        let got = x.powf(Q32::from_i32(800)).to_f64();
        assert!((got - 0.999f64.powf(800.0)).abs() <= 2f64.powi(-20));
    }

    #[test]
    fn sin_cos_within_max_error() {
        let mut rng = Rng(6);
        let small = (0..300_000).map(|_| Q32::from_bits(rng.next_i64() >> 28));
        let worst = sin_cos_error(small);
        println!("Q32 sin_cos |x| < 8: abs error 2^{:.2}", lg(worst));
        assert!(worst <= SIN_COS_MAX_ERROR);
        // Large angles with raw values exactly representable in f64.
        let wide = (0..300_000).map(|_| Q32::from_bits(rng.next_i64() & !0x7ff));
        let worst = sin_cos_error(wide);
        println!("Q32 sin_cos all angles: abs error 2^{:.2}", lg(worst));
        assert!(worst <= SIN_COS_MAX_ERROR);
    }
}
