//! The firmware's scenes in any core profile, for the per-profile
//! measurements (`fixshade_firmware` built with a `profile-*` feature) and
//! their host check.
//!
//! The scene data is Q16 ([`crate::SCENES`]); a profile with another
//! scalar gets every value *widened* exactly from its Q16 bits
//! ([`widen`]: `Q32` and `f64` hold every Q16 value exactly; `f32` holds
//! those below 2^8 in magnitude exactly, all the scene values are). So a
//! `precise` or `f32` frame here renders the Q16-rounded scene, the same
//! inputs on the host (`host-check --profile NAME`) and on both targets,
//! and their CRCs must agree. The frame loop is [`crate::render_frame`]'s,
//! generic over the profile: geometry (scene, camera, `prepare::<P>`) then
//! bands of [`BAND_ROWS`] rows, RGB565 big-endian, 16-bit depth band.

use crate::{
    Crc32, FrameError, FrameStats, ObjectSpec, Pixel, Probe, SceneSpec, BAND_ROWS, POOL_SLOTS,
    POOL_VALUES, QUAD_SLOTS, SCENE_LIGHTS, SCENE_OBJECTS,
};
use fixshade::geom::{Affine, Vec3};
use fixshade::illum::{Light, LightKind, Material};
use fixshade::num::{Profile, Real, Q16};
use fixshade::render::{prepare, BandState, Frame, Pool, Workspace};
use fixshade::scene::{Camera, Object, Scene, SceneError};
use fixshade::target::{BandBuf, BufferError, Depth16, DepthFormat, Rgb565Be};

/// A Q16 value in the scalar `R`, from its bits: exact for `Q16`, `Q32`
/// and `f64`; for `f32`, exact below 2^8 in magnitude (24 significant
/// bits), else rounded to nearest (relative error at most 2^-24).
#[inline]
pub fn widen<R: Real>(q: Q16) -> R {
    R::from_fixed_i32(q.to_bits(), 16)
}

fn widen3<R: Real>(v: Vec3<Q16>) -> Vec3<R> {
    Vec3::new(widen(v.x), widen(v.y), widen(v.z))
}

fn object<R: Real>(o: &ObjectSpec) -> Object<'static, R> {
    let m = o.material;
    Object {
        mesh: o.mesh,
        transform: Affine::from_parts(widen(o.scale), widen3(o.rotation), widen3(o.translation)),
        material: Material {
            color: widen3(m.color),
            ka: widen(m.ka),
            kd: widen(m.kd),
            ks: widen(m.ks),
            shininess: widen(m.shininess),
        },
        shading: o.shading,
        cull_backfaces: o.cull_backfaces,
    }
}

fn light<R: Real>(l: &Light<Q16>) -> Light<R> {
    Light {
        kind: match l.kind {
            LightKind::Point(p) => LightKind::Point(widen3(p)),
            LightKind::Directional(d) => LightKind::Directional(widen3(d)),
        },
        intensity: widen(l.intensity),
        color: widen3(l.color),
    }
}

/// The parts of a scene in the scalar `R` that the core's `Scene` borrows.
pub(crate) struct Parts<R: Real> {
    pub(crate) camera: Result<Camera<R>, SceneError>,
    objects: heapless::Vec<Object<'static, R>, SCENE_OBJECTS>,
    lights: heapless::Vec<Light<R>, SCENE_LIGHTS>,
}

impl<R: Real> Parts<R> {
    // Not inlined: the collected object list's temporaries then stay out
    // of the caller's frame (the frame loop's, under the whole render).
    #[inline(never)]
    pub(crate) fn new(spec: &SceneSpec) -> Self {
        Self {
            camera: Camera::look_at(
                widen3(spec.eye),
                widen3(spec.target),
                widen3(spec.up),
                widen(spec.fov_y),
                widen(spec.near),
                spec.far.map(widen),
            ),
            objects: spec.objects.iter().map(object).collect(),
            // (Both sized by the build's scenes: every scene fits.)
            lights: spec.lights.iter().map(light).collect(),
        }
    }

    pub(crate) fn scene<'s>(
        &'s self,
        spec: &SceneSpec,
        camera: Camera<R>,
    ) -> Scene<'s, 'static, R> {
        Scene {
            camera,
            objects: &self.objects,
            lights: &self.lights,
            ambient: widen(spec.ambient),
            specular: spec.specular,
            viewer: fixshade::illum::Viewer::Local,
            background: spec.background,
        }
    }
}

