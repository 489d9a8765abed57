//! Exact wide-integer primitives: widening products, counts of leading
//! zeros, 64-bit shifts and small divisions.
//!
//! The Cortex-M0 (ARMv6-M) has no long multiply, no count-leading-zeros,
//! no divide and no 64-bit shifter: LLVM turns `i32 × i32 → i64`,
//! `leading_zeros` and variable `u64` shifts into calls (`__aeabi_lmul`,
//! `__clzsi2`, `__aeabi_llsr`) that cost tens of instructions each. On that
//! target (the `armv6m` cfg alias of `build.rs`) these helpers use inline
//! 32-bit sequences instead; everywhere else they are the plain operators.
//! Both versions are exact, so every target gets bit-identical results (the
//! ARMv6-M versions are compiled everywhere and tested against the
//! operators on the host).

/// `true` on ARMv6-M (no long multiply): callers choose 32-bit formulations
/// of 64-bit formulas there (same values).
pub(crate) const NO_LONG_MUL: bool = cfg!(armv6m);

/// `true` on ARMv6-M, which has no divide instruction either: a 32-bit
/// division is a library call of some fifty instructions there.
pub(crate) const NO_DIVIDE: bool = NO_LONG_MUL;

/// `a · b` exactly, as `i64`.
#[inline(always)]
pub(crate) fn wmul(a: i32, b: i32) -> i64 {
    #[cfg(armv6m)]
    {
        wmul_split(a, b)
    }
    #[cfg(not(armv6m))]
    {
        i64::from(a) * i64::from(b)
    }
}

/// `a · b` exactly from 16×16-bit partial products (the ARMv6-M path of
/// [`wmul`]; compiled everywhere so that the host tests check it).
#[inline(always)]
#[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
#[cfg_attr(not(armv6m), allow(dead_code))]
pub(crate) fn wmul_split(a: i32, b: i32) -> i64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // |ah|, |bh| <= 2^15 and al, bl < 2^16: the cross products fit `i32`
    // (-2^15 · 65535 > -2^31), the low product fits `u32`.
    let lo = (al as u32) * (bl as u32);
    let mid = i64::from(ah * bl) + i64::from(al * bh);
    let hi = ah * bh;
    (i64::from(hi) << 32) + (mid << 16) + i64::from(lo)
}

/// `a · b` exactly, as `u64` (ARMv6-M: [`wmul_u32_split`]).
#[inline(always)]
pub(crate) fn wmul_u32(a: u32, b: u32) -> u64 {
    #[cfg(armv6m)]
    {
        wmul_u32_split(a, b)
    }
    #[cfg(not(armv6m))]
    {
        u64::from(a) * u64::from(b)
    }
}

/// `a · b` exactly from four 16×16-bit products (the ARMv6-M path of
/// [`wmul_u32`]; compiled everywhere so that the host tests check it).
#[inline(always)]
#[cfg_attr(not(armv6m), allow(dead_code))]
pub(crate) fn wmul_u32_split(a: u32, b: u32) -> u64 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // Each partial product is below 2^32; the middle sum below 2^33.
    (u64::from(ah * bh) << 32)
        + ((u64::from(ah * bl) + u64::from(al * bh)) << 16)
        + u64::from(al * bl)
}

/// `x²` exactly for `x < 2^32`, from 16-bit halves: three 16×16-bit
/// products on every target (no 64-bit multiply on the Cortex-M0).
#[inline(always)]
pub(crate) fn sq_u32(x: u32) -> u64 {
    let (h, l) = (x >> 16, x & 0xFFFF);
    // h·l < 2^32; h², l² < 2^32.
    (u64::from(h * h) << 32) + (u64::from(h * l) << 17) + u64::from(l * l)
}

/// `q · x` exactly for `q < 2^16`, `x < 2^32`: two 32-bit products on
/// every target.
#[inline(always)]
pub(crate) fn mul_u16_u32(q: u32, x: u32) -> u64 {
    (u64::from(q * (x >> 16)) << 16) + u64::from(q * (x & 0xFFFF))
}

/// `floor(a·b / 2^32)`, exactly (ARMv6-M: [`mulhi_split`]; elsewhere
/// one high-half multiply, `SMMUL` on the M4).
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
pub(crate) fn mulhi(a: i32, b: i32) -> i32 {
    #[cfg(armv6m)]
    {
        mulhi_split(a, b)
    }
    #[cfg(not(armv6m))]
    {
        (wmul(a, b) >> 32) as i32
    }
}

