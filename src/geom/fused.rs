//! The `fast` profiles' vertex kernel for objects wholly inside the
//! clipping planes: model-view transform, projection scale and subpixel
//! scale fused into three integer rows, the perspective divide as one
//! table reciprocal, every product 32-bit.
//!
//! Per vertex (Q1.14 mesh coordinates `c`): `X = ⌊Σ ax_j c_j / 2^14⌋ +
//! bx`, the same for `Y` and `W` (coefficients with 14 extra fraction
//! bits: 64-bit products on the Cortex-M4, halves `a >> 14`, `a & 0x3FFF`
//! and 32-bit products on the Cortex-M0, the same bits; see
//! [`Fused::new`] for the ranges), then `1/W` from
//! [`recip_mant_top`](crate::num::approx16::recip_mant_top) rounded to 17
//! bits, and `X/W`, `Y/W`, `near/W` each as one product (split in 16-bit
//! halves on the Cortex-M0) and one shift.
//!
//! Measured (`examples/firmware/profile.sh`, bunny Gouraud, 1 839
//! vertices, exact QEMU counts): the vertex loops with lighting cost 127
//! instructions per vertex on the Cortex-M4 and 234 on the Cortex-M0,
//! where the exact-rounding kernel of [`super::q16`] (64-bit transform,
//! Newton-refined reciprocal, variable 64-bit shifts) cost 237 and 515.
//!
//! Error (subpixels) against the exact projection of the point the `Q16`
//! matrix gives: the final rounding (1/2) plus at most 1/4, which
//! [`Fused::new`] proves per object from the bounding sphere before the
//! kernel is used (objects it cannot bound use the exact-rounding kernels
//! of [`super::q16`]). Tested against `f64` in `fused_within_bound`.

use super::bound::Bound;
use super::q16::Proj16;
use crate::num::approx16::recip_mant_top;
use crate::num::wide::clz32;

/// Row magnitude `Σ |a_j| cmax + |b|` of the integer rows: each of the
/// four terms below `2^28`; [`Fused::new`] then checks that every row
/// value over the bounding sphere is below `2^30`, so that the products
/// and the rounding in [`Fused::project`] stay within `i32`.
const ROW_BITS: u32 = 30;

/// The fused transform and projection of one object (see the module docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fused {
    /// Rows X, Y (projection and subpixel scale folded in, `Y` negated:
    /// screen y grows downwards) and W (`= -z`).
    /// The coefficients (14 more fraction bits than the rows, below
    /// `2^31`; read on every target but ARMv6-M) and their halves
    /// `a >> 14`, `a & 0x3FFF` (read on ARMv6-M).
    #[cfg_attr(armv6m, allow(dead_code))]
    a: [[i32; 3]; 3],
    #[cfg_attr(not(armv6m), allow(dead_code))]
    hi: [[i32; 3]; 3],
    #[cfg_attr(not(armv6m), allow(dead_code))]
    lo: [[i32; 3]; 3],
    b: [i32; 3],
    /// Screen centre, subpixels.
    cx: i32,
    cy: i32,
    /// The screen offset is `T >> (sh0 - lz)`, rounded (`lz`: the leading
    /// zeros of `W`).
    sh0: u32,
    /// Depth: `S30 - (G · y / 2^16) >> (gsh - lz)`, clamped to `[0, 2^30]`.
    g: u32,
    gsh: u32,
    s30: u32,
    /// `S30 - (G · y / 2^16) >> (gsh - lz)` lies within `[0, 2^30]` at
    /// every point of the bounding sphere (proved by [`Fused::new`]): the
    /// depth needs no clamp ([`Fused::project`] with `CLAMP = false`).
    pub(crate) depth_in_range: bool,
    /// The proven bound (units of `2^-16` subpixel, at most `2^14`) of
    /// the screen position's error before the final rounding: each
    /// coordinate is within `1/2 + err16 / 2^16` subpixels of the exact
    /// projection.
    pub(crate) err16: u32,
}

/// `round(v · 2^-s)` (ties up) of `v` for a shift of either sign; `None`
/// when a left shift would leave `i64`.
fn shift_round(v: i64, s: i32) -> Option<i64> {
    if s <= 0 {
        let l = s.unsigned_abs();
        if l >= 62 || v.unsigned_abs() >= 1u64 << (62 - l) {
            return None;
        }
        Some(v << l)
    } else if s >= 63 {
        Some(0)
    } else {
        // |v| < 2^63: v >> (s - 1) then one more halving, rounded up.
        Some(((v >> (s - 1)) + 1) >> 1)
    }
}

