//! Back faces decided in object space, before any vertex is transformed.
//!
//! The geometry stage culls a triangle by the exact sign of its projected,
//! rounded subpixel corners (`render::prepare`). [`EarlyCull`] finds,
//! before the vertex work, the vertices all of whose faces are
//! *certainly* back-facing: faces whose rounded corners must give a
//! positive (back-facing) signed area, whatever the rounding. Those
//! vertices are neither projected nor lit, the triangles using them are
//! dropped, and every other triangle takes the screen test as before, so
//! the kept triangles and the frame are bit for bit those of the screen
//! test alone. On the bunny benchmark 669 of the 1 839 vertices are
//! skipped.
//!
//! # The rule and its proof
//!
//! Let `M`, `t` be the object's `Q16` model-view (exact rationals), `K =
//! k·2^sub` the projection scale in subpixels, `p = M c + t` the eye-space
//! point of mesh point `c`, `w = -p_z > 0`, and `ŝ = C + K (p_x/w, -p_y/w)`
//! the exact projection. The fused kernel places every vertex within `δ =
//! 1/2 + err` subpixels of `ŝ` per coordinate (`Fused::err16`), so each
//! rounded edge differs from the exact one by at most `η = 2δ` per
//! coordinate and the rounded doubled area `D` from the exact `D̂` by at
//! most `η (|ê₁|₁ + |ê₂|₁) + 2η²` (`ê₁, ê₂` the exact edges at any one
//! corner). Hence `D̂ > η (|ê₁|₁ + |ê₂|₁) + 2η²` implies `D > 0`: culled
//! by the screen test.
//!
//! `D̂ = K² det(p₀, p₁, p₂) / (w₀w₁w₂)`, and `det(p₀, p₁, p₂) = det(M)
//! · 2A · g` with `2A` the doubled object-space area, `n̂` the unit face
//! normal and `g = n̂ · (P - E)` the signed distance of the face's plane
//! from the eye `E = -M⁻¹ t` in object space (`P` any corner). An exact
//! edge from corner `i` to `j` is `K (Δx - u_i Δw, Δy - v_i Δw) / w_j`
//! (`u, v` the projected offsets of corner `i`, `|u| + |v| <= ρ` over the
//! object), so `|ê|₁ <= K σ √(2 + ρ²) ℓ / w_min` with `σ` a bound of
//! `M`'s stretch and `ℓ` the edge's object-space length. With `w_min <=
//! w_i <= w_max` over the object (bounding box and sphere), the sign is
//! certain when
//!
//! `g > α (ℓ₁ + ℓ₂)/(2A) + β/(2A)`, `α = η σ √(2 + ρ²) w_max³ / (K w_min
//! det M)`, `β = 2η² w_max³ / (K² det M)`.
//!
//! A face's baked slack is at least `4 (ℓ₁ + ℓ₂ + λ)/(2A)` (`λ = 2^-8`,
//! [`face_plane`](super::exact::face_plane)), so with `γ = max(α, β/λ)`
//! the condition `g > γ · slack / 4` suffices. A vertex bakes the largest
//! slack of its faces and a spread `s` with `|n̂_f - a| <= s` for each of
//! its faces `f` (`a` its normal, the cone's axis;
//! [`cone_covers`](super::exact::cone_covers) checks both exactly). Since `g_f = n̂_f · (P - E) >= a · (P - E) - s
//! |P - E|`, every face of the vertex is certainly back when
//!
//! `a · (P - E) > γ · slack / 4 + s · R_E + m_E`,
//!
//! `R_E >= |P - E|` over the mesh, and `m_E = 1.0002·√3·2^-fe` the error
//! of `a · E` with `E` rounded down to `2^-fe`. The per-object constants
//! are computed once, in integers (a 32-bit mantissa and an exponent,
//! every operation rounded towards the safe side: upper bounds for the
//! threshold's factors, lower bounds for their divisors).
//!
//! Per vertex the test is 32-bit: `(d >> sh) - a · E_q > gm · slack + rk
//! · spread + bias` with the baked `d = a · P` (see [`EarlyCull::margin`]
//! for the ranges: nothing wraps). Only objects with `det M > 0` use it.

