//! fixshade benchmark firmware for QEMU's MPS2 boards.
//!
//! Renders each scene of [`fixshade_scenes::SCENES`] once (240×240 RGB565
//! big-endian, 15 bands of 16 rows, a band-sized 16-bit depth buffer) and
//! prints over semihosting, one line per scene:
//!
//! ```text
//! scene <name> crc=0x<crc32> covered=<pixels> triangles=<n> stack=<bytes> static_ram=<bytes>
//! ```
//!
//! The work of each band is bracketed by `yield` instructions and each
//! frame closed by `sev`: the QEMU plugin in `qemu-plugin/` counts the
//! instructions between them (one region per scene, in order). Exits
//! through semihosting with status 0, or 1 on any error or panic.
#![no_std]
#![no_main]

use core::panic::PanicInfo;
use core::ptr::{addr_of, addr_of_mut};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use fixshade_scenes::{render_frame, FrameError, Pixel, Probe, BAND_PIXELS, SCENES};

/// Executes the marker instruction `yield`: a hint that QEMU runs as a
/// no-op and that rustc never emits, so the counting plugin can toggle on
/// it. cortex-m 0.7 has no wrapper for it.
#[inline(always)]
fn yield_marker() {
    // SAFETY: `yield` is an architectural hint (ARMv6-M and ARMv7-M) with
    // no effect on registers, memory or flags. No `nomem`: it also acts as
    // a compiler barrier, so no memory access of the measured work moves
    // across it.
    unsafe { core::arch::asm!("yield", options(nostack, preserves_flags)) }
}

/// Toggles instruction counting around each band's work.
struct Markers;

impl Probe for Markers {
    #[inline(always)]
    fn resume(&mut self) {
        yield_marker();
    }
    #[inline(always)]
    fn pause(&mut self) {
        yield_marker();
    }
}

// Symbols of cortex-m-rt's link.x.
extern "C" {
    static __sbss: u32;
    static __ebss: u32;
    static __sdata: u32;
    static __edata: u32;
    /// Lowest address the stack may grow to (end of static RAM).
    static mut _stack_end: u32;
    /// Initial stack pointer (top of RAM).
    static _stack_start: u32;
}

/// Written over the free stack before a scene, to find its high-water mark.
const PAINT: u32 = 0x5AA5_C33C;

fn stack_limits() -> (usize, usize) {
    // Addresses of linker symbols only: nothing is read through them here.
    (
        addr_of_mut!(_stack_end) as usize,
        addr_of!(_stack_start) as usize,
    )
}

/// Bytes of `.data` plus `.bss`.
fn static_ram() -> usize {
    let data = addr_of!(__edata) as usize - addr_of!(__sdata) as usize;
    let bss = addr_of!(__ebss) as usize - addr_of!(__sbss) as usize;
    data + bss
}

/// Paints the unused stack, from its limit up to a little below the
/// current stack pointer.
#[inline(never)]
fn paint_stack() {
    let (bottom, _) = stack_limits();
    let sp = cortex_m::register::msp::read() as usize;
    let mut p = bottom;
    while p + 64 < sp {
        // SAFETY: [bottom, sp - 64) is RAM below every live stack frame
        // (this function's frame is above sp) and above all statics; no
        // interrupt handler runs. Nothing owns it, so writing it is sound.
        unsafe { (p as *mut u32).write_volatile(PAINT) };
        p += 4;
    }
}

/// Bytes of stack used since [`paint_stack`]: from the top of RAM down to
/// the lowest word no longer painted.
#[inline(never)]
fn stack_used() -> usize {
    let (bottom, top) = stack_limits();
    let mut p = bottom;
    // SAFETY: reads RAM between the end of the statics and the stack top,
    // word-aligned (link.x asserts both ends are 4-aligned).
    while p < top && unsafe { (p as *const u32).read_volatile() } == PAINT {
        p += 4;
    }
    top - p
}

fn run(pixels: &mut [Pixel], depth: &mut [u16]) -> Result<(), FrameError> {
    hprintln!(
        "fixshade-firmware target={} board={} frame=240x240 rgb565be bands=16 depth16 band_ram={}",
        env!("FW_TARGET"),
        env!("FW_BOARD"),
        core::mem::size_of_val(pixels) + core::mem::size_of_val(depth),
    );
    for scene in SCENES.iter() {
        paint_stack();
        let stats = render_frame(scene, pixels, depth, &mut Markers)?;
        let stack = stack_used();
        // Closes the plugin's region for this scene.
        cortex_m::asm::sev();
        hprintln!(
            "scene {} crc=0x{:08x} covered={} triangles={} stack={} static_ram={}",
            scene.name,
            stats.crc,
            stats.covered,
            scene.triangles,
            stack,
            static_ram(),
        );
    }
    Ok(())
}

#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` (the entry runs once):
    // the band's colour and depth memory, in .bss.
    static mut PIXELS: [Pixel; BAND_PIXELS] = [[0; 2]; BAND_PIXELS];
    static mut DEPTH: [u16; BAND_PIXELS] = [0; BAND_PIXELS];
    let status = match run(PIXELS, DEPTH) {
        Ok(()) => debug::EXIT_SUCCESS,
        Err(e) => {
            hprintln!("error: {}", e);
            debug::EXIT_FAILURE
        }
    };
    debug::exit(status);
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(info: &PanicInfo) -> ! {
    hprintln!("panic: {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
