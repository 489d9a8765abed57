//! Unit tests of the mesh module (no std: fixed buffers, libm for f64).

// Reinterpreting random bits as signed values is the point here.
#![allow(clippy::cast_possible_wrap)]

mod exact;
mod generate;
mod mesh;

/// A small xorshift generator for reproducible pseudo-random inputs.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// A pseudo-random i16 (any value).
    fn i16(&mut self) -> i16 {
        (self.next() >> 48) as u16 as i16
    }
}

/// Largest per-component difference, in Q1.14 ulps, between `n` and the
/// exact unit vector along `v`, computed in f64.
fn error_ulps(n: [i16; 3], v: [f64; 3]) -> f64 {
    let len = libm::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    (0..3)
        .map(|k| libm::fabs(f64::from(n[k]) - 16384.0 * v[k] / len))
        .fold(0.0, f64::max)
}
