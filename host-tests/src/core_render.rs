//! Rendering a scene description with the no_std core, in any profile.
//!
//! The host renders exactly as a firmware does: the frame is prepared once,
//! then rasterized in bands of [`BAND_ROWS`] rows with a band-sized 16-bit
//! depth buffer, so the bytes (and their CRC-32) are the ones a Cortex-M
//! produces with the same profile. Coverage is read from the depth band:
//! a pixel is covered when some fragment passed the depth test there.

use crate::ideal::{LightKind, Shading as IShading, SpecularModel};
use crate::scene_file::{PixelFormat, SceneDesc};
use fixshade::geom::{Affine, Mat3, Vec3};
use fixshade::illum::{Light, LightKind as CLightKind, Material, Specular, Viewer};
use fixshade::num::{F32Pc, F64Pc, Fast, FastPc, Precise, PrecisePc, Profile, Real, F32, F64};
use fixshade::render::{prepare, BandState, Pool, RenderError, Tri, Workspace};
use fixshade::scene::{Camera, Object, Scene, SceneError, Shading};
use fixshade::target::{BandBuf, Gray8, PixelFormat as CorePixelFormat, Rgb565Be, Rgb8, Rgb888};
use std::fmt;

/// Rows per band, as in the firmware.
pub const BAND_ROWS: u32 = 16;

/// The core's numeric profiles, by name.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum CoreProfile {
    /// Q16.16, affine.
    Fast,
    /// Q32.32, affine.
    Precise,
    /// `f32`, affine.
    F32,
    /// `f64`, affine: the float twin of the affine profiles.
    F64,
    /// Q16.16, perspective-correct.
    FastPc,
    /// Q32.32, perspective-correct.
    PrecisePc,
    /// `f32`, perspective-correct.
    F32Pc,
    /// `f64`, perspective-correct: the float twin of the `-pc` profiles.
    F64Pc,
}

impl CoreProfile {
    /// Every profile.
    pub const ALL: [Self; 8] = [
        Self::Fast,
        Self::Precise,
        Self::F32,
        Self::F64,
        Self::FastPc,
        Self::PrecisePc,
        Self::F32Pc,
        Self::F64Pc,
    ];

    /// Its name (`fast`, `precise-pc`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Self::Fast => Fast::NAME,
            Self::Precise => Precise::NAME,
            Self::F32 => F32::NAME,
            Self::F64 => F64::NAME,
            Self::FastPc => FastPc::NAME,
            Self::PrecisePc => PrecisePc::NAME,
            Self::F32Pc => F32Pc::NAME,
            Self::F64Pc => F64Pc::NAME,
        }
    }

    /// The profile called `name`.
    pub fn parse(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The float twin that isolates this profile's quantization error.
    pub fn twin(self) -> Self {
        if self.perspective() {
            Self::F64Pc
        } else {
            Self::F64
        }
    }

    /// Whether it interpolates perspective-correctly.
    pub fn perspective(self) -> bool {
        matches!(
            self,
            Self::FastPc | Self::PrecisePc | Self::F32Pc | Self::F64Pc
        )
    }

    /// Whether it is fixed point.
    pub fn is_fixed(self) -> bool {
        matches!(
            self,
            Self::Fast | Self::Precise | Self::FastPc | Self::PrecisePc
        )
    }
}

impl From<crate::scene_file::Profile> for CoreProfile {
    fn from(p: crate::scene_file::Profile) -> Self {
        use crate::scene_file::Profile as P;
        match p {
            P::Fast => Self::Fast,
            P::Precise => Self::Precise,
            P::F32 => Self::F32,
            P::F64 => Self::F64,
        }
    }
}

/// A frame rendered by the core.
#[derive(Clone, Debug, PartialEq)]
pub struct CoreFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The frame as 8-bit RGB (decoded from the pixel format).
    pub rgb: Vec<[u8; 3]>,
    /// Pixels some fragment was drawn at.
    pub covered: Vec<bool>,
    /// The frame buffer's bytes in the scene's pixel format (RGB565
    /// big-endian), row-major.
    pub bytes: Vec<u8>,
    /// Prepared vertices.
    pub vertices: usize,
    /// Prepared triangles.
    pub triangles: usize,
    /// Bytes of the prepared frame (without scratch).
    pub prepared_bytes: usize,
    /// Pixels written (depth-test passes).
    pub pixels_drawn: u32,
}

