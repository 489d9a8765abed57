//! Scenes: camera, objects, lights.
//!
//! A [`Scene`] borrows everything from the caller: objects and lights are
//! slices, meshes are const data in flash. Nothing is copied or allocated;
//! capacities are the slices' lengths (at most [`MAX_OBJECTS`] objects and
//! [`crate::illum::MAX_LIGHTS`] lights, checked with an error value).

mod camera;

pub use camera::Camera;

use crate::geom::Affine;
use crate::illum::{Light, Material, Specular, Viewer, MAX_LIGHTS};
use crate::mesh::Mesh;
use crate::num::Real;
use crate::pixel::{Rgb8, MAX_SCREEN};
use core::fmt;

/// Most objects in one scene: 32.
pub const MAX_OBJECTS: usize = 32;

/// How an object is shaded.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Shading {
    /// One illumination per triangle, at its centroid with the face normal.
    Flat,
    /// Illumination per vertex, colours interpolated. Fast, but misses
    /// highlights smaller than a triangle, and, since it interpolates the
    /// colours of a quad's two triangles separately, shades a quad
    /// differently when it is turned by 90°.
    #[default]
    Gouraud,
    /// Normals (and positions where needed) interpolated, normalised and
    /// illuminated per pixel: catches highlights inside a triangle.
    Phong,
}

/// One mesh placed in the scene.
#[derive(Clone, Copy, Debug)]
pub struct Object<'m, R> {
    /// The mesh (normals required for Gouraud and Phong shading).
    pub mesh: Mesh<'m>,
    /// Model to world.
    pub transform: Affine<R>,
    /// Material.
    pub material: Material<R>,
    /// Shading mode.
    pub shading: Shading,
    /// Drop triangles facing away from the eye; when off, both sides are
    /// drawn and lit (the back side with its normal reversed).
    pub cull_backfaces: bool,
}

/// A scene to render.
#[derive(Clone, Copy, Debug)]
pub struct Scene<'s, 'm, R> {
    /// The camera.
    pub camera: Camera<R>,
    /// The objects, drawn in order.
    pub objects: &'s [Object<'m, R>],
    /// The lights, in world space.
    pub lights: &'s [Light<R>],
    /// Ambient intensity `Ia`.
    pub ambient: R,
    /// Specular model.
    pub specular: Specular,
    /// Where the viewer is for the specular term.
    pub viewer: Viewer,
    /// Background colour.
    pub background: Rgb8,
}

impl<'s, 'm, R> Scene<'s, 'm, R> {
    /// The scene of `objects` and `lights` seen by `camera`, with ambient
    /// intensity `ambient`, the Phong specular model, a local viewer and a
    /// black background (set those fields for others).
    ///
    /// ```
    /// use fixshade::illum::{Specular, Viewer};
    /// use fixshade::scene::{Camera, Scene};
    /// use fixshade::target::Rgb8;
    ///
    /// let camera = Camera::<f32>::look_at_f32([0.0, 0.0, 4.0], [0.0; 3], [0.0, 1.0, 0.0], 45.0, 1.0, None)?;
    /// let scene = Scene::new(camera, &[], &[], 0.25);
    /// assert_eq!((scene.objects.len(), scene.lights.len(), scene.ambient), (0, 0, 0.25));
    /// assert_eq!((scene.specular, scene.viewer, scene.background), (Specular::Phong, Viewer::Local, Rgb8::BLACK));
    /// # Ok::<(), fixshade::scene::SceneError>(())
    /// ```
    pub const fn new(
        camera: Camera<R>,
        objects: &'s [Object<'m, R>],
        lights: &'s [Light<R>],
        ambient: R,
    ) -> Self {
        Self {
            camera,
            objects,
            lights,
            ambient,
            specular: Specular::Phong,
            viewer: Viewer::Local,
            background: Rgb8::BLACK,
        }
    }
}

impl<R: Real> Scene<'_, '_, R> {
    /// Checks the capacities.
    ///
    /// # Errors
    /// [`SceneError::TooManyObjects`] or [`SceneError::TooManyLights`].
    pub fn check(&self) -> Result<(), SceneError> {
        if self.objects.len() > MAX_OBJECTS {
            return Err(SceneError::TooManyObjects);
        }
        if self.lights.len() > MAX_LIGHTS {
            return Err(SceneError::TooManyLights);
        }
        Ok(())
    }
}

/// Why a scene or camera is invalid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum SceneError {
    /// A floating-point input is NaN or infinite (which parameter).
    NotFinite(&'static str),
    /// The eye is at the target.
    EyeAtTarget,
    /// The up vector is (nearly) parallel to the view direction.
    UpParallelToView,
    /// The field of view is outside (0°, 180°).
    FieldOfView,
    /// The near plane distance is not positive.
    Near,
    /// The far plane is not beyond the near plane.
    Far,
    /// The screen size is zero-free but above the limit, or the projection
    /// scale overflows the profile's range.
    Screen,
    /// More than [`MAX_OBJECTS`] objects.
    TooManyObjects,
    /// More than [`MAX_LIGHTS`] lights.
    TooManyLights,
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NotFinite(p) => write!(f, "{p} is not a finite number"),
            Self::EyeAtTarget => write!(f, "the eye is at the target: no view direction"),
            Self::UpParallelToView => write!(f, "the up vector is parallel to the view direction"),
            Self::FieldOfView => write!(
                f,
                "the field of view must lie strictly between 0 and 180 degrees"
            ),
            Self::Near => write!(f, "the near plane distance must be positive"),
            Self::Far => write!(f, "the far plane must lie beyond the near plane"),
            Self::Screen => write!(
                f,
                "the screen size is above {} pixels or out of the profile's range",
                MAX_SCREEN
            ),
            Self::TooManyObjects => write!(f, "at most {MAX_OBJECTS} objects are supported"),
            Self::TooManyLights => write!(f, "at most {MAX_LIGHTS} lights are supported"),
        }
    }
}

impl core::error::Error for SceneError {}
