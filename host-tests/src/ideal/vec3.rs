//! Minimal `[f64; 3]` vector helpers used by the ideal renderer.
//!
//! Plain functions on arrays, so that every formula in the renderer reads
//! like the maths it implements. Nothing here panics.

/// A 3-component `f64` vector (position, direction, normal or colour).
pub(crate) type V3 = [f64; 3];

/// `a + b`.
pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `a - b`.
pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `s * a`.
pub(crate) fn scale(a: V3, s: f64) -> V3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

/// Component-wise product `a * b` (used for colours).
pub(crate) fn mul(a: V3, b: V3) -> V3 {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}

/// Dot product.
pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Right-handed cross product `a x b`.
pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Euclidean length.
pub(crate) fn length(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// Unit vector in the direction of `a`, or `None` when `a` has zero (or
/// non-finite) length.
pub(crate) fn normalize(a: V3) -> Option<V3> {
    let len = length(a);
    if len > 0.0 && len.is_finite() {
        Some(scale(a, 1.0 / len))
    } else {
        None
    }
}

/// `a + t * (b - a)`.
pub(crate) fn lerp(a: V3, b: V3, t: f64) -> V3 {
    add(a, scale(sub(b, a), t))
}

/// True when every component is finite.
pub(crate) fn is_finite(a: V3) -> bool {
    a.iter().all(|c| c.is_finite())
}