use super::bound::Bound;
use super::exact::{SLACK_FRAC_BITS, SLACK_LENGTH};

/// Object-space back-face test of one object (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct EarlyCull {
    /// The eye in object space, `2^-fe` units, each `|e_k| < 2^12`.
    e: [i32; 3],
    /// `14 - fe`: the plane offset's shift to `E`'s scale (2..=30).
    sh: u32,
    /// The threshold factor `γ·2^(14 + fe - SLACK_FRAC_BITS)`, rounded
    /// up, in `[2^13, 2^14]` (`fe` is chosen for it).
    gm: i32,
    /// `R_E · 2^fe`, rounded up, below `2^13`: the spread's factor.
    rk: i32,
}

/// `⌊√n⌋ + 1`: strictly above `√n`.
fn sqrt_up(n: u64) -> u64 {
    crate::num::isqrt_u64(n) + 1
}

/// Significant bits of `v` (`128 - v.leading_zeros()`), from its highest
/// non-zero 32-bit word: one count of leading zeros (a library call on
/// the Cortex-M0, which has no instruction for it) rather than four.
#[inline(always)]
fn bits128(v: u128) -> u32 {
    #[allow(clippy::cast_possible_truncation)]
    let words = [
        (v >> 96) as u32,
        (v >> 64) as u32,
        (v >> 32) as u32,
        v as u32,
    ];
    let mut top = 128;
    for w in words {
        if w != 0 {
            return top - w.leading_zeros();
        }
        top -= 32;
    }
    0
}

/// An upper bound `m · 2^e` of a positive quantity (`m < 2^32` once
/// normalised): every operation rounds up, so the result bounds the exact
/// value from above. Integer only (no soft-float on the Cortex-M0).
#[derive(Clone, Copy, Debug)]
struct Up {
    m: u64,
    e: i32,
}

/// A lower bound `m · 2^e` (operations round down), for divisors.
#[derive(Clone, Copy, Debug)]
struct Dn {
    m: u64,
    e: i32,
}

impl Up {
    /// `v · 2^e`, rounded up to a 32-bit mantissa.
    // Not inlined (nor are the other 128-bit steps of the set-up): a
    // 128-bit variable shift takes a stack slot of its own on the
    // Cortex-M targets, inlined copies one each (about 2.6 KB of stack
    // in all under the object pass).
    #[inline(never)]
    fn new(v: u128, e: i32) -> Self {
        let bits = bits128(v);
        if bits <= 32 {
            return Self { m: v as u64, e };
        }
        // ⌈v / 2^s⌉ (at most 2^32: still an exact upper bound).
        let s = bits - 32;
        let low = v & ((1u128 << s) - 1);
        Self {
            m: (v >> s) as u64 + u64::from(low != 0),
            e: e + s as i32,
        }
    }

    fn mul(self, o: Self) -> Self {
        Self::new(u128::from(self.m) * u128::from(o.m), self.e + o.e)
    }

    /// `self / o`, `None` for a zero divisor.
    fn div(self, o: Dn) -> Option<Self> {
        // m <= 2^32: m 2^31 < 2^64, a 64-bit division; the divisor's
        // mantissa has 32 bits unless the divisor is small and exact.
        let q = (self.m << 31).checked_div(o.m)?;
        Some(Self::new(u128::from(q) + 1, self.e - 31 - o.e))
    }

    /// `self · 2^k`.
    fn shl(self, k: i32) -> Self {
        Self {
            m: self.m,
            e: self.e + k,
        }
    }

    /// Both mantissas at the smaller exponent (`None` beyond 2^90 apart).
    #[inline(never)]
    fn align(self, o: Self) -> Option<(u128, u128, i32)> {
        let e = self.e.min(o.e);
        let (da, db) = ((self.e - e) as u32, (o.e - e) as u32);
        if da > 90 || db > 90 {
            return None;
        }
        Some((u128::from(self.m) << da, u128::from(o.m) << db, e))
    }

