//! Each profile against the f64 twin on the same scenes, pixel by pixel:
//! five scenes (a smooth dodecahedron, the sphere twice, the bunny twice;
//! point and directional lights, coloured lights and materials, Phong and
//! Blinn, local and infinite viewers, shininess up to 200), each shaded
//! Gouraud and Phong, at 240 × 240 with a 32-bit depth buffer.
//!
//! Run with `--nocapture` to see the table of measured figures.

mod common;

use common::{diff, render, smooth, snapped, Desc, Diff, Lamp, Mat, Obj, WHITE};
use fixshade::illum::{Specular, Viewer};
use fixshade::mesh::{BUNNY, DODECAHEDRON, SPHERE};
use fixshade::num::{Fast, FastSub, Precise, Profile, F32, F64};
use fixshade::scene::Shading;

const W: u32 = 240;

fn scenes(shading: Shading) -> Vec<(&'static str, Desc)> {
    let base = |mesh, mat, lamps: Vec<Lamp>, spec, viewer, angles| Desc {
        eye: [0.0, 0.0, 3.5],
        target: [0.0; 3],
        fov_deg: 45.0,
        objects: vec![Obj {
            mesh,
            scale: 1.0,
            angles,
            offset: [0.0; 3],
            mat,
            shading,
            cull: true,
        }],
        lamps,
        ambient: 0.15,
        specular: spec,
        viewer,
    };
    vec![
        (
            "dodecahedron smooth",
            base(
                smooth(DODECAHEDRON),
                Mat {
                    color: WHITE,
                    ka: 1.0,
                    kd: 0.7,
                    ks: 0.4,
                    n: 30.0,
                },
                vec![
                    Lamp::Point([2.0, 2.0, 3.0], 0.9, WHITE),
                    Lamp::Dir([-1.0, 0.3, 0.5], 0.3, WHITE),
                ],
                Specular::Phong,
                Viewer::Local,
                [0.4, 0.7, 0.1],
            ),
        ),
        (
            "sphere",
            base(
                SPHERE,
                Mat {
                    color: [0.9, 0.4, 0.2],
                    ka: 1.0,
                    kd: 0.8,
                    ks: 0.5,
                    n: 60.0,
                },
                vec![
                    Lamp::Dir([1.0, 1.0, 1.0], 0.8, WHITE),
                    Lamp::Point([-3.0, -1.0, 2.0], 0.5, [0.3, 0.5, 1.0]),
                ],
                Specular::Blinn,
                Viewer::Local,
                [0.2, 0.3, 0.0],
            ),
        ),
        (
            "bunny",
            base(
                BUNNY,
                Mat {
                    color: WHITE,
                    ka: 1.0,
                    kd: 0.8,
                    ks: 0.3,
                    n: 20.0,
                },
                vec![Lamp::Dir([1.0, 1.0, 1.0], 0.8, WHITE)],
                Specular::Phong,
                Viewer::Infinite,
                [0.0, 0.0, 0.0],
            ),
        ),
        (
            "sphere n=200 near light",
            base(
                SPHERE,
                Mat {
                    color: WHITE,
                    ka: 1.0,
                    kd: 0.6,
                    ks: 0.6,
                    n: 200.0,
                },
                vec![Lamp::Point([0.8, 0.9, 1.6], 1.0, WHITE)],
                Specular::Phong,
                Viewer::Local,
                [0.0, 0.0, 0.0],
            ),
        ),
        (
            "bunny two lights",
            base(
                BUNNY,
                Mat {
                    color: [0.8, 0.8, 0.6],
                    ka: 1.0,
                    kd: 0.7,
                    ks: 0.4,
                    n: 50.0,
                },
                vec![
                    Lamp::Point([-1.5, 2.0, 2.5], 0.8, WHITE),
                    Lamp::Dir([1.0, -0.2, 0.6], 0.5, [1.0, 0.6, 0.3]),
                ],
                Specular::Blinn,
                Viewer::Local,
                [0.0, 0.6, 0.0],
            ),
        ),
    ]
}

/// Fast's measured figures per scene (in the order of `scenes`), Gouraud
/// then Phong: `(largest error, pixels off by more than 1)`. Rendering is
/// deterministic, so these are the exact measured values, asserted as
/// bounds. Every error above 3 levels is at a silhouette or an occluding
/// contour (see `fast_snaps_some_vertices_one_subpixel_away`), where a
/// vertex one subpixel away shows the neighbouring surface at a pixel.
const FAST: [[(u8, usize); 2]; 5] = [
    [(1, 0), (1, 0)],   // dodecahedron smooth
    [(1, 0), (1, 0)],   // sphere
    [(3, 3), (3, 5)],   // bunny
    [(2, 2), (3, 1)],   // sphere n=200 near light
    [(33, 3), (43, 2)], // bunny two lights
];

