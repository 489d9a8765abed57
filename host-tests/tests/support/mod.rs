//! Shared helpers of the `extreme_*` and `prop_*` tests: owned workspace
//! memory, a counting target, whole-frame and banded renders, and one scene
//! description that builds both a core [`Scene`] for any profile and the
//! matching [`IdealScene`] for the independent f64 reference.
#![allow(dead_code)] // each test module uses a different part

/// The tests' pseudo-random numbers: the core's tests' generator.
#[path = "../../../tests/common/rng.rs"]
pub mod rng;

use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, LightKind, Material, Specular, Viewer};
use fixshade::mesh::Mesh;
use fixshade::num::{Profile, Real};
use fixshade::render::{prepare, BandState, Pool, RenderError, RenderStats};
use fixshade::scene::{Camera, Object, Scene, SceneError, Shading};
use fixshade::target::{
    BandBuf, Depth32, DepthBuffer, FrameBuf, Gray8, PixelFormat, Rgb8, Rgb888, Target, Window,
};
use fixshade_host::core_render::OwnedWorkspace;
use fixshade_host::ideal::{self, IdealScene};

/// The `fixshade` command under test.
pub const EXE: &str = env!("CARGO_BIN_EXE_fixshade");

/// A fresh, empty temporary folder (`fixshade-TAG-PID` in the system's),
/// removed when dropped; it derefs to its path.
pub struct TempDir(pub std::path::PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("fixshade-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("create temp dir");
        Self(dir)
    }

    pub fn path(&self, name: &str) -> std::path::PathBuf {
        self.0.join(name)
    }

    /// Writes `text` to the file `name` in the folder; its path.
    pub fn write(&self, name: &str, text: &str) -> std::path::PathBuf {
        let path = self.path(name);
        std::fs::write(&path, text).expect("write test file");
        path
    }

    /// The names of the files in the folder, sorted.
    pub fn files(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(&self.0)
            .expect("list temp dir")
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl std::ops::Deref for TempDir {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

impl AsRef<std::path::Path> for TempDir {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Runs `fixshade ARGS` in `dir`.
pub fn fixshade(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(EXE)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("run fixshade")
}

/// Owned workspace memory: room for `verts` prepared vertices (of any
/// layout: 8 values each) and `tris` triangles.
pub fn mem<L: Copy + Default>(verts: usize, tris: usize) -> OwnedWorkspace<L> {
    OwnedWorkspace::new(verts, verts * 8, tris, tris)
}

/// A rendered core frame: colours, and coverage read back from the depth
/// buffer (a pixel is covered when its depth is no longer the clear value).
#[derive(Clone, Debug, PartialEq)]
pub struct CoreFrame {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<[u8; 3]>,
    pub covered: Vec<bool>,
    pub stats: RenderStats,
}

impl CoreFrame {
    pub fn covered_count(&self) -> usize {
        self.covered.iter().filter(|&&c| c).count()
    }

    pub fn at(&self, x: u32, y: u32) -> [u8; 3] {
        self.rgb[(y * self.width + x) as usize]
    }
}

/// Prepares and renders `scene` into a whole `w × h` RGB888 frame with a
/// 32-bit depth buffer.
pub fn render_full<P: Profile>(
    scene: &Scene<'_, '_, P::Real>,
    w: u32,
    h: u32,
) -> Result<CoreFrame, RenderError> {
    let mut mem = mem::<P::Lerp>(20_000, 20_000);
    let frame = prepare::<P>(scene, w, h, mem.ws())?;
    let n = (w * h) as usize;
    let mut px = vec![[0u8; 3]; n];
    let mut z = vec![0u32; n];
    let stats = {
        let mut fb = FrameBuf::<Rgb888>::new(&mut px, w, h)?;
        fb.clear(scene.background);
        let mut db = DepthBuffer::<Depth32>::new(&mut z, w, 0, h)?;
        frame.render(scene, &mut fb, Some(&mut db))?
    };
    Ok(CoreFrame {
        width: w,
        height: h,
        rgb: px,
        covered: z.iter().map(|&d| d != u32::MAX).collect(),
        stats,
    })
}

/// As [`render_full`], band by band through `Frame::render_bands`; returns
/// the concatenated RGB888 bytes of the bands.
pub fn render_banded<P: Profile>(
    scene: &Scene<'_, '_, P::Real>,
    w: u32,
    h: u32,
    rows: u32,
) -> Result<Vec<[u8; 3]>, RenderError> {
    let mut mem = mem::<P::Lerp>(20_000, 20_000);
    let frame = prepare::<P>(scene, w, h, mem.ws())?;
    let mut px = vec![[0u8; 3]; (w * rows) as usize];
    let mut z = vec![0u32; (w * rows) as usize];
    let mut out = Vec::with_capacity((w * h) as usize);
    let mut band = BandBuf::<Rgb888, Depth32>::with_depth(&mut px, Some(&mut z), w, rows)?;
    let mut order = vec![0u16; 2 * frame.triangle_count()];
    let mut pool = Box::new(Pool::<P::Lerp, 512, 8>::new());
    let mut state = BandState::new(&mut order, &mut pool);
    let stats = frame.render_bands(scene, &mut state, &mut band, |b| {
        out.extend_from_slice(b.pixels());
        Ok::<(), RenderError>(())
    })?;
    // Every prepared triangle set up once (the pool holds them all).
    assert_eq!(stats.triangles as usize, frame.triangle_count());
    Ok(out)
}

/// A target without a fast path that counts the writes per pixel and
/// panics on a write outside its window (the rasterizer promises none).
pub struct Counter {
    pub w: u32,
    pub y0: u32,
    pub y1: u32,
    pub count: Vec<u32>,
    pub last: Vec<u8>,
}

impl Counter {
    pub fn new(w: u32, h: u32) -> Self {
        Self::band(w, 0, h)
    }

    pub fn band(w: u32, y0: u32, y1: u32) -> Self {
        let n = (w * (y1 - y0)) as usize;
        Self {
            w,
            y0,
            y1,
            count: vec![0; n],
            last: vec![0; n],
        }
    }

    pub fn get(&self, x: u32, y: u32) -> u32 {
        self.count[((y - self.y0) * self.w + x) as usize]
    }

    pub fn total(&self) -> u64 {
        self.count.iter().map(|&c| c as u64).sum()
    }
}

impl Target for Counter {
    type Format = Gray8;
    fn window(&self) -> Window {
        Window {
            width: self.w,
            y0: self.y0,
            y1: self.y1,
        }
    }
    fn write_pixel(&mut self, x: u32, y: u32, p: [u8; 1]) {
        assert!(
            x < self.w && y >= self.y0 && y < self.y1,
            "write outside the window at ({x}, {y})"
        );
        let i = ((y - self.y0) * self.w + x) as usize;
        self.count[i] += 1;
        self.last[i] = p[0];
    }
}

/// Exact integer coverage of a pixel centre by a subpixel triangle (edge
/// functions in i128, top-left rule, y down, either winding): the
/// independent reference of the rasterizer's coverage rule.
pub fn covers(tri: &[(i64, i64); 3], px: i64, py: i64, s: i64) -> bool {
    let (a, mut b, mut c) = (tri[0], tri[1], tri[2]);
    let e = |a: (i64, i64), b: (i64, i64), p: (i64, i64)| {
        (b.0 - a.0) as i128 * (p.1 - a.1) as i128 - (b.1 - a.1) as i128 * (p.0 - a.0) as i128
    };
    let area = e(a, b, c);
    if area == 0 {
        return false;
    }
    if area < 0 {
        core::mem::swap(&mut b, &mut c);
    }
    let p = (px * s + s / 2, py * s + s / 2);
    [(a, b), (b, c), (c, a)].iter().all(|&(p0, p1)| {
        let v = e(p0, p1, p);
        let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
        v > 0 || (v == 0 && (dy < 0 || (dy == 0 && dx > 0)))
    })
}

/// Level of a grey Gray8-encoded colour.
pub fn grey(c: Rgb8) -> u8 {
    Gray8::encode(c)[0]
}

// ---------------------------------------------------------------------
// One scene description for the core (any profile) and the ideal.

/// A light in world space.
#[derive(Clone, Copy, Debug)]
pub enum LightSpec {
    Point([f64; 3]),
    Directional([f64; 3]),
}

/// One object: a mesh placed by `from_parts(scale, angles, translation)`.
#[derive(Clone, Copy, Debug)]
pub struct ObjSpec<'m> {
    pub mesh: Mesh<'m>,
    pub scale: f64,
    pub angles: [f64; 3],
    pub translation: [f64; 3],
    pub color: [f64; 3],
    pub ka: f64,
    pub kd: f64,
    pub ks: f64,
    pub shininess: f64,
    pub shading: Shading,
    pub cull: bool,
}

impl<'m> ObjSpec<'m> {
    /// A white, diffuse object at the origin.
    pub fn new(mesh: Mesh<'m>, shading: Shading) -> Self {
        Self {
            mesh,
            scale: 1.0,
            angles: [0.0; 3],
            translation: [0.0; 3],
            color: [1.0; 3],
            ka: 0.2,
            kd: 0.8,
            ks: 0.0,
            shininess: 1.0,
            shading,
            cull: false,
        }
    }
}

/// A whole scene.
#[derive(Clone, Debug)]
pub struct Spec<'m> {
    pub width: u32,
    pub height: u32,
    pub eye: [f64; 3],
    pub target: [f64; 3],
    pub fov_deg: f64,
    pub near: f64,
    pub far: Option<f64>,
    pub ambient: f64,
    pub specular: Specular,
    pub lights: Vec<(LightSpec, f64, [f64; 3])>,
    pub objects: Vec<ObjSpec<'m>>,
}

impl<'m> Spec<'m> {
    pub fn new(width: u32, height: u32, eye: [f64; 3]) -> Self {
        Self {
            width,
            height,
            eye,
            target: [0.0; 3],
            fov_deg: 60.0,
            near: 0.5,
            far: None,
            ambient: 1.0,
            specular: Specular::Phong,
            lights: vec![],
            objects: vec![],
        }
    }

    /// The core camera, lights and objects for profile scalar `R`.
    pub fn core<R: Real>(&self) -> (Camera<R>, Vec<Light<R>>, Vec<Object<'m, R>>) {
        let f = |v: [f64; 3]| v.map(|c| c as f32);
        let camera = Camera::look_at_f32(
            f(self.eye),
            f(self.target),
            [0.0, 1.0, 0.0],
            self.fov_deg as f32,
            self.near as f32,
            self.far.map(|v| v as f32),
        )
        .expect("valid camera");
        let v = |a: [f64; 3]| Vec3::new(R::from_f64(a[0]), R::from_f64(a[1]), R::from_f64(a[2]));
        let lights = self
            .lights
            .iter()
            .map(|&(kind, intensity, color)| Light {
                kind: match kind {
                    LightSpec::Point(p) => LightKind::Point(v(p)),
                    LightSpec::Directional(d) => LightKind::Directional(v(d)),
                },
                intensity: R::from_f64(intensity),
                color: v(color),
            })
            .collect();
        let objects = self
            .objects
            .iter()
            .map(|o| Object {
                mesh: o.mesh,
                transform: Affine::from_parts(R::from_f64(o.scale), v(o.angles), v(o.translation)),
                material: Material {
                    color: v(o.color),
                    ka: R::from_f64(o.ka),
                    kd: R::from_f64(o.kd),
                    ks: R::from_f64(o.ks),
                    shininess: R::from_f64(o.shininess),
                },
                shading: o.shading,
                cull_backfaces: o.cull,
            })
            .collect();
        (camera, lights, objects)
    }

    /// Renders with profile `P` (whole frame, 32-bit depth).
    pub fn render<P: Profile>(&self) -> Result<CoreFrame, RenderError> {
        let (camera, lights, objects) = self.core::<P::Real>();
        let scene = self.scene(camera, &lights, &objects);
        render_full::<P>(&scene, self.width, self.height)
    }

    /// Renders with each of the eight profiles, named.
    pub fn render_every_profile(&self) -> Result<Vec<(&'static str, CoreFrame)>, RenderError> {
        use fixshade::num::{F32Pc, F64Pc, Fast, FastPc, Precise, PrecisePc, F32, F64};
        Ok(vec![
            (F64::NAME, self.render::<F64>()?),
            (F64Pc::NAME, self.render::<F64Pc>()?),
            (F32::NAME, self.render::<F32>()?),
            (F32Pc::NAME, self.render::<F32Pc>()?),
            (Precise::NAME, self.render::<Precise>()?),
            (PrecisePc::NAME, self.render::<PrecisePc>()?),
            (Fast::NAME, self.render::<Fast>()?),
            (FastPc::NAME, self.render::<FastPc>()?),
        ])
    }

    /// Renders with profile `P` band by band.
    pub fn render_banded<P: Profile>(&self, rows: u32) -> Result<Vec<[u8; 3]>, RenderError> {
        let (camera, lights, objects) = self.core::<P::Real>();
        let scene = self.scene(camera, &lights, &objects);
        render_banded::<P>(&scene, self.width, self.height, rows)
    }

    pub fn scene<'s, R: Real>(
        &self,
        camera: Camera<R>,
        lights: &'s [Light<R>],
        objects: &'s [Object<'m, R>],
    ) -> Scene<'s, 'm, R> {
        Scene {
            camera,
            objects,
            lights,
            ambient: R::from_f64(self.ambient),
            specular: self.specular,
            viewer: Viewer::Local,
            background: Rgb8::new(1, 2, 3),
        }
    }

    /// The same scene for the ideal reference: mesh positions and normals
    /// transformed in f64 (`from_parts`: scale, rotate about X, Y, Z, then
    /// translate).
    pub fn ideal(&self) -> IdealScene {
        let objects = self
            .objects
            .iter()
            .map(|o| {
                let rot = rotation(o.angles);
                let apply = |m: &[[f64; 3]; 3], p: [f64; 3]| {
                    [0, 1, 2].map(|r| m[r][0] * p[0] + m[r][1] * p[1] + m[r][2] * p[2])
                };
                let mesh = o.mesh;
                let triangles = (0..mesh.triangle_count())
                    .map(|t| {
                        let pos = mesh.triangle_positions(t).unwrap();
                        [0, 1, 2].map(|c| {
                            let p = apply(&rot, pos[c].map(|q| q as f64 / 16384.0));
                            let n = mesh
                                .corner_normal(t, c)
                                .map(|n| apply(&rot, n.map(|q| q as f64 / 16384.0)))
                                .unwrap_or([0.0; 3]);
                            ideal::Vertex {
                                position: [0, 1, 2].map(|k| p[k] * o.scale + o.translation[k]),
                                normal: n,
                            }
                        })
                    })
                    .collect();
                ideal::Object {
                    triangles,
                    shading: match o.shading {
                        Shading::Flat => ideal::Shading::Flat,
                        Shading::Gouraud => ideal::Shading::Gouraud,
                        Shading::Phong => ideal::Shading::Phong,
                    },
                    material: ideal::Material {
                        color: o.color,
                        ka: o.ka,
                        kd: o.kd,
                        ks: o.ks,
                        shininess: o.shininess,
                    },
                    cull_backfaces: o.cull,
                }
            })
            .collect();
        IdealScene {
            width: self.width,
            height: self.height,
            background: [1.0 / 255.0, 2.0 / 255.0, 3.0 / 255.0],
            camera: ideal::Camera {
                eye: self.eye,
                target: self.target,
                up: [0.0, 1.0, 0.0],
                fov_y_deg: self.fov_deg,
                near: self.near,
                far: self.far,
            },
            ambient: self.ambient,
            specular: match self.specular {
                Specular::Phong => ideal::SpecularModel::Phong,
                Specular::Blinn => ideal::SpecularModel::Blinn,
            },
            lights: self
                .lights
                .iter()
                .map(|&(kind, intensity, color)| ideal::Light {
                    kind: match kind {
                        LightSpec::Point(p) => ideal::LightKind::Point { position: p },
                        LightSpec::Directional(d) => ideal::LightKind::Directional { direction: d },
                    },
                    intensity,
                    color,
                })
                .collect(),
            objects,
        }
    }

    /// The ideal frame: 8-bit colours and coverage.
    pub fn render_ideal(&self) -> (Vec<[u8; 3]>, Vec<bool>) {
        let f = ideal::render(&self.ideal()).expect("valid ideal scene");
        (f.to_rgb8(), f.covered)
    }
}

