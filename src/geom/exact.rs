//! Exact integer normalisation, face normals, face planes and normal cones
//! of Q1.14 positions (what the mesh tables bake and the geometry stage
//! tests against).
//!
//! Each function states its bound; the tables built from them carry the
//! error analysis of the geometry stage that reads them.

use crate::num::isqrt_u64;

/// `round(v · 2^frac / |v|)` per component, half away from zero, for
/// `frac <= 30`; `None` for the zero vector. Each magnitude is at most
/// `2^frac`.
pub(crate) const fn unit(v: [i64; 3], frac: u32) -> Option<[i64; 3]> {
    let mag = [
        v[0].unsigned_abs(),
        v[1].unsigned_abs(),
        v[2].unsigned_abs(),
    ];
    let mut max = mag[0];
    if mag[1] > max {
        max = mag[1];
    }
    if mag[2] > max {
        max = mag[2];
    }
    if max == 0 {
        return None;
    }
    // Bring the largest magnitude into [2^30, 2^31).
    let bits = u64::BITS - max.leading_zeros();
    let mut scaled = mag;
    let mut i = 0;
    while i < 3 {
        scaled[i] = if bits > 31 {
            mag[i] >> (bits - 31)
        } else {
            mag[i] << (31 - bits)
        };
        i += 1;
    }
    // Each square < 2^62, so the sum < 3 · 2^62 fits.
    let sum = scaled[0] * scaled[0] + scaled[1] * scaled[1] + scaled[2] * scaled[2];
    let len = isqrt_u64(sum); // >= 2^30, and >= every scaled[i].
    if len == 0 {
        // Unreachable (len >= 2^30); removes the division's panic branch.
        return None;
    }
    let mut out = [0i64; 3];
    let mut i = 0;
    while i < 3 {
        // scaled[i] << 30 < 2^61: no overflow.
        let q = ((scaled[i] << frac) + len / 2) / len;
        // q <= 2^frac <= 2^30: both casts are exact.
        let q = q as u32 as i64;
        out[i] = if v[i] < 0 { -q } else { q };
        i += 1;
    }
    Some(out)
}

/// Normalises any integer vector to a Q1.14 unit vector; `None` for the
/// zero vector.
///
/// Each component is within 0.5 + 7·10⁻⁵ ulp (2⁻¹⁴) of the exact unit
/// vector's and is in [-16384, 16384].
pub const fn normalize_q14(v: [i64; 3]) -> Option<[i16; 3]> {
    match unit(v, 14) {
        // Magnitudes are at most 16384: the casts are exact.
        Some(u) => Some([u[0] as i16, u[1] as i16, u[2] as i16]),
        None => None,
    }
}

/// Exact cross product `(b - a) × (c - a)` of i16 positions.
pub(crate) const fn cross(a: [i16; 3], b: [i16; 3], c: [i16; 3]) -> [i64; 3] {
    let d1 = [
        b[0] as i64 - a[0] as i64,
        b[1] as i64 - a[1] as i64,
        b[2] as i64 - a[2] as i64,
    ];
    let d2 = [
        c[0] as i64 - a[0] as i64,
        c[1] as i64 - a[1] as i64,
        c[2] as i64 - a[2] as i64,
    ];
    [
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ]
}

/// Unit normal of the counter-clockwise triangle `a, b, c` in Q1.14
/// (within 0.5 + 7·10⁻⁵ ulp per component), or (0, 0, 0) if its area is
/// zero.
pub const fn face_normal(a: [i16; 3], b: [i16; 3], c: [i16; 3]) -> [i16; 3] {
    match normalize_q14(cross(a, b, c)) {
        Some(n) => n,
        None => [0; 3],
    }
}

/// Unit face normal in Q1.30 (within 5 units of 2⁻³⁰ per component),
/// or zero for a zero-area face.
pub(crate) const fn face_normal_q30(a: [i16; 3], b: [i16; 3], c: [i16; 3]) -> [i32; 3] {
    match unit(cross(a, b, c), 30) {
        // Magnitudes are at most 2^30: the casts are exact.
        Some(u) => [u[0] as i32, u[1] as i32, u[2] as i32],
        None => [0; 3],
    }
}

/// Fraction bits of a face's culling slack (see [`face_plane`]).
pub const SLACK_FRAC_BITS: u32 = 2;

/// The length `λ` added to a face's edges in its culling slack (see
/// [`face_plane`]): `2^-8` units, in Q1.14.
pub const SLACK_LENGTH: u64 = 64;

/// `⌊√s⌋` for `s < 3·2^66`, or a lower bound of it (`4·⌊√(s/16)⌋`)
/// beyond `2^64`.
const fn floor_sqrt_u128(s: u128) -> u64 {
    if s < 1 << 64 {
        isqrt_u64(s as u64)
    } else {
        // s >> 4 < 3·2^62 fits u64.
        isqrt_u64((s >> 4) as u64) << 2
    }
}

