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
#[rustfmt::skip]
mod generated;
pub mod knobs;
pub mod profiled;
pub mod spec;

pub use crc::Crc32;
pub use generated::{MAX_NEEDS, MAX_OBJECTS, MESH_NORMAL_BYTES, MESH_SHAPE_BYTES, SCENES};
pub use spec::{Needs, ObjectSpec, SceneSpec};

use core::fmt;
use fixshade::num::{Fast, Q16};
use fixshade::render::{prepare, BandState, Frame, Pool, RenderError, Workspace};
use fixshade::scene::Object;
use fixshade::target::{BandBuf, BufferError, Depth16, DepthFormat, Rgb565Be};

/// Widest frame (and height) the band buffers hold.
pub const WIDTH: u32 = 240;
/// Rows per band.
pub const BAND_ROWS: u32 = 16;
/// Pixels (and depth values) per band buffer: 3 840.
pub const BAND_PIXELS: usize = (WIDTH * BAND_ROWS) as usize;

/// One stored pixel: RGB565, big-endian.
pub type Pixel = [u8; 2];
/// A band of the frame, with its 16-bit depth band.
pub type Band<'a> = BandBuf<'a, Rgb565Be>;

/// Active triangles the firmware keeps from band to band (the scene tests
/// check that every built-in scene sets each triangle up once with it:
/// the bunny keeps at most 55).
pub const POOL_SLOTS: usize = 64;
/// Values a pool slot holds: 8, every layout (dodeca-phong-n100 has 7:
/// depth, normal, eye position).
pub const POOL_VALUES: usize = 8;
/// The firmware's pool of active triangles.
pub type BandPool = Pool<i32, POOL_SLOTS, POOL_VALUES>;

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

/// The lengths of a workspace's parts.
pub fn capacity_of(ws: &Workspace<'_, i32>) -> Needs {
    Needs {
        vertices: ws.xy.len(),
        values: ws.vals.len(),
        triangles: ws.tris.len(),
        prepared_bytes: 0,
    }
}

/// The objects of `spec` for the core.
fn objects(spec: &SceneSpec) -> heapless::Vec<Object<'static, Q16>, MAX_OBJECTS> {
    spec.objects.iter().map(ObjectSpec::object).collect()
}

/// Prepares `spec` into `ws` (no probe): for the firmware's start-up
/// check that every scene fits its workspace.
///
/// # Errors
/// The core's error, e.g. `RenderError::Capacity` naming the part that
/// is too small and the object.
pub fn check(spec: &SceneSpec, ws: Workspace<'_, i32>) -> Result<FrameStats, FrameError> {
    let objects = objects(spec);
    let scene = spec.scene(spec.camera()?, &objects);
    let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws)?;
    Ok(prepared_stats(&frame))
}

fn prepared_stats(frame: &Frame<'_, Fast>) -> FrameStats {
    FrameStats {
        vertices: frame.vertex_count() as u32,
        triangles: frame.triangle_count() as u32,
        prepared_bytes: frame.bytes_used() as u32,
        ..FrameStats::default()
    }
}

