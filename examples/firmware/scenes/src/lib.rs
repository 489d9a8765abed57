//! The firmware's scenes and frame loop, shared by the firmware
//! (`thumbv6m-none-eabi`, `thumbv7em-none-eabihf`) and by `host-check`,
//! which renders the same scenes on the host so that the CRCs can be
//! compared.
//!
//! The scenes ([`SCENES`]) are built-in 3D scenes of the host
//! (`fixshade scenes`), turned into constant Q16 data by the host's
//! generator (`fixshade_host::firmware_scenes`, file `generated.rs`): no
//! floating point here. A frame is rendered with the core's `Fast` profile
//! (Q16.16) as the host's `fixshade render --profile fast` renders it:
//!
//! 1. *geometry*: build the core's `Scene` (camera by `Camera::look_at`,
//!    model transforms by `Affine::from_parts`, from the Q16 inputs) and
//!    `prepare::<Fast>` it once into the caller's workspace;
//! 2. *raster*: per band of [`BAND_ROWS`] rows (RGB565 big-endian, as SPI
//!    displays take it; a band-sized 16-bit depth buffer): clear the band
//!    to the background, clear the depth, render the prepared frame.
//!
//! Both are measured (a [`Probe`] brackets them); the CRC-32 of the
//! band's bytes and the count of covered pixels (depth values no longer
//! clear) are taken outside the brackets.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

#[cfg(test)]
extern crate std;

mod crc;
// With the feature `dodeca` or `bunny`, its whole-set constants are
// unused.
#[cfg_attr(any(feature = "dodeca", feature = "bunny"), allow(dead_code))]
#[rustfmt::skip]
mod generated;
pub mod knobs;
pub mod profiled;
pub mod spec;

pub mod alone;

#[cfg(all(feature = "bunny", not(feature = "dodeca")))]
pub use alone::bunny::{CAPACITY, DEPTH, SCENES, WIDTH};
#[cfg(feature = "dodeca")]
pub use alone::dodeca::{CAPACITY, DEPTH, SCENES, WIDTH};
pub use crc::Crc32;
#[cfg(not(any(feature = "dodeca", feature = "bunny")))]
pub use generated::{CAPACITY, DEPTH, SCENES, WIDTH};
pub use generated::{MAX_OBJECTS, MESH_NORMAL_BYTES, MESH_SHAPE_BYTES};
pub use spec::{ObjectSpec, SceneSpec};

use core::fmt;
use fixshade::num::{Fast, Profile};
use fixshade::render::{Capacity, Pool, RenderError, Workspace};
use fixshade::target::{BandBuf, BufferError, Rgb565Be};

/// The largest `len()` of field `$field` over [`SCENES`], at compile time
/// (a `const` loop: const evaluation takes no closure).
macro_rules! most_of_scenes {
    ($field:ident) => {{
        let mut n = 0;
        let mut i = 0;
        while i < SCENES.len() {
            if SCENES[i].$field.len() > n {
                n = SCENES[i].$field.len();
            }
            i += 1;
        }
        n
    }};
}

/// Most objects of a scene of the build ([`SCENES`]): the frame loop
/// holds a scene's objects in its stack frame, for the whole frame.
pub const SCENE_OBJECTS: usize = most_of_scenes!(objects);

/// Most lights of a scene of the build ([`SCENES`]; at most the core's
/// `MAX_LIGHTS`, checked by a test), held as [`SCENE_OBJECTS`].
pub const SCENE_LIGHTS: usize = most_of_scenes!(lights);

