//! Pipeline tests: projection, transforms, clipping, culling, bands,
//! memory figures and bad input.

extern crate std;
use std::{vec, vec::Vec};

use super::*;
use crate::geom::{Affine, Vec3};
use crate::illum::{Light, Material, Specular, Viewer};
use crate::mesh::{shapes, CornerNormals, Mesh};
use crate::num::{Fast, Precise, Profile, Real, F32, F64, Q16};
use crate::scene::{Camera, Object, Scene, Shading};
use crate::target::{BandBuf, Depth16, DepthBuffer, FrameBuf, Rgb565Be, Rgb8, Target};
use std::boxed::Box;

/// Owned workspace memory for tests.
struct Mem<L> {
    xy: Vec<super::ScreenXy>,
    vals: Vec<L>,
    tris: Vec<Tri>,
    colors: Vec<Rgb8>,
    faces: Vec<u8>,
}

impl<L: Copy + Default> Mem<L> {
    fn new(verts: usize, tris: usize) -> Self {
        Self {
            xy: vec![super::ScreenXy::ZERO; verts],
            vals: vec![L::default(); verts * 7],
            tris: vec![Tri::default(); tris],
            // Triangle numbers (and flat colours): every mesh triangle's
            // (more than the kept triangles of `tris`).
            colors: vec![Rgb8::BLACK; 4 * tris],
            faces: vec![0; 4 * tris],
        }
    }
    fn ws(&mut self) -> Workspace<'_, L> {
        Workspace {
            xy: &mut self.xy,
            vals: &mut self.vals,
            tris: &mut self.tris,
            colors: &mut self.colors,
            faces: &mut self.faces,
        }
    }
}

fn material<R: Real>(ks: f32) -> Material<R> {
    Material {
        color: Vec3::from_f32([1.0, 0.3, 0.2]),
        ka: R::from_f32(0.2),
        kd: R::from_f32(0.5),
        ks: R::from_f32(ks),
        shininess: R::from_f32(100.0),
    }
}

fn object<R: Real>(mesh: Mesh<'static>, shading: Shading, angles: [f32; 3]) -> Object<'static, R> {
    Object {
        mesh,
        transform: Affine::from_parts(R::ONE, Vec3::from_f32(angles), Vec3::ZERO),
        material: material(0.5),
        shading,
        cull_backfaces: true,
    }
}

/// A two-sided matte object (no specular term) of `mesh` placed by
/// `transform`.
fn matte<R: Real>(
    mesh: Mesh<'static>,
    transform: Affine<R>,
    shading: Shading,
) -> Object<'static, R> {
    Object {
        mesh,
        transform,
        material: material(0.0),
        shading,
        cull_backfaces: false,
    }
}

fn scene<'s, R: Real>(
    objects: &'s [Object<'static, R>],
    lights: &'s [Light<R>],
    eye: [f32; 3],
) -> Scene<'s, 'static, R> {
    Scene {
        camera: Camera::look_at_f32(eye, [0.0; 3], [0.0, 1.0, 0.0], 40.0, 0.5, None).unwrap(),
        objects,
        lights,
        ambient: R::from_f32(0.2),
        specular: Specular::Phong,
        viewer: Viewer::Local,
        background: Rgb8::new(0, 0, 40),
    }
}

fn lights<R: Real>() -> [Light<R>; 2] {
    [
        Light::point(Vec3::from_f32([2.0, 2.0, 4.0]), R::ONE),
        Light::directional(Vec3::from_f32([-1.0, 0.5, 1.0]), R::from_f32(0.5)),
    ]
}

/// Renders a whole frame at once; returns the RGB565 bytes.
fn full<P: Profile>(s: &Scene<'_, 'static, P::Real>, w: u32, h: u32, depth: bool) -> Vec<u8> {
    let mut mem = Mem::<P::Lerp>::new(12_000, 12_000);
    let frame = prepare::<P>(s, w, h, mem.ws()).unwrap();
    assert_face_rows(&frame);
    let mut px = vec![0u16; (w * h) as usize];
    let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, w, h).unwrap();
    fb.clear(s.background);
    let mut z = vec![0u16; (w * h) as usize];
    let mut db = DepthBuffer::<Depth16>::new(&mut z, w, 0, h).unwrap();
    frame
        .render(s, &mut fb, if depth { Some(&mut db) } else { None })
        .unwrap();
    fb.bytes().collect()
}

fn banded<P: Profile>(s: &Scene<'_, 'static, P::Real>, w: u32, h: u32, rows: u32) -> Vec<u8> {
    let (out, stats, n) = banded_with::<P, 256, 8>(s, w, h, rows, true);
    // A pool large enough: every prepared triangle set up exactly once.
    assert_eq!(stats.triangles as usize, n, "rows {rows}");
    // A pool of two slots of two values: the same bytes, more setups.
    let (tiny, tiny_stats, _) = banded_with::<P, 2, 2>(s, w, h, rows, true);
    assert_eq!(tiny, out, "tiny pool, rows {rows}");
    if rows < h && n > 20 {
        assert!(tiny_stats.triangles as usize > n, "rows {rows}");
    }
    out
}

/// The kept triangles prepare counted by row code are those of the face
/// bytes, code by code.
fn assert_face_rows<P: Profile>(frame: &Frame<'_, P>) {
    let mut want = [0u16; FACE_ROW as usize + 1];
    for &b in &frame.faces[..frame.triangle_numbers()] {
        want[usize::from(b & FACE_ROW)] += 1;
    }
    want[0] = 0;
    assert_eq!(frame.face_rows, want);
    let kept = frame.faces[..frame.triangle_numbers()]
        .iter()
        .filter(|&&b| b & FACE_ROW != 0)
        .count();
    assert_eq!(frame.triangle_count(), kept);
}