/// A frame with the profile `P` ([`crate::render_frame`] is this with
/// `Fast`): prepares `spec` into `ws`, renders it band by band into
/// `pixels` and `depth` (none for a scene that needs no depth band:
/// [`SceneSpec::depth`]), `probe` around the geometry and around each
/// band.
///
/// # Errors
/// As [`crate::render_frame`].
pub fn render_frame_with<P: Profile, Q: Probe>(
    spec: &SceneSpec,
    ws: Workspace<'_, P::Lerp>,
    pixels: &mut [Pixel],
    depth: Option<&mut [u16]>,
    order: &mut [u16],
    pool: &mut ProfilePool<P>,
    probe: &mut Q,
) -> Result<FrameStats, FrameError> {
    crate::knobs::render_frame_knobs::<P, Depth16, Q>(
        spec, ws, pixels, depth, BAND_ROWS, order, pool, probe,
    )
}

/// The active-triangle pool of the band renderer for profile `P` (the
/// benchmark's capacities, values of `P`'s type).
pub type ProfilePool<P> = Pool<<P as Profile>::Lerp, POOL_SLOTS, POOL_VALUES, QUAD_SLOTS>;

/// A depth band given as an `Option` in the form the `_in` functions
/// take: the slice (empty for `None`) and whether to use it.
#[inline(always)]
pub(crate) fn depth_in<T>(depth: Option<&mut [T]>) -> (&mut [T], bool) {
    let with_depth = depth.is_some();
    (depth.unwrap_or(&mut []), with_depth)
}

/// The raster part of a frame: the band state, then band by band (clear,
/// render) in bands of `rows` rows with the depth format `D` (or no depth
/// band: `with_depth` false; covered pixels are then the fragments drawn,
/// each pixel at most once), each band bracketed by `probe`, its bytes
/// added to the CRC. The depth band is a slice and whether to use it (the
/// firmware passes its static band and the scene's need: the optimiser
/// then sees the static, and its alignment, in the band clears;
/// [`depth_in`] makes the pair from an `Option`).
///
/// # Errors
/// Buffers shorter than a band, or a render error.
// Not inlined: the band loop's locals (band state, shades, kernels) then
// take a stack frame of their own, apart from the geometry's, whose
// deepest calls (the object pass) no longer stack upon them.
#[inline(never)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn raster_bands_in<P: Profile, D: DepthFormat, Q: Probe>(
    frame: &Frame<'_, P>,
    scene: &Scene<'_, '_, P::Real>,
    pixels: &mut [Pixel],
    depth: &mut [D::Raw],
    with_depth: bool,
    rows: u32,
    order: &mut [u16],
    pool: &mut ProfilePool<P>,
    probe: &mut Q,
) -> Result<FrameStats, FrameError> {
    let depth = with_depth.then_some(depth);
    let mut stats = FrameStats {
        vertices: frame.vertex_count() as u32,
        triangles: frame.triangle_count() as u32,
        prepared_bytes: frame.bytes_used() as u32,
        ..FrameStats::default()
    };
    let w = frame.size().0;
    let mut crc = Crc32::new();
    let n = (w * rows) as usize;
    let short = |actual| BufferError::WrongLength {
        expected: n,
        actual,
    };
    let plen = pixels.len();
    let px = pixels.get_mut(..n).ok_or(short(plen))?;
    let z = match depth {
        Some(d) => {
            let dlen = d.len();
            Some(d.get_mut(..n).ok_or(short(dlen))?)
        }
        None => None,
    };
    let with_depth = z.is_some();
    let mut band = BandBuf::<Rgb565Be, D>::with_depth(px, z, w, rows)?;
    let mut state = BandState::new(order, pool);
    probe.resume();
    let mut bands = frame.bands(scene, &mut state, rows);
    probe.pause();
    // Borrowed in its `Result` (not moved out: a stack slot of its own).
    let bands = match &mut bands {
        Ok(b) => b,
        Err(e) => return Err((*e).into()),
    };
    loop {
        probe.resume();
        let r = bands.next_band(&mut band);
        probe.pause();
        if r?.is_none() {
            break;
        }
        crc.update(band.bytes());
        let z = band.depth().unwrap_or(&[]);
        stats.covered += z.iter().filter(|&&d| d != D::CLEAR).count() as u32;
    }
    stats.setups = bands.stats().triangles;
    stats.active_peak = bands.active_peak() as u32;
    stats.drawn = bands.stats().pixels;
    if !with_depth {
        stats.covered = stats.drawn;
    }
    probe.close();
    stats.crc = crc.finish();
    Ok(stats)
}

