//! The kernel against the same model in `f64` (the twin's `Shade::at` on
//! the exactly interpolated normal), on random spans and on the
//! highlight-peak set.
extern crate std;
use super::*;
use crate::geom::Vec3;
use crate::illum::{Light, LightKind, Material};
use crate::num::Q16;
use std::vec::Vec;

fn xorshift(s: &mut u64) -> u64 {
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    *s
}

struct Case {
    mat: Material<Q16>,
    lights: Vec<Light<Q16>>,
    ambient: Q16,
    specular: Specular,
    viewer: Viewer,
}

/// A case of random material (colour, `ka`, `kd`, `ks`, then shininess
/// 1 to 10 000 when `high`, else to 200) and ambient, drawn from `f` in
/// that order, with `lights`, `specular` and `viewer`.
fn random_case(
    f: &mut impl FnMut(f64, f64) -> f64,
    lights: Vec<Light<Q16>>,
    high: bool,
    specular: Specular,
    viewer: Viewer,
) -> Case {
    let mat = Material {
        color: v3(f(0.0, 1.0), f(0.0, 1.0), f(0.0, 1.0)),
        ka: q(f(0.0, 0.5)),
        kd: q(f(0.0, 1.0)),
        ks: q(f(0.0, 1.0)),
        shininess: q(f(1.0, if high { 10_000.0 } else { 200.0 })),
    };
    Case {
        mat,
        lights,
        ambient: q(f(0.0, 0.4)),
        specular,
        viewer,
    }
}

fn to64(v: Vec3<Q16>) -> Vec3<f64> {
    Vec3::new(v.x.to_f64(), v.y.to_f64(), v.z.to_f64())
}

/// Largest channel error (levels) of the kernel against `f64` along one
/// span of `len` pixels; also checks `skip` keeps the kernel in step.
fn span_error(c: &Case, n0: [f64; 3], dn: [f64; 3], p0: [f64; 3], dp: [f64; 3], len: i32) -> f64 {
    let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
    let twin = twin_of(c);
    let k = PhongKernel::new(&shade).unwrap();
    let (n0, dn, p0, dp) = (q30(n0), q30(dn), q16(p0), q16(dp));
    let mut sp = k.begin(n0, dn, p0, dp, false);
    // The span loop (`fill`, the renderer's) and `begin`/`next`.
    let mut filled = std::vec![None; len as usize];
    k.fill(
        n0,
        dn,
        p0,
        dp,
        false,
        len as u32,
        |i| i % 7 != 3,
        |i, c| filled[i as usize] = Some(c),
    );
    let mut worst = 0f64;
    for i in 0..len {
        if i % 7 == 3 {
            sp.skip();
            assert_eq!(filled[i as usize], None);
            continue;
        }
        let got = sp.next();
        let got2 = filled[i as usize].unwrap();
        let n = Vec3::new(
            f64::from(n0[0] + i * dn[0]),
            f64::from(n0[1] + i * dn[1]),
            f64::from(n0[2] + i * dn[2]),
        )
        .normalize();
        let p = Vec3::new(
            f64::from(p0[0] + i * dp[0]) / 65536.0,
            f64::from(p0[1] + i * dp[1]) / 65536.0,
            f64::from(p0[2] + i * dp[2]) / 65536.0,
        );
        let e = twin.at(n, p);
        for got in [got, got2] {
            for (g, w) in [got.r, got.g, got.b].into_iter().zip([e.x, e.y, e.z]) {
                worst = worst.max((f64::from(g) - w * 255.0).abs());
            }
        }
    }
    worst
}

fn q(v: f64) -> Q16 {
    Q16::from_f64(v)
}

fn v3(x: f64, y: f64, z: f64) -> Vec3<Q16> {
    Vec3::new(q(x), q(y), q(z))
}

