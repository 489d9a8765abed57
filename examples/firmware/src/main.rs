//! fixshade benchmark firmware for QEMU's MPS2 boards.
//!
//! Renders each scene of [`fixshade_scenes::SCENES`] (built-in 3D scenes of
//! the host, generated as Q16 constants) once with the core's `Fast`
//! profile: RGB565 big-endian in bands of 16 rows with a band-sized 16-bit
//! depth buffer, from a prepared frame in static workspace buffers. Prints
//! over semihosting a header, one `capacity` line, and one line per scene:
//!
//! ```text
//! scene <name> crc=0x<crc32> covered=<px> drawn=<px> setups=<n> triangles=<mesh> prepared_vertices=<n> prepared_triangles=<n> prepared_bytes=<bytes> storage_bytes=<bytes> depth_bytes=<bytes> pool_bytes=<bytes> stack=<bytes> static_ram=<bytes>
//! ```
//!
//! Before rendering, every scene is prepared once (unmeasured) to check
//! that it fits the fixed workspace: a scene that does not is a start-up
//! error. Per scene two regions are measured: the geometry (scene, camera,
//! `prepare`) bracketed by `yield` and closed by `sev`, then the bands
//! (each bracketed by `yield`) closed by `sev`: the QEMU plugin in
//! `qemu-plugin/` counts the instructions in each. Exits through
//! semihosting with status 0, or 1 on any error or panic.
#![no_std]
#![no_main]
// With a `profile-*` feature, `profiled::main` is the entry (with
// `knobs`, `knobs::main`) and the default build's frame and span-loop
// code is unused.
#![cfg_attr(
    any(feature = "profiled", feature = "knobs"),
    allow(dead_code, unused_imports)
)]

#[cfg(feature = "knobs")]
mod knobs;
#[cfg(feature = "profiled")]
mod profiled;
mod qemu;

use core::hint::black_box;
use core::ptr::{addr_of, addr_of_mut};
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use fixshade::geom::Vec3;
use fixshade::illum::{Light, Material, Shade, Specular, Viewer};
use fixshade::num::{Fast, Profile, SubpixelBits, Q16};
use fixshade::raster::{Fill, Flat, GouraudMono, Shader, Span, Spans};
use fixshade::render::{Capacity, PhongFill, PhongKernel, PhongShader, TriQuad};
use fixshade::target::{Depth16, DepthBuffer, FrameBuf, Rgb565Be, Rgb8};
use fixshade_scenes::{
    check, render_frame_in, BandPool, ChipFields, FrameError, Pixel, Probe, SceneLine, BAND_PIXELS,
    BAND_ROWS, CAPACITY, DEPTH_PIXELS, MESH_NORMAL_BYTES, MESH_SHAPE_BYTES, SCENES,
    WIDTH as SCENE_WIDTH,
};

/// Prints the `scene` line of a frame just rendered with profile `P`:
/// its figures and the chip's (the profile's storage for the scene, a
/// band pool of `pool_bytes`, the stack used since the last
/// [`paint_stack`], the static RAM).
fn print_scene<P: Profile>(
    spec: &fixshade_scenes::SceneSpec,
    stats: &fixshade_scenes::FrameStats,
    pool_bytes: usize,
) {
    let chip = ChipFields {
        storage_bytes: fixshade_scenes::storage_bytes::<P>(spec),
        pool_bytes,
        stack: stack_used(),
        static_ram: static_ram(),
    };
    hprintln!(
        "{}",
        SceneLine {
            spec,
            stats,
            chip: Some(chip)
        }
    );
}

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

