//! The render loop: culling, shading set-up, clipping, rasterisation,
//! perspective-correct interpolation and the depth test.

use super::clip::{clip_triangle, ClipVertex};
use super::error::IdealError;
use super::frame::IdealFrame;
use super::light::{clamp01, illuminate};
use super::raster::for_each_covered;
use super::scene::{IdealScene, Object, Shading, Vertex};
use super::vec3::{self, V3};
use super::view::View;

/// Renders `scene` exactly (in `f64`) following the conventions in the
/// [module docs](super). Validates the scene first and returns an error
/// instead of panicking on bad input; a zero-size frame renders as an empty
/// frame.
pub fn render(scene: &IdealScene) -> Result<IdealFrame, IdealError> {
    scene.validate()?;
    let mut frame = IdealFrame::new(scene.width, scene.height, scene.background);
    if scene.width == 0 || scene.height == 0 {
        return Ok(frame);
    }
    let view = View::new(&scene.camera, scene.width, scene.height).ok_or(IdealError::UpParallel)?;
    for (index, object) in scene.objects.iter().enumerate() {
        for tri in &object.triangles {
            draw_triangle(scene, &view, index, object, tri, &mut frame)?;
        }
    }
    Ok(frame)
}

/// Which side of a world-space triangle the eye sees.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Facing {
    /// The side from which the corners run counter-clockwise.
    Front,
    /// The other side.
    Back,
    /// The eye lies in the triangle's plane (or the triangle is degenerate).
    EdgeOn,
}

/// Classifies a triangle: front when `((p1 - p0) x (p2 - p0)) . (eye - p0) > 0`,
/// i.e. the corners run counter-clockwise seen from the eye.
pub(crate) fn facing(p: [V3; 3], eye: V3) -> Facing {
    let n = vec3::cross(vec3::sub(p[1], p[0]), vec3::sub(p[2], p[0]));
    let s = vec3::dot(n, vec3::sub(eye, p[0]));
    if s > 0.0 {
        Facing::Front
    } else if s < 0.0 {
        Facing::Back
    } else {
        Facing::EdgeOn
    }
}

/// Culls, shades, clips and rasterises one triangle into `frame`.
fn draw_triangle(
    scene: &IdealScene,
    view: &View,
    index: usize,
    object: &Object,
    tri: &[Vertex; 3],
    frame: &mut IdealFrame,
) -> Result<(), IdealError> {
    let p = tri.map(|v| v.position);
    let sign = match facing(p, view.eye()) {
        Facing::Front => 1.0,
        Facing::Back if !object.cull_backfaces => -1.0,
        Facing::Back | Facing::EdgeOn => return Ok(()),
    };
    // Normals used for lighting, flipped towards the eye on back faces.
    let normals = tri.map(|v| vec3::scale(vec3::normalize(v.normal).unwrap_or([0.0; 3]), sign));
    let material = &object.material;
    let flat_color = match object.shading {
        Shading::Flat => {
            let face = vec3::cross(vec3::sub(p[1], p[0]), vec3::sub(p[2], p[0]));
            let face = vec3::scale(vec3::normalize(face).unwrap_or([0.0; 3]), sign);
            let centroid = vec3::scale(vec3::add(vec3::add(p[0], p[1]), p[2]), 1.0 / 3.0);
            illuminate(scene, material, centroid, face)
        }
        Shading::Gouraud | Shading::Phong => [0.0; 3],
    };
    let corners: [ClipVertex; 3] = std::array::from_fn(|i| ClipVertex {
        eye: view.eye_space(p[i]),
        world: p[i],
        normal: normals[i],
        color: match object.shading {
            Shading::Gouraud => illuminate(scene, material, p[i], normals[i]),
            Shading::Flat | Shading::Phong => [0.0; 3],
        },
    });
    let poly = clip_triangle(corners, scene.camera.near, scene.camera.far);
    for k in 1..poly.len().saturating_sub(1) {
        let sub = [poly[0], poly[k], poly[k + 1]];
        let projected = sub.map(|v| view.project(v.eye));
        let screen = projected.map(|(s, _)| s);
        let w = projected.map(|(_, w)| w);
        if screen.iter().flatten().chain(&w).any(|c| !c.is_finite()) {
            return Err(IdealError::Overflow);
        }
        let mut overflow = false;
        for_each_covered(screen, frame.width, frame.height, |x, y, b| {
            let Some(i) = frame.index(x, y) else { return };
            // Perspective correction: weights proportional to b_i / w_i.
            let q = [b[0] / w[0], b[1] / w[1], b[2] / w[2]];
            let depth = 1.0 / (q[0] + q[1] + q[2]);
            if !(depth > 0.0 && depth < frame.depth[i]) {
                return;
            }
            let wt = q.map(|qi| qi * depth);
            let mix = |f: fn(&ClipVertex) -> V3| -> V3 {
                let mut acc = [0.0; 3];
                for (v, &t) in sub.iter().zip(&wt) {
                    acc = vec3::add(acc, vec3::scale(f(v), t));
                }
                acc
            };
            let color = match object.shading {
                Shading::Flat => flat_color,
                Shading::Gouraud => mix(|v| v.color).map(clamp01),
                Shading::Phong => illuminate(scene, material, mix(|v| v.world), mix(|v| v.normal)),
            };
            if color.iter().any(|c| c.is_nan()) {
                overflow = true;
                return;
            }
            frame.color[i] = color;
            frame.covered[i] = true;
            frame.depth[i] = depth;
            frame.object[i] = Some(index);
        });
        if overflow {
            return Err(IdealError::Overflow);
        }
    }
    Ok(())
}
