//! Tests of the ideal reference renderer: exact pixels on tiny frames,
//! illumination values computed by hand, clipping, culling, depth and
//! error handling. Shared scene builders live here; the tests are grouped
//! in the submodules.

use fixshade_host::ideal::{
    Camera, IdealFrame, IdealScene, Light, LightKind, Material, Object, Shading, SpecularModel,
    Vertex,
};

mod coverage;
mod errors;
mod geometry;
mod reference;
mod shading;

/// A camera at `eye` looking at `target` with `+y` up.
pub fn camera(eye: [f64; 3], target: [f64; 3], fov_y_deg: f64, near: f64) -> Camera {
    Camera {
        eye,
        target,
        up: [0.0, 1.0, 0.0],
        fov_y_deg,
        near,
        far: None,
    }
}

/// An empty scene: black background, no ambient, Phong specular, no
/// lights, no objects.
pub fn scene(width: u32, height: u32, camera: Camera) -> IdealScene {
    IdealScene {
        width,
        height,
        background: [0.0; 3],
        camera,
        ambient: 0.0,
        specular: SpecularModel::Phong,
        lights: Vec::new(),
        objects: Vec::new(),
    }
}

/// A material.
pub fn material(color: [f64; 3], ka: f64, kd: f64, ks: f64, shininess: f64) -> Material {
    Material {
        color,
        ka,
        kd,
        ks,
        shininess,
    }
}

/// A white-ish matte material (kd = 1, no ambient or specular).
pub fn matte() -> Material {
    material([1.0; 3], 0.0, 1.0, 0.0, 1.0)
}

/// A triangle from three positions, all corners with normal `n`.
pub fn tri(p: [[f64; 3]; 3], n: [f64; 3]) -> [Vertex; 3] {
    p.map(|position| Vertex {
        position,
        normal: n,
    })
}

/// The axis-aligned square `[x0, x1] x [y0, y1]` at height `z`, as two
/// triangles counter-clockwise seen from `+z`, normals `+z`.
pub fn square(x0: f64, y0: f64, x1: f64, y1: f64, z: f64) -> Vec<[Vertex; 3]> {
    let n = [0.0, 0.0, 1.0];
    vec![
        tri([[x0, y0, z], [x1, y0, z], [x1, y1, z]], n),
        tri([[x0, y0, z], [x1, y1, z], [x0, y1, z]], n),
    ]
}

/// An object.
pub fn object(
    triangles: Vec<[Vertex; 3]>,
    shading: Shading,
    material: Material,
    cull: bool,
) -> Object {
    Object {
        triangles,
        shading,
        material,
        cull_backfaces: cull,
    }
}

/// A white light of intensity 1.
pub fn light(kind: LightKind) -> Light {
    Light {
        kind,
        intensity: 1.0,
        color: [1.0; 3],
    }
}

/// Covered pixels as `(x, y)`, row-major order.
pub fn covered(frame: &IdealFrame) -> Vec<(u32, u32)> {
    let w = frame.width as usize;
    let mut out = Vec::new();
    for (i, &c) in frame.covered.iter().enumerate() {
        if c {
            out.push(((i % w) as u32, (i / w) as u32));
        }
    }
    out
}

/// Colour of pixel `(x, y)`.
pub fn color_at(frame: &IdealFrame, x: u32, y: u32) -> [f64; 3] {
    frame.color[frame.index(x, y).expect("pixel inside the frame")]
}
