//! The firmware built with a `profile-*` feature: every scene rendered
//! with that core profile instead of `Fast`, for the per-profile chip
//! costs (`fixshade measure-firmware`, `.ci/firmware`).
//!
//! Same output as the default build (header, `capacity`, one `scene`
//! line each; no span-loop lines), same two measured regions per scene
//! (geometry, bands), the scenes widened exactly from their Q16 data
//! (`fixshade_scenes::profiled`). The workspace is sized for the profile
//! (`needs_for`: one more value per vertex in the `-pc` profiles) and its
//! values are the profile's `Lerp` (4 bytes, or 8 for `f64`).

use core::mem::MaybeUninit;
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use fixshade::num::Profile;
use fixshade::render::{Tri, Workspace};
use fixshade_scenes::profiled::{check_with, needs_for, render_frame_with, ProfilePool};
use fixshade_scenes::{Needs, Pixel, BAND_PIXELS, BAND_ROWS, MAX_NEEDS, SCENES, WIDTH};

#[cfg(feature = "profile-precise")]
type P = fixshade::num::Precise;
#[cfg(feature = "profile-f32")]
type P = fixshade::num::F32;
#[cfg(feature = "profile-f64")]
type P = fixshade::num::F64;
#[cfg(feature = "profile-fast-pc")]
type P = fixshade::num::FastPc;
#[cfg(feature = "profile-precise-pc")]
type P = fixshade::num::PrecisePc;
#[cfg(feature = "profile-f32-pc")]
type P = fixshade::num::F32Pc;
#[cfg(feature = "profile-f64-pc")]
type P = fixshade::num::F64Pc;

/// The interpolated values' type.
type L = <P as Profile>::Lerp;

/// The workspace's capacities for the profile.
const CAP: Needs = needs_for::<P>(MAX_NEEDS);

/// `MaybeUninit` array storage filled with `f()`.
fn fill<T, const N: usize>(
    s: &'static mut MaybeUninit<[T; N]>,
    f: impl Fn() -> T,
) -> &'static mut [T; N] {
    let p = s.as_mut_ptr().cast::<T>();
    for i in 0..N {
        // SAFETY: `i < N`, within the array; writing into uninitialised
        // memory through a raw pointer is sound.
        unsafe { p.add(i).write(f()) };
    }
    // SAFETY: every element was initialised above.
    unsafe { s.assume_init_mut() }
}

#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` (the entry runs once).
    static mut PIXELS: [Pixel; BAND_PIXELS] = [[0; 2]; BAND_PIXELS];
    static mut DEPTH: [u16; BAND_PIXELS] = [0; BAND_PIXELS];
    static mut XY: [[i32; 2]; CAP.vertices] = [[0; 2]; CAP.vertices];
    static mut VALS: MaybeUninit<[L; CAP.values]> = MaybeUninit::uninit();
    static mut TRIS: [Tri; CAP.triangles] = [Tri::EMPTY; CAP.triangles];
    static mut ORDER: [u16; 2 * CAP.triangles] = [0; 2 * CAP.triangles];
    static mut POOL: ProfilePool<P> = ProfilePool::<P>::new();
    let vals = fill(VALS, L::default);
    let status = match run(PIXELS, DEPTH, XY, vals, TRIS, ORDER, POOL) {
        Ok(()) => debug::EXIT_SUCCESS,
        Err((name, e)) => {
            hprintln!("error: scene {}: {}", name, e);
            debug::EXIT_FAILURE
        }
    };
    debug::exit(status);
    loop {
        cortex_m::asm::wfi();
    }
}

#[allow(clippy::too_many_arguments)]
fn run(
    pixels: &mut [Pixel; BAND_PIXELS],
    depth: &mut [u16; BAND_PIXELS],
    xy: &mut [[i32; 2]; CAP.vertices],
    vals: &mut [L; CAP.values],
    tris: &mut [Tri; CAP.triangles],
    order: &mut [u16; 2 * CAP.triangles],
    pool: &mut ProfilePool<P>,
) -> Result<(), (&'static str, fixshade_scenes::FrameError)> {
    let workspace_bytes =
        core::mem::size_of_val(xy) + core::mem::size_of_val(vals) + core::mem::size_of_val(tris);
    hprintln!(
        "fixshade-firmware target={} board={} profile={} max_frame={}x{} rgb565be band_rows={} depth16",
        env!("FW_TARGET"),
        env!("FW_BOARD"),
        P::NAME,
        WIDTH,
        WIDTH,
        BAND_ROWS,
    );
    hprintln!(
        "capacity band_bytes={} depth_bytes={} ws_vertices={} ws_values={} ws_triangles={} workspace_bytes={} mesh_shape_bytes={} mesh_normal_bytes={} static_ram={}",
        core::mem::size_of_val(pixels),
        core::mem::size_of_val(depth),
        CAP.vertices,
        CAP.values,
        CAP.triangles,
        workspace_bytes,
        fixshade_scenes::MESH_SHAPE_BYTES,
        fixshade_scenes::MESH_NORMAL_BYTES,
        super::static_ram(),
    );
    macro_rules! ws {
        () => {
            Workspace {
                xy: &mut xy[..],
                vals: &mut vals[..],
                tris: &mut tris[..],
            }
        };
    }
    for spec in SCENES.iter() {
        check_with::<P>(spec, ws!()).map_err(|e| (spec.name, e))?;
    }
    for spec in SCENES.iter() {
        super::paint_stack();
        let stats = render_frame_with::<P, _>(
            spec,
            ws!(),
            &mut pixels[..],
            &mut depth[..],
            &mut order[..],
            pool,
            &mut super::Markers,
        )
        .map_err(|e| (spec.name, e))?;
        let stack = super::stack_used();
        hprintln!(
            "scene {} size={}x{} crc=0x{:08x} covered={} drawn={} setups={} triangles={} prepared_vertices={} prepared_triangles={} prepared_bytes={} stack={} static_ram={}",
            spec.name,
            spec.width,
            spec.height,
            stats.crc,
            stats.covered,
            stats.drawn,
            stats.setups,
            spec.triangles(),
            stats.vertices,
            stats.triangles,
            stats.prepared_bytes,
            stack,
            super::static_ram(),
        );
    }
    Ok(())
}
