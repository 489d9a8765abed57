//! A turning Stanford bunny on a 240×240 ST7789 from a Raspberry Pi Pico
//! (RP2040, Cortex-M0+ at 125 MHz), shaded by fixshade (Gouraud, `Fast`
//! profile, Q16.16).
//!
//! The display is driven by `mipidsi` (initialisation, orientation, the
//! address window of each band). The pixels of a band go out by DMA
//! straight from the band buffer (fixshade's `Rgb565Be` is the byte order
//! the ST7789 takes) while the CPU renders the next band into the other
//! buffer: two 7 680-byte band buffers, one 16-bit depth band. The only
//! code here that a driver crate does not already have is [`DmaSpi`]:
//! `mipidsi`'s display interface over rp2040-hal's SPI, with a DMA path
//! for whole bands.
//!
//! The scene is the project's bunny benchmark (white, one directional
//! light); each frame turns the bunny by 15° about Y (the model transform
//! from the core's Q16 `sin_cos`), as the QEMU animation firmware does,
//! and logs over defmt (RTT) the microseconds of the geometry and of the
//! raster plus transfer, measured with the RP2040's 1 MHz timer. A scene that does not fit the workspace is a compile-time
//! error (the const assertions below) or a start-up error over defmt.
#![no_std]
#![no_main]

use defmt_rtt as _;
use panic_probe as _;

