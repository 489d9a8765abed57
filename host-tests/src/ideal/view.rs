//! World -> eye -> screen transforms.
//!
//! Eye space is right-handed: `x` right, `y` up, the camera looks down `-z`.
//! A point at eye-space `(x, y, z)` with `w = -z > 0` projects to
//! `ndc = (fx * x / w, fy * y / w)` where `fy = 1 / tan(fov_y / 2)` and
//! `fx = fy / aspect`, `aspect = width / height`; the viewport maps
//! `ndc.x` in `[-1, 1]` to `[0, width]` and `ndc.y` in `[-1, 1]` to
//! `[height, 0]` (screen `y` grows downward).

use super::scene::Camera;
use super::vec3::{self, V3};

/// Precomputed camera basis and projection for one frame size.
#[derive(Clone, Copy, Debug)]
pub(crate) struct View {
    /// Eye position in world space.
    eye: V3,
    /// Unit eye-space `x` axis in world space.
    right: V3,
    /// Unit eye-space `y` axis in world space.
    up: V3,
    /// Unit eye-space `z` axis in world space (points away from the target).
    back: V3,
    /// Horizontal projection scale `fy / aspect`.
    fx: f64,
    /// Vertical projection scale `1 / tan(fov_y / 2)`.
    fy: f64,
    /// Frame width in pixels.
    width: f64,
    /// Frame height in pixels.
    height: f64,
}

impl View {
    /// Builds the view for a camera that passed [`Camera::validate`] and a
    /// non-empty frame. Returns `None` if the basis is degenerate anyway.
    pub(crate) fn new(camera: &Camera, width: u32, height: u32) -> Option<Self> {
        let forward = vec3::normalize(vec3::sub(camera.target, camera.eye))?;
        let right = vec3::normalize(vec3::cross(forward, camera.up))?;
        let up = vec3::cross(right, forward);
        let fy = 1.0 / (camera.fov_y_deg.to_radians() * 0.5).tan();
        let (w, h) = (f64::from(width), f64::from(height));
        Some(Self {
            eye: camera.eye,
            right,
            up,
            back: vec3::scale(forward, -1.0),
            fx: fy * h / w,
            fy,
            width: w,
            height: h,
        })
    }

    /// World-space eye position.
    pub(crate) fn eye(&self) -> V3 {
        self.eye
    }

    /// World position -> eye-space position.
    pub(crate) fn eye_space(&self, p: V3) -> V3 {
        let d = vec3::sub(p, self.eye);
        [
            vec3::dot(d, self.right),
            vec3::dot(d, self.up),
            vec3::dot(d, self.back),
        ]
    }

    /// Eye-space position with `z < 0` -> screen position `[x, y]` in
    /// pixels and `w = -z`.
    pub(crate) fn project(&self, e: V3) -> ([f64; 2], f64) {
        let w = -e[2];
        let ndc_x = self.fx * e[0] / w;
        let ndc_y = self.fy * e[1] / w;
        let sx = (ndc_x + 1.0) * 0.5 * self.width;
        let sy = (1.0 - ndc_y) * 0.5 * self.height;
        ([sx, sy], w)
    }
}
