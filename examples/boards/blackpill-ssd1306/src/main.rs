//! A turning dodecahedron on a 128×64 SSD1306 OLED from an STM32F411
//! "Black Pill" (Cortex-M4F at 100 MHz), shaded by fixshade (Phong,
//! `Fast` profile, Q16.16) and dithered to 1 bit.
//!
//! The `ssd1306` crate drives the display over I2C (400 kHz) in its
//! buffered graphics mode, an `embedded-graphics` `DrawTarget` of
//! `BinaryColor`: each 16-row band is rendered in 8-bit grey and handed to
//! it with `fixshade::target::eg::draw_band_with` and the level mapping
//! `Levels::ONE_BIT` (a contrast stretch before the 4×4 ordered dither,
//! see the crate's README), then `flush` sends the 1 KiB frame.
//!
//! Each frame turns the solid by 10° about Y and logs over defmt (RTT) the
//! CPU cycles (DWT cycle counter) of the geometry, of the raster with the
//! dither (one band buffer: `Frame::render_bands` hands each band to the
//! dither), and of the I2C transfer. The scene and the memory plan are in
//! [`scene`]; a scene that does not fit the workspace is a compile-time
//! error (the const assertions there) or a start-up error over defmt.
#![no_std]
#![no_main]

use defmt_rtt as _;
use panic_probe as _;

use cortex_m::peripheral::DWT;
use fixshade::num::Fast;
use fixshade::render::{prepare, BandState, RenderError, Tri, Workspace};
use fixshade::target::eg::{draw_band_with, Levels};
use fixshade::target::{BandBuf, Gray8};
use ssd1306::{prelude::*, I2CDisplayInterface, Ssd1306};
use stm32f4xx_hal::{pac, prelude::*, rcc::Config};

mod scene;

use scene::{
    BandPool, BAND_PX, COLORS, FRAMES, H, MADE, ORDER, ROWS, TRIANGLES, VALUES, VERTICES, W,
};

#[cortex_m_rt::entry]
fn main() -> ! {
    let (Some(dp), Some(mut cp)) = (
        pac::Peripherals::take(),
        cortex_m::peripheral::Peripherals::take(),
    ) else {
        defmt::panic!("peripherals taken twice");
    };
    // 25 MHz crystal, 100 MHz system clock.
    let mut rcc = dp.RCC.freeze(Config::hse(25.MHz()).sysclk(100.MHz()));
    cp.DCB.enable_trace();
    cp.DWT.enable_cycle_counter();

    // Wiring: SCL PB6, SDA PB7 (the module's pull-ups, or these), 3V3, GND.
    let gpiob = dp.GPIOB.split(&mut rcc);
    let scl = gpiob.pb6.internal_pull_up(true);
    let sda = gpiob.pb7.internal_pull_up(true);
    let i2c = dp.I2C1.i2c((scl, sda), 400.kHz(), &mut rcc);
    let mut oled = Ssd1306::new(
        I2CDisplayInterface::new(i2c),
        DisplaySize128x64,
        DisplayRotation::Rotate0,
    )
    .into_buffered_graphics_mode();
    if let Err(e) = oled.init() {
        defmt::panic!("SSD1306 init: {}", defmt::Debug2Format(&e));
    }

    let mut pixels = [[0u8; 1]; BAND_PX];
    let mut depth = [0u16; BAND_PX];
    let mut xy = [fixshade::render::ScreenXy::ZERO; VERTICES];
    let mut vals = [0i32; VALUES];
    let mut tris = [Tri::EMPTY; MADE];
    let mut faces = [0u8; TRIANGLES];
    let mut colors = [fixshade::target::Rgb8::BLACK; COLORS];
    let mut order = [0u16; ORDER];
    let mut pool = BandPool::new();
    let mut band = match BandBuf::<Gray8>::new(&mut pixels, Some(&mut depth), W, ROWS) {
        Ok(b) => b,
        Err(e) => defmt::panic!("band buffer: {}", e),
    };

    let Ok(camera) = scene::camera() else {
        defmt::panic!("camera refused");
    };
    let lights = scene::lights();

    let mut i = 0;
    loop {
        let t0 = DWT::cycle_count();
        let objects = scene::objects(i);
        let scene = scene::scene(camera, &objects, &lights);
        let ws = Workspace {
            xy: &mut xy,
            vals: &mut vals,
            tris: &mut tris,
            colors: &mut colors,
            faces: &mut faces,
        };
        let frame = match prepare::<Fast>(&scene, W, H, ws) {
            Ok(f) => f,
            Err(e) => defmt::panic!("frame {} does not fit the workspace: {}", i, e),
        };
        let t1 = DWT::cycle_count();
        let mut state = BandState::new(&mut order, &mut pool);
        // Each band in 8-bit grey, then dithered into the driver's 1 KiB
        // buffer (which cannot fail).
        let stats = match frame.render_bands(&scene, &mut state, &mut band, |b| {
            let _ = draw_band_with(b, &mut oled, &Levels::ONE_BIT);
            Ok::<(), RenderError>(())
        }) {
            Ok(s) => s,
            Err(e) => defmt::panic!("render: {}", e),
        };
        let t2 = DWT::cycle_count();
        if let Err(e) = oled.flush() {
            defmt::panic!("SSD1306 flush: {}", defmt::Debug2Format(&e));
        }
        let t3 = DWT::cycle_count();
        defmt::info!(
            "frame {}: geometry {} cycles, raster + dither {} cycles, I2C {} cycles, {} setups, {} pixels drawn",
            i,
            t1.wrapping_sub(t0),
            t2.wrapping_sub(t1),
            t3.wrapping_sub(t2),
            stats.triangles,
            stats.pixels
        );
        i = (i + 1) % FRAMES;
    }
}
