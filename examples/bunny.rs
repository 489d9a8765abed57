//! Renders the bunny benchmark scene (Gouraud, one directional light) with
//! a chosen profile, in 16-row bands, and writes a PNG.
//!
//! `cargo run --release --example bunny -- [fast|precise|f32|f64] [OUT.png]`

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::shapes::BUNNY;
use fixshade::num::{Fast, Precise, Profile, Real, F32, F64};
use fixshade::render::{prepare, BandState, Pool, RenderError, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{BandBuf, PixelFormat, Rgb565Be, Rgb8};
use std::{error::Error, fs::File, io::BufWriter};

const W: u32 = 240;

fn run<P: Profile>(out: &str, shading: Shading) -> Result<(), Box<dyn Error>> {
    let r = |v: f32| P::Real::from_f32(v);
    let camera = Camera::look_at_f32(
        [0.0, 0.0, 3.922],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        45.0,
        1.0,
        Some(10.0),
    )?;
    let material = Material {
        color: Vec3::new(r(1.0), r(1.0), r(1.0)),
        ka: r(1.0),
        kd: r(1.0),
        ks: r(0.0),
        shininess: r(1.0),
    };
    let objects = [Object {
        mesh: BUNNY,
        transform: Affine::IDENTITY,
        material,
        shading,
        cull_backfaces: true,
    }];
    let lights = [Light::directional(Vec3::from_f32([1.0, 1.0, 1.0]), r(0.8))];
    let scene = Scene {
        camera,
        objects: &objects,
        lights: &lights,
        ambient: r(0.2),
        specular: Specular::Phong,
        viewer: Viewer::Local,
        background: Rgb8::BLACK,
    };
    let (mut xy, mut vals, mut tris) = (
        vec![fixshade::render::ScreenXy::ZERO; 8000],
        vec![P::Lerp::default(); 32000],
        vec![Tri::default(); 8000],
    );
    let mut colors = vec![fixshade::target::Rgb8::BLACK; tris.len()];
    let mut faces = vec![0u8; tris.len()];
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tris,
        colors: &mut colors,
        faces: &mut faces,
    };
    let frame = prepare::<P>(&scene, W, W, ws)?;
    let mut band = vec![0u16; (W * 16) as usize];
    let mut z = vec![0u16; (W * 16) as usize];
    let mut rgb = Vec::new();
    let mut buf = BandBuf::<Rgb565Be>::new(&mut band, Some(&mut z), W, 16)?;
    let mut order = vec![0u16; 2 * frame.triangle_count()];
    let mut pool = Box::new(Pool::<P::Lerp, 64, 8>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let stats = frame.render_bands(&scene, &mut state, &mut buf, |b| {
        rgb.extend(b.pixels().iter().flat_map(|&p| {
            let c = Rgb565Be::decode(p);
            [c.r, c.g, c.b]
        }));
        Ok::<(), RenderError>(())
    })?;
    let mut enc = png::Encoder::new(BufWriter::new(File::create(out)?), W, W);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(&rgb)?;
    println!(
        "{}: {} prepared vertices, {} triangles, {} bytes; drew {} pixels",
        P::NAME,
        frame.vertex_count(),
        frame.triangle_count(),
        frame.bytes_used(),
        stats.pixels
    );
    Ok(())
}

fn main() -> Result<(), Box<dyn Error>> {
    let profile = std::env::args().nth(1).unwrap_or_else(|| "precise".into());
    let out = std::env::args()
        .nth(2)
        .unwrap_or_else(|| "bunny.png".into());
    let shading = Shading::Gouraud;
    match profile.as_str() {
        "fast" => run::<Fast>(&out, shading),
        "precise" => run::<Precise>(&out, shading),
        "f32" => run::<F32>(&out, shading),
        "f64" => run::<F64>(&out, shading),
        p => Err(format!("unknown profile {p}").into()),
    }
}