/// Why the core could not render a scene.
#[derive(Debug)]
pub enum CoreError {
    /// The scene does not convert (a camera the core refuses).
    Scene(SceneError),
    /// Preparing or rendering failed.
    Render(RenderError),
}

impl fmt::Display for CoreError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Scene(e) => write!(f, "{e}"),
            Self::Render(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for CoreError {}

impl From<RenderError> for CoreError {
    fn from(e: RenderError) -> Self {
        Self::Render(e)
    }
}

impl From<SceneError> for CoreError {
    fn from(e: SceneError) -> Self {
        Self::Scene(e)
    }
}

fn v3<R: Real>(v: [f64; 3]) -> Vec3<R> {
    Vec3::new(R::from_f64(v[0]), R::from_f64(v[1]), R::from_f64(v[2]))
}

/// The core's model transform of `t`: `Affine::from_parts` for a uniform
/// scale (as the firmware builds it), else the rotation of
/// `Affine::from_parts` with unit scale times `diag(sx, sy, sz)`, so that
/// `m = R · S` as in the scene file's [`Transform`](crate::scene_file::Transform).
pub fn model_transform<R: Real>(t: &crate::scene_file::Transform) -> Affine<R> {
    let angles = v3(t.rotation_rad);
    let translation = v3(t.translation);
    if t.is_uniform() {
        return Affine::from_parts(R::from_f64(t.scale[0]), angles, translation);
    }
    let rotation = Affine::from_parts(R::ONE, angles, translation);
    let [sx, sy, sz] = t.scale.map(R::from_f64);
    let z = R::ZERO;
    let scale = Mat3::from_rows([[sx, z, z], [z, sy, z], [z, z, sz]]);
    Affine {
        m: rotation.m.compose(&scale),
        t: translation,
    }
}

/// The arguments of the core's [`Camera::look_at`] for a scene, as
/// [`CoreScene::new`] converts them (the generated firmware scenes hold
/// exactly these values).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraInputs<R> {
    /// Eye position.
    pub eye: Vec3<R>,
    /// The point looked at.
    pub target: Vec3<R>,
    /// Up direction.
    pub up: Vec3<R>,
    /// Vertical field of view in radians.
    pub fov_y: R,
    /// Near plane distance.
    pub near: R,
    /// Far plane distance, if any.
    pub far: Option<R>,
}

/// An object's model transform as [`Affine::from_parts`] takes it: for a
/// uniformly scaled object it is the transform [`CoreScene`] gives it (the
/// firmware's scenes store these three values per object).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectParts<R> {
    /// The scale (the first component of the scene file's scale).
    pub scale: R,
    /// Rotation angles in radians about x, y, z.
    pub rotation: Vec3<R>,
    /// Translation.
    pub translation: Vec3<R>,
}

/// A scene description converted to the core's types for scalar `R`
/// (values through `R::from_f64`, exactly as the firmware's generated
/// constants): it owns the objects and lights a [`Scene`] borrows. The
/// one conversion from a scene file to the core's types (the renderers,
/// the timings and the firmware scene generator all use it).
#[derive(Debug)]
pub struct CoreScene<'d, R> {
    camera_in: CameraInputs<R>,
    camera: Camera<R>,
    parts: Vec<ObjectParts<R>>,
    objects: Vec<Object<'d, R>>,
    lights: Vec<Light<R>>,
    ambient: R,
    specular: Specular,
    background: Rgb8,
}

