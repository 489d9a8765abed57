//! Phong accuracy budgets (issue 15, part 4): `fast` within 2 levels of
//! its `f64` twin and `precise` within 1, on every Phong built-in scene and
//! on the highlight-peak set; the twin against the ideal reference beside
//! them. Run with `--nocapture` to print every figure; `docs/accuracy.md`
//! lists them.
//!
//! `fast` at the peak of shininess 10 000 (Phong, light straight above
//! the face, local viewer) was 3 levels from its twin while the kernel
//! took the walked eye positions, whose steps are rounded to a raw `Q16`
//! unit (off by `k · 2^-17` units `k` pixels from the triangle's anchor);
//! with the span's start from the triangle's exact position plane
//! (`render::phong_span::PosPlane`, at shininess 512 or more) it is 1. `fast-pc`, not in the
//! issue's budget, is 23 levels off there (its normal and position come
//! out of a per-pixel division in `Q16`). The affine twin is up to 237
//! levels from the ideal on the grazing face: screen-linear
//! interpolation of a face turned 75° from the eye; `f64-pc` is within 7
//! (1 below shininess 100).

use crate::support::*;
use fixshade::illum::Specular;
use fixshade::num::{F64Pc, Fast, FastPc, Precise, PrecisePc, F64};
use fixshade::scene::Shading;
use fixshade_host::builtin::{builtin_scenes, load_builtin};
use fixshade_host::compare::compare_scene;
use fixshade_host::core_render::CoreProfile;

/// Every Phong built-in scene, `fast` and `precise` (and their
/// perspective-correct variants) against their twins: the largest channel
/// difference over the pixels both frames cover. Measured: `fast` 2,
/// `precise` 0, `fast-pc` 3, `precise-pc` 1 (docs/accuracy.md's table;
/// `fast-pc` is outside the budget, which names `fast`).
#[test]
fn phong_scenes_within_budget_of_the_twin() {
    let mut worst = [0u8; 4];
    let mut scenes = 0;
    for &(name, _, _) in builtin_scenes() {
        let desc = load_builtin(name).unwrap();
        if !desc
            .objects
            .iter()
            .any(|o| o.shading == fixshade_host::ideal::Shading::Phong)
        {
            continue;
        }
        scenes += 1;
        for (k, p) in [
            CoreProfile::Fast,
            CoreProfile::Precise,
            CoreProfile::FastPc,
            CoreProfile::PrecisePc,
        ]
        .into_iter()
        .enumerate()
        {
            let c = compare_scene(&desc, p).unwrap();
            let (f, i) = (&c.metrics.vs_float, &c.metrics.vs_ideal);
            println!(
                "{name:28} {:10} twin: max {} mean {:.4} | ideal: max {:3} mean {:.3}",
                p.name(),
                f.max_abs_error,
                f.mean_abs_error,
                i.max_abs_error,
                i.mean_abs_error
            );
            worst[k] = worst[k].max(f.max_abs_error);
        }
    }
    println!("worst fast, precise, fast-pc, precise-pc vs twin: {worst:?} over {scenes} scenes");
    assert_eq!(scenes, 11);
    assert!(worst[0] <= 2, "fast {}", worst[0]);
    assert!(worst[1] <= 1, "precise {}", worst[1]);
    assert!(worst[2] <= 3, "fast-pc {}", worst[2]);
    assert!(worst[3] <= 1, "precise-pc {}", worst[3]);
}

/// Shininess of the highlight-peak set.
const SHININESS: [f64; 9] = [1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0, 3000.0, 10_000.0];

