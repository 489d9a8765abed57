//! Clipping of triangles against the near and far planes in eye space.
//!
//! Clipping happens before the perspective divide, against `z = -near`
//! (keep `z <= -near`) and optionally `z = -far` (keep `z >= -far`). This is
//! the same as homogeneous clipping: every attribute of a new vertex is the
//! 3D linear interpolation along the clipped edge. The intersection of an
//! edge is always computed from its endpoints in one canonical order, so two
//! triangles that share an edge get bit-identical clip vertices.

use super::vec3::{self, V3};

/// A polygon corner carrying every attribute the renderer interpolates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ClipVertex {
    /// Eye-space position.
    pub(crate) eye: V3,
    /// World-space position (Phong shading).
    pub(crate) world: V3,
    /// World-space normal, not renormalised here (Phong shading).
    pub(crate) normal: V3,
    /// Vertex colour (Gouraud shading).
    pub(crate) color: V3,
}

impl ClipVertex {
    /// `a + t * (b - a)` for every attribute.
    fn lerp(a: &Self, b: &Self, t: f64) -> Self {
        Self {
            eye: vec3::lerp(a.eye, b.eye, t),
            world: vec3::lerp(a.world, b.world, t),
            normal: vec3::lerp(a.normal, b.normal, t),
            color: vec3::lerp(a.color, b.color, t),
        }
    }
}

/// A clipping plane in eye space.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Plane {
    /// Keep `z <= -near`.
    Near(f64),
    /// Keep `z >= -far`.
    Far(f64),
}

impl Plane {
    /// Signed distance: `>= 0` inside.
    fn distance(self, e: V3) -> f64 {
        match self {
            Plane::Near(near) => -e[2] - near,
            Plane::Far(far) => e[2] + far,
        }
    }
}

/// Point where the edge `p`-`q` crosses `plane`, computed from the endpoints
/// ordered lexicographically by eye position so the result does not depend
/// on the edge's direction.
fn intersect(p: &ClipVertex, q: &ClipVertex, plane: Plane) -> ClipVertex {
    let (a, b) = if p.eye.partial_cmp(&q.eye) == Some(std::cmp::Ordering::Greater) {
        (q, p)
    } else {
        (p, q)
    };
    let da = plane.distance(a.eye);
    let db = plane.distance(b.eye);
    let t = da / (da - db);
    let mut v = ClipVertex::lerp(a, b, t);
    // Put the new vertex exactly on the plane (the lerp may be an ulp off).
    v.eye[2] = match plane {
        Plane::Near(near) => -near,
        Plane::Far(far) => -far,
    };
    v
}

/// Sutherland-Hodgman clip of a convex polygon against one plane.
/// Vertices on the plane count as inside.
pub(crate) fn clip_polygon(poly: &[ClipVertex], plane: Plane) -> Vec<ClipVertex> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for (i, cur) in poly.iter().enumerate() {
        let next = &poly[(i + 1) % poly.len()];
        let dc = plane.distance(cur.eye);
        let dn = plane.distance(next.eye);
        if dc >= 0.0 {
            out.push(*cur);
        }
        if (dc >= 0.0) != (dn >= 0.0) {
            out.push(intersect(cur, next, plane));
        }
    }
    out
}

/// Clips a triangle against the near plane and the optional far plane and
/// returns the resulting convex polygon (empty, or 3 to 5 vertices).
pub(crate) fn clip_triangle(tri: [ClipVertex; 3], near: f64, far: Option<f64>) -> Vec<ClipVertex> {
    let mut poly = clip_polygon(&tri, Plane::Near(near));
    if let Some(far) = far {
        if !poly.is_empty() {
            poly = clip_polygon(&poly, Plane::Far(far));
        }
    }
    if poly.len() < 3 {
        poly.clear();
    }
    poly
}
