//! `Shade::at` of every profile against the Phong illumination formula
//! evaluated in `f64` (an independent transcription in `common`), on a
//! table of normals, lights, viewers and shininesses including n = 800,
//! grazing light (N·L near 0 and near 1), highlights at R·V near 1, Phong
//! and Blinn, point and directional lights, several lights, coloured
//! materials and lights, and saturation; plus a deterministic random sweep.
//!
//! Errors are in 8-bit levels (the output times 255, before `to_level`
//! rounds it). Inputs are given in `f64` and converted by each profile, so
//! the error includes the rounding of the inputs. Run with `--nocapture`
//! to see the measured maxima.

mod common;

use common::per_profile;
use common::rng::Rng;
use common::{phong_f64, Lamp, Mat, WHITE};
use fixshade::illum::{Shade, Specular, Viewer};
use fixshade::num::{Fast, Precise, Profile, Real, F32, F64};

/// One illumination query.
#[derive(Clone, Debug)]
struct Case {
    name: &'static str,
    mat: Mat,
    ambient: f64,
    lamps: Vec<Lamp>,
    spec: Specular,
    viewer: Viewer,
    n: [f64; 3],
    p: [f64; 3],
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

/// Direction at angle `a` (radians) from +z towards +x.
fn tilt(a: f64) -> [f64; 3] {
    [a.sin(), 0.0, a.cos()]
}

fn grey(ka: f64, kd: f64, ks: f64, n: f64) -> Mat {
    Mat {
        color: WHITE,
        ka,
        kd,
        ks,
        n,
    }
}

const RED: [f64; 3] = [1.0, 0.0, 0.0];

fn table() -> Vec<Case> {
    let base = Case {
        name: "",
        mat: grey(1.0, 0.7, 0.3, 10.0),
        ambient: 0.1,
        lamps: vec![],
        spec: Specular::Phong,
        viewer: Viewer::Infinite,
        n: [0.0, 0.0, 1.0],
        p: [0.0, 0.0, -3.0],
    };
    let dir = |a: f64| Lamp::Dir(tilt(a), 1.0, WHITE);
    let mut t = vec![];
    for spec in [Specular::Phong, Specular::Blinn] {
        // Head-on: N·L = 1, R·V = 1.
        for n in [0.5, 1.0, 10.0, 100.0, 800.0, 10_000.0] {
            t.push(Case {
                name: "head-on",
                mat: grey(1.0, 0.5, 0.4, n),
                lamps: vec![dir(0.0)],
                spec,
                ..base.clone()
            });
        }
        // Highlight edge at n = 800: R·V = cos(a) (Phong) near 1; the
        // half-width at half maximum is 0.042 rad.
        for a in [0.001, 0.005, 0.01, 0.02, 0.03, 0.042, 0.05, 0.07, 0.1] {
            t.push(Case {
                name: "n=800 near R·V=1",
                mat: grey(1.0, 0.5, 0.4, 800.0),
                lamps: vec![dir(a)],
                spec,
                ..base.clone()
            });
        }
        // Grazing: N·L near 0 (89.9°, 89°, 85°), exactly 0 and behind
        // (1.6 rad). (Exactly 0 is given exactly: `tilt(π/2)` would leave
        // N·L = 6e-17 > 0 in f64 and 0 in Q16, and the model's specular
        // term, counted only where N·L > 0, jumps there: by 0.5 · cos(π/4)^5
        // = 22 levels for Blinn.)
        for l in [1.5690, 1.5533, 1.4835, 1.6]
            .map(tilt)
            .into_iter()
            .chain([[1.0, 0.0, 0.0]])
        {
            t.push(Case {
                name: "grazing N·L",
                mat: grey(1.0, 0.9, 0.5, 5.0),
                lamps: vec![Lamp::Dir(l, 1.0, WHITE)],
                spec,
                ..base.clone()
            });
        }
        // Tilted normal, light near its mirror direction about V.
        for (nrm, l) in [
            (unit([0.6, 0.0, 0.8]), unit([0.96, 0.0, 0.28])),
            (unit([0.3, 0.4, 0.866]), unit([0.5, 0.7, 0.5])),
            (unit([-0.2, 0.1, 0.97]), unit([-0.35, 0.2, 0.91])),
        ] {
            for n in [3.0, 50.0, 800.0] {
                t.push(Case {
                    name: "tilted normal",
                    mat: grey(0.5, 0.6, 0.5, n),
                    lamps: vec![Lamp::Dir(l, 0.9, WHITE)],
                    spec,
                    n: nrm,
                    ..base.clone()
                });
            }
        }
        // Point lights and the local viewer.
        for (p, lp, nrm) in [
            ([0.3, -0.2, -3.0], [1.0, 2.0, 1.0], unit([0.1, 0.3, 0.9])),
            ([0.0, 0.0, -2.0], [0.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
            ([0.5, 0.5, -4.0], [-2.0, 1.0, -1.0], unit([-0.4, 0.2, 0.8])),
            ([0.2, 0.0, -1.0], [0.4, 0.0, 0.0], [0.0, 0.0, 1.0]),
        ] {
            for n in [1.0, 30.0, 800.0] {
                t.push(Case {
                    name: "point light, local viewer",
                    mat: grey(1.0, 0.6, 0.4, n),
                    lamps: vec![Lamp::Point(lp, 1.0, WHITE)],
                    spec,
                    viewer: Viewer::Local,
                    n: nrm,
                    p,
                    ..base.clone()
                });
            }
        }
        // Several coloured lights, a coloured material.
        t.push(Case {
            name: "three coloured lights",
            mat: Mat {
                color: [0.9, 0.5, 0.2],
                ka: 0.8,
                kd: 0.7,
                ks: 0.35,
                n: 40.0,
            },
            ambient: 0.15,
            lamps: vec![
                Lamp::Dir(unit([0.3, 0.2, 1.0]), 0.6, [1.0, 0.9, 0.8]),
                Lamp::Point([-2.0, 1.0, 0.0], 0.5, [0.2, 0.4, 1.0]),
                Lamp::Dir(unit([-0.5, -0.5, 0.7]), 0.3, [0.0, 1.0, 0.0]),
            ],
            spec,
            viewer: Viewer::Local,
            n: unit([0.1, 0.05, 1.0]),
            p: [0.1, 0.0, -2.5],
        });
        // Red object under a white light, at and near the highlight peak.
        for a in [0.0, 0.02, 0.2] {
            t.push(Case {
                name: "red object, white light",
                mat: Mat {
                    color: RED,
                    ka: 1.0,
                    kd: 0.6,
                    ks: 0.5,
                    n: 60.0,
                },
                lamps: vec![dir(a)],
                spec,
                ..base.clone()
            });
        }
        // Eight lights saturating every channel (sum about 4.5).
        t.push(Case {
            name: "eight lights saturate",
            mat: grey(1.0, 0.8, 0.4, 20.0),
            lamps: (0..8).map(|k| dir(0.05 * k as f64)).collect(),
            spec,
            ..base.clone()
        });
    }
    t
}

/// A random direction, uniform on the unit sphere (rejection sampling in
/// the cube, away from the centre).
fn random_dir(rng: &mut Rng) -> [f64; 3] {
    loop {
        let v = [0, 1, 2].map(|_| 2.0 * rng.f() - 1.0);
        let l = v.iter().map(|c| c * c).sum::<f64>();
        if l > 0.01 && l < 1.0 {
            return unit(v);
        }
    }
}

/// Random cases: normals facing +z, lights near the mirror direction (so
/// half of them sit on a highlight), shininess from 1 to 800.
fn random(count: usize) -> Vec<Case> {
    let mut rng = Rng(0x5eed_0001);
    let mut out = vec![];
    for i in 0..count {
        let mut n = random_dir(&mut rng);
        n[2] = n[2].abs().max(0.2);
        let n = unit(n);
        let p = [rng.f() - 0.5, rng.f() - 0.5, -2.0 - 2.0 * rng.f()];
        let local = i % 2 == 0;
        let v = if local {
            unit(p.map(|c| -c))
        } else {
            [0.0, 0.0, 1.0]
        };
        // Mirror of V about N, jittered.
        let nv = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
        let r = [0, 1, 2].map(|k| 2.0 * nv * n[k] - v[k] + 0.1 * (rng.f() - 0.5));
        let l = unit(r);
        let shin = [1.0, 5.0, 20.0, 100.0, 800.0][i % 5];
        let lamp = if i % 3 == 0 {
            let d = 1.0 + 3.0 * rng.f();
            Lamp::Point(
                [0, 1, 2].map(|k| p[k] + d * l[k]),
                0.5 + 0.5 * rng.f(),
                WHITE,
            )
        } else {
            Lamp::Dir(l, 0.5 + 0.5 * rng.f(), WHITE)
        };
        out.push(Case {
            name: "random",
            mat: Mat {
                color: [rng.f(), rng.f(), rng.f()],
                ka: rng.f(),
                kd: rng.f(),
                ks: rng.f(),
                n: shin,
            },
            ambient: 0.2 * rng.f(),
            lamps: vec![lamp],
            spec: if i % 4 < 2 {
                Specular::Phong
            } else {
                Specular::Blinn
            },
            viewer: if local {
                Viewer::Local
            } else {
                Viewer::Infinite
            },
            n,
            p,
        });
    }
    out
}

/// The case's colour by profile `P`'s `Shade::at`.
fn shade_at<P: Profile>(c: &Case) -> fixshade::geom::Vec3<P::Real> {
    let lights: Vec<_> = c.lamps.iter().map(|l| l.to::<P::Real>()).collect();
    let s = Shade::new(
        &c.mat.to::<P::Real>(),
        P::Real::from_f64(c.ambient),
        &lights,
        c.spec,
        c.viewer,
    )
    .unwrap();
    s.at(common::v3(c.n), common::v3(c.p))
}

fn shade<P: Profile>(c: &Case) -> [f64; 3] {
    let out = shade_at::<P>(c).to_f64();
    for v in out {
        assert!(
            v.is_finite() && (0.0..=1.0).contains(&v),
            "{}: {out:?}",
            c.name
        );
    }
    out
}

fn reference(c: &Case) -> [f64; 3] {
    phong_f64(&c.mat, c.ambient, &c.lamps, c.spec, c.viewer, c.n, c.p)
}

/// Largest error in levels over the cases, and the case that gave it.
fn worst<P: Profile>(cases: &[Case]) -> (f64, String) {
    let mut w = (0.0, String::new());
    for c in cases {
        let (got, want) = (shade::<P>(c), reference(c));
        for k in 0..3 {
            let e = (got[k] - want[k]).abs() * 255.0;
            if e > w.0 {
                w = (e, format!("{} {:?} n={}", c.name, c.spec, c.mat.n));
            }
        }
    }
    w
}

/// Why the fixed profiles err most in highlights: an error `δ` in `R·V`
/// (or `N·H`) moves `ks·x^n` by up to `ks · n/e · δ` near the highlight's
/// flank. `δ` collects the errors of the unit vectors entering the dot
/// product: each `normalize` (L of a point light, V of the local viewer, H
/// for Blinn, and L of a directional light once per `Shade`) carries the
/// `rsqrt` error (Q16: 2^-15 relative; Q32: 2^-30; f32: 2^-22), and the
/// inputs are rounded to the scalar (Q16: 2^-17). With `δ` about 2^-14 for
/// Q16, n = 800 gives 294 · 6e-5 · 255 = 4.6 levels per unit `ks`; the
/// sweep measured 6.2. `powf`'s own error (Q16 2^-14, Q32 2^-31, f32 2^-23
/// absolute) adds at most 0.016 level. Away from highlights the error is a
/// few hundredths of a level.
///
/// Bounds in levels, per shininess class of the sweep: the measured
/// maxima (printed with `--nocapture`) with a margin of 25 to 60 %:
/// `(n, fast, precise, f32)`. f64 is within 1e-9 everywhere.
const SWEEP_BOUNDS: [(f64, f64, f64, f64); 5] = [
    // measured: fast 0.031, precise 3.2e-7, f32 5.9e-5
    (1.0, 0.05, 1e-6, 1e-4),
    // measured: fast 0.123, precise 2.5e-6, f32 3.1e-4
    (5.0, 0.2, 5e-6, 5e-4),
    // measured: fast 0.484, precise 1.8e-5, f32 1.1e-3
    (20.0, 0.75, 3e-5, 2e-3),
    // measured: fast 1.64, precise 2.2e-5, f32 3.7e-3
    (100.0, 2.5, 5e-5, 6e-3),
    // measured: fast 6.23, precise 1.4e-4, f32 2.6e-2
    (800.0, 8.0, 3e-4, 0.04),
];

/// Bounds in levels on the table `(fast, precise, f32, f64)`; measured:
/// fast 1.99 (Blinn, n = 800, tilted normal), precise 2.7e-5, f32 0.061
/// (head-on at n = 10 000: `R·V` = 1 - 1e-7 after the f32 normalisation
/// of L, and 0.9999999^10000 = 0.999).
const TABLE_BOUNDS: [f64; 4] = [2.5, 1e-4, 0.1, 1e-9];

fn check<P: Profile>(cases: &[Case], what: &str, bounds: [f64; 4]) {
    let (e, at) = worst::<P>(cases);
    let b = match P::NAME {
        "fast" => bounds[0],
        "precise" => bounds[1],
        "f32" => bounds[2],
        _ => bounds[3],
    };
    println!(
        "{:>7} {what}: max error {e:.3e} levels (bound {b:e}) at {at}",
        P::NAME
    );
    assert!(e <= b, "{} {what}: {e} levels at {at}", P::NAME);
}

#[test]
fn table_against_f64_formula() {
    let t = table();
    check::<Fast>(&t, "table", TABLE_BOUNDS);
    check::<Precise>(&t, "table", TABLE_BOUNDS);
    check::<F32>(&t, "table", TABLE_BOUNDS);
    check::<F64>(&t, "table", TABLE_BOUNDS);
}

#[test]
fn random_sweep_against_f64_formula() {
    let t = random(4000);
    for (n, fast, precise, f32) in SWEEP_BOUNDS {
        let sub: Vec<Case> = t.iter().filter(|c| c.mat.n == n).cloned().collect();
        assert!(sub.len() >= 800);
        let what = format!("sweep n={n}");
        let b = [fast, precise, f32, 1e-9];
        check::<Fast>(&sub, &what, b);
        check::<Precise>(&sub, &what, b);
        check::<F32>(&sub, &what, b);
        check::<F64>(&sub, &what, b);
    }
}

/// The reference itself, at points where the formula is known by hand, so
/// that a wrong reference cannot hide a wrong shader.
#[test]
fn reference_hand_values() {
    let m = grey(1.0, 0.5, 0.4, 800.0);
    let l = [Lamp::Dir([0.0, 0.0, 1.0], 1.0, WHITE)];
    let r = phong_f64(
        &m,
        0.1,
        &l,
        Specular::Phong,
        Viewer::Infinite,
        [0.0, 0.0, 1.0],
        [0.0; 3],
    );
    // 0.1·1 + 0.5·1 + 0.4·1 = 1.0.
    assert!((r[0] - 1.0).abs() < 1e-12);
    // R·V = cos a for a light tilted by a (V = N = +z).
    let a = 0.042_f64;
    let l = [Lamp::Dir(tilt(a), 1.0, WHITE)];
    let r = phong_f64(
        &m,
        0.0,
        &l,
        Specular::Phong,
        Viewer::Infinite,
        [0.0, 0.0, 1.0],
        [0.0; 3],
    );
    let want = 0.5 * a.cos() + 0.4 * a.cos().powf(800.0);
    assert!((r[0] - want).abs() < 1e-12);
    // Blinn: N·H = cos(a/2).
    let r = phong_f64(
        &m,
        0.0,
        &l,
        Specular::Blinn,
        Viewer::Infinite,
        [0.0, 0.0, 1.0],
        [0.0; 3],
    );
    let want = 0.5 * a.cos() + 0.4 * (a / 2.0).cos().powf(800.0);
    assert!((r[0] - want).abs() < 1e-12);
}

/// Shade of profile `P` for the case, as levels rounded like the shaders
/// (`Real::to_level`).
fn levels<P: Profile>(c: &Case) -> [u8; 3] {
    let v = shade_at::<P>(c);
    [v.x.to_level(), v.y.to_level(), v.z.to_level()]
}

fn white_highlight<P: Profile>() {
    // Red object (1, 0, 0), ka 1, kd 0.6, ks 0.5, n 60, under a white
    // directional light along the normal, viewer at infinity on the
    // normal: R·V = 1. Red: 0.1 + 0.6 + 0.5 = 1.2, clamped to 255; green
    // and blue: the specular term alone, 0.5 → 127.5 → 128 (both equal:
    // the highlight takes the light's colour, not the object's).
    let c = &table()
        .into_iter()
        .find(|c| c.name == "red object, white light")
        .unwrap();
    let peak = levels::<P>(c);
    assert_eq!(peak[0], 255, "{}", P::NAME);
    assert_eq!(peak[1], peak[2], "{}: highlight not white", P::NAME);
    assert!((127..=128).contains(&peak[1]), "{}: {peak:?}", P::NAME);
    // Off the peak (0.2 rad): the highlight fades in g and b alike.
    let off = Case {
        lamps: vec![Lamp::Dir(tilt(0.2), 1.0, WHITE)],
        ..c.clone()
    };
    let o = levels::<P>(&off);
    assert_eq!(o[1], o[2]);
    // 0.5 · cos(0.2)^60 = 0.5 · 0.2987 = 0.149 → 38.
    assert!((37..=39).contains(&o[1]), "{}: {o:?}", P::NAME);
    // Red: 0.1 + 0.6 cos(0.2) + 0.149 = 0.837 → 213.
    assert!((212..=214).contains(&o[0]), "{}: {o:?}", P::NAME);
}

per_profile!(
    fn red_object_white_light_white_highlight = white_highlight
);

fn saturation<P: Profile>() {
    // Eight white lights: each channel sums to about 4.5 and is clamped
    // to exactly 1 after the summation, whatever the profile.
    let c = table()
        .into_iter()
        .find(|c| c.name == "eight lights saturate")
        .unwrap();
    assert_eq!(levels::<P>(&c), [255; 3], "{}", P::NAME);
    // Coloured: eight green lights of intensity 8 on a (0.5, 0.25, 0)
    // object: the lights have no red or blue, so red and blue keep their
    // ambient term; green sums to 16.05 and clamps to 255, alone (each
    // channel is clamped on its own: no hue shift towards white).
    let c2 = Case {
        mat: Mat {
            color: [0.5, 0.25, 0.0],
            ka: 1.0,
            kd: 1.0,
            ks: 0.0,
            n: 1.0,
        },
        ambient: 0.2,
        lamps: vec![Lamp::Dir([0.0, 0.0, 1.0], 8.0, [0.0, 1.0, 0.0]); 8],
        ..c.clone()
    };
    // Red: 0.2 · 0.5 = 0.1 → 25.5 → 26 (f64 rounds 25.5 to 26; Q16 holds
    // 0.1 as 6554/65536, just above, also 26). Green: clamped. Blue: 0.
    let l = levels::<P>(&c2);
    assert_eq!(l[1], 255, "{}: {l:?}", P::NAME);
    assert_eq!(l[2], 0, "{}: {l:?}", P::NAME);
    assert!((25..=26).contains(&l[0]), "{}: {l:?}", P::NAME);
    // Huge intensities saturate the fixed sums instead of wrapping.
    let c3 = Case {
        lamps: vec![Lamp::Dir([0.0, 0.0, 1.0], 30_000.0, WHITE); 8],
        ..c.clone()
    };
    assert_eq!(levels::<P>(&c3), [255; 3], "{}", P::NAME);
}

per_profile!(
    fn many_lights_clamp_after_summation = saturation
);

/// Sanity of the table: it does reach the regimes it names (so the bounds
/// above are measured where they matter).
#[test]
fn table_covers_its_regimes() {
    let t = table();
    let nl = |c: &Case| match c.lamps[0] {
        Lamp::Dir(d, _, _) => {
            let d = unit(d);
            c.n[0] * d[0] + c.n[1] * d[1] + c.n[2] * d[2]
        }
        Lamp::Point(..) => f64::NAN,
    };
    assert!(t.iter().any(|c| (0.0..0.002).contains(&nl(c))));
    assert!(t.iter().any(|c| nl(c) > 0.999_999 && c.mat.n == 800.0));
    assert!(t.iter().any(|c| nl(c) < 0.0));
    assert!(t.iter().any(|c| c.mat.n == 10_000.0));
    // Highlight at n = 800 half on: 0.4 · cos(0.042)^800 = 0.2 ± 0.01.
    let c = t
        .iter()
        .find(|c| c.name.starts_with("n=800") && nl(c) < 0.9992 && nl(c) > 0.999)
        .unwrap();
    let s = reference(c)[0] - 0.1 - 0.5 * nl(c);
    assert!((s - 0.2).abs() < 0.01, "{s}");
}
