//! Link-time proof that fixshade's fixed-profile render path cannot panic.
//!
//! A firmware-like binary (cortex-m-rt, QEMU MPS2 memory map) that builds a
//! 3D scene with the `Fast` profile (`Precise` with `--features precise`):
//! the built-in `BUNNY` and `DODECAHEDRON` meshes in flat, Gouraud
//! (one-sided and two-sided) and Phong shading (two-sided), a point light
//! and a directional light, every value an integer ratio (no float). It
//! prepares each frame into static workspace buffers and renders it in
//! 16-row bands with a 16-bit depth band, checksumming each band.
//!
//! The `#[panic_handler]` calls a function that is declared but defined
//! nowhere (the technique of the `panic-never` crate): if any panic branch
//! survives optimisation, the handler is reachable and linking fails with
//! an undefined reference to
//! `fixshade_panic_branch_survived_optimisation`. With `--features
//! inspect` the handler exits through semihosting instead, so the ELF links
//! and `llvm-objdump`/`nm` show the remaining panic sites.
//!
//! The scene, the screen size and the band height pass through
//! [`core::hint::black_box`], so the optimiser cannot specialise the
//! library on this particular scene: what links panic-free here is the
//! render path for any scene, any mesh and any workspace sizes, not just
//! for these constants.
//!
//! Under QEMU (`cargo run --release --target thumbv6m-none-eabi`) it prints
//! one line per frame and exits with status 0, or 1 on a render error.
#![no_std]
#![no_main]

use core::hint::black_box;
use core::panic::PanicInfo;
use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hio};
use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::shapes::{BUNNY, DODECAHEDRON};
use fixshade::num::{Profile, Real};
use fixshade::render::{prepare, BandState, Pool, RenderError, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{BandBuf, Rgb565Be, Rgb8};

#[cfg(not(feature = "precise"))]
type P = fixshade::num::Fast;
#[cfg(feature = "precise")]
type P = fixshade::num::Precise;
type R = <P as Profile>::Real;
type L = <P as Profile>::Lerp;

/// Screen size and band height.
const WIDTH: u32 = 240;
const HEIGHT: u32 = 240;
const BAND_ROWS: u32 = 16;
const BAND_PIXELS: usize = (WIDTH * BAND_ROWS) as usize;
/// Active triangles kept from band to band.
const POOL: usize = 32;

/// Workspace capacities (the scene below uses about half of each; the
/// frame lines printed under QEMU give the figures).
const MAX_VERTS: usize = 8192;
const MAX_VALS: usize = 32768;
const MAX_TRIS: usize = 8192;

/// Frames rendered, each with another rotation and specular model.
const FRAMES: i32 = 4;

#[cfg(not(feature = "inspect"))]
#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    extern "Rust" {
        // Defined nowhere: linking fails if a panic branch is reachable.
        fn fixshade_panic_branch_survived_optimisation() -> !;
    }
    // SAFETY: never executed: the call only links when the optimiser has
    // proven this handler unreachable and removed it.
    unsafe { fixshade_panic_branch_survived_optimisation() }
}

#[cfg(feature = "inspect")]
#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    debug::exit(Err(()));
    loop {
        cortex_m::asm::bkpt();
    }
}

/// `num/den` in the profile's scalar (integer ratio, no float).
fn q(num: i32, den: i32) -> R {
    R::from_ratio(num, den)
}

fn v3(x: R, y: R, z: R) -> Vec3<R> {
    Vec3::new(x, y, z)
}

/// A line of ASCII built without `core::fmt` (whose padding code is not
/// the subject here).
struct Line {
    buf: [u8; 128],
    len: usize,
}

impl Line {
    fn new() -> Self {
        Self {
            buf: [0; 128],
            len: 0,
        }
    }

    fn text(&mut self, s: &str) -> &mut Self {
        for &b in s.as_bytes() {
            if let Some(slot) = self.buf.get_mut(self.len) {
                *slot = b;
                self.len += 1;
            }
        }
        self
    }

