//! The scene file exactly as written: serde types with the defaults, before
//! any range check. See the [module docs](super) for the format.

use serde::Deserialize;

use super::{PixelFormat, Profile};

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawScene {
    #[serde(default = "default_size")]
    pub width: i64,
    #[serde(default = "default_size")]
    pub height: i64,
    #[serde(default)]
    pub pixel_format: PixelFormat,
    #[serde(default)]
    pub profile: Profile,
    #[serde(default)]
    pub background: [i64; 3],
    #[serde(default)]
    pub camera: RawCamera,
    #[serde(default)]
    pub lighting: RawLighting,
    #[serde(default)]
    pub light: Vec<RawLight>,
    #[serde(default)]
    pub object: Vec<RawObject>,
}

fn default_size() -> i64 {
    240
}

/// `[camera]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCamera {
    #[serde(default = "default_eye")]
    pub eye: [f64; 3],
    #[serde(default)]
    pub target: [f64; 3],
    #[serde(default = "default_up")]
    pub up: [f64; 3],
    #[serde(default = "default_fov")]
    pub fov_y_deg: f64,
    #[serde(default = "default_near")]
    pub near: f64,
    #[serde(default)]
    pub far: Option<f64>,
}

impl Default for RawCamera {
    fn default() -> Self {
        Self {
            eye: default_eye(),
            target: [0.0; 3],
            up: default_up(),
            fov_y_deg: default_fov(),
            near: default_near(),
            far: None,
        }
    }
}

fn default_eye() -> [f64; 3] {
    [0.0, 0.0, 6.0]
}

fn default_up() -> [f64; 3] {
    [0.0, 1.0, 0.0]
}

fn default_fov() -> f64 {
    40.0
}

fn default_near() -> f64 {
    0.1
}

/// `[lighting]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLighting {
    #[serde(default = "default_ambient")]
    pub ambient: f64,
    #[serde(default)]
    pub specular: RawSpecular,
}

impl Default for RawLighting {
    fn default() -> Self {
        Self {
            ambient: default_ambient(),
            specular: RawSpecular::Phong,
        }
    }
}

fn default_ambient() -> f64 {
    0.2
}

/// `lighting.specular`.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawSpecular {
    #[default]
    Phong,
    Blinn,
}

/// `light.type`.
#[derive(Clone, Copy, Debug, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawLightType {
    Point,
    Directional,
}

/// One `[[light]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLight {
    #[serde(rename = "type")]
    pub kind: RawLightType,
    #[serde(default)]
    pub position: Option<[f64; 3]>,
    #[serde(default)]
    pub direction: Option<[f64; 3]>,
    #[serde(default = "one")]
    pub intensity: f64,
    #[serde(default = "white")]
    pub color: [f64; 3],
}

fn one() -> f64 {
    1.0
}

fn white() -> [f64; 3] {
    [1.0; 3]
}

/// `object.shading`.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(rename_all = "lowercase")]
pub(crate) enum RawShading {
    Flat,
    #[default]
    Gouraud,
    Phong,
}

/// One `[[object]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawObject {
    pub mesh: String,
    #[serde(default)]
    pub shading: RawShading,
    #[serde(default)]
    pub crease_angle_deg: Option<f64>,
    #[serde(default)]
    pub scale: RawScale,
    #[serde(default)]
    pub rotate_deg: [f64; 3],
    #[serde(default)]
    pub translate: [f64; 3],
    #[serde(default = "yes")]
    pub cull_backfaces: bool,
    #[serde(default)]
    pub material: RawMaterial,
}

/// `object.scale`: one number (uniform) or `[x, y, z]` (per mesh axis).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum RawScale {
    Uniform(f64),
    Axes([f64; 3]),
}

impl Default for RawScale {
    fn default() -> Self {
        Self::Uniform(1.0)
    }
}

impl<'de> Deserialize<'de> for RawScale {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = RawScale;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number or an array of three numbers [x, y, z]")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<RawScale, E> {
                Ok(RawScale::Uniform(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<RawScale, E> {
                // Exact for |v| <= 2^53; larger values fail the range check.
                Ok(RawScale::Uniform(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<RawScale, E> {
                Ok(RawScale::Uniform(v as f64))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<RawScale, A::Error> {
                let mut axes = [0.0; 3];
                for (i, slot) in axes.iter_mut().enumerate() {
                    *slot = seq
                        .next_element::<f64>()?
                        .ok_or_else(|| serde::de::Error::invalid_length(i, &self))?;
                }
                if seq.next_element::<serde::de::IgnoredAny>()?.is_some() {
                    return Err(serde::de::Error::invalid_length(4, &self));
                }
                Ok(RawScale::Axes(axes))
            }
        }
        d.deserialize_any(Visitor)
    }
}

fn yes() -> bool {
    true
}

/// `object.material`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMaterial {
    #[serde(default = "white")]
    pub color: [f64; 3],
    #[serde(default = "default_ka")]
    pub ka: f64,
    #[serde(default = "default_kd")]
    pub kd: f64,
    #[serde(default = "default_ks")]
    pub ks: f64,
    #[serde(default = "default_shininess")]
    pub shininess: f64,
}

impl Default for RawMaterial {
    fn default() -> Self {
        Self {
            color: white(),
            ka: default_ka(),
            kd: default_kd(),
            ks: default_ks(),
            shininess: default_shininess(),
        }
    }
}

fn default_ka() -> f64 {
    0.2
}

fn default_kd() -> f64 {
    0.5
}

fn default_ks() -> f64 {
    0.5
}

fn default_shininess() -> f64 {
    100.0
}
