//! Integer kernels behind the [`Q16`](super::Q16) approximations.
//!
//! All functions take and return raw Q16.16 bit patterns (`i32`, value =
//! bits / 2^16) and use no floating point and no division.
//!
//! - `rsqrt`: leading-zero normalisation to a mantissa `f` in `[1, 4)` with
//!   an even exponent, then linear interpolation in a 193-entry table of
//!   `1/sqrt(f)` (step 1/64). One 16x16->32 product, no 64-bit arithmetic.
//!   Chord error <= 2^-15.4 relative; measured total 2^-15.46 relative
//!   plus the 1/2 ulp output rounding.
//! - `sqrt`: exact digit-by-digit integer square root (no multiplication),
//!   correctly rounded to nearest.
//! - `pow`: `x^n = 2^(-n * L)`, `L = -log2 x`. `L` comes from a table
//!   reduction `x = 2^-k * (1 + j/64) * (1 + r)` with an exact short
//!   reciprocal, so `r` is exact and `L` keeps its *relative* accuracy as
//!   `x -> 1` (which is what `x^800` needs), plus a cubic in `r`. `2^-y`
//!   uses a 64-entry table and a quadratic. One 32x32->64 product
//!   (`n * L`); the scaling by `1/ln 2` is split into two 32-bit products.
//!   Measured output error 2^-14.79 absolute.
//! - `sin_cos`: reduction by a 2/pi constant (Q0.32: 2^-17.4 rad at
//!   `|x| = 2^15`), 65-entry quarter-wave table, Taylor correction of the
//!   residual (|h| <= pi/256) in 64-bit integers (a per-vertex function).
//!   Measured 2^-16.44 absolute.
//!
//! Each function's bound is a constant next to it (`RSQRT_MAX_ERROR`,
//! `POW_MAX_ERROR`, …), which the tests at the bottom of this file check
//! against `f64` over sweeps of the function's domain. The tables are in
//! `tables`, with the test that re-derives every entry.

use super::tables::{EXP2, LOG_INV, LOG_T, RSQRT, SIN};
use super::wide::{clz32, wmul, wmul_u32};

/// Q16 one.
const ONE: i32 = 1 << 16;

/// [`rsqrt`]'s largest relative error beyond the half-ulp rounding of its
/// output: `2^-15` (measured `2^-15.46`).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const RSQRT_MAX_ERROR: f64 = 1.0 / 32_768.0;

/// [`sqrt`]'s largest absolute error: half an ulp, `2^-17` (correctly
/// rounded).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const SQRT_MAX_ERROR: f64 = 1.0 / 131_072.0;

/// [`pow`]'s largest absolute error for `x` in `[0, 1]`, `n` up to 32767:
/// `2^-14` (measured `2^-14.79`).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const POW_MAX_ERROR: f64 = 1.0 / 16_384.0;

/// [`sin_cos`]'s largest absolute error over every angle: `2^-16`
/// (measured `2^-16.44`; the half-ulp output rounding for `|x| < 8`).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const SIN_COS_MAX_ERROR: f64 = 1.0 / 65_536.0;

/// [`recip_mant`]'s largest relative error: `2^-17` (measured
/// `2^-17.004` over every 18-bit position).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const RECIP_MANT_MAX_ERROR: f64 = 1.0 / 131_072.0;

/// [`rsqrt_newton`]'s largest relative error: `2^-28.5` (measured
/// `2^-28.79`; about 2.3 units of a result near `2^30`).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const RSQRT_NEWTON_MAX_ERROR: f64 = 2.7e-9;

/// [`unit`]'s largest absolute error per component: `2^-15` (measured
/// `2^-15.4`).
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const UNIT_MAX_ERROR: f64 = 1.0 / 32_768.0;

/// `1/sqrt(f)` for a mantissa `m` = `f * 2^30`, `f` in `[1, 4)`, as Q1.31.
///
/// Linear interpolation between table points 1/64 apart: the chord lies
/// above the convex curve by at most `(1/64)^2 / 8 * 3/4 = 2^-15.4` relative
/// (at `f = 1`); the result is never below the exact value by more than
/// the table rounding (2^-31).
pub(crate) fn rsqrt_mant(m: u32) -> u32 {
    let idx = ((m >> 24).saturating_sub(64) as usize).min(191);
    let t = (m >> 8) & 0xFFFF;
    let a = RSQRT[idx];
    // a - RSQRT[idx + 1] < 2^24, so `d * t` < 2^32.
    let d = (a - RSQRT[idx + 1]) >> 8;
    a - ((d * t) >> 8)
}