/// Renders band by band through [`Frame::render_bands`]: the bytes, the
/// statistics and the number of prepared triangles.
fn banded_with<P: Profile, const CAP: usize, const V: usize>(
    s: &Scene<'_, 'static, P::Real>,
    w: u32,
    h: u32,
    rows: u32,
    depth: bool,
) -> (Vec<u8>, RenderStats, usize) {
    let mut mem = Mem::<P::Lerp>::new(12_000, 12_000);
    let frame = prepare::<P>(s, w, h, mem.ws()).unwrap();
    assert_face_rows(&frame);
    let mut px = vec![0u16; (w * rows) as usize];
    let mut z = vec![0u16; (w * rows) as usize];
    let mut band = BandBuf::<Rgb565Be>::new(&mut px, depth.then_some(&mut z[..]), w, rows).unwrap();
    let mut order = vec![0u16; 2 * frame.triangle_count()];
    let mut pool = Box::new(Pool::<P::Lerp, CAP, V>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let mut out = vec![];
    let stats = frame
        .render_bands(s, &mut state, &mut band, |b| {
            out.extend(b.bytes());
            Ok::<(), RenderError>(())
        })
        .unwrap();
    (out, stats, frame.triangle_count())
}

#[test]
fn projection_matches_the_f64_formula() {
    fn run<P: Profile>(tol_sub: f64) {
        // One triangle; its prepared vertices are the projected corners.
        const POS: [[i16; 3]; 3] = [
            [-12000, 3000, 1000],
            [16000, -9000, -16000],
            [500, 14000, 7000],
        ];
        let mesh = Mesh::new(&POS, &[[0, 1, 2]], None).unwrap();
        let t = Affine::from_parts(
            P::Real::from_f32(1.5),
            Vec3::ZERO,
            Vec3::from_f32([0.25, -0.5, 0.0]),
        );
        let objs = [matte(mesh, t, Shading::Flat)];
        let ls = lights();
        let s = scene(&objs, &ls, [1.0, 2.0, 6.0]);
        let (w, h) = (200u32, 150u32);
        let mut mem = Mem::<P::Lerp>::new(16, 16);
        let frame = prepare::<P>(&s, w, h, mem.ws()).unwrap();
        assert_face_rows(&frame);
        assert_eq!(frame.vertex_count(), 3);
        // The f64 formula, from scratch.
        let (eye, up) = ([1.0f64, 2.0, 6.0], [0.0f64, 1.0, 0.0]);
        let norm = |v: [f64; 3]| {
            let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            v.map(|c| c / l)
        };
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let f = norm(eye.map(|c| -c));
        let sv = norm(cross(f, up));
        let u = cross(sv, f);
        let k = h as f64 / 2.0 / (20.0f64.to_radians()).tan();
        for (i, p) in POS.iter().enumerate() {
            let wp = [
                p[0] as f64 / 16384.0 * 1.5 + 0.25,
                p[1] as f64 / 16384.0 * 1.5 - 0.5,
                p[2] as f64 / 16384.0 * 1.5,
            ];
            let d = [wp[0] - eye[0], wp[1] - eye[1], wp[2] - eye[2]];
            let (x, y, w) = (dot(sv, d), dot(u, d), dot(f, d));
            let sx = (200.0 / 2.0 + k * x / w) * 16.0;
            let sy = (h as f64 / 2.0 - k * y / w) * 16.0;
            let got = frame.xy(i).unwrap();
            assert!(
                (got[0] as f64 - sx).abs() <= tol_sub,
                "{} vertex {i}: x {} vs {sx}",
                P::NAME,
                got[0]
            );
            assert!(
                (got[1] as f64 - sy).abs() <= tol_sub,
                "{} vertex {i}: y {} vs {sy}",
                P::NAME,
                got[1]
            );
        }
    }
    // Float twins round to the nearest subpixel; fixed profiles are within
    // one more subpixel (Q16: trigonometry 2^-16, reciprocal and products
    // within a few ulps of values below 2^9).
    run::<F64>(0.5 + 1e-9);
    run::<F32>(0.5 + 1e-3);
    run::<Precise>(0.5 + 1e-3);
    run::<Fast>(1.5);
}

#[test]
fn a_full_turn_is_the_identity_within_the_trigonometry_error() {
    fn run<R: Real>(bound: f64) {
        let tau = R::from_f64(core::f64::consts::TAU);
        let p = Vec3::from_f32([0.75, -0.5, 1.0]);
        for axis in 0..3 {
            let mut a = [R::ZERO; 3];
            a[axis] = tau;
            let t = Affine::from_parts(R::ONE, Vec3::new(a[0], a[1], a[2]), Vec3::ZERO);
            let q = t.point(p).to_f64();
            let e = p.to_f64();
            for c in 0..3 {
                assert!((q[c] - e[c]).abs() <= bound, "axis {axis}: {q:?} vs {e:?}");
            }
        }
    }
    // |sin|, |cos| errors (2^-16 for Q16, plus the rounding of 2 pi and of
    // the products) times |p| summed over the three rows: 3 * 2^-15 bounds it.
    run::<crate::num::Q16>(3.0 / 32768.0);
    run::<crate::num::Q32>(1e-8);
    run::<f32>(1e-6);
    run::<f64>(1e-14);
}

#[test]
fn normalize_is_unit_across_the_range_of_lengths() {
    use crate::num::{Q16, Q32};
    fn run<R: Real>(lengths: &[f64], tol: f64) {
        for &len in lengths {
            let v = Vec3::new(
                R::from_f64(len * 0.6),
                R::from_f64(-len * 0.48),
                R::from_f64(len * 0.64),
            );
            let n = v.normalize().to_f64();
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            assert!(
                (l - 1.0).abs() <= tol,
                "{}: length {len} normalises to {l}",
                core::any::type_name::<R>()
            );
        }
    }
    // Short of, at and beyond the point where the squared length saturates
    // (181 units for Q16, 46341 for Q32): unit either way.
    run::<Q16>(
        &[
            0.05, 1.0, 100.0, 180.0, 181.0, 182.0, 200.0, 1000.0, 32000.0,
        ],
        2e-3,
    );
    run::<Q32>(&[1e-3, 1.0, 46340.0, 46342.0, 1e6, 2e9], 1e-5);
    run::<f32>(&[1e-3, 1.0, 1e6, 1e19, 1e30], 1e-6);
}

#[test]
fn degrees_convert_to_radians_within_the_stated_error() {
    use crate::geom::radians;
    use crate::num::{Q16, Q32};
    for deg in [-360i32, -90, -1, 0, 1, 30, 45, 90, 180, 270, 360] {
        let exact = (deg as f64).to_radians();
        // One rounding (half a Q16 step) plus the constant's error.
        assert!(
            (radians(Q16::from_i32(deg)).to_f64() - exact).abs()
                <= 0.5 / 65536.0 + 8.5e-8 * exact.abs(),
            "{deg}"
        );
        assert!(
            (radians(Q32::from_i32(deg)).to_f64() - exact).abs() <= 8.5e-8 * exact.abs() + 1e-9,
            "{deg}"
        );
        assert!(
            (radians(deg as f64) - exact).abs() <= 8.5e-8 * exact.abs() + 1e-15,
            "{deg}"
        );
    }
}

#[test]
fn triangles_behind_the_eye_draw_nothing_and_the_camera_may_sit_inside_a_mesh() {
    // Eye at z = 6 looking at the origin; a triangle at z = 10 is behind it.
    const POS: [[i16; 3]; 3] = [
        [-8000, -8000, 16000],
        [8000, -8000, 16000],
        [0, 8000, 16000],
    ];
    let mesh = Mesh::new(&POS, &[[0, 1, 2]], None).unwrap();
    let t = Affine::from_parts(
        Precise::default_one(),
        Vec3::ZERO,
        Vec3::from_f32([0.0, 0.0, 9.0]),
    );
    let objs = [matte(mesh, t, Shading::Flat)];
    let ls = lights();
    let s = scene(&objs, &ls, [0.0, 0.0, 6.0]);
    let bytes = full::<Precise>(&s, 64, 48, true);
    let bg = Rgb565Be::encode_bytes(s.background);
    assert!(bytes.chunks(2).all(|c| c == bg));

    // Inside the sphere, culling off: every pixel is covered.
    let mut sphere = object::<crate::num::Q32>(shapes::SPHERE, Shading::Gouraud, [0.0; 3]);
    sphere.cull_backfaces = false;
    let objs = [sphere];
    let s = scene(&objs, &ls, [0.1, 0.2, 0.3]);
    let bytes = full::<Precise>(&s, 64, 48, true);
    assert!(bytes.chunks(2).all(|c| c != bg));
}

trait One {
    fn default_one() -> crate::num::Q32;
}
impl One for Precise {
    fn default_one() -> crate::num::Q32 {
        crate::num::Q32::ONE
    }
}

trait Encode {
    fn encode_bytes(c: Rgb8) -> [u8; 2];
}
impl Encode for Rgb565Be {
    fn encode_bytes(c: Rgb8) -> [u8; 2] {
        crate::target::RawPixel::bytes(<Rgb565Be as crate::target::PixelFormat>::encode(c))
    }
}

fn every_shape<R: Real>(shading: Shading) -> Vec<Object<'static, R>> {
    shapes::ALL
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let mut o = object::<R>(*m, shading, [0.3 * i as f32, 0.5 + 0.2 * i as f32, 0.1]);
            o.transform.t = Vec3::from_f32([
                (i as f32 - 2.5) * 0.9,
                (i % 2) as f32 * 0.8 - 0.4,
                -(i as f32) * 0.3,
            ]);
            o.cull_backfaces = i != 4; // the grid is open: two-sided
            o
        })
        .collect()
}

#[test]
fn bands_equal_the_full_frame_for_every_shape_mode_and_profile() {
    fn run<P: Profile>() {
        for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
            let objs = every_shape::<P::Real>(shading);
            let ls = lights();
            let s = scene(&objs, &ls, [0.5, 1.0, 7.0]);
            let (w, h) = (96, 64);
            let whole = full::<P>(&s, w, h, true);
            let bg = Rgb565Be::encode_bytes(s.background);
            assert!(
                whole.chunks(2).filter(|c| *c != bg).count() > 1500,
                "{} {shading:?}",
                P::NAME
            );
            for rows in [1, 7, 16, h] {
                assert_eq!(
                    banded::<P>(&s, w, h, rows),
                    whole,
                    "{} {shading:?} rows {rows}",
                    P::NAME
                );
            }
        }
    }
    run::<Fast>();
    run::<Precise>();
    run::<F32>();
    run::<F64>();
    run::<crate::num::FastPc>();
    run::<crate::num::PrecisePc>();
    run::<crate::num::F64Pc>();
}