fn unit(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

/// The highlight-peak set: shininess 1 to 10 000, a light straight above
/// the face (normal, light and viewer along +z) and grazing (80° off),
/// Phong and Blinn, directional light with the viewer at infinity and a
/// point light with a local viewer; spans of 64 pixels sweeping the
/// normal across the peak by 0.5 (n = 1) down to 0.005 (n = 10 000)
/// radians. Within 1 level of `f64` (the budget for `fast`: 2).
#[test]
fn highlight_peak_set() {
    let mut worst = 0f64;
    let mut table = Vec::new();
    for &n in &[1.0, 2.0, 5.0, 10.0, 50.0, 100.0, 800.0, 2000.0, 10_000.0] {
        let mut row = Vec::new();
        for &(model, viewer, point) in &[
            (Specular::Phong, Viewer::Infinite, false),
            (Specular::Blinn, Viewer::Infinite, false),
            (Specular::Phong, Viewer::Local, true),
            (Specular::Blinn, Viewer::Local, true),
        ] {
            for &graze in &[false, true] {
                let ang: f64 = if graze { 80f64.to_radians() } else { 0.0 };
                let ldir = [ang.sin(), 0.0, ang.cos()];
                // The normal at the peak: H for Blinn and for Phong (R = V).
                let h = unit([ldir[0], ldir[1], ldir[2] + 1.0]);
                let light = if point {
                    Light::point(
                        v3(ldir[0] * 4.0, ldir[1] * 4.0, ldir[2] * 4.0 - 5.0),
                        q(1.0),
                    )
                } else {
                    Light::directional(v3(ldir[0], ldir[1], ldir[2]), q(1.0))
                };
                let c = Case {
                    mat: Material {
                        color: v3(1.0, 0.8, 0.6),
                        ka: q(0.1),
                        kd: q(0.3),
                        ks: q(0.7),
                        shininess: q(n),
                    },
                    lights: std::vec![light],
                    ambient: q(0.2),
                    specular: model,
                    viewer,
                };
                let width = (2.0 / n.sqrt()).clamp(0.005, 0.5);
                let len = 64;
                let n0 = [h[0] - width, h[1] + 0.01, h[2]];
                let dn = [2.0 * width / f64::from(len), 0.0, 0.0];
                // Local viewer: the surface point at (0, 0, -5), the eye at the origin.
                let (p0, dp) = ([0.0, 0.0, -5.0], [0.001, 0.0, 0.0]);
                let e = span_error(&c, n0, dn, p0, dp, len);
                row.push(e);
                worst = worst.max(e);
            }
        }
        table.push((n, row));
    }
    for (n, row) in &table {
        std::println!("n = {n:>6}: {row:.2?}");
    }
    assert!(worst <= 1.0, "{worst}");
}

/// Random materials, 1 to 4 lights, directional and point, both models
/// and viewers, spans with normals up to 60° apart: within 1 level.
#[test]
fn random_spans_against_f64() {
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut f =
        |lo: f64, hi: f64| lo + (hi - lo) * ((xorshift(&mut s) >> 11) as f64 / (1u64 << 53) as f64);
    let mut worst = [0f64; 2];
    for it in 0..3000 {
        let viewer = if it % 2 == 0 {
            Viewer::Infinite
        } else {
            Viewer::Local
        };
        let point = it % 4 >= 2;
        let nl = 1 + it % 4;
        let mut lights = Vec::new();
        for _ in 0..nl {
            let mut l = if point && f(0.0, 1.0) < 0.7 {
                Light::point(v3(f(-5.0, 5.0), f(-5.0, 5.0), f(-3.0, 5.0)), q(f(0.2, 1.5)))
            } else {
                Light::directional(v3(f(-1.0, 1.0), f(-1.0, 1.0), f(0.0, 1.0)), q(f(0.2, 1.5)))
            };
            l.color = v3(f(0.3, 1.0), f(0.3, 1.0), f(0.3, 1.0));
            lights.push(l);
        }
        let specular = if it % 3 == 1 {
            Specular::Blinn
        } else {
            Specular::Phong
        };
        let c = random_case(&mut f, lights, it % 3 == 0, specular, viewer);
        let n0 = unit([f(-0.7, 0.7), f(-0.7, 0.7), 1.0]);
        let n1 = unit([f(-0.7, 0.7), f(-0.7, 0.7), 1.0]);
        let len = 1 + f(0.0, 79.99) as i32;
        let dn = [0, 1, 2].map(|k| (n1[k] - n0[k]) / 80.0);
        let p0 = [f(-2.0, 2.0), f(-2.0, 2.0), f(-8.0, -3.0)];
        let dp = [f(0.0, 0.03), f(-0.005, 0.005), f(-0.01, 0.01)];
        let e = span_error(&c, n0, dn, p0, dp, len);
        let w = &mut worst[usize::from(viewer == Viewer::Local || point)];
        *w = w.max(e);
    }
    std::println!(
        "kernel vs f64: directional/infinite {:.3}, point/local {:.3} levels",
        worst[0],
        worst[1]
    );
    assert!(worst[0] <= 1.0 && worst[1] <= 1.0, "{worst:?}");
}

/// One to four directional lights with the viewer at infinity on spans
/// of 33 to 256 pixels (the spans run with a single plan, `one::Whole`,
/// and the longer ones past it): random materials, light colours and
/// directions, both models, shininess 1 to 10 000, normals up to 60°
/// apart over 256 pixels: within 1 level of `f64`.
#[test]
fn long_directional_spans_against_f64() {
    let mut s = 0x1234_5678_9abc_def1u64;
    let mut f =
        |lo: f64, hi: f64| lo + (hi - lo) * ((xorshift(&mut s) >> 11) as f64 / (1u64 << 53) as f64);
    let mut worst = [0f64; 2];
    for it in 0..1600 {
        let nl = 1 + it % 4;
        let mut lights = Vec::new();
        for _ in 0..nl {
            let mut l =
                Light::directional(v3(f(-1.0, 1.0), f(-1.0, 1.0), f(0.0, 1.0)), q(f(0.2, 1.5)));
            l.color = v3(f(0.3, 1.0), f(0.3, 1.0), f(0.3, 1.0));
            lights.push(l);
        }
        let specular = if it % 8 >= 4 {
            Specular::Blinn
        } else {
            Specular::Phong
        };
        let c = random_case(&mut f, lights, it % 3 == 0, specular, Viewer::Infinite);
        let n0 = unit([f(-0.7, 0.7), f(-0.7, 0.7), 1.0]);
        let n1 = unit([f(-0.7, 0.7), f(-0.7, 0.7), 1.0]);
        let len = 33 + f(0.0, 250.99) as i32;
        let dn = [0, 1, 2].map(|k| (n1[k] - n0[k]) / 256.0);
        let e = span_error(&c, n0, dn, [0.0; 3], [0.0; 3], len);
        let w = &mut worst[usize::from(nl > 1)];
        *w = w.max(e);
    }
    std::println!(
        "kernel vs f64, long spans: one light {:.3}, two to four {:.3} levels",
        worst[0],
        worst[1]
    );
    assert!(worst[0] <= 1.0 && worst[1] <= 1.0, "{worst:?}");
}

/// Two to eight directional lights with the viewer at infinity (the
/// loop of several lights, module `multi`): random materials, light
/// colours and directions, both models, shininess 1 to 10 000, spans of
/// 1 to 120 pixels (short spans, full and partial chunks) with normals up
/// to 60° apart: within 1 level of `f64`, every case through that loop.
#[test]
fn several_directional_lights_against_f64() {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut f =
        |lo: f64, hi: f64| lo + (hi - lo) * ((xorshift(&mut s) >> 11) as f64 / (1u64 << 53) as f64);
    let mut worst = 0f64;
    let mut cases = 0;
    for it in 0..1200 {
        let nl = 2 + it % 7;
        let mut lights = Vec::new();
        for _ in 0..nl {
            let mut l = Light::directional(
                v3(f(-1.0, 1.0), f(-1.0, 1.0), f(0.0, 1.0)),
                q(f(0.1, 2.0) / nl as f64),
            );
            l.color = v3(f(0.3, 1.0), f(0.3, 1.0), f(0.3, 1.0));
            lights.push(l);
        }
        let specular = if it % 2 == 1 {
            Specular::Blinn
        } else {
            Specular::Phong
        };
        let c = random_case(&mut f, lights, it % 3 == 0, specular, Viewer::Infinite);
        let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
        assert!(
            PhongKernel::new(&shade).unwrap().multi.is_some(),
            "case {it}"
        );
        let n0 = unit([f(-0.7, 0.7), f(-0.7, 0.7), 1.0]);
        let n1 = unit([f(-0.7, 0.7), f(-0.7, 0.7), 1.0]);
        let len = 1 + f(0.0, 119.99) as i32;
        let dn = [0, 1, 2].map(|k| (n1[k] - n0[k]) / 120.0);
        let e = span_error(&c, n0, dn, [0.0; 3], [0.0; 3], len);
        worst = worst.max(e);
        cases += 1;
    }
    std::println!("several directional lights vs f64: {worst:.3} levels over {cases} spans");
    assert_eq!(cases, 1200);
    assert!(worst <= 1.0, "{worst}");
}

/// The loop of several lights is taken while every channel sum, each
/// light at its largest terms, stays below `2^31`, and not beyond (each
/// light at most `2^28 c` for diffuse and specular coefficients `c`): two
/// lights of coefficient 3 fit, two of 4 do not, eight of 0.9 fit, eight
/// of 1 do not (`2^31.003` with the ambient term).
#[test]
fn several_lights_sum_bound() {
    let mat = Material {
        color: v3(1.0, 1.0, 1.0),
        ka: q(0.5),
        kd: q(1.0),
        ks: q(1.0),
        shininess: q(20.0),
    };
    let kernel_multi = |k: usize, ip: f64| {
        let lights: Vec<Light<Q16>> = (0..k)
            .map(|_| Light::directional(v3(0.0, 0.0, 1.0), q(ip)))
            .collect();
        let shade = Shade::new(&mat, q(0.2), &lights, Specular::Phong, Viewer::Infinite).unwrap();
        PhongKernel::new(&shade).unwrap().multi
    };
    assert!(kernel_multi(1, 1.0).is_none(), "one light: module one");
    assert!(kernel_multi(2, 3.0).is_some());
    assert!(kernel_multi(2, 4.0).is_none());
    assert!(kernel_multi(8, 0.9).is_some());
    assert!(kernel_multi(8, 1.0).is_none());
    // The start is the ambient term plus 2^15 (d + s) per light, wrapping.
    let lights = [Light::directional(v3(0.0, 0.0, 1.0), q(1.0)); 2];
    let shade = Shade::new(&mat, q(0.2), &lights, Specular::Phong, Viewer::Infinite).unwrap();
    let k = PhongKernel::new(&shade).unwrap();
    let l = &k.lights[0];
    let want = (0..3).map(|c| {
        (i64::from(k.amb19[c]) + 2 * ((i64::from(l.d4[c]) + i64::from(l.s4[c])) << 15)) as i32
    });
    assert!(k.multi.unwrap().into_iter().eq(want));
}

/// Error of the linearly interpolated specular table against
/// `(1 - u/m)^m` in `f64`, for table sizes 16 to 512 (the sweep that chose
/// [`SPEC_SEGMENTS`]): printed, and the chosen size within 0.2 level.
#[test]
fn spec_table_sweep() {
    let mut chosen = 0f64;
    std::println!("segments | max error (levels of 255), shininess 1 .. 10 000");
    for seg in [16usize, 32, 64, 128, 256, 512] {
        let mut worst = 0f64;
        for &n in &[1.0f64, 2.0, 3.0, 10.0, 31.0, 64.0, 100.0, 800.0, 10_000.0] {
            let m = (n * 65536.0) as u32;
            let t = m.min(U_MAX);
            let tab: Vec<f64> = (0..=seg)
                .map(|j| {
                    let u = (u64::from(t) * j as u64 / seg as u64) as u32;
                    if j == seg && t == m {
                        0.0
                    } else {
                        f64::from(approx16::spec_entry(u, m)) / 32768.0
                    }
                })
                .collect();
            let mf = f64::from(m) / 65536.0;
            let tf = f64::from(t) / 65536.0;
            for k in 0..=20_000 {
                let u = tf * f64::from(k) / 20_000.0;
                let pos = u / tf * seg as f64;
                let j = (pos as usize).min(seg - 1);
                let fr = pos - j as f64;
                let got = tab[j] + (tab[j + 1] - tab[j]) * fr;
                let want = (1.0 - u / mf).max(0.0).powf(mf);
                worst = worst.max((got - want).abs() * 255.0);
            }
        }
        std::println!("{seg:>8} | {worst:.3}");
        if seg == SPEC_SEGMENTS {
            chosen = worst;
        }
    }
    assert!(chosen <= 0.2, "{chosen}");
}

/// `spec_entry` against `f64` at every table point of a few shininesses.
#[test]
fn spec_entries() {
    let mut worst = 0f64;
    for &n in &[1.0f64, 1.5, 7.0, 31.9, 32.0, 100.0, 5000.0, 10_000.0] {
        let m = (n * 65536.0) as u32;
        for k in 0..=256u32 {
            let u = (u64::from(m.min(U_MAX)) * u64::from(k) / 256) as u32;
            let got = f64::from(approx16::spec_entry(u, m)) / 32768.0;
            let (uf, mf) = (f64::from(u) / 65536.0, f64::from(m) / 65536.0);
            let want = (1.0 - uf / mf).max(0.0).powf(mf);
            worst = worst.max((got - want).abs());
        }
    }
    std::println!("spec_entry: {:.2e} ({:.2} bits)", worst, -worst.log2());
    assert!(worst <= 1.0 / 2048.0, "{worst}");
}

/// The `1/|n|` table: within `2^-11.4` relative at `|n|² = 1/4`, `2^-14.5`
/// from `|n|² >= 0.9`.
#[test]
fn rsqrt_n_table() {
    let (mut lo, mut hi) = (0f64, 0f64);
    for f in (1 << 26)..(5 << 26) {
        if f % 7 != 0 {
            continue;
        }
        let r = f64::from(rsqrt_n(f).unwrap()) / 65536.0;
        let want = 1.0 / (f64::from(f) / f64::from(1 << 28)).sqrt();
        let e = (r / want - 1.0).abs();
        if f64::from(f) >= 0.9 * f64::from(1 << 28) {
            hi = hi.max(e);
        } else {
            lo = lo.max(e);
        }
    }
    std::println!(
        "rsqrt_n: {:.2} bits below 0.9, {:.2} bits above",
        -lo.log2(),
        -hi.log2()
    );
    assert!(
        lo <= 2f64.powf(-11.4) && hi <= 2f64.powf(-14.5),
        "{lo} {hi}"
    );
    assert_eq!(rsqrt_n((1 << 26) - 1), None);
    assert_eq!(rsqrt_n(5 << 26), None);
}

/// Seed 000's Phong example (`tests/seed_phong.rs`) through the `fast`
/// profile's own shaders, which that integration test cannot reach: the
/// normals of row 11 of the seed's triangle, interpolated by the
/// rasterizer, then normalised as each shader does per pixel — the span
/// kernel (`n · 2^16/|n|` from the table [`RS`], affine `fast`) and the
/// per-pixel shader of `fast-pc` (`approx16::unit` of the Q16 normal) —
/// against the exact plane normal. Bounds: the kernel's table is within
/// `2^-12.7` relative for `|n|² >= 1/2` (row 11's normals are at least
/// 0.707 long; linear interpolation error `h²/8 · (3/4) f^-5/2` over
/// segments of `h = 1/64`, 1.3e-4 of `1/|n| = 1.41`) plus the Q16 rounding
/// `2^-17`: 1.2e-4; `approx16::unit` is within `2^-15` plus the Q30 -> Q16
/// rounding `2^-17` divided by the length (x 1.41): 4.1e-5, allowed 5e-5.
#[test]
fn seed_row_11_fast_shaders() {
    use crate::num::{Fast, Profile, Real};
    use crate::raster::{draw_triangle, SubpixelBits, Vertex};
    use crate::target::Window;
    struct Row11(Vec<[i32; 3]>);
    impl crate::raster::Spans<i32, 3> for Row11 {
        fn span(&mut self, s: &Span<i32, 3>) {
            if s.y == 11 {
                // (7, 11), (10, 11) and one step past the end, (13, 11).
                for i in [0, 3, 6] {
                    self.0.push([0, 1, 2].map(|k| s.a[k] + i * s.da[k]));
                }
            }
        }
    }
    let h = core::f64::consts::FRAC_1_SQRT_2;
    let c = |i: i32| i * 16 + 8;
    let vert = |x, y, n: [f64; 3]| Vertex {
        x: c(x),
        y: c(y),
        z: Fast::depth(Q16::from_f64(0.5)),
        attrs: n.map(|v| Fast::unit(Q16::from_f64(v))),
    };
    let tri = [
        vert(9, 15, [1.0, 0.0, 0.0]),
        vert(3, 3, [h, h, 0.0]),
        vert(17, 7, [0.0, 0.0, 1.0]),
    ];
    let win = Window {
        width: 32,
        y0: 0,
        y1: 32,
    };
    let mut row = Row11(Vec::new());
    draw_triangle(&tri, SubpixelBits::DEFAULT, win, &mut row).unwrap();
    assert_eq!(row.0.len(), 3);
    // The exact plane normal (barycentric) at (x, 11), normalised.
    let plane = |x: f64| {
        let p = [(9.0, 15.0), (3.0, 3.0), (17.0, 7.0)];
        let nv = [[1.0, 0.0, 0.0], [h, h, 0.0], [0.0, 0.0, 1.0]];
        let area = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
            (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)
        };
        let q = (x, 11.0);
        let t = area(p[0], p[1], p[2]);
        let w = [
            area(q, p[1], p[2]) / t,
            area(p[0], q, p[2]) / t,
            area(p[0], p[1], q) / t,
        ];
        unit([0, 1, 2].map(|k| w[0] * nv[0][k] + w[1] * nv[1][k] + w[2] * nv[2][k]))
    };
    for (n, x) in row.0.iter().zip([7.0, 10.0, 13.0]) {
        let want = plane(x);
        // The kernel: N·X = (n·X) · 2^16/|n| (Q30 · Q16).
        let r = rsqrt_n((sq3(*n) >> 32) as i32).unwrap();
        let kernel = n.map(|c| (c as f64 / (1u64 << 30) as f64) * f64::from(r) / 65536.0);
        // `fast-pc`'s per-pixel shader: `approx16::unit` of the Q16 normal.
        let n16 = n.map(|c| Fast::unit_back(c).to_fixed_i32(16));
        let pc = approx16::unit(n16).map(|c| f64::from(c) / 65536.0);
        let e = |a: [f64; 3]| (0..3).map(|k| (a[k] - want[k]).abs()).fold(0.0, f64::max);
        std::println!("({x}, 11): kernel {:.2e}, fast-pc {:.2e}", e(kernel), e(pc));
        for k in 0..3 {
            assert!(
                (kernel[k] - want[k]).abs() <= 1.2e-4,
                "kernel at ({x}, 11): {kernel:?} vs {want:?}"
            );
            assert!(
                (pc[k] - want[k]).abs() <= 5e-5,
                "fast-pc at ({x}, 11): {pc:?} vs {want:?}"
            );
        }
    }
}

