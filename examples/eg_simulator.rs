//! Renders the seed dodecahedron (Phong, fast profile) through
//! `embedded-graphics`: band by band into a `SimulatorDisplay<Rgb565>` (as a
//! firmware would into an SPI display driver) and, dithered, into a 128×64
//! `BinaryColor` display (an SSD1306-sized OLED); writes both as PNG. No
//! window is opened (the simulator is built without SDL).
//!
//! `cargo run --release --features embedded-graphics --example eg_simulator -- [OUT_DIR]`

use embedded_graphics_core::geometry::Size;
use embedded_graphics_core::pixelcolor::{BinaryColor, PixelColor, Rgb565};
use embedded_graphics_simulator::{BinaryColorTheme, OutputSettingsBuilder, SimulatorDisplay};
use fixshade::geom::{radians, Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::shapes::DODECAHEDRON;
use fixshade::num::{Fast, Real, Q16};
use fixshade::render::{prepare, BandState, Pool, RenderError, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::eg::{draw_band, FromShaded};
use fixshade::target::{BandBuf, Rgb565Be, Rgb8};
use std::error::Error;

fn render_to<C: PixelColor + FromShaded>(
    display: &mut SimulatorDisplay<C>,
    w: u32,
    h: u32,
) -> Result<u32, Box<dyn Error>> {
    let q = |n: i32, d: i32| Q16::from_ratio(n, d);
    let v = |x, y, z| Vec3::new(q(x, 1), q(y, 1), q(z, 1));
    let camera = Camera::look_at(
        v(0, 0, 6),
        Vec3::ZERO,
        v(0, 1, 0),
        radians(q(40, 1)),
        q(1, 2),
        None,
    )?;
    let material = Material {
        color: Vec3::new(q(1, 1), q(3, 10), q(2, 10)),
        ka: q(2, 10),
        kd: q(5, 10),
        ks: q(5, 10),
        shininess: q(25, 1),
    };
    let transform = Affine::from_parts(
        q(1, 1),
        Vec3::new(radians(q(20, 1)), radians(q(30, 1)), q(0, 1)),
        Vec3::ZERO,
    );
    let objects = [Object {
        mesh: DODECAHEDRON,
        transform,
        material,
        shading: Shading::Phong,
        cull_backfaces: true,
    }];
    let lights = [Light::point(v(2, 2, 4), q(1, 1))];
    let scene = Scene {
        camera,
        objects: &objects,
        lights: &lights,
        ambient: q(1, 1),
        specular: Specular::Phong,
        viewer: Viewer::Local,
        background: Rgb8::BLACK,
    };
    let (mut xy, mut vals, mut tris) = ([[0; 2]; 64], [0i32; 64 * 7], [Tri::default(); 64]);
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tris,
    };
    let frame = prepare::<Fast>(&scene, w, h, ws)?;
    let mut pixels = vec![[0u8; 2]; (w * 16) as usize];
    let mut depth = vec![0u16; (w * 16) as usize];
    let mut band = BandBuf::<Rgb565Be>::new(&mut pixels, Some(&mut depth), w, 16)?;
    let (mut order, mut pool) = ([0u16; 128], Pool::<i32, 32, 8>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let stats = frame.render_bands(&scene, &mut state, &mut band, |b| {
        // The simulator's DrawTarget never fails.
        let _ = draw_band(b, display);
        Ok::<(), RenderError>(())
    })?;
    Ok(stats.pixels)
}

fn main() -> Result<(), Box<dyn Error>> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    let mut tft = SimulatorDisplay::<Rgb565>::new(Size::new(240, 240));
    let n = render_to(&mut tft, 240, 240)?;
    tft.to_rgb_output_image(&OutputSettingsBuilder::new().scale(1).build())
        .save_png(dir.join("eg_rgb565.png"))?;
    let mut oled = SimulatorDisplay::<BinaryColor>::new(Size::new(128, 64));
    let m = render_to(&mut oled, 128, 64)?;
    oled.to_rgb_output_image(
        &OutputSettingsBuilder::new()
            .scale(2)
            .theme(BinaryColorTheme::OledWhite)
            .build(),
    )
    .save_png(dir.join("eg_oled.png"))?;
    println!(
        "wrote {0}/eg_rgb565.png ({n} pixels shaded) and {0}/eg_oled.png ({m} pixels, dithered)",
        dir.display()
    );
    Ok(())
}
