//! [`SceneDesc`] to the ideal renderer's [`IdealScene`].

use crate::bake::unit_face_normal;
use crate::ideal::{IdealScene, Object, Vertex};

use super::{ObjectDesc, SceneDesc};

/// A Q1.14 value as a real number.
fn q14(v: [i16; 3]) -> [f64; 3] {
    v.map(|c| f64::from(c) / 16384.0)
}

impl SceneDesc {
    /// The scene for the ideal renderer: world-space triangles made from
    /// the Q1.14 mesh data (converted exactly to f64, then transformed in
    /// f64 by each object's [`Transform`](super::Transform)), world-space
    /// per-corner normals (the mesh's Q1.14 normals by the inverse transpose
    /// of the model transform, [`Transform::apply_normal`](super::Transform::apply_normal)), and the same
    /// frame, camera, lights and materials. The background levels become
    /// `level / 255`. So the ideal reference sees exactly the geometry the
    /// fixed-point core is given.
    pub fn to_ideal(&self) -> IdealScene {
        IdealScene {
            width: self.width,
            height: self.height,
            background: self.background.map(|l| f64::from(l) / 255.0),
            camera: self.camera.clone(),
            ambient: self.ambient,
            specular: self.specular,
            lights: self.lights.clone(),
            objects: self.objects.iter().map(ideal_object).collect(),
        }
    }
}

fn ideal_object(object: &ObjectDesc) -> Object {
    let mesh = object.mesh.mesh();
    let t = &object.transform;
    let triangles = (0..mesh.triangle_count())
        .filter_map(|tri| {
            let corners = mesh.triangle_positions(tri)?;
            let world = corners.map(|p| t.apply_point(q14(p)));
            let face = unit_face_normal(world[0], world[1], world[2]).unwrap_or([0.0; 3]);
            Some(std::array::from_fn(|c| Vertex {
                position: world[c],
                normal: mesh
                    .corner_normal(tri, c)
                    .map_or(face, |n| t.apply_normal(q14(n))),
            }))
        })
        .collect();
    Object {
        triangles,
        shading: object.shading,
        material: object.material.clone(),
        cull_backfaces: object.cull_backfaces,
    }
}