/// `1/sqrt(x)` on Q16 bits, within [`RSQRT_MAX_ERROR`] relative plus
/// half an ulp; `x <= 0` gives 0.
pub(crate) fn rsqrt(b: i32) -> i32 {
    if b <= 0 {
        return 0;
    }
    let u = b.unsigned_abs();
    // Shift so the MSB lands on bit 30 or 31 with an even shift (the
    // leading-zero count, 1..=31, rounded down to even): then
    // x = f * 4^((14 - sh) / 2) with f = m / 2^30 in [1, 4).
    let sh = clz32(u) & !1;
    let y = rsqrt_mant(u << sh);
    let s = 22 - sh / 2; // 7..=22
    let r = (y + (1 << (s - 1))) >> s;
    i32::try_from(r).unwrap_or(i32::MAX)
}

/// `sqrt(x)` on Q16 bits, correctly rounded (within [`SQRT_MAX_ERROR`]);
/// `x <= 0` gives 0.
pub(crate) fn sqrt(b: i32) -> i32 {
    if b <= 0 {
        return 0;
    }
    let (root, rem) = super::isqrt_rem_u64(u64::from(b.unsigned_abs()) << 16);
    let root = if rem > root { root + 1 } else { root };
    i32::try_from(root).unwrap_or(i32::MAX)
}

/// `-log2(x)` for Q16 bits `xb` in `[1, 2^16)`, as Q5.27.
fn neg_log2(xb: i32) -> i64 {
    let lz = clz32(xb.unsigned_abs()); // 16..=31 (xb > 0)
    let k = i64::from(lz) - 15; // x = m * 2^-k, m in [1, 2)
    let m = xb << (lz - 16); // Q1.15
    let j = (((m - (1 << 15) + (1 << 8)) >> 9) as usize).min(64);
    // Exact: m * inv < 2^29. |r| <= 2^-7 + 2^-13 (units 2^-28: < 2^21.1).
    let r = m * i32::from(LOG_INV[j]) - (1 << 28);
    // s = ln(1 + r) = r - r^2/2 + r^3/3 (truncation r^4/4: 2^-23 relative).
    let rh = r >> 7; // units 2^-21
    let r2 = (rh * rh) >> 14; // units 2^-28
    let r3 = (r2 * rh) >> 21; // units 2^-28
    let s = r - (r2 >> 1) + ((r3 * 21_845) >> 16);
    // log2(1 + r) = s / ln 2 = s + s * 0.442695; the second product split
    // in two 32-bit halves (58_025 = 0.442695 * 2^17).
    let prod = (((s >> 6) * 58_025) >> 11) + (((s & 63) * 58_025) >> 17);
    let log2_1r = i64::from(s + prod); // units 2^-28
    let t = i64::try_from(LOG_T[j] >> 34).unwrap_or(0); // units 2^-28
    ((k << 28) - t - log2_1r) >> 1
}

/// `2^-y` for `y` in Q5.27 (`y < 17`), as Q16 bits, rounded.
fn exp2_neg(y: u32) -> i32 {
    let q = y >> 27;
    let g = y & ((1 << 27) - 1);
    let j = (g >> 21) as usize; // 64 segments
    let h = g & ((1 << 21) - 1); // units 2^-27, h < 1/64
    let t = ((h >> 5) * 45_426) >> 8; // h * ln 2, units 2^-30
    let t16 = t >> 14;
    // 1 - e^-t = t - t^2/2 (+ t^3/6 <= 2^-22, ignored), units 2^-30.
    let delta = t - ((t16 * t16) >> 3);
    let e = (EXP2[j] >> 32) as u32; // Q1.31, <= 2^31
    let v = e - (((e >> 15) * (delta >> 10)) >> 5);
    let s = 15 + q;
    let r = (v + (1 << (s - 1))) >> s;
    i32::try_from(r).unwrap_or(ONE)
}

