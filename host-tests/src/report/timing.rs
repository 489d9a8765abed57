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
//! The scene conversion and the banded frame are `core_render`'s own
//! ([`CoreScene`], [`Renderer`]), so the timed frame is byte for byte the
//! one `render_core` renders (checked by the report's tests).

use std::time::{Duration, Instant};

use fixshade::num::Profile;
use fixshade::target::PixelFormat as CorePixelFormat;

use crate::core_render::{dispatch_fn, CoreError, CoreProfile, CoreScene, Renderer, BAND_ROWS};
use crate::scene_file::SceneDesc;

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
    dispatch_fn!(profile, desc.pixel_format, time_format(desc: &SceneDesc, repeats: Repeats) -> Result<Timing, CoreError>)
}

fn time_format<P: Profile, F: CorePixelFormat>(
    desc: &SceneDesc,
    repeats: Repeats,
) -> Result<Timing, CoreError> {
    let cs = CoreScene::<P::Real>::new(desc)?;
    let scene = cs.scene();
    let mut r = Renderer::<P, F>::new(&cs, desc.width, desc.height, BAND_ROWS);

    // The bytes of one frame, kept once (untimed) for the check.
    let mut bytes = Vec::with_capacity((desc.width * desc.height) as usize * F::BYTES);
    let pixels_drawn = r.frame(&scene, |b| bytes.extend(b.bytes()))?.pixels;
    let mut runs_ns = Vec::new();
    let mut total = Duration::ZERO;
    while runs_ns.len() < repeats.max_runs.max(1) as usize
        && (runs_ns.len() < repeats.min_runs.max(1) as usize || total < repeats.min_time)
    {
        let start = Instant::now();
        r.frame(&scene, |_| {})?;
        let t = start.elapsed();
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