/// `floor(a·b / 2^32)` from 16-bit halves in 32-bit arithmetic (the
/// ARMv6-M path of [`mulhi`], four `MULS`, beside [`wmul_split`];
/// compiled everywhere so that the host tests check it). With `a = 2^16
/// ah + al` and `b = 2^16 bh + bl` (`al`, `bl` in `[0, 2^16)`), let `t1 =
/// ah bl + (al bl >> 16)` and `t2 = al bh + (t1 & 0xFFFF)`; the result is
/// `ah bh + (t1 >> 16) + (t2 >> 16)` (nested floors of `(ah bl + al bh +
/// al bl / 2^16) / 2^16`). No sum leaves `i32` for any operands: `|ah
/// bl|` and `|al bh|` are at most `2^15 (2^16 - 1)`, and each adds below
/// `2^16`. Three instructions fewer than the four partial products summed
/// with a separate carry word (the point-light Phong span on the M0,
/// exact QEMU counts: 547.04 -> 502.41 instructions a pixel).
#[inline(always)]
#[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
#[cfg_attr(not(armv6m), allow(dead_code))]
pub(crate) fn mulhi_split(a: i32, b: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    let lo = ((al as u32 * bl as u32) >> 16) as i32;
    let t1 = ah.wrapping_mul(bl).wrapping_add(lo);
    let t2 = al.wrapping_mul(bh).wrapping_add(t1 & 0xFFFF);
    ah.wrapping_mul(bh)
        .wrapping_add(t1 >> 16)
        .wrapping_add(t2 >> 16)
}

/// Largest operand magnitude of [`mul16_small`]'s second factor: 2.
pub(crate) const SMALL: u32 = 1 << 17;

/// The `Q16` product `round(a · b / 2^16)` (ties up, as `Q16`'s `*`) in 32-bit arithmetic for `|a| < 2^24` and `|b| <= 2^17`
/// (`|b| <= 2`): the same result, exactly (no saturation is reachable).
///
/// With `a = 2^16 ah + al`, `b = 2^16 bh + bl` (`al`, `bl` in
/// `[0, 2^16)`): `floor((a b + 2^15) / 2^16) = 2^16 ah bh + ah bl + al bh
/// + floor((al bl + 2^15) / 2^16)`, every term within `i32`
/// (`|ah| <= 2^8`, `|bh| <= 2`).
#[inline(always)]
#[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)]
pub(crate) fn mul16_small(a: i32, b: i32) -> i32 {
    let (ah, al) = (a >> 16, a & 0xFFFF);
    let (bh, bl) = (b >> 16, b & 0xFFFF);
    // al bl + 2^15 <= (2^16 - 1)^2 + 2^15 < 2^32.
    let lo = (((al as u32) * (bl as u32) + (1 << 15)) >> 16) as i32;
    ((ah * bh) << 16) + ah * bl + al * bh + lo
}

/// The sign (-1, 0, 1) of `a·b - c·d`, exactly. On the Cortex-M0, when
/// every operand is below 2^15 in magnitude (e.g. the edges of an
/// on-screen triangle in subpixels), from 32-bit products (|products| <
/// 2^30, difference < 2^31); else from [`wmul`].
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
pub(crate) fn det_sign(a: i32, b: i32, c: i32, d: i32) -> i32 {
    #[cfg(armv6m)]
    {
        if let Some(s) = det_sign_small(a, b, c, d) {
            return s;
        }
    }
    (wmul(a, b) - wmul(c, d)).signum() as i32
}

/// [`det_sign`]'s 32-bit path; `None` unless every operand lies in
/// `[-2^15, 2^15)`.
///
/// In that range `a·b` lies in `[-2^30 + 2^15, 2^30]` and `c·d` too, so
/// the difference lies strictly within `(-2^31, 2^31)`: no overflow. The
/// range test is one offset per operand and one comparison for all four
/// (`v + 2^15` in `[0, 2^16)` for every `v` iff their `OR` is below
/// 2^16), rather than an absolute value and a comparison per operand.
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
#[cfg_attr(not(armv6m), allow(dead_code))]
pub(crate) fn det_sign_small(a: i32, b: i32, c: i32, d: i32) -> Option<i32> {
    let off = |v: i32| v.wrapping_add(1 << 15) as u32;
    if off(a) | off(b) | off(c) | off(d) < 1 << 16 {
        Some((a * b - c * d).signum())
    } else {
        None
    }
}

