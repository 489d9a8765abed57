//! Seed 000's Phong worked example, on the triangle of the core's Gouraud
//! example: vertices on the pixel centres (9, 15), (3, 3), (17, 7) with the
//! unit normals (1, 0, 0), (1, 1, 0)/√2 and (0, 0, 1).
//!
//! Row 11 is covered for x = 7..=12: (7, 11) lies on the edge (3,3)-(9,15)
//! (a left edge, covered) and (13, 11) on the edge (9,15)-(17,7) (a right
//! edge: not covered under the top-left rule), so the normal there is read
//! by extending the row's span by one step, exactly as the rasterizer would
//! step it.
//!
//! Each profile's normal is read through the Phong shader its renderers
//! run ([`shipped_levels`]): the span kernel (`render::PhongKernel`) where
//! the profile has one (`fast`), else the per-pixel `render::PhongShader`.

mod common;

use common::per_profile;
use fixshade::geom::Vec3;
use fixshade::illum::{Light, Material, Shade, Specular, Viewer};
use fixshade::num::{Kernels, Profile, Real};
use fixshade::raster::{draw_triangle, Lerp, Shader, Span, Spans, SubpixelBits, Vertex};
use fixshade::render::{PhongKernel, PhongKernelShader, PhongShader};
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

/// The rasterizer's interpolated normal (in [`Profile::unit`] form) at
/// (7, 11), (10, 11) and (13, 11) for profile `P`: the vertex normals
/// converted with `Profile::unit` and interpolated by `draw_triangle`.
fn row11_attrs<P: Profile>() -> [[P::Lerp; 3]; 3] {
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
    [probe.px[0].1, probe.px[3].1, a_end]
}

/// The interpolated normals of [`row11_attrs`] converted back with
/// `Profile::unit_back` and normalised with `Vec3::normalize`: what the
/// per-pixel shader (`render::PhongShader`) does for `precise`, `f32` and
/// `f64`, which have no span kernel. (`fast` normalises otherwise, see
/// [`shipped_levels`].)
fn row11_normals<P: Profile>() -> [[f64; 3]; 3] {
    row11_attrs::<P>().map(|a| {
        Vec3::new(P::unit_back(a[0]), P::unit_back(a[1]), P::unit_back(a[2]))
            .normalize()
            .to_f64()
    })
}

