//! fixshade animation firmware for QEMU's MPS2 boards: a turn of the bunny
//! and of the dodecahedron, measured frame by frame.
//!
//! For each scene of [`ANIMATED`] (the firmware's generated scenes), renders
//! [`FRAMES`] frames of one turn: frame `i` adds `2π·i/FRAMES` (in Q16) to
//! every object's rotation about Y and builds the model transform with
//! `Affine::from_parts` (the core's Q16 `sin_cos`); the camera, lights and
//! meshes stay as they are. Per frame, one measured region (bracketed by
//! `yield`, closed by `sev`, counted by the QEMU plugin in `qemu-plugin/`)
//! holds the geometry (scene, camera, per-frame transform, `prepare`) and
//! the raster (per band of 16 rows: clear colour and depth, render); the
//! CRC-32 of the frame and the covered pixels are taken outside it.
//! Prints one line per frame:
//!
//! ```text
//! frame <scene> i=<i> angle_q16=<bits> crc=0x<crc32> covered=<px> setups=<n> prepared_triangles=<n>
//! ```
//!
//! Before anything is measured, every frame of every scene is prepared once
//! into the static workspace: a frame that does not fit stops the firmware
//! with the core's error and exit status 1 (never a hang). `.ci/firmware`
//! turns the regions into per-frame instructions min / median / max and the
//! frame rates at 48 MHz (M0) and 168 MHz (M4F).
#![no_std]
#![no_main]

#[path = "../qemu.rs"]
mod qemu;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use fixshade::geom::{Affine, Vec3};
use fixshade::num::{Fast, Q16};
use fixshade::render::{prepare, BandState, RenderError};
use fixshade::scene::Object;
use fixshade::target::{Depth16, DepthFormat};
use fixshade_scenes::{
    Band, BandPool, Crc32, FrameError, Pixel, SceneSpec, SceneStorage, BAND_PIXELS, BAND_ROWS,
    CAPACITY, MAX_OBJECTS, SCENES,
};

/// The animated scenes (names of [`SCENES`]).
const ANIMATED: [&str; 2] = ["bunny-gouraud", "dodeca-gouraud-n100"];

/// Frames per turn: 15° apart.
const FRAMES: u32 = 24;

/// 2π in Q16.16, rounded: 411 775 / 65 536 = 6.283 188 (2π = 6.283 185).
const TAU_Q16: i64 = 411_775;

/// The rotation added in frame `i`: `round(2π·i/FRAMES)` in Q16.
const fn angle(i: u32) -> Q16 {
    Q16::from_bits(((TAU_Q16 * i as i64 + FRAMES as i64 / 2) / FRAMES as i64) as i32)
}

/// The storage: the benchmark firmware's, the core's bound for the
/// scenes' meshes in `fast` (every mesh vertex and triangle), whatever a turn shows
/// (the start-up check proves each frame fits).
const CAP: fixshade::render::Capacity = CAPACITY.in_profile::<Fast>();

/// Executes `yield`, the plugin's marker (see the benchmark firmware).
#[inline(always)]
fn yield_marker() {
    // SAFETY: `yield` is an architectural hint with no effect on registers,
    // memory or flags; as an asm block it is also a compiler barrier.
    unsafe { core::arch::asm!("yield", options(nostack, preserves_flags)) }
}

struct Memory {
    pixels: &'static mut [Pixel; BAND_PIXELS],
    depth: &'static mut [u16; BAND_PIXELS],
    storage: &'static mut SceneStorage,
    pool: &'static mut BandPool,
}

/// The objects of `spec` turned by `a` more about Y.
fn turned(spec: &SceneSpec, a: Q16) -> heapless::Vec<Object<'static, Q16>, MAX_OBJECTS> {
    spec.objects
        .iter()
        .map(|o| {
            let r = o.rotation;
            Object {
                transform: Affine::from_parts(o.scale, Vec3::new(r.x, r.y + a, r.z), o.translation),
                ..o.object()
            }
        })
        .collect()
}

/// What a frame gave.
struct Stats {
    crc: u32,
    covered: u32,
    setups: u32,
    triangles: u32,
}