    fn add(self, o: Self) -> Option<Self> {
        let (a, b, e) = self.align(o)?;
        Some(Self::new(a + b, e))
    }

    fn max(self, o: Self) -> Option<Self> {
        let (a, b, _) = self.align(o)?;
        Some(if a >= b { self } else { o })
    }

    /// An upper bound of the square root.
    fn sqrt(self) -> Self {
        // m · 2^e with e even, m < 2^33; m 2^30 < 2^63.
        let (m, e) = if self.e % 2 == 0 {
            (self.m, self.e)
        } else {
            (self.m << 1, self.e - 1)
        };
        Self::new(u128::from(sqrt_up(m << 30)), (e - 30) / 2)
    }

    /// `⌈self⌉` (`None` from `2^32 · 2^31` on).
    fn ceil(self) -> Option<u64> {
        if self.e >= 0 {
            // m < 2^32: the shift stays below 2^64.
            (self.e < 32).then(|| self.m << self.e)
        } else if self.e <= -64 {
            Some(u64::from(self.m > 0))
        } else {
            let s = (-self.e) as u32;
            Some((self.m >> s) + u64::from(self.m & ((1 << s) - 1) != 0))
        }
    }
}

impl Dn {
    /// `v · 2^e`, rounded down to a 32-bit mantissa.
    #[inline(never)]
    fn new(v: u128, e: i32) -> Self {
        let bits = bits128(v);
        let s = bits.saturating_sub(32);
        Self {
            m: (v >> s) as u64,
            e: e + s as i32,
        }
    }

    fn mul(self, o: Self) -> Self {
        Self::new(u128::from(self.m) * u128::from(o.m), self.e + o.e)
    }
}

// λ = 2^-8: β/λ is β shifted by 8 bits.
const _: () = assert!(SLACK_LENGTH == 64);

/// At least `1.0002 · √3 · 2^14 < 28 384`: the error of `a · E` with `E`
/// rounded down to `2^-fe` (`|a| <= 1.0002`), in units of `2^-(14 +
/// fe)`. A constant of every object, not a field, and `0x7000` = 28 672
/// rather than 28 384: a Thumb-2 immediate the marking loop adds without
/// a register (one value fewer live; a slightly larger threshold, the
/// same 669 vertices skipped on the bunny). Bunny Gouraud geometry 376
/// 107 -> 372 421 on the Cortex-M4 (636 634 -> 636 631 on the
/// Cortex-M0).
const BIAS: i32 = 28_672;

// Above `m_E` (28 384, checked by the test `bias_bounds_the_eye_error`)
// and within the bound [`EarlyCull::margin`] assumes (`2^26 + 1`).
const _: () = assert!(BIAS >= 28_384 && BIAS <= (1 << 26) + 1);

/// Whether every `|num_k| 2^fe` is below `4000 · det` (`fe` in
/// `-16..=12`, `|num_k| < 3·2^72`: no shift leaves 128 bits).
#[inline(never)]
fn below(num: &[i128; 3], dt: i128, fe: i32) -> bool {
    num.iter().all(|v| {
        if fe >= 0 {
            v.unsigned_abs() << fe < 4000 * dt.unsigned_abs()
        } else {
            v.unsigned_abs() < (4000 * dt.unsigned_abs()) << -fe
        }
    })
}

/// `⌊v 2^fe / dt⌋` (`dt > 0`; `|v| < 3·2^72`, `fe` in `-16..=12`: no
/// shift leaves i128) when it is below `2^12` in magnitude: within
/// `2^-fe` below `v / dt`.
#[inline(never)]
fn scaled_quotient(v: i128, fe: i32, dt: i128) -> Option<i32> {
    let q = if fe >= 0 {
        (v << fe).checked_div_euclid(dt)
    } else {
        v.checked_div_euclid(dt << -fe)
    };
    q.and_then(|q| i32::try_from(q).ok())
        .filter(|q| q.unsigned_abs() < 1 << 12)
}