/// `x^n` on Q16 bits for `x` in `[0, 1]`, `n >= 0` (see `Real::powf`),
/// within [`POW_MAX_ERROR`] absolute.
pub(crate) fn pow(xb: i32, nb: i32) -> i32 {
    if nb <= 0 || xb >= ONE {
        return ONE;
    }
    if xb <= 0 {
        return 0;
    }
    let l = u64::try_from(neg_log2(xb)).unwrap_or(0);
    let y = (l * u64::from(nb.unsigned_abs())) >> 16;
    match u32::try_from(y) {
        Ok(y) if y < 17 << 27 => exp2_neg(y),
        _ => 0,
    }
}

/// `(sin, cos)` of an angle in Q16 bits, results in Q16 bits, within
/// [`SIN_COS_MAX_ERROR`] absolute.
pub(crate) fn sin_cos(b: i32) -> (i32, i32) {
    // Quarter turns in units of 2^-48: b * 2/pi (2/pi as Q0.32,
    // 0xA2F9_836E = 2^32 - 0x5D06_7C92, so the product is one `wmul`:
    // |b| <= 2^31 keeps b * 2^32 and the difference within i64).
    let u = (i64::from(b) << 32) - wmul(b, 0x5D06_7C92);
    let quadrant = (u >> 48) & 3;
    let f = (u >> 16) & 0xFFFF_FFFF; // fraction of a quarter turn, 2^-32
    let ji = ((f + (1 << 25)) >> 26).min(64);
    let j = ji as usize;
    let d = f - (ji << 26); // |d| <= 2^25
    let h = (d * 0x6487_ed51) >> 32; // d * pi/2, Q.30
    let h2 = (h * h) >> 30;
    let h3 = (h2 * h) >> 30;
    let cos_h = (1 << 30) - (h2 >> 1);
    let sin_h = h - ((h3 * 0x2aaa_aaab) >> 32); // h - h^3/6
    let st = i64::try_from(SIN[j] >> 33).unwrap_or(0); // Q.30
    let ct = i64::try_from(SIN[64 - j] >> 33).unwrap_or(0);
    let s = (st * cos_h + ct * sin_h) >> 30;
    let c = (ct * cos_h - st * sin_h) >> 30;
    let (s, c) = match quadrant {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    };
    let round = |v: i64| i32::try_from((v + (1 << 13)) >> 14).unwrap_or(0);
    (round(s), round(c))
}

/// `round(2^38 / (256 + j))` = `2^30 / (1 + j/256)` for `j` in `0..=256`
/// (values in `[2^29, 2^30]`), computed at compile time.
const RECIP: [u32; 257] = {
    let mut t = [0u32; 257];
    let mut j = 0;
    while j < 257 {
        let d = 256 + j as u64;
        t[j] = (((1u64 << 38) + d / 2) / d) as u32;
        j += 1;
    }
    t
};

/// `2^30 / f` for a mantissa `m = f · 2^31`, `f` in `[1, 2)`: linear
/// interpolation in [`RECIP`] (256 segments) with a 10-bit fraction.
///
/// Error: the chord lies above the convex curve by at most
/// `(1/256)^2 / 8 · 2 = 2^-18` relative; truncating the position to 18 bits
/// moves it by at most `2^-18` relative (downwards); table rounding
/// `2^-30`. Within [`RECIP_MANT_MAX_ERROR`] = `2^-17` relative in all
/// (tested over every 18-bit position below).
pub(crate) fn recip_mant(m: u32) -> u32 {
    let idx = ((m >> 23) as usize).saturating_sub(256).min(255);
    let t = (m >> 13) & 0x3FF;
    let a = RECIP[idx];
    // a - RECIP[idx + 1] < 2^30 / 257 < 2^22, so `d * t` < 2^32.
    let d = a - RECIP[idx + 1];
    a - ((d * t) >> 10)
}