/// `v` in Q30 (unit normals and their steps).
fn q30(v: [f64; 3]) -> [i32; 3] {
    v.map(|c| (c * (1u64 << 30) as f64).round() as i32)
}

/// `v` in Q16 (positions and their steps).
fn q16(v: [f64; 3]) -> [i32; 3] {
    v.map(|c| (c * 65536.0).round() as i32)
}

/// The point loop's test material (shininess `n`) lit by one point light
/// at `lp`, Phong, local viewer.
fn point_case(n: f64, lp: [f64; 3]) -> Case {
    Case {
        mat: Material {
            color: v3(1.0, 0.7, 0.5),
            ka: q(0.1),
            kd: q(0.6),
            ks: q(0.9),
            shininess: q(n),
        },
        lights: std::vec![Light::point(v3(lp[0], lp[1], lp[2]), q(1.0))],
        ambient: q(0.2),
        specular: Specular::Phong,
        viewer: Viewer::Local,
    }
}

/// Light positions, first pixels and steps of the point loop's span
/// tests (a light close to the surface: steps up to 1/20 of `|l|`).
const POINT_SPANS: [([f64; 3], [f64; 3], [f64; 3]); 3] = [
    ([1.5, 1.0, -3.0], [-1.0, 0.0, -5.0], [0.01, 0.0, 0.0]),
    ([0.0, 0.0, -2.5], [-0.8, 0.1, -3.4], [0.02, 0.0, 0.002]),
    ([0.3, -0.2, -2.0], [0.5, 0.5, -2.8], [-0.01, 0.003, -0.004]),
];

/// The point loop (module `point`): one point light, local viewer,
/// Phong, shininess below 256, on spans like the firmware's and the
/// dodecahedron's (a light close to the surface: steps up to 1/20 of
/// `|l|`), across the highlight: every chunk runs the 32-bit loop, within
/// 1 level of `f64`.
#[test]
fn point_loop_runs() {
    let mut worst = 0f64;
    for &n in &[1.0, 3.0, 20.0, 100.0, 255.0] {
        for &(lp, p0, dp) in &POINT_SPANS {
            let c = point_case(n, lp);
            let n0 = unit([-0.4, 0.1, 1.0]);
            let dn = [0.006, 0.0, -0.002];
            let len = 100;
            let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
            let k = PhongKernel::new(&shade).unwrap();
            let span = (q30(n0), q30(dn), q16(p0), q16(dp));
            assert!(k.point_plan_runs(span, len), "n {n} light {lp:?}");
            for i in (0..len).step_by(point::PCHUNK) {
                let kk = (len - i).min(point::PCHUNK as u32) as usize;
                assert!(
                    k.point_loop_runs(span, i, kk),
                    "n {n} light {lp:?} chunk {i}"
                );
            }
            let e = span_error(&c, n0, dn, p0, dp, len as i32);
            worst = worst.max(e);
        }
    }
    std::println!("point loop vs f64: {worst:.3} levels");
    assert!(worst <= 1.0, "{worst}");
}

