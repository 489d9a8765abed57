//! Integer kernels of the `fast` profiles' vertex path: raw Q16.16 values
//! in `i32`, mesh data in Q1.14 (`i16`). Used for the scalars that run
//! them ([`Q16Kernels`](crate::num::Q16Kernels)); every kernel is exact integer arithmetic
//! up to one stated rounding, so all targets compute the same bits (the
//! ARMv6-M variants are tested against the generic ones).

use super::Affine;
use crate::num::approx16::{recip_mant, rsqrt_newton};
use crate::num::wide::{clz32, mul_u16_u32, sq_u32, wmul, wmul_u32};
use crate::num::{Raw16, Real, COORD_LIMIT_PX};

/// Largest matrix entry magnitude (exclusive) of the integer transform:
/// 256 (a model scale up to about 256). Larger transforms use the generic
/// path.
const M_LIMIT: u32 = 1 << 24;

/// An affine transform in raw Q16 for Q1.14 mesh coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Xform16 {
    /// The linear part (read by [`row_wide`]: every target but ARMv6-M).
    #[cfg_attr(armv6m, allow(dead_code))]
    m: [[i32; 3]; 3],
    /// `m >> 14` and `m & 0x3FFF`, the halves of [`row_split_pre`] (the
    /// ARMv6-M path), split once per transform rather than per product.
    #[cfg_attr(not(armv6m), allow(dead_code))]
    mh: [[i32; 3]; 3],
    #[cfg_attr(not(armv6m), allow(dead_code))]
    ml: [[i32; 3]; 3],
    t: [i32; 3],
}

impl Xform16 {
    /// `round(Σ m_kj c_j / 2^14)` exactly (ties up), for `|m_kj| < 2^24`.
    #[inline(always)]
    fn row(&self, k: usize, c: [i16; 3]) -> i32 {
        #[cfg(armv6m)]
        {
            row_split_pre(&self.mh[k], &self.ml[k], c)
        }
        #[cfg(not(armv6m))]
        {
            row_wide(&self.m[k], c)
        }
    }
}

/// [`Xform16::row`] with `i64` products.
#[inline(always)]
#[cfg_attr(armv6m, allow(dead_code))]
#[allow(clippy::cast_possible_truncation)]
fn row_wide(m: &[i32; 3], c: [i16; 3]) -> i32 {
    let s = i64::from(m[0]) * i64::from(c[0])
        + i64::from(m[1]) * i64::from(c[1])
        + i64::from(m[2]) * i64::from(c[2]);
    // |s| < 3 · 2^39: the result is below 3 · 2^25.
    ((s + (1 << 13)) >> 14) as i32
}

/// [`Xform16::row`] with 32-bit products only: `m = 2^14 mh + ml`, `ml` in
/// `[0, 2^14)`, so `Σ ml c < 3 · 2^29` and `Σ mh c < 3 · 2^25`, and
/// `floor((2^14 A + B + 2^13) / 2^14) = A + floor((B + 2^13) / 2^14)`.
#[cfg(test)]
fn row_split(m: &[i32; 3], c: [i16; 3]) -> i32 {
    row_split_pre(&m.map(|v| v >> 14), &m.map(|v| v & 0x3FFF), c)
}

/// [`row_split`] with the halves `mh = m >> 14`, `ml = m & 0x3FFF` given.
#[inline(always)]
#[cfg_attr(not(armv6m), allow(dead_code))]
fn row_split_pre(mh: &[i32; 3], ml: &[i32; 3], c: [i16; 3]) -> i32 {
    let c = c.map(i32::from);
    let a = mh[0] * c[0] + mh[1] * c[1] + mh[2] * c[2];
    let b = ml[0] * c[0] + ml[1] * c[1] + ml[2] * c[2];
    a + ((b + (1 << 13)) >> 14)
}

