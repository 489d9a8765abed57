//! Seed 000's Phong worked example, on the triangle of the core's Gouraud
//! example: vertices on the pixel centres (9, 15), (3, 3), (17, 7) with the
//! unit normals (1, 0, 0), (1, 1, 0)/√2 and (0, 0, 1).
//!
//! Row 11 is covered for x = 7..=12: (7, 11) lies on the edge (3,3)-(9,15)
//! (a left edge, covered) and (13, 11) on the edge (9,15)-(17,7) (a right
//! edge: not covered under the top-left rule), so the normal there is read
//! by extending the row's span by one step, exactly as the rasterizer would
//! step it.

mod common;

use common::per_profile;
use fixshade::geom::Vec3;
use fixshade::num::{Profile, Real};
use fixshade::raster::{draw_triangle, Lerp, Span, Spans, SubpixelBits, Vertex};
use fixshade::target::Window;

/// Records the interpolated normal (three attributes) of every pixel of
/// row 11, and the value one step past the end of that row's span.
struct Row11<L> {
    px: Vec<(u32, [L; 3])>,
    past_end: Option<(u32, [L; 3])>,
}

impl<L: Lerp> Spans<L, 3> for Row11<L> {
    fn span(&mut self, s: &Span<L, 3>) {
        if s.y != 11 {
            return;
        }
        let mut a = s.a;
        for x in s.x0..s.x1 {
            self.px.push((x, a));
            a = [0, 1, 2].map(|k| a[k].add(s.da[k]));
        }
        self.past_end = Some((s.x1, a));
    }
}

/// The crate's normalised interpolated normal at (7, 11), (10, 11) and
/// (13, 11) for profile `P`: the vertex normals converted with
/// `Profile::unit`, interpolated by `draw_triangle`, converted back with
/// `Profile::unit_back` and normalised with `Vec3::normalize`. That is
/// what the per-pixel Phong shader (`render::PhongShader`) does for
/// `precise`, `f32` and `f64`. `fast` ships other normalisations (the span
/// kernel's table `1/|n|` for the affine profile, `approx16::unit` for
/// `fast-pc`), which are internal: the unit test
/// `render::phong_span::tests::seed_row_11_fast_shaders` runs this very
/// triangle through both (measured 5.9e-5 and 8.7e-6 from the exact
/// normal); here `fast` checks the rasterizer's interpolated normal with
/// the same `normalize` as the others.
fn row11_normals<P: Profile>() -> [[f64; 3]; 3] {
    let r = |v: f64| P::unit(P::Real::from_f64(v));
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let c = |i: i32| i * 16 + 8;
    let vert = |x, y, n: [f64; 3]| Vertex {
        x: c(x),
        y: c(y),
        z: P::depth(P::Real::from_f64(0.5)),
        attrs: n.map(r),
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
    let mut probe = Row11 {
        px: vec![],
        past_end: None,
    };
    draw_triangle(&tri, SubpixelBits::DEFAULT, win, &mut probe).unwrap();
    let xs: Vec<u32> = probe.px.iter().map(|p| p.0).collect();
    assert_eq!(
        xs,
        vec![7, 8, 9, 10, 11, 12],
        "{}: row 11 coverage",
        P::NAME
    );
    let (x_end, a_end) = probe.past_end.unwrap();
    assert_eq!(x_end, 13);
    let unit = |a: [P::Lerp; 3]| {
        Vec3::new(P::unit_back(a[0]), P::unit_back(a[1]), P::unit_back(a[2]))
            .normalize()
            .to_f64()
    };
    [unit(probe.px[0].1), unit(probe.px[3].1), unit(a_end)]
}

/// The exact plane interpolation (barycentric, f64) of the vertex normals
/// at pixel centre `(x, y)`.
fn plane_normal(x: f64, y: f64) -> [f64; 3] {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let p = [(9.0, 15.0), (3.0, 3.0), (17.0, 7.0)];
    let n = [[1.0, 0.0, 0.0], [h, h, 0.0], [0.0, 0.0, 1.0]];
    let area = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)
    };
    let q = (x, y);
    let t = area(p[0], p[1], p[2]);
    let w = [
        area(q, p[1], p[2]) / t,
        area(p[0], q, p[2]) / t,
        area(p[0], p[1], q) / t,
    ];
    [0, 1, 2].map(|k| w[0] * n[0][k] + w[1] * n[1][k] + w[2] * n[2][k])
}

fn normalize(v: [f64; 3]) -> [f64; 3] {
    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    v.map(|c| c / l)
}

fn max_err(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
}

/// The seed's figures, to its four decimals.
const AT_7: [f64; 3] = [0.9675, 0.2527, 0.0];
#[allow(clippy::approx_constant)] // the seed's printed figure, not 1/√2
const AT_13: [f64; 3] = [0.7071, 0.0, 0.7071];
const SEED_AT_10: [f64; 3] = [0.9127, 0.1378, 0.3854];
const CRATE_AT_10: [f64; 3] = [0.9303, 0.1564, 0.3317];