/// The steps of [`small_floor_divmod`] written out, nested: `$step` and
/// the quotient `$q` set to each value in turn while `$more` holds, then
/// `None` (the caller divides).
macro_rules! divmod_steps {
    ($more:expr, $step:expr, $q:ident: $k:literal) => {
        $step;
        $q = $k;
        if $more {
            return None;
        }
    };
    ($more:expr, $step:expr, $q:ident: $k:literal, $($rest:literal),+) => {
        $step;
        $q = $k;
        if $more {
            divmod_steps!($more, $step, $q: $($rest),+);
        }
    };
}

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
        divmod_steps!(m < 0, m += d, q: -1, -2, -3, -4);
    } else if m >= d {
        divmod_steps!(m >= d, m -= d, q: 1, 2, 3, 4);
    }
    Some((q, m))
}

/// `a · b` for `b` within `i16` (`-2^15 <= b < 2^15`), exact: on ARMv6-M
/// two 32-bit `MULS` (`a = hi·2^16 + lo`, `|hi·b| <= 2^30`, `|lo·b| <
/// 2^31`) instead of [`wmul_split`]'s four; elsewhere
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
#[cfg_attr(not(armv6m), allow(dead_code))]
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

#[inline(always)]
fn join(hi: u32, lo: u32) -> u64 {
    ((hi as u64) << 32) | lo as u64
}

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
#[cfg_attr(not(armv6m), allow(dead_code))]
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
#[cfg_attr(not(armv6m), allow(dead_code))]
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

/// `a · b` exactly, as `i128` (the [`Q32`](super::Q32) product).
#[inline(always)]
pub(crate) fn wmul64(a: i64, b: i64) -> i128 {
    i128::from(a) * i128::from(b)
}

/// Leading zeros of a `u32` (32 for 0).
#[inline(always)]
pub(crate) fn clz32(x: u32) -> u32 {
    #[cfg(armv6m)]
    {
        clz32_soft(x)
    }
    #[cfg(not(armv6m))]
    {
        x.leading_zeros()
    }
}

/// Leading zeros of a byte (8 for 0): 256 bytes of flash.
pub(crate) static CLZ8: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut i = 0;
    while i < 256 {
        t[i] = (i as u8).leading_zeros() as u8;
        i += 1;
    }
    t
};