/// [`recip_mant`] for a mantissa with its top bit set (`m >= 2^31`): the
/// same value (the segment index is then `(m >> 23) & 0xFF`, no clamp).
#[inline(always)]
pub(crate) fn recip_mant_top(m: u32) -> u32 {
    let idx = ((m >> 23) & 0xFF) as usize;
    let t = (m >> 13) & 0x3FF;
    let a = RECIP.get(idx).copied().unwrap_or(0);
    let b = RECIP.get(idx + 1).copied().unwrap_or(0);
    a - (((a - b) * t) >> 10)
}

/// [`rsqrt_mant`] refined by one Newton step `y (3 - f y^2) / 2`: within
/// [`RSQRT_NEWTON_MAX_ERROR`] = `2^-28.5` relative of `2^31 / sqrt(f)`
/// (the chord error `2^-15.4` squared, times 1.5, is `2^-30.2`; the
/// truncations of the 32-bit steps, a few units of `2^-31` each, add the
/// rest: measured `2^-28.79`), at most `2^31`.
/// Exact 32x32-bit products ([`wmul`]: 16-bit halves on the Cortex-M0).
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_possible_wrap,
    clippy::cast_sign_loss
)]
pub(crate) fn rsqrt_newton(m: u32) -> u32 {
    let y = rsqrt_mant(m) >> 1; // 2^30 / sqrt(f), < 2^31
    let yy = (wmul(y as i32, y as i32) >> 29) as u32; // 2^31 / f, < 2^32
                                                      // f y^2 = m yy / 2^30 ~ 2^31; both factors halved to fit i32.
    let fyy = wmul((m >> 1) as i32, (yy >> 1) as i32) >> 28; // ~2^31
    let e = (3i64 << 31) - fyy; // ~2^32
                                // y1 = y e / 2^31 (as Q1.31 of 2^31 / sqrt f): split e in halves.
    let e_hi = (e >> 16) as i32; // ~2^16
    let e_lo = (e & 0xFFFF) as i32;
    let r = ((wmul(y as i32, e_hi) << 16) + wmul(y as i32, e_lo)) >> 31;
    r.clamp(0, 1 << 31) as u32
}

/// The unit vector in the direction of `v` (any scale) as Q16 bits; the
/// zero vector gives zero. 32-bit arithmetic only (no 64-bit product).
///
/// The largest magnitude is brought into `[2^15, 2^16)` (truncating the
/// others: at most `2^-15` of the length each), the squared length comes
/// from three 32-bit squares, its reciprocal square root from
/// [`rsqrt_newton`] (within `2^-28.5` relative), and the products are
/// split in 16-bit halves (exact floor) before the final rounding. Error
/// per component, tested over random and axis-near vectors of every
/// magnitude (components up to `i32::MIN`): within [`UNIT_MAX_ERROR`] =
/// `2^-15` absolute of the exact unit vector (measured `2^-15.4`), hence
/// no component above `1 + 2^-15`.
pub(crate) fn unit(v: [i32; 3]) -> [i32; 3] {
    let mag = v.map(i32::unsigned_abs);
    let max = mag[0].max(mag[1]).max(mag[2]);
    if max == 0 {
        return [0; 3];
    }
    let bits = 32 - clz32(max); // 1..=32
    let u = if bits > 16 {
        // Rounded to nearest, at most 2^16 - 1 (keeps the squares in u32).
        let sh = bits - 16;
        mag.map(|m| (((m >> (sh - 1)) + 1) >> 1).min(0xFFFF))
    } else {
        mag.map(|m| m << (16 - bits))
    };
    // Each u < 2^16: u^2 / 4 < 2^30; the largest >= 2^15 gives >= 2^28.
    let l2 = ((u[0] * u[0]) >> 2) + ((u[1] * u[1]) >> 2) + ((u[2] * u[2]) >> 2);
    // |u| = 2 sqrt(l2). With f = m / 2^30 in [1, 4) and y = 2^31 / sqrt(f):
    // l2 >= 2^30: m = l2, |u| = 2^16 sqrt(f), n = u y / 2^31;
    // l2 <  2^30: m = 4 l2, |u| = 2^15 sqrt(f), n = u y / 2^30.
    let (m, s) = if l2 >= 1 << 30 {
        (l2, 15)
    } else {
        (l2 << 2, 14)
    };
    let y = rsqrt_newton(m);
    let (yh, yl) = (y >> 16, y & 0xFFFF);
    let out = |k: usize| {
        // floor(u y / 2^16), exactly: u yh < 2^31, u yl < 2^32.
        let t = u[k] * yh + ((u[k] * yl) >> 16);
        let r = ((t + (1 << (s - 1))) >> s) as i32;
        if v[k] < 0 {
            -r
        } else {
            r
        }
    };
    [out(0), out(1), out(2)]
}

