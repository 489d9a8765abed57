use fixshade::num::Fast;
use fixshade::render::{prepare, BandState, Capacity, Frame, Workspace};
use fixshade::scene::Scene;
use fixshade::target::{BandBuf, Depth16, DepthFormat, Gray8, PixelFormat, Rgb565Be};
use fixshade_scenes::Crc32;

/// What one frame of a turn used.
#[derive(Debug, Default, Clone, Copy)]
struct Use {
    vertices: usize,
    triangles: usize,
    bytes: usize,
    peak: usize,
    setups: u32,
    pixels: u32,
    covered: u32,
    crc: u32,
}

/// Renders `frame` band by band, the board's way, with its pool.
fn bands<F: PixelFormat, const CAP: usize, const V: usize, const Q: usize>(
    frame: &Frame<'_, Fast>,
    scene: &fixshade::scene::Scene<'_, '_, fixshade::num::Q16>,
    pool: &mut fixshade::render::Pool<i32, CAP, V, Q>,
    order: &mut [u16],
    w: u32,
    rows: u32,
) -> Use {
    let n = (w * rows) as usize;
    let mut px = vec![F::Raw::default(); n];
    let mut z = vec![0u16; n];
    let mut band = BandBuf::<F>::new(&mut px, Some(&mut z), w, rows).unwrap();
    let mut state = BandState::new(order, pool);
    let mut bands = frame.bands(scene, &mut state, rows).unwrap();
    let mut u = Use::default();
    // The firmware's frame checksum (CRC-32/ISO-HDLC, from the `crc` crate).
    let mut crc = Crc32::new();
    while bands.next_band(&mut band).unwrap().is_some() {
        crc.update(band.bytes());
        u.covered += band
            .depth()
            .unwrap()
            .iter()
            .filter(|&&d| d != Depth16::CLEAR)
            .count() as u32;
    }
    u.crc = crc.finish();
    u.peak = bands.active_peak();
    u.setups = bands.stats().triangles;
    u.pixels = bands.stats().pixels;
    u.vertices = frame.vertex_count();
    u.triangles = frame.triangle_count();
    u.bytes = frame.bytes_used();
    u
}

fn max(a: Use, b: Use) -> Use {
    Use {
        vertices: a.vertices.max(b.vertices),
        triangles: a.triangles.max(b.triangles),
        bytes: a.bytes.max(b.bytes),
        peak: a.peak.max(b.peak),
        setups: a.setups.max(b.setups),
        pixels: a.pixels.max(b.pixels),
        covered: a.covered.max(b.covered),
        crc: 0,
    }
}

/// Every frame of a board's turn (the scene module's `camera`, `lights`,
/// `objects(i)` for `i` in `0..FRAMES`), prepared in `$store` and rendered
/// in the board's bands of pixel format `$fmt` with `$pool`, printed;
/// checks that the pool holds every active triangle (each set up once)
/// and that each frame covers more than `$covered` pixels. Gives each
/// frame's [`Use`] and the most of each figure.
macro_rules! turn {
    ($name:literal, $fmt:ty, $store:ident, $pool:ident, $covered:expr) => {{
        let camera = camera().unwrap();
        let lights = lights();
        let mut most = Use::default();
        let mut turn = Vec::new();
        for i in 0..FRAMES {
            let objects = objects(i);
            let scene = Scene::new(camera, &objects, &lights, AMBIENT);
            let (ws, order) = $store.split();
            let frame = prepare::<Fast>(&scene, W, H, ws).unwrap();
            let u = bands::<$fmt, POOL_SLOTS, POOL_VALUES, 0>(
                &frame, &scene, &mut $pool, order, W, ROWS,
            );
            println!("{} frame {i:2}: crc 0x{:08x} {u:?}", $name, u.crc);
            turn.push(u);
            most = max(most, u);
        }
        println!("{} turn, most: {most:?}", $name);
        for (i, u) in turn.iter().enumerate() {
            assert!(u.peak <= POOL_SLOTS, "frame {i}: {u:?}");
            assert_eq!(u.setups as usize, u.triangles, "frame {i}");
            assert!(
                u.covered > $covered && u.pixels >= u.covered,
                "frame {i}: {u:?}"
            );
        }
        (turn, most)
    }};
}