impl EarlyCull {
    /// The test of an object with `Q16` model-view `m` (linear part) and
    /// `t`, projection scale `k` (raw `Q16`) and `sub` subpixel bits,
    /// whose mesh lies in `bound`, placed by the fused kernel within `1/2
    /// + err16/2^16` subpixels per coordinate. `None` when the object is
    ///   mirrored, its ranges exceed the ones proven here, or the test would
    ///   decide nothing (the caller then transforms every vertex).
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss,
        clippy::cast_possible_wrap
    )]
    pub(crate) fn new(
        m: &[[i32; 3]; 3],
        t: &[i32; 3],
        k: i32,
        sub: u32,
        bound: &Bound,
        err16: u32,
    ) -> Option<Self> {
        let mmax = m.iter().flatten().map(|v| v.unsigned_abs()).max()?;
        if mmax == 0 || mmax >= 1 << 20 || k <= 0 || sub > 15 || err16 > 1 << 14 {
            return None;
        }
        let m = m.map(|r| r.map(i64::from));
        let t = t.map(i64::from);
        // Cofactors (below 2^41) and determinant (below 3·2^61), raw
        // units 2^-32 and 2^-48.
        let o = |i: usize| [(i + 1) % 3, (i + 2) % 3];
        let cof = |r: usize, c: usize| {
            let ([r1, r2], [c1, c2]) = (o(r), o(c));
            let at = |i: usize, j: usize| m.get(i).and_then(|row| row.get(j)).copied();
            Some(at(r1, c1)? * at(r2, c2)? - at(r1, c2)? * at(r2, c1)?)
        };
        let det = (0..3).try_fold(0i64, |acc, j| Some(acc + m[0][j] * cof(0, j)?))?;
        if det <= 0 {
            return None;
        }
        // E = -adj(M) t / det M = -adj(m) t_raw / det(m), units (the
        // powers of two cancel); numerators below 3·2^72.
        let mut num = [0i128; 3];
        for (i, v) in num.iter_mut().enumerate() {
            for (j, tj) in t.iter().enumerate() {
                *v -= i128::from(cof(j, i)?) * i128::from(*tj);
            }
        }
        let dt = i128::from(det);
        // The largest fe <= 12 with every |E_k| 2^fe below 4000 (|E_k|
        // 2^fe < 2^12 after rounding; fe is lowered further below to scale
        // the threshold).
        let mut fe_max = 12i32;
        while !below(&num, dt, fe_max) {
            fe_max -= 1;
            if fe_max < -16 {
                return None;
            }
        }
        // Eye-space rows at the centre (Q30) and their reach over the
        // bounding box and sphere.
        let c = bound.center.map(i64::from);
        let h = bound.half.map(i64::from);
        let row = |r: usize| (0..3).map(|j| m[r][j] * c[j]).sum::<i64>() + (t[r] << 14);
        let reach = |r: usize| (0..3).map(|j| m[r][j].abs() * h[j]).sum::<i64>();
        // σ² <= the largest row sum of |MᵀM| (Q32, below 9·2^40).
        let g = |i: usize, j: usize| (0..3).map(|r| m[r][i] * m[r][j]).sum::<i64>().abs();
        let rows = (0..3).map(|i| (g(i, 0) + g(i, 1) + g(i, 2)) as u64);
        let sigma = sqrt_up(rows.max()?); // Q16
        let rad = i64::from(bound.radius.min(1 << 17));
        let sph = sigma as i64 * rad; // Q30
        let wc = -row(2);
        let wr = reach(2).min(sph);
        let (w_min, w_max) = (wc - wr, wc + wr);
        if w_min <= 0 {
            return None;
        }
        // √2 < 1449/1024.
        let xy = (reach(0) + reach(1)).min(((sph * 1449) >> 10) + 1);
        let rho_num = row(0).abs() + row(1).abs() + xy;
        // α = η σ √(2 + ρ²) w_max³ / (K w_min det M), β = 2η² w_max³ /
        // (K² det M), γ = max(α, β/λ) (λ = 2^-8), each rounded up.
        let up = |v: i64, e: i32| Up::new(u128::from(v.unsigned_abs()), e);
        let dn = |v: i64, e: i32| Dn::new(u128::from(v.unsigned_abs()), e);
        let rho = up(rho_num, -30).div(dn(w_min, -30))?;
        let sq = up(2, 0).add(rho.mul(rho))?.sqrt();
        let eta = up(65_536 + 2 * i64::from(err16), -16);
        let wh = up(w_max, -30);
        let w3 = wh.mul(wh).mul(wh);
        let kk = dn(i64::from(k), sub as i32 - 16);
        let (wl, dm) = (dn(w_min, -30), dn(det, -48));
        let alpha = eta
            .mul(up(sigma as i64, -16))
            .mul(sq)
            .mul(w3)
            .div(kk.mul(wl).mul(dm))?;
        let beta = up(2, 0).mul(eta).mul(eta).mul(w3).div(kk.mul(kk).mul(dm))?;
        let gamma = alpha.max(beta.shl(8))?;
        // R_E >= |P - E| for every mesh point P: the L1 distance of E to
        // the centre, |num_k 2^14 - c_k det| / (det 2^14) summed, and the
        // radius.
        let l1: u128 = (0..3)
            .map(|i| ((num[i] << 14) - i128::from(c[i]) * dt).unsigned_abs())
            .sum();
        let re = Up::new(l1, -14).div(dn(det, 0))?.add(up(rad, -14))?;
        // The scale: gm = ⌈γ·2^(14 + fe - SLACK_FRAC_BITS)⌉ in [2^13, 2^14).
        let sfb = SLACK_FRAC_BITS as i32;
        let mut fe = fe_max;
        let gm = loop {
            match gamma.shl(14 + fe - sfb).ceil() {
                Some(g) if g < 16_383 => break g,
                _ => {}
            }
            fe -= 1;
            if fe < -16 {
                return None;
            }
        };
        if gm < 8192 {
            // |E| too large for a finer scale: the threshold could not
            // keep the saturated slack out of reach.
            return None;
        }
        // The spread's factor: R_E 2^fe (spread in 2^-14 units).
        let rk = re.shl(fe).ceil().filter(|&r| r < 8191)?;
        let dt = i128::from(det);
        let e = [
            scaled_quotient(num[0], fe, dt)?,
            scaled_quotient(num[1], fe, dt)?,
            scaled_quotient(num[2], fe, dt)?,
        ];
        Some(Self {
            e,
            sh: (14 - fe) as u32,
            // Both below 2^14 (checked above).
            gm: gm as i32,
            rk: rk as i32,
        })
    }

    /// Whether the vertex is skipped: [`EarlyCull::margin`] is negative.
    #[cfg(test)]
    pub(crate) fn skip(&self, a: [i16; 3], cone: [i32; 2]) -> bool {
        self.margin(a, cone) < 0
    }

    /// Whether every face of the vertex with axis `a` (its normal) and
    /// cone `[d, slack | spread << 16]`
    /// ([`cone_covers`](super::exact::cone_covers), checked when the cones
    /// are baked) certainly faces away, as a sign: the threshold
    /// `gm · slack + rk · spread + BIAS` less the left side `(d >> sh) - a
    /// · e`, negative exactly when every face's rounded screen area is
    /// positive (the vertex then needs no projection). One value a vertex
    /// loop can store as its mark.
    ///
    /// No overflow: `|d >> sh| < 2^30 >> 2`, `|a · e| < 28 400 · 2^12 <
    /// 2^27`, so the left side is below `2^28 + 2^27`; the threshold is
    /// below `2^30 + 2^29 + 2^26 + 1`; every partial sum and the result
    /// below `2^30 + 2^29 + 2^28 + 2^27 + 2^26 + 1 < 2^31`. A slack of 65
    /// 535 (faces the bake could not bound) never passes: the threshold
    /// is then at least `2^13 · 65 535 > 2^28 + 2^27`.
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)]
    pub(crate) fn margin(&self, a: [i16; 3], cone: [i32; 2]) -> i32 {
        // `gm · slack + rk · spread` as `gm · w + (rk - 2^16 gm) · spread`
        // of the whole word `w = slack + 2^16 spread`: equal modulo 2^32,
        // so the wrapping sum below is the exact margin (which fits).
        let spread = ((cone[1] as u32) >> 16) as i32;
        let rk = self.rk.wrapping_sub(self.gm.wrapping_shl(16));
        // One sum: threshold + a·E - (d >> sh).
        BIAS.wrapping_add(i32::from(a[0]) * self.e[0])
            .wrapping_add(i32::from(a[1]) * self.e[1])
            .wrapping_add(i32::from(a[2]) * self.e[2])
            .wrapping_add(self.gm.wrapping_mul(cone[1]))
            .wrapping_add(rk.wrapping_mul(spread))
            .wrapping_sub(cone[0] >> self.sh)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// [`BIAS`] bounds `m_E = 1.0002·√3` in units of `2^-14` (the error
    /// of `a · E` with `E` rounded down, `|a| <= 1.0002`), and the largest
    /// axis length is within that `1.0002`.
    #[test]
    fn bias_bounds_the_eye_error() {
        let m_e = 1.0002 * 3f64.sqrt() * 16384.0;
        assert!(m_e < 28_384.0 && 28_384 <= BIAS, "{m_e}");
        assert!((MAX_AXIS2 as f64).sqrt() / 16384.0 <= 1.0002);
    }

    #[test]
    fn bits128_counts_the_significant_bits() {
        assert_eq!(bits128(0), 0);
        for k in 0..128 {
            let v = 1u128 << k;
            assert_eq!(bits128(v), k + 1);
            assert_eq!(bits128(v | (v >> 1) | 1), k + 1);
            assert_eq!(bits128(v - 1), k);
        }
        assert_eq!(bits128(u128::MAX), 128);
    }
    use crate::geom::exact::{cone_covers, face_normal, face_plane, MAX_AXIS2};
    use crate::geom::fused::Fused;
    use crate::geom::testkit::{proj, rotation, uniform};

    /// Whenever [`EarlyCull::back`] holds, the fused kernel's rounded
    /// corners give a positive doubled area (the screen test culls the
    /// face too), on random objects and random faces: ordinary ones,
    /// slivers, and faces nearly edge-on to the eye (the uncertain ones).
    /// And the test decides most back faces that are not nearly edge-on.
    #[test]
    fn certain_back_faces_are_back_on_screen() {
        let mut u = uniform(0x5eed_cafe_1234_5678);
        let (mut objects, mut faces, mut back, mut decided, mut edge_on) = (0, 0, 0, 0, 0);
        let (mut clear_back, mut clear_decided) = (0, 0);
        for i in 0..1500 {
            let sub = [4u32, 4, 2, 6][i % 4];
            let k = 80.0 + 500.0 * u();
            let near = [1.0, 0.5, 0.1][i % 3];
            let pj = proj(k, near, sub, 100);
            let sc = 0.3 + 2.5 * u();
            let (a, b, c) = (6.3 * u(), 6.3 * u(), 6.3 * u());
            let r = rotation(a, b, c);
            // Mostly uniform, sometimes stretched along one axis.
            let st = if i % 5 == 0 {
                [1.0, 1.6, 0.7]
            } else {
                [1.0; 3]
            };
            let m = [0, 1, 2]
                .map(|row| [0, 1, 2].map(|j| (r[row][j] * st[j] * sc * 65536.0).round() as i32));
            let dist = near + sc * 2.5 + 10.0 * u();
            let t = [(u() - 0.5) * dist * 0.4, (u() - 0.5) * dist * 0.4, -dist]
                .map(|v| (v * 65536.0).round() as i32);
            let center = [0; 3].map(|_| ((u() - 0.5) * 4000.0) as i16);
            let half = [0; 3].map(|_| 3000 + (u() * 9000.0) as u16);
            let radius = {
                let h2: f64 = half.iter().map(|&h| f64::from(h) * f64::from(h)).sum();
                h2.sqrt().ceil() as u32
            };
            let bound = Bound {
                center,
                radius,
                half,
            };
            let Some(f) = Fused::new(&m, &t, &pj, sub, None, &bound) else {
                continue;
            };
            let Some(cull) = EarlyCull::new(&m, &t, pj.k, sub, &bound, f.err16) else {
                continue;
            };
            objects += 1;
            // The eye in object space (f64).
            let mf = m.map(|row| row.map(|v| f64::from(v) / 65536.0));
            let tf = t.map(|v| f64::from(v) / 65536.0);
            let inv = inverse(mf);
            let eye = [0, 1, 2].map(|i| -(0..3).map(|j| inv[i][j] * tf[j]).sum::<f64>());
            let point = |u: &mut dyn FnMut() -> f64| {
                [0, 1, 2].map(|j| f64::from(center[j]) + (u() - 0.5) * 2.0 * f64::from(half[j]))
            };
            for n in 0..300 {
                let p0 = point(&mut u);
                let size = [40.0, 400.0, 3000.0][n % 3] * (0.2 + u());
                let d1 = [u() - 0.5, u() - 0.5, u() - 0.5].map(|v| v * size);
                let mut d2 = [u() - 0.5, u() - 0.5, u() - 0.5].map(|v| v * size);
                if n % 4 == 1 {
                    // Nearly edge-on: the second edge close to the plane
                    // through the eye and the first edge.
                    let to_eye = [0, 1, 2].map(|j| eye[j] * 16384.0 - p0[j]);
                    let l = to_eye.iter().map(|v| v * v).sum::<f64>().sqrt();
                    let w = (u() - 0.5) * 0.05;
                    d2 = [0, 1, 2].map(|j| d2[j] * w + to_eye[j] / l * size * (u() - 0.3));
                    d2 = [0, 1, 2].map(|j| d2[j] + d1[j] * (u() - 0.5));
                } else if n % 4 == 2 {
                    // A sliver.
                    d2 = [0, 1, 2].map(|j| d1[j] * (0.3 + u()) + d2[j] * 0.01);
                }
                let q = |v: [f64; 3]| -> Option<[i16; 3]> {
                    let r = v.map(|x| x.round());
                    let inside =
                        (0..3).all(|j| (r[j] - f64::from(center[j])).abs() <= f64::from(half[j]));
                    inside.then(|| r.map(|x| x as i16))
                };
                let (Some(a), Some(b), Some(c)) = (
                    q(p0),
                    q([0, 1, 2].map(|j| p0[j] + d1[j])),
                    q([0, 1, 2].map(|j| p0[j] + d2[j])),
                ) else {
                    continue;
                };
                faces += 1;
                let xy = [a, b, c].map(|p| f.project::<true>(p).0);
                let det = |p: [[i32; 2]; 3]| {
                    let [a, b, c] = p.map(|v| v.map(i64::from));
                    (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])
                };
                let d = det(xy);
                let nrm = face_normal(a, b, c);
                // Corner `a` as a vertex whose only face this is, its
                // axis the face normal turned a little (odd faces).
                let axis = if n % 2 == 1 {
                    nrm.map(|v| v.saturating_add(((u() - 0.5) * 900.0) as i16))
                } else {
                    nrm
                };
                let axis = if axis.iter().map(|&v| i64::from(v).pow(2)).sum::<i64>() > MAX_AXIS2 {
                    nrm
                } else {
                    axis
                };
                let slack = face_plane(a, b, c)[1];
                let mut spread = 0u16;
                while slack < 65535 && !cone_covers(axis, spread, a, b, c) {
                    spread += 1;
                }
                let d0: i64 = (0..3).map(|k| i64::from(axis[k]) * i64::from(a[k])).sum();
                let cone = [d0 as i32, slack | (i32::from(spread) << 16)];
                let is_back = cull.skip(axis, cone);
                if is_back {
                    assert!(d > 0, "object {i} face {n}: culled early, screen area {d}");
                    decided += 1;
                }
                if d > 0 {
                    back += 1;
                    // Clearly back: the eye at least 20° off the plane.
                    let nf = nrm.map(|v| f64::from(v) / 16384.0);
                    let to = [0, 1, 2].map(|j| eye[j] - f64::from(a[j]) / 16384.0);
                    let l = to.iter().map(|v| v * v).sum::<f64>().sqrt();
                    let cos = -(0..3).map(|j| nf[j] * to[j]).sum::<f64>() / l;
                    if cos > 0.34 && d > 16 * 256 {
                        clear_back += 1;
                        clear_decided += usize::from(is_back);
                    }
                }
                edge_on += usize::from(n % 4 == 1 && d > 0 && !is_back);
            }
        }
        std::println!(
            "early cull: {objects} objects, {faces} faces, {back} back, {decided} decided early, \
             {edge_on} edge-on left to the screen; clearly back {clear_decided} of {clear_back}"
        );
        assert!(objects > 800, "{objects}");
        assert!(edge_on > 1000, "{edge_on}");
        assert!(decided * 4 > back, "{decided} of {back}");
        assert!(
            clear_decided * 10 > clear_back * 9,
            "{clear_decided} of {clear_back}"
        );
    }

    fn inverse(m: [[f64; 3]; 3]) -> [[f64; 3]; 3] {
        let c = |r: usize, k: usize| {
            let (r1, r2, k1, k2) = ((r + 1) % 3, (r + 2) % 3, (k + 1) % 3, (k + 2) % 3);
            m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1]
        };
        let det: f64 = (0..3).map(|j| m[0][j] * c(0, j)).sum();
        [0, 1, 2].map(|i| [0, 1, 2].map(|j| c(j, i) / det))
    }

    /// Mirrored objects and out-of-range matrices are left to the screen
    /// test; the test's integer terms stay within their proven ranges.
    #[test]
    fn mirrored_and_huge_objects_are_not_decided_early() {
        let pj_k = 290 << 16;
        let bound = Bound {
            center: [0; 3],
            radius: 28378,
            half: [16384; 3],
        };
        let t = [0, 0, -4 << 16];
        let id = [[65536, 0, 0], [0, 65536, 0], [0, 0, 65536]];
        let c = EarlyCull::new(&id, &t, pj_k, 4, &bound, 100).expect("identity");
        assert!(c.e.iter().all(|v| v.unsigned_abs() < 1 << 12));
        assert!((1 << 13..=1 << 14).contains(&c.gm));
        assert!((2..=30).contains(&c.sh));
        let mirror = [[-65536, 0, 0], [0, 65536, 0], [0, 0, 65536]];
        assert!(EarlyCull::new(&mirror, &t, pj_k, 4, &bound, 100).is_none());
        let huge = [[1 << 20, 0, 0], [0, 1 << 20, 0], [0, 0, 1 << 20]];
        assert!(EarlyCull::new(&huge, &t, pj_k, 4, &bound, 100).is_none());
        // The eye inside the box's depth range: no w bound.
        assert!(EarlyCull::new(&id, &[0, 0, -(1 << 16)], pj_k, 4, &bound, 100).is_none());
        // A face with the saturated slack is never decided, even with the
        // eye far behind it.
        assert!(!c.skip([0, 0, -16384], [(1 << 30) - 1, 65535]));
        assert!(c.skip([0, 0, -16384], [0, 100]));
        // A wide cone is not decided where a narrow one is.
        assert!(!c.skip([0, 0, -16384], [0, 100 | (20000 << 16)]));
    }
}
