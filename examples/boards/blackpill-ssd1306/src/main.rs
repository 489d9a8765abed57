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
//! dither, and of the I2C transfer. A scene that does not fit the
//! workspace is a compile-time error (the const assertions below) or a
//! start-up error over defmt.
#![no_std]
#![no_main]

use defmt_rtt as _;
use panic_probe as _;

use cortex_m::peripheral::DWT;
use fixshade::geom::{radians, Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::DODECAHEDRON;
use fixshade::num::{Fast, Q16};
use fixshade::render::{prepare, Link, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::eg::{draw_band_with, Levels};
use fixshade::target::{Depth16, DepthBuffer, FrameBuf, Gray8, Rgb8, Target};
use ssd1306::{prelude::*, I2CDisplayInterface, Ssd1306};
use stm32f4xx_hal::{pac, prelude::*, rcc::Config};

/// Screen and bands.
const W: u32 = 128;
const H: u32 = 64;
const ROWS: u32 = 16;
const BAND_PX: usize = (W * ROWS) as usize;

/// Workspace capacities: a prepared vertex per triangle corner at most
/// (the vertex cache merges corners sharing a position and a normal: 60
/// for the dodecahedron), 7 values per vertex (Phong: normal, position,
/// depth), every triangle (the camera never clips). 4.6 KB, with the 2 KiB
/// grey band and the 4 KiB depth band: 11 KB of the F411's 128 KB.
const TRIANGLES: usize = 36;
const VERTICES: usize = 3 * TRIANGLES;
const VALUES: usize = 7 * VERTICES;
const HEADS: usize = 20;

const _: () = assert!(
    TRIANGLES >= DODECAHEDRON.triangle_count() && VERTICES >= 3 * DODECAHEDRON.triangle_count(),
    "the workspace holds fewer triangles or corners than the mesh has"
);
const _: () = assert!(
    HEADS >= DODECAHEDRON.vertex_count(),
    "the workspace's heads are fewer than the mesh's vertices"
);

/// Frames per turn.
const FRAMES: i32 = 36;

/// `n / d` in Q16.16.
const fn q(n: i32, d: i32) -> Q16 {
    Q16::from_ratio_const(n, d)
}

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

    let mut band = [[0u8; 1]; BAND_PX];
    let mut depth = [0u16; BAND_PX];
    let mut xy = [[0i32; 2]; VERTICES];
    let mut vals = [0i32; VALUES];
    let mut tris = [Tri::EMPTY; TRIANGLES];
    let mut heads = [0u16; HEADS];
    let mut links = [Link::default(); VERTICES];

    // The view of examples/eg_simulator.rs: the solid fills ~60 of the 64
    // rows; a bright material (see the README's 1-bit section).
    let Ok(camera) = Camera::look_at(
        Vec3::new(q(0, 1), q(0, 1), q(6, 1)),
        Vec3::ZERO,
        Vec3::new(q(0, 1), q(1, 1), q(0, 1)),
        radians(q(20, 1)),
        q(1, 2),
        None,
    ) else {
        defmt::panic!("camera refused");
    };
    let material = Material {
        color: Vec3::new(q(1, 1), q(9, 10), q(6, 10)),
        ka: q(2, 10),
        kd: q(7, 10),
        ks: q(4, 10),
        shininess: q(25, 1),
    };
    let lights = [Light::point(Vec3::new(q(2, 1), q(2, 1), q(4, 1)), q(1, 1))];

    let mut i = 0;
    loop {
        let t0 = DWT::cycle_count();
        let angle = q(2 * 314_159 * i, 100_000 * FRAMES);
        let objects = [Object {
            mesh: DODECAHEDRON,
            transform: Affine::from_parts(
                q(1, 1),
                Vec3::new(radians(q(20, 1)), angle, q(0, 1)),
                Vec3::ZERO,
            ),
            material,
            shading: Shading::Phong,
            cull_backfaces: true,
        }];
        let scene = Scene {
            camera,
            objects: &objects,
            lights: &lights,
            ambient: q(1, 1),
            specular: Specular::Phong,
            viewer: Viewer::Local,
            background: Rgb8::BLACK,
        };
        let ws = Workspace {
            xy: &mut xy,
            vals: &mut vals,
            tris: &mut tris,
            heads: &mut heads,
            links: &mut links,
        };
        let frame = match prepare::<Fast>(&scene, W, H, ws) {
            Ok(f) => f,
            Err(e) => defmt::panic!("frame {} does not fit the workspace: {}", i, e),
        };
        let t1 = DWT::cycle_count();
        let mut drawn = 0;
        let mut y0 = 0;
        while y0 < H {
            let y1 = (y0 + ROWS).min(H);
            let n = ((y1 - y0) * W) as usize;
            let r = FrameBuf::<Gray8>::band(&mut band[..n], W, y0, y1).and_then(|mut fb| {
                fb.clear(scene.background);
                let mut db = DepthBuffer::<Depth16>::new(&mut depth[..n], W, y0, y1)?;
                let stats = frame.render(&scene, &mut fb, Some(&mut db));
                // Into the driver's 1 KiB buffer, dithered; it cannot fail.
                let _ = draw_band_with(&fb, &mut oled, &Levels::ONE_BIT);
                Ok(stats)
            });
            match r {
                Ok(Ok(s)) => drawn += s.pixels,
                Ok(Err(e)) => defmt::panic!("render: {}", e),
                Err(e) => defmt::panic!("band: {}", e),
            }
            y0 = y1;
        }
        let t2 = DWT::cycle_count();
        if let Err(e) = oled.flush() {
            defmt::panic!("SSD1306 flush: {}", defmt::Debug2Format(&e));
        }
        let t3 = DWT::cycle_count();
        defmt::info!(
            "frame {}: geometry {} cycles, raster + dither {} cycles, I2C {} cycles, {} pixels drawn",
            i,
            t1.wrapping_sub(t0),
            t2.wrapping_sub(t1),
            t3.wrapping_sub(t2),
            drawn
        );
        i = (i + 1) % FRAMES;
    }
}