/// One case of the highlight-peak set: a square (2 × 2 units) with corner
/// normals tilted 20° outwards, its face turned by `tilt` about y, the eye
/// 3 units away on the z axis, and one directional light (`Ip = 1`, `ks =
/// 1`) at the mirror direction of the view about the face normal, so the
/// highlight's peak lies at the face's centre: `tilt` 0 puts the light
/// straight above the face, 75° makes it (and the view) graze the face.
fn peak_case(tilt_deg: f64, specular: Specular, n: f64) -> Spec<'static> {
    let mut s = Spec::new(256, 192, [0.0, 0.0, 3.0]);
    s.ambient = 0.1;
    s.specular = specular;
    let mesh = quad(&TILTED);
    let mut o = ObjSpec::new(mesh, Shading::Phong);
    o.angles = [0.0, tilt_deg.to_radians(), 0.0];
    (o.ka, o.kd, o.ks, o.shininess) = (0.2, 0.3, 1.0, n);
    s.objects.push(o);
    let r = rotation(o.angles);
    let nrm = [r[0][2], r[1][2], r[2][2]];
    // L = 2 (n·v) n - v with v = +z.
    let l = [
        2.0 * nrm[2] * nrm[0],
        2.0 * nrm[2] * nrm[1],
        2.0 * nrm[2] * nrm[2] - 1.0,
    ];
    s.lights.push((LightSpec::Directional(l), 1.0, [1.0; 3]));
    s
}

/// The highlight-peak set: shininess 1 to 10 000, Phong and Blinn, the
/// light straight above the face and grazing it (75°). `fast` within 2
/// levels of its twin, `precise` within 1; the twin within 2 of the ideal
/// (measured figures in docs/accuracy.md).
#[test]
fn highlight_peak_set_within_budget() {
    let mut worst = [0u8; 6];
    for tilt in [0.0, 75.0] {
        for specular in [Specular::Phong, Specular::Blinn] {
            for n in SHININESS {
                let s = peak_case(tilt, specular, n);
                let (ideal, icov) = s.render_ideal();
                let mut row = [0u8; 6];
                let mut common = 0;
                for (k, (twin, p, f)) in [
                    (
                        s.render::<F64>().unwrap(),
                        s.render::<Precise>().unwrap(),
                        s.render::<Fast>().unwrap(),
                    ),
                    (
                        s.render::<F64Pc>().unwrap(),
                        s.render::<PrecisePc>().unwrap(),
                        s.render::<FastPc>().unwrap(),
                    ),
                ]
                .into_iter()
                .enumerate()
                {
                    let di;
                    (di, common) = max_diff_covered(&ideal, &icov, &twin.rgb, &twin.covered);
                    let (dp, _) = max_diff_covered(&p.rgb, &p.covered, &twin.rgb, &twin.covered);
                    let (df, _) = max_diff_covered(&f.rgb, &f.covered, &twin.rgb, &twin.covered);
                    row[3 * k..3 * k + 3].copy_from_slice(&[di, dp, df]);
                }
                println!(
                    "tilt {tilt:2} {specular:?} n {n:5}: f64-ideal {}, precise {}, fast {} | f64-pc-ideal {}, precise-pc {}, fast-pc {} over {common} pixels",
                    row[0], row[1], row[2], row[3], row[4], row[5]
                );
                assert!(common > 1_000, "the face is on screen: {common}");
                // The affine twin against the ideal: exact only on the
                // face turned to the eye (depth constant over it).
                if tilt == 0.0 {
                    assert!(row[0] <= 1, "f64 {} from the ideal", row[0]);
                }

                assert!(row[1] <= 1 && row[4] <= 1, "precise {row:?}");
                assert!(row[2] <= 2, "fast {row:?}");
                for (w, r) in worst.iter_mut().zip(row) {
                    *w = (*w).max(r);
                }
            }
        }
    }
    println!("highlight peaks: worst f64-ideal, precise, fast, f64-pc-ideal, precise-pc, fast-pc = {worst:?}");
    // Measured: [237, 0, 1, 7, 1, 23] (docs/accuracy.md; `fast` 3 before
    // the position plane).
    assert!(worst[1] <= 1 && worst[4] <= 1, "precise {worst:?}");
    assert!(worst[2] <= 1, "fast {worst:?}");
    assert!(worst[3] <= 7, "f64-pc from the ideal {worst:?}");
    assert!(worst[5] <= 23, "fast-pc {worst:?}");
}
