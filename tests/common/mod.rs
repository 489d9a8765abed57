//! Shared helpers of the shading integration tests: scenes described once
//! in `f64` and built for any profile, full-frame renders with coverage,
//! and image comparisons.
#![allow(dead_code)] // each test binary uses a different subset

pub mod rng;

/// A test running the check `$check::<P>()` for each of the four
/// profiles `P`: `Fast`, `Precise`, `F32` and `F64`.
#[allow(unused_macros)] // not every test binary runs per-profile checks
macro_rules! per_profile {
    ($(#[$m:meta])* fn $test:ident = $check:ident) => {
        $(#[$m])*
        #[test]
        fn $test() {
            $check::<fixshade::num::Fast>();
            $check::<fixshade::num::Precise>();
            $check::<fixshade::num::F32>();
            $check::<fixshade::num::F64>();
        }
    };
}
#[allow(unused_imports)] // not every test binary runs per-profile checks
pub(crate) use per_profile;

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, LightKind, Material, Specular, Viewer};
use fixshade::mesh::Mesh;
use fixshade::num::{Profile, Real};
use fixshade::render::{prepare, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, Shading};
use fixshade::target::{Depth32, DepthBuffer, FrameBuf, Rgb8, Rgb888};

/// A material in `f64`: colour, ka, kd, ks, shininess.
#[derive(Clone, Copy, Debug)]
pub struct Mat {
    pub color: [f64; 3],
    pub ka: f64,
    pub kd: f64,
    pub ks: f64,
    pub n: f64,
}

impl Mat {
    pub fn to<R: Real>(self) -> Material<R> {
        Material {
            color: v3(self.color),
            ka: R::from_f64(self.ka),
            kd: R::from_f64(self.kd),
            ks: R::from_f64(self.ks),
            shininess: R::from_f64(self.n),
        }
    }
}

/// A light in `f64`, world space.
#[derive(Clone, Copy, Debug)]
pub enum Lamp {
    /// Point light at a position, intensity, colour.
    Point([f64; 3], f64, [f64; 3]),
    /// Directional light towards a direction, intensity, colour.
    Dir([f64; 3], f64, [f64; 3]),
}

impl Lamp {
    pub fn to<R: Real>(self) -> Light<R> {
        match self {
            Lamp::Point(p, i, c) => Light {
                kind: LightKind::Point(v3(p)),
                intensity: R::from_f64(i),
                color: v3(c),
            },
            Lamp::Dir(d, i, c) => Light {
                kind: LightKind::Directional(v3(d)),
                intensity: R::from_f64(i),
                color: v3(c),
            },
        }
    }
}

pub const WHITE: [f64; 3] = [1.0, 1.0, 1.0];

/// An object in `f64` terms.
#[derive(Clone, Copy, Debug)]
pub struct Obj {
    pub mesh: Mesh<'static>,
    /// Uniform scale, rotation angles (radians, X then Y then Z), offset.
    pub scale: f64,
    pub angles: [f64; 3],
    pub offset: [f64; 3],
    pub mat: Mat,
    pub shading: Shading,
    pub cull: bool,
}

/// A scene in `f64` terms: camera eye and target (up = +y), vertical field
/// of view in degrees, objects, lights, ambient, specular model, viewer.
#[derive(Clone, Debug)]
pub struct Desc {
    pub eye: [f64; 3],
    pub target: [f64; 3],
    pub fov_deg: f64,
    pub objects: Vec<Obj>,
    pub lamps: Vec<Lamp>,
    pub ambient: f64,
    pub specular: Specular,
    pub viewer: Viewer,
}

pub fn v3<R: Real>(v: [f64; 3]) -> Vec3<R> {
    Vec3::new(R::from_f64(v[0]), R::from_f64(v[1]), R::from_f64(v[2]))
}

/// A rendered frame: colours and which pixels were drawn.
#[derive(Clone, Debug)]
pub struct Image {
    pub w: u32,
    pub h: u32,
    pub px: Vec<Rgb8>,
    pub covered: Vec<bool>,
}

impl Image {
    pub fn at(&self, x: u32, y: u32) -> Rgb8 {
        self.px[(y * self.w + x) as usize]
    }

    /// Red channel (grey scenes: the level).
    pub fn lvl(&self, x: u32, y: u32) -> u8 {
        self.at(x, y).r
    }

    pub fn is_covered(&self, x: u32, y: u32) -> bool {
        self.covered[(y * self.w + x) as usize]
    }

    /// Brightest pixel (sum of channels) and its position (first in
    /// row-major order on ties).
    pub fn brightest(&self) -> (u32, u32, Rgb8) {
        let mut best = (0, 0, Rgb8::BLACK);
        let mut key = -1i32;
        for y in 0..self.h {
            for x in 0..self.w {
                let c = self.at(x, y);
                let k = c.r as i32 + c.g as i32 + c.b as i32;
                if self.is_covered(x, y) && k > key {
                    key = k;
                    best = (x, y, c);
                }
            }
        }
        best
    }
}

/// Builds the scene for profile `P` and renders it full-frame (`w × h`,
/// RGB888, 32-bit depth, black background). Panics on any error.
pub fn render<P: Profile>(d: &Desc, w: u32, h: u32) -> Image {
    build::<P, _>(d, |scene| render_scene::<P>(scene, w, h))
}

/// Builds the scene for profile `P` and hands it to `f`.
pub fn build<P: Profile, T>(d: &Desc, then: impl FnOnce(&Scene<'_, '_, P::Real>) -> T) -> T {
    let f = |x: f64| x as f32;
    let camera = Camera::<P::Real>::look_at_f32(
        d.eye.map(f),
        d.target.map(f),
        [0.0, 1.0, 0.0],
        d.fov_deg as f32,
        0.1,
        Some(100.0),
    )
    .expect("camera");
    let objects: Vec<Object<'static, P::Real>> = d
        .objects
        .iter()
        .map(|o| Object {
            mesh: o.mesh,
            transform: Affine::from_parts(P::Real::from_f64(o.scale), v3(o.angles), v3(o.offset)),
            material: o.mat.to(),
            shading: o.shading,
            cull_backfaces: o.cull,
        })
        .collect();
    let lights: Vec<Light<P::Real>> = d.lamps.iter().map(|l| l.to()).collect();
    let scene = Scene {
        camera,
        objects: &objects,
        lights: &lights,
        ambient: P::Real::from_f64(d.ambient),
        specular: d.specular,
        viewer: d.viewer,
        background: Rgb8::BLACK,
    };
    then(&scene)
}

/// Renders a scene already built for profile `P`.
pub fn render_scene<P: Profile>(scene: &Scene<'_, '_, P::Real>, w: u32, h: u32) -> Image {
    with_scene::<P, _>(scene, w, h, |_| ()).0
}

/// The snapped screen positions (subpixels) of every prepared vertex.
pub fn snapped<P: Profile>(d: &Desc, w: u32, h: u32) -> Vec<[i32; 2]> {
    build::<P, _>(d, |scene| {
        with_scene::<P, _>(scene, w, h, |f| {
            (0..f.vertex_count()).map(|v| f.xy(v).unwrap()).collect()
        })
        .1
    })
}

/// Prepares and renders `scene`, and hands the prepared frame to `inspect`.
pub fn with_scene<P: Profile, T>(
    scene: &Scene<'_, '_, P::Real>,
    w: u32,
    h: u32,
    inspect: impl FnOnce(&fixshade::render::Frame<'_, P>) -> T,
) -> (Image, T) {
    let tris: usize = scene.objects.iter().map(|o| o.mesh.triangle_count()).sum();
    let mesh_verts: usize = scene.objects.iter().map(|o| o.mesh.vertex_count()).sum();
    let verts = mesh_verts + 2 * 3 * tris + 64;
    let mut xy = vec![fixshade::render::ScreenXy::ZERO; verts];
    let mut vals = vec![P::Lerp::default(); verts * 7];
    let mut tri_buf = vec![Tri::default(); 4 * tris + 16];
    // Triangle numbers: the meshes' and the made triangles'.
    let mut faces = vec![0u8; 8 * tris + 16];
    let mut colors = vec![fixshade::target::Rgb8::BLACK; faces.len()];
    let ws = Workspace {
        xy: &mut xy,
        vals: &mut vals,
        tris: &mut tri_buf,
        colors: &mut colors,
        faces: &mut faces,
    };
    let frame = prepare::<P>(scene, w, h, ws).expect("prepare");
    let mut px = vec![[0u8; 3]; (w * h) as usize];
    let mut z = vec![0u32; (w * h) as usize];
    let mut fb = FrameBuf::<Rgb888>::new(&mut px, w, h).expect("frame");
    let mut db = DepthBuffer::<Depth32>::new(&mut z, w, 0, h).expect("depth");
    frame.render(scene, &mut fb, Some(&mut db)).expect("render");
    let t = inspect(&frame);
    let covered = z.iter().map(|&d| d != u32::MAX).collect();
    let img = Image {
        w,
        h,
        px: px.iter().map(|p| Rgb8::new(p[0], p[1], p[2])).collect(),
        covered,
    };
    (img, t)
}

/// Pixel-by-pixel comparison of a profile's frame with the reference.
#[derive(Clone, Copy, Debug, Default)]
pub struct Diff {
    /// Pixels covered by both.
    pub both: usize,
    /// Pixels covered by exactly one of them.
    pub coverage: usize,
    /// Largest channel difference over pixels covered by both.
    pub max: u8,
    /// Pixels (covered by both) whose largest channel difference is > 1.
    pub over1: usize,
    /// Mean absolute channel difference over pixels covered by both.
    pub mean: f64,
    /// Largest channel difference over interior pixels: those whose 3 × 3
    /// neighbourhood is covered by both (away from silhouettes).
    pub interior: u8,
}

pub fn diff(a: &Image, reference: &Image) -> Diff {
    assert_eq!((a.w, a.h), (reference.w, reference.h));
    let mut d = Diff::default();
    let mut sum = 0u64;
    for i in 0..a.px.len() {
        match (a.covered[i], reference.covered[i]) {
            (true, true) => {
                d.both += 1;
                let (p, q) = (a.px[i], reference.px[i]);
                let e = [p.r.abs_diff(q.r), p.g.abs_diff(q.g), p.b.abs_diff(q.b)];
                let m = e[0].max(e[1]).max(e[2]);
                d.max = d.max.max(m);
                let (x, y) = ((i as u32 % a.w) as i64, (i as u32 / a.w) as i64);
                let inside = (-1..=1).all(|dy| {
                    (-1..=1).all(|dx| {
                        let (u, v) = (x + dx, y + dy);
                        u >= 0
                            && v >= 0
                            && u < a.w as i64
                            && v < a.h as i64
                            && a.is_covered(u as u32, v as u32)
                            && reference.is_covered(u as u32, v as u32)
                    })
                });
                if inside {
                    d.interior = d.interior.max(m);
                }
                if m > 1 {
                    d.over1 += 1;
                }
                sum += e.iter().map(|&v| v as u64).sum::<u64>();
            }
            (false, false) => {}
            _ => d.coverage += 1,
        }
    }
    d.mean = sum as f64 / (3 * d.both.max(1)) as f64;
    d
}

/// Q1.14 from a float.
pub fn q14(v: f64) -> i16 {
    (v * 16384.0).round() as i16
}

/// Leaks a slice so a test-built mesh can be `'static`.
pub fn leak<T>(v: Vec<T>) -> &'static [T] {
    Box::leak(v.into_boxed_slice())
}

/// The square of [`square`] with vertex normals `normals`, seen
/// head-on from (0, 0, 3) at 45°, culled, under `lamps` (Phong, local
/// viewer).
pub fn square_scene(
    normals: [[i16; 3]; 4],
    mat: Mat,
    lamps: Vec<Lamp>,
    shading: Shading,
    ambient: f64,
) -> Desc {
    Desc {
        eye: [0.0, 0.0, 3.0],
        target: [0.0; 3],
        fov_deg: 45.0,
        objects: vec![Obj {
            mesh: square(normals),
            scale: 1.0,
            angles: [0.0; 3],
            offset: [0.0; 3],
            mat,
            shading,
            cull: true,
        }],
        lamps,
        ambient,
        specular: Specular::Phong,
        viewer: Viewer::Local,
    }
}

/// A square `[-1, 1]²` in the plane z = 0 facing +z, as two triangles
/// with the diagonal from (-1, -1) to (1, 1), and one normal per corner
/// (`normals` in corner order (-1,-1), (1,-1), (1,1), (-1,1), not
/// necessarily unit: raw Q1.14).
pub fn square(normals: [[i16; 3]; 4]) -> Mesh<'static> {
    let pos = leak(vec![
        [-16384, -16384, 0],
        [16383, -16384, 0],
        [16383, 16383, 0],
        [-16384, 16383, 0],
    ]);
    let tris = leak(vec![[0u16, 1, 2], [0, 2, 3]]);
    let nrm = leak(normals.to_vec());
    Mesh::new(pos, tris, Some(nrm)).expect("square mesh")
}