/// Rows per band: 16 ([`alone::dodeca::BAND_ROWS`] with the feature
/// `dodeca`, [`alone::bunny::BAND_ROWS`] with `bunny`).
pub const BAND_ROWS: u32 = if cfg!(feature = "dodeca") {
    alone::dodeca::BAND_ROWS
} else if cfg!(feature = "bunny") {
    alone::bunny::BAND_ROWS
} else {
    16
};
/// Pixels per band buffer: the widest scene's width × [`BAND_ROWS`]
/// (3 840 at 240 pixels).
pub const BAND_PIXELS: usize = (WIDTH * BAND_ROWS) as usize;
/// Depth values per depth band: [`BAND_PIXELS`], or none when no scene
/// needs depth ([`DEPTH`]: one convex object with back faces culled).
pub const DEPTH_PIXELS: usize = if DEPTH { BAND_PIXELS } else { 0 };

/// One stored pixel: RGB565, big-endian.
pub type Pixel = u16;
/// A band of the frame, with its 16-bit depth band.
pub type Band<'a> = BandBuf<'a, Rgb565Be>;

/// The storage the scenes need with profile `P`: [`CAPACITY`] in `P`
/// ([`Capacity::in_profile`]: one more value per vertex for
/// perspective-correct profiles, one value per grey Gouraud vertex for
/// `fast`, which packs its depth and level).
pub const fn capacity_for<P: Profile>() -> Capacity {
    CAPACITY.in_profile::<P>()
}

/// Bytes of the storage a firmware built for `spec` alone would hold with
/// profile `P` (`Capacity::bytes` of its capacity in `P`, for `P`'s
/// values): the scene's own share of the static RAM.
pub const fn storage_bytes<P: Profile>(spec: &SceneSpec) -> usize {
    spec.capacity
        .in_profile::<P>()
        .bytes(core::mem::size_of::<P::Lerp>())
}

/// A `scene` line as the firmware and `host-check` print it: name, size,
/// CRC, coverage, setups, mesh and prepared counts, and on a chip (with
/// [`ChipFields`]) the memory of a firmware built for the scene alone and
/// the stack.
#[derive(Clone, Copy, Debug)]
pub struct SceneLine<'a> {
    /// The scene.
    pub spec: &'a SceneSpec,
    /// Its frame.
    pub stats: &'a FrameStats,
    /// The fields only a chip prints.
    pub chip: Option<ChipFields>,
}

/// The `scene` line's fields only a chip prints.
#[derive(Clone, Copy, Debug)]
pub struct ChipFields {
    /// [`storage_bytes`] of the scene with the build's profile.
    pub storage_bytes: usize,
    /// Bytes of the pool of active triangles.
    pub pool_bytes: usize,
    /// Stack high-water mark, bytes.
    pub stack: usize,
    /// Static RAM of the whole build, bytes.
    pub static_ram: usize,
}

impl fmt::Display for SceneLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let (spec, s) = (self.spec, self.stats);
        write!(
            f,
            "scene {} size={}x{} crc=0x{:08x} covered={} drawn={} setups={} triangles={} prepared_vertices={} prepared_triangles={} prepared_bytes={}",
            spec.name,
            spec.width,
            spec.height,
            s.crc,
            s.covered,
            s.drawn,
            s.setups,
            spec.triangles(),
            s.vertices,
            s.triangles,
            s.prepared_bytes,
        )?;
        if let Some(c) = self.chip {
            let depth = if spec.depth {
                2 * spec.width * BAND_ROWS
            } else {
                0
            };
            write!(
                f,
                " storage_bytes={} depth_bytes={} pool_bytes={} stack={} static_ram={}",
                c.storage_bytes, depth, c.pool_bytes, c.stack, c.static_ram
            )?;
        }
        Ok(())
    }
}

/// The `Fast` storage of the scenes (sized by the compiler from their
/// meshes: see `generated.rs`).
pub type SceneStorage = fixshade::storage!(i32, CAPACITY);

