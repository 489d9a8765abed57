//! The firmware's benchmark scenes and frame loop, shared by the firmware
//! (`thumbv6m-none-eabi`, `thumbv7em-none-eabihf`) and by `host-check`,
//! which renders the same scenes on the host so that the three CRCs can be
//! compared.
//!
//! A frame is 240×240 RGB565 (big-endian, as SPI displays take it),
//! rendered in 15 bands of 16 rows with a band-sized 16-bit depth buffer:
//! 7 680 + 7 680 bytes of RAM. Per band: move both buffers (clearing the
//! depth), clear the colour, draw the scene (triangles that miss the band
//! are skipped by a bounding-row test before setup). That is the measured
//! work; the CRC-32 of the band's bytes and the count of covered pixels
//! (depth values no longer clear) are taken outside it.
//!
//! Scenes are a table ([`SCENES`]) of plain functions that draw into one
//! band, so that the core's 3D scenes can replace them later.
#![no_std]
#![forbid(unsafe_code)]
#![deny(missing_docs)]

#[cfg(test)]
extern crate std;

mod crc;
mod fan;
mod grid;

pub use crc::Crc32;

use core::fmt;
use fixshade::raster::{RasterError, SubpixelBits, Vertex};
use fixshade::target::{
    BufferError, Depth16, DepthBuffer, DepthFormat, FrameBuf, Rgb565Be, Rgb8, Target, Window,
};

/// Frame width in pixels.
pub const WIDTH: u32 = 240;
/// Frame height in pixels.
pub const HEIGHT: u32 = 240;
/// Rows per band.
pub const BAND_ROWS: u32 = 16;
/// Pixels (and depth values) per band: 3 840.
pub const BAND_PIXELS: usize = (WIDTH * BAND_ROWS) as usize;
/// Background colour (black, as in the bunny benchmark).
pub const BACKGROUND: Rgb8 = Rgb8::BLACK;
/// Subpixel precision of every scene: 1/16 pixel.
pub const SUB: SubpixelBits = SubpixelBits::DEFAULT;

/// One stored pixel: RGB565, big-endian.
pub type Pixel = [u8; 2];
/// A band of the frame.
pub type Band<'a> = FrameBuf<'a, Rgb565Be>;
/// The band's depth buffer.
pub type BandDepth<'a> = DepthBuffer<'a, Depth16>;
/// Draws a scene into one band (colour cleared, depth cleared).
pub type DrawFn = fn(&mut Band<'_>, &mut BandDepth<'_>) -> Result<(), RasterError>;

/// A benchmark scene.
#[derive(Clone, Copy, Debug)]
pub struct Scene {
    /// Short name, printed by the firmware and the host check.
    pub name: &'static str,
    /// Triangles submitted per frame (before band culling).
    pub triangles: u32,
    /// Draws the scene into a band.
    pub draw: DrawFn,
}

/// Every scene, in the order the firmware runs them.
pub static SCENES: [Scene; 4] = [
    Scene {
        name: "fan-gouraud",
        triangles: fan::TRIANGLES as u32,
        draw: fan::draw_gouraud,
    },
    Scene {
        name: "fan-flat",
        triangles: fan::TRIANGLES as u32,
        draw: fan::draw_flat,
    },
    Scene {
        name: "grid-gouraud",
        triangles: grid::TRIANGLES as u32,
        draw: grid::draw_gouraud,
    },
    Scene {
        name: "grid-flat",
        triangles: grid::TRIANGLES as u32,
        draw: grid::draw_flat,
    },
];

/// Marks the measured work of a frame: the firmware executes a marker
/// instruction in both methods, which the instruction-counting QEMU plugin
/// toggles counting on; the host does nothing.
pub trait Probe {
    /// Counting on: the band's work starts.
    fn resume(&mut self);
    /// Counting off: the band's work ended.
    fn pause(&mut self);
}

/// A probe that does nothing.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoProbe;

impl Probe for NoProbe {
    fn resume(&mut self) {}
    fn pause(&mut self) {}
}

/// What a frame produced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FrameStats {
    /// CRC-32 of the frame's bytes, row-major, top to bottom.
    pub crc: u32,
    /// Pixels covered by at least one fragment (depth no longer clear).
    pub covered: u32,
}

/// Why a frame failed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameError {
    /// A band buffer was refused.
    Buffer(BufferError),
    /// A triangle was refused.
    Raster(RasterError),
}

impl From<BufferError> for FrameError {
    fn from(e: BufferError) -> Self {
        Self::Buffer(e)
    }
}

impl From<RasterError> for FrameError {
    fn from(e: RasterError) -> Self {
        Self::Raster(e)
    }
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Buffer(e) => write!(f, "band buffer: {e}"),
            Self::Raster(e) => write!(f, "raster: {e}"),
        }
    }
}

impl core::error::Error for FrameError {}