impl<'d, R: Real> CoreScene<'d, R> {
    /// Converts `desc`.
    ///
    /// # Errors
    /// [`CoreError::Scene`] for a camera the core refuses.
    pub fn new(desc: &'d SceneDesc) -> Result<Self, CoreError> {
        let c = &desc.camera;
        let camera_in = CameraInputs {
            eye: v3(c.eye),
            target: v3(c.target),
            up: v3(c.up),
            fov_y: R::from_f64(c.fov_y_deg.to_radians()),
            near: R::from_f64(c.near),
            far: c.far.map(R::from_f64),
        };
        let camera = Camera::look_at(
            camera_in.eye,
            camera_in.target,
            camera_in.up,
            camera_in.fov_y,
            camera_in.near,
            camera_in.far,
        )?;
        let parts = desc
            .objects
            .iter()
            .map(|o| ObjectParts {
                scale: R::from_f64(o.transform.scale[0]),
                rotation: v3(o.transform.rotation_rad),
                translation: v3(o.transform.translation),
            })
            .collect();
        let objects = desc
            .objects
            .iter()
            .map(|o| Object {
                mesh: o.mesh.mesh(),
                transform: model_transform(&o.transform),
                material: Material {
                    color: v3(o.material.color),
                    ka: R::from_f64(o.material.ka),
                    kd: R::from_f64(o.material.kd),
                    ks: R::from_f64(o.material.ks),
                    shininess: R::from_f64(o.material.shininess),
                },
                shading: match o.shading {
                    IShading::Flat => Shading::Flat,
                    IShading::Gouraud => Shading::Gouraud,
                    IShading::Phong => Shading::Phong,
                },
                cull_backfaces: o.cull_backfaces,
            })
            .collect();
        let lights = desc
            .lights
            .iter()
            .map(|l| Light {
                kind: match l.kind {
                    LightKind::Point { position } => CLightKind::Point(v3(position)),
                    LightKind::Directional { direction } => CLightKind::Directional(v3(direction)),
                },
                intensity: R::from_f64(l.intensity),
                color: v3(l.color),
            })
            .collect();
        let [r, g, b] = desc.background;
        Ok(Self {
            camera_in,
            camera,
            parts,
            objects,
            lights,
            ambient: R::from_f64(desc.ambient),
            specular: match desc.specular {
                SpecularModel::Phong => Specular::Phong,
                SpecularModel::Blinn => Specular::Blinn,
            },
            background: Rgb8::new(r, g, b),
        })
    }

    /// The camera's inputs.
    pub fn camera_inputs(&self) -> CameraInputs<R> {
        self.camera_in
    }

    /// Per object, its transform's parts (see [`ObjectParts`]).
    pub fn object_parts(&self) -> &[ObjectParts<R>] {
        &self.parts
    }

    /// The scene, borrowing the objects and lights.
    pub fn scene(&self) -> Scene<'_, 'd, R> {
        Scene {
            camera: self.camera,
            objects: &self.objects,
            lights: &self.lights,
            ambient: self.ambient,
            specular: self.specular,
            viewer: Viewer::Local,
            background: self.background,
        }
    }

    /// Workspace that always suffices: (vertices, triangles). Every mesh
    /// vertex makes a prepared vertex, and clipping and two-sided back
    /// faces add at most 14 vertices and 7 triangles per triangle; values
    /// are 8 per vertex at most.
    pub fn workspace_sizes(&self) -> (usize, usize) {
        let tris: usize = self.objects.iter().map(|o| o.mesh.triangle_count()).sum();
        let mesh_verts: usize = self.objects.iter().map(|o| o.mesh.vertex_count()).sum();
        let verts = (mesh_verts + tris * 14).min(u16::MAX as usize - 1);
        (verts, tris * 8)
    }
}

/// Renders `desc` with `profile` (the scene's own when `None`).
///
/// # Errors
/// [`CoreError`] when the core refuses the camera or the workspace (sized
/// from the scene's meshes) does not suffice.
pub fn render_core(desc: &SceneDesc, profile: Option<CoreProfile>) -> Result<CoreFrame, CoreError> {
    render_core_rows(desc, profile, BAND_ROWS)
}

/// Renders `desc` with `profile` in bands of `rows` rows (at least 1).
///
/// # Errors
/// As [`render_core`].
pub fn render_core_rows(
    desc: &SceneDesc,
    profile: Option<CoreProfile>,
    rows: u32,
) -> Result<CoreFrame, CoreError> {
    let profile = profile.unwrap_or_else(|| desc.profile.into());
    dispatch_fn!(profile, desc.pixel_format, render_format(desc: &SceneDesc, rows: u32) -> Result<CoreFrame, CoreError>)
}

/// Work generic over a profile and a pixel format, both chosen at run
/// time by [`dispatch`].
pub trait ProfileJob {
    /// What the work gives.
    type Output;
    /// Does the work with profile `P` and pixel format `F`.
    fn run<P: Profile, F: CorePixelFormat>(self) -> Self::Output;
}