/// [`exp_neg`]'s largest absolute error: `2^-15.5`.
#[cfg_attr(not(test), allow(dead_code))]
pub(crate) const EXP_NEG_MAX_ERROR: f64 = 1.0 / 46_340.95;

/// `log2(e)` in Q21 (`1.442695… · 2^21`, rounded).
const LOG2E_Q21: u32 = 3_025_525;

/// `e^-x` for `x >= 0` in Q16 bits, as Q16 bits: through [`exp2_neg`]
/// (`x · log2 e` in Q5.27, the constant within `2^-22` relative), so
/// within [`EXP_NEG_MAX_ERROR`] = `2^-15.5` absolute; 0 from `x >= 11.7`
/// on.
pub(crate) fn exp_neg(x: u32) -> i32 {
    let y = wmul_u32(x, LOG2E_Q21) >> 10; // Q16 · Q21 = Q37 -> Q27
    match u32::try_from(y) {
        Ok(y) if y < 17 << 27 => exp2_neg(y),
        _ => 0,
    }
}

/// `1/k` in Q16 for `k` in `1..=16` (index `k`), rounded.
const INV_K: [u32; 17] = {
    let mut t = [0u32; 17];
    let mut k = 1;
    while k < 17 {
        t[k] = ((1u32 << 16) + k as u32 / 2) / k as u32;
        k += 1;
    }
    t
};

/// `(1 - u/m)^m` in Q15 bits for `u` and `m` in Q16 bits, `0 <= u <= m`,
/// `m >= 1`: one entry of the Phong specular table (`render::phong_span`).
///
/// For `m >= 32` and `u <= 8` (`y = u/m <= 1/4`) by the series
/// `-m ln(1 - y) = u (1 + y/2 + y^2/3 + … + y^15/16)` in 32-bit Q16
/// arithmetic (truncation `y^16 / 17 · u <= 2^-35`, rounding `2^-14`
/// relative per term) and [`exp_neg`]; else by [`pow`] on `x = 1 - u/m`
/// rounded to Q16 (which moves `u` by at most `m · 2^-17 <= 2^-12` for
/// `m < 32`). Within `2^-11` absolute in all (measured `2^-11.5`; tested against `f64` in
/// the kernel's tests).
pub(crate) fn spec_entry(u: u32, m: u32) -> u16 {
    let q = (u64::from(u) << 16).checked_div(u64::from(m));
    spec_entry_q(u, m, q)
}

/// [`spec_entry`] with `q = floor(u · 2^16 / m)` given (`None` for `m =
/// 0`): the same value, for callers that step `q` without a division.
#[allow(clippy::cast_possible_truncation)]
pub(crate) fn spec_entry_q(u: u32, m: u32, q: Option<u64>) -> u16 {
    let v = if m >= 32 << 16 && u <= 8 << 16 {
        // y = u/m in Q16 (<= 2^14).
        let y = q.unwrap_or(0) as u32;
        let mut sum = 1u32 << 16;
        let mut yk = 1u32 << 16;
        for inv in INV_K.iter().skip(2) {
            yk = (yk * y) >> 16; // <= 2^14 · 2^16
            if yk == 0 {
                // Every later term is 0 too (the same sum, sooner: at
                // shininess 100 after 5 terms of 15).
                break;
            }
            sum += (yk * *inv) >> 16; // yk < 2^16, inv <= 2^15
        }
        // E = u · sum, Q16; u <= 2^19, sum < 2^17 (sum < 1.16).
        let e = wmul_u32(u, sum) >> 16;
        exp_neg(u32::try_from(e).unwrap_or(u32::MAX))
    } else {
        let q = q.unwrap_or(1 << 16).min(1 << 16) as i32;
        pow(ONE - q, i32::try_from(m).unwrap_or(i32::MAX))
    };
    // Q16 -> Q15, rounded; v <= 2^16.
    (((v.clamp(0, ONE) + 1) >> 1) as u32).min(1 << 15) as u16
}

