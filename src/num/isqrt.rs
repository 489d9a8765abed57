//! The integer square root with its remainder: `⌊√n⌋` from core's
//! `isqrt` (exact for every `u64` and `u128`) and `n - ⌊√n⌋²`. The one
//! square root behind the mesh's exact normals and bounding spheres, the
//! correctly rounded `Q16`/`Q32` square roots, the Phong kernels' unit
//! vectors and their `1/|n|` table (`rsqrt_quarter_table`).

/// `(⌊√n⌋, n - ⌊√n⌋²)`, exactly, for every `u64`.
#[inline]
pub(crate) const fn isqrt_rem_u64(n: u64) -> (u64, u64) {
    let r = n.isqrt();
    (r, n - r * r)
}

/// `(⌊√n⌋, n - ⌊√n⌋²)`, exactly, for every `u128`.
#[inline]
pub(crate) const fn isqrt_rem_u128(n: u128) -> (u128, u128) {
    let r = n.isqrt();
    (r, n - r * r)
}

/// ⌊√n⌋, exactly, for every `u64`.
pub const fn isqrt_u64(n: u64) -> u64 {
    n.isqrt()
}

#[cfg(test)]
mod tests {
    use super::{isqrt_rem_u128, isqrt_rem_u64, isqrt_u64};

    fn check(n: u64) {
        let (r, rem) = isqrt_rem_u64(n);
        let (r, rem, n) = (u128::from(r), u128::from(rem), u128::from(n));
        assert!(r * r <= n && (r + 1) * (r + 1) > n, "isqrt({n}) = {r}");
        assert_eq!(rem, n - r * r, "{n}");
        let (r2, rem2) = isqrt_rem_u128(n);
        assert_eq!((r2, rem2), (r, rem), "{n}");
    }

    fn check_wide(n: u128) {
        let (r, rem) = isqrt_rem_u128(n);
        // r < 2^64: r² and (r + 1)² - 1 fit u128.
        assert!(r < 1 << 64, "{n}");
        assert!(r * r <= n && n - r * r <= 2 * r, "isqrt({n}) = {r}");
        assert_eq!(rem, n - r * r, "{n}");
    }

    #[test]
    fn isqrt_is_exact() {
        for n in 0..5000 {
            check(n);
        }
        for k in [1u64, 2, 3, 65535, 65536, 1 << 31, (1 << 32) - 1] {
            for n in [k * k - 1, k * k, k * k + 1, k * k + 2 * k] {
                check(n);
            }
        }
        check(u64::MAX);
        assert_eq!(isqrt_u64(u64::MAX), u64::from(u32::MAX));
        assert_eq!(
            isqrt_rem_u64(u64::MAX),
            (u64::from(u32::MAX), 2 * u64::from(u32::MAX))
        );
        assert_eq!(
            isqrt_rem_u128(u128::MAX),
            (u128::from(u64::MAX), 2 * u128::from(u64::MAX))
        );
        let mut s = 0x9E37_79B9_7F4A_7C15u64;
        for _ in 0..20_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            check(s);
            check(s >> (s % 64));
            let w = (u128::from(s) << 64) | u128::from(s.rotate_left(17));
            check_wide(w);
            check_wide(w >> (s % 128));
        }
    }
}