/// The point loop's `1/|ṽ|` as a quadratic a chunk (`point::VIEW_QUAD`)
/// against its series step a pixel on the same chunks: `N·L` the same,
/// the specular factor within `4·2^15·m·(3152 r³ + 2^-19 + 2·2^-18.7)`
/// units of Q15 (`r` the view vector's step over its length: the
/// quadratic's error and both loops' own, `|n|² >= 1/4`) plus one step
/// of the table's Q7 position (where the rounding flips, the quadratic's
/// `2^-18.4` of `1/|ṽ|` suffices) and 2, over the spans of
/// `point_fine_chunks` (`r` from 1/680 to 1/420) and shininesses 1 to
/// 255.
#[test]
fn point_view_quad_against_series() {
    let spans: [([f64; 3], [f64; 3], [f64; 3]); 4] = [
        ([1.5, 1.0, -3.0], [-1.0, 0.0, -5.0], [0.01, 0.0, 0.0]),
        ([0.0, 2.0, 0.0], [-0.8, 0.1, -3.4], [0.005, 0.0, 0.001]),
        ([-3.0, 1.0, -2.0], [0.5, 0.5, -2.8], [-0.004, 0.002, -0.002]),
        ([10.0, 20.0, 5.0], [-2.0, 1.0, -9.0], [0.02, 0.01, 0.0]),
    ];
    let (mut wsp, mut runs) = (0f64, 0);
    for &n in &[1.0, 3.0, 20.0, 100.0, 255.0] {
        for &(lp, p0, dp) in &spans {
            let c = point_case(n, lp);
            let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
            let k = PhongKernel::new(&shade).unwrap();
            for len in [40u32, 64, 100] {
                let span = (
                    q30(unit([-0.4, 0.1, 1.0])),
                    q30([0.006, 0.0, -0.002]),
                    q16(p0),
                    q16(dp),
                );
                let Some((dnl, dsp)) = k.quad_against_series(span, len) else {
                    panic!("no plan: n {n} light {lp:?} len {len}");
                };
                // The step over the shortest |p| along the span.
                let len2 = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                let pmin = (0..len)
                    .map(|t| len2([0, 1, 2].map(|a| p0[a] + f64::from(t) * dp[a])))
                    .fold(f64::MAX, f64::min);
                let r = len2(dp) / pmin;
                // The position K·w·A/|n|² (|n|² >= 1/4) moved by the errors
                // of w, and one Q7 step of the table where it flips.
                let step7 = k
                    .table
                    .windows(2)
                    .map(|w| (i32::from(w[0]) - i32::from(w[1])).abs())
                    .max()
                    .unwrap_or(0)
                    / 128
                    + 1;
                let bound = 4.0
                    * 32768.0
                    * n
                    * (3152.0 * r.powi(3) + 2f64.powi(-19) + 2.0 * 2f64.powf(-18.7))
                    + f64::from(step7)
                    + 2.0;
                assert!(
                    dnl == 0 && f64::from(dsp) <= bound,
                    "n {n} {lp:?} len {len}: {dnl} {dsp} > {bound}"
                );
                wsp = wsp.max(f64::from(dsp) / bound);
                runs += 1;
            }
        }
    }
    std::println!("view quadratic vs series: specular within {wsp:.3} of the bound, {runs} spans");
}

/// The point loop's fine chunks (module `point`: steps of `l̃` and `ṽ`
/// at most 1/64 of their length, one first-order step a pixel): spans
/// with the light and the eye far enough take them, within 1 level of
/// `f64`, and their terms stay within the bound of the loop's error
/// (`2^-18.7` of `w` each: the specular factor within `m·2^-2.7 + 2`
/// units of Q15, `N·L` within 1) of the same chunks run without them;
/// a light close to the surface (steps of 1/20 of `|l|`) is not fine.
#[test]
fn point_fine_chunks() {
    let spans: [([f64; 3], [f64; 3], [f64; 3]); 4] = [
        ([1.5, 1.0, -3.0], [-1.0, 0.0, -5.0], [0.01, 0.0, 0.0]),
        ([0.0, 2.0, 0.0], [-0.8, 0.1, -3.4], [0.005, 0.0, 0.001]),
        ([-3.0, 1.0, -2.0], [0.5, 0.5, -2.8], [-0.004, 0.002, -0.002]),
        ([10.0, 20.0, 5.0], [-2.0, 1.0, -9.0], [0.02, 0.01, 0.0]),
    ];
    let (mut worst, mut wnl, mut wsp) = (0f64, 0, 0f64);
    for &n in &[1.0, 3.0, 20.0, 100.0, 255.0] {
        for &(lp, p0, dp) in &spans {
            let c = point_case(n, lp);
            let n0 = unit([-0.4, 0.1, 1.0]);
            let dn = [0.006, 0.0, -0.002];
            let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
            let k = PhongKernel::new(&shade).unwrap();
            for len in [40u32, 64, 100] {
                let span = (q30(n0), q30(dn), q16(p0), q16(dp));
                let Some((fine, dnl, dsp)) = k.fine_against_coarse(span, len) else {
                    panic!("no plan: n {n} light {lp:?} len {len}");
                };
                assert!(fine, "n {n} light {lp:?} len {len}");
                let bound = n * 2f64.powf(-2.7) + 2.0;
                assert!(
                    dnl <= 1 && f64::from(dsp) <= bound,
                    "n {n} {lp:?}: {dnl} {dsp}"
                );
                wnl = wnl.max(dnl);
                wsp = wsp.max(f64::from(dsp) / bound);
                worst = worst.max(span_error(&c, n0, dn, p0, dp, len as i32));
            }
        }
        let (lp, p0, dp) = POINT_SPANS[1];
        let c = point_case(n, lp);
        let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
        let k = PhongKernel::new(&shade).unwrap();
        let span = (
            q30(unit([-0.4, 0.1, 1.0])),
            q30([0.006, 0.0, -0.002]),
            q16(p0),
            q16(dp),
        );
        assert_eq!(k.fine_against_coarse(span, 100).map(|f| f.0), Some(false));
    }
    std::println!(
        "point fine chunks vs f64: {worst:.3} levels; against the other loop: N·L {wnl}, specular {wsp:.3} of the bound"
    );
    assert!(worst <= 1.0, "{worst}");
}

/// Short spans of the point loop (below `point::SHORT_SPAN` pixels: the
/// loop's arithmetic a pixel alone, `point_one`) across the highlight:
/// every pixel takes `point_one`, within 1 level of `f64`.
#[test]
fn point_short_spans() {
    let mut worst = 0f64;
    let mut pixels = 0;
    for &n in &[1.0, 3.0, 20.0, 100.0, 255.0] {
        for &(lp, p0, dp) in &POINT_SPANS {
            let c = point_case(n, lp);
            let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
            let k = PhongKernel::new(&shade).unwrap();
            let dn = [0.006, 0.0, -0.002];
            // Spans of 1 to 7 pixels from every 9th pixel of a 100-pixel one.
            for s in (0..100).step_by(9) {
                let t = f64::from(s);
                let n0 = unit([-0.4 + 0.006 * t, 0.1, 1.0 - 0.002 * t]);
                let ps = [0, 1, 2].map(|a| p0[a] + t * dp[a]);
                let len = 1 + s % 7;
                let span = (q30(n0), q30(dn), q16(ps), q16(dp));
                for j in 0..len as u32 {
                    assert!(k.point_one_runs(span, j), "n {n} light {lp:?} at {s}");
                }
                worst = worst.max(span_error(&c, n0, dn, ps, dp, len));
                pixels += len;
            }
        }
    }
    std::println!("point short spans vs f64: {worst:.3} levels over {pixels} pixels");
    assert!(worst <= 1.0, "{worst}");
}

