//! Exact wide-integer helpers for the triangle setup.
//!
//! The ARMv6-M (Cortex-M0/M0+) has no long multiply, no count-leading-zeros
//! and no 64-bit shifter: LLVM turns `u32 × u32 → u64`, `leading_zeros` and
//! variable `u64` shifts into calls (`__aeabi_lmul`, `__clzsi2`,
//! `__aeabi_llsr`) that cost tens of instructions each. On that target these
//! helpers use inline 32-bit sequences instead; everywhere else they are the
//! plain operators. Both versions are exact, so they give the same bits on
//! every target (the `soft` versions are tested against the operators on the
//! host).
//!
//! The target is recognised as "ARM without 32-bit atomics", which is
//! ARMv6-M (and the old ARMv4T/v5TE, which lose nothing but a little speed):
//! the ARM target features (`v7`, `thumb2`) are not visible to `cfg` on
//! stable Rust.

/// `true` on ARMv6-M (no long multiply): callers choose 32-bit formulations
/// of 64-bit formulas there (same values).
pub(crate) const NO_LONG_MUL: bool = cfg!(armv6m);

/// `true` on ARMv6-M, which has no divide instruction either: a 32-bit
/// division is a library call of some fifty instructions there.
pub(crate) const NO_DIVIDE: bool = NO_LONG_MUL;

/// `(⌊n/d⌋, n mod d)` for `d > 0` by at most four subtractions or
/// additions, when the quotient lies in `-4..=4`; `None` otherwise (the
/// caller divides). Exact, and nothing overflows (`m + d` only for `m < 0`,
/// `m - d` only for `m >= d`). Written out rather than as a loop: LLVM
/// turns such a loop back into a division.
#[inline(always)]
pub(crate) fn small_floor_divmod(n: i32, d: i32) -> Option<(i32, i32)> {
    let mut m = n;
    let mut q = 0;
    if m < 0 {
        m += d;
        q = -1;
        if m < 0 {
            m += d;
            q = -2;
            if m < 0 {
                m += d;
                q = -3;
                if m < 0 {
                    m += d;
                    q = -4;
                    if m < 0 {
                        return None;
                    }
                }
            }
        }
    } else if m >= d {
        m -= d;
        q = 1;
        if m >= d {
            m -= d;
            q = 2;
            if m >= d {
                m -= d;
                q = 3;
                if m >= d {
                    m -= d;
                    q = 4;
                    if m >= d {
                        return None;
                    }
                }
            }
        }
    }
    Some((q, m))
}

/// `a · b`, exact.
#[inline(always)]
pub(crate) fn mul_u32(a: u32, b: u32) -> u64 {
    #[cfg(armv6m)]
    {
        mul_u32_soft(a, b)
    }
    #[cfg(not(armv6m))]
    {
        a as u64 * b as u64
    }
}

/// `a · b` from four 16 × 16-bit products (ARMv6-M's `MULS` is 32 × 32 → 32).
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn mul_u32_soft(a: u32, b: u32) -> u64 {
    let (a0, a1) = (a & 0xffff, a >> 16);
    let (b0, b1) = (b & 0xffff, b >> 16);
    let lo = a0 * b0;
    let hi = a1 * b1;
    let (mid, c1) = (a0 * b1).overflowing_add(a1 * b0);
    let (lo, c2) = lo.overflowing_add(mid << 16);
    let hi = hi
        .wrapping_add(mid >> 16)
        .wrapping_add((c1 as u32) << 16)
        .wrapping_add(c2 as u32);
    join(hi, lo)
}

/// `a · b`, exact (signed).
#[inline(always)]
pub(crate) fn mul_i32(a: i32, b: i32) -> i64 {
    #[cfg(armv6m)]
    {
        mul_i32_soft(a, b)
    }
    #[cfg(not(armv6m))]
    {
        a as i64 * b as i64
    }
}