/// Prepares `spec` with the profile `P` into `ws` (no probe): the
/// start-up check that every scene fits the workspace.
///
/// # Errors
/// The core's error, e.g. a workspace part too small.
// Not inlined: its locals (the scene's parts, the prepared frame) then
// take a stack frame only during the check, not one in the caller's
// (a firmware's `main`, under every frame rendered after it).
#[inline(never)]
pub fn check_with<P: Profile>(
    spec: &SceneSpec,
    ws: Workspace<'_, P::Lerp>,
) -> Result<u32, FrameError> {
    let parts = Parts::<P::Real>::new(spec);
    let camera = parts.camera?;
    let scene = parts.scene(spec, camera);
    let frame = prepare::<P>(&scene, spec.width, spec.height, ws)?;
    Ok(frame.bytes_used() as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{capacity_for, render_frame, BandPool, NoProbe, BAND_PIXELS, SCENES};
    use fixshade::num::{Fast, FastPc, Precise, F32, F64};
    use fixshade::render::Tri;
    use std::{boxed::Box, vec, vec::Vec};

    fn run<P: Profile>(spec: &SceneSpec) -> FrameStats {
        let n = capacity_for::<P>();
        let (mut xy, mut vals, mut tris) = (
            vec![fixshade::render::ScreenXy::ZERO; n.vertices],
            vec![<P::Lerp as fixshade::raster::Lerp>::ZERO; n.values],
            vec![Tri::default(); n.made],
        );
        let mut colors = vec![fixshade::target::Rgb8::BLACK; n.colors];
        let mut faces = vec![0u8; n.triangles];
        let ws = Workspace {
            xy: &mut xy,
            vals: &mut vals,
            tris: &mut tris,
            colors: &mut colors,
            faces: &mut faces,
        };
        let mut px = vec![0u16; BAND_PIXELS];
        let mut z = vec![0u16; BAND_PIXELS];
        let mut order = vec![0u16; n.triangles];
        let mut pool = Box::new(ProfilePool::<P>::new());
        render_frame_with::<P, _>(
            spec,
            ws,
            &mut px,
            Some(&mut z),
            &mut order,
            &mut pool,
            &mut NoProbe,
        )
        .unwrap()
    }

    #[test]
    fn fast_equals_the_firmware_frame_loop() {
        let mut st = Box::new(crate::SceneStorage::new());
        for spec in SCENES.iter() {
            let (ws, order) = st.split();
            let mut px = vec![0u16; BAND_PIXELS];
            let mut z = vec![0u16; BAND_PIXELS];
            let mut pool = Box::new(BandPool::new());
            let want = render_frame(
                spec,
                ws,
                &mut px,
                Some(&mut z),
                order,
                &mut pool,
                &mut NoProbe,
            )
            .unwrap();
            assert_eq!(run::<Fast>(spec), want, "{}", spec.name);
        }
    }
    #[test]
    fn every_profile_renders_every_scene_with_the_same_coverage_nearly() {
        for spec in SCENES.iter() {
            let fast = run::<Fast>(spec);
            let others: Vec<FrameStats> = vec![
                run::<Precise>(spec),
                run::<F32>(spec),
                run::<F64>(spec),
                run::<FastPc>(spec),
            ];
            for s in others {
                // All profiles snap to the same subpixel grid: coverage
                // departs only where depth or projection rounding moves
                // an edge by a subpixel (a few pixels per frame).
                let d = s.covered.abs_diff(fast.covered);
                assert!(d * 200 <= fast.covered, "{}: {s:?} vs {fast:?}", spec.name);
                assert_eq!(s.triangles, fast.triangles, "{}", spec.name);
            }
        }
    }

    #[test]
    fn widening_is_exact_for_the_wide_scalars() {
        for bits in [-(1 << 24), -65536, -1, 0, 1, 13107, 6_553_600, i32::MAX] {
            let q = Q16::from_bits(bits);
            assert_eq!(widen::<f64>(q), f64::from(bits) / 65536.0);
            assert_eq!(widen::<Q16>(q), q);
        }
        assert_eq!(widen::<f32>(Q16::from_bits(13107)), 13107.0 / 65536.0);
    }
}