/// A span's plan (module `point`), stepped from chunk to chunk by shifts
/// and adds, gives each chunk the very 32-bit state of the chunk's own
/// set-up from its first pixel's vectors where the two scale them alike
/// (spans of 40 to 400 pixels, lights near and far, a viewer close up).
#[test]
fn point_plan_equals_chunk_setup() {
    let (mut chunks, mut spans) = (0, 0);
    for &(lp, p0, dp) in &[
        ([1.5, 1.0, -3.0], [-1.0, 0.0, -5.0], [0.01, 0.0, 0.0]),
        ([0.0, 0.0, -2.5], [-0.8, 0.1, -3.4], [0.004, 0.0, 0.002]),
        ([0.3, -0.2, -2.0], [0.5, 0.5, -2.8], [-0.003, 0.001, -0.001]),
        ([10.0, 20.0, 5.0], [-2.0, 1.0, -9.0], [0.002, 0.001, 0.0]),
    ] {
        let c = point_case(40.0, lp);
        let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
        let k = PhongKernel::new(&shade).unwrap();
        for &len in &[40u32, 65, 100, 200, 400] {
            let n0 = unit([-0.4, 0.1, 1.0]);
            let dn = [0.6 / f64::from(len), 0.0, -0.2 / f64::from(len)];
            let span = (q30(n0), q30(dn), q16(p0), q16(dp));
            // (A span whose proven ranges the plan's bounds over the
            // whole span miss has no plan: each chunk sets itself up.)
            if let Some((both, equal)) = k.plan_matches_setup(span, len) {
                assert!(equal, "light {lp:?} len {len}");
                chunks += both;
                spans += 1;
            }
        }
    }
    std::println!("{chunks} chunks of {spans} spans equal");
    assert!(spans >= 16 && chunks >= 80, "{spans} {chunks}");
}

/// The specular table built with the stepped quotient (`PhongKernel::new`)
/// equals `spec_entry` at every entry, for shininesses around the
/// branches (8, 32) and up to 10 000.
#[test]
fn spec_table_stepped_equals_direct() {
    for &n in &[
        1.0, 2.5, 7.99, 8.0, 9.3, 31.0, 32.0, 100.0, 255.5, 4096.0, 10_000.0,
    ] {
        let mat = Material {
            color: v3(1.0, 1.0, 1.0),
            ka: q(0.1),
            kd: q(0.5),
            ks: q(0.5),
            shininess: q(n),
        };
        let lights = [Light::directional(v3(0.0, 0.0, 1.0), q(1.0))];
        let shade = Shade::new(&mat, q(0.2), &lights, Specular::Phong, Viewer::Infinite).unwrap();
        let k = PhongKernel::new(&shade).unwrap();
        let m = q(n).to_bits() as u32;
        let t = m.min(U_MAX);
        for j in 0..SPEC_SEGMENTS {
            let u = (u64::from(t) * j as u64 / SPEC_SEGMENTS as u64) as u32;
            assert_eq!(k.table[j], approx16::spec_entry(u, m), "n {n} entry {j}");
        }
    }
}

/// A kernel made through the specular-table cache equals the kernel made
/// afresh: with an empty cache, a cache of another shininess (rebuilt and
/// replaced) and one of the same shininess (taken), for Phong and Blinn.
#[test]
fn spec_cache_same_kernel() {
    let light = Light::directional(v3(0.3, 0.4, 0.866), q(1.0));
    let shade = |n: f64, s: Specular| {
        let mat = Material {
            color: v3(0.9, 0.7, 0.5),
            ka: q(0.1),
            kd: q(0.7),
            ks: q(0.5),
            shininess: q(n),
        };
        Shade::new(&mat, q(0.2), &[light], s, Viewer::Infinite).unwrap()
    };
    let mut cache = None;
    for s in [Specular::Phong, Specular::Blinn] {
        for n in [20.0, 20.0, 800.0, 3.0, 3.0, 10_000.0] {
            let sh = shade(n, s);
            let fresh = PhongKernel::new(&sh).unwrap();
            let cached = PhongKernel::new_cached(crate::num::Raw16::Q16, &sh, &mut cache).unwrap();
            assert_eq!(fresh.table, cached.table, "n = {n}");
            assert_eq!(fresh.kf, cached.kf);
            let m = if s == Specular::Blinn { n / 2.0 } else { n };
            assert_eq!(
                cache.as_ref().map(|c| c.m),
                Some(SpecCache::key((m * 65536.0) as u32))
            );
            // The same pixels along a span across the highlight.
            let n0 = [-(1 << 28), 1 << 27, 1 << 30];
            let dn = [1 << 22, 0, -(1 << 20)];
            let mut a = fresh.begin(n0, dn, [0; 3], [0; 3], false);
            let mut b = cached.begin(n0, dn, [0; 3], [0; 3], false);
            for _ in 0..64 {
                assert_eq!(a.next(), b.next());
            }
        }
    }
}

/// `rsqrt64` against `f64` over `x` from 2 to `u64::MAX`: both ends of
/// every even shift's mantissa range and random values of every
/// magnitude, within the bound stated in its doc comment.
#[test]
fn rsqrt64_within_max_error() {
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut worst = 0f64;
    let mut check = |x: u64| {
        let (y, e) = rsqrt64(x);
        assert!((1 << 29..=1 << 30).contains(&y), "{x}: {y}");
        let got = f64::from(y) * 2f64.powi(-(e as i32));
        // 1/sqrt(x) in f64 from two halves (x is not exact in f64 above 2^53).
        let xf = (x >> 11) as f64 * 2048.0 + (x & 0x7FF) as f64;
        let exact = 1.0 / xf.sqrt();
        worst = worst.max((got - exact).abs() / exact);
    };
    for b in 1..64u32 {
        let lo = 1u64 << b;
        for k in 0..2000u64 {
            check(lo + k);
            check(lo.wrapping_mul(2).wrapping_sub(1).wrapping_sub(k).max(lo));
        }
    }
    for _ in 0..400_000 {
        let x = xorshift(&mut seed) >> (xorshift(&mut seed) % 62);
        check(x.max(2));
    }
    let lg = worst.log2();
    std::println!("rsqrt64: rel error 2^{lg:.2}");
    assert!(worst <= RSQRT64_MAX_ERROR, "2^{lg:.2}");
    assert!(
        worst > RSQRT64_MAX_ERROR / 4.0,
        "2^{lg:.2}: the bound is tight"
    );
}

