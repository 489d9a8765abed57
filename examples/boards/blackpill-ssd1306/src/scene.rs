//! The board's scene and memory plan: the dodecahedron of
//! `examples/eg_simulator.rs`'s OLED view (a bright material for 1 bit,
//! Phong, one point light) turned 10° per frame about Y.
//!
//! This file has no board dependency: `examples/boards/scene-check`
//! includes it to render every frame of the turn on the host with these
//! very capacities (fit, active-triangle peak).

use fixshade::geom::{radians, Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::DODECAHEDRON;
use fixshade::num::{Fast, Profile, Q16};
use fixshade::render::{Capacity, Layout, Pool, Reach};
use fixshade::scene::{Camera, Object, Scene, SceneError, Shading};
use fixshade::target::Rgb8;

/// Screen width (pixels).
pub const W: u32 = 128;
/// Screen height (pixels).
pub const H: u32 = 64;
/// Rows of a band.
pub const ROWS: u32 = 16;
/// Pixels of a band.
pub const BAND_PX: usize = (W * ROWS) as usize;

/// The prepared frame's capacities, computed by the core's `const fn`
/// from the mesh: every vertex (60: one per face corner, the faces are
/// flat; the camera never clips, so none is added), 7 values per vertex
/// (Phong: depth, normal, eye position for the point light and the local
/// viewer), every triangle (36).
pub const CAPACITY: Capacity =
    Capacity::EMPTY.object(&DODECAHEDRON, Layout::PhongPosition, Reach::Inside);
/// Vertices of the workspace.
pub const VERTICES: usize = CAPACITY.vertices;
/// Values of the workspace (7 per vertex).
pub const VALUES: usize = CAPACITY.values;
/// Triangle numbers of the workspace (a byte each: kept or not, first
/// row, back face; the mesh's triangles are read from flash, not copied).
pub const TRIANGLES: usize = CAPACITY.triangles;
/// Triangles the workspace makes (none: inside the clipping planes,
/// culled).
pub const MADE: usize = CAPACITY.made;
/// Flat-triangle colours (none: the dodecahedron is shaded Phong).
pub const COLORS: usize = CAPACITY.colors;
/// The band renderer's order scratch: a `u16` per triangle number (the
/// kept triangles by band, and the queue of those put off while the pool
/// is full).
pub const ORDER: usize = TRIANGLES;

/// Active-triangle pool: the most triangles kept across a band border in
/// any frame of the turn is 12 (`Bands::active_peak`, measured on the host
/// by `scene-check` for every frame; 6 to 12 per frame); 16 slots leave a
/// margin of 4. A fuller pool is not an error: the triangles that find it
/// full are set up again in each band they reach (same pixels, more
/// setups, logged).
pub const POOL_SLOTS: usize = 16;
/// Values a slot holds: 8, as Phong with the eye position has 7 (a
/// triangle with more values than a slot holds is set up in every band).
pub const POOL_VALUES: usize = 8;
/// The pool: 3 008 bytes (16 × 188: a slot is 88 bytes of walk plus 12 per
/// value, and 4 for the pool's lists; `size_of` checked by scene-check).
pub type BandPool = Pool<<Fast as Profile>::Lerp, POOL_SLOTS, POOL_VALUES>;

const _: () = assert!(
    VERTICES >= DODECAHEDRON.vertex_count(),
    "the workspace holds fewer vertices than the mesh has"
);
const _: () = assert!(
    TRIANGLES >= DODECAHEDRON.triangle_count(),
    "the workspace holds fewer triangles than the mesh has"
);
const _: () = assert!(
    ORDER >= TRIANGLES,
    "the order scratch needs an entry per triangle number"
);

/// Frames per turn (10° apart).
pub const FRAMES: i32 = 36;

/// `n / d` in Q16.16.
const fn q(n: i32, d: i32) -> Q16 {
    Q16::from_ratio_const(n, d)
}

/// The view of examples/eg_simulator.rs's OLED frame: the solid fills ~60
/// of the 64 rows.
///
/// # Errors
/// The camera's error for a degenerate view (not with these values).
pub fn camera() -> Result<Camera<Q16>, SceneError> {
    Camera::look_at(
        Vec3::new(q(0, 1), q(0, 1), q(6, 1)),
        Vec3::ZERO,
        Vec3::new(q(0, 1), q(1, 1), q(0, 1)),
        radians(q(20, 1)),
        q(1, 2),
        None,
    )
}

/// One white point light at (2, 2, 4).
pub fn lights() -> [Light<Q16>; 1] {
    [Light::point(Vec3::new(q(2, 1), q(2, 1), q(4, 1)), q(1, 1))]
}

/// The solid of frame `i`: a bright pale yellow (see the README's 1-bit
/// section), tilted 20° about X and turned by `2π·i/FRAMES` about Y.
pub fn objects(i: i32) -> [Object<'static, Q16>; 1] {
    let material = Material {
        color: Vec3::new(q(1, 1), q(9, 10), q(6, 10)),
        ka: q(2, 10),
        kd: q(7, 10),
        ks: q(4, 10),
        shininess: q(25, 1),
    };
    let angle = q(2 * 314_159 * i, 100_000 * FRAMES);
    [Object {
        mesh: DODECAHEDRON,
        transform: Affine::from_parts(
            q(1, 1),
            Vec3::new(radians(q(20, 1)), angle, q(0, 1)),
            Vec3::ZERO,
        ),
        material,
        shading: Shading::Phong,
        cull_backfaces: true,
    }]
}

/// The scene of `objects` and `lights` seen by `camera`.
pub fn scene<'s>(
    camera: Camera<Q16>,
    objects: &'s [Object<'static, Q16>],
    lights: &'s [Light<Q16>],
) -> Scene<'s, 'static, Q16> {
    Scene {
        camera,
        objects,
        lights,
        ambient: q(1, 1),
        specular: Specular::Phong,
        viewer: Viewer::Local,
        background: Rgb8::BLACK,
    }
}