/// `Rz · Ry · Rx` as in `Affine::from_parts`.
pub fn rotation(a: [f64; 3]) -> [[f64; 3]; 3] {
    let (sx, cx) = a[0].sin_cos();
    let (sy, cy) = a[1].sin_cos();
    let (sz, cz) = a[2].sin_cos();
    let rx = [[1.0, 0.0, 0.0], [0.0, cx, -sx], [0.0, sx, cx]];
    let ry = [[cy, 0.0, sy], [0.0, 1.0, 0.0], [-sy, 0.0, cy]];
    let rz = [[cz, -sz, 0.0], [sz, cz, 0.0], [0.0, 0.0, 1.0]];
    mat_mul(&mat_mul(&rz, &ry), &rx)
}

fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    let mut m = [[0.0; 3]; 3];
    for (r, row) in m.iter_mut().enumerate() {
        for (c, v) in row.iter_mut().enumerate() {
            *v = (0..3).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    m
}

/// Largest channel difference between two frames over the pixels covered
/// in both, and how many such pixels there are.
pub fn max_diff_covered(a: &[[u8; 3]], ca: &[bool], b: &[[u8; 3]], cb: &[bool]) -> (u8, usize) {
    let mut worst = 0;
    let mut n = 0;
    for i in 0..a.len() {
        if ca[i] && cb[i] {
            n += 1;
            for k in 0..3 {
                worst = worst.max(a[i][k].abs_diff(b[i][k]));
            }
        }
    }
    (worst, n)
}

/// Whether `e` is a scene error (for readable asserts).
pub fn is_scene_error(e: &RenderError, want: SceneError) -> bool {
    *e == RenderError::Scene(want)
}

/// A square in z = 0 with corner normals tilted outwards (a curved patch
/// for Phong and Gouraud).
pub const QUAD: [[i16; 3]; 4] = [
    [-16000, -16000, 0],
    [16000, -16000, 0],
    [16000, 16000, 0],
    [-16000, 16000, 0],
];
/// Corner normals 20° off the face normal: the interpolated normal sweeps
/// across a highlight's peak.
pub const TILTED: [[i16; 3]; 4] = [
    [-4000, -4000, 15400],
    [4000, -4000, 15400],
    [4000, 4000, 15400],
    [-4000, 4000, 15400],
];
/// Every corner normal along the face normal (+z).
pub static FLAT_UP: [[i16; 3]; 4] = [[0, 0, 16384]; 4];
/// [`QUAD`]'s two triangles.
pub const QUAD_TRIS: [[u16; 3]; 2] = [[0, 1, 2], [0, 2, 3]];

/// [`QUAD`] with the corner normals `normals`.
pub fn quad(normals: &'static [[i16; 3]; 4]) -> Mesh<'static> {
    Mesh::new(&QUAD, &QUAD_TRIS, Some(normals)).unwrap()
}

/// Eight point lights of intensity 0.3 on a ring of radius 2 at z = 2.5,
/// 45° apart: the many-lights case of the extreme suite.
pub fn ring_of_eight_lights(s: &mut Spec<'_>) {
    for k in 0..8 {
        let a = f64::from(k) * std::f64::consts::PI / 4.0;
        s.lights.push((
            LightSpec::Point([2.0 * a.cos(), 2.0 * a.sin(), 2.5]),
            0.3,
            [1.0; 3],
        ));
    }
}