/// [`PosPlane::start`] against the exact plane through the three vertices
/// (`f64`, exact for these magnitudes): at pixel `i` of a span, the start
/// stepped by the rounded gradient `dp` lies within `½ + |i - h| · |dp -
/// g| + (1 + |Δx| + |Δy|) · (2^-13 + G · 2^-28) + 2^-12` raw units of it
/// (the bound on [`PosPlane`]), on random triangles of up to 4096 pixels
/// with positions within `±2^28` raw and spans within the triangle's box.
#[test]
fn plane_start_error() {
    let mut seed = 0x05ee_d0f9_1a4e_u64;
    let sub = crate::num::SubpixelBits::DEFAULT;
    let sc = f64::from(1u32 << sub.get());
    let mut worst_mid = 0.0f64;
    let mut cases = 0;
    for _ in 0..4000 {
        let mut r = |m: u64| (xorshift(&mut seed) % m) as i64;
        let size = 1 << (2 + r(11));
        let v: [([i32; 2], [i32; 3]); 3] = core::array::from_fn(|_| {
            (
                [
                    (r(size * 16) + r(1000) * 16) as i32,
                    (r(size * 16) + r(1000) * 16) as i32,
                ],
                [0; 3].map(|_: i32| (r(1 << 29) - (1 << 28)) as i32),
            )
        });
        let p = PosPlane::new(v, sub);
        let ([x0, y0], _) = v[0];
        let d = [
            f64::from(v[1].0[0] - x0),
            f64::from(v[1].0[1] - y0),
            f64::from(v[2].0[0] - x0),
            f64::from(v[2].0[1] - y0),
        ];
        let area2 = d[0] * d[3] - d[2] * d[1];
        if area2 == 0.0 {
            assert_eq!(p, PosPlane::NONE);
            continue;
        }
        let exact = |k: usize, x: f64, y: f64| {
            let a = |j: usize| f64::from(v[j].1[k]);
            let (d1, d2) = (a(1) - a(0), a(2) - a(0));
            let gx = (d1 * d[3] - d2 * d[1]) / area2;
            let gy = (d2 * d[0] - d1 * d[2]) / area2;
            let (px, py) = (x * sc + sc / 2.0, y * sc + sc / 2.0);
            (
                a(0) + gx * (px - f64::from(x0)) + gy * (py - f64::from(y0)),
                gx * sc,
            )
        };
        if !p.ok {
            // Only for gradients of 2^28 raw a pixel or more.
            let big = (0..3).any(|k| {
                let (b, gx) = exact(k, 0.0, 0.0);
                let gy = exact(k, 0.0, 1.0).0 - b;
                gx.abs().max(gy.abs()) >= (1u64 << 28) as f64 - 1.0
            });
            assert!(big, "{v:?}");
            continue;
        }
        cases += 1;
        let xs = v.map(|c| i64::from(c.0[0]) >> sub.get());
        let ys = v.map(|c| i64::from(c.0[1]) >> sub.get());
        let (xlo, xhi) = (*xs.iter().min().unwrap(), *xs.iter().max().unwrap());
        let (ylo, yhi) = (*ys.iter().min().unwrap(), *ys.iter().max().unwrap());
        for _ in 0..4 {
            let mut r = |m: i64| (xorshift(&mut seed) % m.max(1) as u64) as i64;
            let y = ylo + r(yhi - ylo + 1);
            let xa = xlo + r(xhi - xlo + 1);
            let len = 1 + r(xhi - xa + 1) as u32;
            let dp: [i32; 3] = core::array::from_fn(|k| exact(k, 0.0, 0.0).1.round() as i32);
            let start = p.start(xa as i32, y as i32, len, [0; 3], dp);
            let h = (len - 1) / 2;
            for i in [0, h, len - 1] {
                for k in 0..3 {
                    let (e, g) = exact(k, (xa + i64::from(i)) as f64, y as f64);
                    let got = f64::from(start[k]) + f64::from(i) * f64::from(dp[k]);
                    let off = (f64::from(i) - f64::from(h)).abs();
                    let gm = (0..3)
                        .map(|k| exact(k, 0.0, 0.0).1.abs())
                        .chain((0..3).map(|k| {
                            let (a, _) = exact(k, 1.0, 0.0);
                            let (b, _) = exact(k, 0.0, 0.0);
                            let (c, _) = exact(k, 0.0, 1.0);
                            (a - b).abs().max((c - b).abs())
                        }))
                        .fold(0.0, f64::max);
                    let far = 1.0
                        + ((xa + i64::from(h)) - (i64::from(x0) >> sub.get())).abs() as f64
                        + (y - (i64::from(y0) >> sub.get())).abs() as f64;
                    let plane = far * (1.0 / 8192.0 + gm / (1u64 << 28) as f64) + 1.0 / 4096.0;
                    let bound = 0.5 + off * (f64::from(dp[k]) - g).abs() + plane;
                    // Modulo 2^32 (wrapping beyond the triangle).
                    let m = (got - e).rem_euclid(4_294_967_296.0);
                    let err = m.min(4_294_967_296.0 - m);
                    assert!(
                        err <= bound,
                        "{v:?} x {xa} y {y} len {len} i {i}: {err} > {bound}"
                    );
                    if i == h {
                        worst_mid = worst_mid.max(err - plane);
                    }
                }
            }
        }
    }
    std::println!("plane start: {cases} triangles, worst at the middle {worst_mid:.4} raw");
    assert!(cases > 3000 && worst_mid <= 0.5);
}

/// One triangle of the point loop from its quadratics (`TriQuad`): every
/// row's span from the pixel centres inside the triangle (vertices `s` in
/// pixels, normals `n`, eye positions `p`), the kernel's colours against
/// the twin on the exactly interpolated normal and position at each
/// centre; returns the worst channel error (levels) and how many pixels
/// took the quadratics (spans of `TRI_SHORT_SPAN` pixels or more), or
/// `None` when the triangle has no quadratics.
fn tri_error(c: &Case, s: [[f64; 2]; 3], n: [[f64; 3]; 3], p: [[f64; 3]; 3]) -> Option<(f64, u32)> {
    let shade = Shade::new(&c.mat, c.ambient, &c.lights, c.specular, c.viewer).unwrap();
    let k = PhongKernel::new(&shade).unwrap();
    let twin = twin_of(c);
    let sub = crate::num::SubpixelBits::DEFAULT;
    let sc = f64::from(1u32 << sub.get());
    let xy = s.map(|v| v.map(|c| (c * sc).round() as i32));
    let sf = xy.map(|v| v.map(|c| f64::from(c) / sc));
    let verts = [0, 1, 2].map(|j| (xy[j], q30(n[j]), q16(p[j])));
    let mut tri = TriQuad::new(&k, verts, sub, false);
    if !tri.ok() {
        return None;
    }
    // Barycentric weights at (x, y).
    let area = (sf[1][0] - sf[0][0]) * (sf[2][1] - sf[0][1])
        - (sf[2][0] - sf[0][0]) * (sf[1][1] - sf[0][1]);
    let bary = |x: f64, y: f64| {
        let e = |a: usize, b: usize| {
            ((sf[b][0] - sf[a][0]) * (y - sf[a][1]) - (x - sf[a][0]) * (sf[b][1] - sf[a][1])) / area
        };
        [e(1, 2), e(2, 0), e(0, 1)]
    };
    let lerp = |w: [f64; 3], a: [[f64; 3]; 3]| {
        [0, 1, 2].map(|k| w[0] * a[0][k] + w[1] * a[1][k] + w[2] * a[2][k])
    };
    let (x_lo, x_hi) = (
        sf.iter().map(|v| v[0]).fold(f64::MAX, f64::min),
        sf.iter().map(|v| v[0]).fold(f64::MIN, f64::max),
    );
    let (y_lo, y_hi) = (
        sf.iter().map(|v| v[1]).fold(f64::MAX, f64::min),
        sf.iter().map(|v| v[1]).fold(f64::MIN, f64::max),
    );
    let (mut worst, mut quads) = (0f64, 0u32);
    for y in y_lo.floor() as i32..=y_hi.ceil() as i32 {
        let inside = |x: i32| {
            bary(f64::from(x) + 0.5, f64::from(y) + 0.5)
                .iter()
                .all(|&w| w >= 0.0)
        };
        let xs: Vec<i32> = (x_lo.floor() as i32..=x_hi.ceil() as i32)
            .filter(|&x| inside(x))
            .collect();
        let (Some(&x0), Some(&x1)) = (xs.first(), xs.last()) else {
            continue;
        };
        let len = (x1 - x0 + 1) as u32;
        let at = |x: i32| bary(f64::from(x) + 0.5, f64::from(y) + 0.5);
        let (n0, p0) = (lerp(at(x0), n), lerp(at(x0), p));
        let (n1, p1) = (lerp(at(x0 + 1), n), lerp(at(x0 + 1), p));
        let dn = [0, 1, 2].map(|k| n1[k] - n0[k]);
        let dp = [0, 1, 2].map(|k| p1[k] - p0[k]);
        let mut got = std::vec![None; len as usize];
        k.fill_with(
            q30(n0),
            q30(dn),
            q16(p0),
            q16(dp),
            false,
            len,
            FnOut {
                test: |_| true,
                write: |i: u32, c| got[i as usize] = Some(c),
            },
            Some((&mut tri, x0, y)),
        );
        if len >= point::TRI_SHORT_SPAN {
            quads += len;
        }
        for (i, g) in got.iter().enumerate() {
            let w = at(x0 + i as i32);
            let e = twin.at(
                Vec3::new(lerp(w, n)[0], lerp(w, n)[1], lerp(w, n)[2]).normalize(),
                {
                    let q = lerp(w, p);
                    Vec3::new(q[0], q[1], q[2])
                },
            );
            let g = g.unwrap();
            for (g, w) in [g.r, g.g, g.b].into_iter().zip([e.x, e.y, e.z]) {
                worst = worst.max((f64::from(g) - w * 255.0).abs());
            }
        }
    }
    Some((worst, quads))
}

/// The `f64` twin of a case's shade.
fn twin_of(c: &Case) -> Shade<f64> {
    let mat64 = Material {
        color: to64(c.mat.color),
        ka: c.mat.ka.to_f64(),
        kd: c.mat.kd.to_f64(),
        ks: c.mat.ks.to_f64(),
        shininess: c.mat.shininess.to_f64(),
    };
    let l64: Vec<Light<f64>> = c
        .lights
        .iter()
        .map(|l| Light {
            kind: match l.kind {
                LightKind::Point(p) => LightKind::Point(to64(p)),
                LightKind::Directional(d) => LightKind::Directional(to64(d)),
            },
            intensity: l.intensity.to_f64(),
            color: to64(l.color),
        })
        .collect();
    Shade::new(&mat64, c.ambient.to_f64(), &l64, c.specular, c.viewer).unwrap()
}

