//! Exact integer square root, normalisation and face normals.
//!
//! The error analysis is in the [module docs](super#arithmetic-and-error-bounds).

/// ⌊√n⌋, exactly, for every u64 (bit-by-bit, 32 steps, no division).
pub const fn isqrt_u64(n: u64) -> u64 {
    if n < 2 {
        return n;
    }
    // Highest power of four not above n.
    let mut bit = 1u64 << ((63 - n.leading_zeros()) & !1);
    let mut rest = n;
    // Invariant: `root` is the root found so far, shifted left by the
    // number of bit pairs still to process.
    let mut root = 0u64;
    while bit != 0 {
        if rest >= root + bit {
            rest -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    root
}

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
