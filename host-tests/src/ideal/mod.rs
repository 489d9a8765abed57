//! The ideal reference renderer: exact, slow, obviously correct `f64` code
//! that the fixed-point core is measured against.
//!
//! It has its own plain scene types ([`IdealScene`] and friends) and shares
//! no code with the core crate. [`render`] returns an [`IdealFrame`] with
//! colour, coverage, depth and object id per pixel.
//!
//! # Conventions
//!
//! * **Camera**: right-handed look-at; eye space has `x` right, `y` up and
//!   looks down `-z`. Perspective with vertical field of view `fov_y_deg`
//!   and aspect `width / height`. The viewport maps NDC `x` in `[-1, 1]` to
//!   `[0, width]` and NDC `y` in `[-1, 1]` to `[height, 0]` (screen `y`
//!   grows downward). Pixel `(i, j)` has its centre at `(i + 0.5, j + 0.5)`;
//!   frames are row-major from the top row.
//! * **Clipping**: against `z_eye = -near` and, if set, `z_eye = -far`, in
//!   eye space before the divide (equivalent to homogeneous clipping), with
//!   every attribute interpolated linearly in 3D. The clipped convex polygon
//!   is drawn as a fan from its first vertex. No `x`/`y` clipping: coverage
//!   is only evaluated at the screen's pixel centres.
//! * **Coverage**: `f64` edge functions at pixel centres with the top-left
//!   rule (see [`raster_screen`]): shared edges leave no gap and cover no
//!   pixel twice; zero-area triangles cover nothing.
//! * **Facing and culling**: a triangle `(p0, p1, p2)` is front-facing when
//!   `((p1 - p0) x (p2 - p0)) . (eye - p0) > 0`, i.e. its corners run
//!   counter-clockwise as seen from the eye in the right-handed world. On
//!   the y-down screen the same triangle has a *negative* screen edge
//!   function `E(s0 -> s1, s2)` (clockwise when the y-down coordinates are
//!   read as a y-up plane). The test is done in world space, so it is exact
//!   for triangles crossing the near plane too. Triangles whose plane
//!   contains the eye are skipped. With `cull_backfaces` the back faces are
//!   skipped; without it they are drawn with the face and vertex normals
//!   negated, so they face the viewer for lighting.
//! * **Depth**: the visible fragment is the one with the smallest
//!   eye-space depth `w = -z_eye`, interpolated perspective-correctly
//!   (`1 / w` is affine in screen space). A fragment replaces the stored one
//!   only if strictly nearer, so on equal depth the first drawn (object
//!   order, then triangle order, then fan order) wins.
//! * **Attributes**: screen-space barycentrics `b_i` at the pixel centre are
//!   corrected to `(b_i / w_i) / sum_j (b_j / w_j)`.
//! * **Illumination**: see [`illuminate`]. Flat shading evaluates it once
//!   per triangle at the centroid with the unit face normal
//!   `normalize((p1 - p0) x (p2 - p0))`; Gouraud at each corner with the
//!   (normalised) vertex normal, colours then interpolated and clamped;
//!   Phong per pixel with the interpolated position and renormalised
//!   interpolated normal. A zero normal shades as ambient only.
//! * **Output**: channels are clamped to `[0, 1]`; 8-bit levels are
//!   `round(c * 255)` ([`to_level`]).
//! * **Errors**: NaN/infinite input, a field of view outside `(0, 180)`,
//!   `near <= 0`, `far <= near`, `eye == target`, an up vector parallel to
//!   the view direction, a zero light direction, a negative shininess or a
//!   frame above [`MAX_PIXELS`] give an [`IdealError`]; a zero-size frame
//!   renders as an empty frame.

mod clip;
mod error;
mod frame;
mod light;
mod raster;
mod render;
mod scene;
mod vec3;
mod view;

pub use error::IdealError;
pub use frame::{to_level, IdealFrame};
pub use light::illuminate;
pub use raster::raster_screen;
pub use render::render;
pub use scene::{
    Camera, IdealScene, Light, LightKind, Material, Object, Shading, SpecularModel, Vertex,
    MAX_PIXELS,
};

#[cfg(test)]
mod tests;