/// `$fun::<P, F>(args..)` for the profile `$profile` and the pixel format
/// `$format` named at run time: a [`ProfileJob`] holding the arguments
/// (their types as written, elided lifetimes allowed), run by [`dispatch`].
macro_rules! dispatch_fn {
    ($profile:expr, $format:expr, $fun:ident($($arg:ident: $ty:ty),* $(,)?) -> $out:ty) => {{
        struct Job<A>(A);
        impl $crate::core_render::ProfileJob for Job<($($ty,)*)> {
            type Output = $out;
            fn run<P: fixshade::num::Profile, F: fixshade::target::PixelFormat>(self) -> $out {
                let ($($arg,)*) = self.0;
                $fun::<P, F>($($arg),*)
            }
        }
        $crate::core_render::dispatch($profile, $format, Job(($($arg,)*)))
    }};
}
pub(crate) use dispatch_fn;

/// Runs `job` with the profile and the pixel format named at run time.
pub fn dispatch<J: ProfileJob>(profile: CoreProfile, format: PixelFormat, job: J) -> J::Output {
    fn with_format<P: Profile, J: ProfileJob>(format: PixelFormat, job: J) -> J::Output {
        match format {
            PixelFormat::Gray8 => job.run::<P, Gray8>(),
            PixelFormat::Rgb565 => job.run::<P, Rgb565Be>(),
            PixelFormat::Rgb888 => job.run::<P, Rgb888>(),
        }
    }
    match profile {
        CoreProfile::Fast => with_format::<Fast, J>(format, job),
        CoreProfile::Precise => with_format::<Precise, J>(format, job),
        CoreProfile::F32 => with_format::<F32, J>(format, job),
        CoreProfile::F64 => with_format::<F64, J>(format, job),
        CoreProfile::FastPc => with_format::<FastPc, J>(format, job),
        CoreProfile::PrecisePc => with_format::<PrecisePc, J>(format, job),
        CoreProfile::F32Pc => with_format::<F32Pc, J>(format, job),
        CoreProfile::F64Pc => with_format::<F64Pc, J>(format, job),
    }
}

/// What one frame prepared and drew.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FrameStats {
    /// Prepared vertices.
    pub vertices: usize,
    /// Prepared triangles.
    pub triangles: usize,
    /// Bytes of the prepared frame (without scratch).
    pub prepared_bytes: usize,
    /// Pixels written (depth-test passes).
    pub pixels: u32,
}

/// A workspace on the heap, of lengths chosen at run time (the core's
/// `Storage` takes them as const generics).
#[derive(Debug)]
pub struct OwnedWorkspace<L> {
    xy: Vec<fixshade::render::ScreenXy>,
    vals: Vec<L>,
    tris: Vec<Tri>,
    colors: Vec<fixshade::target::Rgb8>,
    faces: Vec<u8>,
}

impl<L: Copy + Default> OwnedWorkspace<L> {
    /// Room for `vertices` prepared vertices, `values` values, `made`
    /// made triangles and `triangles` triangle numbers (a face byte and a
    /// flat colour each).
    pub fn new(vertices: usize, values: usize, made: usize, triangles: usize) -> Self {
        Self {
            xy: vec![fixshade::render::ScreenXy::ZERO; vertices],
            vals: vec![L::default(); values],
            tris: vec![Tri::default(); made],
            colors: vec![fixshade::target::Rgb8::BLACK; triangles],
            faces: vec![0; triangles],
        }
    }

    /// The workspace over these vectors.
    pub fn ws(&mut self) -> Workspace<'_, L> {
        Workspace {
            xy: &mut self.xy,
            vals: &mut self.vals,
            tris: &mut self.tris,
            colors: &mut self.colors,
            faces: &mut self.faces,
        }
    }
}

/// Active triangles the host renderer keeps from band to band (every
/// layout: 8 values a slot); more at a band border are set up afresh.
const POOL: usize = 512;

/// The memory for rendering one scene again and again, as a firmware
/// does: the workspace (sized by [`CoreScene::workspace_sizes`]), a colour
/// band and a 16-bit depth band, allocated once.
#[derive(Debug)]
pub struct Renderer<P: Profile, F: CorePixelFormat> {
    ws: OwnedWorkspace<P::Lerp>,
    band: Vec<F::Raw>,
    depth: Vec<u16>,
    order: Vec<u16>,
    pool: Box<Pool<P::Lerp, POOL, 8>>,
    width: u32,
    height: u32,
    rows: u32,
}

