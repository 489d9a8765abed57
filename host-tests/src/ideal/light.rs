//! The Phong illumination model.
//!
//! `I = Ia*ka*C + sum_lights Ip * (kd*max(0, N.L)*C*Lc + ks*spec*Lc)`, each
//! channel clamped to `[0, 1]` after the sum, where `spec` is
//! `max(0, R.V)^n` with `R = 2(N.L)N - L` ([`SpecularModel::Phong`]) or
//! `max(0, N.H)^n` with `H = normalize(L + V)` ([`SpecularModel::Blinn`]),
//! and only lights with `N.L > 0` contribute a specular term. `L` points
//! from the shaded point towards the light, `V` towards the eye. No
//! attenuation.
//!
//! Degenerate directions are defined, never NaN: a zero normal shades as
//! ambient only; a point light exactly at the shaded point contributes
//! nothing; a zero `V` (or zero `L + V` for Blinn) gives no specular term.

use super::scene::{IdealScene, LightKind, Material, SpecularModel};
use super::vec3::{self, V3};

/// Illumination of `point` with surface normal `normal` (normalised here)
/// seen from `scene.camera.eye`, lit by `scene.lights` with
/// `scene.ambient` and `scene.specular`. Returns the clamped colour.
///
/// Does not validate its input (see [`IdealScene::validate`]); non-finite
/// input gives a non-finite colour, never a panic.
pub fn illuminate(
    scene: &IdealScene,
    material: &Material,
    point: [f64; 3],
    normal: [f64; 3],
) -> [f64; 3] {
    let c = material.color;
    let mut sum = vec3::scale(c, scene.ambient * material.ka);
    if let Some(n) = vec3::normalize(normal) {
        let v = vec3::normalize(vec3::sub(scene.camera.eye, point));
        for light in &scene.lights {
            let l = match light.kind {
                LightKind::Point { position } => vec3::normalize(vec3::sub(position, point)),
                LightKind::Directional { direction } => vec3::normalize(direction),
            };
            let Some(l) = l else { continue };
            let n_dot_l = vec3::dot(n, l);
            if n_dot_l <= 0.0 {
                continue;
            }
            let diffuse = vec3::scale(vec3::mul(c, light.color), material.kd * n_dot_l);
            let spec = v.map_or(0.0, |v| {
                specular(scene.specular, n, l, v, n_dot_l, material.shininess)
            });
            let specular = vec3::scale(light.color, material.ks * spec);
            sum = vec3::add(
                sum,
                vec3::scale(vec3::add(diffuse, specular), light.intensity),
            );
        }
    }
    sum.map(clamp01)
}

/// The specular factor `spec` for unit `n`, `l`, `v` with `n.l > 0`.
fn specular(model: SpecularModel, n: V3, l: V3, v: V3, n_dot_l: f64, shininess: f64) -> f64 {
    let cos = match model {
        SpecularModel::Phong => {
            let r = vec3::sub(vec3::scale(n, 2.0 * n_dot_l), l);
            vec3::dot(r, v)
        }
        SpecularModel::Blinn => match vec3::normalize(vec3::add(l, v)) {
            Some(h) => vec3::dot(n, h),
            None => 0.0,
        },
    };
    cos.max(0.0).powf(shininess)
}

/// Clamps to `[0, 1]` (NaN stays NaN).
pub(crate) fn clamp01(x: f64) -> f64 {
    x.clamp(0.0, 1.0)
}
