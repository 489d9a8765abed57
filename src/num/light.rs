//! The Phong span kernel's per-kernel light set-up in integers: its colour
//! scaling, its Q30 unit vectors and a directional light's half vectors
//! (public so that the report's table-size sweep folds lights the same way).

/// `round(v · 255 · 2^k / 2^16)` for a Q16 coefficient `v` (a negative `v`
/// counts as 0; exact for `k <= 24`).
#[must_use]
pub fn scale255(v: i32, k: u32) -> u64 {
    let v = u64::from(v.max(0).unsigned_abs());
    (v * 255 * (1 << k) + (1 << 15)) >> 16
}

/// The unit vector of `v` (any scale, components within `±2^62`) in Q30, by
/// 64-bit arithmetic (per kernel): within `2^-29` per component; `[0; 3]`
/// for the zero vector.
#[allow(clippy::cast_possible_truncation)]
#[must_use]
pub fn unit30(v: [i64; 3]) -> [i32; 3] {
    let s: u128 = v.iter().map(|&c| (c as i128 * c as i128) as u128).sum();
    if s == 0 {
        return [0; 3];
    }
    // |v| to 2^-.. precision: isqrt of s scaled to ~2^124.
    let sh = s.leading_zeros() & !1;
    let big = s << sh; // >= 2^126
    let top = (big >> 64) as u64; // >= 2^62
    let root = super::isqrt_u64(top); // |v| · 2^(sh/2 - 32) ~ 2^31
    let root = root.max(1);
    v.map(|c| {
        // c · 2^30 / |v| = c · 2^(30 + sh/2 - 32) / root
        let e = 30 + i64::from(sh / 2) - 32;
        let num = if e >= 0 {
            (c as i128) << e
        } else {
            (c as i128) >> -e
        };
        num.checked_div(root as i128)
            .unwrap_or(0)
            .clamp(-(1 << 30), 1 << 30) as i32
    })
}

/// `2^30 / sqrt 2`, rounded.
const INV_SQRT2_Q30: i64 = 759_250_125;

/// The half vectors of a directional light `l` (a Q30 unit vector toward
/// the light) for the viewer at `+z`: for Blinn, `(unit30(l + v), [0; 3])`
/// (within `2^-29` per component); else `((l + v)/sqrt 2, (l - v)/sqrt 2)`
/// in Q30, each component rounded (within `2^-30`, the constant's rounding
/// adding at most `2^-30 · 2^-29`).
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
#[must_use]
pub fn light_halves(l: [i32; 3], blinn: bool) -> ([i32; 3], [i32; 3]) {
    let l64 = l.map(i64::from);
    let v = [0i64, 0, 1 << 30];
    if blinn {
        (
            unit30([l64[0] + v[0], l64[1] + v[1], l64[2] + v[2]]),
            [0; 3],
        )
    } else {
        let f = |a: i64| ((a * INV_SQRT2_Q30 + (1 << 29)) >> 30) as i32;
        (
            [f(l64[0] + v[0]), f(l64[1] + v[1]), f(l64[2] + v[2])],
            [f(l64[0] - v[0]), f(l64[1] - v[1]), f(l64[2] - v[2])],
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scale255_rounds_to_nearest() {
        assert_eq!(scale255(1 << 16, 0), 255);
        assert_eq!(scale255(1 << 16, 6), 255 * 64);
        assert_eq!(scale255(-5, 6), 0);
        // 0.5 · 255 · 2^13 = 1 044 480 exactly.
        assert_eq!(scale255(1 << 15, 13), 1_044_480);
        // 1/65536 · 255 = 0.0039 rounds to 0; · 2^8 = 0.996 rounds to 1.
        assert_eq!(scale255(1, 0), 0);
        assert_eq!(scale255(1, 8), 1);
        for v in (0..=4 << 16).step_by(977) {
            for k in [4, 6, 13, 19] {
                let exact = f64::from(v) * 255.0 * f64::from(1u32 << k) / 65536.0;
                assert_eq!(scale255(v, k), exact.round() as u64, "v={v} k={k}");
            }
        }
    }

    #[test]
    fn unit30_within_2_pow_minus_29() {
        assert_eq!(unit30([0; 3]), [0; 3]);
        assert_eq!(unit30([0, 0, 5]), [0, 0, 1 << 30]);
        assert_eq!(unit30([-7, 0, 0]), [-(1 << 30), 0, 0]);
        let mut worst = 0.0f64;
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for i in 0..3000 {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            // Magnitudes from 2^1 to 2^61.
            let sh = 2 + (i % 60);
            let c = |k: u32| ((x.rotate_left(k) as i64) >> sh) | 1;
            let v = [c(0), c(21), c(42)];
            let n = v.iter().map(|&c| (c as f64).powi(2)).sum::<f64>().sqrt();
            let u = unit30(v);
            for (&c, &uc) in v.iter().zip(&u) {
                let err = (c as f64 / n * f64::from(1 << 30) - f64::from(uc)).abs();
                worst = worst.max(err);
            }
        }
        assert!(worst <= 2.0, "worst {worst} units of 2^-30");
    }

    #[test]
    fn light_halves_match_their_definitions() {
        let s = f64::from(1 << 30);
        for l in [
            [0, 0, 1 << 30],
            [1 << 30, 0, 0],
            [0, -(1 << 30), 0],
            unit30([3, -4, 12]),
            unit30([-1, 2, -2]),
        ] {
            let lf = l.map(|c| f64::from(c) / s);
            let (a, b) = light_halves(l, false);
            let r = core::f64::consts::FRAC_1_SQRT_2;
            let want_a = [lf[0] * r, lf[1] * r, (lf[2] + 1.0) * r];
            let want_b = [lf[0] * r, lf[1] * r, (lf[2] - 1.0) * r];
            for i in 0..3 {
                assert!((f64::from(a[i]) - want_a[i] * s).abs() <= 1.0, "{l:?}");
                assert!((f64::from(b[i]) - want_b[i] * s).abs() <= 1.0, "{l:?}");
            }
            let (h, z) = light_halves(l, true);
            assert_eq!(z, [0; 3]);
            if l == [0, 0, 1 << 30] {
                assert_eq!(h, [0, 0, 1 << 30]);
            }
            let sum = [lf[0], lf[1], lf[2] + 1.0];
            let n = sum.iter().map(|c| c * c).sum::<f64>().sqrt();
            if n > 0.0 {
                for i in 0..3 {
                    assert!((f64::from(h[i]) - sum[i] / n * s).abs() <= 2.0, "{l:?}");
                }
            } else {
                assert_eq!(h, [0; 3]);
            }
        }
    }
}