/// Every shape grey with no specular term, and one white directional
/// light: the objects and light of the fast path's streams.
fn grey_shapes(shading: Shading) -> (Vec<Object<'static, Q16>>, [Light<Q16>; 1]) {
    let mut objs = every_shape::<Q16>(shading);
    for o in &mut objs {
        o.material.color = Vec3::from_f32([0.9, 0.9, 0.9]);
        o.material.ks = Q16::ZERO;
    }
    let ls = [Light::directional(
        Vec3::from_f32([-1.0, 0.5, 1.0]),
        Q16::ONE,
    )];
    (objs, ls)
}

/// Flat and grey Gouraud shapes (grey, no specular term, one white
/// directional light: the fast path's streams) in bands of 1, 7, 16 and
/// all rows, with pools of 1, 2 and 256 slots (the triangles that find the
/// pool full queued: the order taken past the merge interleaved with the
/// queue's and the ring's), equal the full frame; with 256 slots each
/// triangle is set up once.
#[test]
fn fast_streams_with_any_pool_equal_the_full_frame() {
    for shading in [Shading::Flat, Shading::Gouraud] {
        let (objs, ls) = grey_shapes(shading);
        let mut s = scene(&objs, &ls, [0.5, 1.0, 7.0]);
        s.ambient = Q16::ONE;
        let (w, h) = (96, 64);
        let whole = full::<Fast>(&s, w, h, true);
        let bg = Rgb565Be::encode_bytes(s.background);
        assert!(
            whole.chunks(2).filter(|c| *c != bg).count() > 1500,
            "{shading:?}"
        );
        for rows in [1, 7, 16, h] {
            let m = std::format!("{shading:?} rows {rows}");
            assert_eq!(
                banded_with::<Fast, 1, 4>(&s, w, h, rows, true).0,
                whole,
                "{m}"
            );
            assert_eq!(
                banded_with::<Fast, 2, 4>(&s, w, h, rows, true).0,
                whole,
                "{m}"
            );
            let (out, stats, n) = banded_with::<Fast, 256, 4>(&s, w, h, rows, true);
            assert_eq!(out, whole, "{m}");
            assert_eq!(stats.triangles as usize, n, "{m}");
        }
    }
}

/// The banded frame of [`Fast`] with a pool of `Q` slots of quadratics
/// ([`QuadSlot`]) and the set-ups of quadratics it made.
fn banded_quads<const Q: usize>(
    s: &Scene<'_, 'static, crate::num::Q16>,
    w: u32,
    h: u32,
    rows: u32,
) -> (Vec<u8>, u32) {
    let mut mem = Mem::<<Fast as Profile>::Lerp>::new(12_000, 12_000);
    let frame = prepare::<Fast>(s, w, h, mem.ws()).unwrap();
    let mut px = vec![0u16; (w * rows) as usize];
    let mut z = vec![0u16; (w * rows) as usize];
    let mut band = BandBuf::<Rgb565Be>::new(&mut px, Some(&mut z[..]), w, rows).unwrap();
    let mut order = vec![0u16; 2 * frame.triangle_count()];
    let mut pool = Box::new(Pool::<<Fast as Profile>::Lerp, 256, 8, Q>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let mut out = vec![];
    let makes = super::phong_span::tri_makes();
    frame
        .render_bands(s, &mut state, &mut band, |b| {
            out.extend(b.bytes());
            Ok::<(), RenderError>(())
        })
        .unwrap();
    (out, super::phong_span::tri_makes() - makes)
}

/// One point light, local viewer: the band renderer keeps the triangles'
/// quadratics from band to band in the pool's slots. Any number of slots
/// gives the full frame's bytes; with slots enough every triangle's are
/// made once a frame, as in one band; with none, again in every band.
#[test]
fn quadratics_kept_across_bands_give_the_full_frame() {
    let objs = every_shape::<crate::num::Q16>(Shading::Phong);
    let ls = [Light::point(
        Vec3::from_f32([2.0, 2.0, 4.0]),
        crate::num::Q16::ONE,
    )];
    let s = scene(&objs, &ls, [0.5, 1.0, 7.0]);
    let (w, h) = (240, 160);
    let whole = full::<Fast>(&s, w, h, true);
    let (one_band, once) = banded_quads::<0>(&s, w, h, h);
    assert_eq!(one_band, whole);
    assert!(once > 40, "{once}");
    for rows in [1, 7, 16, h] {
        let (none, again) = banded_quads::<0>(&s, w, h, rows);
        let (tiny, tiny_makes) = banded_quads::<1>(&s, w, h, rows);
        let (few, few_makes) = banded_quads::<2>(&s, w, h, rows);
        let (many, many_makes) = banded_quads::<64>(&s, w, h, rows);
        for b in [&none, &tiny, &few, &many] {
            assert!(*b == whole, "rows {rows}");
        }
        assert_eq!(many_makes, once, "rows {rows}");
        assert!(tiny_makes <= again && few_makes <= again, "rows {rows}");
        if rows < h {
            assert!(
                again > once && tiny_makes < again,
                "rows {rows}: {again} {once}"
            );
        }
    }
}

#[test]
fn a_convex_object_with_culling_needs_no_depth_buffer() {
    for m in [shapes::CUBE, shapes::DODECAHEDRON, shapes::SPHERE] {
        for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
            let objs = [object::<crate::num::Q16>(m, shading, [0.4, 0.7, 0.2])];
            let ls = lights();
            let s = scene(&objs, &ls, [0.0, 0.5, 4.0]);
            let whole = full::<Fast>(&s, 80, 60, true);
            assert_eq!(whole, full::<Fast>(&s, 80, 60, false), "{shading:?}");
            for rows in [1, 7, 60] {
                let (b, ..) = banded_with::<Fast, 64, 8>(&s, 80, 60, rows, false);
                assert_eq!(b, whole, "{shading:?} rows {rows}");
            }
        }
    }
}

#[test]
fn memory_figures_are_as_documented() {
    assert_eq!(core::mem::size_of::<Tri>(), 6);
    assert_eq!(core::mem::size_of::<Rgb8>(), 3);
    assert_eq!(core::mem::size_of::<PreparedObject>(), 20);
    let strides = [
        (Layout::Flat, 1),
        (Layout::GouraudMono, 2),
        (Layout::GouraudRgb, 4),
        (Layout::PhongNormal, 4),
        (Layout::PhongPosition, 7),
    ];
    for (l, s) in strides {
        assert_eq!(l.stride(), s);
    }
    // The bunny in Gouraud under a white light: grey, so one level per
    // vertex; 1839 vertices (no clipping), 4 + 4 bytes each with `fast`
    // (depth and level packed in one value; 4 + 2 * 4 in the profiles
    // that do not pack).
    let white = Material {
        color: Vec3::from_f32([1.0; 3]),
        ..material::<crate::num::Q16>(0.0)
    };
    let objs = [Object {
        material: white,
        ..object::<crate::num::Q16>(shapes::BUNNY, Shading::Gouraud, [0.0; 3])
    }];
    let ls = [Light::directional(
        Vec3::from_f32([1.0, 1.0, 1.0]),
        crate::num::Q16::from_f32(0.8),
    )];
    let s = scene(&objs, &ls, [0.0, 0.0, 3.922]);
    let mut mem = Mem::<i32>::new(4000, 4000);
    let frame = prepare::<Fast>(&s, 240, 240, mem.ws()).unwrap();
    assert_eq!(frame.objects()[0].layout(), Layout::GouraudMono);
    assert_eq!(frame.vertex_count(), 1839);
    let t = frame.triangle_count();
    assert!((1400..1900).contains(&t), "{t} front faces");
    // A byte per mesh triangle (whether the view keeps it), none copied.
    assert_eq!(frame.triangle_numbers(), 3674);
    assert_eq!(frame.bytes_used(), 1839 * (4 + 4) + 3674);
    // Phong with a point light and a local viewer carries positions.
    let objs = [object::<crate::num::Q16>(
        shapes::CUBE,
        Shading::Phong,
        [0.0; 3],
    )];
    let ls = lights();
    let s = scene(&objs, &ls, [0.0, 0.0, 5.0]);
    let mut mem = Mem::<i32>::new(100, 100);
    let frame = prepare::<Fast>(&s, 64, 64, mem.ws()).unwrap();
    assert_eq!(frame.objects()[0].layout(), Layout::PhongPosition);
    // Directional light and a viewer at infinity: normals only.
    let ls = [Light::directional(
        Vec3::from_f32([0.0, 0.0, 1.0]),
        crate::num::Q16::ONE,
    )];
    let s = Scene {
        viewer: Viewer::Infinite,
        ..scene(&objs, &ls, [0.0, 0.0, 5.0])
    };
    let mut mem = Mem::<i32>::new(100, 100);
    let frame = prepare::<Fast>(&s, 64, 64, mem.ws()).unwrap();
    assert_eq!(frame.objects()[0].layout(), Layout::PhongNormal);
}

