//! The perspective camera.

use super::SceneError;
use crate::geom::{Affine, Mat3, Vec3};
use crate::num::Real;

/// A perspective camera: a world-to-eye transform (the eye at the origin
/// looking down −z, y up) and a vertical field of view.
///
/// A point at eye-space `(x, y, z)` with `w = −z ≥ near` projects to the
/// screen at `(W/2 + k·x/w, H/2 − k·y/w)` pixels, with `k = H/2 ·
/// cot(fov/2)`; its depth is `d = 1 − near/w` (far plane at infinity) or
/// `d = far/(far − near) · (1 − near/w)`, in `[0, 1]`, affine in screen
/// space (which is why it is the interpolated depth).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera<R> {
    /// World to eye.
    pub view: Affine<R>,
    /// `cot(fov_y / 2)`.
    pub focal: R,
    /// Near plane distance.
    pub near: R,
    /// Optional far plane distance.
    pub far: Option<R>,
}

impl<R: Real> Camera<R> {
    /// Looks from `eye` at `target` with `up` roughly up, vertical field of
    /// view `fov_y` radians, near plane `near` and optional far plane.
    ///
    /// # Errors
    /// [`SceneError`] for eye at target, up parallel to the view direction,
    /// field of view outside (0, π), `near ≤ 0`, `far ≤ near`.
    pub fn look_at(
        eye: Vec3<R>,
        target: Vec3<R>,
        up: Vec3<R>,
        fov_y: R,
        near: R,
        far: Option<R>,
    ) -> Result<Self, SceneError> {
        let f = target - eye;
        if f.is_zero() {
            return Err(SceneError::EyeAtTarget);
        }
        let f = f.normalize();
        if f.is_zero() {
            return Err(SceneError::EyeAtTarget);
        }
        let s = f.cross(up.normalize());
        // |f × up| = sin(angle): refuse angles below 2^-7 rad (0.45°).
        if s.length_sq() < R::from_ratio(1, 1 << 14) {
            return Err(SceneError::UpParallelToView);
        }
        let s = s.normalize();
        let u = s.cross(f);
        Self::from_basis(eye, s, u, f, fov_y, near, far)
    }

    /// The viewing convention of the seed project "Phong and Gouraud
    /// shading": view reference point `vrp`, view plane normal `vpn` (the
    /// viewing direction), view up `vup`, and the centre of projection
    /// `cop` units behind the VRP along the VPN: the eye is at `vrp − cop ·
    /// vpn/|vpn|`. Its defaults, VRP (0,0,1), VPN (0,0,−1), VUP (0,1,0),
    /// COP 5, put the eye at (0, 0, 6) looking at the origin.
    ///
    /// # Errors
    /// As [`Camera::look_at`]; a zero VPN or `cop ≤ 0` is
    /// [`SceneError::EyeAtTarget`].
    pub fn from_vrp(
        vrp: Vec3<R>,
        vpn: Vec3<R>,
        vup: Vec3<R>,
        cop: R,
        fov_y: R,
        near: R,
        far: Option<R>,
    ) -> Result<Self, SceneError> {
        let n = vpn.normalize();
        if n.is_zero() || cop <= R::ZERO {
            return Err(SceneError::EyeAtTarget);
        }
        let eye = vrp - n.scale(cop);
        Self::look_at(eye, vrp, vup, fov_y, near, far)
    }

    /// [`Camera::look_at`] from `f32` values, the field of view in
    /// degrees: each input is checked for NaN and infinity first.
    ///
    /// # Errors
    /// [`SceneError::NotFinite`] naming the parameter, or as
    /// [`Camera::look_at`].
    pub fn look_at_f32(
        eye: [f32; 3],
        target: [f32; 3],
        up: [f32; 3],
        fov_y_deg: f32,
        near: f32,
        far: Option<f32>,
    ) -> Result<Self, SceneError> {
        let fin = |v: &[f32], name| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(SceneError::NotFinite(name))
            }
        };
        fin(&eye, "eye")?;
        fin(&target, "target")?;
        fin(&up, "up")?;
        fin(&[fov_y_deg], "fov_y_deg")?;
        fin(&[near], "near")?;
        if let Some(f) = far {
            fin(&[f], "far")?;
        }
        if !(fov_y_deg > 0.0 && fov_y_deg < 180.0) {
            return Err(SceneError::FieldOfView);
        }
        let rad = R::from_f32(fov_y_deg * (core::f32::consts::PI / 180.0));
        Self::look_at(
            Vec3::from_f32(eye),
            Vec3::from_f32(target),
            Vec3::from_f32(up),
            rad,
            R::from_f32(near),
            far.map(R::from_f32),
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn from_basis(
        eye: Vec3<R>,
        s: Vec3<R>,
        u: Vec3<R>,
        f: Vec3<R>,
        fov_y: R,
        near: R,
        far: Option<R>,
    ) -> Result<Self, SceneError> {
        // pi as 355/113 (error 2.7e-7, below one Q16 step).
        if fov_y <= R::ZERO || fov_y >= R::from_ratio(355, 113) {
            return Err(SceneError::FieldOfView);
        }
        if near <= R::ZERO {
            return Err(SceneError::Near);
        }
        if let Some(fa) = far {
            if fa <= near {
                return Err(SceneError::Far);
            }
        }
        let (sn, cs) = fov_y.half().sin_cos();
        if sn <= R::ZERO {
            return Err(SceneError::FieldOfView);
        }
        let m = Mat3 { rows: [s, u, -f] };
        let t = -m.apply(eye);
        Ok(Self {
            view: Affine { m, t },
            focal: cs.div(sn),
            near,
            far,
        })
    }
}