/// Active triangles the firmware keeps from band to band: 56, or every
/// triangle of the storage when fewer; with the feature `dodeca`,
/// [`alone::dodeca::POOL_SLOTS`], with `bunny`
/// [`alone::bunny::POOL_SLOTS`]. A slot is `Pool::<i32, _, V>::SLOT_BYTES`
/// = 88 + 12·V bytes (the walk and the triangle index, see
/// `fixshade::render::Pool`'s docs). The bunny at 240×240
/// in 16-row bands keeps up to 55 triangles at once (`active_peak`), so 56
/// slots set every built-in scene's triangles up once (the scene tests
/// check it); with fewer, the triangles that find the pool full at a band
/// border are set up afresh in the next band (the same bytes, more setups).
pub const POOL_SLOTS: usize = if cfg!(feature = "dodeca") {
    alone::dodeca::POOL_SLOTS
} else if cfg!(feature = "bunny") {
    alone::bunny::POOL_SLOTS
} else if CAPACITY.triangles < 56 {
    CAPACITY.triangles
} else {
    56
};
/// Values a pool slot holds: 8, every layout (dodeca-phong-n100 has 7:
/// depth, normal, eye position; its `-pc` profiles 8); with the feature
/// `dodeca`, [`alone::dodeca::POOL_VALUES`], with `bunny`
/// [`alone::bunny::POOL_VALUES`].
pub const POOL_VALUES: usize = if cfg!(feature = "dodeca") {
    alone::dodeca::POOL_VALUES
} else if cfg!(feature = "bunny") {
    alone::bunny::POOL_VALUES
} else {
    8
};
/// Triangles whose point-light quadratics (Phong, position layout, one
/// point light) the pool keeps from band to band
/// ([`fixshade::render::QuadSlot`], `QuadSlot::BYTES` = 328 each, 3 280
/// bytes): set up once a frame instead of once a band. dodeca-phong-n100
/// in 16-row bands makes 18 set-ups with 10 slots (8: 20, 6: 24, none:
/// 46); a slot is taken when a triangle continues below its band and
/// freed once the bands are past the triangle's last row. None with the
/// features `dodeca` and `bunny` (their small boards' RAM).
pub const QUAD_SLOTS: usize = if cfg!(feature = "dodeca") || cfg!(feature = "bunny") {
    0
} else {
    10
};
/// The firmware's pool of active triangles.
pub type BandPool = Pool<i32, POOL_SLOTS, POOL_VALUES, QUAD_SLOTS>;

/// Marks the measured work: the firmware executes marker instructions
/// that the instruction-counting QEMU plugin toggles counting on (and
/// closes a region on); the host does nothing.
pub trait Probe {
    /// Counting on: measured work starts.
    fn resume(&mut self);
    /// Counting off: measured work ended.
    fn pause(&mut self);
    /// Closes a measured region (geometry, then raster, per frame).
    fn close(&mut self);
}

/// A probe that does nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProbe;

impl Probe for NoProbe {
    fn resume(&mut self) {}
    fn pause(&mut self) {}
    fn close(&mut self) {}
}

/// What a frame produced.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// CRC-32 of the frame's bytes, row-major, top to bottom.
    pub crc: u32,
    /// Pixels covered by at least one fragment (depth no longer clear).
    pub covered: u32,
    /// Fragments written (depth-test passes, over all bands).
    pub drawn: u32,
    /// Triangle setups (a triangle spanning two bands counts twice).
    pub setups: u32,
    /// Most triangles carried across a band border (the pool slots that
    /// set every triangle up once).
    pub active_peak: u32,
    /// Prepared vertices.
    pub vertices: u32,
    /// Prepared triangles.
    pub triangles: u32,
    /// `Frame::bytes_used()`: bytes of the prepared frame.
    pub prepared_bytes: u32,
}

/// Why a frame failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// A band buffer was refused.
    Buffer(BufferError),
    /// The core refused the scene, the workspace or a band.
    Render(RenderError),
}

impl From<BufferError> for FrameError {
    fn from(e: BufferError) -> Self {
        Self::Buffer(e)
    }
}

impl From<RenderError> for FrameError {
    fn from(e: RenderError) -> Self {
        Self::Render(e)
    }
}