/// `|p - q|` rounded strictly up (`⌊√⌋ + 1`; the square below 3·2^32).
const fn edge_up(p: [i16; 3], q: [i16; 3]) -> u64 {
    let dx = (p[0] as i64 - q[0] as i64).unsigned_abs();
    let dy = (p[1] as i64 - q[1] as i64).unsigned_abs();
    let dz = (p[2] as i64 - q[2] as i64).unsigned_abs();
    isqrt_u64(dx * dx + dy * dy + dz * dz) + 1
}

/// The culling plane of the counter-clockwise triangle `a, b, c`, as
/// `[d, slack]`; its slack bounds the per-vertex normal cones
/// ([`cone_covers`]):
///
/// - `d = n · a` exactly, with `n` the Q1.14 [`face_normal`] (so
///   `|d| <= 16386 · 2^15·√3 < 2^30`);
/// - `slack >= 2^SLACK_FRAC_BITS · (ℓ₁ + ℓ₂ + λ) / (2·area)` (units⁻¹),
///   with `ℓ₁, ℓ₂` the two edges at the corner facing the longest edge
///   and `λ` = [`SLACK_LENGTH`]: each length rounded up, the area rounded
///   down, the quotient rounded up; `u16::MAX` (65535) when it would not
///   fit, and for a zero-area face. The geometry stage uses it to bound
///   how far the rounding of projected corners can move the sign of the
///   face's screen area (`render::prepare`).
pub const fn face_plane(a: [i16; 3], b: [i16; 3], c: [i16; 3]) -> [i32; 2] {
    let n = face_normal(a, b, c);
    // |d| < 2^30 (above): the cast is exact.
    let d =
        (n[0] as i64 * a[0] as i64 + n[1] as i64 * a[1] as i64 + n[2] as i64 * a[2] as i64) as i32;
    let cr = cross(a, b, c);
    // Each component below 2^33: the sum of squares below 3·2^66.
    let s = (cr[0] as i128 * cr[0] as i128
        + cr[1] as i128 * cr[1] as i128
        + cr[2] as i128 * cr[2] as i128) as u128;
    let area2 = floor_sqrt_u128(s);
    if area2 == 0 {
        return [d, u16::MAX as i32];
    }
    // Edge lengths rounded up.
    let l = [edge_up(a, b), edge_up(b, c), edge_up(c, a)];
    let mut max = l[0];
    if l[1] > max {
        max = l[1];
    }
    if l[2] > max {
        max = l[2];
    }
    // Below 3·2^17 + λ: the shifted sum below 2^36.
    let sum = l[0] + l[1] + l[2] - max + SLACK_LENGTH;
    // Real units: (sum / 2^14) / (area2 / 2^28) = sum · 2^14 / area2.
    let num = sum << (SLACK_FRAC_BITS + 14);
    let q = num.div_ceil(area2);
    if q >= u16::MAX as u64 {
        [d, u16::MAX as i32]
    } else {
        [d, q as i32]
    }
}

/// The largest squared length of a cone axis (Q1.14): a unit normal
/// rounded per component, `16386²` (so `|axis| <= 1.0002`).
pub const MAX_AXIS2: i64 = 16386 * 16386;

/// Whether the direction of the counter-clockwise face `p, q, r` lies
/// within `spread / 2^14` (Euclidean) of the vector `a / 2^14`: `|n̂ -
/// a/2^14| <= spread/2^14` with `n̂` the exact unit normal of the face.
/// Exact integer arithmetic (no rounding); `false` for a zero-area face
/// and for `|a|² >` [`MAX_AXIS2`].
pub const fn cone_covers(a: [i16; 3], spread: u16, p: [i16; 3], q: [i16; 3], r: [i16; 3]) -> bool {
    let n = cross(p, q, r);
    // |n|² < 3·2^66; a·n < 3·2^14·2^33.
    let nn = (n[0] as i128 * n[0] as i128
        + n[1] as i128 * n[1] as i128
        + n[2] as i128 * n[2] as i128) as u128;
    if nn == 0 {
        return false;
    }
    let an =
        a[0] as i128 * n[0] as i128 + a[1] as i128 * n[1] as i128 + a[2] as i128 * n[2] as i128;
    let aa = a[0] as i64 * a[0] as i64 + a[1] as i64 * a[1] as i64 + a[2] as i64 * a[2] as i64;
    if aa > MAX_AXIS2 {
        return false;
    }
    // |n̂ - a'|² = 1 + |a'|² - 2 a'·n̂ <= s'², scaled by 2^28:
    // 2^15 (a·n)/|n| >= R = |a|² + 2^28 - s².
    let rr = aa + (1 << 28) - (spread as i64) * (spread as i64);
    // (2^15 a·n)² = 2^30 (a·n)² < 2^128; |R| < 2^29.1, R² |n|² < 2^126.
    let lhs = (an.unsigned_abs() * an.unsigned_abs()) << 30;
    let rhs = (rr.unsigned_abs() as u128 * rr.unsigned_abs() as u128) * nn;
    if rr <= 0 {
        // Holds when a·n >= 0; else needs 2^15 |a·n| <= |R| |n|.
        an >= 0 || lhs <= rhs
    } else {
        an > 0 && lhs >= rhs
    }
}