/// The reference Phong illumination in `f64`, written from the formula
/// in `fixshade::illum` (not from its code): `I = Ia·ka·C + Σ Ip·Lc·(kd·
/// max(0, N·L)·C + ks·S)`, `S` only where `N·L > 0`, channels clamped
/// after the sum. Inputs are used as given (coefficients clamped to
/// `[0, 1]`, shininess to `[0, 10 000]`).
pub fn phong_f64(
    m: &Mat,
    ambient: f64,
    lamps: &[Lamp],
    specular: Specular,
    viewer: Viewer,
    n: [f64; 3],
    p: [f64; 3],
) -> [f64; 3] {
    let c01 = |x: f64| x.clamp(0.0, 1.0);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let norm = |a: [f64; 3]| {
        let l = dot(a, a).sqrt();
        if l == 0.0 {
            a
        } else {
            a.map(|x| x / l)
        }
    };
    let col = m.color.map(c01);
    let (ka, kd, ks) = (c01(m.ka), c01(m.kd), c01(m.ks));
    let sh = m.n.clamp(0.0, 10_000.0);
    let v = match viewer {
        Viewer::Local => norm(p.map(|x| -x)),
        Viewer::Infinite => [0.0, 0.0, 1.0],
    };
    let mut out = col.map(|c| c01(ambient) * ka * c);
    for lamp in lamps {
        let (l, ip, lc) = match *lamp {
            Lamp::Point(q, i, c) => (norm([q[0] - p[0], q[1] - p[1], q[2] - p[2]]), i, c),
            Lamp::Dir(d, i, c) => (norm(d), i, c),
        };
        let lc = lc.map(|x| c01(x) * ip.max(0.0));
        let nl = dot(n, l);
        if nl <= 0.0 {
            continue;
        }
        let s = if ks > 0.0 {
            let base = match specular {
                Specular::Phong => {
                    let r = [0, 1, 2].map(|k| 2.0 * nl * n[k] - l[k]);
                    dot(r, v)
                }
                Specular::Blinn => dot(n, norm([l[0] + v[0], l[1] + v[1], l[2] + v[2]])),
            };
            // max(0, base)^n, with 0^0 = 1 as the core (`Real::powf`)
            // and the ideal renderer define it: at n = 0 the specular term
            // is ks wherever N·L > 0, even where R·V (or N·H) <= 0.
            if base > 0.0 {
                base.min(1.0).powf(sh)
            } else if sh == 0.0 {
                1.0
            } else {
                0.0
            }
        } else {
            0.0
        };
        for k in 0..3 {
            out[k] += lc[k] * (kd * nl * col[k] + ks * s);
        }
    }
    out.map(c01)
}