    fn dec(&mut self, v: u32) -> &mut Self {
        let mut digits = [0u8; 10];
        let (mut v, mut n) = (v, 0);
        loop {
            if let Some(d) = digits.get_mut(n) {
                *d = b'0' + (v % 10) as u8;
            }
            n += 1;
            v /= 10;
            if v == 0 || n == digits.len() {
                break;
            }
        }
        for &d in digits.iter().take(n).rev() {
            self.text(core::str::from_utf8(&[d]).unwrap_or("?"));
        }
        self
    }

    fn hex(&mut self, v: u32) -> &mut Self {
        self.text("0x");
        for k in (0..8).rev() {
            let d = ((v >> (4 * k)) & 15) as u8;
            let c = if d < 10 { b'0' + d } else { b'a' + d - 10 };
            self.text(core::str::from_utf8(&[c]).unwrap_or("?"));
        }
        self
    }

    fn print(&mut self) {
        self.text("\n");
        if let Ok(mut out) = hio::hstdout() {
            let _ = out.write_all(self.buf.get(..self.len).unwrap_or(&[]));
        }
        self.len = 0;
    }
}

/// FNV-1a over the band's bytes (a cheap checksum to print).
fn fnv1a(h: u32, pixels: &[u16]) -> u32 {
    pixels
        .iter()
        .flat_map(|p| p.to_ne_bytes())
        .fold(h, |h, b| (h ^ u32::from(b)).wrapping_mul(0x0100_0193))
}

/// What one frame produced.
struct Stats {
    checksum: u32,
    pixels: u32,
    triangles: u32,
    verts: u32,
    tris: u32,
}

/// Builds, prepares and renders frame `f` of the scene.
fn frame(
    f: i32,
    ws: Workspace<'_, L>,
    band: &mut [u16],
    depth: &mut [u16],
    order: &mut [u16],
    pool: &mut Pool<L, POOL, 8>,
) -> Result<Stats, RenderError> {
    // The eye at (0, 1/2, 4) looking at the origin, vertical field of view
    // 0.785 rad (45°), near plane 1, far plane 10.
    let camera = Camera::look_at(
        v3(R::ZERO, q(1, 2), R::from_i32(4)),
        Vec3::ZERO,
        v3(R::ZERO, R::ONE, R::ZERO),
        q(785, 1000),
        R::ONE,
        Some(R::from_i32(10)),
    )?;
    let white = v3(R::ONE, R::ONE, R::ONE);
    let matte = Material {
        color: v3(q(9, 10), q(9, 10), q(9, 10)),
        ka: R::ONE,
        kd: q(8, 10),
        ks: R::ZERO,
        shininess: R::ONE,
    };
    let shiny = Material {
        color: v3(q(3, 10), q(6, 10), R::ONE),
        ka: R::ONE,
        kd: q(7, 10),
        ks: q(6, 10),
        shininess: R::from_i32(40),
    };
    // Rotation about y: f · 0.3 rad.
    let turn = |dx: i32| v3(q(dx, 10), q(3 * f, 10), R::ZERO);
    let objects = [
        Object {
            mesh: BUNNY,
            transform: Affine::from_parts(q(7, 10), turn(0), v3(q(-9, 10), q(-1, 10), R::ZERO)),
            material: matte,
            shading: Shading::Gouraud,
            cull_backfaces: true,
        },
        Object {
            mesh: BUNNY,
            transform: Affine::from_parts(q(7, 10), turn(2), v3(q(9, 10), q(-1, 10), R::ZERO)),
            material: shiny,
            shading: Shading::Phong,
            cull_backfaces: false,
        },
        Object {
            mesh: DODECAHEDRON,
            transform: Affine::from_parts(q(1, 3), turn(5), v3(q(-6, 10), q(9, 10), -R::ONE)),
            material: shiny,
            shading: Shading::Flat,
            cull_backfaces: true,
        },
        Object {
            // Crosses the near plane (eye at z = 4, near 1): clipped.
            mesh: DODECAHEDRON,
            transform: Affine::from_parts(q(1, 2), turn(1), v3(q(6, 10), q(9, 10), q(29, 10))),
            material: matte,
            shading: Shading::Gouraud,
            cull_backfaces: false,
        },
    ];
    let lights = [
        Light {
            color: v3(R::ONE, q(9, 10), q(8, 10)),
            ..Light::point(v3(R::from_i32(2), R::from_i32(3), R::from_i32(4)), q(8, 10))
        },
        Light {
            color: white,
            ..Light::directional(v3(-R::ONE, R::ONE, q(1, 2)), q(5, 10))
        },
    ];
    let scene = Scene {
        camera,
        objects: &objects,
        lights: &lights,
        ambient: q(15, 100),
        specular: if f % 2 == 0 {
            Specular::Phong
        } else {
            Specular::Blinn
        },
        viewer: if f < 2 {
            Viewer::Local
        } else {
            Viewer::Infinite
        },
        background: Rgb8::new(0, 0, 32),
    };
    // Hide the scene and sizes from the optimiser: the proof then covers
    // any scene, not just this one.
    let scene = black_box(scene);
    let (w, h, rows) = black_box((WIDTH, HEIGHT, BAND_ROWS));
    let frame = prepare::<P>(&scene, w, h, ws)?;
    let mut checksum = 0x811c_9dc5;
    let mut band = BandBuf::<Rgb565Be>::new(band, Some(depth), w, rows)?;
    let mut state = BandState::new(order, pool);
    let stats = frame.render_bands(&scene, &mut state, &mut band, |fb| {
        checksum = fnv1a(checksum, fb.pixels());
        Ok::<(), RenderError>(())
    })?;
    Ok(Stats {
        checksum,
        pixels: stats.pixels,
        triangles: stats.triangles,
        verts: frame.vertex_count() as u32,
        tris: frame.triangle_count() as u32,
    })
}