impl Xform16 {
    /// The integer form of `Q16` transform `a` (its raw bits read by `q`,
    /// which [`Kernels`](crate::num::Kernels) hands out for
    /// `Q16` only), or `None` when an entry of the linear part reaches
    /// 256.
    pub(crate) fn new<R: Real>(q: Raw16<R>, a: &Affine<R>) -> Option<Self> {
        let raw = |v: R| q.raw(v);
        let m = a.m.rows.map(|r| [raw(r.x), raw(r.y), raw(r.z)]);
        if m.iter().flatten().any(|v| v.unsigned_abs() >= M_LIMIT) {
            return None;
        }
        Some(Self {
            m,
            mh: m.map(|r| r.map(|v| v >> 14)),
            ml: m.map(|r| r.map(|v| v & 0x3FFF)),
            t: [raw(a.t.x), raw(a.t.y), raw(a.t.z)],
        })
    }

    /// The linear part and the translation, raw `Q16`.
    pub(crate) fn parts(&self) -> (&[[i32; 3]; 3], &[i32; 3]) {
        (&self.m, &self.t)
    }

    /// A Q1.14 point transformed, in raw Q16: the exact value rounded to
    /// nearest once (<= 1/2 ulp), the translation added with saturation.
    #[inline]
    pub(crate) fn point(&self, c: [i16; 3]) -> [i32; 3] {
        [
            self.row(0, c).saturating_add(self.t[0]),
            self.row(1, c).saturating_add(self.t[1]),
            self.row(2, c).saturating_add(self.t[2]),
        ]
    }

    /// A Q1.14 direction transformed (no translation), in raw Q16, rounded
    /// once (<= 1/2 ulp).
    #[inline]
    pub(crate) fn vector(&self, c: [i16; 3]) -> [i32; 3] {
        [self.row(0, c), self.row(1, c), self.row(2, c)]
    }
}

/// The cross product `(b - a) × (c - a)` of Q1.14 points scaled down by a
/// power of two so that every component fits `i16` (direction kept to 15
/// bits, truncated towards zero), for [`Xform16::vector`] and a
/// normalisation. Exact integer products (32-bit when the edges are
/// shorter than 2^15, which is every edge of a mesh within the unit cube).
#[allow(dead_code)] // not yet used: see the report of the wt-geom branch
pub(crate) fn face_cross(a: [i16; 3], b: [i16; 3], c: [i16; 3]) -> [i16; 3] {
    let e1 = [0, 1, 2].map(|k| i32::from(b[k]) - i32::from(a[k]));
    let e2 = [0, 1, 2].map(|k| i32::from(c[k]) - i32::from(a[k]));
    let small = e1
        .iter()
        .chain(e2.iter())
        .all(|v| v.unsigned_abs() < 1 << 15);
    let x: [i64; 3] = if small {
        // |products| < 2^30: the differences fit i32.
        [
            i64::from(e1[1] * e2[2] - e1[2] * e2[1]),
            i64::from(e1[2] * e2[0] - e1[0] * e2[2]),
            i64::from(e1[0] * e2[1] - e1[1] * e2[0]),
        ]
    } else {
        [
            wmul(e1[1], e2[2]) - wmul(e1[2], e2[1]),
            wmul(e1[2], e2[0]) - wmul(e1[0], e2[2]),
            wmul(e1[0], e2[1]) - wmul(e1[1], e2[0]),
        ]
    };
    let max = x[0]
        .unsigned_abs()
        .max(x[1].unsigned_abs())
        .max(x[2].unsigned_abs());
    let bits = 64 - max.leading_zeros();
    let sh = bits.saturating_sub(15);
    // Magnitudes shifted below 2^15; the sign applied after the shift so
    // that both signs truncate alike.
    x.map(|v| {
        let m = (v.unsigned_abs() >> sh) as i16;
        if v < 0 {
            -m
        } else {
            m
        }
    })
}