fn compare<P: Profile>(name: &str, shading: Shading, d: &Desc, r: &common::Image) -> Diff {
    let df = diff(&render::<P>(d, W, W), r);
    let Diff {
        both,
        coverage,
        max,
        over1,
        mean,
        interior,
    } = df;
    println!(
        "{name:24} {:8} {:>7}: {both} px, coverage differs at {coverage}, \
         max {max} (interior {interior}), {over1} px > 1, mean {mean:.4}",
        format!("{shading:?}"),
        P::NAME
    );
    assert!(both > 15_000, "{name}: {both} pixels");
    df
}

/// Precise and the f32 twin against f64: identical coverage (they snap
/// every vertex to the same subpixel as f64 on these scenes), Gouraud
/// within 1 level, Phong within 2 (measured: 1), mean error below 0.01
/// level. Fast: coverage differs at 2 pixels per scene at most; the
/// largest error and the count of pixels more than 1 level off are at most
/// the measured figures of `FAST`; pixels whose 3 × 3 neighbourhood is
/// covered in both frames are within 1 level, except on the bunny (3) and
/// the bunny with two lights (43, a neighbourhood across an occluding
/// contour); mean error below 0.025 level.
#[test]
fn fixed_profiles_against_the_f64_twin() {
    for (si, shading) in [Shading::Gouraud, Shading::Phong].into_iter().enumerate() {
        for (i, (name, d)) in scenes(shading).into_iter().enumerate() {
            let r = render::<F64>(&d, W, W);
            let limit = if shading == Shading::Gouraud { 1 } else { 2 };
            for df in [
                compare::<Precise>(name, shading, &d, &r),
                compare::<F32>(name, shading, &d, &r),
            ] {
                assert_eq!(df.coverage, 0, "{name} {shading:?}");
                assert!(df.max <= limit, "{name} {shading:?}: {df:?}");
                // Measured at most 0.0052 (Precise, Phong with a point
                // light: eye positions interpolate to 2^-16).
                assert!(df.mean < 0.01, "{name} {shading:?}: {df:?}");
            }
            let f = compare::<Fast>(name, shading, &d, &r);
            let (max, over1) = FAST[i][si];
            // Measured: 2 silhouette pixels on the sphere near its light.
            assert!(f.coverage <= 2, "{name} {shading:?}: {f:?}");
            // Since the Q16 kernels of `geom::q16` (which changed which
            // vertices snap differently) one pixel of "bunny two lights"
            // inside the silhouette is 33 (Gouraud) / 43 (Phong) levels
            // off, and the bunny's Phong interior 3: a 3 x 3 neighbourhood
            // covered in both frames can still straddle an occluding
            // contour (the Q16 lighting itself is within 0.25 level of
            // f64 for this scene's lights: measured 0.143 by
            // `fast_lighting_of_bunny_two_lights_against_f64`).
            let interior = match name {
                "bunny two lights" => 43,
                "bunny" => 3,
                _ => 1,
            };
            assert!(f.interior <= interior, "{name} {shading:?}: {f:?}");
            assert!(
                f.max <= max && f.over1 <= over1,
                "{name} {shading:?}: {f:?}"
            );
            assert!(f.mean < 0.025, "{name} {shading:?}: {f:?}");
        }
    }
}

/// Why Fast differs at silhouettes: its Q16 projection (`x/w` to 2^-16,
/// times the 290-pixel focal scale: about 0.004 pixel, 0.07 subpixel)
/// rounds 82 of the bunny's 1 839 vertices to the neighbouring subpixel
/// (117 before the integer projection of `geom::q16`: the rest is the
/// rounding of eye-space positions to 2^-16).
/// That moves edges by 1/16 pixel, which changes the coverage of a pixel
/// or two, and at an occluding contour the surface seen at a pixel (the
/// errors above 3 levels in `FAST`: the pixel shows the neighbouring
/// surface, shaded correctly for that surface). Precise snaps every vertex exactly
/// as f64 does.
#[test]
fn fast_snaps_some_vertices_one_subpixel_away() {
    let d = scenes(Shading::Gouraud).swap_remove(2).1;
    let (a, p, b) = (
        snapped::<Fast>(&d, W, W),
        snapped::<Precise>(&d, W, W),
        snapped::<F64>(&d, W, W),
    );
    assert_eq!(a.len(), b.len());
    assert_eq!(p, b);
    let moved: Vec<i32> = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x[0] - y[0]).abs().max((x[1] - y[1]).abs()))
        .filter(|&m| m > 0)
        .collect();
    println!("{} vertices; fast moves {}", b.len(), moved.len());
    assert_eq!(moved.len(), 82);
    assert!(moved.iter().all(|&m| m == 1));
}

