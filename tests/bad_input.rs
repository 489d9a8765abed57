//! Degenerate and out-of-range inputs to illumination and shading: zero
//! normals, a light at the shaded point, shininess 0 and huge, coefficients
//! outside `[0, 1]`. Every profile must give the defined result: no panic,
//! no NaN (a NaN would reach the screen as level 0, see `Real::to_level`,
//! so pixels are checked against the ambient floor), values asserted.

mod common;

use common::per_profile;
use common::{render, square_scene, Desc, Image, Lamp, Mat, WHITE};
use fixshade::illum::{Shade, Specular, Viewer};
use fixshade::num::{Profile, Real};
use fixshade::scene::Shading;

/// `Shade::at` for profile `P`, as `f64` (checked finite and in `[0, 1]`).
fn shade<P: Profile>(
    m: Mat,
    ambient: f64,
    lamps: &[Lamp],
    spec: Specular,
    viewer: Viewer,
    n: [f64; 3],
    p: [f64; 3],
) -> [f64; 3] {
    let lights: Vec<_> = lamps.iter().map(|l| l.to::<P::Real>()).collect();
    let s = Shade::new(
        &m.to::<P::Real>(),
        P::Real::from_f64(ambient),
        &lights,
        spec,
        viewer,
    )
    .unwrap();
    let out = s.at(common::v3(n), common::v3(p)).to_f64();
    for v in out {
        assert!(
            v.is_finite() && (0.0..=1.0).contains(&v),
            "{}: {out:?}",
            P::NAME
        );
    }
    out
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

/// Tolerance on a shaded value per profile for these simple cases (inputs
/// and one power; see `illumination.rs` for the measured maxima).
fn tol(name: &str) -> f64 {
    match name {
        "fast" => 2e-4,
        "precise" => 1e-8,
        "f32" => 1e-6,
        _ => 1e-12,
    }
}

const MAT: Mat = Mat {
    color: [1.0, 0.5, 0.25],
    ka: 1.0,
    kd: 0.6,
    ks: 0.3,
    n: 10.0,
};
const Z: [f64; 3] = [0.0, 0.0, 1.0];

fn zero_normal_and_light_at_point<P: Profile>() {
    let t = tol(P::NAME);
    let lamps = [
        Lamp::Dir([0.0, 0.0, 1.0], 1.0, WHITE),
        Lamp::Point([0.0, 0.0, 1.0], 1.0, WHITE),
    ];
    // Ambient only: 0.2 · C.
    let amb = [0.2, 0.1, 0.05];
    for spec in [Specular::Phong, Specular::Blinn] {
        for viewer in [Viewer::Local, Viewer::Infinite] {
            // A zero normal: no diffuse, no specular.
            let s = shade::<P>(MAT, 0.2, &lamps, spec, viewer, [0.0; 3], [0.0, 0.0, -2.0]);
            assert!(close(s, amb, t), "{} zero normal: {s:?}", P::NAME);
            // A point light exactly at the shaded point: L = 0, no
            // contribution, whatever the normal.
            let at = [0.3, -0.2, -2.0];
            let s = shade::<P>(
                MAT,
                0.2,
                &[Lamp::Point(at, 1.0, WHITE)],
                spec,
                viewer,
                Z,
                at,
            );
            assert!(close(s, amb, t), "{} light at point: {s:?}", P::NAME);
            // The eye at the shaded point (local viewer, p = 0): V = 0.
            // Phong: R·V = 0, Blinn: H = L, N·H = N·L = 1 with this light
            // on the normal; the diffuse term is unchanged.
            let s = shade::<P>(MAT, 0.2, &lamps[..1], spec, viewer, Z, [0.0; 3]);
            let spec_term = match (spec, viewer) {
                (Specular::Phong, Viewer::Local) => 0.0,
                _ => 0.3,
            };
            let want =
                [0, 1, 2].map(|k| (0.2 * MAT.color[k] + 0.6 * MAT.color[k] + spec_term).min(1.0));
            assert!(
                close(s, want, t),
                "{} {spec:?} {viewer:?} eye at point: {s:?}",
                P::NAME
            );
        }
    }
}

per_profile!(
    fn zero_normal_and_light_at_the_shaded_point = zero_normal_and_light_at_point
);

fn shininess<P: Profile>() {
    let t = tol(P::NAME);
    let m = |n| Mat {
        color: WHITE,
        ka: 0.0,
        kd: 0.0,
        ks: 1.0,
        n,
    };
    let spec = |n: f64, a: f64| {
        shade::<P>(
            m(n),
            0.0,
            &[Lamp::Dir([a.sin(), 0.0, a.cos()], 1.0, WHITE)],
            Specular::Phong,
            Viewer::Infinite,
            Z,
            [0.0, 0.0, -1.0],
        )[0]
    };
    // n = 0: x^0 = 1 wherever R·V > 0 and N·L > 0 (a uniform
    // "highlight" of ks); negative shininess is clamped to 0.
    for a in [0.0, 0.3, 1.0] {
        assert!((spec(0.0, a) - 1.0).abs() <= t, "{} n=0 a={a}", P::NAME);
        assert!((spec(-5.0, a) - 1.0).abs() <= t, "{} n=-5 a={a}", P::NAME);
    }
    // N·L = cos(2.0) < 0: the light is behind the surface, no specular
    // even at n = 0.
    assert_eq!(spec(0.0, 2.0), 0.0);
    // N·L > 0 > R·V: the normal tilted by -0.8 rad, the light at +0.5 rad
    // (N·L = cos 1.3 = 0.27), so R lies at -2.1 rad and R·V = cos 2.1 =
    // -0.50. At n = 0 the specular term is max(0, R·V)^0 = 0^0 = 1 (as
    // `Real::powf` defines it and the ideal renderer does); at n = 1 it
    // is 0.
    let lamp = [Lamp::Dir([0.5f64.sin(), 0.0, 0.5f64.cos()], 1.0, WHITE)];
    let normal = [(-0.8f64).sin(), 0.0, (-0.8f64).cos()];
    let (model, view, at) = (Specular::Phong, Viewer::Infinite, [0.0, 0.0, -1.0]);
    let tilted = |n: f64| shade::<P>(m(n), 0.0, &lamp, model, view, normal, at)[0];
    assert!(
        (tilted(0.0) - 1.0).abs() <= t,
        "{} n=0: {}",
        P::NAME,
        tilted(0.0)
    );
    assert_eq!(tilted(1.0), 0.0, "{} n=1", P::NAME);
    // The reference agrees.
    let want = |n: f64| common::phong_f64(&m(n), 0.0, &lamp, model, view, normal, at)[0];
    assert_eq!((want(0.0), want(1.0)), (1.0, 0.0));
    // Huge shininess is clamped to 10 000: at R·V = cos(0.01), 10 000
    // gives 0.99995^10000 = e^-0.5 = 0.6065, where 1e6 would give
    // e^-50 = 0. Q16 holds R·V = 0.99995000 as 65533/65536 = 0.99995422
    // (the nearest value), and that to the 10 000th is 0.6327: the
    // rounding of x documented for `Real::powf` (n x^(n-1) dx = 0.026
    // here).
    let x = if P::NAME == "fast" {
        (0.01f64.cos() * 65536.0).round() / 65536.0
    } else {
        0.01f64.cos()
    };
    let want = x.powf(10_000.0);
    for n in [10_000.0, 1e6, 1e30] {
        let s = spec(n, 0.01);
        assert!((s - want).abs() <= 1e-3, "{} n={n}: {s} vs {want}", P::NAME);
    }
    assert_eq!(spec(1e6, 0.01), spec(10_000.0, 0.01));
    // Head-on, R·V = 1: 1 for every shininess. The f32 twin normalises
    // L = (0, 0, 1) with its approximate rsqrt (2^-22 relative) to a length
    // 6e-8 short of 1, and 0.99999994^10000 = 0.9994 (0.15 level).
    let head_on = spec(1e6, 0.0);
    let t_peak = if P::NAME == "f32" { 1e-3 } else { t };
    assert!((head_on - 1.0).abs() <= t_peak, "{}: {head_on}", P::NAME);
}

per_profile!(
    fn shininess_zero_and_huge = shininess
);

fn coefficients<P: Profile>() {
    let t = tol(P::NAME);
    let l = [Lamp::Dir([0.6, 0.0, 0.8], 1.0, WHITE)];
    let p = [0.0, 0.0, -2.0];
    let bad = Mat {
        color: [1.5, -0.2, 0.5],
        ka: -0.5,
        kd: 1.7,
        ks: 2.0,
        n: 4.0,
    };
    let clamped = Mat {
        color: [1.0, 0.0, 0.5],
        ka: 0.0,
        kd: 1.0,
        ks: 1.0,
        n: 4.0,
    };
    for spec in [Specular::Phong, Specular::Blinn] {
        let a = shade::<P>(bad, 0.3, &l, spec, Viewer::Infinite, Z, p);
        let b = shade::<P>(clamped, 0.3, &l, spec, Viewer::Infinite, Z, p);
        assert_eq!(a, b, "{} {spec:?}", P::NAME);
    }
    // By hand (Phong, V = +z): N·L = 0.8, R·V = 0.8, S = 0.8^4 = 0.4096.
    // Red: 0.8 + 0.4096 -> 1 (clamped); green: 0 + 0.4096; blue: 0.4 +
    // 0.4096 = 0.8096.
    let a = shade::<P>(bad, 0.3, &l, Specular::Phong, Viewer::Infinite, Z, p);
    assert!(
        close(a, [1.0, 0.4096, 0.8096], 2.0 * t),
        "{}: {a:?}",
        P::NAME
    );
    // Ambient above 1 is 1, below 0 is 0; a negative light intensity
    // gives no light; a light colour above 1 is 1.
    let m = Mat { ks: 0.0, ..clamped };
    let hi = shade::<P>(
        Mat { ka: 0.5, ..m },
        7.0,
        &[Lamp::Dir(Z, -3.0, WHITE)],
        Specular::Phong,
        Viewer::Infinite,
        Z,
        p,
    );
    assert!(close(hi, [0.5, 0.0, 0.25], t), "{}: {hi:?}", P::NAME);
    let lo = shade::<P>(
        Mat { ka: 0.5, ..m },
        -7.0,
        &[Lamp::Dir(Z, 0.5, [3.0, 3.0, -1.0])],
        Specular::Phong,
        Viewer::Infinite,
        Z,
        p,
    );
    assert!(close(lo, [0.5, 0.0, 0.0], t), "{}: {lo:?}", P::NAME);
}

per_profile!(
    fn coefficients_outside_unit_range_are_clamped = coefficients
);

const UP: [i16; 3] = [0, 0, 16384];
const DOWN: [i16; 3] = [0, 0, -16384];

fn scene(normals: [[i16; 3]; 4], shading: Shading, lamps: Vec<Lamp>) -> Desc {
    let mat = Mat {
        color: WHITE,
        ka: 1.0,
        kd: 0.7,
        ks: 0.3,
        n: 20.0,
    };
    square_scene(normals, mat, lamps, shading, 0.2)
}

/// Every covered pixel's level, and the count of covered pixels.
fn levels(img: &Image) -> Vec<u8> {
    (0..img.px.len())
        .filter(|&i| img.covered[i])
        .map(|i| img.px[i].r)
        .collect()
}

fn zero_normals_render<P: Profile>() {
    let light = vec![Lamp::Point([0.5, 0.5, 2.0], 1.0, WHITE)];
    // All four corner normals zero: Gouraud and Phong give the ambient
    // level 0.2 · 255 = 51 everywhere; flat shading uses the face normal
    // (computed from the positions) and is lit.
    for shading in [Shading::Gouraud, Shading::Phong] {
        let img = render::<P>(&scene([[0; 3]; 4], shading, light.clone()), 120, 120);
        let l = levels(&img);
        assert_eq!(l.len(), 96 * 96, "{} {shading:?}", P::NAME);
        assert!(l.iter().all(|&v| v == 51), "{} {shading:?}", P::NAME);
    }
    let flat = render::<P>(&scene([[0; 3]; 4], Shading::Flat, light.clone()), 120, 120);
    assert!(levels(&flat).iter().all(|&v| v > 150), "{} flat", P::NAME);
    // Normals that cancel: up at two adjacent corners, down at the other
    // two. Phong interpolates them through zero along the square's middle
    // (the normal is exactly zero on the edge midpoints): defined results,
    // never below the ambient floor (a NaN would give 0), ambient on the
    // down side, lit on the up side.
    let img = render::<P>(
        &scene([UP, UP, DOWN, DOWN], Shading::Phong, light.clone()),
        120,
        120,
    );
    let l = levels(&img);
    assert_eq!(l.len(), 96 * 96);
    assert!(l.iter().all(|&v| v >= 51), "{}: below ambient", P::NAME);
    // Corners (-1,-1), (1,-1) are up (screen bottom), the others down.
    assert!(
        img.lvl(60, 100) > 150 && img.lvl(60, 20) == 51,
        "{}",
        P::NAME
    );
    // A point light in the plane of the square, at its centre: N·L = 0 at
    // every point (L lies in the plane), the light is exactly at the
    // shaded point nowhere on a pixel centre but passes through zero
    // distance there: ambient everywhere, no NaN.
    for shading in [Shading::Gouraud, Shading::Phong, Shading::Flat] {
        let img = render::<P>(
            &scene([UP; 4], shading, vec![Lamp::Point([0.0; 3], 1.0, WHITE)]),
            120,
            120,
        );
        let l = levels(&img);
        assert!(
            l.iter().all(|&v| v == 51),
            "{} {shading:?}: {:?}",
            P::NAME,
            l.iter().max()
        );
    }
}

per_profile!(
    fn zero_and_cancelling_normals_render_defined = zero_normals_render
);
