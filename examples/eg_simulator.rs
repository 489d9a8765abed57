//! Renders the seed dodecahedron (Phong, fast profile) through
//! `embedded-graphics`: band by band into a `SimulatorDisplay<Rgb565>` (as a
//! firmware would into an SPI display driver) and, dithered, into a 128×64
//! `BinaryColor` display (an SSD1306-sized OLED); writes them as PNG. No
//! window is opened (the simulator is built without SDL).
//!
//! The material is a pale yellow (luma ~0.9 of white): a saturated red's
//! luma is below a third, and dithered to 1 bit its faces become one even
//! field of sparse dots. The OLED frame is written twice: dithered as
//! shaded (`eg_oled_linear.png`) and through the level mapping
//! `Levels::ONE_BIT` (`eg_oled.png`), beside the same 128×64 frame in
//! RGB565 (`eg_oled_rgb565.png`).
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
use fixshade::target::eg::{draw_band_with, FromShaded, Levels};
use fixshade::target::{BandBuf, Rgb565Be, Rgb8};
use std::error::Error;

fn render_to<C: PixelColor + FromShaded>(
    display: &mut SimulatorDisplay<C>,
    w: u32,
    h: u32,
    levels: &Levels,
) -> Result<u32, Box<dyn Error>> {
    let q = |n: i32, d: i32| Q16::from_ratio(n, d);
    let v = |x, y, z| Vec3::new(q(x, 1), q(y, 1), q(z, 1));
    // The 64-row OLED gets a narrower field of view: the shape fills ~60
    // rows instead of ~30.
    let fov = if h < 100 { 20 } else { 40 };
    let camera = Camera::look_at(
        v(0, 0, 6),
        Vec3::ZERO,
        v(0, 1, 0),
        radians(q(fov, 1)),
        q(1, 2),
        None,
    )?;
    let material = Material {
        color: Vec3::new(q(1, 1), q(9, 10), q(6, 10)),
        ka: q(2, 10),
        kd: q(7, 10),
        ks: q(4, 10),
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
    let (mut xy, mut vals, mut tris) = (
        [fixshade::render::ScreenXy::ZERO; 64],
        [0i32; 64 * 7],
        [Tri::default(); 64],
    );
    let mut colors = vec![fixshade::target::Rgb8::BLACK; tris.len()];
    let mut faces = [0u8; 64];
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tris,
        colors: &mut colors,
        faces: &mut faces,
    };
    let frame = prepare::<Fast>(&scene, w, h, ws)?;
    let mut pixels = vec![0u16; (w * 16) as usize];
    let mut depth = vec![0u16; (w * 16) as usize];
    let mut band = BandBuf::<Rgb565Be>::new(&mut pixels, Some(&mut depth), w, 16)?;
    let (mut order, mut pool) = ([0u16; 128], Pool::<i32, 32, 8>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let stats = frame.render_bands(&scene, &mut state, &mut band, |b| {
        // The simulator's DrawTarget never fails.
        let _ = draw_band_with(b, display, levels);
        Ok::<(), RenderError>(())
    })?;
    Ok(stats.pixels)
}

fn main() -> Result<(), Box<dyn Error>> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    let rgb = |scale| OutputSettingsBuilder::new().scale(scale).build();
    let mut tft = SimulatorDisplay::<Rgb565>::new(Size::new(240, 240));
    let n = render_to(&mut tft, 240, 240, &Levels::IDENTITY)?;
    tft.to_rgb_output_image(&rgb(1))
        .save_png(dir.join("eg_rgb565.png"))?;
    // The OLED's frame in colour, for comparison.
    let mut small = SimulatorDisplay::<Rgb565>::new(Size::new(128, 64));
    let m = render_to(&mut small, 128, 64, &Levels::IDENTITY)?;
    small
        .to_rgb_output_image(&rgb(2))
        .save_png(dir.join("eg_oled_rgb565.png"))?;
    let oled_theme = OutputSettingsBuilder::new()
        .scale(2)
        .theme(BinaryColorTheme::OledWhite)
        .build();
    let mut lit = [0; 2];
    for (levels, name, lit) in [
        (Levels::IDENTITY, "eg_oled_linear.png"),
        (Levels::ONE_BIT, "eg_oled.png"),
    ]
    .into_iter()
    .zip(&mut lit)
    .map(|((l, n), c)| (l, n, c))
    {
        let mut oled = SimulatorDisplay::<BinaryColor>::new(Size::new(128, 64));
        render_to(&mut oled, 128, 64, &levels)?;
        *lit = (0..64)
            .flat_map(|y| (0..128).map(move |x| (x, y)))
            .filter(|&(x, y)| {
                oled.get_pixel(embedded_graphics_core::geometry::Point::new(x, y))
                    == BinaryColor::On
            })
            .count();
        oled.to_rgb_output_image(&oled_theme)
            .save_png(dir.join(name))?;
    }
    println!(
        "wrote {0}/eg_rgb565.png ({n} pixels shaded), {0}/eg_oled_rgb565.png ({m} shaded), \
         {0}/eg_oled_linear.png ({1} pixels lit) and {0}/eg_oled.png (Levels::ONE_BIT, {2} lit)",
        dir.display(),
        lit[0],
        lit[1]
    );
    Ok(())
}
