//! The firmware built with the feature `knobs`: the knobs a user trades,
//! on one scene (`fixshade_scenes::knobs::KNOB_SCENE`) with the `Fast`
//! profile: band rows (`BAND_ROWS_SWEEP`), a 32-bit depth band instead of
//! 16, subpixel bits (`SUBPIXEL_SWEEP`). One line per variant, two
//! measured regions each (geometry, bands), as the default build's scenes:
//!
//! ```text
//! knob rows=<n> depth=<16|32> subpixel=<bits> scene=<name> crc=0x<crc32> covered=<px> drawn=<px> setups=<n> prepared_bytes=<bytes> band_bytes=<bytes> depth_bytes=<bytes> stack=<bytes>
//! ```

use crate::qemu;
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use fixshade::num::{Fast, Profile};
use fixshade::target::{Depth16, Depth32, DepthFormat};
use fixshade_scenes::knobs::{
    render_frame_knobs, FastSub, BAND_ROWS_SWEEP, KNOB_SCENE, MAX_BAND_PIXELS,
};
use fixshade_scenes::{BandPool, FrameError, Pixel, SceneSpec, SceneStorage, SCENES};

/// Static memory.
struct Mem {
    pixels: &'static mut [Pixel; MAX_BAND_PIXELS],
    depth16: &'static mut [u16; MAX_BAND_PIXELS],
    depth32: &'static mut [u32; MAX_BAND_PIXELS],
    /// The core's bound holds for every subpixel precision (finer
    /// subpixels keep more thin triangles, never more than the mesh's).
    storage: &'static mut SceneStorage,
    pool: &'static mut BandPool,
}

impl Mem {
    /// One variant: render, print its line.
    fn run<P: Profile<Lerp = i32>, D: DepthFormat>(
        &mut self,
        spec: &SceneSpec,
        rows: u32,
        bits: u32,
    ) -> Result<(), FrameError> {
        super::paint_stack();
        let depth_bytes = core::mem::size_of::<D::Raw>();
        let (ws, order) = self.storage.split();
        let stats = if depth_bytes == 2 {
            render_frame_knobs::<P, Depth16, _>(
                spec,
                ws,
                &mut self.pixels[..],
                Some(&mut self.depth16[..]),
                rows,
                order,
                self.pool,
                &mut super::Markers,
            )?
        } else {
            render_frame_knobs::<P, Depth32, _>(
                spec,
                ws,
                &mut self.pixels[..],
                Some(&mut self.depth32[..]),
                rows,
                order,
                self.pool,
                &mut super::Markers,
            )?
        };
        let stack = super::stack_used();
        let band = spec.width * rows.min(spec.height);
        hprintln!(
            "knob rows={} depth={} subpixel={} scene={} crc=0x{:08x} covered={} drawn={} setups={} prepared_bytes={} band_bytes={} depth_bytes={} stack={}",
            rows,
            8 * depth_bytes,
            bits,
            spec.name,
            stats.crc,
            stats.covered,
            stats.drawn,
            stats.setups,
            stats.prepared_bytes,
            band * 2,
            band as usize * depth_bytes,
            stack,
        );
        Ok(())
    }
}

fn run(mem: &mut Mem) -> Result<(), FrameError> {
    hprintln!(
        "fixshade-firmware target={} board={} knobs scene={} profile={}",
        env!("FW_TARGET"),
        env!("FW_BOARD"),
        KNOB_SCENE,
        Fast::NAME
    );
    let Some(spec) = SCENES.iter().find(|s| s.name == KNOB_SCENE) else {
        return Err(FrameError::Render(fixshade::render::RenderError::Window));
    };
    for rows in BAND_ROWS_SWEEP {
        mem.run::<Fast, Depth16>(spec, rows, 4)?;
    }
    mem.run::<Fast, Depth32>(spec, 16, 4)?;
    mem.run::<FastSub<2>, Depth16>(spec, 16, 2)?;
    mem.run::<FastSub<3>, Depth16>(spec, 16, 3)?;
    mem.run::<FastSub<6>, Depth16>(spec, 16, 6)?;
    mem.run::<FastSub<8>, Depth16>(spec, 16, 8)?;
    Ok(())
}

#[entry]
fn main() -> ! {
    static mut PIXELS: [Pixel; MAX_BAND_PIXELS] = [0; MAX_BAND_PIXELS];
    static mut DEPTH16: [u16; MAX_BAND_PIXELS] = [0; MAX_BAND_PIXELS];
    static mut DEPTH32: [u32; MAX_BAND_PIXELS] = [0; MAX_BAND_PIXELS];
    static mut STORAGE: SceneStorage = SceneStorage::EMPTY;
    static mut POOL: BandPool = BandPool::new();
    let mut mem = Mem {
        pixels: PIXELS,
        depth16: DEPTH16,
        depth32: DEPTH32,
        storage: STORAGE,
        pool: POOL,
    };
    let status = match run(&mut mem) {
        Ok(()) => debug::EXIT_SUCCESS,
        Err(e) => {
            hprintln!("error: knobs: {}", e);
            debug::EXIT_FAILURE
        }
    };
    qemu::exit(status)
}