/// Bit length of `v` (0 for 0).
fn bits(v: u64) -> i32 {
    (64 - v.leading_zeros()) as i32
}

/// One integer row `Σ n_j 2^-ea c_j + nb 2^-eb`, scaled by `2^e` so that
/// each of its four terms over `|c_j| <= cmax` stays below `2^(ROW_BITS -
/// 2)`; returns the coefficients `a_j ≈ n_j 2^(e + 14 - ea)` (14 more
/// fraction bits, kept as `a >> 14` and `a & 0x3FFF`), `b` and `e`.
#[allow(clippy::type_complexity)]
fn row(n: [i64; 3], ea: i32, nb: i64, eb: i32, cmax: u64) -> Option<(Split, i32, i32)> {
    let cb = bits(cmax);
    let top = n
        .iter()
        .map(|v| bits(v.unsigned_abs()) + cb - ea)
        .chain(core::iter::once(bits(nb.unsigned_abs()) - eb))
        .max()
        .unwrap_or(0);
    let e = (ROW_BITS as i32 - 2 - top).clamp(-100, 100);
    row_at(n, ea, nb, eb, e).map(|(a, b)| (a, b, e))
}

/// [`row`] at a given exponent `e`.
fn row_at(n: [i64; 3], ea: i32, nb: i64, eb: i32, e: i32) -> Option<(Split, i32)> {
    let c = |v: i64| i32::try_from(v).ok();
    let a = [
        shift_round(n[0], ea - e - 14)?,
        shift_round(n[1], ea - e - 14)?,
        shift_round(n[2], ea - e - 14)?,
    ];
    let split = Split {
        a,
        a32: [c(a[0])?, c(a[1])?, c(a[2])?],
        hi: [c(a[0] >> 14)?, c(a[1] >> 14)?, c(a[2] >> 14)?],
        lo: [c(a[0] & 0x3FFF)?, c(a[1] & 0x3FFF)?, c(a[2] & 0x3FFF)?],
    };
    Some((split, c(shift_round(nb, eb - e)?)?))
}

/// Row coefficients with 14 extra fraction bits, and their halves.
#[derive(Clone, Copy, Debug)]
struct Split {
    a: [i64; 3],
    a32: [i32; 3],
    hi: [i32; 3],
    lo: [i32; 3],
}