/// [`face_normal`](super::exact::face_normal), bit for bit, without its
/// 64-bit square root and divisions when every edge is shorter than
/// 2^15 (every mesh within the unit cube; longer edges call it).
///
/// Same steps and the same integers: the exact cross product (32-bit),
/// its largest magnitude scaled into `[2^30, 2^31)`, `L = ⌊√S⌋` of the
/// exact sum of squares `S`, and `round(s · 2^14 / L)` per component
/// (halves away from zero). `L` and the quotients are first estimated
/// ([`rsqrt_newton`](crate::num::approx16::rsqrt_newton): a few units of
/// `L`; [`recip_mant`]: within one of the quotient) and then corrected
/// with exact 64-bit comparisons, so the result is exact (no
/// approximation error; tested against the reference).
pub(crate) fn face_normal_q14(a: [i16; 3], b: [i16; 3], c: [i16; 3]) -> [i16; 3] {
    let e1 = [0, 1, 2].map(|k| i32::from(b[k]) - i32::from(a[k]));
    let e2 = [0, 1, 2].map(|k| i32::from(c[k]) - i32::from(a[k]));
    let or = [e1[0], e1[1], e1[2], e2[0], e2[1], e2[2]]
        .iter()
        .fold(0, |o, v| o | v.unsigned_abs());
    if or >= 1 << 15 {
        return super::exact::face_normal(a, b, c);
    }
    // |products| < 2^30: the differences fit i32.
    let x = [
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    ];
    let mag = x.map(i32::unsigned_abs);
    let max = mag[0].max(mag[1]).max(mag[2]);
    if max == 0 {
        return [0; 3];
    }
    // max < 2^31: scaling up (exact), the largest into [2^30, 2^31).
    // `clz32`: a table lookup on the M0 rather than a `__clzsi2` call.
    let sh = clz32(max) - 1;
    let s = mag.map(|m| m << sh);
    // S < 3 · 2^62.
    let sum = sq_u32(s[0]) + sq_u32(s[1]) + sq_u32(s[2]);
    // Estimate √S from the top 32 bits: S ≈ f · 2^60 (m = 4 hi) or
    // f · 2^62 (m = hi), f = m / 2^30 in [1, 4); √S = √f · 2^30 or 2^31
    // and √f · 2^30 = m · rsqrt / 2^31.
    #[allow(clippy::cast_possible_truncation)]
    let hi = (sum >> 32) as u32; // >= 2^28
    let (m, up) = if hi < 1 << 30 {
        (hi << 2, false)
    } else {
        (hi, true)
    };
    let y = rsqrt_newton(m); // <= 2^31
    #[allow(clippy::cast_possible_truncation)]
    let my = wmul_u32(m, y);
    #[allow(clippy::cast_possible_truncation)]
    let mut len = if up { my >> 30 } else { my >> 31 } as u32;
    // Within a few units (2^-28.5 relative of at most 2^32, and the dropped
    // low bits of S): step to the exact floor root. (len + 1)² < 2^64.
    // One square, then steps of (len ± 1)² = len² ± (2 len ∓ 1).
    let mut sq = sq_u32(len);
    while sq > sum && len > 0 {
        sq -= 2 * u64::from(len) - 1;
        len -= 1;
    }
    while len < u32::MAX && sum - sq > 2 * u64::from(len) {
        sq += 2 * u64::from(len) + 1;
        len += 1;
    }
    // len in [2^30, 2^32): 1/len = 2^lz / m2 with m2 = f 2^31, f in [1, 2).
    // len >= 2^30 (the largest scaled component is >= 2^30): lz is 0 or
    // 1 (a comparison, not a `__clzsi2` call on the M0).
    let lz = u32::from(len < 1 << 31);
    let r = recip_mant(len << lz); // 2^30 / f within 2^-17 relative
    let half = u64::from(len >> 1);
    let q = |sk: u32| -> u32 {
        // s 2^14 / len = s r 2^lz / 2^47 (s < 2^31, r <= 2^30).
        let p = wmul_u32(sk, r);
        // The shift from the high half (p < 2^61): `p >> 46` or `p >> 45`
        // written on `u64` were merged into one variable 64-bit shift, an
        // `__aeabi_llsr` call on the M0.
        #[allow(clippy::cast_possible_truncation)]
        let p_hi = (p >> 32) as u32;
        let est = if lz == 0 { p_hi >> 14 } else { p_hi >> 13 };
        let mut q = ((est + 1) >> 1).min(1 << 15);
        // num = s 2^14 + len/2; exact: q = floor(num / len).
        let num = (u64::from(sk) << 14) + half;
        // One product, then steps of len.
        let mut prod = mul_u16_u32(q, len);
        while prod > num && q > 0 {
            prod -= u64::from(len);
            q -= 1;
        }
        while num - prod >= u64::from(len) {
            prod += u64::from(len);
            q += 1;
        }
        q
    };
    // q <= 2^14: the casts are exact.
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    let out = |k: usize| {
        let v = q(s[k]) as i16;
        if x[k] < 0 {
            -v
        } else {
            v
        }
    };
    [out(0), out(1), out(2)]
}