/// `a · b` for `b` within `i16` (`-2^15 <= b < 2^15`), exact: on ARMv6-M
/// two 32-bit `MULS` (`a = hi·2^16 + lo`, `|hi·b| <= 2^30`, `|lo·b| <
/// 2^31`) instead of [`mul_i32_soft`]'s four and its carries; elsewhere
/// the plain product. Callers check the range of `b`.
#[inline(always)]
pub(crate) fn mul_i32_i16(a: i32, b: i32) -> i64 {
    #[cfg(armv6m)]
    {
        mul_i32_i16_soft(a, b)
    }
    #[cfg(not(armv6m))]
    {
        a as i64 * b as i64
    }
}

/// [`mul_i32_i16`] from two 32-bit products.
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn mul_i32_i16_soft(a: i32, b: i32) -> i64 {
    let hi = (a >> 16) * b;
    let lo = (a & 0xffff) * b;
    ((hi as i64) << 16) + lo as i64
}

/// `true` when `v` fits an `i16` (`-2^15 <= v < 2^15`).
#[inline(always)]
pub(crate) fn fits_i16(v: i32) -> bool {
    (v as u32).wrapping_add(1 << 15) < 1 << 16
}

/// Signed product from the unsigned one: `a·b = ua·ub - 2^32·(ub·[a<0] +
/// ua·[b<0])` (mod 2^64), with `ua`, `ub` the two's-complement bit patterns.
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn mul_i32_soft(a: i32, b: i32) -> i64 {
    let (ua, ub) = (a as u32, b as u32);
    let p = mul_u32_soft(ua, ub);
    let mut hi = (p >> 32) as u32;
    if a < 0 {
        hi = hi.wrapping_sub(ub);
    }
    if b < 0 {
        hi = hi.wrapping_sub(ua);
    }
    join(hi, p as u32) as i64
}

#[inline(always)]
fn join(hi: u32, lo: u32) -> u64 {
    ((hi as u64) << 32) | lo as u64
}

// `clz32` (the table-based count on ARMv6-M) lives in `num::wide`, shared
// with the vertex path.
pub(crate) use crate::num::wide::clz32;
#[cfg(test)]
use crate::num::wide::clz32_soft;

/// Leading zeros of a `u64` (64 for 0).
#[inline(always)]
pub(crate) fn clz64(x: u64) -> u32 {
    let hi = (x >> 32) as u32;
    if hi != 0 {
        clz32(hi)
    } else {
        32 + clz32(x as u32)
    }
}

/// `x >> s` for `s < 64`.
#[inline(always)]
pub(crate) fn shr64(x: u64, s: u32) -> u64 {
    #[cfg(armv6m)]
    {
        shr64_soft(x, s)
    }
    #[cfg(not(armv6m))]
    {
        x >> (s & 63)
    }
}

/// `x >> s` (`s < 64`) on 32-bit halves.
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn shr64_soft(x: u64, s: u32) -> u64 {
    let (hi, lo) = ((x >> 32) as u32, x as u32);
    let s = s & 63;
    if s >= 32 {
        (hi >> (s - 32)) as u64
    } else if s == 0 {
        x
    } else {
        join(hi >> s, (lo >> s) | (hi << (32 - s)))
    }
}

/// `x << s` for `s < 64` (bits shifted out are lost).
#[inline(always)]
pub(crate) fn shl64(x: u64, s: u32) -> u64 {
    #[cfg(armv6m)]
    {
        shl64_soft(x, s)
    }
    #[cfg(not(armv6m))]
    {
        x << (s & 63)
    }
}