impl From<fixshade::scene::SceneError> for FrameError {
    fn from(e: fixshade::scene::SceneError) -> Self {
        Self::Render(e.into())
    }
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Buffer(e) => write!(f, "band buffer: {e}"),
            Self::Render(e) => write!(f, "{e}"),
        }
    }
}

impl core::error::Error for FrameError {}

/// Prepares `spec` into `ws` (no probe): for the firmware's start-up
/// check that every scene fits its storage.
///
/// # Errors
/// The core's error, e.g. `RenderError::Capacity` naming the part that
/// is too small and the object.
pub fn check(spec: &SceneSpec, ws: Workspace<'_, i32>) -> Result<u32, FrameError> {
    profiled::check_with::<Fast>(spec, ws)
}

/// Renders one frame of `spec` with the `Fast` profile
/// ([`profiled::render_frame_with`]): prepares it into `ws`, then renders
/// it band by band into the band memory (`BAND_PIXELS` pixels, and as
/// many depth values or none, see [`DEPTH_PIXELS`]), with `probe` around
/// the measured work: one region for the geometry (scene, camera,
/// transforms, `prepare`), one for the bands.
///
/// # Errors
/// [`FrameError`] when the core refuses the scene, the workspace is too
/// small or a band buffer is refused.
pub fn render_frame<P: Probe>(
    spec: &SceneSpec,
    ws: Workspace<'_, i32>,
    pixels: &mut [Pixel],
    depth: Option<&mut [u16]>,
    order: &mut [u16],
    pool: &mut BandPool,
    probe: &mut P,
) -> Result<FrameStats, FrameError> {
    profiled::render_frame_with::<Fast, P>(spec, ws, pixels, depth, order, pool, probe)
}

