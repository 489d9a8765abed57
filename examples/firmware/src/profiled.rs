//! The firmware built with a `profile-*` feature: every scene rendered
//! with that core profile instead of `Fast`, for the per-profile chip
//! costs (`fixshade measure-firmware`, `.ci/firmware`).
//!
//! Same output as the default build (header, `capacity`, one `scene`
//! line each; no span-loop lines), same two measured regions per scene
//! (geometry, bands), the scenes widened exactly from their Q16 data
//! (`fixshade_scenes::profiled`). The storage is sized for the profile
//! (`capacity_for`: one more value per vertex in the `-pc` profiles) and
//! its values are the profile's `Lerp` (4 bytes, or 8 for `f64`).

use crate::qemu;
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use fixshade::num::Profile;
use fixshade::render::Capacity;
use fixshade_scenes::profiled::{check_with, render_frame_with, ProfilePool};
use fixshade_scenes::{capacity_for, Pixel, BAND_PIXELS, BAND_ROWS, DEPTH_PIXELS, SCENES, WIDTH};

/// The profile of the build's `profile-*` feature.
macro_rules! profile_of_feature {
    ($($feature:literal => $profile:ident),* $(,)?) => {
        $(
            #[cfg(feature = $feature)]
            type P = fixshade::num::$profile;
        )*
    };
}
profile_of_feature! {
    "profile-precise" => Precise,
    "profile-f32" => F32,
    "profile-f64" => F64,
    "profile-fast-pc" => FastPc,
    "profile-precise-pc" => PrecisePc,
    "profile-f32-pc" => F32Pc,
    "profile-f64-pc" => F64Pc,
}

/// The interpolated values' type.
type L = <P as Profile>::Lerp;

/// The storage's capacities for the profile.
const CAP: Capacity = capacity_for::<P>();

/// The prepared frame's storage, sized by the compiler.
type FrameStorage = fixshade::storage!(L, CAP);

#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` (the entry runs once).
    static mut PIXELS: [Pixel; BAND_PIXELS] = [0; BAND_PIXELS];
    static mut DEPTH: [u16; DEPTH_PIXELS] = [0; DEPTH_PIXELS];
    static mut STORAGE: FrameStorage = FrameStorage::EMPTY;
    static mut POOL: ProfilePool<P> = ProfilePool::<P>::new();
    let status = match run(PIXELS, DEPTH, STORAGE, POOL) {
        Ok(()) => debug::EXIT_SUCCESS,
        Err((name, e)) => {
            hprintln!("error: scene {}: {}", name, e);
            debug::EXIT_FAILURE
        }
    };
    qemu::exit(status)
}

fn run(
    pixels: &mut [Pixel; BAND_PIXELS],
    depth: &mut [u16; DEPTH_PIXELS],
    storage: &mut FrameStorage,
    pool: &mut ProfilePool<P>,
) -> Result<(), (&'static str, fixshade_scenes::FrameError)> {
    let workspace_bytes = FrameStorage::BYTES;
    hprintln!(
        "fixshade-firmware target={} board={} profile={} max_frame={}x{} rgb565be band_rows={} depth16={}",
        env!("FW_TARGET"),
        env!("FW_BOARD"),
        P::NAME,
        WIDTH,
        WIDTH,
        BAND_ROWS,
        DEPTH_PIXELS > 0,
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
    for spec in SCENES.iter() {
        check_with::<P>(spec, storage.workspace()).map_err(|e| (spec.name, e))?;
    }
    for spec in SCENES.iter() {
        super::paint_stack();
        let (ws, order) = storage.split();
        let stats = render_frame_with::<P, _>(
            spec,
            ws,
            &mut pixels[..],
            spec.depth.then_some(&mut depth[..]),
            order,
            pool,
            &mut super::Markers,
        )
        .map_err(|e| (spec.name, e))?;
        super::print_scene::<P>(spec, &stats, core::mem::size_of::<ProfilePool<P>>());
    }
    Ok(())
}