impl Fused {
    /// The fused kernel of an object with model-view `m` (linear part,
    /// raw `Q16`, entries below 2^24) and `t` (raw `Q16`), projected by
    /// `pj` with `sub` subpixel bits and depth scale `scale` (raw `Q16`,
    /// `far / (far - near)`, or none), whose mesh lies in `bound`.
    ///
    /// `None` (the caller uses the exact-rounding kernel) unless every
    /// intermediate of every vertex within the bounding sphere provably
    /// fits its integer and the screen position is provably within
    /// 1/4 subpixel (before the final rounding to the subpixel grid) of
    /// the exact projection of the point: with `Vmax` the largest screen
    /// offset of the sphere (subpixels), `Wmin` the smallest `W`, `εx,
    /// εw = (Σ_j cmax_j + 1)/2` the coefficient roundings of the rows,
    /// `ρ = 3·2^-17` the reciprocal's relative error (table `2^-17`,
    /// rounding to 17 bits `2^-16`) and `sh` the final shift,
    /// `Vmax·ρ + (Vmax·εw + εx·2^(31 - sh0))/Wmin + 2^-sh <= 1/4`.
    /// Depth is within `2^-13` of `S·(1 - near/w)` before clamping (the
    /// reciprocal's `ρ` times `S < 4`, and the rounding of `G`).
    pub(crate) fn new(
        m: &[[i32; 3]; 3],
        t: &[i32; 3],
        pj: &Proj16,
        sub: u32,
        scale: Option<i32>,
        bound: &Bound,
    ) -> Option<Self> {
        if sub > 15 || pj.k <= 0 || pj.near <= 0 {
            return None;
        }
        let r = u64::from(bound.radius.min(1 << 17));
        let cm = bound
            .center
            .map(|c| (u64::from(c.unsigned_abs()) + r).min(1 << 15));
        let cmax = cm[0].max(cm[1]).max(cm[2]);
        let csum = cm[0] + cm[1] + cm[2];
        let kr = i64::from(pj.k);
        let sub_i = sub as i32;
        // X, Y in subpixels·units: k m c 2^sub / 2^(16 + 16 + 14), the
        // translation k t 2^sub / 2^32; W = -(m₂ c / 2^30 + t₂ / 2^16).
        let rx = |k: usize, sign: i64| {
            let n = m[k].map(|v| sign * kr * i64::from(v));
            row(n, 46 - sub_i, sign * kr * i64::from(t[k]), 32 - sub_i, cmax)
        };
        let (_, _, ex) = rx(0, 1)?;
        let (_, _, ey) = rx(1, -1)?;
        // X and Y share one exponent (the smaller).
        let e = ex.min(ey);
        let rx_e = |k: usize, sign: i64| {
            let n = m[k].map(|v| sign * kr * i64::from(v));
            row_at(n, 46 - sub_i, sign * kr * i64::from(t[k]), 32 - sub_i, e)
        };
        let (ax, bx) = rx_e(0, 1)?;
        let (ay, by) = rx_e(1, -1)?;
        let (aw, bw, ew) = row(m[2].map(|v| -i64::from(v)), 30, -i64::from(t[2]), 16, cmax)?;
        // The rows over the sphere: value at the centre ± Σ|a_j| r, ± 1
        // for the floor of the low halves.
        let at = |a: &Split, b: i32| {
            let c: i64 = (0..3)
                .map(|j| a.a[j] * i64::from(bound.center[j]))
                .sum::<i64>();
            let d: i64 = a.a.iter().map(|v| v.abs()).sum::<i64>() * r as i64;
            let c = (c >> 14) + i64::from(b);
            (c - (d >> 14) - 2, c + (d >> 14) + 2)
        };
        let (w_lo, w_hi) = at(&aw, bw);
        let (x_lo, x_hi) = at(&ax, bx);
        let (y_lo, y_hi) = at(&ay, by);
        if w_lo < 1 || w_hi >= 1 << 30 {
            return None;
        }
        let xy_abs = [x_lo, x_hi, y_lo, y_hi]
            .iter()
            .map(|v| v.unsigned_abs())
            .max()
            .unwrap_or(0);
        if xy_abs >= 1 << 30 {
            return None;
        }
        let (w_lo, w_hi) = (w_lo as u64, w_hi as u64);
        let lz_max = (w_lo as u32).leading_zeros();
        let lz_min = (w_hi as u32).leading_zeros();
        // 1/W = y 2^(lz - 47) (y: 17 bits); X/W 2^(ew - e) = T 2^(lz - 31 + ew - e).
        let sh0 = 31 + e - ew;
        if sh0 < 0 {
            return None;
        }
        let sh0 = sh0 as u32;
        if sh0 < lz_max + 1 || sh0 > lz_min + 31 {
            return None;
        }
        let sh_min = sh0 - lz_max;
        // The error bound, in 2^-16 subpixels.
        // Vmax = ceil(xy_abs 2^(31 - sh0) / w_lo).
        let q = (xy_abs << 31) / w_lo;
        if sh0 >= 63 {
            return None;
        }
        let vmax = (q + (1u64 << sh0) - 1) >> sh0;
        if vmax >= 1 << 17 {
            return None;
        }
        // Coefficient roundings (1/2 of 2^-14 per unit of c), the floor of
        // the low halves (1) and the rounding of b (1/2).
        let eps = (csum >> 15) + 2;
        if 47 - (sh0 as i32) > 40 {
            return None;
        }
        let ex_term = if sh0 <= 47 {
            eps << (47 - sh0)
        } else {
            (eps >> (sh0 - 47)) + 1
        };
        let e1 = (3 * vmax).div_ceil(2);
        let e23 = ((vmax * eps) << 16).saturating_add(ex_term).div_ceil(w_lo);
        let e4 = 1u64 << (16u32.saturating_sub(sh_min));
        let err16 = e1 + e23 + e4;
        if err16 > 1 << 14 {
            return None;
        }
        // Depth: S (1 - near/w) = S - S near 2^ew y 2^(lz - 47), as
        // S30 - (G y >> 16) >> (gsh - lz), G = S near 2^(ew - 1 + gsh).
        let sr = i64::from(scale.unwrap_or(1 << 16));
        if !(1 << 16..1 << 18).contains(&sr) {
            return None;
        }
        let gsh = lz_max;
        let g = shift_round(sr * i64::from(pj.near), 33 - ew - gsh as i32)?;
        if !(0..1 << 31).contains(&g) || gsh - lz_min > 31 {
            return None;
        }
        // The unclamped depth term `p = ((G y16) >> 16) >> (gsh - lz)`:
        // with `y16 = 2^47 (1 ± ρ) / (W 2^lz)`, `ρ = 3·2^-17`, it is
        // `G 2^(31 - gsh) (1 ± ρ) / W` (the `lz` cancel) less at most 2 for
        // the two floors. Over `W` in `[w_lo, w_hi]`: `p <= ⌈G 2^31 /
        // (w_lo 2^gsh)⌉ (1 + ρ)` and `p >= ⌊G 2^31 / (w_hi 2^gsh)⌋ (1 - ρ)
        // - 2`; the clamp is idle when `p_max <= S30` and `S30 - p_min <=
        // 2^30` (ρ rounded up to 2^-15 below).
        let depth_in_range = {
            let gn = (g as u64) << 31;
            // (Both divisors are at least `w_lo >= 1`: `checked_div` only
            // keeps the panic-free build free of a division-by-zero branch.)
            match (gn.checked_div(w_lo << gsh), gn.checked_div(w_hi << gsh)) {
                (Some(q), Some(q_lo)) => {
                    let q_hi = q + 1;
                    let p_max = q_hi + q_hi.div_ceil(1 << 15);
                    let p_min = (q_lo - q_lo.div_ceil(1 << 15)).saturating_sub(2);
                    let s30 = (sr as u64) << 14;
                    p_max <= s30 && s30 - p_min <= 1 << 30
                }
                _ => false,
            }
        };
        Some(Self {
            a: [ax.a32, ay.a32, aw.a32],
            hi: [ax.hi, ay.hi, aw.hi],
            lo: [ax.lo, ay.lo, aw.lo],
            b: [bx, by, bw],
            cx: pj.cx,
            cy: pj.cy,
            sh0,
            g: g as u32,
            gsh,
            s30: (sr as u32) << 14,
            depth_in_range,
            // At most 2^14 (checked above).
            err16: err16 as u32,
        })
    }