/// `FastSub<B>` is `Fast` on a grid of `1/2^B` pixel: `FastSub<4>` renders
/// the very pixels of `Fast`; with 2 bits every stored coordinate is
/// `Fast`'s divided by 4 and rounded (the same projected position on a
/// coarser grid, so within half a coarse step, in coarse units), and the
/// frame differs from `Fast`'s (edge pixels move).
#[test]
fn fast_sub_is_fast_on_another_subpixel_grid() {
    let d = scenes(Shading::Gouraud).swap_remove(2).1;
    let (a, b) = (render::<Fast>(&d, W, W), render::<FastSub<4>>(&d, W, W));
    assert_eq!(a.px, b.px);
    assert_eq!(a.covered, b.covered);
    let (fine, coarse) = (snapped::<Fast>(&d, W, W), snapped::<FastSub<2>>(&d, W, W));
    assert_eq!(fine.len(), coarse.len());
    for (f, c) in fine.iter().zip(&coarse) {
        for k in 0..2 {
            // |4c - f| <= 2 + 1: half a coarse step and each grid's own
            // rounding of the projected point (one fine subpixel).
            assert!((4 * c[k] - f[k]).abs() <= 3, "{f:?} {c:?}");
        }
    }
    let coarse_frame = render::<FastSub<2>>(&d, W, W);
    let moved = (a.covered.iter())
        .zip(&coarse_frame.covered)
        .filter(|(x, y)| x != y)
        .count();
    println!("FastSub<2> covers {moved} pixels differently from Fast");
    assert!(moved > 0);
}

/// The Q16 lighting of "bunny two lights" on its own: `fast`'s
/// `Shade::at` against the f64 formula (`common::phong_f64`) at 100 000
/// random surface points of the bunny's box (`[-1, 1]³`, in eye space: the
/// eye at the origin, 3.5 in front of the world's origin) with random
/// normals facing the eye, and the scene's material, ambient, lights,
/// Blinn highlights and local viewer.
///
/// Bound: the highlight flank's error of `tests/illumination.rs`
/// (`ks · n/e · δ` per unit light, `δ` about 2^-14 for Q16) for both
/// lights at once: 0.4 · 50/e · 2^-14 · 255 · (0.8 + 0.5) = 0.15 level,
/// times 1.35 (what that file's sweep measured above its estimate): 0.2,
/// asserted as 0.25. Measured 0.143 (0.185 over 400 000 points). The 33
/// and 43 levels of `FAST` therefore come from coverage at occluding
/// contours, not from the shading.
#[test]
fn fast_lighting_of_bunny_two_lights_against_f64() {
    use common::phong_f64;
    use common::rng::Rng;
    use fixshade::illum::Shade;
    use fixshade::num::Real;
    let (_, d) = scenes(Shading::Gouraud)
        .into_iter()
        .find(|(name, _)| *name == "bunny two lights")
        .expect("the scene");
    let eye = d.eye;
    let lamps: Vec<Lamp> = d
        .lamps
        .iter()
        .map(|l| match *l {
            Lamp::Point(q, i, c) => Lamp::Point([0, 1, 2].map(|k| q[k] - eye[k]), i, c),
            dir @ Lamp::Dir(..) => dir,
        })
        .collect();
    type R = <Fast as Profile>::Real;
    let mat = d.objects[0].mat;
    let lights: Vec<_> = lamps.iter().map(|l| l.to::<R>()).collect();
    let shade = Shade::new(
        &mat.to::<R>(),
        R::from_f64(d.ambient),
        &lights,
        d.specular,
        d.viewer,
    )
    .unwrap();
    let mut rng = Rng(0x5eed_0b22);
    let (mut worst, mut lit) = (0.0f64, 0);
    while lit < 100_000 {
        let p = [0, 1, 2].map(|k| 2.0 * rng.f() - 1.0 - eye[k]);
        let v = [0, 1, 2].map(|_| 2.0 * rng.f() - 1.0);
        let len = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        let n = v.map(|c| c / len);
        // Facing the eye (at the origin), a normal of the sphere's ball.
        if !(0.1..=1.0).contains(&len) || n.iter().zip(p).map(|(a, b)| a * b).sum::<f64>() >= 0.0 {
            continue;
        }
        lit += 1;
        let got = shade.at(common::v3(n), common::v3(p)).to_f64();
        let want = phong_f64(&mat, d.ambient, &lamps, d.specular, d.viewer, n, p);
        for k in 0..3 {
            worst = worst.max((got[k] - want[k]).abs() * 255.0);
        }
    }
    println!("bunny two lights, Q16 lighting: {worst:.4} level");
    assert!(worst <= 0.25, "{worst} levels");
}
