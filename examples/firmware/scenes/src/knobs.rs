//! The knobs a user trades, on one scene: band rows, 16- or 32-bit depth,
//! subpixel bits (the firmware's `knobs` build and host-check `--knobs`).
//!
//! [`render_frame_knobs`] is [`crate::profiled::render_frame_with`] with
//! the band height and the depth format as parameters; [`FastSub`] (the
//! core's) is the `Fast` profile with another subpixel precision (every
//! other quantity as `Fast`'s).

use crate::profiled::{depth_in, raster_bands_in, ProfilePool};
use crate::{FrameError, FrameStats, Pixel, Probe, SceneSpec, WIDTH};
pub use fixshade::num::FastSub;
use fixshade::num::Profile;
use fixshade::render::{prepare_in, Frame, RenderError, Workspace};
use fixshade::scene::Scene;
use fixshade::target::DepthFormat;

/// The scene the knobs are measured on.
pub const KNOB_SCENE: &str = "bunny-gouraud";
/// Band heights measured (16 is the default).
pub const BAND_ROWS_SWEEP: [u32; 6] = [4, 8, 16, 32, 80, 240];
/// Subpixel bits measured (4 is the default, 1/16 pixel).
pub const SUBPIXEL_SWEEP: [u32; 5] = [2, 3, 4, 6, 8];
/// Most rows of a band: pixels (and depth values) of the largest band.
pub const MAX_BAND_PIXELS: usize = (WIDTH * 240) as usize;
/// A frame with the profile `P` in bands of `rows` rows with the depth
/// format `D` (`pixels` and `depth` hold at least `width × rows`; no depth
/// band with `None`): [`crate::profiled::render_frame_with`] is this with
/// 16-bit depth in bands of [`crate::BAND_ROWS`] rows.
///
/// # Errors
/// As [`crate::render_frame`].
#[allow(clippy::too_many_arguments)]
pub fn render_frame_knobs<P: Profile, D: DepthFormat, Q: Probe>(
    spec: &SceneSpec,
    ws: Workspace<'_, P::Lerp>,
    pixels: &mut [Pixel],
    depth: Option<&mut [D::Raw]>,
    rows: u32,
    order: &mut [u16],
    pool: &mut ProfilePool<P>,
    probe: &mut Q,
) -> Result<FrameStats, FrameError> {
    let (depth, with_depth) = depth_in(depth);
    render_frame_knobs_in::<P, D, Q>(
        spec, ws, pixels, depth, with_depth, rows, order, pool, probe,
    )
}

/// [`render_frame_knobs`] with the depth band as a slice and whether to
/// use it (see [`crate::render_frame_in`]).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn render_frame_knobs_in<P: Profile, D: DepthFormat, Q: Probe>(
    spec: &SceneSpec,
    ws: Workspace<'_, P::Lerp>,
    pixels: &mut [Pixel],
    depth: &mut [D::Raw],
    with_depth: bool,
    rows: u32,
    order: &mut [u16],
    pool: &mut ProfilePool<P>,
    probe: &mut Q,
) -> Result<FrameStats, FrameError> {
    let rows = rows.max(1);
    // Geometry.
    probe.resume();
    let parts = crate::profiled::Parts::<P::Real>::new(spec);
    // The scene and the frame stay where they are made (borrowed below,
    // never moved; the frame made in place by `prepare_in`): each move of a large value can take a stack slot of
    // its own in this frame, which the whole render stands on.
    let scene = match &parts.camera {
        Ok(c) => parts.scene(spec, *c),
        Err(e) => {
            probe.pause();
            probe.close();
            return Err((*e).into());
        }
    };
    let mut frame = None;
    let prepared = prepare_frame::<P>(&scene, spec, ws, &mut frame);
    probe.pause();
    probe.close();
    prepared?;
    match &frame {
        Some(frame) => raster_bands_in::<P, D, Q>(
            frame, &scene, pixels, depth, with_depth, rows, order, pool, probe,
        ),
        // (`prepare_in` leaves a frame after `Ok`.)
        None => Err(RenderError::Window.into()),
    }
}

/// [`prepare_in`] of `scene` at `spec`'s size into `frame`. Not inlined:
/// its locals (the eye-space lights, the preparer) then take a stack
/// frame only while the geometry runs, not under the bands.
#[inline(never)]
fn prepare_frame<'w, 's: 'w, 'm: 'w, P: Profile>(
    scene: &Scene<'s, 'm, P::Real>,
    spec: &SceneSpec,
    ws: Workspace<'w, P::Lerp>,
    frame: &mut Option<Frame<'w, P>>,
) -> Result<(), RenderError> {
    prepare_in::<P>(scene, spec.width, spec.height, ws, frame)
}

// The knob scene (the bunny) is not in the `dodeca` build.
#[cfg(all(test, not(feature = "dodeca")))]
mod tests {
    use super::*;
    use crate::{NoProbe, POOL_SLOTS, SCENES};
    use fixshade::num::Fast;
    use fixshade::target::Depth16;
    use std::{boxed::Box, vec};

    /// Every band height gives the same frame, and with the active
    /// triangle list every prepared triangle is set up once when the
    /// pool's slots hold the triangles kept across a border; the bunny
    /// may keep more than the firmware's slots in some band heights, so
    /// some are set up again (the pool's fallback: same bytes).
    #[test]
    fn every_band_height_renders_the_same_frame_with_one_setup_per_triangle() {
        let spec = SCENES.iter().find(|s| s.name == KNOB_SCENE).unwrap();
        // The core's bound holds for every subpixel precision: finer
        // subpixels keep more thin triangles, never more than the mesh's.
        let mut st = Box::new(crate::SceneStorage::new());
        let mut px = vec![0u16; MAX_BAND_PIXELS];
        let mut z = vec![0u16; MAX_BAND_PIXELS];
        let mut pool = Box::new(ProfilePool::<Fast>::new());
        let mut last: Option<FrameStats> = None;
        for rows in BAND_ROWS_SWEEP {
            let (ws, order) = st.split();
            let s = render_frame_knobs::<Fast, Depth16, _>(
                spec,
                ws,
                &mut px,
                Some(&mut z),
                rows,
                order,
                &mut pool,
                &mut NoProbe,
            )
            .unwrap();
            // Once each while the pool holds every triangle carried across
            // a border (the whole frame as one band at least); else the
            // ones that found it full are set up again in the next band.
            if s.active_peak as usize <= POOL_SLOTS || rows == 240 {
                assert_eq!(s.setups, s.triangles, "{rows} rows");
            } else {
                assert!(s.setups > s.triangles, "{rows} rows");
            }
            if let Some(l) = last {
                assert_eq!(
                    (s.crc, s.covered, s.drawn),
                    (l.crc, l.covered, l.drawn),
                    "{rows}"
                );
            }
            last = Some(s);
        }
    }
}