/// The levels the profile's shipped Phong shader gives at (7, 11),
/// (10, 11) and (13, 11), lit so that they read the normal: a white,
/// purely diffuse material (`kd` = 1, no ambient or specular term) under
/// one white directional light along +x, +y or +z (viewer at infinity),
/// so that each channel is `255 · max(N·L, 0)` = 255 times that
/// component of the shader's normalised normal, rounded. The shader is
/// the one the renderers choose: the span kernel
/// ([`PhongKernelShader`], the colour its span loop computes at that
/// pixel) where [`PhongKernel::new`] makes one (the affine `Q16` profile
/// `fast`), else [`PhongShader`] (`fast-pc` normalises with
/// `approx16::unit` there, the others with `Vec3::normalize`).
fn shipped_levels<P: Profile>() -> [[u8; 3]; 3] {
    let attrs = row11_attrs::<P>();
    let one = P::Real::ONE;
    let zero = P::Real::ZERO;
    let white = Vec3::new(one, one, one);
    let material = Material {
        color: white,
        ka: zero,
        kd: one,
        ks: zero,
        shininess: one,
    };
    let axes = [
        Vec3::new(one, zero, zero),
        Vec3::new(zero, one, zero),
        Vec3::new(zero, zero, one),
    ];
    let mut levels = [[0u8; 3]; 3];
    for (k, axis) in axes.into_iter().enumerate() {
        let light = Light::directional(axis, one);
        let shade =
            Shade::new(&material, zero, &[light], Specular::Phong, Viewer::Infinite).unwrap();
        // As the renderers: the kernel for the affine profiles that have
        // one, else the per-pixel shader.
        let kernel = if P::PERSPECTIVE {
            None
        } else {
            <P::Real as Real>::Kernels::pick(
                |q| Some(PhongKernel::new_cached(q, &shade, &mut None)),
                || None,
            )
        };
        let colours = match kernel {
            Some(Ok(kernel)) => {
                assert_eq!(P::NAME, "fast", "a span kernel for {}", P::NAME);
                let sh = PhongKernelShader::new(&kernel);
                attrs.map(|a| Shader::<P::Lerp, 3>::shade(&sh, &a))
            }
            other => {
                assert!(other.is_none(), "{}: no kernel made", P::NAME);
                assert_ne!(P::NAME, "fast");
                // (For `fast-pc`, perspective, the renderers wrap this
                // shader to divide its attributes by the interpolated
                // `1/w`; with no `w` here the normal reaches it as is.)
                let sh = PhongShader::<P>::new(&shade, false);
                attrs.map(|a| Shader::<P::Lerp, 3>::shade(&sh, &a))
            }
        };
        for (i, c) in colours.iter().enumerate() {
            // A white light on a white material: one grey level.
            assert!(c.r == c.g && c.g == c.b, "{}: {c:?}", P::NAME);
            levels[i][k] = c.r;
        }
    }
    levels
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

/// Per-profile tolerance on each component of the normal normalised by
/// `Vec3::normalize` ([`row11_normals`], the per-pixel shader's
/// normalisation for the profiles without a span kernel), from the
/// documented error budget:
///
/// - vertex normals rounded to 2^-30 by `Profile::unit` (1/2 unit);
/// - interpolation (`raster` module docs): `(n + 2)(1/2 + |g|·2^-30)` units
///   of 2^-30 at `n` pixels from the anchor pixel (3, 3); `n <= 18` on row
///   11 and `|g|·2^-30 < 0.1`, so at most 12 units, 1.1e-8 per component;
/// - `unit_back` is exact for Q32 (32 fraction bits);
/// - `normalize` divides those errors by the length of the interpolated
///   normal (at least 0.707 on row 11, so times 1.41), and adds its own:
///   `rsqrt` (Q32: 2^-30 relative + 1/2 ulp; f32: 2^-22 relative) and the
///   products' rounding.
///
/// Q32: 1.41 · 1.2e-8 + 2^-30 + 2^-32 = 1.8e-8, allowed 2.5e-8 (the
/// interpolation dominates: measured 1.2e-8 at (13, 11), 18 pixels from the
/// anchor). f32: the same interpolation with f32 rounding (about 20 steps of
/// 6e-8, times 1.41) plus 2^-22: 2e-6, allowed 3e-6. f64: 1e-12.
fn tolerance(name: &str) -> f64 {
    match name {
        "precise" => 2.5e-8,
        "f32" => 3e-6,
        "f64" => 1e-12,
        _ => unreachable!(),
    }
}

/// Per-profile bound on a level of [`shipped_levels`] against `255 ·` the
/// exact normalised normal: 1/2 for the rounding to a level, plus 255 times
/// the shader's error on `N·L`:
///
/// - `fast`, the span kernel (module `render::phong_span`, "Accuracy"):
///   `1/|n|` from its 65-entry table, within 2^-11.4 relative at `|n|² =
///   1/4` and 2^-15.4 at 1 (linear interpolation of `f^-1/2`, whose second
///   derivative falls as `f^-5/2`: 2^-13.9 at `|n|² = 1/2`, the least on
///   row 11, whose normals are at least 0.707 long), the coefficients'
///   rounding 1/128 level, the Q30 light direction and Q16 interpolated
///   normal below 2^-15 together: 0.5 + 255 · (2^-13.9 + 2^-15) + 1/128
///   = 0.532, allowed 0.54;
/// - `fast-pc`, the per-pixel shader: `approx16::unit` within 2^-15 a
///   component, the normal rounded to Q16 before it (2^-17, times 1.41 by
///   the normalisation) and `N·L` after it (2^-17): 0.5 + 255 · (2^-15 +
///   2.41 · 2^-17) = 0.5125, allowed 0.513;
/// - `precise`, `f32`, `f64`: the per-pixel shader normalises with
///   `Vec3::normalize` ([`tolerance`]) and lights in the profile's scalar
///   (a few units of its resolution): 0.5 + 255 · 2.5e-8 (`precise`), 0.5 +
///   255 · 4e-6 (`f32`), 0.5 + 1e-9 (`f64`).
fn level_bound(name: &str) -> f64 {
    match name {
        "fast" => 0.54,
        "fast-pc" => 0.513,
        "precise" => 0.5 + 255.0 * 2.5e-8,
        "f32" => 0.5 + 255.0 * 4e-6,
        "f64" => 0.5 + 1e-9,
        _ => unreachable!(),
    }
}

fn check<P: Profile>() {
    let exact = [7.0, 10.0, 13.0].map(|x| normalize(plane_normal(x, 11.0)));
    // The shipped shader, every profile.
    let bound = level_bound(P::NAME);
    let levels = shipped_levels::<P>();
    for ((got, want), x) in levels.iter().zip(exact).zip([7, 10, 13]) {
        let e = (0..3)
            .map(|k| (f64::from(got[k]) - 255.0 * want[k]).abs())
            .fold(0.0, f64::max);
        println!(
            "{:>7} ({x}, 11): levels {got:?}, 255 n = ({:.3}, {:.3}, {:.3}), error {e:.4} (bound {bound:.4})",
            P::NAME,
            255.0 * want[0],
            255.0 * want[1],
            255.0 * want[2],
        );
        assert!(e <= bound, "{} at ({x}, 11): {got:?} vs {want:?}", P::NAME);
    }
    // Not the seed's span-end value at (10, 11): its z, 0.3854, is 13.7
    // levels above the crate's.
    let z10 = f64::from(levels[1][2]);
    assert!(
        (z10 - 255.0 * SEED_AT_10[2]).abs() > 13.0,
        "{}: {:?}",
        P::NAME,
        levels[1]
    );
    if P::NAME.starts_with("fast") {
        // The span kernel's normal, to 1.2e-4 a component, and `fast-pc`'s
        // `approx16::unit`, to 5e-5, on this very triangle: the unit test
        // `render::phong_span::tests::seed_row_11_fast_shaders`.
        return;
    }
    // The per-pixel shader's normalisation to its own tolerance.
    let tol = tolerance(P::NAME);
    let [n7, n10, n13] = row11_normals::<P>();
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

/// The same for `fast-pc`, whose per-pixel shader normalises with
/// `approx16::unit` (the perspective profiles take no span kernel).
#[test]
fn phong_normal_at_row_11_fast_pc() {
    check::<fixshade::num::FastPc>();
}