/// Projection constants in raw Q16 (see [`Proj16::project`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Proj16 {
    /// Projection scale `k` (pixels per unit at distance 1), raw Q16.
    pub k: i32,
    /// Near plane distance, raw Q16.
    pub near: i32,
    /// Screen centre in subpixels.
    pub cx: i32,
    /// Screen centre in subpixels.
    pub cy: i32,
    /// Coordinate limit in subpixels.
    pub lim: i32,
}

/// `round(p / 2^s)` of a wide value, ties up, `s` in `1..=62`, clamped
/// to `±lim` (`lim >= 0`), for `|p| < 2^62`.
///
/// In 32-bit halves: no variable 64-bit shift (a call of `__aeabi_lasr`
/// on the Cortex-M0) and no 64-bit comparisons. The same result as
/// [`shr_round_clamp_wide`], exactly (tested).
#[inline(always)]
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_possible_wrap
)]
fn shr_round_clamp(p: i64, s: u32, lim: i32) -> i32 {
    let (rhi, rlo) = shr_round_halves(p, s);
    let r = rlo as i32;
    // The value fits `i32` iff the high half is the sign of the low.
    let v = if rhi == r >> 31 {
        r
    } else if rhi < 0 {
        i32::MIN
    } else {
        i32::MAX
    };
    v.max(lim.wrapping_neg()).min(lim)
}

/// [`shr_round_clamp`] without the clamp, for results known to lie
/// within `±lim <= 2^30`: the same value then (tested), fewer
/// instructions (no saturation to `i32`, no clamp).
#[inline(always)]
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_possible_wrap
)]
fn shr_round(p: i64, s: u32) -> i32 {
    // The low half of the rounded quotient: the value, as it fits.
    shr_round_halves(p, s).1 as i32
}

/// `floor((p + 2^(s-1)) / 2^s)` (`round(p / 2^s)`, ties up), `s` in
/// `1..=62`, `|p| < 2^62` (the sum fits), as its high and low 32-bit
/// halves, computed in 32-bit halves.
#[inline(always)]
#[allow(
    clippy::cast_possible_truncation,
    clippy::cast_sign_loss,
    clippy::cast_possible_wrap
)]
fn shr_round_halves(p: i64, s: u32) -> (i32, u32) {
    let (mut hi, mut lo) = ((p >> 32) as i32, p as u32);
    let k = s.wrapping_sub(1) & 63;
    if k < 32 {
        let (l, carry) = lo.overflowing_add(1 << k);
        lo = l;
        hi = hi.wrapping_add(i32::from(carry));
    } else {
        hi = hi.wrapping_add(1 << (k & 31));
    }
    let s = s & 63;
    if s < 32 {
        let up = ((hi as u32) << 1) << (31 - (s & 31));
        (hi >> (s & 31), (lo >> (s & 31)) | up)
    } else {
        (hi >> 31, (hi >> ((s - 32) & 31)) as u32)
    }
}

/// The plain 64-bit [`shr_round_clamp`] it replaces (the reference of its
/// test).
#[cfg(test)]
#[allow(clippy::cast_possible_truncation)]
fn shr_round_clamp_wide(p: i64, s: u32, lim: i32) -> i32 {
    let r = ((p >> (s - 1)) + 1) >> 1;
    r.max(-i64::from(lim)).min(i64::from(lim)) as i32
}

