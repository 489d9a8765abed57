//! Plain scene description consumed by the ideal renderer.
//!
//! All quantities are `f64` in world units; colours are linear values where
//! `1.0` is full intensity. These types are independent of the core crate's
//! scene types; glue code converts between them.

use serde::{Deserialize, Serialize};

use super::error::IdealError;
use super::vec3::{self, V3};

/// Largest frame (in pixels) that [`super::render`] accepts; bigger frames
/// are rejected with [`IdealError::FrameTooLarge`] instead of exhausting
/// memory. This is 4096 x 4096.
pub const MAX_PIXELS: u64 = 1 << 24;

/// A complete scene: frame size, camera, lighting and objects.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct IdealScene {
    /// Frame width in pixels (0 gives an empty frame).
    pub width: u32,
    /// Frame height in pixels (0 gives an empty frame).
    pub height: u32,
    /// Colour of pixels that no triangle covers (clamped to `[0, 1]`).
    pub background: [f64; 3],
    /// The viewer.
    pub camera: Camera,
    /// Ambient intensity `Ia`.
    pub ambient: f64,
    /// Which specular term the illumination model uses.
    pub specular: SpecularModel,
    /// Light sources, summed in order.
    pub lights: Vec<Light>,
    /// Objects, drawn in order (order matters only for depth ties).
    pub objects: Vec<Object>,
}

/// Right-handed look-at perspective camera.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Camera {
    /// Eye position in world space.
    pub eye: [f64; 3],
    /// A point the camera looks at; the view direction is `target - eye`.
    pub target: [f64; 3],
    /// Approximate up direction; must not be parallel to the view direction.
    pub up: [f64; 3],
    /// Vertical field of view in degrees, strictly between 0 and 180.
    pub fov_y_deg: f64,
    /// Distance of the near clipping plane, `> 0`.
    pub near: f64,
    /// Distance of the optional far clipping plane, `> near`.
    pub far: Option<f64>,
}

/// Specular term of the illumination model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum SpecularModel {
    /// `max(0, R.V)^n` with `R = 2(N.L)N - L`.
    Phong,
    /// `max(0, N.H)^n` with `H = normalize(L + V)`.
    Blinn,
}

/// A light source.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Light {
    /// Where the light is.
    pub kind: LightKind,
    /// Intensity `Ip`.
    pub intensity: f64,
    /// Colour `Lc` (multiplies both diffuse and specular terms).
    pub color: [f64; 3],
}

/// Geometry of a light source.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum LightKind {
    /// A point light at a world-space position (no attenuation).
    Point {
        /// World-space position of the light.
        position: [f64; 3],
    },
    /// A light at infinity.
    Directional {
        /// Direction from the scene *towards* the light; need not be unit
        /// length but must not be zero.
        direction: [f64; 3],
    },
}

/// One corner of a triangle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Vertex {
    /// World-space position.
    pub position: [f64; 3],
    /// World-space normal; normalised by the renderer, a zero normal shades
    /// as ambient only.
    pub normal: [f64; 3],
}

/// How an object's triangles are shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum Shading {
    /// One illumination per triangle, at its centroid with the face normal.
    Flat,
    /// Illumination at the vertices, colours interpolated.
    Gouraud,
    /// Normals and positions interpolated, illumination per pixel.
    Phong,
}

/// Surface reflectance of an object.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    /// Surface colour `C`.
    pub color: [f64; 3],
    /// Ambient coefficient.
    pub ka: f64,
    /// Diffuse coefficient.
    pub kd: f64,
    /// Specular coefficient.
    pub ks: f64,
    /// Specular exponent `n`, `>= 0`.
    pub shininess: f64,
}

/// A triangle mesh with one material and shading mode.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Object {
    /// Triangles; front faces are counter-clockwise seen from the front.
    pub triangles: Vec<[Vertex; 3]>,
    /// Shading mode.
    pub shading: Shading,
    /// Reflectance.
    pub material: Material,
    /// Skip triangles whose back faces the eye.
    pub cull_backfaces: bool,
}

