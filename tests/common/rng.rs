//! Deterministic pseudo-random numbers for the tests: xorshift64* (shifts
//! 12, 25, 27, multiplier 0x2545F4914F6CDD1D). One generator for the
//! core's integration tests (`tests/common`) and the host crate's
//! (`host-tests/tests/support` includes this file).

/// A xorshift64* sequence; the seed must not be 0 (0 stays 0).
pub struct Rng(pub u64);

impl Rng {
    /// The next raw 64-bit value.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in `[0, 1)`: the top 53 bits of the next value, times 2^-53.
    pub fn f(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}