#[test]
fn bad_camera_input_is_an_error() {
    use crate::scene::SceneError as E;
    type C = Camera<crate::num::Q16>;
    let ok = |e: [f32; 3], t: [f32; 3], u: [f32; 3], fov: f32, n: f32, f: Option<f32>| {
        C::look_at_f32(e, t, u, fov, n, f).map(|_| ())
    };
    let (eye, at, up) = ([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0]);
    let (nan, inf) = (f32::NAN, f32::INFINITY);
    for (e, t, u, fov, n, f, want) in [
        ([1.0; 3], [1.0; 3], up, 40.0, 0.5, None, E::EyeAtTarget),
        (
            [0.0, 5.0, 0.0],
            at,
            up,
            40.0,
            0.5,
            None,
            E::UpParallelToView,
        ),
        (eye, at, up, 0.0, 0.5, None, E::FieldOfView),
        (eye, at, up, 180.0, 0.5, None, E::FieldOfView),
        (eye, at, up, 40.0, 0.0, None, E::Near),
        (eye, at, up, 40.0, -1.0, None, E::Near),
        (eye, at, up, 40.0, 1.0, Some(1.0), E::Far),
        (
            [nan, 0.0, 5.0],
            at,
            up,
            40.0,
            1.0,
            None,
            E::NotFinite("eye"),
        ),
        (
            eye,
            at,
            [0.0, inf, 0.0],
            40.0,
            1.0,
            None,
            E::NotFinite("up"),
        ),
        (eye, at, up, nan, 1.0, None, E::NotFinite("fov_y_deg")),
        (eye, at, up, 40.0, 1.0, Some(nan), E::NotFinite("far")),
    ] {
        assert_eq!(
            ok(e, t, u, fov, n, f),
            Err(want),
            "{e:?} {u:?} {fov} {n} {f:?}"
        );
    }
    // The seed's VRP convention: eye at (0, 0, 6).
    let q = |v: f32| crate::num::Q16::from_f32(v);
    let c = C::from_vrp(
        Vec3::from_f32([0.0, 0.0, 1.0]),
        Vec3::from_f32([0.0, 0.0, -1.0]),
        Vec3::from_f32([0.0, 1.0, 0.0]),
        q(5.0),
        q(0.7),
        q(0.5),
        None,
    )
    .unwrap();
    assert_eq!(c.view.point(Vec3::from_f32([0.0, 0.0, 6.0])), Vec3::ZERO);
    assert_eq!(
        C::from_vrp(
            Vec3::ZERO,
            Vec3::ZERO,
            Vec3::from_f32([0.0, 1.0, 0.0]),
            q(5.0),
            q(0.7),
            q(0.5),
            None
        )
        .unwrap_err(),
        E::EyeAtTarget
    );
}

#[test]
fn capacity_and_scene_errors_are_values() {
    let objs = [object::<crate::num::Q16>(
        shapes::SPHERE,
        Shading::Gouraud,
        [0.0; 3],
    )];
    let ls = lights();
    let s = scene(&objs, &ls, [0.0, 0.0, 5.0]);
    for (verts, tris, part) in [(10, 1000, Part::Vertices), (1000, 10, Part::Triangles)] {
        let mut mem = Mem::<i32>::new(verts, tris);
        let e = prepare::<Fast>(&s, 64, 64, mem.ws()).unwrap_err();
        assert_eq!(e, RenderError::Capacity { part, object: 0 });
    }
    let mut mem = Mem::<i32>::new(1000, 1000);
    mem.vals.truncate(10);
    assert_eq!(
        prepare::<Fast>(&s, 64, 64, mem.ws()).unwrap_err(),
        RenderError::Capacity {
            part: Part::Values,
            object: 0
        }
    );
    // Smooth shading needs normals.
    const POS: [[i16; 3]; 3] = [[0, 0, 0], [16384, 0, 0], [0, 16384, 0]];
    let bare = Mesh::new(&POS, &[[0, 1, 2]], None).unwrap();
    let objs2 = [objs[0], object(bare, Shading::Phong, [0.0; 3])];
    let s2 = scene(&objs2, &ls, [0.0, 0.0, 5.0]);
    let mut mem = Mem::<i32>::new(1000, 1000);
    assert_eq!(
        prepare::<Fast>(&s2, 64, 64, mem.ws()).unwrap_err(),
        RenderError::MissingNormals { object: 1 }
    );
    // Too many lights, too many objects, too big a screen.
    let many = [ls[0]; 9];
    let s3 = scene(&objs, &many, [0.0, 0.0, 5.0]);
    let mut mem = Mem::<i32>::new(1000, 1000);
    assert_eq!(
        prepare::<Fast>(&s3, 64, 64, mem.ws()).unwrap_err(),
        RenderError::Scene(crate::scene::SceneError::TooManyLights)
    );
    let lots = [objs[0]; 33];
    let s4 = scene(&lots, &ls, [0.0, 0.0, 5.0]);
    let mut mem = Mem::<i32>::new(1000, 1000);
    assert_eq!(
        prepare::<Fast>(&s4, 64, 64, mem.ws()).unwrap_err(),
        RenderError::Scene(crate::scene::SceneError::TooManyObjects)
    );
    let mut mem = Mem::<i32>::new(1000, 1000);
    assert_eq!(
        prepare::<Fast>(&s, 4097, 64, mem.ws()).unwrap_err(),
        RenderError::Scene(crate::scene::SceneError::Screen)
    );
    // A field of view too narrow for Q16 at this screen size (k saturates).
    let narrow = Scene {
        camera: Camera::look_at_f32([0.0, 0.0, 5.0], [0.0; 3], [0.0, 1.0, 0.0], 0.5, 0.5, None)
            .unwrap(),
        ..s
    };
    let mut mem = Mem::<i32>::new(1000, 1000);
    assert_eq!(
        prepare::<Fast>(&narrow, 240, 240, mem.ws()).unwrap_err(),
        RenderError::Scene(crate::scene::SceneError::Screen)
    );
    // A target of another width is refused.
    let mut mem = Mem::<i32>::new(1000, 1000);
    let frame = prepare::<Fast>(&s, 64, 64, mem.ws()).unwrap();
    let mut px = vec![0u16; 32 * 64];
    let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, 32, 64).unwrap();
    assert_eq!(
        frame.render::<_, Depth16>(&s, &mut fb, None).unwrap_err(),
        RenderError::Window
    );
    // Zero-size frames are fine and empty.
    let mut mem = Mem::<i32>::new(1000, 1000);
    let frame = prepare::<Fast>(&s, 0, 0, mem.ws()).unwrap();
    let mut px: Vec<u16> = vec![];
    let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, 0, 0).unwrap();
    assert_eq!(
        frame
            .render::<_, Depth16>(&s, &mut fb, None)
            .unwrap()
            .pixels,
        0
    );
    let _ = CornerNormals {
        normals: &[],
        indices: &[],
    };
}