/// [`render_frame`] with the depth band given whole (at least
/// `BAND_PIXELS` values when the build has one, [`DEPTH`]) and used when
/// the scene needs it ([`SceneSpec::depth`]): what the firmware calls
/// with its static bands, whose addresses (and alignment, for the band
/// clears) the optimiser then sees through to the band loop.
///
/// # Errors
/// As [`render_frame`].
pub fn render_frame_in<P: Probe>(
    spec: &SceneSpec,
    ws: Workspace<'_, i32>,
    pixels: &mut [Pixel],
    depth: &mut [u16],
    order: &mut [u16],
    pool: &mut BandPool,
    probe: &mut P,
) -> Result<FrameStats, FrameError> {
    knobs::render_frame_knobs_in::<Fast, fixshade::target::Depth16, P>(
        spec, ws, pixels, depth, spec.depth, BAND_ROWS, order, pool, probe,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixshade::render::{prepare, Part};
    use fixshade::target::{Depth16, DepthBuffer, DepthFormat, FrameBuf, Target};
    use std::{boxed::Box, vec};

    /// Renders a scene into a whole frame at once (no bands, a depth
    /// buffer): CRC and covered pixels.
    fn whole_frame(spec: &SceneSpec, ws: Workspace<'_, i32>) -> (u32, u32) {
        let objects: heapless::Vec<_, MAX_OBJECTS> =
            spec.objects.iter().map(ObjectSpec::object).collect();
        let scene = spec.scene(spec.camera().unwrap(), &objects);
        let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws).unwrap();
        let n = (spec.width * spec.height) as usize;
        let mut px = vec![0u16; n];
        let mut z = vec![0u16; n];
        let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, spec.width, spec.height).unwrap();
        fb.clear(scene.background);
        let mut db = DepthBuffer::<Depth16>::new(&mut z, spec.width, 0, spec.height).unwrap();
        frame.render(&scene, &mut fb, Some(&mut db)).unwrap();
        let mut crc = Crc32::new();
        crc.update(fb.bytes());
        let covered = z.iter().filter(|&&d| d != Depth16::CLEAR).count() as u32;
        (crc.finish(), covered)
    }

    #[test]
    fn bands_equal_the_whole_frame() {
        let mut st = Box::new(SceneStorage::new());
        let mut whole = Box::new(SceneStorage::new());
        // The band memory as the firmware holds it: arrays (no depth band
        // in the `dodeca` build, `DEPTH_PIXELS` = 0).
        let mut px = [0u16; BAND_PIXELS];
        let mut z = [0u16; DEPTH_PIXELS];
        let mut pool = Box::new(BandPool::new());
        for spec in SCENES.iter() {
            let (ws, order) = st.split();
            let depth = spec.depth.then_some(&mut z[..]);
            let s = render_frame(spec, ws, &mut px, depth, order, &mut pool, &mut NoProbe).unwrap();
            // Each triangle set up once: the pool's slots hold every
            // triangle kept across a band border (POOL_SLOTS: the bunny
            // keeps at most 55) with all its values (POOL_VALUES).
            std::println!(
                "{} active peak {} setups {}",
                spec.name,
                s.active_peak,
                s.setups
            );
            assert!(s.active_peak as usize <= POOL_SLOTS, "{}", spec.name);
            assert_eq!(s.setups, s.triangles, "{}", spec.name);
            // Without a depth band (one convex object): the same bytes,
            // each pixel drawn once.
            assert_eq!(
                (s.crc, s.covered),
                whole_frame(spec, whole.workspace()),
                "{}",
                spec.name
            );
            assert!(s.drawn >= s.covered && s.covered > 5000, "{s:?}");
            assert!(spec.depth || s.drawn == s.covered, "{s:?}");
        }
    }

    #[test]
    fn every_scene_fits_its_storage_and_not_less() {
        for spec in SCENES.iter() {
            let c = spec.capacity;
            let (mut xy, mut vals, mut tris) = (
                vec![fixshade::render::ScreenXy::ZERO; c.vertices],
                vec![0i32; c.values],
                vec![fixshade::render::Tri::EMPTY; c.made],
            );
            let mut colors = vec![fixshade::target::Rgb8::BLACK; c.colors];
            let mut faces = vec![0u8; c.triangles];
            let ws = Workspace {
                xy: &mut xy[..],
                vals: &mut vals[..],
                tris: &mut tris[..],
                colors: &mut colors[..],
                faces: &mut faces[..],
            };
            check(spec, ws).unwrap();
            let short = Workspace {
                xy: &mut xy[..c.vertices - 1],
                vals: &mut vals[..],
                tris: &mut tris[..],
                colors: &mut colors[..],
                faces: &mut faces[..],
            };
            let e = check(spec, short).unwrap_err();
            assert_eq!(
                e,
                FrameError::Render(RenderError::Capacity {
                    part: Part::Vertices,
                    object: spec.objects.len() - 1
                }),
                "{}",
                spec.name
            );
            assert!(
                std::format!("{e}")
                    .starts_with("workspace too small (Vertices) while preparing object"),
                "{e}"
            );
        }
    }

    #[test]
    fn the_storage_covers_every_scene() {
        for spec in SCENES.iter() {
            assert_eq!(spec.capacity.max(CAPACITY), CAPACITY);
            assert!(spec.width <= WIDTH && spec.objects.len() <= MAX_OBJECTS);
            assert!(spec.objects.len() <= SCENE_OBJECTS && spec.lights.len() <= SCENE_LIGHTS);
        }
        const { assert!(SCENE_OBJECTS <= MAX_OBJECTS) };
        const { assert!(SCENE_LIGHTS <= fixshade::illum::MAX_LIGHTS) };
        assert!(SCENES
            .iter()
            .any(|s| s.objects.len() == SCENE_OBJECTS && s.lights.len() == SCENE_LIGHTS));
        for spec in SCENES.iter() {
            assert!(DEPTH || !spec.depth);
        }
        // (A storage's `packed_values` are its values: it holds them in
        // any profile.)
        assert_eq!(
            SceneStorage::CAPACITY,
            Capacity {
                packed_values: CAPACITY.values,
                ..CAPACITY
            }
        );
    }
}