/// One random triangle of [`tri_quad_sweep`]: its case, screen vertices,
/// normals and eye positions.
type RandomTri = (Case, [[f64; 2]; 3], [[f64; 3]; 3], [[f64; 3]; 3]);

/// The eye positions of screen vertices `s` on a surface at `depth`,
/// about a unit across and tilted along x about column `cx`.
fn surface(s: [[f64; 2]; 3], depth: f64, cx: f64) -> [[f64; 3]; 3] {
    s.map(|v| {
        [
            (v[0] - 110.0) / 100.0,
            (v[1] - 110.0) / 100.0,
            depth + (v[0] - cx) / 300.0,
        ]
    })
}

/// Sixty random triangles of the point loop from their quadratics, each
/// drawn by `draw` (given the draw `t`, its shininess and a uniform
/// source `f(lo, hi)` seeded by `seed`) and measured against the `f64`
/// twin ([`tri_error`]). Returns the worst error in levels, the
/// triangles made, their pixels from the quadratics, and the set-ups,
/// fine ones and viewer-alone fine ones counted meanwhile.
fn tri_quad_sweep(
    seed: u64,
    mut draw: impl FnMut(usize, f64, &mut dyn FnMut(f64, f64) -> f64) -> RandomTri,
) -> (f64, u32, u32, u32, u32, u32) {
    let (makes0, fines0, fv0) = (super::tri_makes(), super::tri_fines(), super::tri_fines_v());
    let mut seed = seed;
    let mut f = |lo: f64, hi: f64| {
        lo + (hi - lo) * (xorshift(&mut seed) >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut worst, mut quads, mut made) = (0f64, 0u32, 0u32);
    for t in 0..60 {
        let n = [1.0, 3.0, 20.0, 100.0, 255.0][t % 5];
        let (c, s, nv, p) = draw(t, n, &mut f);
        if let Some((e, q)) = tri_error(&c, s, nv, p) {
            made += 1;
            quads += q;
            worst = worst.max(e);
        }
    }
    let (makes, fines) = (super::tri_makes() - makes0, super::tri_fines() - fines0);
    let fv = super::tri_fines_v() - fv0;
    (worst, made, quads, makes, fines, fv)
}

/// Random triangles of the point loop from their quadratics (`TriQuad`):
/// 10 to 120 pixels across, vertex normals up to ~35° apart, the light
/// 1 to 4 units from the surface, shininess 1 to 255: within 1 level of
/// the `f64` twin at every pixel, and most pixels from the quadratics;
/// most triangles fine (module `point`: the first-order step a pixel;
/// the extreme triangles have the others).
#[test]
fn tri_quad_random_against_f64() {
    let (qv0, qn0) = (super::tri_quads_v(), super::tri_quads_n());
    let (worst, made, quads, makes, fines, fv) =
        tri_quad_sweep(0x1234_5678_9abc_def1, |_, n, f| {
            let lp = [f(-2.0, 2.0), f(-2.0, 2.0), f(-3.0, 0.0)];
            let c = point_case(n, lp);
            let size = f(10.0, 120.0);
            let (cx, cy) = (f(20.0, 200.0), f(20.0, 200.0));
            let s = [0, 1, 2].map(|_| [cx + f(-0.5, 0.5) * size, cy + f(-0.5, 0.5) * size]);
            // A surface 4 to 6 units in front of the eye, spanning about a
            // unit; normals around its facing direction.
            let p = surface(s, f(-6.0, -4.0), cx);
            let base = [f(-0.3, 0.3), f(-0.3, 0.3), 1.0];
            let nv =
                [0, 1, 2].map(|_| unit([base[0] + f(-0.3, 0.3), base[1] + f(-0.3, 0.3), base[2]]));
            (c, s, nv, p)
        });
    std::println!(
        "tri quads vs f64: {worst:.3} levels, {made} triangles, {quads} pixels from the quadratics"
    );
    let qv = super::tri_quads_v() - qv0;
    let qn = super::tri_quads_n() - qn0;
    std::println!(
        "tri quads: {fines} of {makes} set-ups fine, {fv} the viewer alone, {qv} with 1/|v| a quadratic, {qn} 1/|n| too"
    );
    assert!(made >= 50 && quads >= 20_000, "{made} {quads}");
    assert!(fines >= 40, "{fines} of {makes}");
    // Shininess 1, 3 and 20 of the five (r = 1/500 a pixel).
    assert!(!point::VIEW_QUAD || qv >= 25, "{qv} of {makes}");
    assert!(!point::NORMAL_QUAD || qn >= 5, "{qn} of {makes}");
    assert!(worst <= 1.0, "{worst}");
}

/// Random triangles of the point loop from their quadratics with the
/// light close to the surface (0.25 to 0.6 units above it, steps of
/// `l̃` above `1/64` of its length) and the eye 4 to 6 units away: the
/// viewer alone fine (module `point`: the first-order step a pixel for
/// `1/|ṽ|`, the series step for `1/|l̃|`); within 1 level of the `f64`
/// twin at every pixel.
#[test]
fn tri_quad_close_light_against_f64() {
    let (worst, made, quads, makes, fines, fv) =
        tri_quad_sweep(0x0bad_cafe_1234_5679, |_, n, f| {
            let size = f(10.0, 60.0);
            let (cx, cy) = (f(60.0, 160.0), f(60.0, 160.0));
            let s = [0, 1, 2].map(|_| [cx + f(-0.5, 0.5) * size, cy + f(-0.5, 0.5) * size]);
            let depth = f(-6.0, -4.0);
            let p = surface(s, depth, cx);
            // Above the triangle's middle, towards the eye.
            let lp = [
                (cx - 110.0) / 100.0 + f(-0.2, 0.2),
                (cy - 110.0) / 100.0 + f(-0.2, 0.2),
                depth + f(0.25, 0.6),
            ];
            let c = point_case(n, lp);
            let base = [f(-0.2, 0.2), f(-0.2, 0.2), 1.0];
            let nv =
                [0, 1, 2].map(|_| unit([base[0] + f(-0.2, 0.2), base[1] + f(-0.2, 0.2), base[2]]));
            (c, s, nv, p)
        });
    std::println!(
        "tri quads, close light, vs f64: {worst:.3} levels, {made} triangles, {quads} pixels from the quadratics; {fines} of {makes} set-ups fine, {fv} the viewer alone"
    );
    assert!(made >= 30 && quads >= 5_000, "{made} {quads}");
    assert!(fv >= 20, "{fv} of {makes}");
    assert!(worst <= 1.0, "{worst}");
}

/// A named extreme triangle: light, screen vertices, normals, positions,
/// and whether it has quadratics (`None`: either).
type ExtremeTri = (
    &'static str,
    [f64; 3],
    [[f64; 2]; 3],
    [[f64; 3]; 3],
    [[f64; 3]; 3],
    Option<bool>,
);

/// Extreme triangles of the point loop: a triangle 4 000 pixels wide, a
/// sliver, one of a pixel, vertex normals 157° apart, the light on the
/// surface, the eye close up, positions near the coordinate range's
/// edge. Each either has no quadratics (the per-span path) or stays
/// within 1 level of the twin at every pixel; none panics. The wide one,
/// 4 000 pixels across (forward differences over whole rows of the
/// 32-bit loop re-seeded a chunk at a time), keeps its quadratics.
#[test]
fn tri_quad_extreme_triangles() {
    let up = unit([0.0, 0.0, 1.0]);
    let tilt = unit([0.3, 0.2, 1.0]);
    let c = |n: f64, lp: [f64; 3]| point_case(n, lp);
    // (name, light, screen vertices, normals, positions, quadratics expected)
    let cases: [ExtremeTri; 9] = [
        (
            "far light",
            [16000.0, 0.0, 16000.0],
            [[10.0, 10.0], [60.0, 10.0], [10.0, 60.0]],
            [up, tilt, up],
            [[-1.0, 0.0, -5.0], [1.0, 0.0, -5.0], [0.0, 1.0, -5.0]],
            None,
        ),
        (
            "far light 2",
            [8000.0, 0.0, 4000.0],
            [[10.0, 10.0], [60.0, 10.0], [10.0, 60.0]],
            [up, tilt, up],
            [[-1.0, 0.0, -5.0], [1.0, 0.0, -5.0], [0.0, 1.0, -5.0]],
            None,
        ),
        (
            "wide",
            [0.0, 0.0, -2.0],
            [[10.0, 10.0], [4010.0, 30.0], [2000.0, 60.0]],
            [up, tilt, up],
            [[-20.0, 1.0, -30.0], [20.0, 1.0, -30.0], [0.0, 0.7, -30.0]],
            Some(true),
        ),
        (
            "sliver",
            [0.5, 0.5, -3.0],
            [[10.0, 10.0], [300.0, 11.0], [150.0, 10.6]],
            [up, tilt, up],
            [[-1.0, 0.0, -5.0], [1.0, 0.0, -5.0], [0.0, 0.01, -5.0]],
            None,
        ),
        (
            "pixel",
            [0.5, 0.5, -3.0],
            [[10.2, 10.2], [11.1, 10.4], [10.5, 11.3]],
            [up, tilt, up],
            [[-0.01, 0.0, -5.0], [0.01, 0.0, -5.0], [0.0, 0.01, -5.0]],
            None,
        ),
        (
            "normals 157° apart",
            [0.5, 0.5, -3.0],
            [[10.0, 10.0], [80.0, 10.0], [10.0, 80.0]],
            [unit([1.0, 0.0, 0.2]), unit([-1.0, 0.0, 0.2]), up],
            [[-0.5, 0.0, -5.0], [0.5, 0.0, -5.0], [-0.5, 0.7, -5.0]],
            Some(false),
        ),
        (
            "light on the surface",
            [0.0, 0.2, -5.0],
            [[10.0, 10.0], [80.0, 10.0], [10.0, 80.0]],
            [up, tilt, up],
            [[-0.5, 0.0, -5.0], [0.5, 0.0, -5.0], [-0.5, 0.7, -5.0]],
            Some(false),
        ),
        (
            "eye close up",
            [0.5, 0.5, 1.0],
            [[10.0, 10.0], [200.0, 10.0], [10.0, 200.0]],
            [up, tilt, up],
            [[-1.0, -1.0, -0.05], [1.0, -1.0, -0.05], [-1.0, 1.0, -0.05]],
            Some(false),
        ),
        (
            "far away",
            [0.5, 0.5, -3.0],
            [[10.0, 10.0], [60.0, 10.0], [10.0, 60.0]],
            [up, tilt, up],
            [
                [-1.0, 0.0, -16400.0],
                [1.0, 0.0, -16400.0],
                [0.0, 1.0, -16400.0],
            ],
            Some(false),
        ),
    ];
    let (makes0, fines0, fv0) = (super::tri_makes(), super::tri_fines(), super::tri_fines_v());
    for (name, lp, s, n, p, expect) in cases {
        for shin in [1.0, 100.0, 255.0] {
            let r = tri_error(&c(shin, lp), s, n, p);
            if let Some(e) = expect {
                assert_eq!(r.is_some(), e, "{name}: quadratics {:?}", r.map(|r| r.1));
            }
            if let Some((worst, quads)) = r {
                std::println!(
                    "{name} n {shin}: {worst:.3} levels, {quads} pixels from the quadratics"
                );
                assert!(worst <= 1.0, "{name} n {shin}: {worst}");
            }
        }
    }
    // Fine triangles and others (a light close to a wide triangle).
    let (makes, fines) = (super::tri_makes() - makes0, super::tri_fines() - fines0);
    let fv = super::tri_fines_v() - fv0;
    std::println!("extreme triangles: {fines} of {makes} set-ups fine, {fv} the viewer alone");
    assert!(fines >= 3 && makes - fines >= 3, "{fines} of {makes}");
}

/// The renderer's row fill of one directional light (the fused loop of
/// module `one`: depth test, terms, channels and store a pixel) writes
/// exactly the pixels that pass the depth test and, there, the colours
/// of [`PhongKernel::fill`] (the kernel's own loop through its test and
/// write closures): spans of a single plan and of chunks (beyond
/// `one::WHOLE_MAX`), short ones, depths in range (no clamp) and not,
/// a depth buffer failing every fifth or seventh pixel, and none.
#[test]
fn row_fill_one_light_writes_the_passing_pixels() {
    use crate::target::{Depth16, Rgb565Be};
    let case = Case {
        mat: Material {
            color: v3(0.9, 0.7, 0.5),
            ka: q(0.1),
            kd: q(0.7),
            ks: q(0.5),
            shininess: q(40.0),
        },
        lights: std::vec![Light::directional(v3(0.3, 0.4, 0.866), q(1.0))],
        ambient: q(0.2),
        specular: Specular::Phong,
        viewer: Viewer::Infinite,
    };
    let shade = Shade::new(
        &case.mat,
        case.ambient,
        &case.lights,
        case.specular,
        case.viewer,
    )
    .unwrap();
    let k = PhongKernel::new(&shade).unwrap();
    let n = q30([-0.3, 0.1, 0.95]);
    let dn = q30([0.003, 0.0, -0.001]);
    let mut checked = 0usize;
    let mut failed_total = 0usize;
    for len in [3u32, 5, 20, 32, 33, 100, 256, 257, 300] {
        let dn = dn.map(|c| c * 300 / len as i32);
        for (z, dz) in [(1i32 << 28, 1i32 << 16), ((1 << 30) - (1 << 20), 1 << 14)] {
            for fail_every in [0usize, 5, 7] {
                // The expected colours: `fill` with the same depth test.
                let mut want = std::vec![None; len as usize];
                let mut zb: Vec<u16> = (0..len as usize)
                    .map(|i| {
                        if fail_every != 0 && i % fail_every == 2 {
                            0
                        } else {
                            Depth16::CLEAR
                        }
                    })
                    .collect();
                let zb0 = zb.clone();
                let mut d = DepthTest::<i32, Depth16> {
                    drow: &mut zb,
                    z,
                    dz,
                    in_range: false,
                };
                let passed_want = k.fill(
                    n,
                    dn,
                    [0; 3],
                    [0; 3],
                    false,
                    len,
                    |i| d.test(i),
                    |i, c| want[i as usize] = Some(Rgb565Be::encode(c)),
                );
                // The row fill over a row and a depth row.
                let mut row = std::vec![0x1234u16; len as usize];
                let mut zr = zb0.clone();
                let passed = row_fill::<i32, Rgb565Be, Depth16, Q16>(
                    &k,
                    &mut row,
                    Some(&mut zr),
                    z,
                    dz,
                    (n, dn, [0; 3], [0; 3]),
                    false,
                    None,
                );
                assert_eq!(passed, passed_want, "len {len} z {z} every {fail_every}");
                assert_eq!(zr, zb, "depths: len {len} z {z} every {fail_every}");
                for (i, (&got, w)) in row.iter().zip(want.iter()).enumerate() {
                    assert_eq!(got, w.unwrap_or(0x1234), "pixel {i} of {len}, z {z}");
                    checked += 1;
                }
                failed_total += (len - passed) as usize;
                // Without a depth buffer: every pixel, the same colours
                // where the depth test passed.
                let mut row = std::vec![0x1234u16; len as usize];
                let all = row_fill::<i32, Rgb565Be, Depth16, Q16>(
                    &k,
                    &mut row,
                    None,
                    z,
                    dz,
                    (n, dn, [0; 3], [0; 3]),
                    false,
                    None,
                );
                assert_eq!(all, len);
                for (&got, w) in row.iter().zip(want.iter()) {
                    if let Some(w) = w {
                        assert_eq!(got, *w);
                    }
                }
            }
        }
    }
    assert_eq!(checked, 2 * 3 * 1006);
    assert!(failed_total > 400, "{failed_total}");
}

/// Every specular table is non-increasing (shininess 1 to 10 000 in
/// steps of 997/65536), so that the one-light loop's packed table
/// (`one::pack_table`) holds each segment's difference in 16 bits, and
/// the packed entry gives the pair form's value at every fraction.
#[test]
fn spec_table_is_non_increasing() {
    let mut tables = 0;
    let mut m = 1u32 << 16;
    while m <= 10_000 << 16 {
        let t = spec_table(m);
        let p = one::pack_table(&t);
        for j in 0..SPEC_SEGMENTS + 1 {
            assert!(t[j] >= t[j + 1], "m {m} j {j}");
            let (a, b) = (u32::from(t[j]), u32::from(t[j + 1]));
            for f in [0u32, 1, 0x7FFF, 0x8000, 0xFFFF, (j as u32 * 7919) & 0xFFFF] {
                let e = p[j];
                let packed = (e & 0xFFFF).wrapping_sub(((e >> 16) * f) >> 16);
                assert_eq!(packed, a - (((a - b) * f) >> 16));
            }
        }
        tables += 1;
        m += 997;
    }
    assert_eq!(tables, 657_267);
}