#[cfg(test)]
mod tests {
    extern crate std;

    use std::println;
    use std::vec::Vec;

    use super::super::testkit::{
        lg, near_one, pow_error, q16_positive, rel_beyond_rounding, sin_cos_error, Rng,
    };
    use super::super::{Real, Q16};
    use super::*;

    #[test]
    fn rsqrt_within_max_error() {
        let mut worst = 0f64;
        for b in q16_positive() {
            let x = Q16::from_bits(b);
            let exact = 1.0 / x.to_f64().sqrt();
            let e = rel_beyond_rounding(x.rsqrt().to_f64(), exact, 2f64.powi(-16));
            worst = worst.max(e);
        }
        println!("Q16 rsqrt: rel error beyond 1/2 ulp = 2^{:.2}", lg(worst));
        assert!(worst <= RSQRT_MAX_ERROR);
    }

    #[test]
    fn sqrt_correctly_rounded() {
        for b in q16_positive() {
            let x = Q16::from_bits(b);
            let exact = x.to_f64().sqrt();
            let err = (x.sqrt().to_f64() - exact).abs();
            assert!(err <= SQRT_MAX_ERROR * (1.0 + 1e-9), "Q16 sqrt {b}");
        }
    }

    #[test]
    fn pow_within_max_error() {
        let mut xs: Vec<Q16> = (0..=65536).map(Q16::from_bits).collect();
        xs.extend(near_one().map(Q16::from_f64));
        let worst = pow_error(&xs);
        println!("Q16 powf: abs error 2^{:.2}", lg(worst));
        assert!(worst <= POW_MAX_ERROR);
        // x = 0.999 (as represented), n = 800: 0.999^800 = 0.449.
        let x = Q16::from_f64(0.999);
        let got = x.powf(Q16::from_i32(800)).to_f64();
        assert!((got - x.to_f64().powf(800.0)).abs() <= 2f64.powi(-12));
        assert!((got - 0.449).abs() < 0.01);
    }

    #[test]
    fn sin_cos_quarter_turn_product_is_exact() {
        // sin_cos's b · 0xA2F9_836E as b · 2^32 - wmul(b, 0x5D06_7C92).
        let mut rng = Rng(7);
        let edges = [0, 1, -1, i32::MAX, i32::MIN, i32::MIN + 1, 0x7FFF, -0x8000];
        for b in edges
            .into_iter()
            .chain((0..100_000).map(|_| (rng.next_i64() >> 32) as i32))
        {
            let want = i64::from(b) * 0xA2F9_836E;
            assert_eq!((i64::from(b) << 32) - wmul(b, 0x5D06_7C92), want, "{b}");
        }
    }

    #[test]
    fn sin_cos_within_max_error() {
        let dense = (-(8 << 16)..(8 << 16)).map(Q16::from_bits);
        let worst = sin_cos_error(dense);
        println!("Q16 sin_cos |x| < 8: abs error 2^{:.2}", lg(worst));
        assert!(worst <= SIN_COS_MAX_ERROR);
        let mut rng = Rng(5);
        let wide = (0..300_000).map(|_| Q16::from_bits((rng.next_i64() >> 32) as i32));
        let worst = sin_cos_error(wide.chain([Q16::MAX, Q16::MIN]));
        println!("Q16 sin_cos all angles: abs error 2^{:.2}", lg(worst));
        assert!(worst <= SIN_COS_MAX_ERROR);
    }

    /// Every 18-bit position of a mantissa (the interpolation reads no
    /// lower bit), at the lowest and highest mantissa of each; and
    /// [`recip_mant_top`] equal to it.
    #[test]
    fn recip_mant_within_max_error_at_every_position() {
        let mut worst = 0f64;
        for p in 0..1u32 << 18 {
            for low in [0, (1 << 13) - 1] {
                let m = 1 << 31 | p << 13 | low;
                let exact = 2f64.powi(61) / f64::from(m);
                let got = f64::from(recip_mant(m));
                worst = worst.max((got - exact).abs() / exact);
                assert_eq!(recip_mant_top(m), recip_mant(m));
            }
        }
        println!("recip_mant: rel error 2^{:.3}", lg(worst));
        assert!(worst <= RECIP_MANT_MAX_ERROR);
        assert!(
            worst > RECIP_MANT_MAX_ERROR / 2.0,
            "{worst}: the bound is tight"
        );
    }