impl Proj16 {
    /// The projection of scale `k` (pixels per unit at distance 1), near
    /// plane `near` and screen centre `(cx, cy)` (pixels) for `sub`
    /// subpixel bits (at most [`SubpixelBits::MAX`](crate::num::SubpixelBits::MAX)),
    /// of a `Q16` scalar (its raw bits read by `q`).
    pub(crate) fn new<R: Real>(q: Raw16<R>, k: R, near: R, [cx, cy]: [R; 2], sub: u32) -> Self {
        Self {
            k: q.raw(k),
            near: q.raw(near),
            cx: cx.to_fixed_i32(sub),
            cy: cy.to_fixed_i32(sub),
            lim: COORD_LIMIT_PX << sub,
        }
    }

    /// Screen position in subpixels (`sub <= 15` fraction bits) and the weight `q = near/w` in raw Q16 of the
    /// eye-space point `p` (raw Q16) with `w = -z > 0`.
    ///
    /// `1/w` comes from [`recip_mant`] (within 2^-17 relative) and one
    /// Newton step (within 2^-28 relative); `k/w` is kept to at least 23
    /// significant bits for `k >= 1`, so the screen position is within
    /// 2^-22 relative plus 1/2 subpixel (rounding) of the exact
    /// projection of the given point. Positions are clamped to `±lim` subpixels; `q` to `[0, 1]`.
    #[inline]
    pub(crate) fn project(&self, p: [i32; 3], sub: u32) -> ([i32; 2], i32) {
        let w = p[2].saturating_neg().max(1).unsigned_abs();
        // `clz32`: a table lookup on the M0 rather than a `__clzsi2` call.
        let lz = clz32(w); // 1..=31
        let m = w << lz; // f 2^31, f in [1, 2), w = f 2^(31 - lz)
        #[allow(clippy::cast_possible_wrap)]
        let y0 = recip_mant(m) as i32; // 2^30 / f within 2^-17
                                       // One Newton step y (2 - f y): the error squares (2^-34) plus
                                       // truncations (2^-29); y <= 2^30 / f, so y <= 2^30.
        let fy = wmul((m >> 1) as i32, y0) >> 30; // ~2^30
        #[allow(clippy::cast_possible_truncation)]
        let e = ((1i64 << 31) - fy) as i32; // ~2^30
        #[allow(clippy::cast_possible_truncation)]
        let y = (wmul(y0, e) >> 30) as i32;
        // 1/w = y 2^(lz - 61). k y < 2^60; g = k y / 2^30 < 2^30.
        #[allow(clippy::cast_possible_truncation)]
        let g = (wmul(self.k, y) >> 30) as i32;
        // x k / w in subpixels = x k 2^(sub - 16) / w = x g 2^(lz + sub - 47).
        let s = 47 - lz - sub;
        let dx = shr_round_clamp(wmul(p[0], g), s, self.lim);
        // y is down on the screen: round -y k / w, so that ties round up
        // on the screen as for x (`round(cy - y k / w)`, as the generic
        // path does).
        let dy = shr_round_clamp(-wmul(p[1], g), s, self.lim);
        let sx = self.cx.saturating_add(dx).max(-self.lim).min(self.lim);
        let sy = self.cy.saturating_add(dy).max(-self.lim).min(self.lim);
        // q = near / w in Q16 = near y 2^(lz - 61 + 16).
        let q = shr_round_clamp(wmul(self.near, y), 45 - lz, 1 << 16).max(0);
        ([sx, sy], q)
    }
}

