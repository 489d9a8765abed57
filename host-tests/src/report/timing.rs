//! Host cost: the core's work for one frame, timed over repeated runs.
//!
//! A timed frame is what a firmware does per frame: prepare the scene
//! (transform, project, light the vertices) into a workspace allocated
//! once, then for each band of [`BAND_ROWS`] rows clear the colour band,
//! clear the depth band and rasterize. Building the core's scene from the
//! description, allocating and reading the frame back are outside the
//! timed region: [`render_core`](crate::core_render::render_core) does all
//! of that per call, and its allocation (workspace sized for worst-case
//! clipping) would dominate a sub-millisecond frame.
//!
//! The conversion from [`SceneDesc`] to the core's scene is
//! `core_render`'s own ([`CoreScene`]); [`time_frames`] also checks that
//! the timed frame's bytes are exactly `render_core`'s.

use std::time::{Duration, Instant};

use fixshade::num::{F32Pc, F64Pc, Fast, FastPc, Precise, PrecisePc, Profile, F32, F64};
use fixshade::render::{prepare, Link, RenderError, Tri, Workspace};
use fixshade::target::{
    Depth16, DepthBuffer, FrameBuf, Gray8, PixelFormat as CorePixelFormat, Rgb565Be, Rgb888, Target,
};

use crate::core_render::{CoreError, CoreProfile, CoreScene, BAND_ROWS};
use crate::scene_file::{PixelFormat, SceneDesc};

/// How many times to render a frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Repeats {
    /// At least this many timed runs (after one untimed warm-up run).
    pub min_runs: u32,
    /// ...and keep going until this much time was spent timing...
    pub min_time: Duration,
    /// ...but never more than this many runs.
    pub max_runs: u32,
}

/// The timings of one scene with one profile.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    /// Duration of every timed run, in nanoseconds, sorted.
    pub runs_ns: Vec<u64>,
    /// Pixels written per frame (depth-test passes).
    pub pixels_drawn: u32,
    /// The frame's bytes in the scene's pixel format, for the check
    /// against `render_core`.
    pub bytes: Vec<u8>,
}

impl Timing {
    /// The median run in nanoseconds (the lower middle for an even count).
    pub fn median_ns(&self) -> u64 {
        self.runs_ns
            .get(self.runs_ns.len().saturating_sub(1) / 2)
            .copied()
            .unwrap_or(0)
    }
}

/// Times `desc` rendered with `profile` in its own pixel format.
///
/// # Errors
/// [`CoreError`] when the core refuses the scene.
pub fn time_frames(
    desc: &SceneDesc,
    profile: CoreProfile,
    repeats: Repeats,
) -> Result<Timing, CoreError> {
    match profile {
        CoreProfile::Fast => time_profile::<Fast>(desc, repeats),
        CoreProfile::Precise => time_profile::<Precise>(desc, repeats),
        CoreProfile::F32 => time_profile::<F32>(desc, repeats),
        CoreProfile::F64 => time_profile::<F64>(desc, repeats),
        CoreProfile::FastPc => time_profile::<FastPc>(desc, repeats),
        CoreProfile::PrecisePc => time_profile::<PrecisePc>(desc, repeats),
        CoreProfile::F32Pc => time_profile::<F32Pc>(desc, repeats),
        CoreProfile::F64Pc => time_profile::<F64Pc>(desc, repeats),
    }
}

fn time_profile<P: Profile>(desc: &SceneDesc, repeats: Repeats) -> Result<Timing, CoreError> {
    match desc.pixel_format {
        PixelFormat::Gray8 => time_format::<P, Gray8>(desc, repeats),
        PixelFormat::Rgb565 => time_format::<P, Rgb565Be>(desc, repeats),
        PixelFormat::Rgb888 => time_format::<P, Rgb888>(desc, repeats),
    }
}

fn time_format<P: Profile, F: CorePixelFormat>(
    desc: &SceneDesc,
    repeats: Repeats,
) -> Result<Timing, CoreError> {
    let cs = CoreScene::<P::Real>::new(desc)?;
    let scene = cs.scene();
    // The workspace as `core_render` sizes it, allocated once.
    let (verts, tris, heads) = cs.workspace_sizes();
    let mut xy = vec![[0i32; 2]; verts];
    let mut vals = vec![P::Lerp::default(); verts * 8];
    let mut tri_buf = vec![Tri::default(); tris];
    let mut heads = vec![0u16; heads];
    let mut links = vec![Link::default(); verts];
    let (w, h) = (desc.width, desc.height);
    let mut band = vec![F::Raw::default(); (w * BAND_ROWS) as usize];
    let mut depth = vec![0u16; (w * BAND_ROWS) as usize];

    // One frame; `keep` collects the bytes (outside the timed region).
    let mut frame_once = |keep: Option<&mut Vec<u8>>| -> Result<(Duration, u32), CoreError> {
        let mut keep = keep;
        let mut elapsed = Duration::ZERO;
        let start = Instant::now();
        let ws = Workspace {
            xy: &mut xy,
            vals: &mut vals,
            tris: &mut tri_buf,
            heads: &mut heads,
            links: &mut links,
        };
        let frame = prepare::<P>(&scene, w, h, ws)?;
        let mut pixels = 0;
        let mut y0 = 0;
        let mut lap = start;
        while y0 < h {
            let y1 = (y0 + BAND_ROWS).min(h);
            let n = ((y1 - y0) * w) as usize;
            let mut fb =
                FrameBuf::<F>::band(&mut band[..n], w, y0, y1).map_err(RenderError::from)?;
            fb.clear(scene.background);
            let mut db = DepthBuffer::<Depth16>::new(&mut depth[..n], w, y0, y1)
                .map_err(RenderError::from)?;
            pixels += frame.render(&scene, &mut fb, Some(&mut db))?.pixels;
            if let Some(out) = keep.as_deref_mut() {
                elapsed += lap.elapsed();
                out.extend(fb.bytes());
                lap = Instant::now();
            }
            y0 = y1;
        }
        elapsed += lap.elapsed();
        Ok((elapsed, pixels))
    };

    let mut bytes = Vec::with_capacity((w * h) as usize * F::BYTES);
    let (_, pixels_drawn) = frame_once(Some(&mut bytes))?;
    let mut runs_ns = Vec::new();
    let mut total = Duration::ZERO;
    while runs_ns.len() < repeats.max_runs.max(1) as usize
        && (runs_ns.len() < repeats.min_runs.max(1) as usize || total < repeats.min_time)
    {
        let (t, _) = frame_once(None)?;
        total += t;
        runs_ns.push(u64::try_from(t.as_nanos()).unwrap_or(u64::MAX));
    }
    runs_ns.sort_unstable();
    Ok(Timing {
        runs_ns,
        pixels_drawn,
        bytes,
    })
}

impl Repeats {
    /// The full run: at least 15 runs and 100 ms per record.
    pub const FULL: Self = Self {
        min_runs: 15,
        min_time: Duration::from_millis(100),
        max_runs: 2000,
    };

    /// `--quick`: 3 runs per record.
    pub const QUICK: Self = Self {
        min_runs: 3,
        min_time: Duration::ZERO,
        max_runs: 3,
    };
}
