//! One bunny benchmark frame (clear + prepare + render in 16-row bands,
//! Gouraud, RGB565, 16-bit depth), in a function of its own so that
//! `valgrind --tool=callgrind --toggle-collect=*one_frame*` counts exactly
//! one frame's instructions.
//!
//! `cargo build --release --example bunny_frame && valgrind --tool=callgrind
//! --toggle-collect='*one_frame*' target/release/examples/bunny_frame [PROFILE]`

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::shapes::BUNNY;
use fixshade::num::{Fast, Precise, Profile, Real, F32, F64};
use fixshade::render::{prepare, BandState, Pool, RenderError, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{BandBuf, Rgb565Be, Rgb8};
use std::hint::black_box;

struct Mem<L> {
    xy: Vec<fixshade::render::ScreenXy>,
    vals: Vec<L>,
    tris: Vec<Tri>,
    colors: Vec<fixshade::target::Rgb8>,
    faces: Vec<u8>,
    band: Vec<u16>,
    z: Vec<u16>,
    order: Vec<u16>,
    pool: Box<Pool<L, 64, 8>>,
}

#[inline(never)]
fn one_frame<P: Profile>(scene: &Scene<'_, '_, P::Real>, m: &mut Mem<P::Lerp>) -> u32 {
    let ws = Workspace {
        xy: &mut m.xy,
        vals: &mut m.vals,
        tris: &mut m.tris,
        colors: &mut m.colors,
        faces: &mut m.faces,
    };
    let frame = prepare::<P>(scene, 240, 240, ws).expect("prepare");
    let mut crc = 0u32;
    let mut band = BandBuf::<Rgb565Be>::new(&mut m.band, Some(&mut m.z), 240, 16).expect("band");
    let mut state = BandState::new(&mut m.order, &mut m.pool);
    let stats = frame
        .render_bands(scene, &mut state, &mut band, |b| {
            crc = crc.wrapping_add(b.pixels().len() as u32);
            Ok::<(), RenderError>(())
        })
        .expect("render");
    stats.pixels ^ crc
}

fn run<P: Profile>() {
    let r = |v: f32| P::Real::from_f32(v);
    let camera = Camera::look_at_f32(
        [0.0, 0.0, 3.922],
        [0.0; 3],
        [0.0, 1.0, 0.0],
        45.0,
        1.0,
        Some(10.0),
    )
    .expect("camera");
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
        shading: Shading::Gouraud,
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
    let mut m = Mem {
        xy: vec![fixshade::render::ScreenXy::ZERO; 4000],
        vals: vec![P::Lerp::default(); 16000],
        tris: vec![Tri::default(); 4000],
        colors: vec![fixshade::target::Rgb8::BLACK; 4000],
        faces: vec![0; 4000],
        band: vec![0; 240 * 16],
        z: vec![0; 240 * 16],
        order: vec![0; 8000],
        pool: Box::new(Pool::new()),
    };
    println!(
        "{}: {} pixels",
        P::NAME,
        black_box(one_frame::<P>(black_box(&scene), &mut m))
    );
}

fn main() {
    match std::env::args().nth(1).as_deref().unwrap_or("fast") {
        "fast" => run::<Fast>(),
        "precise" => run::<Precise>(),
        "f32" => run::<F32>(),
        "f64" => run::<F64>(),
        p => eprintln!("unknown profile {p}"),
    }
}