#[test]
fn double_buffered_bands_equal_the_full_frame() {
    let objs = every_shape::<crate::num::Q16>(Shading::Gouraud);
    let ls = lights();
    let s = scene(&objs, &ls, [0.5, 1.0, 7.0]);
    let (w, h, rows) = (96u32, 64u32, 10u32);
    let whole = full::<Fast>(&s, w, h, true);
    let mut mem = Mem::<i32>::new(12_000, 12_000);
    let frame = prepare::<Fast>(&s, w, h, mem.ws()).unwrap();
    let n = (w * rows) as usize;
    let (mut p0, mut z0, mut p1, mut z1) =
        (vec![0u16; n], vec![0u16; n], vec![0u16; n], vec![0u16; n]);
    let mut bufs = [
        BandBuf::<Rgb565Be>::new(&mut p0, Some(&mut z0), w, rows).unwrap(),
        BandBuf::<Rgb565Be>::new(&mut p1, Some(&mut z1), w, rows).unwrap(),
    ];
    let mut order = vec![0u16; 2 * frame.triangle_count()];
    let mut pool = Box::new(Pool::<i32, 64, 4>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let mut bands = frame.bands(&s, &mut state, rows).unwrap();
    let (mut out, mut i, mut sent) = (vec![], 0, None::<usize>);
    while let Some(win) = bands.next_band(&mut bufs[i]).unwrap() {
        assert_eq!(
            win.y0,
            out.len() as u32 / (2 * w) + sent.map_or(0, |_| rows)
        );
        // "Send" the buffer rendered before this one, while this one holds
        // the next band.
        if let Some(j) = sent {
            out.extend(bufs[j].bytes());
        }
        sent = Some(i);
        i ^= 1;
    }
    if let Some(j) = sent {
        out.extend(bufs[j].bytes());
    }
    assert_eq!(out, whole);
    assert_eq!(bands.stats().triangles as usize, frame.triangle_count());
    // Bad band buffers and scratch are errors.
    let mut small = vec![0u16; 3];
    let mut pool = Pool::<i32, 4, 2>::new();
    let mut st = BandState::new(&mut small, &mut pool);
    assert_eq!(
        frame.bands(&s, &mut st, rows).unwrap_err(),
        RenderError::Capacity {
            part: Part::Order,
            object: 0
        }
    );
    let mut order = vec![0u16; 2 * frame.triangle_count()];
    let mut pool = Pool::<i32, 4, 2>::new();
    let mut st = BandState::new(&mut order, &mut pool);
    assert_eq!(
        frame.bands(&s, &mut st, 0).unwrap_err(),
        RenderError::Window
    );
    let mut b = frame.bands(&s, &mut st, rows + 1).unwrap();
    assert_eq!(b.next_band(&mut bufs[0]).unwrap_err(), RenderError::Window);
}

#[test]
fn band_of_equals_the_division() {
    for rows in 1..=300u32 {
        let (shift, m) = super::active::band_consts(rows);
        for r in 0..4096 {
            assert_eq!(
                super::active::band_of(r, rows, shift, m),
                r / rows,
                "{r} / {rows}"
            );
        }
    }
}

#[test]
fn band_state_memory_is_as_documented() {
    use core::mem::size_of;
    // The walk: three edge walkers of 20 bytes, five i32 rows and three
    // flags = 83, 84 aligned; with the triangle index 88; then 12 bytes
    // per value.
    assert_eq!(size_of::<crate::raster::Walk>(), 84);
    assert_eq!(Pool::<i32, 1, 2>::SLOT_BYTES, 88 + 24);
    assert_eq!(Pool::<i32, 1, 4>::SLOT_BYTES, 88 + 48);
    assert_eq!(Pool::<i32, 1, 8>::SLOT_BYTES, 88 + 96);
    // The pool adds two u16 list entries per slot.
    assert_eq!(size_of::<Pool<i32, 64, 8>>(), 64 * (88 + 96 + 4));
    assert_eq!(size_of::<Pool<i32, 32, 2>>(), 32 * (88 + 24 + 4));
    // The point light's six quadratics (288), key, light, last row, flag
    // and anchor: 328 bytes per triangle kept from band to band.
    assert_eq!(QuadSlot::BYTES, 328);
    assert_eq!(
        size_of::<Pool<i32, 56, 8, 10>>(),
        56 * (88 + 96 + 4) + 10 * 328
    );
}

/// The bounding sphere decides once per object: wholly inside (no
/// outcodes), wholly outside one plane (nothing prepared), or across.
#[test]
fn bounding_sphere_accepts_and_rejects_whole_objects() {
    use super::clip::Planes;
    use super::prepare::{sphere, Sphere};
    fn place<R: Real>(z: f32, scale: f32) -> Sphere {
        let cam = Camera::look_at_f32(
            [0.0, 0.0, 4.0],
            [0.0; 3],
            [0.0, 1.0, 0.0],
            45.0,
            1.0,
            Some(20.0),
        )
        .unwrap();
        let planes = Planes {
            near: cam.near,
            far: cam.far,
            guard: R::from_f32(4096.0 / 290.0),
        };
        let t = Affine::from_parts(
            R::from_f32(scale),
            Vec3::ZERO,
            Vec3::from_f32([0.0, 0.0, z]),
        );
        let mv = cam.view.then_after(&t);
        sphere(&planes, &shapes::BUNNY, &mv)
    }
    for (z, scale, want) in [
        (0.0, 1.0, Sphere::Inside),
        (2.5, 1.0, Sphere::Across),   // crosses the near plane (w = 1)
        (5.5, 1.0, Sphere::Outside),  // behind the near plane
        (-15.5, 1.0, Sphere::Across), // crosses the far plane (w = 20)
        (-30.0, 1.0, Sphere::Outside),
        (0.0, 0.01, Sphere::Inside),
    ] {
        assert_eq!(place::<crate::num::Q16>(z, scale), want, "Q16 {z} {scale}");
        assert_eq!(place::<f64>(z, scale), want, "f64 {z} {scale}");
    }
}

/// Non-uniform scale: normals go through the inverse-transpose and are
/// renormalised. Gouraud vertex levels of a sphere stretched (3, 1, 0.5)
/// and turned, under one directional light, against the f64 formula
/// `ka·Ia·C + kd·max(0, N·L)·C` with `N = normalize(M⁻ᵀ n)`: within 0.02
/// level (F64), 1 level (Q16, Q32); a uniform scale lights as before
/// (object-space path) within the same bounds.
#[test]
fn non_uniform_scale_lights_with_the_inverse_transpose() {
    use crate::geom::Mat3;
    fn run<P: Profile>(stretch: [f32; 3], tol: f64, lv: fn(P::Lerp) -> f64) {
        type R<P> = <P as Profile>::Real;
        let rot = Mat3::<R<P>>::rotation_y(R::<P>::from_f32(0.6))
            .compose(&Mat3::rotation_x(R::<P>::from_f32(0.3)));
        let diag = Mat3::from_rows([
            [R::<P>::from_f32(stretch[0]), R::<P>::ZERO, R::<P>::ZERO],
            [R::<P>::ZERO, R::<P>::from_f32(stretch[1]), R::<P>::ZERO],
            [R::<P>::ZERO, R::<P>::ZERO, R::<P>::from_f32(stretch[2])],
        ]);
        let m = rot.compose(&diag);
        let objs = [Object {
            mesh: shapes::SPHERE,
            transform: Affine { m, t: Vec3::ZERO },
            material: Material {
                color: Vec3::from_f32([1.0; 3]),
                ka: R::<P>::from_f32(0.2),
                kd: R::<P>::from_f32(0.8),
                ks: R::<P>::ZERO,
                shininess: R::<P>::ONE,
            },
            shading: Shading::Gouraud,
            cull_backfaces: true,
        }];
        let l = [0.3f64, 0.5, 0.81];
        let ls = [Light::directional(
            Vec3::from_f32(l.map(|c| c as f32)),
            R::<P>::ONE,
        )];
        let mut s = scene(&objs, &ls, [0.0, 0.0, 8.0]);
        s.ambient = R::<P>::ONE;
        let mut mem = Mem::<P::Lerp>::new(4000, 4000);
        let frame = prepare::<P>(&s, 128, 128, mem.ws()).unwrap();
        let po = &frame.objects()[0];
        assert_eq!(po.layout(), Layout::GouraudMono);
        // The exact inverse-transpose of the (f64) matrix, in world
        // space (the camera is a translation along z).
        let mf = m.rows.map(|r| r.to_f64());
        let c = |i: usize, j: usize| {
            mf[(i + 1) % 3][(j + 1) % 3] * mf[(i + 2) % 3][(j + 2) % 3]
                - mf[(i + 1) % 3][(j + 2) % 3] * mf[(i + 2) % 3][(j + 1) % 3]
        };
        let ln = {
            let n = (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]).sqrt();
            l.map(|x| x / n)
        };
        let mut worst = 0f64;
        // The vertices of the kept triangles (the others may have been
        // skipped: their triangles were culled in object space).
        let mut used = [false; 4000];
        for t in frame.tris() {
            for v in t.v {
                used[usize::from(v - po.verts.start)] = true;
            }
        }
        let normals = shapes::SPHERE.vertex_normals().unwrap();
        assert!(used.iter().filter(|&&u| u).count() * 3 > normals.len());
        for (i, n) in normals.iter().enumerate() {
            if !used[i] {
                continue;
            }
            let nq = n.map(|v| f64::from(v) / 16384.0);
            let ne: [f64; 3] =
                core::array::from_fn(|r| (0..3).map(|k| c(r, k) * nq[k]).sum::<f64>());
            let len = (ne[0] * ne[0] + ne[1] * ne[1] + ne[2] * ne[2]).sqrt();
            let nl = (0..3).map(|k| ne[k] / len * ln[k]).sum::<f64>().max(0.0);
            let want = 255.0 * (0.2 + 0.8 * nl).min(1.0);
            let at = po.val_base() + i * po.stride();
            let v = if po.layout().packed_in::<P>() {
                // Depth and level in one value: the level, in Q16.
                use crate::raster::Lerp;
                let raw = frame.ws.vals[at].fixed_raw().unwrap();
                P::Lerp::from_fixed_raw(unpack_grey(raw).1)
            } else {
                frame.ws.vals[at + 1]
            };
            let got = lv(v);
            worst = worst.max((got - want).abs());
        }
        assert!(worst <= tol, "{} {stretch:?}: {worst}", P::NAME);
    }
    let fixed = |v: i32| f64::from(v) / 65536.0;
    for stretch in [[3.0, 1.0, 0.5], [1.5, 1.5, 1.5]] {
        run::<F64>(stretch, 0.02, |v| v);
        run::<Precise>(stretch, 1.0, fixed);
        run::<Fast>(stretch, 1.0, fixed);
    }
}