    /// Every Q16 `x` up to 12 (where the result is 0) and beyond.
    #[test]
    fn exp_neg_within_max_error() {
        let mut worst = 0f64;
        for x in (0..12 << 16).chain([u32::MAX, 1 << 31, 17 << 16]) {
            let exact = (-f64::from(x) / 65536.0).exp();
            let got = f64::from(exp_neg(x)) / 65536.0;
            worst = worst.max((got - exact).abs());
        }
        println!("exp_neg: abs error 2^{:.2}", lg(worst));
        assert!(worst <= EXP_NEG_MAX_ERROR);
    }

    /// Every mantissa near both ends of `[1, 4)` and random ones between.
    #[test]
    fn rsqrt_newton_within_max_error() {
        let mut rng = Rng(12);
        let ends = (0..20_000u32).flat_map(|k| [(1 << 30) + k, u32::MAX - k]);
        let random = (0..400_000)
            .map(|_| (1 << 30) | (rng.next() >> 34) as u32 | ((rng.next() >> 62) as u32) << 30);
        let mut worst = 0f64;
        for m in ends.chain(random) {
            let exact = 2f64.powi(31) / (f64::from(m) / 2f64.powi(30)).sqrt();
            let got = rsqrt_newton(m);
            assert!(got <= 1 << 31);
            worst = worst.max((f64::from(got) - exact).abs() / exact);
        }
        println!("rsqrt_newton: rel error 2^{:.2}", lg(worst));
        assert!(worst <= RSQRT_NEWTON_MAX_ERROR);
    }

    /// `approx16::unit` against `f64` over random vectors of every magnitude
    /// (and near the axes): the bound stated in its doc comment.
    #[test]
    fn unit_within_max_error() {
        let mut rng = Rng(7);
        let mut worst = 0f64;
        let mut longest = 0f64;
        // Random vectors of every magnitude up to the whole i32 range (e = 31
        // draws any i32, i32::MIN included), then the extremes by hand.
        let extremes = [
            [i32::MIN, 0, 0],
            [0, i32::MIN, 0],
            [0, 0, i32::MIN],
            [i32::MIN, i32::MIN, i32::MIN],
            [i32::MAX, i32::MIN, 1],
            [i32::MIN, i32::MAX, i32::MAX],
            [1 << 30, -(1 << 30), 1 << 30],
            [i32::MAX, 1, -1],
            [i32::MIN, 1 << 30, -(1 << 29)],
        ];
        let random = (0..400_000u32).map(|i| {
            let e = i % 32;
            let mut v = [0i32; 3];
            for c in &mut v {
                *c = if e == 31 {
                    (rng.next() >> 32) as u32 as i32
                } else {
                    let r = (rng.next() >> 33) as i64 & ((1i64 << e) - 1).max(1);
                    if rng.next() & 1 == 0 {
                        r as i32
                    } else {
                        -(r as i32)
                    }
                };
            }
            if i % 7 == 0 {
                v[(i % 3) as usize] = ((1i64 << e) - 1) as i32;
            }
            v
        });
        for v in random.chain(extremes) {
            if v == [0; 3] {
                continue;
            }
            let u = unit(v);
            let f = v.map(f64::from);
            let l = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]).sqrt();
            let mut len2 = 0.0;
            for k in 0..3 {
                let got = f64::from(u[k]) / 65536.0;
                worst = worst.max((got - f[k] / l).abs());
                len2 += got * got;
            }
            longest = longest.max(len2.sqrt());
        }
        println!(
            "Q16 unit: abs error 2^{:.2}, longest 1 + 2^{:.2}",
            lg(worst),
            lg(longest - 1.0)
        );
        assert!(worst <= UNIT_MAX_ERROR);
        assert_eq!(unit([0; 3]), [0; 3]);
    }
}