use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::{SpiBus, MODE_0};
use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::BUNNY;
use fixshade::num::{Fast, Q16};
use fixshade::render::{prepare, Link, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{Depth16, DepthBuffer, FrameBuf, Rgb565Be, Rgb8, Target};
use fugit::RateExtU32;
use hal::dma::{single_buffer, Channel, DMAExt, CH0};
use hal::gpio::bank0::{Gpio16, Gpio18, Gpio19};
use hal::gpio::{FunctionSioOutput, FunctionSpi, Pin, PullDown};
use hal::pac;
use hal::spi::Enabled;
use hal::Clock;
use mipidsi::interface::Interface;
use mipidsi::models::ST7789;
use mipidsi::options::ColorInversion;
use rp2040_hal as hal;

/// The second-stage bootloader for the Pico's W25Q080 flash.
#[link_section = ".boot2"]
#[used]
pub static BOOT2_FIRMWARE: [u8; 256] = rp2040_boot2::BOOT_LOADER_W25Q080;

/// The Pico's crystal.
const XTAL_FREQ_HZ: u32 = 12_000_000;

/// Screen and bands.
const W: u32 = 240;
const H: u32 = 240;
const ROWS: u32 = 16;
const BAND_PX: usize = (W * ROWS) as usize;

/// Workspace capacities: every vertex of the bunny (1 839), four values
/// per vertex (colour Gouraud: three channels and the depth; this white
/// scene uses two, a coloured material or light four), every triangle
/// (3 674: a turn shows other faces than any one view; the camera never
/// clips, so no triangle is split). 110 KB with the
/// band buffers' 23 KB: 133 KB of the RP2040's 264 KB. A material or
/// shading that needs more values is a start-up error over defmt.
const VERTICES: usize = 1839;
const VALUES: usize = 4 * VERTICES;
const TRIANGLES: usize = 3674;
const HEADS: usize = 1839;

const _: () = assert!(
    VERTICES >= BUNNY.vertex_count() && HEADS >= BUNNY.vertex_count(),
    "the workspace holds fewer vertices than the mesh has"
);
const _: () = assert!(
    TRIANGLES >= BUNNY.triangle_count(),
    "the workspace holds fewer triangles than the mesh has"
);

/// Frames per turn.
const FRAMES: i32 = 24;

/// `n / d` in Q16.16.
const fn q(n: i32, d: i32) -> Q16 {
    Q16::from_ratio_const(n, d)
}

type Mosi = Pin<Gpio19, FunctionSpi, PullDown>;
type Sck = Pin<Gpio18, FunctionSpi, PullDown>;
type Dc = Pin<Gpio16, FunctionSioOutput, PullDown>;
type Bus = hal::spi::Spi<Enabled, pac::SPI0, (Mosi, Sck), 8>;
type Band = &'static mut [u8; 2 * BAND_PX];

/// `mipidsi`'s display interface over the SPI bus, with DMA for bands.
///
/// Commands and small pixel runs go out blocking; [`DmaSpi::send_band`]
/// starts a DMA transfer of a whole buffer and returns at once. Any
/// command first waits for a running transfer (and the SPI's FIFO) to
/// finish, so `mipidsi` always sees an idle bus, and the buffer comes
/// back through [`DmaSpi::take_free`].
struct DmaSpi {
    idle: Option<(Channel<CH0>, Bus)>,
    busy: Option<single_buffer::Transfer<Channel<CH0>, Band, Bus>>,
    free: Option<Band>,
    dc: Dc,
}

impl DmaSpi {
    /// Waits for a running transfer; the bus is idle afterwards.
    fn finish(&mut self) -> &mut Bus {
        if let Some(t) = self.busy.take() {
            let (ch, buf, bus) = t.wait();
            self.free = Some(buf);
            self.idle = Some((ch, bus));
        }
        let (_, bus) = self.idle.as_mut().expect("the bus is idle after finish");
        // The DMA is done when the last byte is in the FIFO: wait for the
        // shift register before DC changes.
        let _ = SpiBus::<u8>::flush(bus);
        bus
    }

    /// Starts sending `band` (after `mipidsi` set the window and started
    /// the memory write).
    fn send_band(&mut self, band: Band) {
        self.finish();
        let (ch, bus) = self.idle.take().expect("the bus is idle after finish");
        self.busy = Some(single_buffer::Config::new(ch, band, bus).start());
    }

    /// The buffer of the last finished transfer, if one finished (any
    /// command waits for the transfer before it): does not wait.
    fn take_free(&mut self) -> Option<Band> {
        self.free.take()
    }
}

impl Interface for DmaSpi {
    type Word = u8;
    type Error = Infallible;

    fn send_command(&mut self, command: u8, args: &[u8]) -> Result<(), Infallible> {
        self.finish();
        let _ = self.dc.set_low();
        let bus = self.finish();
        let _ = SpiBus::write(bus, &[command]);
        let _ = SpiBus::<u8>::flush(bus);
        let _ = self.dc.set_high();
        let bus = self.finish();
        let _ = SpiBus::write(bus, args);
        Ok(())
    }

    fn send_pixels<const N: usize>(
        &mut self,
        pixels: impl IntoIterator<Item = [u8; N]>,
    ) -> Result<(), Infallible> {
        let bus = self.finish();
        for p in pixels {
            let _ = SpiBus::write(bus, &p);
        }
        Ok(())
    }

    fn send_repeated_pixel<const N: usize>(
        &mut self,
        pixel: [u8; N],
        count: u32,
    ) -> Result<(), Infallible> {
        let bus = self.finish();
        for _ in 0..count {
            let _ = SpiBus::write(bus, &pixel);
        }
        Ok(())
    }
}

#[hal::entry]
fn main() -> ! {
    let mut pac = pac::Peripherals::take().unwrap();
    let mut watchdog = hal::Watchdog::new(pac.WATCHDOG);
    let Ok(clocks) = hal::clocks::init_clocks_and_plls(
        XTAL_FREQ_HZ,
        pac.XOSC,
        pac.CLOCKS,
        pac.PLL_SYS,
        pac.PLL_USB,
        &mut pac.RESETS,
        &mut watchdog,
    ) else {
        defmt::panic!("clocks did not start");
    };
    let mut timer = hal::Timer::new(pac.TIMER, &mut pac.RESETS, &clocks);
    let sio = hal::Sio::new(pac.SIO);
    let pins = hal::gpio::Pins::new(
        pac.IO_BANK0,
        pac.PADS_BANK0,
        sio.gpio_bank0,
        &mut pac.RESETS,
    );

    // Wiring: SCK GP18, MOSI GP19, CS GP17 (held low: the display is alone
    // on the bus), DC GP16, RST GP20, backlight GP21.
    let bus: Bus = hal::spi::Spi::<_, _, _, 8>::new(
        pac.SPI0,
        (pins.gpio19.into_function(), pins.gpio18.into_function()),
    )
    .init(
        &mut pac.RESETS,
        clocks.peripheral_clock.freq(),
        62_500_000u32.Hz(),
        MODE_0,
    );
    let mut cs = pins.gpio17.into_push_pull_output();
    let _ = cs.set_low();
    let mut backlight = pins.gpio21.into_push_pull_output();
    let _ = backlight.set_high();
    let rst = pins.gpio20.into_push_pull_output();
    let dma = pac.DMA.split(&mut pac.RESETS);
    let iface = DmaSpi {
        idle: Some((dma.ch0, bus)),
        busy: None,
        free: None,
        dc: pins.gpio16.into_push_pull_output(),
    };
    // Neither the interface nor the reset pin can fail (their error types
    // are `Infallible`), so the pattern is irrefutable.
    let Ok(mut display) = mipidsi::Builder::new(ST7789, iface)
        .display_size(W as u16, H as u16)
        .invert_colors(ColorInversion::Inverted)
        .reset_pin(rst)
        .init(&mut timer);

    // Memory: two band buffers for the DMA, the depth band, the workspace.
    let (Some(a), Some(b)) = (
        cortex_m::singleton!(: [u8; 2 * BAND_PX] = [0; 2 * BAND_PX]),
        cortex_m::singleton!(: [u8; 2 * BAND_PX] = [0; 2 * BAND_PX]),
    ) else {
        defmt::panic!("band buffers taken twice");
    };
    let mut spare: Option<Band> = Some(b);
    let mut next: Option<Band> = Some(a);
    let depth = cortex_m::singleton!(: [u16; BAND_PX] = [0; BAND_PX]).unwrap();
    let xy = cortex_m::singleton!(: [[i32; 2]; VERTICES] = [[0; 2]; VERTICES]).unwrap();
    let vals = cortex_m::singleton!(: [i32; VALUES] = [0; VALUES]).unwrap();
    let tris = cortex_m::singleton!(: [Tri; TRIANGLES] = [Tri::EMPTY; TRIANGLES]).unwrap();
    let heads = cortex_m::singleton!(: [u16; HEADS] = [0; HEADS]).unwrap();
    let links = cortex_m::singleton!(: [Link; VERTICES] = [Link::default(); VERTICES]).unwrap();

    // The bunny benchmark scene (host-tests/scenes/bunny-gouraud.toml),
    // with the Q16 values the host's `Q16::from_f64` gives: the frames
    // are the firmware animation's (examples/firmware/src/bin/animate.rs),
    // whose cost is measured under QEMU.
    let Ok(camera) = Camera::look_at(
        Vec3::new(q(0, 1), q(0, 1), Q16::from_bits(257_032)), // 3.922
        Vec3::ZERO,
        Vec3::new(q(0, 1), q(1, 1), q(0, 1)),
        Q16::from_bits(51_472), // 45° in radians
        q(1, 1),
        Some(q(10, 1)),
    ) else {
        defmt::panic!("camera refused");
    };
    // I = 0.2 + 0.8 max(0, N·L), white.
    let material = Material {
        color: Vec3::new(q(1, 1), q(1, 1), q(1, 1)),
        ka: q(1, 1),
        kd: q(1, 1),
        ks: q(0, 1),
        shininess: q(1, 1),
    };
    let lights = [Light::directional(
        Vec3::new(q(1, 1), q(1, 1), q(1, 1)),
        Q16::from_bits(52_429), // 0.8
    )];

    let mut i = 0;
    loop {
        let t0 = timer.get_counter();
        // 2π·i/FRAMES rounded in Q16 (2π = 411 775 / 65 536), as the
        // firmware animation turns.
        let angle = Q16::from_bits((411_775 * i + FRAMES / 2) / FRAMES);
        let objects = [Object {
            mesh: BUNNY,
            transform: Affine::from_parts(q(1, 1), Vec3::new(q(0, 1), angle, q(0, 1)), Vec3::ZERO),
            material,
            shading: Shading::Gouraud,
            cull_backfaces: true,
        }];
        let scene = Scene {
            camera,
            objects: &objects,
            lights: &lights,
            ambient: Q16::from_bits(13_107), // 0.2
            specular: Specular::Phong,
            viewer: Viewer::Local,
            background: Rgb8::BLACK,
        };
        let ws = Workspace {
            xy: &mut xy[..],
            vals: &mut vals[..],
            tris: &mut tris[..],
            heads: &mut heads[..],
            links: &mut links[..],
        };
        let frame = match prepare::<Fast>(&scene, W, H, ws) {
            Ok(f) => f,
            Err(e) => defmt::panic!("frame {} does not fit the workspace: {}", i, e),
        };
        let t1 = timer.get_counter();
        let mut drawn = 0;
        let mut y0 = 0;
        while y0 < H {
            let y1 = (y0 + ROWS).min(H);
            let n = ((y1 - y0) * W) as usize;
            let Some(buf) = next.take() else {
                defmt::panic!("no free band buffer");
            };
            let (pixels, _) = buf.as_chunks_mut::<2>();
            let stats =
                FrameBuf::<Rgb565Be>::band(&mut pixels[..n], W, y0, y1).and_then(|mut fb| {
                    fb.clear(scene.background);
                    let mut db = DepthBuffer::<Depth16>::new(&mut depth[..n], W, y0, y1)?;
                    Ok(frame.render(&scene, &mut fb, Some(&mut db)))
                });
            match stats {
                Ok(Ok(s)) => drawn += s.pixels,
                Ok(Err(e)) => defmt::panic!("render: {}", e),
                Err(e) => defmt::panic!("band: {}", e),
            }
            // mipidsi sets the window and starts the memory write (waiting
            // for the previous band's DMA), then this band goes out by DMA
            // while the loop renders the next one into the other buffer.
            let _ = display.set_pixels(
                0,
                y0 as u16,
                (W - 1) as u16,
                (y1 - 1) as u16,
                core::iter::empty::<Rgb565>(),
            );
            // SAFETY (mipidsi's contract for `dcs`): sending pixel data
            // after `set_pixels` started the memory write changes no
            // controller state that mipidsi tracks.
            let dcs = unsafe { display.dcs() };
            dcs.send_band(buf);
            // The buffer of the previous band, free since `set_pixels`
            // waited for its transfer (the first band uses the spare).
            next = dcs.take_free().or_else(|| spare.take());
            y0 = y1;
        }
        let t2 = timer.get_counter();
        defmt::info!(
            "frame {}: geometry {} us, raster + transfer {} us, {} prepared triangles, {} pixels drawn",
            i,
            (t1 - t0).to_micros(),
            (t2 - t1).to_micros(),
            frame.triangle_count(),
            drawn
        );
        i = (i + 1) % FRAMES;
    }
}
