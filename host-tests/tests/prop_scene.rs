//! Property tests of the 3D pipeline over random scenes: rendering band by
//! band (any band height 1..=H) gives the full frame byte for byte in every
//! profile, float twins included; Precise stays within 1 level of the f64 twin on random
//! Gouraud scenes; arbitrary camera and transform numbers (NaN, infinities,
//! huge values) never panic and never make the rasterizer refuse a
//! triangle.

use crate::support::*;
use fixshade::geom::{Affine, Mat3, Vec3};
use fixshade::illum::Specular;
use fixshade::mesh::{shapes, Mesh};
use fixshade::num::{F32Pc, F64Pc, Fast, FastPc, Precise, PrecisePc, Profile, Real, F32, F64};
use fixshade::render::RenderError;
use fixshade::scene::{Camera, Shading};
use proptest::prelude::*;

const W: u32 = 40;
const H: u32 = 30;

const MESHES: [Mesh<'static>; 5] = [
    shapes::CUBE,
    shapes::DODECAHEDRON,
    shapes::SPHERE,
    shapes::CAN,
    shapes::GRID,
];

fn shading() -> impl Strategy<Value = Shading> {
    prop_oneof![
        Just(Shading::Flat),
        Just(Shading::Gouraud),
        Just(Shading::Phong)
    ]
}

prop_compose! {
    fn object()(
        mesh in 0..MESHES.len(),
        scale in 0.3f64..1.4,
        angles in prop::array::uniform3(-3.2f64..3.2),
        t in prop::array::uniform3(-1.2f64..1.2),
        color in prop::array::uniform3(0.0f64..1.0),
        k in prop::array::uniform3(0.0f64..1.0),
        shininess in 0.0f64..200.0,
        shading in shading(),
        cull in any::<bool>(),
    ) -> ObjSpec<'static> {
        let mut o = ObjSpec::new(MESHES[mesh], shading);
        (o.scale, o.angles, o.translation, o.color) = (scale, angles, t, color);
        (o.ka, o.kd, o.ks, o.shininess, o.cull) = (k[0], k[1], k[2], shininess, cull);
        o
    }
}

prop_compose! {
    fn light()(
        point in any::<bool>(),
        at in prop::array::uniform3(-5.0f64..5.0),
        intensity in 0.0f64..1.2,
        color in prop::array::uniform3(0.3f64..1.0),
    ) -> (LightSpec, f64, [f64; 3]) {
        let kind = if point || at == [0.0; 3] {
            LightSpec::Point(at)
        } else {
            LightSpec::Directional(at)
        };
        (kind, intensity, color)
    }
}

prop_compose! {
    fn scene()(
        objects in prop::collection::vec(object(), 1..4),
        lights in prop::collection::vec(light(), 0..4),
        yaw in -3.2f64..3.2,
        pitch in -1.2f64..1.2,
        dist in 2.5f64..7.0,
        fov in 25.0f64..90.0,
        far in prop::option::of(8.0f64..30.0),
        blinn in any::<bool>(),
        ambient in 0.0f64..1.0,
    ) -> Spec<'static> {
        let eye = [
            dist * pitch.cos() * yaw.sin(),
            dist * pitch.sin(),
            dist * pitch.cos() * yaw.cos(),
        ];
        let mut s = Spec::new(W, H, eye);
        (s.objects, s.lights, s.fov_deg, s.far, s.ambient) = (objects, lights, fov, far, ambient);
        s.specular = if blinn { Specular::Blinn } else { Specular::Phong };
        s
    }
}

fn bands_match<P: Profile>(s: &Spec<'_>, rows: u32) -> Result<(), TestCaseError> {
    let whole = s.render::<P>().unwrap();
    let banded = s.render_banded::<P>(rows).unwrap();
    // Every profile, float twins included, byte for byte: fixed point
    // steps exactly (modulo 2^32), floats recompute each row's start
    // value from the anchor (`Lerp::EXACT_STEPS`).
    prop_assert!(banded == whole.rgb, "{} rows {}", P::NAME, rows);
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    /// Band by band equals the full frame for random scenes (shapes,
    /// transforms, shading modes, lights, cameras), every profile and any
    /// band height 1..=H, byte for byte (see `bands_match`).
    #[test]
    fn bands_equal_the_full_frame(s in scene(), profile in 0..8u8, rows in 1..=H) {
        match profile {
            0 => bands_match::<Fast>(&s, rows)?,
            1 => bands_match::<Precise>(&s, rows)?,
            2 => bands_match::<F32>(&s, rows)?,
            3 => bands_match::<F64>(&s, rows)?,
            4 => bands_match::<FastPc>(&s, rows)?,
            5 => bands_match::<PrecisePc>(&s, rows)?,
            6 => bands_match::<F32Pc>(&s, rows)?,
            _ => bands_match::<F64Pc>(&s, rows)?,
        }
    }

    /// Precise against the f64 twin on random Gouraud scenes of one convex
    /// object with back faces culled: within 1 level at every pixel both
    /// cover (colours are computed in Q32 per vertex and interpolated with
    /// the rasterizer's bound, far below a level; rounding to a level adds
    /// at most 1), and coverage differs only where a vertex snapped to the
    /// other side of a subpixel half (a handful of edge pixels).
    #[test]
    fn precise_is_within_one_level_of_f64(
        s in scene(),
        mesh in 0..3usize,
    ) {
        let mut s = s;
        s.objects.truncate(1);
        let o = &mut s.objects[0];
        (o.mesh, o.shading, o.cull) = (MESHES[mesh], Shading::Gouraud, true);
        let p = s.render::<Precise>().unwrap();
        let f = s.render::<F64>().unwrap();
        let (d, _) = max_diff_covered(&p.rgb, &p.covered, &f.rgb, &f.covered);
        prop_assert!(d <= 1, "{} levels", d);
        let mismatched = p.covered.iter().zip(&f.covered).filter(|(a, b)| a != b).count();
        prop_assert!(mismatched <= 8, "{} pixels' coverage differs", mismatched);
    }
}