/// Leading zeros from the top non-zero byte and a 256-entry table (two
/// comparisons and one load, instead of a five-step binary search).
#[inline(always)]
#[cfg_attr(not(armv6m), allow(dead_code))]
pub(crate) fn clz32_soft(x: u32) -> u32 {
    let byte = |v: u32| CLZ8[(v as u8) as usize] as u32;
    if x >= 1 << 16 {
        if x >= 1 << 24 {
            byte(x >> 24)
        } else {
            8 + byte(x >> 16)
        }
    } else if x >= 1 << 8 {
        16 + byte(x >> 8)
    } else {
        24 + byte(x)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    #[test]
    fn sq_u32_and_mul_u16_u32_are_exact() {
        let mut s = 0x2545_f491_4f6c_dd1du64;
        let mut xs = std::vec![0u32, 1, 0xFFFF, 0x1_0000, 0xFFFF_FFFF, 0x8000_0000];
        for _ in 0..10_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            xs.push(s as u32);
        }
        for &x in &xs {
            assert_eq!(sq_u32(x), u64::from(x) * u64::from(x), "{x}");
            for q in [0u32, 1, 0x7FFF, 0xFFFF, x >> 16] {
                assert_eq!(mul_u16_u32(q, x), u64::from(q) * u64::from(x), "{q} {x}");
            }
        }
    }

    #[test]
    fn det_sign_is_exact() {
        let mut s = 0x7777_1234_abcd_0001u64;
        let ext = [
            0,
            1,
            -1,
            0x7FFF,
            -0x7FFF,
            0x8000,
            -0x8000,
            0x1_FFFF,
            i32::MAX,
            i32::MIN + 1,
        ];
        let check = |a: i32, b: i32, c: i32, d: i32| {
            let exact = (i128::from(a) * i128::from(b) - i128::from(c) * i128::from(d)).signum();
            assert_eq!(i128::from(det_sign(a, b, c, d)), exact, "{a} {b} {c} {d}");
            if let Some(v) = det_sign_small(a, b, c, d) {
                assert_eq!(i128::from(v), exact, "{a} {b} {c} {d}");
            }
        };
        for &a in &ext {
            for &b in &ext {
                check(a, b, b, a);
                check(a, b, a, b);
                check(a, b, 0x7FFF, -0x7FFF);
            }
        }
        for i in 0..400_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let m: u64 = if i % 2 == 0 { 1 << 16 } else { 1 << 12 };
            let v = [0, 16, 32, 48].map(|k| ((s >> k) % m) as i32 - (m / 2) as i32);
            check(v[0], v[1], v[2], v[3]);
            check(v[0], v[1], v[1], v[0]);
        }
    }

    #[test]
    fn det_sign_small_range_edges() {
        // Every combination of the range's edges (the extreme products,
        // checked for overflow by the debug build) and just beyond them.
        let vals = [-0x8001, -0x8000, -0x7FFF, -1, 0, 1, 0x7FFE, 0x7FFF, 0x8000];
        let inside = |v: i32| (-0x8000..0x8000).contains(&v);
        for &a in &vals {
            for &b in &vals {
                for &c in &vals {
                    for &d in &vals {
                        let exact =
                            (i64::from(a) * i64::from(b) - i64::from(c) * i64::from(d)).signum();
                        let small = det_sign_small(a, b, c, d);
                        let all_in = inside(a) && inside(b) && inside(c) && inside(d);
                        assert_eq!(small.is_some(), all_in, "{a} {b} {c} {d}");
                        if let Some(v) = small {
                            assert_eq!(i64::from(v), exact, "{a} {b} {c} {d}");
                        }
                        assert_eq!(i64::from(det_sign(a, b, c, d)), exact);
                    }
                }
            }
        }
    }

    #[test]
    fn split_product_is_exact() {
        let edge = crate::num::testkit::EDGES_I32;
        for &a in &edge {
            for &b in &edge {
                assert_eq!(wmul_split(a, b), i64::from(a) * i64::from(b), "{a} {b}");
                assert_eq!(wmul(a, b), i64::from(a) * i64::from(b));
            }
        }
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        for _ in 0..200_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let a = (s >> 32) as u32 as i32;
            let b = s as u32 as i32;
            assert_eq!(wmul_split(a, b), i64::from(a) * i64::from(b), "{a} {b}");
        }
    }

    /// `mulhi_split` (the ARMv6-M high product) equals the exact
    /// `floor(a·b / 2^32)` on random and extreme operands.
    #[test]
    fn mulhi_split_exact() {
        let mut s = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            s
        };
        let ext = [
            0,
            1,
            -1,
            i32::MAX,
            i32::MIN,
            i32::MIN + 1,
            0xFFFF,
            0x1_0000,
            -0xFFFF,
            -0x1_0000,
            -0x1_0001,
            0x7FFF_0001,
        ];
        for &a in &ext {
            for &b in &ext {
                let want = ((i64::from(a) * i64::from(b)) >> 32) as i32;
                assert_eq!(mulhi_split(a, b), want, "{a} {b}");
            }
        }
        let mut vals = ext.to_vec();
        for _ in 0..20_000 {
            vals.push(next() as i32);
            let (a, b) = (next(), next());
            vals.push((a as i32) >> (b % 31));
        }
        for w in vals.windows(2) {
            let (a, b) = (w[0], w[1]);
            let want = ((i64::from(a) * i64::from(b)) >> 32) as i32;
            assert_eq!(mulhi_split(a, b), want, "{a} {b}");
            assert_eq!(mulhi(a, b), want, "{a} {b}");
        }
    }

    #[test]
    fn unsigned_and_shift_helpers_equal_the_operators() {
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
        let all: std::vec::Vec<u64> = edges
            .into_iter()
            .chain((0..20_000).map(|i| {
                v ^= v << 13;
                v ^= v >> 7;
                v ^= v << 17;
                // Vary the magnitude too.
                v >> (i % 64)
            }))
            .collect();
        for (i, &x) in all.iter().enumerate() {
            let y = all[(i * 7 + 3) % all.len()];
            let (a, b) = (x as u32, y as u32);
            assert_eq!(wmul_u32_split(a, b), u64::from(a) * u64::from(b), "{a} {b}");
            assert_eq!(wmul_u32(a, b), u64::from(a) * u64::from(b), "{a} {b}");
            let sa = a as i32;
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
