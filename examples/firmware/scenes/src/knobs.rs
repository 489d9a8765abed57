//! The knobs a user trades, on one scene: band rows, 16- or 32-bit depth,
//! subpixel bits (the firmware's `knobs` build and host-check `--knobs`).
//!
//! [`render_frame_knobs`] is [`crate::profiled::render_frame_with`] with
//! the band height and the depth format as parameters; [`FastSub`] is the
//! `Fast` profile with another subpixel precision (every other quantity as
//! `Fast`'s).

use crate::{
    Band, Crc32, FrameError, FrameStats, Needs, Pixel, Probe, SceneSpec, MAX_NEEDS, WIDTH,
};
use fixshade::num::{Fast, Profile, Q16};
use fixshade::raster::SubpixelBits;
use fixshade::render::{prepare, Workspace};
use fixshade::target::{BufferError, DepthBuffer, DepthFormat, Target};

/// The scene the knobs are measured on.
pub const KNOB_SCENE: &str = "bunny-gouraud";
/// Band heights measured (16 is the default).
pub const BAND_ROWS_SWEEP: [u32; 6] = [4, 8, 16, 32, 80, 240];
/// Subpixel bits measured (4 is the default, 1/16 pixel).
pub const SUBPIXEL_SWEEP: [u32; 5] = [2, 3, 4, 6, 8];
/// Most rows of a band: pixels (and depth values) of the largest band.
pub const MAX_BAND_PIXELS: usize = (WIDTH * 240) as usize;
/// The workspace for the knobs' scene: twice `Fast`'s at 4 subpixel
/// bits, since finer subpixels keep more thin triangles (the bunny at 6
/// bits needs more than the 1 498 prepared at 4).
pub const KNOB_NEEDS: Needs = Needs {
    vertices: 2 * MAX_NEEDS.vertices,
    values: 2 * MAX_NEEDS.values,
    triangles: 2 * MAX_NEEDS.triangles,
    heads: MAX_NEEDS.heads,
    prepared_bytes: 0,
};

/// `Fast` with `B` subpixel bits.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FastSub<const B: u32>;

impl<const B: u32> Profile for FastSub<B> {
    type Real = Q16;
    type Lerp = i32;
    const NAME: &'static str = "fast";
    const SUBPIXEL_BITS: SubpixelBits = match SubpixelBits::new(B) {
        Ok(b) => b,
        Err(_) => panic!("subpixel bits out of range"),
    };
    fn level(r: Q16) -> i32 {
        Fast::level(r)
    }
    fn depth(r: Q16) -> i32 {
        Fast::depth(r)
    }
    fn unit(r: Q16) -> i32 {
        Fast::unit(r)
    }
    fn unit_back(l: i32) -> Q16 {
        Fast::unit_back(l)
    }
    fn coord(r: Q16) -> i32 {
        Fast::coord(r)
    }
    fn coord_back(l: i32) -> Q16 {
        Fast::coord_back(l)
    }
}

/// [`crate::profiled::render_frame_with`] in bands of `rows` rows with the
/// depth format `D` (`pixels` and `depth` hold at least `width × rows`).
///
/// # Errors
/// As [`crate::render_frame`].
pub fn render_frame_knobs<P: Profile, D: DepthFormat, Q: Probe>(
    spec: &SceneSpec,
    ws: Workspace<'_, P::Lerp>,
    pixels: &mut [Pixel],
    depth: &mut [D::Raw],
    rows: u32,
    probe: &mut Q,
) -> Result<FrameStats, FrameError> {
    let rows = rows.max(1);
    // Geometry, as `render_frame_with`.
    probe.resume();
    let parts = crate::profiled::Parts::<P::Real>::new(spec);
    let prepared = match parts.camera {
        Ok(camera) => {
            let scene = parts.scene(spec, camera);
            prepare::<P>(&scene, spec.width, spec.height, ws).map(|f| (scene, f))
        }
        Err(e) => Err(e.into()),
    };
    probe.pause();
    probe.close();
    let (scene, frame) = prepared?;
    let mut stats = FrameStats {
        vertices: frame.vertex_count() as u32,
        triangles: frame.triangle_count() as u32,
        prepared_bytes: frame.bytes_used() as u32,
        ..FrameStats::default()
    };
    let (w, h) = (spec.width, spec.height);
    let mut crc = Crc32::new();
    let mut y0 = 0;
    while y0 < h {
        let y1 = (y0 + rows).min(h);
        let n = ((y1 - y0) * w) as usize;
        let (Some(px), Some(z)) = (pixels.get_mut(..n), depth.get_mut(..n)) else {
            return Err(BufferError::WrongLength {
                expected: n,
                actual: pixels.len().min(depth.len()),
            }
            .into());
        };
        probe.resume();
        let r = (|| {
            let mut fb = Band::band(px, w, y0, y1)?;
            fb.clear(scene.background);
            let mut db = DepthBuffer::<D>::new(z, w, y0, y1)?;
            Ok::<_, FrameError>(frame.render(&scene, &mut fb, Some(&mut db))?)
        })();
        probe.pause();
        let s = r?;
        stats.setups += s.triangles;
        stats.drawn += s.pixels;
        let fb = Band::band(px, w, y0, y1)?;
        crc.update(fb.bytes());
        stats.covered += z.iter().filter(|&&d| d != D::CLEAR).count() as u32;
        y0 = y1;
    }
    probe.close();
    stats.crc = crc.finish();
    Ok(stats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{NoProbe, SCENES};
    use fixshade::render::{Link, Tri};
    use fixshade::target::Depth16;
    use std::vec;

    #[test]
    fn every_band_height_renders_the_same_frame_with_fewer_setups_per_taller_band() {
        let spec = SCENES.iter().find(|s| s.name == KNOB_SCENE).unwrap();
        let n = KNOB_NEEDS;
        let (mut xy, mut vals, mut tris, mut heads, mut links) = (
            vec![[0i32; 2]; n.vertices],
            vec![0i32; n.values],
            vec![Tri::default(); n.triangles],
            vec![0u16; n.heads],
            vec![Link::default(); n.vertices],
        );
        let mut px = vec![[0u8; 2]; MAX_BAND_PIXELS];
        let mut z = vec![0u16; MAX_BAND_PIXELS];
        let mut last: Option<FrameStats> = None;
        for rows in BAND_ROWS_SWEEP {
            let ws = Workspace {
                xy: &mut xy,
                vals: &mut vals,
                tris: &mut tris,
                heads: &mut heads,
                links: &mut links,
            };
            let s = render_frame_knobs::<Fast, Depth16, _>(
                spec,
                ws,
                &mut px,
                &mut z,
                rows,
                &mut NoProbe,
            )
            .unwrap();
            if let Some(l) = last {
                assert_eq!(
                    (s.crc, s.covered, s.drawn),
                    (l.crc, l.covered, l.drawn),
                    "{rows}"
                );
                assert!(s.setups < l.setups, "{rows}: {} setups", s.setups);
            }
            last = Some(s);
        }
        // One band: every prepared triangle set up once.
        let l = last.unwrap();
        assert_eq!(l.setups, l.triangles);
    }
}
