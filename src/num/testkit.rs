//! Test scaffolding shared by the accuracy tests of the approximations
//! (each test lives in the file of the function it checks, next to its
//! stated bound): a reproducible generator, sweeps of the positive ranges
//! and the error measures.

extern crate std;

use std::vec::Vec;

use super::Real;

/// Edge operands of 32-bit products: 0, ±1, 2, the borders of the 16-bit
/// halves (`0x7FFF` to `±2^16`), the ends of `i32`, `2^23` and the
/// neighbours of `2^23.5` (where Q16 products reach `2^47` and saturate),
/// and a value with mixed bits.
pub(super) const EDGES_I32: [i32; 20] = [
    0,
    1,
    -1,
    2,
    0x7FFF,
    0x8000,
    -0x8000,
    0xFFFF,
    0x1_0000,
    -0x1_0000,
    0x7FFF_FFFF,
    i32::MIN,
    i32::MIN + 1,
    0x00B5_04F3,
    0x00B5_04F4,
    -0x00B5_04F4,
    0x0080_0000,
    -0x0080_0000,
    0x1234_5678,
    -0x1234_5678,
];

/// Deterministic pseudo-random `u64` stream (xorshift64*).
pub(super) struct Rng(pub(super) u64);

impl Rng {
    pub(super) fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    pub(super) fn next_i64(&mut self) -> i64 {
        i64::from_ne_bytes(self.next().to_ne_bytes())
    }
}

/// Positive Q16 raw values: every value below 2^12, then 4096 per octave.
pub(super) fn q16_positive() -> Vec<i32> {
    let mut v: Vec<i32> = (1..4096).collect();
    let mut rng = Rng(1);
    for e in 12..31 {
        for _ in 0..4096 {
            let r = (rng.next() >> 33) as i32 & ((1 << e) - 1);
            v.push((1 << e) | r);
        }
        v.push((1 << e) - 1);
        v.push(1 << e);
    }
    v.push(i32::MAX);
    v
}

/// Positive Q32 raw values: every value below 2^10, then 2048 per octave.
pub(super) fn q32_positive() -> Vec<i64> {
    let mut v: Vec<i64> = (1..1024).collect();
    let mut rng = Rng(2);
    for e in 10..63 {
        for _ in 0..2048 {
            let r = rng.next_i64() & ((1 << e) - 1);
            v.push((1 << e) | r);
        }
        v.push((1 << e) - 1);
        v.push(1 << e);
    }
    v.push(i64::MAX);
    v
}

/// `log2` of an error, for printing.
pub(super) fn lg(e: f64) -> f64 {
    e.log2()
}

/// Relative error after removing the half-ulp output rounding allowance.
pub(super) fn rel_beyond_rounding(got: f64, exact: f64, ulp: f64) -> f64 {
    ((got - exact).abs() - 0.5 * ulp).max(0.0) / exact
}

/// The shininess exponents required by the specification, plus extremes.
pub(super) const EXPONENTS: [f64; 12] = [
    0.0, 0.5, 1.0, 2.0, 10.0, 25.0, 100.0, 800.0, 1000.0, 10_000.0, 3.3, 32767.0,
];

/// Max absolute error of `powf` over raw `x` values for every exponent.
pub(super) fn pow_error<R: Real>(xs: &[R]) -> f64 {
    let mut worst = 0f64;
    for &n in &EXPONENTS {
        let rn = R::from_f64(n);
        let nf = rn.to_f64();
        for &x in xs {
            let exact = x.to_f64().powf(nf);
            worst = worst.max((x.powf(rn).to_f64() - exact).abs());
        }
    }
    worst
}

/// `x` values near 1 that matter for high powers: cosines of small angles.
pub(super) fn near_one() -> impl Iterator<Item = f64> {
    (0..20_000).map(|i| (f64::from(i) * 1e-5).cos())
}

/// Max absolute error of `sin_cos` over the given angles.
pub(super) fn sin_cos_error<R: Real>(angles: impl Iterator<Item = R>) -> f64 {
    let mut worst = 0f64;
    for a in angles {
        let (s, c) = a.sin_cos();
        let t = a.to_f64();
        worst = worst
            .max((s.to_f64() - t.sin()).abs())
            .max((c.to_f64() - t.cos()).abs());
    }
    worst
}