/// Toggles instruction counting around the measured work and closes the
/// plugin's regions.
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
    #[inline(always)]
    fn close(&mut self) {
        cortex_m::asm::sev();
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

/// The storage's capacities: the scenes' in `fast` ([`CAPACITY`],
/// computed by the core's `const fn`s from their meshes, with one value
/// per grey Gouraud vertex: [`Capacity::in_profile`]), or, with the feature
/// `tiny-workspace` (to test the start-up check), half the vertices.
const CAP: Capacity = if cfg!(feature = "tiny-workspace") {
    Capacity {
        vertices: CAPACITY.vertices / 2,
        ..CAPACITY.in_profile::<Fast>()
    }
} else {
    CAPACITY.in_profile::<Fast>()
};

/// The prepared frame's storage, sized by the compiler.
type FrameStorage = fixshade::storage!(i32, CAP);

/// Static memory: the band buffers (no depth band when no scene needs
/// one), the prepared frame's storage and the active triangles.
struct Memory {
    pixels: &'static mut [Pixel; BAND_PIXELS],
    depth: &'static mut [u16; DEPTH_PIXELS],
    storage: &'static mut FrameStorage,
    pool: &'static mut BandPool,
}

/// Why the firmware stops.
enum Failure {
    /// A scene does not fit the workspace (or the core refuses it).
    Startup(&'static str, FrameError),
    /// Rendering a scene failed.
    Frame(&'static str, FrameError),
}

fn run(mem: &mut Memory) -> Result<(), Failure> {
    // (The three lengths printed, not the whole `Capacity`: fewer bytes
    // in this frame, under every scene's.)
    let ws = FrameStorage::CAPACITY;
    let (ws_vertices, ws_values, ws_triangles) = (ws.vertices, ws.values, ws.triangles);
    let band_bytes = core::mem::size_of_val(mem.pixels);
    let depth_bytes = core::mem::size_of_val(mem.depth);
    hprintln!(
        "fixshade-firmware target={} board={} profile=fast max_frame={}x{} rgb565be band_rows={} depth16={}",
        env!("FW_TARGET"),
        env!("FW_BOARD"),
        SCENE_WIDTH,
        SCENE_WIDTH,
        BAND_ROWS,
        fixshade_scenes::DEPTH,
    );
    hprintln!(
        "capacity band_bytes={} depth_bytes={} ws_vertices={} ws_values={} ws_triangles={} workspace_bytes={} mesh_shape_bytes={} mesh_normal_bytes={} static_ram={}",
        band_bytes,
        depth_bytes,
        ws_vertices,
        ws_values,
        ws_triangles,
        FrameStorage::BYTES,
        MESH_SHAPE_BYTES,
        MESH_NORMAL_BYTES,
        static_ram(),
    );
    // Start-up check: every scene must fit the fixed workspace.
    for spec in SCENES.iter() {
        check(spec, mem.storage.workspace()).map_err(|e| Failure::Startup(spec.name, e))?;
    }
    for spec in SCENES.iter() {
        paint_stack();
        let stats = scene_frame(spec, mem.pixels, mem.depth, mem.storage, mem.pool)
            .map_err(|e| Failure::Frame(spec.name, e))?;
        print_scene::<Fast>(spec, &stats, core::mem::size_of::<BandPool>());
    }
    // The span loops write 16 rows of a 240-pixel band and its depth
    // band: not in a build whose scenes are narrower, need no depth band
    // (one convex object each: a build for other scenes than the built-in
    // ones) or whose bands are shorter (the bunny alone: 8 rows).
    if fixshade_scenes::DEPTH
        && BAND_ROWS >= SPAN_ROWS
        && BAND_PIXELS >= (WIDTH * BAND_ROWS) as usize
    {
        span_loops(mem).map_err(|e| Failure::Frame("span-loops", e))?;
    }
    Ok(())
}

/// One frame of `spec` ([`render_frame_in`]) from the static memory. Not
/// inlined: its geometry locals (the scene's parts, the prepared frame's
/// object list) then take a stack frame of their own, not one in `main`
/// under the start-up check's `prepare` (which stacked both: 4 KB more).
/// The statics are passed one by one (not in [`Memory`]): from its one
/// call site the optimiser then sees them, and their alignment (the band
/// clears' word-wide `memset`s).
#[inline(never)]
fn scene_frame(
    spec: &fixshade_scenes::SceneSpec,
    pixels: &mut [Pixel; BAND_PIXELS],
    depth: &mut [u16; DEPTH_PIXELS],
    storage: &mut FrameStorage,
    pool: &mut BandPool,
) -> Result<fixshade_scenes::FrameStats, FrameError> {
    let (ws, order) = storage.split();
    render_frame_in(
        spec,
        ws,
        &mut pixels[..],
        &mut depth[..],
        order,
        pool,
        &mut Markers,
    )
}

/// Width of the span-loop regions' band (their spans are [`SPAN_LONG`]
/// pixels long): the built-in scenes' widest.
const WIDTH: u32 = 240;

/// Rows (spans) per span-loop region.
const SPAN_ROWS: u32 = 16;
/// Pixels of a long span (the short one has 1).
const SPAN_LONG: u32 = 200;

/// Q16 from a decimal in thousandths.
const fn q3(milli: i32) -> Q16 {
    Q16::from_bits(milli * 65536 / 1000)
}

/// One region: `SPAN_ROWS` spans of `len` pixels into a fresh band and
/// depth band (cleared outside the region), through `fill`'s span stage.
fn span_region<const N: usize, S: Shader<i32, N>>(
    mem: &mut Memory,
    shader: S,
    len: u32,
    z: i32,
    dz: i32,
    a: [i32; N],
    da: [i32; N],
) -> Result<(), FrameError> {
    let mut fb = FrameBuf::<Rgb565Be>::band(&mut mem.pixels[..], WIDTH, 0, BAND_ROWS)?;
    let mut db = DepthBuffer::<Depth16>::new(&mut mem.depth[..], WIDTH, 0, BAND_ROWS)?;
    let mut fill =
        Fill::new(&mut fb, Some(&mut db), shader).map_err(|e| FrameError::Render(e.into()))?;
    let x0 = (WIDTH - SPAN_LONG) / 2;
    yield_marker();
    for y in 0..SPAN_ROWS {
        // Opaque values: the loop is compiled as for spans of a triangle.
        let s = black_box(Span {
            y,
            x0,
            x1: x0 + len,
            z,
            dz,
            a,
            da,
        });
        fill.span(&s);
    }
    yield_marker();
    cortex_m::asm::sev();
    if fill.drawn() != SPAN_ROWS * len {
        return Err(FrameError::Render(fixshade::render::RenderError::Window));
    }
    Ok(())
}

/// Measures the span loops alone (see the crate docs): flat, Gouraud
/// (one grey level) and Phong (normal only, one directional light with
/// a specular term), each with a long and a 1-pixel span per row. Not
/// inlined: its locals (shades, kernels) stay out of `main`'s stack frame
/// while the scenes render.
#[inline(never)]
fn span_loops(mem: &mut Memory) -> Result<(), FrameError> {
    let material = Material {
        color: Vec3::new(q3(900), q3(700), q3(500)),
        ka: q3(100),
        kd: q3(700),
        ks: q3(500),
        shininess: q3(20_000),
    };
    let light = Light::directional(Vec3::new(q3(300), q3(400), q3(866)), q3(1000));
    let shade = Shade::new(
        &material,
        q3(200),
        &[light],
        Specular::Phong,
        Viewer::Infinite,
    )
    .map_err(|_| FrameError::Render(fixshade::render::RenderError::Window))?;
    let z = 1 << 28;
    let dz = 1 << 16;
    for len in [SPAN_LONG, 1] {
        span_region::<0, _>(mem, Flat(Rgb8::new(200, 100, 50)), len, z, dz, [], [])?;
    }
    hprintln!("span flat rows={} long={} short=1", SPAN_ROWS, SPAN_LONG);
    for len in [SPAN_LONG, 1] {
        span_region(mem, GouraudMono, len, z, dz, [40 << 16], [1 << 14])?;
    }
    hprintln!("span gouraud rows={} long={} short=1", SPAN_ROWS, SPAN_LONG);
    // A normal sweeping across the highlight along the span.
    let n = [
        Fast::unit(q3(-300)),
        Fast::unit(q3(100)),
        Fast::unit(q3(950)),
    ];
    let dn = [Fast::unit(q3(3)), 0, -Fast::unit(q3(1))];
    for len in [SPAN_LONG, 1] {
        span_region(
            mem,
            PhongShader::<Fast>::new(&shade, false),
            len,
            z,
            dz,
            n,
            dn,
        )?;
    }
    hprintln!("span phong rows={} long={} short=1", SPAN_ROWS, SPAN_LONG);
    phong_kernel_spans(mem, &material, n, dn)
}

/// The Phong span kernel (`render::PhongKernel`) on the same sweep: 1, 2
/// and 4 directional lights with the viewer at infinity, and one point
/// light with a local viewer (the eye-space position stepping too).
fn phong_kernel_spans(
    mem: &mut Memory,
    material: &Material<Q16>,
    n: [i32; 3],
    dn: [i32; 3],
) -> Result<(), FrameError> {
    let bad = || FrameError::Render(fixshade::render::RenderError::Window);
    let dir = [
        Light::directional(Vec3::new(q3(300), q3(400), q3(866)), q3(1000)),
        Light::directional(Vec3::new(q3(-500), q3(200), q3(800)), q3(500)),
        Light::directional(Vec3::new(q3(100), q3(-600), q3(700)), q3(400)),
        Light::directional(Vec3::new(q3(700), q3(100), q3(600)), q3(300)),
    ];
    // A surface point 5 units in front of the eye, moving 1/100 unit per
    // pixel; the point light 2 units towards the eye, up and to the right.
    let p = [0, 0, -5 << 16];
    let dp = [655, 0, 0];
    let point = [Light::point(
        Vec3::new(q3(1500), q3(1000), q3(-3000)),
        q3(1000),
    )];
    let cases: [(&str, &[Light<Q16>], Viewer); 4] = [
        ("phong-k1", &dir[..1], Viewer::Infinite),
        ("phong-k2", &dir[..2], Viewer::Infinite),
        ("phong-k4", &dir[..4], Viewer::Infinite),
        ("phong-kpoint", &point[..], Viewer::Local),
    ];
    for (name, lights, viewer) in cases {
        let shade =
            Shade::new(material, q3(200), lights, Specular::Phong, viewer).map_err(|_| bad())?;
        let kernel = PhongKernel::new(&shade).map_err(|_| bad())?;
        for len in [SPAN_LONG, 1] {
            let mut fb = FrameBuf::<Rgb565Be>::band(&mut mem.pixels[..], WIDTH, 0, BAND_ROWS)?;
            let mut db = DepthBuffer::<Depth16>::new(&mut mem.depth[..], WIDTH, 0, BAND_ROWS)?;
            let mut fill = PhongFill::new(&mut fb, Some(&mut db), &kernel)
                .map_err(|e| FrameError::Render(e.into()))?;
            let x0 = (WIDTH - SPAN_LONG) / 2;
            let mut a = [0i32; 6];
            let mut da = [0i32; 6];
            a[..3].copy_from_slice(&n);
            a[3..].copy_from_slice(&p);
            da[..3].copy_from_slice(&dn);
            da[3..].copy_from_slice(&dp);
            // The point light's spans from their triangle's quadratics
            // (`TriQuad`), as the renderers draw them: a triangle whose
            // normal and position step along x alone, covering the
            // region (vertices at the centres of pixels (x0, 0), (x0 +
            // 2 SPAN_LONG, 0) and (x0, 2 SPAN_ROWS)).
            if kernel.wants_tri() {
                let sub = SubpixelBits::DEFAULT;
                let c = |px: u32| ((px as i32) << sub.get()) + (1 << (sub.get() - 1));
                let far = |v: [i32; 3], d: [i32; 3]| {
                    [0, 1, 2].map(|k| v[k] + d[k] * 2 * SPAN_LONG as i32)
                };
                let v = [
                    ([c(x0), c(0)], n, p),
                    ([c(x0 + 2 * SPAN_LONG), c(0)], far(n, dn), far(p, dp)),
                    ([c(x0), c(2 * SPAN_ROWS)], n, p),
                ];
                fill.tri = TriQuad::new(&kernel, v, sub, false);
                if !fill.tri.ok() {
                    return Err(bad());
                }
            }
            yield_marker();
            for y in 0..SPAN_ROWS {
                let s = black_box(Span {
                    y,
                    x0,
                    x1: x0 + len,
                    z: 1 << 28,
                    dz: 1 << 16,
                    a,
                    da,
                });
                fill.span(&s);
            }
            yield_marker();
            cortex_m::asm::sev();
            if fill.drawn() != SPAN_ROWS * len {
                return Err(bad());
            }
        }
        hprintln!(
            "span {} rows={} long={} short=1",
            name,
            SPAN_ROWS,
            SPAN_LONG
        );
    }
    Ok(())
}

/// A band buffer on a word boundary.
#[repr(C, align(4))]
struct Words<T>(T);

#[cfg(not(any(feature = "profiled", feature = "knobs")))]
#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` (the entry runs once),
    // in .bss.
    static mut PIXELS: Words<[Pixel; BAND_PIXELS]> = Words([0; BAND_PIXELS]);
    static mut DEPTH: Words<[u16; DEPTH_PIXELS]> = Words([0; DEPTH_PIXELS]);
    static mut STORAGE: FrameStorage = FrameStorage::EMPTY;
    static mut POOL: BandPool = BandPool::new();
    let mut mem = Memory {
        pixels: &mut PIXELS.0,
        depth: &mut DEPTH.0,
        storage: STORAGE,
        pool: POOL,
    };
    let status = match run(&mut mem) {
        Ok(()) => debug::EXIT_SUCCESS,
        Err(Failure::Startup(name, e)) => {
            hprintln!(
                "error: scene {} does not fit the firmware's workspace (capacities: {} vertices, {} values, {} triangles; it needs {:?}): {}",
                name,
                CAP.vertices,
                CAP.values,
                CAP.triangles,
                SCENES.iter().find(|s| s.name == name).map(|s| s.capacity),
                e
            );
            debug::EXIT_FAILURE
        }
        Err(Failure::Frame(name, e)) => {
            hprintln!("error: scene {}: {}", name, e);
            debug::EXIT_FAILURE
        }
    };
    qemu::exit(status)
}
