//! Perspective-correct interpolation against affine, measured against the
//! ideal reference (which interpolates perspective-correctly) on a floor
//! receding from the eye, with colours varying along it.

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, Material, Specular, Viewer};
use fixshade::mesh::Mesh;
use fixshade::num::{F64Pc, Fast, FastPc, Precise, PrecisePc, Profile, Real, F64};
use fixshade::render::{prepare, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{Depth16, FrameBuf, Rgb8, Rgb888, Target};
use fixshade_host::ideal::{self, IdealScene};

const W: u32 = 120;
const H: u32 = 90;
/// A floor quad from z = 1.9 (near the eye at z = 2.2) to z = -1.9 (far),
/// normals tilted so Gouraud colours vary strongly along it.
const POS: [[i16; 3]; 4] = [
    [-16000, -8000, 31000],
    [16000, -8000, 31000],
    [16000, -8000, -31000],
    [-16000, -8000, -31000],
];
/// One normal per vertex: up at the near edge, towards +z at the far one.
const NRM: [[i16; 3]; 4] = [[0, 16384, 0], [0, 16384, 0], [0, 0, 16384], [0, 0, 16384]];
const TRIS: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

fn core_frame<P: Profile>(shading: Shading) -> Vec<[u8; 3]> {
    let mesh = Mesh::new(&POS, &TRIS, Some(&NRM)).unwrap();
    let r = |v: f32| P::Real::from_f32(v);
    let m = Material {
        color: Vec3::from_f32([1.0; 3]),
        ka: r(0.1),
        kd: r(0.9),
        ks: r(0.0),
        shininess: r(1.0),
    };
    let objs = [Object {
        mesh,
        transform: Affine::IDENTITY,
        material: m,
        shading,
        cull_backfaces: false,
    }];
    let lights = [Light::directional(Vec3::from_f32([0.0, 0.0, 1.0]), r(1.0))];
    let camera = Camera::look_at_f32(
        [0.0, 0.0, 2.2],
        [0.0, -0.6, 0.0],
        [0.0, 1.0, 0.0],
        70.0,
        0.1,
        None,
    )
    .unwrap();
    let scene = Scene {
        camera,
        objects: &objs,
        lights: &lights,
        ambient: r(1.0),
        specular: Specular::Phong,
        viewer: Viewer::Infinite,
        background: Rgb8::BLACK,
    };
    let (mut xy, mut vals, mut tris) = (
        vec![fixshade::render::ScreenXy::ZERO; 64],
        vec![P::Lerp::default(); 512],
        vec![Tri::default(); 64],
    );
    let mut colors = vec![fixshade::target::Rgb8::BLACK; tris.len()];
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tris,
        colors: &mut colors,
    };
    let frame = prepare::<P>(&scene, W, H, ws).unwrap();
    let mut px = vec![[0u8; 3]; (W * H) as usize];
    let mut fb = FrameBuf::<Rgb888>::new(&mut px, W, H).unwrap();
    fb.clear(Rgb8::BLACK);
    frame.render::<_, Depth16>(&scene, &mut fb, None).unwrap();
    px
}

fn ideal_frame(shading: ideal::Shading) -> Vec<[u8; 3]> {
    let v = |i: usize, n: usize| ideal::Vertex {
        position: POS[i].map(|c| c as f64 / 16384.0),
        normal: NRM[n].map(|c| c as f64 / 16384.0),
    };
    let tri = |t: usize| [0, 1, 2].map(|c| v(TRIS[t][c] as usize, TRIS[t][c] as usize));
    let scene = IdealScene {
        width: W,
        height: H,
        background: [0.0; 3],
        camera: ideal::Camera {
            eye: [0.0, 0.0, 2.2],
            target: [0.0, -0.6, 0.0],
            up: [0.0, 1.0, 0.0],
            fov_y_deg: 70.0,
            near: 0.1,
            far: None,
        },
        ambient: 1.0,
        specular: ideal::SpecularModel::Phong,
        lights: vec![ideal::Light {
            kind: ideal::LightKind::Directional {
                direction: [0.0, 0.0, 1.0],
            },
            intensity: 1.0,
            color: [1.0; 3],
        }],
        objects: vec![ideal::Object {
            triangles: vec![tri(0), tri(1)],
            shading,
            material: ideal::Material {
                color: [1.0; 3],
                ka: 0.1,
                kd: 0.9,
                ks: 0.0,
                shininess: 1.0,
            },
            cull_backfaces: false,
        }],
    };
    ideal::render(&scene).unwrap().to_rgb8()
}

/// Mean absolute error in levels over pixels lit in both.
fn mean_error(a: &[[u8; 3]], b: &[[u8; 3]]) -> f64 {
    let pairs: Vec<_> = a
        .iter()
        .zip(b)
        .filter(|(p, q)| p[0] > 0 && q[0] > 0)
        .collect();
    assert!(pairs.len() > 2000, "the floor covers the frame");
    pairs
        .iter()
        .map(|(p, q)| (p[0] as f64 - q[0] as f64).abs())
        .sum::<f64>()
        / pairs.len() as f64
}

#[test]
fn perspective_correct_interpolation_is_closer_to_the_ideal() {
    for (shading, ishading) in [
        (Shading::Gouraud, ideal::Shading::Gouraud),
        (Shading::Phong, ideal::Shading::Phong),
    ] {
        let want = ideal_frame(ishading);
        let errs = [
            ("f64", mean_error(&core_frame::<F64>(shading), &want)),
            ("f64-pc", mean_error(&core_frame::<F64Pc>(shading), &want)),
            (
                "precise",
                mean_error(&core_frame::<Precise>(shading), &want),
            ),
            (
                "precise-pc",
                mean_error(&core_frame::<PrecisePc>(shading), &want),
            ),
            ("fast", mean_error(&core_frame::<Fast>(shading), &want)),
            ("fast-pc", mean_error(&core_frame::<FastPc>(shading), &want)),
        ];
        println!("{shading:?}: mean error vs ideal {errs:?}");
        for pair in errs.chunks(2) {
            let (affine, correct) = (pair[0].1, pair[1].1);
            // Affine interpolation is off by several levels on average on
            // this floor; perspective-correct is within rounding.
            assert!(
                affine > 3.0,
                "{shading:?} {}: affine error {affine}",
                pair[0].0
            );
            assert!(
                correct < 0.6,
                "{shading:?} {}: correct error {correct}",
                pair[1].0
            );
        }
    }
}