/// Renders one frame of `scene` band by band into the given band memory
/// (`BAND_PIXELS` pixels and depth values), calling `probe` around the
/// work of each band.
///
/// # Errors
/// [`FrameError`] when a buffer has the wrong length or a triangle is
/// refused.
pub fn render_frame<P: Probe>(
    scene: &Scene,
    pixels: &mut [Pixel],
    depth: &mut [u16],
    probe: &mut P,
) -> Result<FrameStats, FrameError> {
    let mut fb = Band::band(pixels, WIDTH, 0, BAND_ROWS)?;
    let mut db = BandDepth::new(depth, WIDTH, 0, BAND_ROWS)?;
    let mut crc = Crc32::new();
    let mut covered = 0u32;
    let mut y0 = 0;
    while y0 < HEIGHT {
        probe.resume();
        let r = draw_band(scene, &mut fb, &mut db, y0);
        probe.pause();
        r?;
        crc.update(fb.bytes());
        covered += count_covered(&mut db);
        y0 += BAND_ROWS;
    }
    Ok(FrameStats {
        crc: crc.finish(),
        covered,
    })
}

/// The measured work of one band.
#[inline(always)]
fn draw_band(
    scene: &Scene,
    fb: &mut Band<'_>,
    db: &mut BandDepth<'_>,
    y0: u32,
) -> Result<(), FrameError> {
    fb.move_to(y0)?;
    db.move_to(y0)?;
    fb.clear(BACKGROUND);
    (scene.draw)(fb, db)?;
    Ok(())
}

/// Depth values of the window that are no longer clear.
fn count_covered(db: &mut BandDepth<'_>) -> u32 {
    let w = db.window();
    let mut n = 0;
    for y in w.y0..w.y1 {
        if let Some(row) = db.row_mut(y) {
            n += row.iter().filter(|&&d| d != Depth16::CLEAR).count() as u32;
        }
    }
    n
}

/// Whether a triangle can cover a pixel centre in the window's rows
/// (conservative: compares its vertical extent, in subpixels, with the
/// rows' extent), so that triangles outside a band skip setup.
#[inline(always)]
pub fn meets_rows<const N: usize>(tri: &[Vertex<i32, N>; 3], w: Window) -> bool {
    let s = SUB.get();
    let (a, b, c) = (tri[0].y, tri[1].y, tri[2].y);
    let top = a.min(b).min(c);
    let bottom = a.max(b).max(c);
    bottom >= (w.y0 as i32) << s && top < (w.y1 as i32) << s
}

/// The level `l` (0..=255) as a fixed-point attribute (`l · 2^16`).
const fn level(l: i32) -> i32 {
    l << 16
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::vec;

    /// Renders a scene into a whole frame at once (no bands).
    fn whole_frame(scene: &Scene) -> (u32, u32) {
        let n = (WIDTH * HEIGHT) as usize;
        let mut px = vec![[0u8; 2]; n];
        let mut z = vec![0u16; n];
        let mut fb = Band::new(&mut px, WIDTH, HEIGHT).unwrap();
        fb.clear(BACKGROUND);
        let mut db = BandDepth::new(&mut z, WIDTH, 0, HEIGHT).unwrap();
        (scene.draw)(&mut fb, &mut db).unwrap();
        let mut crc = Crc32::new();
        crc.update(fb.bytes());
        (crc.finish(), count_covered(&mut db))
    }

    #[test]
    fn bands_equal_the_whole_frame() {
        let mut px = [[0u8; 2]; BAND_PIXELS];
        let mut z = [0u16; BAND_PIXELS];
        for scene in SCENES.iter() {
            let banded = render_frame(scene, &mut px, &mut z, &mut NoProbe).unwrap();
            let (crc, covered) = whole_frame(scene);
            assert_eq!(banded.crc, crc, "{}", scene.name);
            assert_eq!(banded.covered, covered, "{}", scene.name);
        }
    }

    #[test]
    fn scenes_cover_what_they_should() {
        let mut px = [[0u8; 2]; BAND_PIXELS];
        let mut z = [0u16; BAND_PIXELS];
        for scene in SCENES.iter() {
            let s = render_frame(scene, &mut px, &mut z, &mut NoProbe).unwrap();
            let frame = WIDTH * HEIGHT;
            assert!(
                s.covered > frame / 10 && s.covered < frame,
                "{scene:?} {s:?}"
            );
        }
        // The grid approximates the bunny's ~14 500 covered pixels.
        let g = render_frame(&SCENES[2], &mut px, &mut z, &mut NoProbe).unwrap();
        assert!((13_500..15_500).contains(&g.covered), "{g:?}");
    }

    #[test]
    fn culling_by_rows_is_conservative() {
        // A triangle that fails the row test draws nothing into that band.
        use fixshade::raster::{Fill, GouraudMono};
        let mut px = [[0u8; 2]; BAND_PIXELS];
        let mut z = [0u16; BAND_PIXELS];
        let mut skipped = 0;
        let fan = fan::FAN.iter().map(|t| {
            t.map(|v| Vertex {
                x: v.x,
                y: v.y,
                z: v.z,
                attrs: [v.attrs[0]],
            })
        });
        for tri in fan.chain(grid::all()) {
            for y0 in (0..HEIGHT).step_by(BAND_ROWS as usize) {
                let mut fb = Band::band(&mut px, WIDTH, y0, y0 + BAND_ROWS).unwrap();
                let mut db = BandDepth::new(&mut z, WIDTH, y0, y0 + BAND_ROWS).unwrap();
                if meets_rows(&tri, fb.window()) {
                    continue;
                }
                skipped += 1;
                Fill::new(&mut fb, Some(&mut db), GouraudMono)
                    .unwrap()
                    .draw(&tri, SUB)
                    .unwrap();
                assert_eq!(count_covered(&mut db), 0, "{tri:?} at {y0}");
            }
        }
        assert!(skipped > 20_000);
    }
}