/// The bunny benchmark (Gouraud and flat, `fast`): culling in object
/// space skips the vertices only back faces use, and the prepared
/// triangles and the frame equal those of the same mesh without culling
/// planes (every triangle culled by the screen sign).
#[test]
fn object_space_culling_keeps_the_frame_and_skips_vertices() {
    use crate::num::Q16;
    let b = shapes::BUNNY;
    let plain = Mesh::new(b.positions(), b.triangles(), b.vertex_normals())
        .unwrap()
        .with_face_normals(b.face_normals().unwrap())
        .unwrap();
    for shading in [Shading::Gouraud, Shading::Flat] {
        let run = |mesh: Mesh<'static>| {
            let objs = [Object {
                mesh,
                transform: Affine::IDENTITY,
                material: Material {
                    color: Vec3::from_f32([1.0; 3]),
                    ka: Q16::ONE,
                    kd: Q16::ONE,
                    ks: Q16::ZERO,
                    shininess: Q16::ONE,
                },
                shading,
                cull_backfaces: true,
            }];
            let ls = [Light::directional(
                Vec3::from_f32([1.0; 3]),
                Q16::from_f32(0.8),
            )];
            let s = Scene {
                camera: Camera::look_at_f32(
                    [0.0, 0.0, 3.922],
                    [0.0; 3],
                    [0.0, 1.0, 0.0],
                    45.0,
                    1.0,
                    Some(10.0),
                )
                .unwrap(),
                objects: &objs,
                lights: &ls,
                ambient: Q16::from_f32(0.2),
                specular: Specular::Phong,
                viewer: Viewer::Infinite,
                background: Rgb8::BLACK,
            };
            let mut mem = Mem::<i32>::new(2000, 2000);
            let frame = prepare::<Fast>(&s, 240, 240, mem.ws()).unwrap();
            let skipped = (0..frame.vertex_count())
                .filter(|&v| frame.xy(v).unwrap()[0] == i32::from(super::prepare::UNUSED))
                .count();
            let tris = frame.tris().collect::<Vec<_>>();
            (tris, skipped, full::<Fast>(&s, 240, 240, true))
        };
        let (t0, s0, f0) = run(plain);
        let (t1, s1, f1) = run(b);
        std::println!(
            "{shading:?}: {} triangles kept, {s1} of {} vertices skipped",
            t1.len(),
            b.vertex_count()
        );
        assert_eq!(s0, 0);
        assert_eq!(t0, t1);
        assert!(f0 == f1, "{shading:?}: frames differ");
        assert_eq!(t1.len(), 1498);
        assert!(s1 > 600, "{shading:?}: {s1}");
    }
}

/// A triangle whose upper edge runs 4 400 pixels across within two
/// subpixel rows: the guard band (2 014 pixels around the centre of a
/// 64 × 48 screen at 4 subpixel bits, see `guard_px`) cuts it into two
/// triangles whose edges stay within ±2 047 pixels, so their walks pack
/// into pool slots: each is set up once, with one-row bands too, and the
/// bytes are those of the full frame (fast path: `Fast`; general path:
/// `F64`).
#[test]
fn walks_within_the_guard_band_pack_with_the_same_bytes() {
    // Raw Q1.14 positions scaled by 200: A (-200, 0.0517) and B (200,
    // 0.0395), 0.13 pixels apart around the centre of row 23; C below.
    const POS: [[i16; 3]; 3] = [[-16384, 1, 0], [16384, 0, 0], [0, -3000, 0]];
    fn run<P: Profile>(shading: Shading) {
        let mesh = Mesh::new(&POS, &[[0, 2, 1]], None).unwrap();
        let f = P::Real::from_f32;
        let objs = [matte(
            mesh,
            Affine::from_parts(f(200.0), Vec3::ZERO, Vec3::new(f(0.0), f(0.03953), f(0.0))),
            shading,
        )];
        let ls = lights();
        let s = scene(&objs, &ls, [0.0, 0.0, 6.0]);
        let (w, h) = (64, 48);
        let whole = full::<P>(&s, w, h, true);
        let bg = Rgb565Be::encode_bytes(s.background);
        // Rows 23 (partly) to 47 covered, row 22 not.
        let row = |y: usize| &whole[y * 2 * w as usize..(y + 1) * 2 * w as usize];
        assert!(row(22).chunks(2).all(|c| c == bg), "{}", P::NAME);
        assert!(row(23).chunks(2).any(|c| c != bg), "{}", P::NAME);
        assert!(row(24).chunks(2).all(|c| c != bg), "{}", P::NAME);
        for rows in [1, 7] {
            let (out, stats, n) = banded_with::<P, 256, 8>(&s, w, h, rows, true);
            assert_eq!(out, whole, "{} rows {rows}", P::NAME);
            // Two triangles, each set up once.
            assert_eq!(n, 2);
            assert_eq!(stats.triangles, 2, "{} rows {rows}", P::NAME);
        }
    }
    run::<Fast>(Shading::Flat);
    run::<F64>(Shading::Flat);
}