/// `mesh` with generated fully smooth normals (one per vertex).
pub fn smooth(mesh: Mesh<'static>) -> Mesh<'static> {
    use fixshade::mesh::{generate_normals, weld, CornerNormals, Smoothing};
    let (t, v) = (mesh.triangle_count(), mesh.vertex_count());
    let mut adjacency = vec![0u16; 3 * t];
    let mut offsets = vec![0u32; v + 1];
    let mut normals = vec![[0i16; 3]; 3 * t];
    let mut indices = vec![[0u16; 3]; t];
    let n = generate_normals(
        &mesh,
        &Smoothing::SMOOTH,
        &mut adjacency,
        &mut offsets,
        &mut normals,
        &mut indices,
    )
    .expect("normals");
    normals.truncate(n);
    let cap = 3 * t;
    let (mut pos, mut nrm) = (vec![[0i16; 3]; cap], vec![[0i16; 3]; cap]);
    let mut tris = vec![[0u16; 3]; t];
    let mut scratch = vec![0u16; v + cap];
    let count = weld(
        mesh.positions(),
        mesh.triangles(),
        CornerNormals {
            normals: &normals,
            indices: &indices,
        },
        &mut pos,
        &mut nrm,
        &mut tris,
        &mut scratch,
    )
    .expect("weld");
    pos.truncate(count);
    nrm.truncate(count);
    Mesh::new(leak(pos), leak(tris), Some(leak(nrm))).expect("smooth mesh")
}