impl Proj16 {
    /// [`Proj16::project`] of a point known to lie inside the near plane
    /// and the guard band (an object whose bounding sphere is inside every
    /// plane): the same result, bit for bit (tested), without the clamps
    /// that cannot act there (`|x k / w| <= GUARD_PX` pixels `< lim`, `q
    /// <= 1`).
    #[inline]
    pub(crate) fn project_inside(&self, p: [i32; 3], sub: u32) -> ([i32; 2], i32) {
        let w = p[2].saturating_neg().max(1).unsigned_abs();
        let lz = clz32(w);
        let m = w << lz;
        #[allow(clippy::cast_possible_wrap)]
        let y0 = recip_mant(m) as i32;
        let fy = wmul((m >> 1) as i32, y0) >> 30;
        #[allow(clippy::cast_possible_truncation)]
        let e = ((1i64 << 31) - fy) as i32;
        #[allow(clippy::cast_possible_truncation)]
        let y = (wmul(y0, e) >> 30) as i32;
        #[allow(clippy::cast_possible_truncation)]
        let g = (wmul(self.k, y) >> 30) as i32;
        let s = 47 - lz - sub;
        let dx = shr_round(wmul(p[0], g), s);
        let dy = shr_round(-wmul(p[1], g), s);
        let q = shr_round(wmul(self.near, y), 45 - lz).max(0);
        ([self.cx + dx, self.cy + dy], q)
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{
        face_cross, face_normal_q14, row_split, row_wide, shr_round, shr_round_clamp,
        shr_round_clamp_wide, Proj16,
    };

    #[test]
    fn face_normal_q14_is_exact() {
        use crate::geom::exact::face_normal;
        let mut next = crate::geom::testkit::xorshift(0x2545_f491_4f6c_dd1d);
        for i in 0..400_000u32 {
            // Edges of every length class: tiny (degenerate-ish), mesh
            // sized, up to the full i16 range (the fallback).
            let span: u64 = match i % 5 {
                0 => 4,
                1 => 64,
                2 => 2048,
                3 => 16384,
                _ => 65536,
            };
            let base = [0; 3].map(|_| (next() % 65536) as i64 - 32768);
            let p = [0; 3].map(|_| {
                [0, 1, 2].map(|k| {
                    (base[k] + (next() % span) as i64 - (span / 2) as i64).clamp(-32768, 32767)
                        as i16
                })
            });
            assert_eq!(
                face_normal_q14(p[0], p[1], p[2]),
                face_normal(p[0], p[1], p[2]),
                "{p:?}"
            );
        }
        let ext = [i16::MIN, -16384, -1, 0, 1, 16383, 16384, i16::MAX];
        for &a in &ext {
            for &b in &ext {
                for &c in &ext {
                    let p = [[a, b, c], [b, c, a], [c, a, b]];
                    let q = [[0, 0, 0], [a, 0, b], [0, c, a]];
                    for t in [p, q] {
                        assert_eq!(
                            face_normal_q14(t[0], t[1], t[2]),
                            face_normal(t[0], t[1], t[2]),
                            "{t:?}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn split_row_matches_wide() {
        let mut next = crate::geom::testkit::xorshift(0x1234_5678_9abc_def0);
        for i in 0..300_000 {
            let lim: i64 = if i % 2 == 0 { 1 << 24 } else { 1 << 17 };
            let m = [0; 3].map(|_| ((next() % (2 * lim as u64 - 1)) as i64 - (lim - 1)) as i32);
            let c = [0; 3].map(|_| next() as u16 as i16);
            assert_eq!(row_split(&m, c), row_wide(&m, c), "{m:?} {c:?}");
        }
        let ext = [[(1 << 24) - 1; 3], [-(1 << 24) + 1; 3]];
        for m in ext {
            for c in [[i16::MIN; 3], [i16::MAX; 3]] {
                assert_eq!(row_split(&m, c), row_wide(&m, c));
            }
        }
    }

    #[test]
    fn face_cross_direction() {
        let n = face_cross([0, 0, 0], [16384, 0, 0], [0, 16384, 0]);
        assert_eq!(n, [0, 0, 16384]);
        let n = face_cross([-32768, 0, 0], [32767, 0, 0], [0, 32767, 0]);
        assert!(n[0] == 0 && n[1] == 0 && n[2] > 16384);
        assert_eq!(face_cross([1, 2, 3], [1, 2, 3], [4, 5, 6]), [0, 0, 0]);
    }

    #[test]
    fn shr_round_clamp_matches_wide() {
        let mut next = crate::geom::testkit::xorshift(0x0bad_cafe_1234_5678);
        let lims = [0, 1, 1 << 16, 8192 << 4, 8192 << 8, i32::MAX];
        for i in 0..2_000_000u32 {
            let s = 1 + (next() % 62) as u32;
            // Every magnitude class below 2^62.
            let bits = next() % 63;
            let mag = (next() >> 1) >> (63 - bits);
            let p = if next() & 1 == 0 {
                mag as i64
            } else {
                -(mag as i64)
            };
            let lim = lims[(i % 6) as usize];
            assert_eq!(
                shr_round_clamp(p, s, lim),
                shr_round_clamp_wide(p, s, lim),
                "{p} {s} {lim}"
            );
        }
        let edge = (1i64 << 62) - 1;
        for s in 1..=62u32 {
            for base in [0, 1i64 << (s - 1), 1i64 << s, 1i64 << 31, 1i64 << 32, edge] {
                for d in -3i64..=3 {
                    for p in [base + d, -base + d] {
                        if p.unsigned_abs() >= 1 << 62 {
                            continue;
                        }
                        for lim in lims {
                            assert_eq!(
                                shr_round_clamp(p, s, lim),
                                shr_round_clamp_wide(p, s, lim),
                                "{p} {s} {lim}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// `project_inside` equals `project` for points inside the near
    /// plane and the guard band, and `shr_round` equals
    /// `shr_round_clamp` where no clamp acts.
    #[test]
    fn project_inside_matches_project() {
        let mut next = crate::geom::testkit::xorshift(0x5eed_0bad_f00d_0001);
        for (k, near, sub) in [
            (290.0f64, 1.0f64, 4u32),
            (41.6, 0.5, 4),
            (2048.0, 0.1, 4),
            (20.0, 0.01, 8),
        ] {
            let p = crate::geom::testkit::proj(k, near, sub, 120);
            let guard = 4096.0 / k;
            for _ in 0..200_000 {
                let u = |r: u64| (r >> 11) as f64 / (1u64 << 53) as f64;
                // w from near to 16000 units, log-uniform; x, y within
                // the guard band.
                let w = near * (16000.0 / near).powf(u(next()));
                let x = (u(next()) * 2.0 - 1.0) * guard * w * 0.999;
                let y = (u(next()) * 2.0 - 1.0) * guard * w * 0.999;
                let raw = |v: f64| (v * 65536.0).round().clamp(-2e9, 2e9) as i32;
                let q = [raw(x), raw(y), raw(-w).min(-p.near)];
                assert_eq!(p.project_inside(q, sub), p.project(q, sub), "{q:?} {k}");
            }
        }
        for _ in 0..1_000_000 {
            let s = 1 + (next() % 62) as u32;
            let v = (next() as i64) >> (next() % 64);
            let lim = 1 << 30;
            let c = shr_round_clamp(v, s, lim);
            if c.unsigned_abs() < lim as u32 {
                assert_eq!(shr_round(v, s), c, "{v} {s}");
            }
        }
    }

    #[test]
    fn projection_matches_f64() {
        let p = Proj16 {
            k: 290 << 16,
            near: 1 << 16,
            cx: 120 << 4,
            cy: 120 << 4,
            lim: 8192 << 4,
        };
        let mut worst = 0f64;
        let mut s = 77u64;
        for _ in 0..200_000 {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            let w = 1.0 + (s % 1_000_000) as f64 * 1e-4; // 1..101
            let x = ((s >> 20) % 20_000) as f64 / 10_000.0 - 1.0;
            let y = ((s >> 40) % 20_000) as f64 / 10_000.0 - 1.0;
            let raw = |v: f64| (v * 65536.0).round() as i32;
            let pr = [raw(x * w), raw(y * w), raw(-w)];
            let ([sx, sy], q) = p.project(pr, 4);
            let (xe, ye, we) = (
                f64::from(pr[0]) / 65536.0,
                f64::from(pr[1]) / 65536.0,
                -f64::from(pr[2]) / 65536.0,
            );
            let ex = 120.0 + xe / we * 290.0;
            let ey = 120.0 - ye / we * 290.0;
            worst = worst
                .max((f64::from(sx) / 16.0 - ex).abs())
                .max((f64::from(sy) / 16.0 - ey).abs());
            assert!((f64::from(q) / 65536.0 - 1.0 / we).abs() <= 1.0 / 65536.0);
        }
        std::println!("projection: worst {worst} px");
        // 1/2 subpixel of rounding plus 2^-22 of at most 290 px.
        assert!(worst <= 1.0 / 32.0 + 290.0 / 4_194_304.0);
    }
}