/// Frame `i` of the firmware animation's turn of `bunny-gouraud`
/// (examples/firmware/src/bin/animate.rs: every object turned by
/// `round(2π·i/24)` in Q16 more about Y), rendered in the Pico's bands.
fn firmware_frame(i: u32, ws: Workspace<'_, i32>, order: &mut [u16]) -> Use {
    use fixshade::geom::{Affine, Vec3};
    use fixshade::num::Q16;
    let spec = fixshade_scenes::SCENES
        .iter()
        .find(|s| s.name == "bunny-gouraud")
        .unwrap();
    let angle = Q16::from_bits(((411_775 * i64::from(i) + 12) / 24) as i32);
    let objects: Vec<_> = spec
        .objects
        .iter()
        .map(|o| {
            let r = o.rotation;
            fixshade::scene::Object {
                transform: Affine::from_parts(
                    o.scale,
                    Vec3::new(r.x, r.y + angle, r.z),
                    o.translation,
                ),
                ..o.object()
            }
        })
        .collect();
    let scene = spec.scene(spec.camera().unwrap(), &objects);
    let frame = prepare::<Fast>(&scene, spec.width, spec.height, ws).unwrap();
    let mut pool = Box::new(fixshade_scenes::BandPool::new());
    bands::<
        Rgb565Be,
        { fixshade_scenes::POOL_SLOTS },
        { fixshade_scenes::POOL_VALUES },
        { fixshade_scenes::QUAD_SLOTS },
    >(
        &frame,
        &scene,
        &mut pool,
        order,
        spec.width,
        fixshade_scenes::BAND_ROWS,
    )
}

#[test]
fn pico_turn_fits_and_is_the_firmware_animation() {
    use crate::pico::*;
    let mut store = Box::new(Store::EMPTY);
    let mut pool = Box::new(BandPool::new());
    let (turn, most) = turn!("pico", Rgb565Be, store, pool, 5000);
    for (i, u) in turn.iter().enumerate() {
        // The very frame the firmware animation renders (and QEMU measures).
        let (ws, order) = store.split();
        let f = firmware_frame(i as u32, ws, order);
        assert_eq!(
            (u.crc, u.covered, u.pixels),
            (f.crc, f.covered, f.pixels),
            "frame {i}"
        );
    }
    // The figures the scene file and the README state.
    assert_eq!(most.peak, PICO_PEAK);
    assert_eq!(
        (most.vertices, most.triangles, most.bytes),
        (1839, 1574, 18_386)
    );
    assert_eq!(
        [turn[0].crc, turn[1].crc, turn[2].crc],
        [0xca58_1561, 0xf462_8b76, 0xb13f_664f]
    );
    assert_eq!(turn.iter().map(|u| u.peak).min(), Some(49));
    assert!(most.vertices <= CAPACITY.vertices && most.triangles <= CAPACITY.triangles);
}

/// The Pico turn's active-triangle peak (pico-st7789/src/scene.rs).
const PICO_PEAK: usize = 69;

#[test]
fn blackpill_turn_fits() {
    use crate::blackpill::*;
    let mut store = Store::EMPTY;
    let mut pool = BandPool::new();
    let (turn, most) = turn!("blackpill", Gray8, store, pool, 1500);
    assert_eq!(most.peak, BLACKPILL_PEAK);
    assert_eq!((most.vertices, most.triangles, most.bytes), (60, 18, 1_956));
    assert_eq!(turn.iter().map(|u| u.peak).min(), Some(6));
    assert_eq!(turn.iter().map(|u| u.pixels).min(), Some(2376));
    assert_eq!(most.pixels, 2488);
    assert!(most.vertices <= CAPACITY.vertices && most.triangles <= CAPACITY.triangles);
}

/// The Black Pill turn's active-triangle peak (blackpill-ssd1306/src/scene.rs).
const BLACKPILL_PEAK: usize = 12;

/// The memory figures the READMEs state: the pools and the workspaces.
#[test]
fn memory_figures() {
    use core::mem::size_of;
    // The workspace (4-byte values, a byte per triangle number, 6 per
    // made triangle) and the band order (a `u16` per triangle number):
    // together the board's `Store`.
    let parts = |c: Capacity, store: usize| {
        let order = 2 * c.triangles;
        assert_eq!(c.bytes(4), store);
        (store - order, order)
    };
    let pico = (
        size_of::<crate::pico::BandPool>(),
        parts(crate::pico::CAPACITY, size_of::<crate::pico::Store>()),
    );
    let blackpill = (
        size_of::<crate::blackpill::BandPool>(),
        parts(
            crate::blackpill::CAPACITY,
            size_of::<crate::blackpill::Store>(),
        ),
    );
    println!("pool, workspace, order bytes: pico {pico:?}, blackpill {blackpill:?}");
    assert_eq!(pico, (11_200, (40_456, 7_348)));
    assert_eq!(blackpill, (3_008, (1_956, 72)));
}