    /// Row `k` at `c`: `floor(Σ a_j c_j / 2^14) + b`.
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    fn row(&self, k: usize, c: [i32; 3]) -> i32 {
        #[cfg(armv6m)]
        {
            // Σ (2^14 h + l) c / 2^14, floored: Σ h c + (Σ l c) >> 14 (each
            // sum below 2^31, see `new`): 32-bit products only.
            let (h, l) = (&self.hi[k], &self.lo[k]);
            h[0] * c[0]
                + h[1] * c[1]
                + h[2] * c[2]
                + ((l[0] * c[0] + l[1] * c[1] + l[2] * c[2]) >> 14)
                + self.b[k]
        }
        #[cfg(not(armv6m))]
        {
            // The same value with 64-bit products of the whole
            // coefficients (below 2^31).
            let a = &self.a[k];
            let s = i64::from(a[0]) * i64::from(c[0])
                + i64::from(a[1]) * i64::from(c[1])
                + i64::from(a[2]) * i64::from(c[2]);
            (s >> 14) as i32 + self.b[k]
        }
    }

    /// Screen position (subpixels) and depth (Q2.30, clamped to `[0, 1]`)
    /// of Q1.14 mesh point `c` within the object's bounding sphere (see
    /// [`Fused::new`] for the error bounds). `CLAMP = false` only when
    /// [`Fused::depth_in_range`]: the same values without the clamp.
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)]
    pub(crate) fn project<const CLAMP: bool>(&self, c: [i16; 3]) -> ([i32; 2], i32) {
        let c = c.map(i32::from);
        let r = |k: usize| self.row(k, c);
        let (x, y, w) = (r(0), r(1), r(2));
        // w >= 1 at every point of the sphere (checked by `new`).
        let w = w as u32;
        let lz = clz32(w);
        // 2^16 / f within 3·2^-17 (f = w 2^lz / 2^31 in [1, 2)).
        let y16 = (recip_mant_top(w << lz) + (1 << 13)) >> 14;
        // Rounded (ties up) right shifts by `sh = sh0 - lz >= 1` (`new`):
        // `(v + 2^(sh-1)) >> sh` is `((v >> (sh - 1)) + 1) >> 1` (with
        // `v = q 2^(sh-1) + r`, `0 <= r < 2^(sh-1)`, both are `(q + 1) >> 1`),
        // one shift amount and no rounding constant live.
        let sh1 = self.sh0 - 1 - lz;
        let dx = ((mul_hi16(x, y16) >> sh1) + 1) >> 1;
        let dy = ((mul_hi16(y, y16) >> sh1) + 1) >> 1;
        let p = mul_hi16_u(self.g, y16) >> (self.gsh - lz);
        let d = if CLAMP {
            self.s30.saturating_sub(p).min(1 << 30) as i32
        } else {
            // Within [0, 2^30] (`depth_in_range`).
            self.s30.wrapping_sub(p) as i32
        };
        ([self.cx + dx, self.cy + dy], d)
    }
}