// cortex-m-rt passes each `static mut` below as an argument.
#[allow(clippy::too_many_arguments)]
#[entry]
fn main() -> ! {
    // cortex-m-rt turns these into `&'static mut` references (safe code).
    static mut XY: [fixshade::render::ScreenXy; MAX_VERTS] =
        [fixshade::render::ScreenXy::ZERO; MAX_VERTS];
    static mut VALS: [L; MAX_VALS] = [0; MAX_VALS];
    static mut TRIS: [Tri; MAX_TRIS] = [Tri::EMPTY; MAX_TRIS];
    static mut COLORS: [fixshade::target::Rgb8; MAX_TRIS] =
        [fixshade::target::Rgb8::BLACK; MAX_TRIS];
    static mut FACES: [u8; MAX_TRIS] = [0; MAX_TRIS];
    static mut BAND: [u16; BAND_PIXELS] = [0; BAND_PIXELS];
    static mut DEPTH: [u16; BAND_PIXELS] = [0; BAND_PIXELS];
    // The band state: triangle order and active pool.
    static mut BAND_STATE: ([u16; 2 * MAX_TRIS], Pool<L, POOL, 8>) =
        ([0; 2 * MAX_TRIS], Pool::new());

    let mut line = Line::new();
    line.text("fixshade panic-never: profile ")
        .text(P::NAME)
        .print();
    let mut ok = true;
    #[cfg(feature = "canary")]
    {
        // An index the optimiser cannot bound: keeps a panic branch.
        let i = black_box(2usize);
        ok &= [true, true][i];
    }
    for f in 0..FRAMES {
        let ws = Workspace {
            xy: &mut XY[..],
            vals: &mut VALS[..],
            tris: &mut TRIS[..],
            colors: &mut COLORS[..],
            faces: &mut FACES[..],
        };
        match frame(
            f,
            ws,
            &mut BAND[..],
            &mut DEPTH[..],
            &mut BAND_STATE.0[..],
            &mut BAND_STATE.1,
        ) {
            Ok(s) => {
                line.text("frame ")
                    .dec(f as u32)
                    .text(" checksum=")
                    .hex(s.checksum)
                    .text(" pixels=")
                    .dec(s.pixels)
                    .text(" triangles_set_up=")
                    .dec(s.triangles)
                    .text(" prepared_vertices=")
                    .dec(s.verts)
                    .text(" prepared_triangles=")
                    .dec(s.tris)
                    .print();
                ok &= s.pixels > 0;
            }
            Err(_) => {
                line.text("frame ").dec(f as u32).text(" FAILED").print();
                ok = false;
            }
        }
    }
    debug::exit(if ok { Ok(()) } else { Err(()) });
    loop {
        cortex_m::asm::bkpt();
    }
}