/// `Fast` with 8 subpixel bits: positions stored from the screen's
/// centre.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Fast8;

impl Profile for Fast8 {
    type Real = crate::num::Q16;
    type Lerp = i32;
    const NAME: &'static str = "fast8";
    const SUBPIXEL_BITS: crate::num::SubpixelBits = match crate::num::SubpixelBits::new(8) {
        Ok(b) => b,
        Err(_) => panic!("8 bits"),
    };
    fn level(r: crate::num::Q16) -> i32 {
        Fast::level(r)
    }
    fn depth(r: crate::num::Q16) -> i32 {
        Fast::depth(r)
    }
    fn unit(r: crate::num::Q16) -> i32 {
        Fast::unit(r)
    }
    fn unit_back(l: i32) -> crate::num::Q16 {
        Fast::unit_back(l)
    }
    fn coord(r: crate::num::Q16) -> i32 {
        Fast::coord(r)
    }
    fn coord_back(l: i32) -> crate::num::Q16 {
        Fast::coord_back(l)
    }
}

/// Stored screen positions are `i16` subpixels ([`ScreenXy`]): the guard
/// band narrows so that they fit (`guard_px`), and a screen too large for
/// any guard band is [`SceneError::Screen`]: 2 044 pixels at 4 subpixel
/// bits (`XY_LIMIT >> 4` = 2 047 pixels of range from the corner: a
/// half-screen of 1 022, a band of 2 047 - 1 022 - 1 = 1 024 pixels
/// around the centre), 250 at 8 bits (from the centre: 127 - 1 = 126 >=
/// 125 + 1). A triangle thousands of pixels across on the largest screen is
/// clipped by the band, and every stored coordinate lies within the
/// band, inside `±XY_LIMIT`.
#[test]
fn compact_positions_hold_the_screen_and_its_guard_band() {
    use super::prepare::guard_px;
    use crate::scene::SceneError;
    let most = (1..=8).map(max_screen).collect::<Vec<_>>();
    assert_eq!(most, [4096, 4096, 4092, 2044, 2042, 1018, 506, 250]);
    assert_eq!(guard_px(4, 2044, 100), Some(1024));
    assert_eq!(guard_px(4, 2045, 100), None);
    assert_eq!(guard_px(4, 240, 240), Some(2047 - 120 - 1));
    assert_eq!(guard_px(8, 240, 250), Some(126));
    assert_eq!(guard_px(8, 251, 240), None);
    assert_eq!(guard_px(2, 4096, 4096), Some(4096));
    assert_eq!(guard_px(2, 4097, 1), None);
    for bits in 1..=8 {
        let n = max_screen(bits);
        assert!(guard_px(bits, n, n).is_some(), "{bits}");
        assert!(n == crate::target::MAX_SCREEN || guard_px(bits, n + 1, 1).is_none());
    }
    // One triangle 10 units across at 1 unit from the eye.
    const POS: [[i16; 3]; 3] = [[-16384, -8000, 0], [16384, -8000, 0], [0, 16000, 0]];
    fn run<P: Profile>(n: u32) -> Result<(), RenderError> {
        let mesh = Mesh::new(&POS, &[[0, 1, 2]], None).unwrap();
        let f = P::Real::from_f32;
        let objs = [matte(
            mesh,
            Affine::from_parts(f(5.0), Vec3::ZERO, Vec3::ZERO),
            Shading::Flat,
        )];
        let ls = lights();
        let s = scene(&objs, &ls, [0.0, 0.0, 1.0]);
        let mut mem = Mem::<P::Lerp>::new(64, 64);
        let frame = prepare::<P>(&s, n, n, mem.ws())?;
        assert_face_rows(&frame);
        let sub = P::SUBPIXEL_BITS.get();
        let g = guard_px(sub, n, n).unwrap();
        assert!(frame.triangle_count() > 1, "clipped into a fan");
        let c = (n << sub) as i32 / 2;
        // The corners of the kept triangles (the mesh's own corners lie
        // outside the planes: marked, never drawn).
        for v in frame.tris().flat_map(|t| t.v).map(usize::from) {
            let p = frame.xy(v).unwrap();
            let stored = mem_xy(&frame, v);
            for (k, q) in p.into_iter().enumerate() {
                assert!((q - c).abs() <= (g + 1) << sub, "{v} {p:?}");
                assert!(i32::from(stored[k]).abs() <= XY_LIMIT);
            }
        }
        Ok(())
    }
    fn mem_xy<P: Profile>(frame: &Frame<'_, P>, v: usize) -> [i16; 2] {
        frame.ws.xy[v].0
    }
    run::<Fast>(2044).unwrap();
    run::<Fast8>(250).unwrap();
    run::<F64>(2044).unwrap();
    assert_eq!(run::<Fast>(2046), Err(SceneError::Screen.into()));
    assert_eq!(run::<Fast8>(252), Err(SceneError::Screen.into()));
    // 8 bits on a 240-pixel screen: stored from the centre, read back
    // from the corner.
    run::<Fast8>(240).unwrap();
}

/// Packed grey values ([`pack_grey`]): the depth back within `2^13` (half
/// a 16-bit depth step) and below `2^30`, the level within `2^7` and never
/// above `255 · 2^16`, over the whole ranges and at their ends.
#[test]
fn packed_grey_values_are_within_their_bounds() {
    let full = 255 << 16;
    let mut worst = (0i64, 0i64);
    let mut check = |d: i32, l: i32| {
        let (d2, l2) = unpack_grey(pack_grey(d, l));
        assert!(
            (0..1 << 30).contains(&d2) && (0..=full).contains(&l2),
            "{d} {l}"
        );
        worst.0 = worst.0.max((i64::from(d2) - i64::from(d)).abs());
        worst.1 = worst.1.max((i64::from(l2) - i64::from(l)).abs());
        // Each half leaves the other alone.
        assert_eq!(unpack_grey(grey_depth(d) | grey_level(l)), (d2, l2));
    };
    let mut x = 0x2545_F491u32;
    for _ in 0..200_000 {
        x ^= x << 13;
        x ^= x >> 17;
        x ^= x << 5;
        let d = (x >> 2) as i32 % ((1 << 30) + 1);
        let l = (x.rotate_left(11) % (full as u32 + 1)) as i32;
        check(d, l);
    }
    for d in [0, 1, (1 << 13) - 1, 1 << 13, (1 << 30) - 1, 1 << 30] {
        for l in [0, 127, 128, full - 128, full - 127, full] {
            check(d, l);
        }
    }
    assert!(worst.0 <= 1 << 13, "{worst:?}");
    assert!(worst.1 <= 1 << 7, "{worst:?}");
    // At the far plane the depth saturates to the last step.
    assert_eq!(unpack_grey(pack_grey(1 << 30, 0)).0, (1 << 30) - (1 << 13));
}