/// Renders one frame of `spec`: prepares it into `ws`, then renders it
/// band by band into the band memory (`BAND_PIXELS` pixels and depth
/// values), with `probe` around the measured work: one region for the
/// geometry (scene, camera, transforms, `prepare`), one for the bands.
///
/// # Errors
/// [`FrameError`] when the core refuses the scene, the workspace is too
/// small or a band buffer is refused.
pub fn render_frame<P: Probe>(
    spec: &SceneSpec,
    ws: Workspace<'_, i32>,
    pixels: &mut [Pixel],
    depth: &mut [u16],
    order: &mut [u16],
    pool: &mut BandPool,
    probe: &mut P,
) -> Result<FrameStats, FrameError> {
    // Geometry.
    probe.resume();
    let objects = objects(spec);
    let camera = spec.camera();
    let prepared = match camera {
        Ok(camera) => {
            let scene = spec.scene(camera, &objects);
            prepare::<Fast>(&scene, spec.width, spec.height, ws).map(|f| (scene, f))
        }
        Err(e) => Err(e.into()),
    };
    probe.pause();
    probe.close();
    let (scene, frame) = prepared?;
    let mut stats = prepared_stats(&frame);

    // Raster: the triangle order, then band by band (clear, render).
    let w = spec.width;
    let mut crc = Crc32::new();
    let n = (w * BAND_ROWS) as usize;
    let (Some(px), Some(z)) = (pixels.get_mut(..n), depth.get_mut(..n)) else {
        return Err(BufferError::WrongLength {
            expected: n,
            actual: pixels.len().min(depth.len()),
        }
        .into());
    };
    let mut band = Band::new(px, Some(z), w, BAND_ROWS)?;
    let mut state = BandState::new(order, pool);
    probe.resume();
    let bands = frame.bands(&scene, &mut state, BAND_ROWS);
    probe.pause();
    let mut bands = bands?;
    loop {
        probe.resume();
        let r = bands.next_band(&mut band);
        probe.pause();
        if r?.is_none() {
            break;
        }
        crc.update(band.bytes());
        let z = band.depth().unwrap_or(&[]);
        stats.covered += z.iter().filter(|&&d| d != Depth16::CLEAR).count() as u32;
    }
    stats.setups = bands.stats().triangles;
    stats.active_peak = bands.active_peak() as u32;
    stats.drawn = bands.stats().pixels;
    probe.close();
    stats.crc = crc.finish();
    Ok(stats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use fixshade::render::{Part, Tri};
    use fixshade::target::{DepthBuffer, FrameBuf, Target};
    use std::{vec, vec::Vec};

    struct Owned {
        xy: Vec<[i32; 2]>,
        vals: Vec<i32>,
        tris: Vec<Tri>,
    }

    impl Owned {
        fn new(n: Needs) -> Self {
            Self {
                xy: vec![[0; 2]; n.vertices],
                vals: vec![0; n.values],
                tris: vec![Tri::default(); n.triangles],
            }
        }
        fn ws(&mut self) -> Workspace<'_, i32> {
            Workspace {
                xy: &mut self.xy,
                vals: &mut self.vals,
                tris: &mut self.tris,
            }
        }
    }

    /// Renders a scene into a whole frame at once (no bands): CRC and
    /// covered pixels.
    fn whole_frame(spec: &SceneSpec, ws: Workspace<'_, i32>) -> (u32, u32) {
        let objects = objects(spec);
        let scene = spec.scene(spec.camera().unwrap(), &objects);
        let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws).unwrap();
        let n = (spec.width * spec.height) as usize;
        let mut px = vec![[0u8; 2]; n];
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
        let mut ws = Owned::new(MAX_NEEDS);
        let mut px = vec![[0u8; 2]; BAND_PIXELS];
        let mut z = vec![0u16; BAND_PIXELS];
        let mut order = vec![0u16; 2 * MAX_NEEDS.triangles];
        let mut pool = std::boxed::Box::new(BandPool::new());
        for spec in SCENES.iter() {
            let s = render_frame(
                spec,
                ws.ws(),
                &mut px,
                &mut z,
                &mut order,
                &mut pool,
                &mut NoProbe,
            )
            .unwrap();
            // The pool holds every active triangle: each set up once.
            std::println!("{} active peak {}", spec.name, s.active_peak);
            assert!(s.active_peak as usize <= POOL_SLOTS, "{}", spec.name);
            assert_eq!(s.setups, s.triangles, "{}", spec.name);
            assert_eq!(
                (s.crc, s.covered),
                whole_frame(spec, ws.ws()),
                "{}",
                spec.name
            );
            assert_eq!(s.prepared_bytes as usize, spec.needs.prepared_bytes);
            assert!(s.drawn >= s.covered && s.covered > 5000, "{s:?}");
        }
    }

    #[test]
    fn every_scene_fits_its_needs_and_not_less() {
        for spec in SCENES.iter() {
            let n = spec.needs;
            check(spec, Owned::new(n).ws()).unwrap();
            let short = Needs {
                vertices: n.vertices - 1,
                ..n
            };
            let e = check(spec, Owned::new(short).ws()).unwrap_err();
            assert_eq!(
                e,
                FrameError::Render(RenderError::Capacity {
                    part: Part::Vertices,
                    object: spec.objects.len() - 1
                })
                .clone(),
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
    fn max_needs_cover_every_scene() {
        for spec in SCENES.iter() {
            let (n, m) = (spec.needs, MAX_NEEDS);
            assert!(n.vertices <= m.vertices && n.values <= m.values);
            assert!(n.triangles <= m.triangles);
            assert!(spec.width <= WIDTH && spec.objects.len() <= MAX_OBJECTS);
        }
    }
}