/// Returns `Err(NonFinite(what))` unless every component is finite.
fn finite3(v: V3, what: impl FnOnce() -> String) -> Result<(), IdealError> {
    if vec3::is_finite(v) {
        Ok(())
    } else {
        Err(IdealError::NonFinite(what()))
    }
}

/// Returns `Err(NonFinite(what))` unless `x` is finite.
fn finite1(x: f64, what: impl FnOnce() -> String) -> Result<(), IdealError> {
    finite3([x, 0.0, 0.0], what)
}

impl Camera {
    /// Checks the camera: finite values, field of view in `(0, 180)`,
    /// `near > 0`, `far > near`, `eye != target`, `up` not parallel to the
    /// view direction.
    pub fn validate(&self) -> Result<(), IdealError> {
        finite3(self.eye, || "camera.eye".into())?;
        finite3(self.target, || "camera.target".into())?;
        finite3(self.up, || "camera.up".into())?;
        finite1(self.fov_y_deg, || "camera.fov_y_deg".into())?;
        finite1(self.near, || "camera.near".into())?;
        if !(self.fov_y_deg > 0.0 && self.fov_y_deg < 180.0) {
            return Err(IdealError::FieldOfView(self.fov_y_deg));
        }
        if self.near <= 0.0 {
            return Err(IdealError::Near(self.near));
        }
        if let Some(far) = self.far {
            finite1(far, || "camera.far".into())?;
            if far <= self.near {
                return Err(IdealError::Far {
                    near: self.near,
                    far,
                });
            }
        }
        let forward =
            vec3::normalize(vec3::sub(self.target, self.eye)).ok_or(IdealError::EyeAtTarget)?;
        let up = vec3::normalize(self.up).ok_or(IdealError::UpParallel)?;
        // Both unit vectors: the cross product's length is sin(angle).
        if vec3::length(vec3::cross(forward, up)) <= 1e-12 {
            return Err(IdealError::UpParallel);
        }
        Ok(())
    }
}

impl IdealScene {
    /// Checks the whole scene; [`super::render`] calls this first.
    pub fn validate(&self) -> Result<(), IdealError> {
        let pixels = u64::from(self.width) * u64::from(self.height);
        if pixels > MAX_PIXELS {
            return Err(IdealError::FrameTooLarge {
                width: self.width,
                height: self.height,
            });
        }
        finite3(self.background, || "background".into())?;
        finite1(self.ambient, || "ambient".into())?;
        self.camera.validate()?;
        for (i, light) in self.lights.iter().enumerate() {
            finite1(light.intensity, || format!("lights[{i}].intensity"))?;
            finite3(light.color, || format!("lights[{i}].color"))?;
            match light.kind {
                LightKind::Point { position } => {
                    finite3(position, || format!("lights[{i}].position"))?;
                }
                LightKind::Directional { direction } => {
                    finite3(direction, || format!("lights[{i}].direction"))?;
                    if vec3::normalize(direction).is_none() {
                        return Err(IdealError::ZeroLightDirection(i));
                    }
                }
            }
        }
        for (o, object) in self.objects.iter().enumerate() {
            let m = &object.material;
            finite3(m.color, || format!("objects[{o}].material.color"))?;
            for (x, name) in [(m.ka, "ka"), (m.kd, "kd"), (m.ks, "ks")] {
                finite1(x, || format!("objects[{o}].material.{name}"))?;
            }
            finite1(m.shininess, || format!("objects[{o}].material.shininess"))?;
            if m.shininess < 0.0 {
                return Err(IdealError::Shininess {
                    object: o,
                    value: m.shininess,
                });
            }
            for (t, tri) in object.triangles.iter().enumerate() {
                for (c, v) in tri.iter().enumerate() {
                    finite3(v.position, || {
                        format!("objects[{o}].triangles[{t}][{c}].position")
                    })?;
                    finite3(v.normal, || {
                        format!("objects[{o}].triangles[{t}][{c}].normal")
                    })?;
                }
            }
        }
        Ok(())
    }
}
