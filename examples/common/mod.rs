//! What the bunny examples share: the benchmark scene (the bunny, Gouraud,
//! one directional light, the camera of the firmware's `bunny-gouraud`) and
//! the storage of its prepared frame.

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material};
use fixshade::mesh::shapes::BUNNY;
use fixshade::num::Real;
use fixshade::render::{Capacity, Layout, Reach};
use fixshade::scene::{Camera, Object, Scene, SceneError, Shading};

/// The bunny's capacities: every vertex and triangle, colour Gouraud (the
/// camera never clips it).
pub const CAPACITY: Capacity = Capacity::EMPTY.object(&BUNNY, Layout::GouraudRgb, Reach::Inside);

/// The workspace and band order scratch of [`CAPACITY`], values of type
/// `L` (box it: about 70 KB for 4-byte values).
pub type Store<L> = fixshade::storage!(L, CAPACITY);

/// The bunny benchmark scene in scalar `R`: a white bunny at the origin,
/// `I = 0.2 + 0.8 max(0, N·L)`, seen from 3.922 on +Z with a 45° field of
/// view.
pub struct Bunny<R> {
    camera: Camera<R>,
    objects: [Object<'static, R>; 1],
    lights: [Light<R>; 1],
}

impl<R: Real> Bunny<R> {
    /// The scene's parts, the bunny shaded with `shading`.
    ///
    /// # Errors
    /// The camera's (not with these values).
    pub fn new(shading: Shading) -> Result<Self, SceneError> {
        let r = |v: f32| R::from_f32(v);
        let camera = Camera::look_at_f32(
            [0.0, 0.0, 3.922],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            45.0,
            1.0,
            Some(10.0),
        )?;
        let material = Material {
            color: Vec3::new(r(1.0), r(1.0), r(1.0)),
            ka: r(1.0),
            kd: r(1.0),
            ks: r(0.0),
            shininess: r(1.0),
        };
        Ok(Self {
            camera,
            objects: [Object {
                mesh: BUNNY,
                transform: Affine::IDENTITY,
                material,
                shading,
                cull_backfaces: true,
            }],
            lights: [Light::directional(Vec3::from_f32([1.0, 1.0, 1.0]), r(0.8))],
        })
    }

    /// The scene.
    pub fn scene(&self) -> Scene<'_, 'static, R> {
        Scene::new(self.camera, &self.objects, &self.lights, R::from_f32(0.2))
    }
}