#[test]
fn reference_figures_follow_from_the_two_methods() {
    // The plane interpolation (this crate's method) reproduces the seed's
    // end values and gives (0.9303, 0.1564, 0.3317) at (10, 11).
    let n7 = normalize(plane_normal(7.0, 11.0));
    let n13 = normalize(plane_normal(13.0, 11.0));
    let n10 = normalize(plane_normal(10.0, 11.0));
    assert!(max_err(n7, AT_7) < 5e-5, "{n7:?}");
    assert!(max_err(n13, AT_13) < 5e-5, "{n13:?}");
    assert!(max_err(n10, CRATE_AT_10) < 5e-5, "{n10:?}");
    // The seed normalises at the span's ends, then interpolates (and
    // normalises the result): (0.9127, 0.1378, 0.3854). Interpolating the
    // *normalised* end normals weighs the ends differently from the plane
    // through the vertex normals, whose lengths vary along the span.
    // (The seed's own rounding leaves its figure 2.3e-4 off the exact
    // value of its method, 0.91247 in x.)
    let seed = normalize([0, 1, 2].map(|k| 0.5 * n7[k] + 0.5 * n13[k]));
    assert!(max_err(seed, SEED_AT_10) < 3e-4, "{seed:?}");
    assert!(max_err(seed, n10) > 0.05);
}

/// Per-profile tolerance on each normalised component, from the documented
/// error budget:
///
/// - vertex normals rounded to 2^-30 by `Profile::unit` (1/2 unit);
/// - interpolation (`raster` module docs): `(n + 2)(1/2 + |g|·2^-30)` units
///   of 2^-30 at `n` pixels from the anchor pixel (3, 3); `n <= 18` on row
///   11 and `|g|·2^-30 < 0.1`, so at most 12 units, 1.1e-8 per component;
/// - `unit_back` rounds to the scalar's resolution: 2^-17 for Q16 (exact for
///   Q32, which has 32 fraction bits);
/// - `normalize` divides those errors by the length of the interpolated
///   normal (at least 0.707 on row 11, so times 1.41), and adds its own:
///   three products rounded (3 · 2^-17 for Q16), `rsqrt` (Q16: 2^-15
///   relative + 1/2 ulp; Q32: 2^-30 relative + 1/2 ulp; f32: 2^-22
///   relative), then three products rounded (2^-17 for Q16).
///
/// Q16: about 2^-15 + 1.41 · 2^-17 + 4 · 2^-17 = 7.2e-5, allowed 1e-4.
/// Q32: 1.41 · 1.2e-8 + 2^-30 + 2^-32 = 1.8e-8, allowed 2.5e-8 (the
/// interpolation dominates: measured 1.2e-8 at (13, 11), 18 pixels from the
/// anchor). f32: the same interpolation with f32 rounding (about 20 steps of
/// 6e-8, times 1.41) plus 2^-22: 2e-6, allowed 3e-6. f64: 1e-12.
fn tolerance(name: &str) -> f64 {
    match name {
        "fast" => 1e-4,
        "precise" => 2.5e-8,
        "f32" => 3e-6,
        "f64" => 1e-12,
        _ => unreachable!(),
    }
}

fn check<P: Profile>() {
    let tol = tolerance(P::NAME);
    let [n7, n10, n13] = row11_normals::<P>();
    let exact = [7.0, 10.0, 13.0].map(|x| normalize(plane_normal(x, 11.0)));
    for (got, want, x) in [(n7, exact[0], 7), (n10, exact[1], 10), (n13, exact[2], 13)] {
        let e = max_err(got, want);
        println!(
            "{:>7} ({x}, 11): ({:.6}, {:.6}, {:.6}), error {e:.2e} (tolerance {tol:.1e})",
            P::NAME,
            got[0],
            got[1],
            got[2]
        );
        assert!(e <= tol, "{} at ({x}, 11): {got:?} vs {want:?}", P::NAME);
    }
    // The seed's figures to their four decimals (plus the tolerance).
    assert!(max_err(n7, AT_7) <= 5e-5 + tol, "{}: {n7:?}", P::NAME);
    assert!(max_err(n13, AT_13) <= 5e-5 + tol, "{}: {n13:?}", P::NAME);
    assert!(
        max_err(n10, CRATE_AT_10) <= 5e-5 + tol,
        "{}: {n10:?}",
        P::NAME
    );
    // And not the seed's span-end value: it differs by far more than the
    // profile's tolerance (0.053 in z).
    let d = max_err(n10, SEED_AT_10);
    assert!(d > 0.05 && d > 100.0 * tol, "{}: {n10:?}", P::NAME);
    // z is the component the two methods disagree on most.
    assert!((n10[2] - SEED_AT_10[2]).abs() > 0.05);
}

per_profile!(
    /// Seed 000's Phong example at (10, 11): the seed normalises the normals at
    /// the span's two ends, (0.9675, 0.2527, 0) at (7, 11) and (0.7071, 0,
    /// 0.7071) at (13, 11), and interpolates those, giving (0.9127, 0.1378,
    /// 0.3854). This crate interpolates the three *vertex* normals with
    /// per-triangle gradients (one plane per component, as for every
    /// attribute) and normalises per pixel, giving (0.9303, 0.1564, 0.3317).
    /// Both agree at the span ends; in between they differ by up to 0.053 per
    /// component, because the plane interpolation weighs the vertex normals by
    /// barycentric weight while the span-end method weighs the already
    /// normalised end normals by distance along the span. The crate's method
    /// is rotation invariant per triangle and costs no normalisation per span.
    fn phong_normal_at_row_11_per_profile = check
);
