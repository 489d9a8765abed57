//! The board's scene and memory plan: the project's bunny benchmark
//! (host-tests/scenes/bunny-gouraud.toml, with the Q16 values the host's
//! `Q16::from_f64` gives) turned about Y by the firmware animation's Q16
//! angle, so its frames are those measured under QEMU
//! (examples/firmware/src/bin/animate.rs).
//!
//! This file has no board dependency: `examples/boards/scene-check`
//! includes it to render every frame of the turn on the host with these
//! very capacities (fit, active-triangle peak, frame CRCs).

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::BUNNY;
use fixshade::num::{Fast, Profile, Q16};
use fixshade::render::{Capacity, Layout, Pool, Reach};
use fixshade::scene::{Camera, Object, Scene, SceneError, Shading};
use fixshade::target::Rgb8;

/// Screen width and height (pixels).
pub const W: u32 = 240;
/// Screen height (pixels).
pub const H: u32 = 240;
/// Rows of a band.
pub const ROWS: u32 = 16;
/// Pixels of a band.
pub const BAND_PX: usize = (W * ROWS) as usize;

/// The prepared frame's capacities, computed by the core's `const fn`
/// from the mesh: every vertex of the bunny (1 839; a prepared vertex per
/// mesh vertex, and the camera never clips, so none is added), four values
/// per vertex (colour Gouraud: depth and three channels; this white scene
/// uses two, a coloured material or light four), every triangle (3 674: a
/// turn shows other faces than any one view). A material or shading that
/// needs more values is a start-up error over defmt.
pub const CAPACITY: Capacity = Capacity::EMPTY.object(&BUNNY, Layout::GouraudRgb, Reach::Inside);
/// Vertices of the workspace.
pub const VERTICES: usize = CAPACITY.vertices;
/// Values of the workspace (4 per vertex).
pub const VALUES: usize = CAPACITY.values;
/// Triangle numbers of the workspace (a byte each: kept or not, first
/// row, back face; the mesh's triangles are read from flash, not copied).
pub const TRIANGLES: usize = CAPACITY.triangles;
/// Triangles the workspace makes (none: inside the clipping planes,
/// culled).
pub const MADE: usize = CAPACITY.made;
/// Flat-triangle colours (none: the bunny is shaded Gouraud).
pub const COLORS: usize = CAPACITY.colors;
/// The band renderer's order scratch: a `u16` per triangle number (the
/// kept triangles by band, and the queue of those put off while the pool
/// is full).
pub const ORDER: usize = TRIANGLES;

/// Active-triangle pool: the most triangles kept across a band border in
/// any frame of the turn is 69 (`Bands::active_peak`, measured on the
/// host by `scene-check` for every frame; 49 to 69 per frame); 80 slots
/// leave a margin of 11.
/// A fuller pool is not an error: the triangles that find it full are set
/// up again in each band they reach (same pixels, more setups, logged).
pub const POOL_SLOTS: usize = 80;
/// Values a slot holds: depth and three colour channels (colour Gouraud,
/// no perspective).
pub const POOL_VALUES: usize = 4;
/// The pool: 11 200 bytes (80 × 140: a slot is 88 bytes of walk plus 12 per
/// value, and 4 for the pool's lists; `size_of` checked by scene-check).
pub type BandPool = Pool<<Fast as Profile>::Lerp, POOL_SLOTS, POOL_VALUES>;

const _: () = assert!(
    VERTICES >= BUNNY.vertex_count(),
    "the workspace holds fewer vertices than the mesh has"
);
const _: () = assert!(
    TRIANGLES >= BUNNY.triangle_count(),
    "the workspace holds fewer triangles than the mesh has"
);
const _: () = assert!(
    ORDER >= TRIANGLES,
    "the order scratch needs an entry per triangle number"
);
const _: () = assert!(
    H.is_multiple_of(ROWS),
    "every band must be full: the DMA sends whole band buffers"
);

/// Frames per turn (15° apart).
pub const FRAMES: i32 = 24;

/// `n / d` in Q16.16.
const fn q(n: i32, d: i32) -> Q16 {
    Q16::from_ratio_const(n, d)
}

/// The camera: 3.922 from the origin on +Z, 45° field of view, near 1,
/// far 10.
///
/// # Errors
/// The camera's error for a degenerate view (not with these values).
pub fn camera() -> Result<Camera<Q16>, SceneError> {
    Camera::look_at(
        Vec3::new(q(0, 1), q(0, 1), Q16::from_bits(257_032)), // 3.922
        Vec3::ZERO,
        Vec3::new(q(0, 1), q(1, 1), q(0, 1)),
        Q16::from_bits(51_472), // 45° in radians
        q(1, 1),
        Some(q(10, 1)),
    )
}

/// One directional white light of 0.8 from the upper right front.
pub fn lights() -> [Light<Q16>; 1] {
    [Light::directional(
        Vec3::new(q(1, 1), q(1, 1), q(1, 1)),
        Q16::from_bits(52_429), // 0.8
    )]
}

/// The bunny of frame `i`: white, `I = 0.2 + 0.8 max(0, N·L)`, turned by
/// `round(2π·i/FRAMES)` in Q16 (2π = 411 775 / 65 536), as the firmware
/// animation turns.
pub fn objects(i: i32) -> [Object<'static, Q16>; 1] {
    let angle = Q16::from_bits((411_775 * i + FRAMES / 2) / FRAMES);
    let material = Material {
        color: Vec3::new(q(1, 1), q(1, 1), q(1, 1)),
        ka: q(1, 1),
        kd: q(1, 1),
        ks: q(0, 1),
        shininess: q(1, 1),
    };
    [Object {
        mesh: BUNNY,
        transform: Affine::from_parts(q(1, 1), Vec3::new(q(0, 1), angle, q(0, 1)), Vec3::ZERO),
        material,
        shading: Shading::Gouraud,
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
        ambient: Q16::from_bits(13_107), // 0.2
        specular: Specular::Phong,
        viewer: Viewer::Local,
        background: Rgb8::BLACK,
    }
}