/// `x << s` (`s < 64`) on 32-bit halves.
#[inline(always)]
#[cfg_attr(not(any(test, armv6m)), allow(dead_code))]
pub(crate) fn shl64_soft(x: u64, s: u32) -> u64 {
    let (hi, lo) = ((x >> 32) as u32, x as u32);
    let s = s & 63;
    if s >= 32 {
        join(lo << (s - 32), 0)
    } else if s == 0 {
        x
    } else {
        join((hi << s) | (lo >> (32 - s)), lo << s)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    fn samples() -> impl Iterator<Item = u64> {
        let mut v = 0x9e37_79b9_7f4a_7c15u64;
        let edges = [
            0u64,
            1,
            2,
            0xffff,
            0x1_0000,
            0x7fff_ffff,
            0x8000_0000,
            0xffff_ffff,
            1 << 32,
            u64::MAX,
            i64::MIN as u64,
            i64::MAX as u64,
        ];
        edges.into_iter().chain((0..20_000).map(move |i| {
            v ^= v << 13;
            v ^= v >> 7;
            v ^= v << 17;
            // Vary the magnitude too.
            v >> (i % 64)
        }))
    }

    #[test]
    fn soft_helpers_equal_the_operators() {
        let all: std::vec::Vec<u64> = samples().collect();
        for (i, &x) in all.iter().enumerate() {
            let y = all[(i * 7 + 3) % all.len()];
            let (a, b) = (x as u32, y as u32);
            assert_eq!(mul_u32_soft(a, b), a as u64 * b as u64, "{a} {b}");
            let (sa, sb) = (a as i32, (y >> 32) as u32 as i32);
            assert_eq!(mul_i32_soft(sa, sb), sa as i64 * sb as i64, "{sa} {sb}");
            assert_eq!(mul_i32_soft(sa, b as i32), sa as i64 * b as i32 as i64);
            assert_eq!(clz32_soft(a), a.leading_zeros());
            assert_eq!(clz64(x), x.leading_zeros());
            for s in [0u32, 1, 5, 31, 32, 33, 47, 63] {
                assert_eq!(shr64_soft(x, s), x >> s, "{x} >> {s}");
                assert_eq!(shl64_soft(x, s), x << s, "{x} << {s}");
            }
            let b16 = (y as u16 as i16) as i32;
            assert!(fits_i16(b16));
            assert_eq!(mul_i32_i16_soft(sa, b16), sa as i64 * b16 as i64);
            assert_eq!(mul_i32_i16(sa, b16), sa as i64 * b16 as i64);
            for b in [-(1 << 15), (1 << 15) - 1, 0, -1] {
                assert_eq!(mul_i32_i16_soft(sa, b), sa as i64 * b as i64);
            }
            let s = (y % 64) as u32;
            assert_eq!(shr64_soft(x, s), x >> s);
            assert_eq!(shl64_soft(x, s), x << s);
        }
    }

    #[test]
    fn table_clz_at_every_bit_boundary() {
        assert_eq!(clz32_soft(0), 32);
        for k in 0..32 {
            for x in [1u32 << k, (1u32 << k) - 1, (1u32 << k) | 1, u32::MAX >> k] {
                assert_eq!(clz32_soft(x), x.leading_zeros(), "{x:#x}");
            }
        }
        for b in 0..=255u32 {
            for shift in [0, 8, 16, 24] {
                let x = b << shift;
                assert_eq!(clz32_soft(x), x.leading_zeros(), "{x:#x}");
            }
        }
    }

    #[test]
    fn fits_i16_bounds() {
        assert!(fits_i16(-(1 << 15)));
        assert!(fits_i16((1 << 15) - 1));
        assert!(!fits_i16(1 << 15));
        assert!(!fits_i16(-(1 << 15) - 1));
        assert!(!fits_i16(i32::MIN));
        assert!(!fits_i16(i32::MAX));
        for a in [i32::MIN, i32::MAX, -1, 0, 0x7fff_0000, -0x7fff_0001] {
            assert_eq!(mul_i32_i16_soft(a, -(1 << 15)), a as i64 * -(1i64 << 15));
            assert_eq!(
                mul_i32_i16_soft(a, (1 << 15) - 1),
                a as i64 * ((1i64 << 15) - 1)
            );
        }
    }

    #[test]
    fn small_floor_divmod_is_exact_or_declines() {
        for d in [1i32, 2, 3, 7, 16, 255, 1 << 20, 1 << 30, i32::MAX] {
            for n in [
                0i32,
                1,
                -1,
                d - 1,
                d,
                -d,
                4 * (d / 8),
                -5 * (d / 8),
                i32::MIN,
                i32::MAX,
                12345,
                -98765,
            ] {
                let want = (n.div_euclid(d), n.rem_euclid(d));
                match small_floor_divmod(n, d) {
                    Some(got) => assert_eq!(got, want, "{n} / {d}"),
                    None => assert!(!(-4..=4).contains(&want.0), "{n} / {d}"),
                }
            }
        }
    }
}