impl<P: Profile, F: CorePixelFormat> Renderer<P, F> {
    /// Memory for `cs` on a `width × height` screen in bands of `rows`.
    pub fn new(cs: &CoreScene<'_, P::Real>, width: u32, height: u32, rows: u32) -> Self {
        let (verts, tris) = cs.workspace_sizes();
        let rows = rows.max(1);
        let band_len = (width * rows.min(height.max(1))) as usize;
        Self {
            ws: OwnedWorkspace::new(verts, verts * 8, tris, tris),
            band: vec![F::Raw::default(); band_len],
            depth: vec![0; band_len],
            order: vec![0; 2 * tris],
            pool: Box::new(Pool::new()),
            width,
            height,
            rows,
        }
    }

    /// Prepares `scene` and renders it band by band (each band cleared to
    /// the background, its depth band cleared), handing every finished
    /// band and its depth band to `band`.
    ///
    /// # Errors
    /// [`CoreError::Render`] when the core refuses the frame.
    pub fn frame(
        &mut self,
        scene: &Scene<'_, '_, P::Real>,
        mut band: impl FnMut(&BandBuf<'_, F>),
    ) -> Result<FrameStats, CoreError> {
        let (w, h) = (self.width, self.height);
        let frame = prepare::<P>(scene, w, h, self.ws.ws())?;
        let mut stats = FrameStats {
            vertices: frame.vertex_count(),
            triangles: frame.triangle_count(),
            prepared_bytes: frame.bytes_used(),
            pixels: 0,
        };
        let mut buf = BandBuf::<F>::new(&mut self.band, Some(&mut self.depth), w, self.rows)
            .map_err(RenderError::from)?;
        let mut state = BandState::new(&mut self.order, &mut self.pool);
        let drawn = frame.render_bands(scene, &mut state, &mut buf, |b| {
            band(b);
            Ok::<(), RenderError>(())
        })?;
        stats.pixels = drawn.pixels;
        Ok(stats)
    }
}

fn render_format<P: Profile, F: CorePixelFormat>(
    desc: &SceneDesc,
    rows: u32,
) -> Result<CoreFrame, CoreError> {
    let cs = CoreScene::<P::Real>::new(desc)?;
    let (w, h) = (desc.width, desc.height);
    let mut r = Renderer::<P, F>::new(&cs, w, h, rows);
    let n = (w * h) as usize;
    let (mut rgb, mut covered, mut bytes) = (
        Vec::with_capacity(n),
        Vec::with_capacity(n),
        Vec::with_capacity(n * F::BYTES),
    );
    let stats = r.frame(&cs.scene(), |b| {
        bytes.extend(b.bytes());
        rgb.extend(b.pixels().iter().map(|&p| {
            let c = F::decode(p);
            [c.r, c.g, c.b]
        }));
        covered.extend(b.depth().unwrap_or(&[]).iter().map(|&d| d != u16::MAX));
    })?;
    Ok(CoreFrame {
        width: w,
        height: h,
        rgb,
        covered,
        bytes,
        vertices: stats.vertices,
        triangles: stats.triangles,
        prepared_bytes: stats.prepared_bytes,
        pixels_drawn: stats.pixels,
    })
}

/// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320: `CRC_32_ISO_HDLC`,
/// the checksum of zlib and of the firmware's `crc` crate) by `crc32fast`.
pub fn crc32(bytes: &[u8]) -> u32 {
    crc32fast::hash(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crc32_of_known_strings() {
        assert_eq!(crc32(b""), 0);
        assert_eq!(crc32(b"123456789"), 0xcbf4_3926);
        assert_eq!(
            crc32(b"The quick brown fox jumps over the lazy dog"),
            0x414f_a339
        );
    }

    #[test]
    fn profiles_parse_by_name_and_have_twins() {
        for p in CoreProfile::ALL {
            assert_eq!(CoreProfile::parse(p.name()), Some(p));
            assert_eq!(p.twin().perspective(), p.perspective());
        }
        assert_eq!(CoreProfile::parse("fast-pc"), Some(CoreProfile::FastPc));
        assert_eq!(CoreProfile::parse("slow"), None);
    }
}