/// `floor(v · y / 2^16)` for `|v| < 2^30`, `y <= 2^16`: exact, in 32-bit
/// products (16-bit halves) on the Cortex-M0, one 64-bit product elsewhere.
#[inline(always)]
#[allow(
    clippy::cast_possible_wrap,
    clippy::cast_sign_loss,
    clippy::cast_possible_truncation
)]
fn mul_hi16(v: i32, y: u32) -> i32 {
    #[cfg(armv6m)]
    {
        // v = 2^16 h + l: v y / 2^16 = h y + l y / 2^16, h y a multiple
        // of nothing to floor; |h y| < 2^30, l y < 2^32.
        let h = v >> 16;
        let l = (v as u32) & 0xFFFF;
        h * y as i32 + ((l * y) >> 16) as i32
    }
    #[cfg(not(armv6m))]
    {
        ((i64::from(v) * i64::from(y)) >> 16) as i32
    }
}

/// [`mul_hi16`] for `v < 2^31` unsigned.
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn mul_hi16_u(v: u32, y: u32) -> u32 {
    #[cfg(armv6m)]
    {
        (v >> 16) * y + (((v & 0xFFFF) * y) >> 16)
    }
    #[cfg(not(armv6m))]
    {
        ((u64::from(v) * u64::from(y)) >> 16) as u32
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::geom::testkit::{proj, rotation, uniform};

    /// The screen position within 1/2 + 1/4 subpixel and the depth within
    /// `2^-13` of the exact projection of the `Q16` matrix's point, on
    /// random objects (rotation, uniform scale, translation) and random
    /// points of their bounding spheres, whenever [`Fused::new`] accepts
    /// the object (and it accepts most on-screen objects).
    #[test]
    fn fused_within_bound() {
        let mut u = uniform(0x0dd_ba11_cafe_f00d);
        let (mut accepted, mut worst, mut worst_d) = (0, 0f64, 0f64);
        let mut in_range = 0;
        for i in 0..3000 {
            let sub = [4u32, 4, 2, 6, 8][i % 5];
            let k = 50.0 + 600.0 * u();
            let near = [1.0, 0.5, 0.1, 2.0][i % 4];
            let pj = proj(k, near, sub, 100);
            let (cx, cy) = (pj.cx, pj.cy);
            let far = if i % 3 == 0 {
                None
            } else {
                Some(near * (2.0 + 50.0 * u()))
            };
            let scale = far.map(|f| (f / (f - near) * 65536.0).round() as i32);
            let sc = 0.2 + 3.0 * u();
            let (a, b, c) = (6.3 * u(), 6.3 * u(), 6.3 * u());
            // Rz Ry Rx, times the scale.
            let r = rotation(a, b, c);
            let m = r.map(|row| row.map(|v| (v * sc * 65536.0).round() as i32));
            let dist = near + sc * 2.0 + 20.0 * u();
            let t = [(u() - 0.5) * dist * 0.6, (u() - 0.5) * dist * 0.6, -dist]
                .map(|v| (v * 65536.0).round() as i32);
            let center = [0; 3].map(|_| ((u() - 0.5) * 8000.0) as i16);
            let radius = 2000 + (u() * 18000.0) as u32;
            let bound = Bound {
                center,
                radius,
                half: [0; 3],
            };
            let Some(f) = Fused::new(&m, &t, &pj, sub, scale, &bound) else {
                continue;
            };
            accepted += 1;
            in_range += usize::from(f.depth_in_range);
            for _ in 0..200 {
                // A point of the sphere.
                let d = [u() - 0.5, u() - 0.5, u() - 0.5];
                let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-9);
                let rr = f64::from(radius) * u().cbrt() * 0.999 / l;
                let p = [0, 1, 2].map(|j| {
                    (f64::from(center[j]) + d[j] * rr)
                        .round()
                        .clamp(-32768.0, 32767.0) as i16
                });
                let e = [0, 1, 2].map(|k| {
                    (0..3)
                        .map(|j| f64::from(m[k][j]) * f64::from(p[j]))
                        .sum::<f64>()
                        / 2f64.powi(30)
                        + f64::from(t[k]) / 65536.0
                });
                let w = -e[2];
                let kk = f64::from(pj.k) / 65536.0;
                let ss = f64::from(1u32 << sub);
                let ex = f64::from(cx) + kk * e[0] / w * ss;
                let ey = f64::from(cy) - kk * e[1] / w * ss;
                let ([gx, gy], gd) = f.project::<true>(p);
                if f.depth_in_range {
                    // The clamp idle, as `new` proved (a wrapped or
                    // out-of-range depth would differ from the clamped one).
                    assert_eq!(f.project::<false>(p), ([gx, gy], gd));
                }
                worst = worst
                    .max((f64::from(gx) - ex).abs())
                    .max((f64::from(gy) - ey).abs());
                let sf = scale.map_or(1.0, |v| f64::from(v) / 65536.0);
                let nr = f64::from(pj.near) / 65536.0;
                let de = (sf * (1.0 - nr / w)).clamp(0.0, 1.0);
                worst_d = worst_d.max((f64::from(gd) / 2f64.powi(30) - de).abs());
            }
        }
        std::println!(
            "fused: {accepted} objects accepted, worst {worst} subpixels, depth {worst_d}"
        );
        std::println!("fused: depth clamp idle for {in_range}");
        assert!(accepted > 1000, "{accepted}");
        assert!(in_range > accepted / 2, "{in_range} of {accepted}");
        assert!(worst <= 0.75, "{worst}");
        assert!(worst_d <= 1.0 / 8192.0, "{worst_d}");
    }

    /// `recip_mant_top` equals `recip_mant` for every mantissa with its
    /// top bit set (each 18-bit position, with low bits), and the 17-bit
    /// reciprocal of [`Fused::project`] is within `3·2^-17` of `2^16 / f`.
    #[test]
    fn reciprocal_within_bound() {
        use crate::num::approx16::{recip_mant, recip_mant_top};
        let mut worst = 0f64;
        for k in 0..1u32 << 18 {
            for low in [0, 0x1FFF, 0x0AAA] {
                let m = (1u32 << 31) | (k << 13) | low;
                let r = recip_mant_top(m);
                assert_eq!(r, recip_mant(m), "{m:#x}");
                let y16 = (r + (1 << 13)) >> 14;
                let exact = 65536.0 * 2f64.powi(31) / f64::from(m);
                worst = worst.max((f64::from(y16) / exact - 1.0).abs());
            }
        }
        std::println!("17-bit reciprocal: worst {worst:e} = 2^{:.2}", worst.log2());
        assert!(worst <= 3.0 / 131_072.0, "{worst}");
    }

    /// The split products equal the wide ones (the Cortex-M0 form).
    #[test]
    fn split_products_are_exact() {
        let mut next = crate::geom::testkit::xorshift(0x9e37_79b9_7f4a_7c15);
        for _ in 0..1_000_000 {
            let v = (next() as i32) >> 2; // |v| <= 2^29... and beyond below
            let y = (next() % ((1 << 16) + 1)) as u32;
            let h = v >> 16;
            let l = (v as u32) & 0xFFFF;
            let split = h * y as i32 + ((l * y) >> 16) as i32;
            assert_eq!(split, ((i64::from(v) * i64::from(y)) >> 16) as i32);
            let u = (next() as u32) >> 1;
            let split = (u >> 16) * y + (((u & 0xFFFF) * y) >> 16);
            assert_eq!(split, ((u64::from(u) * u64::from(y)) >> 16) as u32);
        }
    }
}
