//! A turning Stanford bunny on a 240×240 ST7789 from a Raspberry Pi Pico
//! (RP2040, Cortex-M0+ at 125 MHz), shaded by fixshade (Gouraud, `Fast`
//! profile, Q16.16).
//!
//! The display is driven by `mipidsi` (initialisation, orientation, the
//! address window of each band). The pixels of a band go out by DMA
//! straight from the band buffer (fixshade's `Rgb565Be` is the byte order
//! the ST7789 takes) while the CPU renders the next band into the other
//! buffer (`Bands::next_band` into buffer `i` while buffer `i ^ 1` is
//! sent): two 7 680-byte band buffers, one 16-bit depth band. The only
//! code here that a driver crate does not already have is [`DmaSpi`]:
//! `mipidsi`'s display interface over rp2040-hal's SPI, with a DMA path
//! for whole bands.
//!
//! The scene ([`scene`]) is the project's bunny benchmark (white, one
//! directional light); each frame turns the bunny by 15° about Y (the
//! model transform from the core's Q16 `sin_cos`), as the QEMU animation
//! firmware does, and logs over defmt (RTT) the microseconds of the
//! geometry and of the raster plus transfer, measured with the RP2040's
//! 1 MHz timer, and the band renderer's setups and active-triangle peak.
//! A scene that does not fit the workspace is a compile-time error (the
//! const assertions in [`scene`]) or a start-up error over defmt.
#![no_std]
#![no_main]

use defmt_rtt as _;
use panic_probe as _;

use core::convert::Infallible;
use embedded_graphics_core::pixelcolor::Rgb565;
use embedded_hal::digital::OutputPin;
use embedded_hal::spi::{SpiBus, MODE_0};
use fixshade::num::Fast;
use fixshade::render::{prepare, BandState, Tri, Workspace};
use fixshade::target::{BandBuf, Rgb565Be, Rgb8};
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

mod scene;

use scene::{
    BandPool, BAND_PX, COLORS, FRAMES, H, MADE, ORDER, ROWS, TRIANGLES, VALUES, VERTICES, W,
};

type Mosi = Pin<Gpio19, FunctionSpi, PullDown>;
type Sck = Pin<Gpio18, FunctionSpi, PullDown>;
type Dc = Pin<Gpio16, FunctionSioOutput, PullDown>;
type Bus = hal::spi::Spi<Enabled, pac::SPI0, (Mosi, Sck), 8>;
/// A band buffer as the DMA sends it: the bytes of `BAND_PX` RGB565
/// pixels (`u16`s stored in the display's byte order, big-endian), a
/// byte view of a `u16` array (`bytemuck`: same memory, no copy).
type Band = &'static mut [u8];

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

    // Memory: two band buffers for the DMA, the depth band (shared: only
    // the band being rendered uses it), the workspace, the band state.
    let (Some(a), Some(b)) = (
        cortex_m::singleton!(: [u16; BAND_PX] = [0; BAND_PX]),
        cortex_m::singleton!(: [u16; BAND_PX] = [0; BAND_PX]),
    ) else {
        defmt::panic!("band buffers taken twice");
    };
    let mut spare: Option<Band> = Some(bytemuck::cast_slice_mut::<u16, u8>(b));
    let mut next: Option<Band> = Some(bytemuck::cast_slice_mut::<u16, u8>(a));
    let (
        Some(depth),
        Some(xy),
        Some(vals),
        Some(tris),
        Some(faces),
        Some(colors),
        Some(order),
        Some(pool),
    ) = (
        cortex_m::singleton!(: [u16; BAND_PX] = [0; BAND_PX]),
        cortex_m::singleton!(: [fixshade::render::ScreenXy; VERTICES] = [fixshade::render::ScreenXy::ZERO; VERTICES]),
        cortex_m::singleton!(: [i32; VALUES] = [0; VALUES]),
        cortex_m::singleton!(: [Tri; MADE] = [Tri::EMPTY; MADE]),
        cortex_m::singleton!(: [u8; TRIANGLES] = [0; TRIANGLES]),
        cortex_m::singleton!(: [Rgb8; COLORS] = [Rgb8::BLACK; COLORS]),
        cortex_m::singleton!(: [u16; ORDER] = [0; ORDER]),
        cortex_m::singleton!(: BandPool = BandPool::new()),
    )
    else {
        defmt::panic!("workspace taken twice");
    };

    let Ok(camera) = scene::camera() else {
        defmt::panic!("camera refused");
    };
    let lights = scene::lights();

    let mut i = 0;
    loop {
        let t0 = timer.get_counter();
        let objects = scene::objects(i);
        let scene = scene::scene(camera, &objects, &lights);
        let ws = Workspace {
            xy: &mut xy[..],
            vals: &mut vals[..],
            tris: &mut tris[..],
            colors: &mut colors[..],
            faces: &mut faces[..],
        };
        let frame = match prepare::<Fast>(&scene, W, H, ws) {
            Ok(f) => f,
            Err(e) => defmt::panic!("frame {} does not fit the workspace: {}", i, e),
        };
        let t1 = timer.get_counter();
        let mut state = BandState::new(&mut order[..], &mut *pool);
        let mut bands = match frame.bands(&scene, &mut state, ROWS) {
            Ok(b) => b,
            Err(e) => defmt::panic!("frame {}: band order: {}", i, e),
        };
        loop {
            let Some(buf) = next.take() else {
                defmt::panic!("no free band buffer");
            };
            // The next band into this buffer while the other one (the
            // band above) is still going out by DMA.
            let rendered = {
                // The same memory as `u16` pixels (it was a `u16` array:
                // aligned, an even length).
                let Ok(pixels) = bytemuck::try_cast_slice_mut::<u8, u16>(&mut buf[..]) else {
                    defmt::panic!("band buffer not a u16 array");
                };
                match BandBuf::<Rgb565Be>::new(pixels, Some(&mut depth[..]), W, ROWS) {
                    Ok(mut band) => bands.next_band(&mut band),
                    Err(e) => defmt::panic!("band buffer: {}", e),
                }
            };
            let win = match rendered {
                Ok(Some(win)) => win,
                Ok(None) => {
                    next = Some(buf);
                    break;
                }
                Err(e) => defmt::panic!("render: {}", e),
            };
            // mipidsi sets the window and starts the memory write (waiting
            // for the previous band's DMA), then this band goes out by DMA
            // while the loop renders the next one into the other buffer.
            let _ = display.set_pixels(
                0,
                win.y0 as u16,
                (W - 1) as u16,
                (win.y1 - 1) as u16,
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
        }
        let t2 = timer.get_counter();
        let stats = bands.stats();
        defmt::info!(
            "frame {}: geometry {} us, raster + transfer {} us, {} prepared triangles, {} setups, active peak {}, {} pixels drawn",
            i,
            (t1 - t0).to_micros(),
            (t2 - t1).to_micros(),
            frame.triangle_count(),
            stats.triangles,
            bands.active_peak(),
            stats.pixels
        );
        i = (i + 1) % FRAMES;
    }
}