/// Renders band by band with an order scratch of `len(n, numbers)`
/// entries (`n` prepared triangles, `numbers` triangle numbers) and a pool
/// of `CAP` slots of eight values: the bytes, or the error.
fn banded_order<const CAP: usize>(
    s: &Scene<'_, 'static, crate::num::Q16>,
    (w, h, rows): (u32, u32, u32),
    len: impl Fn(usize, usize) -> usize,
) -> Result<Vec<u8>, RenderError> {
    let mut mem = Mem::<i32>::new(12_000, 12_000);
    let frame = prepare::<Fast>(s, w, h, mem.ws()).unwrap();
    assert_face_rows(&frame);
    let mut px = vec![0u16; (w * rows) as usize];
    let mut z = vec![0u16; (w * rows) as usize];
    let mut band = BandBuf::<Rgb565Be>::new(&mut px, Some(&mut z[..]), w, rows).unwrap();
    let mut order = vec![0u16; len(frame.triangle_count(), frame.triangle_numbers())];
    let mut pool = Box::new(Pool::<i32, CAP, 8>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let mut out = vec![];
    frame.render_bands(s, &mut state, &mut band, |b| {
        out.extend(b.bytes());
        Ok::<(), RenderError>(())
    })?;
    Ok(out)
}

#[test]
fn bands_read_from_the_faces_bytes_equal_the_full_frame() {
    // 200 rows: the faces bytes keep first rows halved (`face_shift` 1):
    // even band heights read the band from them, odd ones from the
    // vertices; beyond 64 bands (1, 2 and 3 rows) the bands are ordered
    // in runs of 64.
    assert_eq!(
        [127, 128, 200, 240, 254, 255, 4096].map(face_shift),
        [0, 1, 1, 1, 1, 2, 6]
    );
    let objs = every_shape::<crate::num::Q16>(Shading::Gouraud);
    let ls = lights();
    let s = scene(&objs, &ls, [0.5, 1.0, 7.0]);
    let (w, h) = (96, 200);
    let whole = full::<Fast>(&s, w, h, true);
    for rows in [1, 2, 3, 8, 13, 200] {
        let at = (w, h, rows);
        // The kept triangles twice: listed, then placed from the list.
        assert_eq!(
            banded_order::<256>(&s, at, |n, _| 2 * n).unwrap(),
            whole,
            "rows {rows}"
        );
        // One entry per triangle number (as `Storage` gives): placed from
        // the bytes when the kept triangles fill more than half of it; a
        // pool of two slots queues the others in the rest.
        assert_eq!(
            banded_order::<256>(&s, at, |_, t| t).unwrap(),
            whole,
            "rows {rows}"
        );
        assert_eq!(
            banded_order::<2>(&s, at, |_, t| t).unwrap(),
            whole,
            "rows {rows}"
        );
        // No room for the queue: the same frame when nothing is put off,
        // else an error naming the order, never another frame.
        assert_eq!(
            banded_order::<256>(&s, at, |n, _| n).unwrap(),
            whole,
            "rows {rows}"
        );
        match banded_order::<2>(&s, at, |n, _| n) {
            Ok(b) => assert_eq!(b, whole, "rows {rows}"),
            Err(e) => assert_eq!(
                e,
                RenderError::Capacity {
                    part: Part::Order,
                    object: 0
                },
                "rows {rows}"
            ),
        }
        // Shorter than the kept triangles: refused.
        assert_eq!(
            banded_order::<256>(&s, at, |n, _| n - 1).unwrap_err(),
            RenderError::Capacity {
                part: Part::Order,
                object: 0
            }
        );
    }
}

#[test]
fn prepare_in_makes_the_frame_prepare_returns() {
    let objs = [
        object::<crate::num::Q16>(shapes::SPHERE, Shading::Gouraud, [0.3, 0.2, 0.0]),
        object::<crate::num::Q16>(shapes::CUBE, Shading::Flat, [0.1, 0.5, 0.0]),
    ];
    let ls = lights();
    let s = scene(&objs, &ls, [0.0, 0.0, 5.0]);
    let mut a = Mem::<i32>::new(2000, 2000);
    let mut b = Mem::<i32>::new(2000, 2000);
    let want = prepare::<Fast>(&s, 64, 48, a.ws()).unwrap();
    let mut out = None;
    prepare_in::<Fast>(&s, 64, 48, b.ws(), &mut out).unwrap();
    let got = out.as_ref().unwrap();
    assert_eq!(got.objects(), want.objects());
    assert_eq!(
        (got.vertex_count(), got.triangle_count(), got.bytes_used()),
        (
            want.vertex_count(),
            want.triangle_count(),
            want.bytes_used()
        )
    );
    assert!(got.triangle_count() > 0);
    drop(want);
    assert_eq!((&a.xy, &a.vals, &a.faces), (&b.xy, &b.vals, &b.faces));
    // An error leaves no frame, also where one was.
    let mut small = Mem::<i32>::new(10, 2000);
    let mut out = Some(prepare::<Fast>(&s, 64, 48, a.ws()).unwrap());
    assert_eq!(
        prepare_in::<Fast>(&s, 64, 48, small.ws(), &mut out),
        Err(RenderError::Capacity {
            part: Part::Vertices,
            object: 0
        })
    );
    assert!(out.is_none());
}

/// [`Frame::tri_in`] with the layout given equals [`Frame::tri_of`] for
/// every triangle number of every object (kept or not, mesh and made
/// triangles: two-sided, clipped), and without the colour for every
/// object that is not flat (the band loop's grey Gouraud path on ARMv6-M).
#[test]
fn triangles_with_the_layout_given_equal_those_read_with_it() {
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
        let objs = every_shape::<<Fast as Profile>::Real>(shading);
        let ls = lights();
        let s = scene(&objs, &ls, [0.5, 1.0, 2.5]);
        let mut mem = Mem::<<Fast as Profile>::Lerp>::new(4096, 4096);
        let frame = prepare::<Fast>(&s, 96, 64, mem.ws()).unwrap();
        let mut seen = 0;
        for po in frame.objects() {
            let mesh = frame.mesh_tris(po);
            let flat = po.layout() == Layout::Flat;
            for i in usize::from(po.tris.start)..usize::from(po.tris.end) {
                let t = frame.tri_of(po, mesh, i);
                assert!(t.is_some(), "{shading:?} {i}");
                assert_eq!(frame.tri_in(po, mesh, i, flat), t);
                if !flat {
                    assert_eq!(frame.tri_in(po, mesh, i, false), t);
                    assert_eq!(t.map(|t| t.color), Some(Rgb8::BLACK));
                }
                seen += 1;
            }
        }
        assert!(seen > 100, "{shading:?} {seen}");
    }
}

/// ARMv6-M's fetch of packed grey triangles ([`active::fetch_grey_then_sort`])
/// equals [`active::fetch_fixed`]'s general form for every triangle of
/// grey Gouraud shapes and for random vertex indices (in range, past the
/// object's vertices and past the positions: `None` alike), with equal `y`s
/// among them (the sort's order for ties).
#[test]
fn grey_fetch_sorting_vertices_equals_sorting_indices() {
    let (objs, ls) = grey_shapes(Shading::Gouraud);
    let mut s = scene(&objs, &ls, [0.5, 1.0, 7.0]);
    s.ambient = Q16::ONE;
    let mut mem = Mem::<<Fast as Profile>::Lerp>::new(4096, 4096);
    let frame = prepare::<Fast>(&s, 96, 64, mem.ws()).unwrap();
    let mut rng = crate::geom::testkit::xorshift(0x5eed_f00d);
    let (mut some, mut none) = (0, 0);
    for po in frame.objects() {
        assert!(po.layout().packed_in::<Fast>());
        let mesh = frame.mesh_tris(po);
        let n = frame.ws.xy.len() as u64;
        let mut check = |tri: &PreparedTri| {
            let a = active::fetch_grey_then_sort::<Fast, 1>(&frame, po, tri);
            assert_eq!(
                a,
                active::fetch_fixed::<Fast, 1>(&frame, po, tri),
                "{tri:?}"
            );
            if a.is_some() {
                some += 1;
            } else {
                none += 1;
            }
        };
        for i in usize::from(po.tris.start)..usize::from(po.tris.end) {
            let t = frame.tri_of(po, mesh, i).unwrap();
            check(&t);
            // The same corners with two of them swapped, and one repeated
            // (equal `y`s).
            check(&PreparedTri {
                v: [t.v[1], t.v[0], t.v[2]],
                ..t
            });
            check(&PreparedTri {
                v: [t.v[2], t.v[0], t.v[2]],
                ..t
            });
        }
        for _ in 0..300 {
            let mut r = || (rng() % (n + 40)) as u16;
            let v = [r(), r(), r()];
            check(&PreparedTri {
                v,
                ..PreparedTri::default()
            });
            let w = [u16::MAX, v[1], v[2]];
            check(&PreparedTri {
                v: w,
                ..PreparedTri::default()
            });
        }
    }
    assert!(some > 1000 && none > 100, "{some} {none}");
}
