//! A 3D scene as constant data without floating point: what the generated
//! file (`generated.rs`) holds per scene.

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::Mesh;
use fixshade::num::Q16;
use fixshade::render::Capacity;
use fixshade::scene::{Camera, Object, Scene, SceneError, Shading};
use fixshade::target::Rgb8;

/// `Q16::from_bits(bits)`, short for the generated file.
pub const fn q(bits: i32) -> Q16 {
    Q16::from_bits(bits)
}

/// A vector of raw Q16 bits.
pub const fn v(x: i32, y: i32, z: i32) -> Vec3<Q16> {
    Vec3::new(q(x), q(y), q(z))
}

/// One object: its mesh and the inputs of its model transform
/// (`Affine::from_parts`, computed at run time as on the host).
#[derive(Clone, Copy, Debug)]
pub struct ObjectSpec {
    /// The mesh (a built-in one, or built-in positions with regenerated
    /// normals).
    pub mesh: Mesh<'static>,
    /// Uniform scale.
    pub scale: Q16,
    /// Rotation about X, Y, Z in radians.
    pub rotation: Vec3<Q16>,
    /// Translation.
    pub translation: Vec3<Q16>,
    /// Material.
    pub material: Material<Q16>,
    /// Shading mode.
    pub shading: Shading,
    /// Back-face culling.
    pub cull_backfaces: bool,
}

impl ObjectSpec {
    /// The core's object.
    pub fn object(&self) -> Object<'static, Q16> {
        Object {
            mesh: self.mesh,
            transform: Affine::from_parts(self.scale, self.rotation, self.translation),
            material: self.material,
            shading: self.shading,
            cull_backfaces: self.cull_backfaces,
        }
    }
}

/// A scene: the camera's `look_at` inputs, objects, lights and the rest
/// of the core's `Scene`, the frame size and the storage it needs.
#[derive(Clone, Copy, Debug)]
pub struct SceneSpec {
    /// The built-in scene's name (`fixshade scenes`).
    pub name: &'static str,
    /// Frame width in pixels (at most [`crate::WIDTH`]).
    pub width: u32,
    /// Frame height in pixels.
    pub height: u32,
    /// Camera position.
    pub eye: Vec3<Q16>,
    /// Point looked at.
    pub target: Vec3<Q16>,
    /// Up direction.
    pub up: Vec3<Q16>,
    /// Vertical field of view, radians.
    pub fov_y: Q16,
    /// Near plane.
    pub near: Q16,
    /// Far plane.
    pub far: Option<Q16>,
    /// Objects.
    pub objects: &'static [ObjectSpec],
    /// Lights.
    pub lights: &'static [Light<Q16>],
    /// Ambient intensity.
    pub ambient: Q16,
    /// Specular model.
    pub specular: Specular,
    /// Background colour.
    pub background: Rgb8,
    /// The storage it needs: the core's bound for its meshes
    /// (`Capacity::object`, in the generated source).
    pub capacity: Capacity,
    /// Whether it needs a depth band (not for one convex object with back
    /// faces culled).
    pub depth: bool,
}

impl SceneSpec {
    /// The camera, by `Camera::look_at` as on the host.
    ///
    /// # Errors
    /// The core's refusal of the camera.
    pub fn camera(&self) -> Result<Camera<Q16>, SceneError> {
        Camera::look_at(
            self.eye,
            self.target,
            self.up,
            self.fov_y,
            self.near,
            self.far,
        )
    }

    /// The core's scene over `objects` (built by [`ObjectSpec::object`]).
    pub fn scene<'s>(
        &'s self,
        camera: Camera<Q16>,
        objects: &'s [Object<'static, Q16>],
    ) -> Scene<'s, 'static, Q16> {
        Scene {
            camera,
            objects,
            lights: self.lights,
            ambient: self.ambient,
            specular: self.specular,
            viewer: Viewer::Local,
            background: self.background,
        }
    }

    /// Triangles of its meshes.
    pub fn triangles(&self) -> usize {
        self.objects.iter().map(|o| o.mesh.triangle_count()).sum()
    }
}
