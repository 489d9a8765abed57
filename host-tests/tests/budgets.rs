//! Accuracy budgets for every built-in scene and profile.
//!
//! Against the float twin (quantization alone): `precise` and `f32` cover
//! exactly the twin's pixels and stay within 1 level (Gouraud, flat) or 2
//! levels (Phong) on every pixel; `fast` (Q16.16) may snap a few vertices
//! to the neighbouring subpixel (its projection is within 1.5 subpixels)
//! and so differ in coverage at a handful of silhouette pixels, where
//! another surface can show through (up to 75 levels, measured on the
//! bunny). `f64` and `f64-pc` are their own twins: they are bounded against
//! the ideal reference alone.
//!
//! Against the ideal reference (everything: subpixel snapping, affine
//! interpolation, quantization), every profile: coverage differs only at a
//! few pixels whose centres lie within snapping distance of an edge, and
//! the mean error stays below one level. The bounds below are the measured
//! figures with a margin; `docs/accuracy.md` lists the measurements.

use fixshade_host::builtin::{builtin_scenes, load_builtin};
use fixshade_host::compare::compare_scene;
use fixshade_host::core_render::CoreProfile;
use fixshade_host::ideal::Shading;

/// Bounds against the ideal reference: (coverage mismatches, mean error in
/// levels, share of pixels more than one level off). Affine profiles
/// interpolate linearly in screen space while the ideal is
/// perspective-correct: up to 31 % of a frame's pixels differ by more than
/// a level (measured: 0.311 on the hot-spot grid), the mean stays below
/// 0.6. The perspective-correct profiles measure 0.0072 and 0.125.
fn ideal_bound(p: CoreProfile) -> (u64, f64, f64) {
    if p.perspective() {
        (6, 0.15, 0.01)
    } else {
        (6, 0.7, 0.35)
    }
}

#[test]
fn every_scene_meets_its_budgets() {
    for &(name, _, _) in builtin_scenes() {
        let desc = load_builtin(name).unwrap();
        let phong = desc.objects.iter().any(|o| o.shading == Shading::Phong);
        for p in CoreProfile::ALL {
            let c = compare_scene(&desc, p).unwrap();
            let (f, i) = (&c.metrics.vs_float, &c.metrics.vs_ideal);
            println!(
                "{name:28} {:10} twin: cov {:2} max {:3} mean {:.4} | ideal: cov {:2} max {:3} mean {:.3} >1: {:.4}",
                p.name(),
                f.coverage_mismatch,
                f.max_abs_error,
                f.mean_abs_error,
                i.coverage_mismatch,
                i.max_abs_error,
                i.mean_abs_error,
                i.share_over_1
            );
            if matches!(p, CoreProfile::F64 | CoreProfile::F64Pc) {
                // The twin is this very profile: nothing to bound there.
            } else if matches!(p, CoreProfile::Fast | CoreProfile::FastPc) {
                // Q16 projection: a few vertices one subpixel off, a few
                // silhouette pixels covered differently (measured 3-4).
                assert!(
                    f.coverage_mismatch <= 6,
                    "{name} {}: coverage {}",
                    p.name(),
                    f.coverage_mismatch
                );
                // Flat shading gives a whole face one colour: on the flat
                // dodecahedron a few faces' Q16 level lands one step from
                // the twin's (max 1 level), which weighs the face's whole
                // area in the mean (measured 0.070).
                let mean_bound = if name == "dodeca-flat-n100" {
                    0.08
                } else {
                    0.05
                };
                assert!(
                    f.mean_abs_error <= mean_bound,
                    "{name} {}: mean {}",
                    p.name(),
                    f.mean_abs_error
                );
                // Phong in `fast` runs the span kernel (`render::PhongKernel`):
                // within 2 levels of the twin on every Phong scene (issue
                // 15's budget; measured 2); `fast-pc` keeps the generic
                // path (measured 3). Gouraud and flat: a silhouette pixel
                // showing another surface (measured 75, the bunny).
                let max_bound = match (phong, p) {
                    (true, CoreProfile::Fast) => 2,
                    (true, _) => 3,
                    (false, _) => 80,
                };
                assert!(
                    f.max_abs_error <= max_bound,
                    "{name} {}: {} levels from the twin",
                    p.name(),
                    f.max_abs_error
                );
            } else {
                assert_eq!(
                    f.coverage_mismatch,
                    0,
                    "{name} {}: coverage differs from the twin",
                    p.name()
                );
                let bound = if phong { 2 } else { 1 };
                assert!(
                    f.max_abs_error <= bound,
                    "{name} {}: {} levels from the twin",
                    p.name(),
                    f.max_abs_error
                );
            }
            let (cov, mean, share) = ideal_bound(p);
            assert!(
                i.coverage_mismatch <= cov,
                "{name} {}: {} coverage mismatches vs ideal",
                p.name(),
                i.coverage_mismatch
            );
            assert!(
                i.mean_abs_error <= mean,
                "{name} {}: mean {} vs ideal",
                p.name(),
                i.mean_abs_error
            );
            assert!(
                i.share_over_1 <= share,
                "{name} {}: share {} vs ideal",
                p.name(),
                i.share_over_1
            );
        }
    }
}