/// Renders frame `i` of `spec`; with `measure`, executes the markers
/// around the measured work and closes the region.
fn frame(spec: &SceneSpec, i: u32, mem: &mut Memory, measure: bool) -> Result<Stats, FrameError> {
    let mark = |on: bool| {
        if on {
            yield_marker()
        }
    };
    mark(measure);
    let objects = turned(spec, angle(i));
    let (ws, order) = mem.storage.split();
    let prepared = match spec.camera() {
        Ok(camera) => {
            let scene = spec.scene(camera, &objects);
            prepare::<Fast>(&scene, spec.width, spec.height, ws).map(|f| (scene, f))
        }
        Err(e) => Err(RenderError::from(e)),
    };
    mark(measure);
    let (scene, frame) = match prepared {
        Ok(p) => p,
        Err(e) => {
            if measure {
                cortex_m::asm::sev();
            }
            return Err(e.into());
        }
    };
    let mut stats = Stats {
        crc: 0,
        covered: 0,
        setups: 0,
        triangles: frame.triangle_count() as u32,
    };
    let w = spec.width;
    let mut crc = Crc32::new();
    // A band buffer holds exactly `w × BAND_ROWS` pixels (scenes narrower
    // than the buffers use a part).
    let n = (w * BAND_ROWS) as usize;
    let (Some(px), Some(z)) = (mem.pixels.get_mut(..n), mem.depth.get_mut(..n)) else {
        return Err(fixshade::target::BufferError::WrongLength {
            expected: n,
            actual: BAND_PIXELS,
        }
        .into());
    };
    let mut band = Band::new(px, Some(z), w, BAND_ROWS)?;
    let mut state = BandState::new(order, mem.pool);
    mark(measure);
    let bands = frame.bands(&scene, &mut state, BAND_ROWS);
    mark(measure);
    let mut bands = bands?;
    loop {
        mark(measure);
        let r = bands.next_band(&mut band);
        mark(measure);
        if r?.is_none() {
            break;
        }
        crc.update(band.bytes());
        let z = band.depth().unwrap_or(&[]);
        stats.covered += z.iter().filter(|&&d| d != Depth16::CLEAR).count() as u32;
    }
    stats.setups = bands.stats().triangles;
    if measure {
        cortex_m::asm::sev();
    }
    stats.crc = crc.finish();
    Ok(stats)
}

fn run(mem: &mut Memory) -> Result<(), (&'static str, u32, FrameError)> {
    hprintln!(
        "fixshade-animate target={} board={} profile=fast frames_per_turn={} band_rows={} depth16 ws_triangles={}",
        env!("FW_TARGET"),
        env!("FW_BOARD"),
        FRAMES,
        BAND_ROWS,
        CAP.triangles,
    );
    let specs = ANIMATED.map(|name| SCENES.iter().find(|s| s.name == name));
    // Start-up check: every frame of the turn fits the workspace.
    for (name, spec) in ANIMATED.iter().zip(specs) {
        let Some(spec) = spec else {
            return Err((name, 0, FrameError::Render(RenderError::Window)));
        };
        for i in 0..FRAMES {
            let objects = turned(spec, angle(i));
            let camera = spec.camera().map_err(|e| (spec.name, i, e.into()))?;
            let scene = spec.scene(camera, &objects);
            prepare::<Fast>(&scene, spec.width, spec.height, mem.storage.workspace())
                .map_err(|e| (spec.name, i, e.into()))?;
        }
    }
    for spec in specs.into_iter().flatten() {
        for i in 0..FRAMES {
            let s = frame(spec, i, mem, true).map_err(|e| (spec.name, i, e))?;
            hprintln!(
                "frame {} i={} angle_q16={} crc=0x{:08x} covered={} setups={} prepared_triangles={}",
                spec.name,
                i,
                angle(i).to_bits(),
                s.crc,
                s.covered,
                s.setups,
                s.triangles,
            );
        }
    }
    Ok(())
}

#[entry]
fn main() -> ! {
    static mut PIXELS: [Pixel; BAND_PIXELS] = [0; BAND_PIXELS];
    static mut DEPTH: [u16; BAND_PIXELS] = [0; BAND_PIXELS];
    static mut STORAGE: SceneStorage = SceneStorage::EMPTY;
    static mut POOL: BandPool = BandPool::new();
    let mut mem = Memory {
        pixels: PIXELS,
        depth: DEPTH,
        storage: STORAGE,
        pool: POOL,
    };
    let status = match run(&mut mem) {
        Ok(()) => debug::EXIT_SUCCESS,
        Err((name, i, e)) => {
            hprintln!(
                "error: scene {} frame {} does not fit the animation's workspace (capacities: {} vertices, {} values, {} triangles): {}",
                name,
                i,
                CAP.vertices,
                CAP.values,
                CAP.triangles,
                e
            );
            debug::EXIT_FAILURE
        }
    };
    qemu::exit(status)
}