/// Maps raw bits to any f32, NaN and infinities included.
fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![
        any::<u32>().prop_map(f32::from_bits),
        prop::sample::select(vec![
            0.0f32,
            -0.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::MAX,
            1e30,
            1e-30,
        ]),
        -100.0f32..100.0,
    ]
}

fn wild<P: Profile>(nums: &[f32], mesh: Mesh<'static>, shading: Shading) {
    let r = |i: usize| P::Real::from_f32(nums[i]);
    let v = |i: usize| Vec3::new(r(i), r(i + 1), r(i + 2));
    let mut s = Spec::new(W, H, [0.0, 0.0, 4.0]);
    let mut o = ObjSpec::new(mesh, shading);
    o.ks = 0.5;
    s.objects.push(o);
    s.lights
        .push((LightSpec::Point([1.0, 1.0, 1.0]), 1.0, [1.0; 3]));
    let (camera, lights, mut objects) = s.core::<P::Real>();
    // Garbage transform and camera fields, set directly (the checked
    // constructors refuse non-finite input).
    objects[0].transform = Affine {
        m: Mat3 {
            rows: [v(0), v(3), v(6)],
        },
        t: v(9),
    };
    let cameras = [
        camera,
        Camera {
            view: Affine {
                m: Mat3 {
                    rows: [v(12), v(15), v(18)],
                },
                t: v(21),
            },
            focal: r(24),
            near: r(25),
            far: Some(r(26)),
        },
    ];
    for camera in cameras {
        let scene = s.scene(camera, &lights, &objects);
        match render_full::<P>(&scene, W, H) {
            Ok(f) => {
                // The frame agrees with its coverage mask (the depth
                // buffer): a pixel it marks uncovered keeps the background,
                // and every covered pixel was counted as drawn.
                for (i, (&covered, px)) in f.covered.iter().zip(&f.rgb).enumerate() {
                    assert!(covered || *px == [1, 2, 3], "pixel {i} drawn without depth");
                }
                let covered = f.covered.iter().filter(|&&c| c).count() as u32;
                assert!(f.stats.pixels >= covered, "{} < {covered}", f.stats.pixels);
                // Band by band: the same frame, whatever the numbers.
                let banded = render_banded::<P>(&scene, W, H, 7).unwrap();
                assert!(banded == f.rgb, "{}: bands differ", P::NAME);
            }
            Err(e) => assert!(!matches!(e, RenderError::Raster(_)), "{e:?}"),
        }
    }
    // The checked constructor with the same numbers: a value or an error.
    let _ = Camera::<P::Real>::look_at_f32(
        [nums[0], nums[1], nums[2]],
        [nums[3], nums[4], nums[5]],
        [nums[6], nums[7], nums[8]],
        nums[9],
        nums[10],
        Some(nums[11]),
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Arbitrary numbers (NaN, infinities, huge values) in the object's
    /// transform and the camera's fields: every profile renders a frame or
    /// returns an error; never a panic, never a `Raster` error.
    #[test]
    fn wild_numbers_never_panic(
        nums in prop::collection::vec(any_f32(), 27),
        mesh in 0..MESHES.len(),
        shading in shading(),
        profile in 0..8u8,
    ) {
        let m = MESHES[mesh];
        match profile {
            0 => wild::<Fast>(&nums, m, shading),
            1 => wild::<Precise>(&nums, m, shading),
            2 => wild::<F32>(&nums, m, shading),
            3 => wild::<F64>(&nums, m, shading),
            4 => wild::<FastPc>(&nums, m, shading),
            5 => wild::<PrecisePc>(&nums, m, shading),
            6 => wild::<F32Pc>(&nums, m, shading),
            _ => wild::<F64Pc>(&nums, m, shading),
        }
    }
}
