//! Preparing a frame: transform, light, cull, clip, project.
//!
//! # Cost per stage
//!
//! Measured with `examples/firmware/profile.sh` (exact QEMU counts) on the
//! bunny benchmark (1 839 vertices, 3 674 triangles of which 1 498 are
//! kept; `fast`, Gouraud, one directional light), instructions:
//!
//! | stage | Cortex-M4 | Cortex-M0 |
//! |---|---:|---:|
//! | culling in object space ([`EarlyCull`], 1 839 vertices, 669 skipped) | 20 / vertex | 33 / vertex |
//! | vertex loops ([`Fused`] projection and depth, then [`OneLight`]) over the 1 170 others | 179 K | 315 K |
//! | triangle loop (`triangles_visible`, faces with a skipped corner dropped first) | 33 / triangle | 54 / triangle |
//! | per object (sphere, matrices, fused rows, culling constants) | 27 K | 61 K |
//! | whole geometry | 0.360 M | 0.624 M |
//!
//! The vertex loop's screen test is one word a vertex (the OR of `W = y
//! · 2^16 | x` and `lim - W`, [`on_screen`]: one register, three
//! instructions) rather than the box of the projected vertices (three
//! registers, nine instructions), and a visible object's rows are the
//! screen's: bunny Gouraud 0.372 -> 0.370 M on the Cortex-M4, 0.637 ->
//! 0.622 M on the Cortex-M0. The triangle loop reads each corner as one
//! word and takes the area from the words ([`area_words`]): 129 488 ->
//! 119 597 on the Cortex-M4, 0.360 M in all; on the host (callgrind,
//! `bunny_frame`) the frame is 2 161 582 -> 2 157 988. Tried: the
//! transform's constants read through an opaque pointer in the loop
//! (`black_box`, hoping for `ldm`/`ldrd` of adjacent fields instead of
//! spill reloads): the compiler loaded them one by one and spilled them
//! again, `kernel_fused` 176 260 -> 181 991. Passes (transform into a
//! scratch array, then project, then light) were costed line by line
//! and not built: each pass adds its own loop, mark test and loads of
//! the position (about 10 a vertex a pass), as many as the spill reloads
//! it saves (about 30 a vertex in the one-pass loop).
//!
//! The culling loop takes two vertices a step (the compiler's unrolling
//! of the one-vertex loop spilled: 24 -> 22 per vertex on the
//! Cortex-M4), and the margin's cone terms one operation fewer on the
//! Cortex-M0 ([`EarlyCull::margin`]); the projection's rounded shifts
//! keep one shift amount live and no rounding constant ([`Fused`]):
//! 0.382 -> 0.376 M on the Cortex-M4, 0.654 -> 0.637 M on the Cortex-M0.
//! Flat objects under one light zip their baked face normals and colour
//! slots with the triangles (no bounds checks, grey decided once):
//! bunny flat 0.450 -> 0.408 M (Cortex-M4), 0.714 -> 0.665 M (Cortex-M0).
//!
//! The culling marks are the test's margin itself (negative: skipped;
//! 29 -> 21 per vertex on the Cortex-M4 against a select of two
//! constants), and a visible object's rows come from its vertices' box
//! rather than a pass over its kept triangles (14 K on the Cortex-M4;
//! `project_loop`): 0.425 -> 0.390 M. Objects of fewer than
//! [`EARLY_CULL_MIN_VERTICES`] vertices and Phong objects skip the
//! culling set-up (cubes-and-sphere: 0.304 -> 0.272 M on the Cortex-M4).
//!
//! Culling in object space ([`EarlyCull`]) skips the vertices all of whose
//! faces are certainly back-facing (their rounded screen area must be
//! positive: the screen test would cull them): 0.444 -> 0.425 M on the
//! Cortex-M4, 0.736 -> 0.681 M on the Cortex-M0, the same triangles and
//! frames. Testing per vertex (a baked cone of its face normals) rather
//! than per face was measured cheaper: per face (3 674 tests, 851
//! vertices skipped) the tests and the marking of the kept faces' corners
//! cost more than the 182 further vertices saved (0.476 M on the
//! Cortex-M4). Measured again with per-face cones computed at compile
//! time (the baked face normal as axis, the spread folded into the
//! slack), the 1 662 faces left flagged in their bytes and only they
//! screen-tested: the vertex loops 179 K -> 158 K (988 vertices), the
//! triangle loop 129 K -> 110 K, but the face pass costs 128 K (24 a
//! face, 22 more a face left) against the vertex marks' 41 K: 0.420 M
//! on the Cortex-M4 (0.376 M before), 0.736 M on the Cortex-M0, and
//! 2.266 M against 2.246 M for the host frame (callgrind). Its floor,
//! about 20 a face (five loads, five multiply-adds, the byte) and 12 a
//! face left, is 93 K against the 82 K it saves.
//!
//! The depth clamp of the projection loop is left out when
//! [`Fused::new`] proves it idle over the bounding sphere (the bunny: 127
//! -> 122 per vertex on the Cortex-M4, 0.452 -> 0.444 M and 0.745 ->
//! 0.736 M in all).
//!
//! Before the fused kernel (exact-rounding Q16 transform with 64-bit
//! products, Newton-refined reciprocal, variable 64-bit shifts, general
//! triangle loop with clamps and a 64-bit sign fallback): 237 / 515 per
//! vertex and 103 / 142 per triangle, 0.842 M / 1.532 M in all. The
//! vertex loops still spill about 20 constants per vertex on the M4
//! (three 3-term rows, the reciprocal table, the depth constants and the
//! screen test do not fit 13 registers: 33 of the projection loop's 105
//! instructions a vertex are stack loads and stores); the triangle
//! loop's floor with this data layout is its loads: 3 + 3 + 3 bounds
//! checks.

use super::clip::{ClipVert, Outcode, Planes, CLIP_ATTRS, GUARD_PX, MAX_POLY};
use super::position::PosFrame;
use super::{
    face_byte, face_shift, FaceRows, Frame, Layout, Part, PreparedObject, RenderError, ScreenXy,
    Subpx, Tri, Workspace, FACE_BACK, FACE_ROW, MAX_TRIANGLES, MAX_VERTICES,
};
use crate::geom::cull::EarlyCull;
use crate::geom::fused::Fused;
use crate::geom::q16::{face_normal_q14, Proj16, Xform16};
use crate::geom::{Affine, Vec3};
use crate::illum::{LevelLight, Light, LightKind, ObjectLight, OneLight, Shade, MAX_LIGHTS};
use crate::mesh::{Mesh, MAX_AXIS2};
use crate::num::approx16;
use crate::num::wide::{det_sign, det_sign_small, mul16_small, SMALL};
use crate::num::{Kernels, Only, Profile, Raw16, Real};
use crate::raster::{first_row, Lerp, SubpixelBits, COORD_LIMIT_PX};
use crate::scene::{Object, Scene, SceneError, Shading};
use crate::target::{Depth16, Rgb8, MAX_SCREEN};

/// Largest magnitude of a stored screen coordinate ([`ScreenXy`]), in
/// subpixels: `i16::MAX - 1` = 32 766, so that every stored coordinate
/// fits an `i16` and the two values below `-XY_LIMIT` (`i16::MIN` and
/// `i16::MIN + 1`) are free for the marks of vertices that are never
/// drawn (outside the planes, or culled in object space).
pub const XY_LIMIT: i32 = i16::MAX as i32 - 1;

/// Profiles with at most this many subpixel bits store screen positions
/// from the screen's top-left corner; profiles with more store them from
/// the screen's centre (see [`guard_px`]).
const FROM_CORNER_MAX_BITS: u32 = 4;

/// The origin of stored screen positions of profile `P` on a `width ×
/// height` screen, in subpixels: the top-left corner (`[0, 0]`) for at
/// most [`FROM_CORNER_MAX_BITS`] subpixel bits, else the screen's centre
/// `[width, height] · 2^s / 2` (exact: `s >= 1`; at most `4096 · 2^7`).
#[inline(always)]
#[allow(clippy::cast_possible_wrap)]
pub(crate) fn xy_origin<P: Profile>(width: u32, height: u32) -> Subpx {
    let s = P::SUBPIXEL_BITS.get();
    if s > FROM_CORNER_MAX_BITS {
        let c = |n: u32| (n.min(MAX_SCREEN) << (s - 1)) as i32;
        Subpx([c(width), c(height)])
    } else {
        Subpx([0, 0])
    }
}

/// The guard band's half-size in pixels (around the screen's centre) for
/// `sub` subpixel bits on a `width × height` screen, or `None` when no
/// guard band both holds the screen and keeps stored positions within
/// ±[`XY_LIMIT`].
///
/// With `R = XY_LIMIT >> sub` whole pixels of stored range, `h =
/// ⌈max(width, height) / 2⌉` and the screen's centre `c <= h`, a vertex
/// inside the guard band lies within `G` pixels of `c`, so
/// - stored from the corner (`sub <= 4`): `|x| <= c + G`, and `G =
///   min(GUARD_PX, R - h - 1)` keeps `|x| <= R - 1` pixels;
/// - stored from the centre (`sub > 4`): `|x - c| <= G`, and `G =
///   min(GUARD_PX, R - 1)`;
///
/// one pixel of `R` left for the rounding of the projection (at most 3/4
/// subpixel in the fused kernel, 1/2 in the others) and of the guard
/// planes' slope. The band must reach beyond the screen: `G >= h + 1`
/// (a corner clipped by a guard plane is then a pixel or more outside
/// the screen, as with the 4096-pixel band before). Hence the largest
/// screen ([`max_screen`]): `h <= (R - 2) / 2` from the corner, `h <= R
/// - 2` from the centre, and at most [`MAX_SCREEN`]: 2 044 pixels at 4
/// bits (`R` = 2 047), 4 092 at 3, 4 096 at 1 and 2; 2 042 at 5 (`R` =
/// 1 023), 1 018 at 6, 506 at 7 and 250 at 8 (`R` = 127).
#[allow(clippy::cast_possible_wrap)]
pub(crate) const fn guard_px(sub: u32, width: u32, height: u32) -> Option<i32> {
    let n = if width > height { width } else { height };
    if n > MAX_SCREEN || sub > 15 {
        return None;
    }
    let h = n.div_ceil(2) as i32;
    let r = XY_LIMIT >> sub;
    let g = if sub > FROM_CORNER_MAX_BITS {
        r - 1
    } else {
        r - h - 1
    };
    let g = if g < GUARD_PX { g } else { GUARD_PX };
    if g > h {
        Some(g)
    } else {
        None
    }
}

/// The largest screen side [`prepare`] takes for `sub` subpixel bits:
/// larger screens are [`SceneError::Screen`]. Stored positions
/// ([`ScreenXy`]) are within ±[`XY_LIMIT`] subpixels, `R = XY_LIMIT >>
/// sub` whole pixels; with `h` half the screen's larger side, the guard
/// band's half-size is `G = min(4096, R - h - 1)` for `sub <= 4`
/// (positions stored from the screen's corner, `|x| <= h + G + 1 <= R`
/// pixels with a pixel for rounding) and `G = min(4096, R - 1)` above
/// (stored from the centre), and must reach past the screen, `G >= h +
/// 1`: `h <= (R - 2) / 2`, resp. `h <= R - 2`. 2 044 pixels at the
/// default 4 bits (`R` = 2 047), 4 096 at 1 and 2, 4 092 at 3, 2 042 at 5,
/// 1 018 at 6, 506 at 7, 250 at 8 (`R` = 127).
#[allow(clippy::cast_sign_loss)]
pub const fn max_screen(sub: u32) -> u32 {
    if sub > 15 {
        return 0;
    }
    let r = XY_LIMIT >> sub;
    let h = if sub > FROM_CORNER_MAX_BITS {
        r - 2
    } else {
        (r - 2) / 2
    };
    let h = if h < GUARD_PX - 1 { h } else { GUARD_PX - 1 };
    let n = 2 * h as u32;
    if n < MAX_SCREEN {
        n
    } else {
        MAX_SCREEN
    }
}

/// The lights of a scene moved to eye space.
pub(super) fn eye_lights<R: Real>(
    scene: &Scene<'_, '_, R>,
) -> Result<heapless::Vec<Light<R>, MAX_LIGHTS>, SceneError> {
    let mut out = heapless::Vec::new();
    eye_lights_into(scene, &mut out)?;
    Ok(out)
}

/// [`eye_lights`] into `out` (empty): no `Result` of the whole list to
/// move (a stack slot of its own in the caller).
fn eye_lights_into<R: Real>(
    scene: &Scene<'_, '_, R>,
    out: &mut heapless::Vec<Light<R>, MAX_LIGHTS>,
) -> Result<(), SceneError> {
    let view = &scene.camera.view;
    for l in scene.lights {
        let kind = match l.kind {
            LightKind::Point(p) => LightKind::Point(view.point(p)),
            LightKind::Directional(d) => LightKind::Directional(view.vector(d)),
        };
        out.push(Light { kind, ..*l })
            .map_err(|_| SceneError::TooManyLights)?;
    }
    Ok(())
}

/// The shading layout an object needs: pay only for what is used.
pub(super) fn layout_of<R: Real>(
    obj: &Object<'_, R>,
    shade: &Shade<R>,
    lights: &[Light<R>],
) -> Layout {
    let grey = |c: Vec3<R>| c.x == c.y && c.y == c.z;
    match obj.shading {
        Shading::Flat => Layout::Flat,
        Shading::Gouraud => {
            if grey(obj.material.color) && lights.iter().all(|l| grey(l.color)) {
                Layout::GouraudMono
            } else {
                Layout::GouraudRgb
            }
        }
        Shading::Phong => {
            if shade.needs_position() {
                Layout::PhongPosition
            } else {
                Layout::PhongNormal
            }
        }
    }
}

/// Projection constants of a frame.
struct View<R: Real> {
    planes: Planes<R>,
    k: R,
    cx: R,
    cy: R,
    depth_scale: Option<R>,
    /// The integer projection (`Q16` only).
    fast: Only<R, Proj16>,
}

/// The raw bits of a Q16.16 value (`to_fixed_i32(16)`): eye-space
/// coordinates, colour levels in `[0, 255 · 2^16]`, the depth scale; not
/// to be mixed with subpixel coordinates ([`Subpx`]) or depths
/// ([`DepthQ30`]). Zero-cost (an `i32`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(transparent)]
pub(super) struct Q16Bits(pub(super) i32);

/// A depth in Q2.30 from the fused kernel (`0` at the near plane, `2^30`
/// at the far one), before the profile stores it
/// ([`Profile::depth_q30`]); not to be mixed with raw Q16 bits or
/// subpixel coordinates. Zero-cost (an `i32`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(transparent)]
pub(super) struct DepthQ30(pub(super) i32);

/// Raw Q16 vector of a `Q16` vector.
#[inline(always)]
fn raw3<R: Real>(v: Vec3<R>) -> [Q16Bits; 3] {
    [
        Q16Bits(v.x.to_fixed_i32(16)),
        Q16Bits(v.y.to_fixed_i32(16)),
        Q16Bits(v.z.to_fixed_i32(16)),
    ]
}

/// A `Q16` vector from raw bits.
#[inline(always)]
fn from_raw3<R: Real>(v: [Q16Bits; 3]) -> Vec3<R> {
    let [Q16Bits(x), Q16Bits(y), Q16Bits(z)] = v;
    Vec3::new(
        R::from_fixed_i32(x, 16),
        R::from_fixed_i32(y, 16),
        R::from_fixed_i32(z, 16),
    )
}

impl<R: Real> View<R> {
    /// [`Planes::outcode`], with the guard band's `g·w` computed once
    /// (the same operations, so the same result).
    #[inline]
    fn outcode(&self, p: Vec3<R>) -> Outcode {
        let pl = &self.planes;
        let w = -p.z;
        let gw = pl.guard * w;
        let mut c = 0;
        if w - pl.near < R::ZERO {
            c |= 1;
        }
        if let Some(f) = pl.far {
            if f - w < R::ZERO {
                c |= 2;
            }
        }
        if gw + p.x < R::ZERO {
            c |= 4;
        }
        if gw - p.x < R::ZERO {
            c |= 8;
        }
        if gw + p.y < R::ZERO {
            c |= 16;
        }
        if gw - p.y < R::ZERO {
            c |= 32;
        }
        c
    }

    /// Screen position (pixels), depth in `[0, 1]` and perspective weight
    /// `q = near/w` in `(0, 1]` of an eye-space point in front of the near
    /// plane.
    fn project(&self, p: Vec3<R>) -> (R, R, R, R) {
        let iw = (-p.z).recip();
        let sx = self.cx + (p.x * iw) * self.k;
        let sy = self.cy - (p.y * iw) * self.k;
        let q = (self.planes.near * iw).clamp(R::ZERO, R::ONE);
        let mut d = R::ONE - q;
        if let Some(s) = self.depth_scale {
            d *= s;
        }
        (sx, sy, d.clamp(R::ZERO, R::ONE), q)
    }
}

/// Prepares `scene` for a `width × height` screen into `ws`.
///
/// # Errors
/// [`RenderError`]: an invalid scene or screen size (a side above
/// [`max_screen`] of the profile's subpixel bits: 2 044 pixels at the
/// default 4), a mesh without
/// normals for smooth shading, or a workspace part too small (naming the
/// part and the object).
pub fn prepare<'w, 's: 'w, 'm: 'w, P: Profile>(
    scene: &Scene<'s, 'm, P::Real>,
    width: u32,
    height: u32,
    ws: Workspace<'w, P::Lerp>,
) -> Result<Frame<'w, P>, RenderError> {
    let mut out = None;
    prepare_in(scene, width, height, ws, &mut out)?;
    // (Always a frame after `Ok`.)
    out.ok_or(RenderError::Window)
}

/// [`prepare`] into `out`: the frame is made in `out` (`Some` after `Ok`,
/// `None` after an error) rather than returned. The frame, with its list
/// of prepared objects, is large (about 700 bytes on a 32-bit target): a
/// caller that keeps it on its stack for the whole render (a firmware's
/// frame loop) holds it once this way, where a returned `Result` may be
/// moved into a slot of its own.
///
/// ```
/// use fixshade::num::{Fast, Q16};
/// use fixshade::render::{prepare_in, Frame, Workspace};
/// use fixshade::scene::Scene;
///
/// fn frame_loop(scene: &Scene<'_, '_, Q16>, ws: Workspace<'_, i32>) {
///     let mut frame: Option<Frame<'_, Fast>> = None;
///     match prepare_in(scene, 240, 240, ws, &mut frame) {
///         Ok(()) => assert!(frame.is_some()), // render it in bands here
///         Err(_) => assert!(frame.is_none()),
///     }
/// }
/// ```
///
/// # Errors
/// As [`prepare`].
pub fn prepare_in<'w, 's: 'w, 'm: 'w, P: Profile>(
    scene: &Scene<'s, 'm, P::Real>,
    width: u32,
    height: u32,
    ws: Workspace<'w, P::Lerp>,
    out: &mut Option<Frame<'w, P>>,
) -> Result<(), RenderError> {
    *out = None;
    scene.check()?;
    // The guard band that keeps stored positions within `±XY_LIMIT`
    // (`None`: the screen is beyond `max_screen`).
    let Some(guard) = guard_px(P::SUBPIXEL_BITS.get(), width, height) else {
        return Err(SceneError::Screen.into());
    };
    let cam = &scene.camera;
    let k = cam.focal.mul_i32(height as i32).half();
    // A saturated projection scale (a field of view too narrow for the
    // screen in this scalar type, e.g. below 0.84° at 240 rows in Q16)
    // would place every vertex wrongly: refuse it.
    if k >= P::Real::MAX.half() {
        return Err(SceneError::Screen.into());
    }
    let (cx, cy) = (
        P::Real::from_i32(width as i32).half(),
        P::Real::from_i32(height as i32).half(),
    );
    let view = View {
        planes: Planes {
            near: cam.near,
            far: cam.far,
            guard: P::Real::from_i32(guard).div(k),
        },
        k,
        cx,
        cy,
        depth_scale: cam.far.map(|f| f.div(f - cam.near)),
        fast: <P::Real as Real>::Kernels::only(|q| {
            Proj16::new(q, k, cam.near, [cx, cy], P::SUBPIXEL_BITS.get())
        }),
    };
    let mut lights = heapless::Vec::new();
    eye_lights_into(scene, &mut lights)?;
    // At most `MAX_TRIANGLES` triangle numbers (and as many made triangles
    // and flat colours): they are `u16` in the object list and the band
    // order.
    fn cut<T>(s: &mut [T]) -> &mut [T] {
        let n = s.len().min(MAX_TRIANGLES);
        s.get_mut(..n).unwrap_or_default()
    }
    let ws = ws.map_triangle_parts(|t, c, f| (cut(t), cut(c), cut(f)));
    // The frame is made first, in `out`, and its object list filled in
    // place: no list or frame to move into another (each move of one can
    // take a stack slot of its own in the caller's frame).
    let frame = out.insert(Frame {
        ws: Workspace {
            xy: &mut [],
            vals: &mut [],
            tris: &mut [],
            colors: &mut [],
            faces: &mut [],
        },
        faces: &[],
        face_rows: [0; FACE_ROW as usize + 1],
        scene: scene.objects,
        objects: heapless::Vec::new(),
        width,
        height,
    });
    let mut p = Preparer::<P> {
        ws,
        view,
        nv: 0,
        nval: 0,
        nt: 0,
        nc: 0,
        nm: 0,
        t_start: 0,
        made_start: 0,
        object: 0,
        width,
        height,
        on_screen: false,
        fit: false,
        rows: None,
        marked: false,
        face_rows: &mut frame.face_rows,
    };
    for (oi, obj) in scene.objects.iter().enumerate() {
        p.object = oi;
        let pushed = match p.object_pass(scene, obj, &lights) {
            Ok(po) => frame
                .objects
                .push(po)
                .map_err(|_| SceneError::TooManyObjects.into()),
            Err(e) => Err(e),
        };
        if let Err(e) = pushed {
            *out = None;
            return Err(e);
        }
    }
    // The frame keeps the face bytes apart from the workspace.
    let mut faces: &mut [u8] = &mut [];
    frame.ws = p.ws.map_triangle_parts(|t, c, f| {
        faces = f;
        (t, c, &mut [])
    });
    frame.faces = faces;
    Ok(())
}

impl<'a, L> Workspace<'a, L> {
    /// The workspace with its triangle parts (made triangles, colours,
    /// face bytes) replaced by `f` of them.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn map_triangle_parts(
        self,
        f: impl FnOnce(
            &'a mut [Tri],
            &'a mut [Rgb8],
            &'a mut [u8],
        ) -> (&'a mut [Tri], &'a mut [Rgb8], &'a mut [u8]),
    ) -> Self {
        let Workspace {
            xy,
            vals,
            tris,
            colors,
            faces,
        } = self;
        let (tris, colors, faces) = f(tris, colors, faces);
        Workspace {
            xy,
            vals,
            tris,
            colors,
            faces,
        }
    }
}

struct Preparer<'w, 'f, P: Profile> {
    ws: Workspace<'w, P::Lerp>,
    view: View<P::Real>,
    nv: usize,
    nval: usize,
    /// Triangle numbers in use.
    nt: usize,
    /// Flat-triangle colours in use.
    nc: usize,
    /// Made triangles in use ([`Workspace::tris`]).
    nm: usize,
    /// The current object's first triangle number.
    t_start: usize,
    /// The current object's first made triangle's number.
    made_start: usize,
    object: usize,
    width: u32,
    height: u32,
    /// The vertex kernel proved every prepared vertex of the current
    /// object within the screen's box ([`on_screen`]), stored from the
    /// screen's corner, and its depth within the small-triangle kernel's
    /// test ([`kernel_depth_in`]).
    on_screen: bool,
    /// Every triangle the current object keeps is fit for the
    /// small-triangle kernel ([`PreparedObject::kernel_fit`]): set by the
    /// triangle loop over the screen's box on a screen that allows it.
    fit: bool,
    /// The rows of the current object when the triangle pass bounded them
    /// (else they are gathered from its triangles).
    rows: Option<[u16; 2]>,
    /// The current object's vertices were marked by [`mark_corners`]:
    /// triangles with an [`UNUSED`] corner were culled in object space.
    marked: bool,
    /// The kept triangles so far by row code (the frame's
    /// [`Frame::face_rows`]).
    face_rows: &'f mut FaceRows,
}

/// The fewest vertices for which an object's culling in object space
/// ([`EarlyCull`]) is set up. The set-up (once per object: the eye in
/// object space, the threshold's bounds, 64- and 128-bit divisions) costs
/// about 7 K instructions on the Cortex-M4 and 12 K on the Cortex-M0
/// (measured: 4.6 K + divisions per cube of cubes-and-sphere on the M4);
/// the test then costs about 20 per vertex and saves about 130 (M4) / 250
/// (M0) per skipped vertex, about a third of a closed mesh's vertices:
/// it pays from about 7 000 / (130 / 3 - 20) = 300 vertices on the M4
/// (12 000 / (250 / 3 - 30) = 225 on the M0). Smaller meshes (the cube,
/// the dodecahedron) skip it; the frames are the same either way.
const EARLY_CULL_MIN_VERTICES: usize = 300;

/// `xy[0]` of a prepared vertex outside the clipping planes: never drawn
/// (its triangles are clipped or dropped), `xy[1]` holds its outcode. No
/// vertex inside the planes has it: they are within ±[`XY_LIMIT`].
const OUTSIDE: i16 = i16::MIN;

/// `xy[0]` of a prepared vertex that no kept triangle needs: every
/// triangle using it is certainly back-facing ([`EarlyCull::margin`]), and
/// the vertex pass skips it. Never drawn, never read by the rasterizer; no
/// projected vertex has it (they are within ±[`XY_LIMIT`]).
pub(super) const UNUSED: i16 = i16::MIN + 1;

/// Where the bounding sphere of `mesh` placed by `mv` lies against
/// the planes. The sphere's eye-space radius is the mesh radius times
/// a bound of the largest stretch of `mv` (the largest row sum of
/// magnitudes of `MᵀM`, at least the largest eigenvalue, square
/// rooted), plus a margin of 1/64 unit and 1/64 relative for the
/// rounding of the vertices' own transform: a vertex of an `Inside`
/// object passes every outcode test, and no vertex of an `Outside`
/// object passes the plane it is outside of.
#[cfg(test)]
pub(super) fn sphere<R: Real>(planes: &Planes<R>, mesh: &Mesh<'_>, mv: &Affine<R>) -> Sphere {
    placement(planes, mesh, mv).0
}

/// [`sphere`], with the reach: the largest magnitude an eye-space
/// coordinate of the sphere can take (`R::MAX` when it does not fit).
fn placement<R: Real>(planes: &Planes<R>, mesh: &Mesh<'_>, mv: &Affine<R>) -> (Sphere, R, R) {
    let b = mesh.bound();
    let c = mv.point(Vec3::from_q14(b.center));
    // How far the linear part stretches the radius (see `Mat3::stretch`).
    let Some(stretch) = mv.m.stretch() else {
        return (Sphere::Across, R::MAX, R::MAX);
    };
    let r0 = R::from_fixed_i32(b.radius.min(1 << 16) as i32, 14) * stretch;
    let r = r0 + r0.mul_i32(1).div(R::from_i32(64)) + R::from_ratio(1, 64);
    if r >= R::MAX.half()
        || c.x.abs() >= R::MAX.half()
        || c.y.abs() >= R::MAX.half()
        || c.z.abs() >= R::MAX.half()
    {
        return (Sphere::Across, R::MAX, R::MAX);
    }
    let pl = planes;
    let w = -c.z;
    // Distances to the guard planes |x| = g·w, scaled by
    // √(1 + g²) (compared with r·√(1 + g²) <= r·(1 + g)).
    let gr = r + r * pl.guard;
    let gw = pl.guard * w;
    let d = [w - pl.near, pl.far.map_or(R::MAX.half(), |f| f - w)];
    let dg = [gw + c.x, gw - c.x, gw + c.y, gw - c.y];
    // The reach: the sphere's coordinates, and every partial sum of the
    // transform of a vertex (`Σ |m_kj|·max|p| + |t_k|`), which a
    // saturating scalar would clip before the later terms bring it back.
    let pmax = R::from_fixed_i32(
        i32::from(b.center.iter().map(|v| v.unsigned_abs()).max().unwrap_or(0))
            + b.radius.min(1 << 17) as i32,
        14,
    );
    let rows = &mv.m.rows;
    let t = [mv.t.x, mv.t.y, mv.t.z];
    let partial = (0..3).fold(R::ZERO, |acc, k| {
        let r = rows[k];
        acc.max((r.x.abs() + r.y.abs() + r.z.abs()) * pmax + t[k].abs())
    });
    let m = (c.x.abs().max(c.y.abs()).max(c.z.abs()) + r).max(partial);
    if d.iter().any(|&v| v < -r) || dg.iter().any(|&v| v < -gr) {
        return (Sphere::Outside, m, r);
    }
    if d.iter().all(|&v| v > r) && dg.iter().all(|&v| v > gr) {
        return (Sphere::Inside, m, r);
    }
    // Clipped: `g·w` may saturate where `w` is far beyond the screen's
    // guard band (`g·w > MAX`), but only at points whose `|x|, |y| <= m <
    // MAX/2` keep the outcode's sign, and a clipped vertex interpolated
    // with a saturated distance stays on the clipped edge, inside the
    // guard band: the drawn pixels are those of the exact clip.
    (Sphere::Across, m, r)
}

/// The sign of `((b - a) × (c - a)) · a`: positive when the triangle
/// faces away from the eye. The edges and `a` are first divided by their
/// largest component magnitude when it exceeds 1 (a positive factor: the
/// same sign), so that no product saturates a fixed-point scalar for any
/// coordinates within half its range.
fn facing<R: Real>(a: Vec3<R>, b: Vec3<R>, c: Vec3<R>) -> R {
    let big = |v: Vec3<R>| v.x.abs().max(v.y.abs()).max(v.z.abs());
    let down = |v: Vec3<R>, m: R| {
        if m > R::ONE {
            Vec3::new(v.x.div(m), v.y.div(m), v.z.div(m))
        } else {
            v
        }
    };
    let (e1, e2) = (b - a, c - a);
    let m = big(e1).max(big(e2));
    let (e1, e2) = (down(e1, m), down(e2, m));
    let n = e1.cross(e2);
    let n = down(n, big(n));
    n.dot(down(a, big(a)))
}

/// The rows a triangle with corners at `xy` can cover on a `width ×
/// height` screen (the rows the rasterizer would visit), or `None` when it
/// covers no pixel centre of the screen.
#[inline(always)]
fn rows_in(xy: [Subpx; 3], width: u32, height: u32, sub: SubpixelBits) -> Option<[u16; 2]> {
    let span = |k: usize| {
        let (a, b, c) = (xy[0].0[k], xy[1].0[k], xy[2].0[k]);
        (a.min(b).min(c), a.max(b).max(c))
    };
    let (x_lo, x_hi) = span(0);
    let (y_lo, y_hi) = span(1);
    // `max`/`min` rather than `clamp`, whose bound check is a panic
    // branch the optimiser cannot remove for a runtime bound.
    let clamp = |r: i32, n: u32| r.max(0).min(n.min(u32::from(u16::MAX)) as i32) as u16;
    // Rows: the rasterizer's own `first_row(top)..first_row(bottom)`.
    // Columns, conservatively: a centre on the rightmost x may count.
    let rows = [
        clamp(first_row(y_lo, sub), height),
        clamp(first_row(y_hi, sub), height),
    ];
    let cols = [
        clamp(first_row(x_lo, sub), width),
        clamp(first_row(x_hi, sub).saturating_add(1), width),
    ];
    if rows[0] >= rows[1] || cols[0] >= cols[1] {
        return None;
    }
    Some(rows)
}

/// The triangle loop of an object wholly inside the planes whose back
/// faces are culled or drawn with its own vertices (every layout but
/// two-sided Gouraud): each mesh triangle's [`Workspace::faces`] byte
/// written into `faces` ([`face_byte`] of its first row and screen row
/// shift `q`, or 0 when the view does not keep it), `color(t, back)`
/// storing the flat colour of kept
/// mesh triangle `t` (false when the colours are full; a no-op for the
/// other layouts). Bit for bit what the general loop keeps; a free
/// function over slices, so that its state stays in registers. Returns
/// `None` when the colours are full.
#[inline(never)]
fn triangles_inside(
    tris: &[[u16; 3]],
    (xy, origin): (&[ScreenXy], Subpx),
    (faces, counts): (&mut [u8], &mut FaceRows),
    (width, height, shift): (u32, u32, u32),
    sub: SubpixelBits,
    (cull, marked): (bool, bool),
    mut color: impl FnMut(usize, bool) -> bool,
) -> Option<()> {
    // Not kept unless found so below (cleared at once: cheaper than a
    // store per triangle).
    faces.fill(0);
    for (t, tri) in tris.iter().enumerate() {
        let q = tri.map(|i| xy.get(usize::from(i)).copied().unwrap_or_default());
        if marked && (q[0].0[0] == UNUSED || q[1].0[0] == UNUSED || q[2].0[0] == UNUSED) {
            // Culled in object space.
            continue;
        }
        let p = q.map(|v| v.unpack(origin));
        let [Subpx(a), Subpx(b), Subpx(c)] = p;
        let (e0, e1, e2, e3) = (b[0] - a[0], c[1] - a[1], c[0] - a[0], b[1] - a[1]);
        let sign = det_sign_small(e0, e1, e2, e3).unwrap_or_else(|| det_sign(e0, e1, e2, e3));
        if sign == 0 {
            continue;
        }
        let back = sign > 0;
        if back && cull {
            continue;
        }
        let Some(rows) = rows_in(p, width, height, sub) else {
            continue;
        };
        if !color(t, back) {
            return None;
        }
        if let Some(f) = faces.get_mut(t) {
            *f = face_byte(u32::from(rows[0]), shift, back);
            let c = &mut counts[usize::from(*f & FACE_ROW)];
            *c = c.wrapping_add(1);
        }
    }
    Some(())
}

/// [`triangles_inside`] for an object whose prepared vertices all lie on
/// the screen with edges shorter than `2^15` subpixels (the vertex kernel's
/// [`on_screen`] test shows it; `CULL`: back faces dropped; `MARKED`: triangles
/// with an [`UNUSED`] corner dropped): the sign in one
/// 32-bit expression, the rows
/// without clamps, no column test (it always passes there). The same
/// triangles, bit for bit. `aux` yields one item per triangle (e.g. its
/// face normal and colour slot, zipped with the triangles: no bounds
/// check), handed to `color` with each kept triangle.
#[inline(never)]
fn triangles_visible<const CULL: bool, const MARKED: bool, A>(
    tris: &[[u16; 3]],
    xy: &[ScreenXy],
    (faces, counts): (&mut [u8], &mut FaceRows),
    (sub, q): (SubpixelBits, u32),
    aux: impl Iterator<Item = A>,
    mut color: impl FnMut(usize, A, bool) -> bool,
) -> Option<()> {
    // Not kept unless found so below (cleared at once: cheaper than a
    // store per triangle).
    faces.fill(0);
    // The stored row: `first_row(y) >> q` = `(y + k) >> (sub + q)`.
    let row_shift = sub.get() + q;
    // A marked corner: its `x` negative (every other `x` here is
    // `0..2^15`); with [`WORDS`] the sign bit 15 of its word, the one load
    // of the corner. (Written out: a function taking the corner by value
    // made the host loop load it whole and cost 12.6 K instructions
    // more on the bunny.)
    macro_rules! marked {
        ($p:expr) => {
            if WORDS {
                $p.word() << 16 < 0
            } else {
                $p.0[0] < 0
            }
        };
    }
    // (As many bytes as triangles: the caller's slices.)
    for (t, ((tri, face), slot)) in tris.iter().zip(faces.iter_mut()).zip(aux).enumerate() {
        // Each corner loaded once, checked as it comes (a missing
        // corner: culled when MARKED, else the origin as before).
        let miss = ScreenXy([if MARKED { -1 } else { 0 }, 0]);
        let pa = xy.get(usize::from(tri[0])).copied().unwrap_or(miss);
        if MARKED && marked!(pa) {
            continue;
        }
        let pb = xy.get(usize::from(tri[1])).copied().unwrap_or(miss);
        if MARKED && marked!(pb) {
            continue;
        }
        let pc = xy.get(usize::from(tri[2])).copied().unwrap_or(miss);
        if MARKED && marked!(pc) {
            continue;
        }
        // Twice the signed area, and the three `y` (the rows' too).
        let (d, [ya, yb, yc]) = if WORDS {
            area_words([pa, pb, pc])
        } else {
            let [a, b, c] = [pa, pb, pc].map(|p| [i32::from(p.0[0]), i32::from(p.0[1])]);
            // |edges| < 2^15: each product below 2^30.
            let d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
            (d, [a[1], b[1], c[1]])
        };
        if d == 0 {
            continue;
        }
        let back = d > 0;
        if back && CULL {
            continue;
        }
        // No row centre within the vertical extent (`first_row` of the
        // lowest `y` not below that of the highest) exactly when the
        // three corners share their first row: `first_row` is a floor
        // shift of `y + k`, and two values floor to the same multiple of
        // `2^sub` exactly when they agree above bit `sub`.
        let k = sub.scale() - 1 - sub.scale() / 2;
        let (ea, eb, ec) = (ya + k, yb + k, yc + k);
        if ((ea ^ eb) | (ea ^ ec)) >> sub.get() == 0 {
            continue;
        }
        if !color(t, slot, back) {
            return None;
        }
        // The first row of the top `y` (at least 0, below the height
        // here), as `face_byte` stores it: `(row >> q) + 1`, at most 127.
        #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
        let code = ((ea.min(eb).min(ec) >> row_shift) + 1) as u8;
        *face = code | if back { FACE_BACK } else { 0 };
        let c = &mut counts[usize::from(code & FACE_ROW)];
        *c = c.wrapping_add(1);
    }
    Some(())
}

/// The triangle loop reads corners as words ([`area_words`]) on ARM
/// (one load a corner; [`ScreenXy`] is aligned as a word for ARMv6-M,
/// which has no unaligned loads): bunny Gouraud geometry 372 421 ->
/// 359 838 on the Cortex-M4; on the Cortex-M0 bunny flat 657 226 -> 635
/// 821, cubes-and-sphere 536 205 -> 530 773, bunny Gouraud 622 439 -> 623
/// 515. x86 loads each half with its sign extension: the words cost the
/// host frame 2 157 988 -> 2 164 297 (callgrind), so it keeps the halves.
const WORDS: bool = cfg!(target_arch = "arm");

/// Twice the signed area `(b - a) × (c - a)` of three corners with `0 <=
/// x < 2^15` and edges shorter than `2^15` subpixels (each product below
/// `2^30`), and their `y`, from the words `W = y·2^16 | x`
/// ([`ScreenXy::word`], one load a corner with [`WORDS`]):
/// with `0 <= x < 2^15`, `W = y·2^16 + x` exactly; the word differences
/// `E = W_b - W_a = Δy·2^16 + Δx`, and `E_1·Δy_2 - E_2·Δy_1 = Δx_1·Δy_2 -
/// Δx_2·Δy_1` (the `2^16·Δy_1·Δy_2` terms cancel), modulo 2^32, which
/// holds it. Measured on the Cortex-M4 (bunny Gouraud): the triangle
/// loop 129 488 -> 119 597 instructions (one load a corner instead of
/// two and their address).
#[inline(always)]
fn area_words(p: [ScreenXy; 3]) -> (i32, [i32; 3]) {
    let [wa, wb, wc] = p.map(ScreenXy::word);
    let (ya, yb, yc) = (wa >> 16, wb >> 16, wc >> 16);
    let d = (wb.wrapping_sub(wa))
        .wrapping_mul(yc - ya)
        .wrapping_sub((wc.wrapping_sub(wa)).wrapping_mul(yb - ya));
    (d, [ya, yb, yc])
}

/// The projection loop of the fused kernel: screen positions into `xy`,
/// depths into the first of every `S` values; returns the OR of every
/// projected vertex's screen word `W = y·2^16 | x` (16-bit halves) and
/// of `lim - W` ([`screen_word_limit`]: bits 15 and 31 clear exactly when
/// every vertex lies within the limit's box, see [`on_screen`]), bit 31
/// also set by a vertex whose depth `d` fails `zin`.
/// `CLAMP = false` only when [`Fused::depth_in_range`]. `MARKED`: only
/// the vertices not marked (negative) by [`cull_light`]; the marked ones
/// get [`UNUSED`] and stay out of the test.
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
fn project_loop<const MARKED: bool, const CLAMP: bool, const S: usize, L>(
    f: &Fused,
    positions: &[[i16; 3]],
    (xy, origin, lim): (&mut [ScreenXy], Subpx, u32),
    vals: &mut [L],
    depth: impl Fn(&mut L, DepthQ30),
    zin: impl Fn(i32) -> bool,
) -> u32 {
    let mut acc = 0u32;
    let verts = positions.iter().zip(xy.iter_mut());
    for ((p, out), v) in verts.zip(vals.chunks_exact_mut(S)) {
        // A negative mark is a skipped vertex ([`mark_vertices`]): it
        // gets the one mark the triangle loops know.
        if MARKED && out.0[0] < 0 {
            out.0[0] = UNUSED;
            continue;
        }
        let (s, d) = f.project::<CLAMP>(*p);
        // Inside the guard band: within `±XY_LIMIT` of the origin.
        *out = ScreenXy::pack(Subpx(s), origin);
        // The screen test in one word and one register: the OR of `W`
        // and `lim - W` (see `on_screen`). It replaced the exact box
        // (the largest x and y and the smallest y: three values live,
        // nine instructions a vertex).
        let w = ((s[1] as u32) << 16) | (s[0] as u32 & 0xFFFF);
        // A depth outside the small-triangle kernel's vertex test sets bit
        // 31 as well (`zin`, [`kernel_depth_in`]): the object then takes
        // the general triangle loop and is not fit for the kernel (rare:
        // a vertex within 2^-15 of the near or far plane). Exact QEMU
        // counts, geometry: bunny-gouraud thumbv7em 359 830 -> 361 291,
        // thumbv6m 623 540 -> 632 595; bunny-flat 394 576 -> 402 768,
        // 635 853 -> 644 810 (a flag of its own: 365 390, 640 525, 405 106,
        // 653 019; the test as the sign of `(f - 2) | -((f + 3) >> 16)`,
        // `f = z >> 14`, without constants: 368 017, 631 074, 411 960,
        // 646 493).
        acc |= w | lim.wrapping_sub(w) | (u32::from(!zin(d)) << 31);
        if let Some(first) = v.first_mut() {
            depth(first, DepthQ30(d));
        }
    }
    acc
}

/// Whether Q2.30 depth `d`, stored as the first value of a vertex
/// (`packed`: as the depth field of a packed grey word, `grey_depth`),
/// passes the small-triangle kernel's vertex depth test (the words' test
/// on the packed word: its field `clamp(d >> 14, 0, 2^16 - 1)` in `2..65533`,
/// exactly `d` in `[2·2^14, 65533·2^14)`; else
/// [`Depth16::vertices_in_range`] of the stored value). Tested on every
/// field's ends.
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
fn kernel_depth_in<P: Profile>(d: i32, packed: bool) -> bool {
    if packed {
        (d.wrapping_sub(2 << 14) as u32) < (65533 - 2) << 14
    } else {
        let z = P::depth_q30(d).fixed_raw().unwrap_or(-1);
        Depth16::vertices_in_range([z; 3])
    }
}

/// The screen word limit `yl·2^16 | xl` of a `width × height` screen
/// with `sub` subpixel bits: `xl = width·2^sub - 2^sub/2` (the last
/// column's centre plus less than half a pixel), `yl = height·2^sub`;
/// `None` unless both are within `0..2^15` (the test of [`on_screen`]
/// needs them there, and the triangle loop's 32-bit sign too).
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn screen_word_limit(width: u32, height: u32, sub: SubpixelBits) -> Option<u32> {
    let s = i64::from(sub.scale());
    let (xl, yl) = (i64::from(width) * s - s / 2, i64::from(height) * s);
    let fits = |v: i64| (0..1 << 15).contains(&v);
    (fits(xl) && fits(yl)).then_some(((yl as u32) << 16) | xl as u32)
}

/// Whether every vertex word `W = y·2^16 | x` (the 16-bit halves of
/// positions `x, y` within ±[`XY_LIMIT`]) ORed into `acc` together with
/// `lim - W` (`lim = yl·2^16 | xl`, [`screen_word_limit`]) lies in `0 <= x
/// <= xl`, `0 <= y <= yl`: exactly when bits 15 and 31 of `acc` are
/// clear. A negative `x` or `y` sets bit 15 or 31 of `W`; otherwise `W =
/// y·2^16 + x` and `lim - W = (yl - y)·2^16 + (xl - x)`, whose low half
/// has bit 15 set exactly when `x > xl` (`xl - x >= -2^15`) and, when not,
/// whose high half is negative exactly when `y > yl`.
#[inline(always)]
fn on_screen(acc: u32) -> bool {
    acc & 0x8000_8000 == 0
}

/// The marks of [`cull_light`] into `xy[0]`: [`EarlyCull::margin`],
/// negative exactly for a skipped vertex (the value itself, not a
/// select: measured 29 -> 21 instructions per vertex on the Cortex-M4).
/// Out of line, the test's constants in registers.
#[inline(never)]
#[allow(clippy::cast_possible_truncation)]
fn mark_vertices(c: EarlyCull, normals: &[[i16; 3]], cones: &[[i32; 2]], xy: &mut [ScreenXy]) {
    let n = normals.len().min(cones.len()).min(xy.len());
    let (normals, cones, xy) = (
        normals.get(..n).unwrap_or_default(),
        cones.get(..n).unwrap_or_default(),
        xy.get_mut(..n).unwrap_or_default(),
    );
    // Two vertices a step, written out (the compiler's own unrolling of
    // the one-vertex loop spilled more: 24 -> 22 instructions per vertex
    // on the Cortex-M4, 3.2 K less on the bunny on both targets; four a
    // step measured 23).
    let pairs = normals.chunks_exact(2).zip(cones.chunks_exact(2));
    for ((a, cone), out) in pairs.zip(xy.chunks_exact_mut(2)) {
        for k in 0..2 {
            // Negative exactly for a skipped vertex (the high half keeps
            // the sign and fits `i16`).
            out[k].0[0] = (c.margin(a[k], cone[k]) >> 16) as i16;
        }
    }
    if n % 2 == 1 {
        if let (Some(a), Some(cone), Some(out)) = (normals.last(), cones.last(), xy.last_mut()) {
            out.0[0] = (c.margin(*a, *cone) >> 16) as i16;
        }
    }
}

/// The first vertex loop of a culled object with culling cones: a
/// vertex whose faces are all certainly back-facing
/// ([`EarlyCull::margin`], on its normal, the cone's axis) is marked
/// [`UNUSED`] in `xy[0]`, every other 0. Then the others are lit
/// (`levels`: the levels of a normal into values `1..S`) in a second
/// loop: fewer constants live in each.
#[inline(always)]
fn cull_light<const S: usize, L>(
    cull: &EarlyCull,
    (normals, cones): (&[[i16; 3]], &[[i32; 2]]),
    xy: &mut [ScreenXy],
    vals: &mut [L],
    levels: Option<&impl Fn([i16; 3]) -> [i32; 3]>,
    level: impl Fn(&mut [L], [i32; 3]),
) {
    mark_vertices(*cull, normals, cones, xy);
    if let Some(l) = levels {
        let verts = normals.iter().zip(xy.iter());
        for ((a, out), v) in verts.zip(vals.chunks_exact_mut(S)) {
            if out.0[0] < 0 {
                continue;
            }
            level(v, l(*a));
        }
    }
}

/// Colour levels in `[0, 255 · 2^16]` rounded to 8 bits.
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn level_rgb(c: [Q16Bits; 3]) -> Rgb8 {
    let q = |Q16Bits(v): Q16Bits| ((v + (1 << 15)) >> 16) as u8;
    Rgb8::new(q(c[0]), q(c[1]), q(c[2]))
}

/// The flat colour of Q1.14 face normal `n` (reversed for a back face)
/// under one light (`grey`: one channel computed).
#[inline(always)]
fn one_color(o: &OneLight, grey: bool, n: [i16; 3], back: bool) -> Rgb8 {
    // Face normals are Q1.14 units: the negation is exact.
    let n = if back { n.map(i16::saturating_neg) } else { n };
    level_rgb(
        if grey {
            [o.at::<true>(n)[0]; 3]
        } else {
            o.at::<false>(n)
        }
        .map(Q16Bits),
    )
}

/// Where an object's bounding sphere lies against the clipping planes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Sphere {
    /// Wholly inside every plane: no outcode, no clipping.
    Inside,
    /// Wholly outside one plane: nothing to draw.
    Outside,
    /// Across a plane (or undecided): outcodes per vertex.
    Across,
}

/// The shade of `obj` under the eye-space `lights` (`None`: too many
/// lights). Not inlined, nor are [`object_light_of`] and [`levels_of`]:
/// their temporaries (several arrays of per-light terms) then take a
/// frame of their own while they run, not room in the object pass's
/// frame under the vertex kernels.
#[inline(never)]
fn shade_of<R: Real>(
    obj: &Object<'_, R>,
    scene: &Scene<'_, '_, R>,
    lights: &[Light<R>],
) -> Option<Shade<R>> {
    Shade::new(
        &obj.material,
        scene.ambient,
        lights,
        scene.specular,
        scene.viewer,
    )
    .ok()
}

/// [`Shade::object_light`], not inlined (see [`shade_of`]).
#[inline(never)]
fn object_light_of<R: Real>(
    shade: &Shade<R>,
    k: &crate::geom::Mat3<R>,
    s: R,
) -> Option<ObjectLight<R>> {
    shade.object_light(k, s)
}

/// [`ObjectLight::levels`], not inlined (see [`shade_of`]).
#[inline(never)]
fn levels_of<R: Real>(q: Raw16<R>, olight: Option<&ObjectLight<R>>) -> Option<LevelLight> {
    olight.and_then(|o| o.levels(q))
}

/// The integer kernels' constants of an object ([`ObjCtx::q16`]: `Q16`
/// only).
struct Q16Consts {
    /// The integer transform (`None`: a scale of 256 or more).
    x: Option<Xform16>,
    /// The integer normal transform (`None` as `x`).
    n: Option<Xform16>,
    /// The integer projection.
    pj: Proj16,
    /// The object-space lights as integer levels, every layout (flat
    /// objects: the face colours; the fused vertex kernel's lighting;
    /// `None` for lights too bright for them).
    levels: Option<LevelLight>,
    /// `levels` of one light (flat objects).
    one: Option<OneLight>,
}

/// Per-object constants while preparing. `repr(C)`: the fields in this
/// order, which the compiler would otherwise choose; the fused vertex
/// kernel's code on the Cortex-M0 was measured to depend on it (bunny
/// Gouraud: 324 225 instructions in `kernel_fused` in this order, 326 328
/// in the compiler's).
#[repr(C)]
struct ObjCtx<'a, 'm, R: Real> {
    mesh: Mesh<'m>,
    /// The mesh's triangles, positions and vertex normals (empty without
    /// normals, or for flat shading).
    tris: &'m [[u16; 3]],
    positions: &'m [[i16; 3]],
    normals: &'m [[i16; 3]],
    mv: Affine<R>,
    /// The normal matrix ([`crate::geom::Mat3::normal_matrix`]).
    nm: Affine<R>,
    shade: &'a Shade<R>,
    /// The integer kernels' constants (`Q16` only: nothing for the other
    /// scalars).
    q16: &'a Only<R, Q16Consts>,
    /// Grey material under white lights: one colour channel computed.
    grey: bool,
    layout: Layout,
    stride: usize,
    cull: bool,
    val_base: usize,
    v_start: usize,
    /// How Phong positions are stored (`render::position`; `None` for
    /// the profiles without a frame).
    pos: Option<&'a PosFrame<R>>,
    /// Directional lights in object space (Gouraud and flat without
    /// point lights or specular term, uniform scale).
    olight: Option<&'a ObjectLight<R>>,
}

impl<R: Real> ObjCtx<'_, '_, R> {
    /// The integer kernels' constants with the raw access: `Some` for
    /// `Q16`, `None` for the other scalars ([`Kernels::get`]: a constant
    /// of the type, so each compiles one arm).
    #[inline(always)]
    fn q16(&self) -> Option<(Raw16<R>, &Q16Consts)> {
        R::Kernels::get(self.q16)
    }
}

impl<P: Profile> Preparer<'_, '_, P> {
    fn cap(&self, part: Part) -> RenderError {
        RenderError::Capacity {
            part,
            object: self.object,
        }
    }

    // Not inlined (one call per object): kept out of the caller, the
    // loops do not change how the caller's own code (e.g. a firmware's
    // band loop) is optimised.
    #[inline(never)]
    fn object_pass(
        &mut self,
        scene: &Scene<'_, '_, P::Real>,
        obj: &Object<'_, P::Real>,
        lights: &[Light<P::Real>],
    ) -> Result<PreparedObject, RenderError> {
        // The shade, the object-space lights and their levels are built
        // out of line (see `shade_of`): their temporaries stay out of
        // this frame, under which the vertex kernels run.
        let shade = shade_of(obj, scene, lights);
        // (Borrowed where it is made: no move to another slot.)
        let Some(shade) = &shade else {
            return Err(SceneError::TooManyLights.into());
        };
        let layout = layout_of(obj, shade, lights);
        let mesh = obj.mesh;
        if layout != Layout::Flat && !mesh.has_normals() {
            return Err(RenderError::MissingNormals {
                object: self.object,
            });
        }
        let mv = scene.camera.view.then_after(&obj.transform);
        let (nm, s, uniform) = mv.m.normal_matrix();
        let nm = Affine {
            m: nm,
            t: Vec3::ZERO,
        };
        let olight = if uniform
            && matches!(
                layout,
                Layout::Flat | Layout::GouraudMono | Layout::GouraudRgb
            ) {
            object_light_of(shade, &nm.m, s)
        } else {
            None
        };
        let frame = P::POSITION_FRAME.then(|| PosFrame::new::<P>(&mesh, &mv));
        let q16 = <P::Real as Real>::Kernels::map(&self.view.fast, |q, pj| {
            let levels = levels_of(q, olight.as_ref());
            Q16Consts {
                x: Xform16::new(q, &mv),
                n: Xform16::new(q, &nm),
                pj: *pj,
                one: match layout {
                    Layout::Flat => levels.as_ref().and_then(LevelLight::one),
                    _ => None,
                },
                levels,
            }
        });
        let ctx = ObjCtx {
            mesh,
            tris: mesh.triangles(),
            positions: mesh.positions(),
            normals: match layout {
                Layout::Flat => &[],
                _ => mesh.vertex_normals().unwrap_or(&[]),
            },
            q16: &q16,
            pos: frame.as_ref(),
            mv,
            nm,
            shade,
            olight: olight.as_ref(),
            grey: {
                let grey = |c: Vec3<P::Real>| c.x == c.y && c.y == c.z;
                grey(obj.material.color) && lights.iter().all(|l| grey(l.color))
            },
            layout,
            stride: layout.values_in::<P>(),
            cull: obj.cull_backfaces,
            val_base: self.nval,
            v_start: self.nv,
        };
        let t_start = self.nt;
        self.t_start = t_start;
        self.made_start = t_start + mesh.triangle_count();
        let made_base = self.nm;
        let color_base = self.nc;
        self.on_screen = false;
        self.fit = false;
        self.rows = None;
        self.marked = false;
        let (place, reach, radius) = placement(&self.view.planes, &mesh, &ctx.mv);
        // Beyond half the scalar's range, an eye-space coordinate or a
        // difference of two (clipping) could saturate and silently move
        // the object: refuse it.
        let limit = P::Real::MAX.half();
        // (An empty screen draws nothing: its guard band is unbounded.)
        let place = if self.width == 0 || self.height == 0 {
            Sphere::Outside
        } else {
            place
        };
        if place != Sphere::Outside && reach >= limit {
            return Err(RenderError::OutOfRange {
                object: self.object,
                limit: i64::from(limit.to_fixed_i32(0)),
            });
        }
        // A clipped vertex lies on an edge at a parameter rounded to the
        // scalar's resolution `ε`: off by up to `|edge|·ε/2` units, which
        // next to the near plane is `|edge|·ε·k / (2·near)` pixels. Keep
        // it within a pixel: objects the planes cut may be at most
        // `2·near / (ε·k)` units across (`Q16`, 240 rows at 45°, near 1:
        // 452 units; `f32`: 2.8·10^7·near / k).
        let across =
            (self.view.planes.near + self.view.planes.near).div(P::Real::EPSILON * self.view.k);
        if place == Sphere::Across && radius + radius >= across {
            return Err(RenderError::OutOfRange {
                object: self.object,
                limit: i64::from(across.to_fixed_i32(0)),
            });
        }
        if place != Sphere::Outside {
            // A number for each mesh triangle (and one per triangle made).
            if self.made_start > self.ws.faces.len() {
                return Err(self.cap(Part::Triangles));
            }
            self.nt = self.made_start;
            if place == Sphere::Inside && !P::PERSPECTIVE {
                self.vertex_pass_fast(&ctx)?;
            } else {
                self.vertex_pass(&ctx, place == Sphere::Inside)?;
            }
            if place == Sphere::Inside {
                self.triangle_pass::<true>(&ctx)?;
            } else {
                self.triangle_pass::<false>(&ctx)?;
            }
        }
        // An object that keeps no triangle takes no number.
        let faces = self.ws.faces.get(t_start..self.nt).unwrap_or(&[]);
        let any = faces.iter().any(|&b| b & FACE_ROW != 0);
        if !any {
            self.rows = None;
            self.nt = t_start;
            self.made_start = t_start;
        }
        let tris = t_start..self.nt;
        let rows = match self.rows {
            Some(rows) => rows,
            None => self.rows_of_tris(&ctx, tris.clone()),
        };
        if layout == Layout::Flat {
            self.nc = color_base + tris.len();
        }
        // Vertices below `MAX_VERTICES` (2^15), values below 8 per
        // vertex (2^18), triangle numbers, made triangles and colours
        // below `MAX_TRIANGLES` (the workspace's parts are cut to it), at
        // most `MAX_OBJECTS` (32) objects: every index fits.
        let mut po = PreparedObject::new(
            layout,
            ctx.stride,
            ctx.val_base,
            self.object,
            ctx.v_start as u16..self.nv as u16,
            tris.start as u16..tris.end as u16,
            made_base as u16,
            color_base as u16,
            if rows[0] < rows[1] { rows } else { [0; 2] },
        );
        if self.fit {
            po.set_kernel_fit();
        }
        Ok(po)
    }

    /// The eye-space position of mesh vertex `i`.
    #[inline(always)]
    fn eye_pos(ctx: &ObjCtx<'_, '_, P::Real>, i: usize) -> Vec3<P::Real> {
        let pos = ctx.positions.get(i).copied().unwrap_or([0; 3]);
        match ctx.q16().and_then(|(_, c)| c.x.as_ref()) {
            Some(x) => from_raw3(x.point(pos).map(Q16Bits)),
            None => ctx.mv.point(Vec3::from_q14(pos)),
        }
    }

    /// The eye-space unit normal of Q1.14 object normal `raw`, by the
    /// normal matrix.
    #[inline]
    fn eye_normal(ctx: &ObjCtx<'_, '_, P::Real>, raw: [i16; 3], flip: bool) -> Vec3<P::Real> {
        let n = match ctx.q16().and_then(|(_, c)| c.n.as_ref()) {
            Some(x) => from_raw3(approx16::unit(x.vector(raw)).map(Q16Bits)),
            None => ctx.nm.vector(Vec3::from_q14(raw)).normalize(),
        };
        if flip {
            -n
        } else {
            n
        }
    }

    /// The attributes of mesh vertex `i` at eye-space `pos`: its colour
    /// (Gouraud) or its eye-space normal (Phong); zero for flat.
    #[inline]
    fn attrs(
        ctx: &ObjCtx<'_, '_, P::Real>,
        i: usize,
        pos: Vec3<P::Real>,
        flip: bool,
    ) -> [P::Real; CLIP_ATTRS] {
        if ctx.layout == Layout::Flat {
            return [P::Real::ZERO; CLIP_ATTRS];
        }
        let raw = ctx.normals.get(i).copied().unwrap_or([0; 3]);
        let v = match ctx.layout {
            Layout::GouraudMono | Layout::GouraudRgb => match &ctx.olight {
                Some(ol) => ol.at(raw, flip, ctx.layout == Layout::GouraudMono),
                None => ctx.shade.at(Self::eye_normal(ctx, raw, flip), pos),
            },
            _ => Self::eye_normal(ctx, raw, flip),
        };
        [v.x, v.y, v.z]
    }

    /// The eye-space vertex of mesh vertex `i`, lit or with its normal.
    fn clip_vert(ctx: &ObjCtx<'_, '_, P::Real>, i: usize, flip: bool) -> ClipVert<P::Real> {
        let pos = Self::eye_pos(ctx, i);
        ClipVert {
            pos,
            attrs: Self::attrs(ctx, i, pos, flip),
        }
    }

    /// One linear pass over the mesh's vertices: transform, outcode
    /// (unless the whole object is `inside`), project, light. Prepared
    /// vertex `v_start + i` is mesh vertex `i`. Every vertex is lit, also
    /// those only culled triangles use: in object space a directional
    /// light costs three multiply-adds per vertex, less than marking and
    /// testing the corners of the kept triangles (see the module docs).
    #[inline(never)]
    fn vertex_pass(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        inside: bool,
    ) -> Result<(), RenderError> {
        let n = ctx.positions.len();
        let stride = ctx.layout.values_in::<P>();
        let end = ctx.v_start + n;
        if end >= MAX_VERTICES || end > self.ws.xy.len() {
            return Err(self.cap(Part::Vertices));
        }
        if ctx.val_base + n * stride > self.ws.vals.len() {
            return Err(self.cap(Part::Values));
        }
        for i in 0..n {
            let pos = Self::eye_pos(ctx, i);
            let code = if inside { 0 } else { self.view.outcode(pos) };
            let base = ctx.val_base + i * stride;
            let v = ctx.v_start + i;
            if code != 0 {
                // Outside: never drawn directly; triangles using it are
                // clipped.
                if let Some(xy) = self.ws.xy.get_mut(v) {
                    *xy = ScreenXy([OUTSIDE, i16::from(code)]);
                }
                if let Some(vals) = self.ws.vals.get_mut(base..base + stride) {
                    vals.fill(P::level(P::Real::ZERO));
                }
                continue;
            }
            let cv = ClipVert {
                pos,
                attrs: Self::attrs(ctx, i, pos, false),
            };
            self.store(ctx, v, base, &cv);
        }
        self.nv = end;
        self.nval = ctx.val_base + n * stride;
        Ok(())
    }

    /// [`Preparer::vertex_pass`] for an object wholly inside the planes,
    /// affine: the `Q16` kernels for flat and object-space-lit Gouraud
    /// objects in a loop per layout (no per-vertex dispatch, no bounds
    /// check but the slices'), the generic pass otherwise. The fused
    /// kernel ([`Fused`], when it can bound the object's error) places
    /// vertices within 3/4 subpixel of the exact projection (1/2 of it
    /// the rounding to the grid) and lights with [`LevelLight`]; otherwise the exact-rounding kernel
    /// gives the same values as the generic pass, bit for bit.
    fn vertex_pass_fast(&mut self, ctx: &ObjCtx<'_, '_, P::Real>) -> Result<(), RenderError> {
        match ctx.q16() {
            // (The transform borrowed, not copied: a copy takes a stack
            // slot.)
            Some((_, Q16Consts { x: Some(x), pj, .. })) => self.vertex_pass_q16(ctx, x, *pj),
            _ => self.vertex_pass(ctx, true),
        }
    }

    /// [`Preparer::vertex_pass_fast`] with the object's integer transform
    /// `x` and projection `pj`.
    #[inline(always)]
    fn vertex_pass_q16(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        x: &Xform16,
        pj: Proj16,
    ) -> Result<(), RenderError> {
        let packed = ctx.layout.packed_in::<P>();
        let (m, t) = x.parts();
        let fused = Fused::new(
            m,
            t,
            &pj,
            P::SUBPIXEL_BITS.get(),
            self.view.depth_scale.map(|s| s.to_fixed_i32(16)),
            &ctx.mesh.bound(),
        );
        if let Some(f) = &fused {
            // (One normal per vertex: the kernel zips them.)
            let levels = ctx
                .q16()
                .and_then(|(_, c)| c.levels.as_ref())
                .filter(|_| ctx.normals.len() == ctx.positions.len());
            let one = levels.and_then(LevelLight::one);
            // Back faces decided in object space (culled objects with
            // baked culling cones, not mirrored, large enough to pay for
            // the set-up), computed only for the layouts that use it.
            let early = || match (ctx.cull, ctx.mesh.vertex_cones()) {
                (true, Some(c)) if c.len() >= EARLY_CULL_MIN_VERTICES => EarlyCull::new(
                    m,
                    t,
                    pj.k,
                    P::SUBPIXEL_BITS.get(),
                    &ctx.mesh.bound(),
                    f.err16,
                ),
                _ => None,
            };
            // Normals checked by `Mesh::with_vertex_cones` (`|n|² <=
            // MAX_AXIS2`) under a light that keeps the clamps idle.
            let bounded = ctx.mesh.vertex_cones().is_some()
                && one.as_ref().is_some_and(|o| o.bounded(MAX_AXIS2));
            // Set up once, for exactly the layouts of the arms below (a
            // flat object, or a Gouraud one with levels: `one` implies
            // `levels`): one result in this frame, not one per arm.
            let fused_arm = match ctx.layout {
                Layout::Flat => true,
                Layout::GouraudMono | Layout::GouraudRgb => levels.is_some(),
                _ => false,
            };
            let e = if fused_arm { early() } else { None };
            match (ctx.layout, &levels, one) {
                (Layout::GouraudMono, _, Some(o)) if bounded => {
                    let l = Some(|n| o.at_bounded::<true>(n));
                    return if packed {
                        self.kernel_fused::<1, true>(ctx, f, l, e.as_ref())
                    } else {
                        self.kernel_fused::<2, false>(ctx, f, l, e.as_ref())
                    };
                }
                (Layout::GouraudRgb, _, Some(o)) if bounded => {
                    let l = Some(|n| o.at_bounded::<false>(n));
                    return self.kernel_fused::<4, false>(ctx, f, l, e.as_ref());
                }
                (Layout::Flat, _, _) => {
                    return self.kernel_fused::<1, false>(ctx, f, None::<fn(_) -> _>, e.as_ref());
                }
                (Layout::GouraudMono, _, Some(o)) => {
                    let l = Some(|n| o.at::<true>(n));
                    return if packed {
                        self.kernel_fused::<1, true>(ctx, f, l, e.as_ref())
                    } else {
                        self.kernel_fused::<2, false>(ctx, f, l, e.as_ref())
                    };
                }
                (Layout::GouraudMono, Some(l), None) => {
                    let l = Some(|n| l.at::<true>(n));
                    return if packed {
                        self.kernel_fused::<1, true>(ctx, f, l, e.as_ref())
                    } else {
                        self.kernel_fused::<2, false>(ctx, f, l, e.as_ref())
                    };
                }
                (Layout::GouraudRgb, _, Some(o)) => {
                    return self.kernel_fused::<4, false>(
                        ctx,
                        f,
                        Some(|n| o.at::<false>(n)),
                        e.as_ref(),
                    );
                }
                (Layout::GouraudRgb, Some(l), None) => {
                    return self.kernel_fused::<4, false>(
                        ctx,
                        f,
                        Some(|n| l.at::<false>(n)),
                        e.as_ref(),
                    );
                }
                _ => {}
            }
        }
        match (ctx.layout, &ctx.olight) {
            (Layout::Flat, _) => self.kernel_q16::<1>(ctx, x, &pj, None),
            (Layout::GouraudMono, Some(ol)) if packed => {
                self.kernel_q16::<1>(ctx, x, &pj, Some(*ol))
            }
            (Layout::GouraudMono, Some(ol)) => self.kernel_q16::<2>(ctx, x, &pj, Some(*ol)),
            (Layout::GouraudRgb, Some(ol)) => self.kernel_q16::<4>(ctx, x, &pj, Some(*ol)),
            _ => self.vertex_pass(ctx, true),
        }
    }

    /// The object's `n` vertices' slots in the workspace of object
    /// `object`: `(n, end, screen positions, values)`, `S` values per
    /// vertex from `ctx.val_base`, the vertices `ctx.v_start..end`; a
    /// capacity error naming the part that is too short.
    #[inline(always)]
    #[allow(clippy::type_complexity)]
    fn vertex_slots<'s, const S: usize>(
        ws: &'s mut Workspace<'_, P::Lerp>,
        ctx: &ObjCtx<'_, '_, P::Real>,
        object: usize,
    ) -> Result<(usize, usize, &'s mut [ScreenXy], &'s mut [P::Lerp]), RenderError> {
        let cap = |part| RenderError::Capacity { part, object };
        let n = ctx.positions.len();
        let end = ctx.v_start + n;
        if end >= MAX_VERTICES {
            return Err(cap(Part::Vertices));
        }
        let Some(xy) = ws.xy.get_mut(ctx.v_start..end) else {
            return Err(cap(Part::Vertices));
        };
        let Some(vals) = ws.vals.get_mut(ctx.val_base..ctx.val_base + n * S) else {
            return Err(cap(Part::Values));
        };
        Ok((n, end, xy, vals))
    }

    /// The vertex loop of [`Preparer::vertex_pass_fast`] with the fused
    /// integer kernel ([`Fused`]) for a layout of `S` values per vertex
    /// (1 flat or packed grey, 2 grey, 4 RGB), lit by `levels` (colour
    /// levels of a normal); `PACK`: depth and grey level packed in one
    /// value ([`Layout::packed_in`]). Records whether every vertex lies
    /// on the screen ([`on_screen`]).
    #[inline(never)]
    fn kernel_fused<const S: usize, const PACK: bool>(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        f: &Fused,
        levels: Option<impl Fn([i16; 3]) -> [i32; 3]>,
        early: Option<&EarlyCull>,
    ) -> Result<(), RenderError> {
        let (n, end, xy, vals) = Self::vertex_slots::<S>(&mut self.ws, ctx, self.object)?;
        // Two loops (positions, then normals): fewer constants live at
        // once, fewer spills (measured: 136 -> 127 instructions per vertex
        // on the Cortex-M4).
        // Vertices whose faces are all certainly back-facing are skipped.
        let culled = match (early, ctx.mesh.vertex_normals(), ctx.mesh.vertex_cones()) {
            (Some(c), Some(normals), Some(cones)) => Some((c, normals, cones)),
            _ => None,
        };
        // Packed grey ([`Layout::packed_in`], `S == 1`): the level in the
        // low half of the one value, the depth ORed into its high half
        // (after the levels of the marked pass) or stored (before the
        // levels of the unmarked one).
        let pack = PACK && S == 1 && levels.is_some();
        let raw = |v: P::Lerp| v.fixed_raw().unwrap_or(0);
        let marked = culled.is_some();
        if let Some((c, normals, cones)) = culled {
            // The vertex normal is the cone's axis, and the normal lit.
            let level = |v: &mut [P::Lerp], lv: [i32; 3]| {
                if pack {
                    if let Some(d) = v.first_mut() {
                        *d = P::Lerp::from_fixed_raw(super::grey_level(lv[0]));
                    }
                } else {
                    for (d, x) in v.iter_mut().skip(1).zip(lv) {
                        *d = P::level_q16(x);
                    }
                }
            };
            cull_light::<S, _>(c, (normals, cones), xy, vals, levels.as_ref(), level);
        }
        let pos = ctx.positions;
        let depth = |v: &mut P::Lerp, DepthQ30(d)| {
            *v = match (pack, marked) {
                (true, true) => P::Lerp::from_fixed_raw(raw(*v) | super::grey_depth(d)),
                (true, false) => P::Lerp::from_fixed_raw(super::grey_depth(d)),
                _ => P::depth_q30(d),
            };
        };
        let o = xy_origin::<P>(self.width, self.height);
        let lim = screen_word_limit(self.width, self.height, P::SUBPIXEL_BITS);
        let xy = (xy, o, lim.unwrap_or(0));
        // Every projected depth within the small-triangle kernel's vertex
        // test ([`kernel_depth_in`]).
        let zin = |d: i32| kernel_depth_in::<P>(d, pack);
        let acc = match (f.depth_in_range, marked) {
            (true, false) => project_loop::<false, false, S, _>(f, pos, xy, vals, depth, zin),
            (false, false) => project_loop::<false, true, S, _>(f, pos, xy, vals, depth, zin),
            (true, true) => project_loop::<true, false, S, _>(f, pos, xy, vals, depth, zin),
            (false, true) => project_loop::<true, true, S, _>(f, pos, xy, vals, depth, zin),
        };
        if let (false, Some(l)) = (marked, levels) {
            for (v, nrm) in vals.chunks_exact_mut(S).zip(ctx.normals) {
                let c = l(*nrm);
                if pack {
                    if let Some(d) = v.first_mut() {
                        *d = P::Lerp::from_fixed_raw(raw(*d) | super::grey_level(c[0]));
                    }
                } else {
                    for (d, c) in v.iter_mut().skip(1).zip(c) {
                        *d = P::level_q16(c);
                    }
                }
            }
        }
        // The triangle loop over the screen's box reads positions stored
        // from the screen's corner.
        self.on_screen = lim.is_some() && on_screen(acc) && o == Subpx([0, 0]);
        self.marked = marked;
        self.nv = end;
        self.nval = ctx.val_base + n * S;
        Ok(())
    }

    /// The vertex loop of [`Preparer::vertex_pass_fast`] for a layout of
    /// `S` values per vertex (1 flat, 2 grey, 4 RGB).
    #[inline(never)]
    fn kernel_q16<const S: usize>(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        x: &Xform16,
        pj: &Proj16,
        ol: Option<&ObjectLight<P::Real>>,
    ) -> Result<(), RenderError> {
        type R<P> = <P as Profile>::Real;
        let (n, end, xy, vals) = Self::vertex_slots::<S>(&mut self.ws, ctx, self.object)?;
        let sub = P::SUBPIXEL_BITS.get();
        let scale = self.view.depth_scale;
        // The depth scale `far / (far - near)` as raw Q16 when at most 2
        // (far at least twice near): `mul16_small`'s range.
        let scale_small = scale
            .map(|s| s.to_fixed_i32(16))
            .filter(|s| s.unsigned_abs() <= SMALL);
        let normals = ctx.normals;
        let o = xy_origin::<P>(self.width, self.height);
        for (i, ((p, out), v)) in ctx
            .positions
            .iter()
            .zip(xy.iter_mut())
            .zip(vals.chunks_exact_mut(S))
            .enumerate()
        {
            let (s, q) = pj.project_inside(x.point(*p), sub);
            // Inside the guard band: within `±XY_LIMIT` of the origin.
            *out = ScreenXy::pack(Subpx(s), o);
            let d = R::<P>::ONE - R::<P>::from_fixed_i32(q, 16);
            let d = match scale_small {
                // `Q16`'s `*` in 32-bit products, bit for bit (`d <= 1`).
                Some(s) => R::<P>::from_fixed_i32(mul16_small(d.to_fixed_i32(16), s), 16),
                None => scale.map_or(d, |s| d * s),
            };
            v[0] = P::depth(d.clamp(R::<P>::ZERO, R::<P>::ONE));
            if let Some(ol) = ol {
                let nrm = normals.get(i).copied().unwrap_or([0; 3]);
                let c = ol.at(nrm, false, S <= 2);
                if S == 1 {
                    // Packed grey ([`Layout::packed_in`]).
                    let raw = |v: P::Lerp| v.fixed_raw().unwrap_or(0);
                    let p = super::pack_grey(raw(v[0]), raw(P::level(c.x)));
                    v[0] = P::Lerp::from_fixed_raw(p);
                }
                for (d, c) in v.iter_mut().skip(1).zip([c.x, c.y, c.z]) {
                    *d = P::level(c);
                }
            }
        }
        self.nv = end;
        self.nval = ctx.val_base + n * S;
        Ok(())
    }

    /// The subpixel position, depth and perspective weight of eye-space
    /// point `p` by the integer projection (`Q16`), clamped to the
    /// rasterizer's range.
    #[inline(always)]
    fn project_q16(
        &self,
        q16: Raw16<P::Real>,
        pj: &Proj16,
        p: Vec3<P::Real>,
    ) -> ([i32; 2], P::Real, P::Real) {
        let (xy, q) = pj.project(raw3(p).map(|Q16Bits(b)| b), P::SUBPIXEL_BITS.get());
        let q = q16.from_raw(q);
        let d = P::Real::ONE - q;
        // `*`, inlined (`*=` measured as a call on the M0).
        let d = self.view.depth_scale.map_or(d, |s| d * s);
        (xy, d.clamp(P::Real::ZERO, P::Real::ONE), q)
    }

    /// [`Preparer::project_q16`] by the scalar's own operations.
    #[inline(always)]
    fn project(&self, p: Vec3<P::Real>) -> ([i32; 2], P::Real, P::Real) {
        let sub = P::SUBPIXEL_BITS.get();
        let (sx, sy, d, q) = self.view.project(p);
        // Clipping keeps a corner within the guard band, but saturated
        // fixed-point arithmetic or float precision lost on huge
        // coordinates can move a clipped corner out of the rasterizer's
        // range: clamp to it (NaN to its lower end) rather than have the
        // rasterizer refuse the whole frame. No-op for in-range corners.
        let lim = P::Real::from_i32(COORD_LIMIT_PX);
        let (sx, sy) = (sx.clamp(-lim, lim), sy.clamp(-lim, lim));
        ([sx.to_fixed_i32(sub), sy.to_fixed_i32(sub)], d, q)
    }

    /// Projects and stores an eye-space vertex inside the planes as
    /// prepared vertex `v` with values at `base` (both in range).
    #[inline(always)]
    fn store(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        v: usize,
        base: usize,
        cv: &ClipVert<P::Real>,
    ) {
        // `ctx.stride`, recomputed so the optimiser sees `stride >= 1`.
        let stride = ctx.layout.values_in::<P>();
        let (xy, d, q) = match ctx.q16() {
            Some((q16, c)) => self.project_q16(q16, &c.pj, cv.pos),
            None => self.project(cv.pos),
        };
        let o = self.origin();
        if let Some(slot) = self.ws.xy.get_mut(v) {
            *slot = ScreenXy::pack_clamped(Subpx(xy), o);
        }
        let Some(vals) = self.ws.vals.get_mut(base..base + stride) else {
            return;
        };
        if ctx.layout.packed_in::<P>() {
            let raw = |v: P::Lerp| v.fixed_raw().unwrap_or(0);
            let l = raw(P::level(cv.attrs[0]));
            vals[0] = P::Lerp::from_fixed_raw(super::pack_grey(raw(P::depth(d)), l));
            return;
        }
        vals[0] = P::depth(d);
        let mut a = cv.attrs;
        let mut pos = cv.pos;
        if P::PERSPECTIVE && ctx.layout != Layout::Flat {
            // Interpolate a·q and q, both affine in screen space.
            a = a.map(|v| v * q);
            pos = pos.scale(q);
            vals[stride - 1] = P::unit(q);
        }
        match ctx.layout {
            Layout::Flat => {}
            Layout::GouraudMono => {
                for (v, x) in vals.iter_mut().skip(1).zip([a[0]]) {
                    *v = P::level(x);
                }
            }
            Layout::GouraudRgb => {
                for (v, x) in vals.iter_mut().skip(1).zip(a) {
                    *v = P::level(x);
                }
            }
            Layout::PhongNormal | Layout::PhongPosition => {
                for (v, x) in vals.iter_mut().skip(1).zip(a) {
                    *v = P::unit(x);
                }
                if ctx.layout == Layout::PhongPosition {
                    let p = PosFrame::store::<P>(ctx.pos, pos);
                    for (v, x) in vals.iter_mut().skip(4).zip(p) {
                        *v = x;
                    }
                }
            }
        }
    }

    /// Appends a prepared vertex for an eye-space vertex inside the planes
    /// (clipping and two-sided back faces).
    fn emit(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        cv: &ClipVert<P::Real>,
    ) -> Result<u16, RenderError> {
        let i = self.nv;
        if i >= MAX_VERTICES || i >= self.ws.xy.len() {
            return Err(self.cap(Part::Vertices));
        }
        let stride = ctx.layout.values_in::<P>();
        let base = ctx.val_base + (i - ctx.v_start) * stride;
        if base + stride > self.ws.vals.len() {
            return Err(self.cap(Part::Values));
        }
        self.store(ctx, i, base, cv);
        self.nv += 1;
        self.nval = base + stride;
        // i < MAX_VERTICES: fits.
        Ok(i as u16)
    }

    /// Keeps the made triangle of vertices `v` when it can cover a pixel
    /// centre of the screen (`color`: its colour when flat).
    fn push_tri(
        &mut self,
        v: [u16; 3],
        color: Option<Rgb8>,
        back: bool,
    ) -> Result<(), RenderError> {
        let xy = v.map(|v| self.xy(usize::from(v)));
        match self.rows_of(xy) {
            Some(rows) => self.store_made(v, color, back, rows[0]),
            None => Ok(()),
        }
    }

    /// The rows of the kept triangles numbered `tris` (the union of the
    /// rows each can cover; `[u16::MAX, 0]` for none).
    fn rows_of_tris(
        &self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        tris: core::ops::Range<usize>,
    ) -> [u16; 2] {
        let xy = &*self.ws.xy;
        let o = self.origin();
        let (sub, h) = (
            P::SUBPIXEL_BITS,
            self.height.min(u32::from(u16::MAX)) as i32,
        );
        let mut lo = i32::MAX;
        let mut hi = i32::MIN;
        let faces = self.ws.faces.get(tris.clone()).unwrap_or(&[]);
        for (i, f) in tris.zip(faces) {
            if f & FACE_ROW == 0 {
                continue;
            }
            let v = match i.checked_sub(self.made_start) {
                // Mesh triangles: base + index < MAX_VERTICES.
                None => ctx
                    .tris
                    .get(i - self.t_start)
                    .map_or([0; 3], |t| t.map(|x| (ctx.v_start + usize::from(x)) as u16)),
                Some(m) => self
                    .ws
                    .tris
                    .get(m + self.nm - (self.nt - self.made_start))
                    .map_or([0; 3], |t| t.v()),
            };
            let y = v.map(|v| xy.get(usize::from(v)).map_or(0, |p| p.unpack(o).0[1]));
            lo = lo.min(y[0].min(y[1]).min(y[2]));
            hi = hi.max(y[0].max(y[1]).max(y[2]));
        }
        if lo > hi {
            return [u16::MAX, 0];
        }
        // `first_row` is monotonic: the rows of the extreme `y`s, clamped
        // as each triangle's are (`max`/`min`: no panic branch).
        let r = |y: i32| first_row(y, sub).max(0).min(h) as u16;
        [r(lo), r(hi)]
    }

    /// The origin of the stored screen positions ([`xy_origin`]).
    #[inline(always)]
    fn origin(&self) -> Subpx {
        xy_origin::<P>(self.width, self.height)
    }

    /// Screen position of prepared vertex `v`, subpixels from the screen's
    /// corner (`[0, 0]` past the end).
    #[inline(always)]
    fn xy(&self, v: usize) -> Subpx {
        self.ws
            .xy
            .get(v)
            .map_or(Subpx([0; 2]), |p| p.unpack(self.origin()))
    }

    /// The rows a triangle with corners at `xy` can cover (the rows the
    /// rasterizer would visit), or `None` when it covers no pixel centre
    /// of the screen.
    #[inline(always)]
    fn rows_of(&self, xy: [Subpx; 3]) -> Option<[u16; 2]> {
        rows_in(xy, self.width, self.height, P::SUBPIXEL_BITS)
    }

    /// Marks triangle number `i` kept (a back face or not, first row
    /// `row`), with its colour when `color` is given (a flat object's).
    #[inline(always)]
    fn keep(
        &mut self,
        i: usize,
        color: Option<Rgb8>,
        back: bool,
        row: u16,
    ) -> Result<(), RenderError> {
        let q = face_shift(self.height);
        let Some(face) = self.ws.faces.get_mut(i) else {
            return Err(self.cap(Part::Triangles));
        };
        *face = face_byte(u32::from(row), q, back);
        let c = &mut self.face_rows[usize::from(*face & FACE_ROW)];
        *c = c.wrapping_add(1);
        if let Some(color) = color {
            let c = self.nc + (i - self.t_start);
            let Some(c) = self.ws.colors.get_mut(c) else {
                return Err(self.cap(Part::Colors));
            };
            *c = color;
        }
        Ok(())
    }

    /// Appends a made triangle (numbered after the object's mesh
    /// triangles and the triangles it made before), kept.
    #[inline(always)]
    fn store_made(
        &mut self,
        v: [u16; 3],
        color: Option<Rgb8>,
        back: bool,
        row: u16,
    ) -> Result<(), RenderError> {
        let Some(slot) = self.ws.tris.get_mut(self.nm) else {
            return Err(self.cap(Part::Made));
        };
        *slot = Tri::new(v, back);
        let i = self.nt;
        self.keep(i, color, back, row)?;
        self.nm += 1;
        self.nt += 1;
        Ok(())
    }

    /// Flat colour of triangle `t`: its face normal (baked with the mesh,
    /// or the exact integer cross product in model space) lit once, in
    /// object space for directional lights (as integer levels for `Q16`,
    /// [`LevelLight`]), else in eye space at the centroid.
    #[inline]
    fn flat_color(ctx: &ObjCtx<'_, '_, P::Real>, t: usize, back: bool) -> Rgb8 {
        if ctx.layout != Layout::Flat {
            return Rgb8::BLACK;
        }
        let n = match ctx.mesh.face_normals() {
            Some(f) => f.get(t).copied().unwrap_or([0; 3]),
            None => {
                let pos = ctx.mesh.triangle_positions(t).unwrap_or([[0; 3]; 3]);
                face_normal_q14(pos[0], pos[1], pos[2])
            }
        };
        if let Some((_, c)) = ctx.q16() {
            if let Some(o) = &c.one {
                return one_color(o, ctx.grey, n, back);
            }
            if let Some(l) = &c.levels {
                // Face normals are Q1.14 units: the negation is exact.
                let n = if back { n.map(i16::saturating_neg) } else { n };
                let c = if ctx.grey {
                    [l.at::<true>(n)[0]; 3]
                } else {
                    l.at::<false>(n)
                };
                return level_rgb(c.map(Q16Bits));
            }
        }
        let col = match &ctx.olight {
            Some(ol) => ol.at(n, back, ctx.grey),
            None => {
                // The centroid only when the lighting depends on the
                // position.
                let c = if ctx.shade.uses_position() {
                    let vs = ctx.tris.get(t).copied().unwrap_or([0; 3]);
                    let e = vs.map(|v| Self::eye_pos(ctx, usize::from(v)));
                    let third = P::Real::from_ratio(1, 3);
                    let big = e.iter().any(|p| {
                        p.x.abs().max(p.y.abs()).max(p.z.abs())
                            >= P::Real::MAX.div(P::Real::from_i32(4))
                    });
                    if big {
                        // A sum that could saturate: scaled term by term.
                        e[0].scale(third) + e[1].scale(third) + e[2].scale(third)
                    } else {
                        (e[0] + e[1] + e[2]).scale(third)
                    }
                } else {
                    Vec3::ZERO
                };
                let n = match ctx.q16().and_then(|(_, c)| c.n.as_ref()) {
                    Some(x) => from_raw3::<P::Real>(x.vector(n).map(Q16Bits)).normalize_geom(),
                    None => ctx.nm.vector(Vec3::from_q14(n)).normalize(),
                };
                ctx.shade.at(if back { -n } else { n }, c)
            }
        };
        Rgb8::new(col.x.to_level(), col.y.to_level(), col.z.to_level())
    }

    /// The triangles of the object, over the prepared vertices of the
    /// vertex pass. `INSIDE`: every vertex is inside the planes (no
    /// outcode to test).
    #[inline(never)]
    fn triangle_pass<const INSIDE: bool>(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
    ) -> Result<(), RenderError> {
        let base = ctx.v_start;
        let gouraud = matches!(ctx.layout, Layout::GouraudMono | Layout::GouraudRgb);
        if INSIDE && (ctx.cull || !gouraud) {
            let flat = ctx.layout == Layout::Flat;
            let xy = self.ws.xy.get(base..self.nv).unwrap_or(&[]);
            let sub = P::SUBPIXEL_BITS;
            // Every vertex within the screen (x up to the last column's
            // centre plus less than half a pixel), and every edge shorter
            // than 2^15 subpixels: the row range needs no clamp, the
            // column test always passes, and the sign fits 32 bits.
            // (The vertex kernel's test, [`on_screen`] within
            // [`screen_word_limit`].)
            let visible = self.on_screen;
            // (Marked vertices only on culled objects.)
            let (origin, marked) = (self.origin(), self.marked && ctx.cull);
            let q = face_shift(self.height);
            // The mesh triangles' bytes (their room checked by the
            // caller) and, flat, colours.
            let t0 = self.t_start;
            let faces = self
                .ws
                .faces
                .get_mut(t0..t0 + ctx.tris.len())
                .unwrap_or_default();
            let cs = self.ws.colors.get_mut(self.nc..).unwrap_or_default();
            if flat && cs.len() < ctx.tris.len() {
                return Err(self.cap(Part::Colors));
            }
            if visible {
                let col = |t, back| Self::flat_color(ctx, t, back);
                // Stores the colour of kept triangle `t` into `cs`.
                fn put<'a>(
                    cs: &'a mut [Rgb8],
                    mut col: impl FnMut(usize, bool) -> Rgb8 + 'a,
                ) -> impl FnMut(usize, (), bool) -> bool + 'a {
                    move |t, (), back| {
                        let c = col(t, back);
                        cs.get_mut(t).map(|s| *s = c).is_some()
                    }
                }
                let tris = ctx.tris;
                // Baked face normals under one light: the colour inline
                // (the same as `flat_color`), the normals and colour slots
                // zipped with the triangles (as many: checked here).
                let one = ctx.q16().and_then(|(_, c)| c.one);
                let one = match (flat, one, ctx.mesh.face_normals()) {
                    (true, Some(o), Some(normals)) if normals.len() == tris.len() => {
                        Some((o, normals))
                    }
                    _ => None,
                };
                let grey = ctx.grey;
                let none = |_, (), _| true;
                let all = || core::iter::repeat(());
                let counts = &mut *self.face_rows;
                let fc = (faces, counts);
                let sq = (sub, q);
                // One call of the pass per (cull, marked) pair and per
                // colour hook (their types differ).
                macro_rules! visible {
                    ($cull:literal, $marked:literal, $aux:expr, $hook:expr) => {
                        triangles_visible::<$cull, $marked, _>(tris, xy, fc, sq, $aux, $hook)
                    };
                }
                let kept = match (ctx.cull, flat, one) {
                    (true, true, Some((o, normals))) => {
                        let aux = normals.iter().zip(cs.iter_mut());
                        // The colour of a kept face (front: culled).
                        fn lit<const GREY: bool>(
                            o: OneLight,
                        ) -> impl FnMut(usize, (&[i16; 3], &mut Rgb8), bool) -> bool
                        {
                            move |_, (n, slot), back| {
                                *slot = one_color(&o, GREY, *n, back);
                                true
                            }
                        }
                        match (grey, marked) {
                            (true, true) => visible!(true, true, aux, lit::<true>(o)),
                            (true, false) => visible!(true, false, aux, lit::<true>(o)),
                            (false, true) => visible!(true, true, aux, lit::<false>(o)),
                            (false, false) => visible!(true, false, aux, lit::<false>(o)),
                        }
                    }
                    (cull, flat, _) => match (cull, flat, marked) {
                        (true, true, false) => visible!(true, false, all(), put(cs, col)),
                        (true, true, true) => visible!(true, true, all(), put(cs, col)),
                        (true, false, false) => {
                            visible!(true, false, all(), none)
                        }
                        (true, false, true) => {
                            visible!(true, true, all(), none)
                        }
                        (false, true, _) => visible!(false, false, all(), put(cs, col)),
                        (false, false, _) => {
                            visible!(false, false, all(), none)
                        }
                    },
                };
                if kept.is_none() {
                    return Err(self.cap(Part::Colors));
                }
                // The whole screen's rows: they hold the rows of every
                // kept triangle (every vertex is on the screen), without a
                // pass over the triangles or a box in the vertex loop.
                let rows = self.height.min(u32::from(u16::MAX)) as u16;
                self.rows = Some([0, rows]);
                // Every kept triangle has its corners in the screen's box
                // (stored from its corner) with their depths in the
                // kernel's range, an area and a row, and no triangle is
                // made: fit for the small-triangle kernel
                // where the screen allows it (a marked corner, negative,
                // is dropped with its triangle when culled; not marked
                // otherwise).
                self.fit = (ctx.cull || !self.marked)
                    && crate::raster::kernel_fit_screen(self.width, self.height, sub);
                return Ok(());
            }
            let kept = triangles_inside(
                ctx.tris,
                (xy, origin),
                (faces, &mut *self.face_rows),
                (self.width, self.height, q),
                P::SUBPIXEL_BITS,
                (ctx.cull, marked),
                |t, back| {
                    !flat
                        || cs
                            .get_mut(t)
                            .map(|c| *c = Self::flat_color(ctx, t, back))
                            .is_some()
                },
            );
            return match kept {
                Some(()) => Ok(()),
                None => Err(self.cap(Part::Colors)),
            };
        }
        for (t, tri) in ctx.tris.iter().enumerate() {
            // Not kept unless said below (its number's room checked by
            // the caller).
            let number = self.t_start + t;
            if let Some(f) = self.ws.faces.get_mut(number) {
                *f = 0;
            }
            // base + index < MAX_VERTICES (checked by the vertex pass).
            let vs = tri.map(|i| (base + usize::from(i)) as u16);
            let q = vs.map(|v| self.ws.xy.get(usize::from(v)).copied().unwrap_or_default());
            if !INSIDE && (q[0].0[0] == OUTSIDE || q[1].0[0] == OUTSIDE || q[2].0[0] == OUTSIDE) {
                #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
                let code = |p: ScreenXy| {
                    if p.0[0] == OUTSIDE {
                        p.0[1] as Outcode
                    } else {
                        0
                    }
                };
                self.clipped(ctx, t, [code(q[0]), code(q[1]), code(q[2])])?;
                continue;
            }
            let o = self.origin();
            let xy = q.map(|p| p.unpack(o));
            let [Subpx(a), Subpx(b), Subpx(c)] = xy;
            // Twice the signed area; only its sign is used: 32-bit
            // products when every edge is shorter than 2^15 subpixels.
            let (e0, e1, e2, e3) = (b[0] - a[0], c[1] - a[1], c[0] - a[0], b[1] - a[1]);
            let sign = det_sign_small(e0, e1, e2, e3).unwrap_or_else(|| det_sign(e0, e1, e2, e3));
            if sign == 0 {
                continue;
            }
            // Front faces are counter-clockwise in the y-up world, hence
            // clockwise (negative area) on the y-down screen.
            let back = sign > 0;
            if back {
                if ctx.cull {
                    continue;
                }
                if matches!(ctx.layout, Layout::GouraudMono | Layout::GouraudRgb) {
                    self.back_gouraud(ctx, t)?;
                    continue;
                }
            }
            let Some(rows) = self.rows_of(xy) else {
                continue;
            };
            let color = if ctx.layout == Layout::Flat {
                Some(Self::flat_color(ctx, t, back))
            } else {
                None
            };
            self.keep(number, color, back, rows[0])?;
        }
        Ok(())
    }

    /// A back face of a two-sided Gouraud object: lit with reversed
    /// normals, in vertices of its own.
    #[inline(never)]
    fn back_gouraud(&mut self, ctx: &ObjCtx<'_, '_, P::Real>, t: usize) -> Result<(), RenderError> {
        let vi = ctx.tris.get(t).copied().unwrap_or([0; 3]);
        let mut vs = [0u16; 3];
        for c in 0..3 {
            let cv = Self::clip_vert(ctx, usize::from(vi[c]), true);
            vs[c] = self.emit(ctx, &cv)?;
        }
        self.push_tri(vs, None, true)
    }

    /// A triangle with a corner outside the planes: dropped when all are
    /// outside one plane, else clipped in eye space.
    #[inline(never)]
    fn clipped(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        t: usize,
        codes: [Outcode; 3],
    ) -> Result<(), RenderError> {
        if codes[0] & codes[1] & codes[2] != 0 {
            return Ok(());
        }
        let vi = ctx.tris.get(t).copied().unwrap_or([0; 3]).map(usize::from);
        // Clip in eye space. Facing from the eye-space plane: front when
        // the normal points towards the eye (at the origin).
        let mut cvs = vi.map(|i| Self::clip_vert(ctx, i, false));
        let facing = facing(cvs[0].pos, cvs[1].pos, cvs[2].pos);
        if facing == P::Real::ZERO {
            return Ok(());
        }
        let back = facing > P::Real::ZERO;
        if back && ctx.cull {
            return Ok(());
        }
        if back && matches!(ctx.layout, Layout::GouraudMono | Layout::GouraudRgb) {
            cvs = vi.map(|i| Self::clip_vert(ctx, i, true));
        }
        let mut poly = [cvs[0]; MAX_POLY];
        let n = self.view.planes.clip(&cvs, codes, &mut poly);
        if n < 3 {
            return Ok(());
        }
        let color = (ctx.layout == Layout::Flat).then(|| Self::flat_color(ctx, t, back));
        let first = self.emit(ctx, &poly[0])?;
        let mut prev = self.emit(ctx, &poly[1])?;
        for q in poly.iter().take(n).skip(2) {
            let cur = self.emit(ctx, q)?;
            self.push_tri([first, prev, cur], color, back)?;
            prev = cur;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::geom::testkit::xorshift;
    use crate::render::{face_shift, FACE_ROW};
    use std::vec::Vec;

    /// Every kept triangle of an object prepare marks fit for the
    /// small-triangle kernel ([`PreparedObject::kernel_fit`]) meets the
    /// kernel's contract ([`crate::raster::kernel_fit_holds`]: corners in
    /// the screen's box, area, a row), on random views of the built-in
    /// meshes (every layout, culled and two-sided) on screens from 1×1 to
    /// the largest that allows it and beyond, close (clipped) and far.
    #[test]
    fn kernel_fit_objects_meet_the_contract() {
        use crate::geom::{Affine, Vec3};
        use crate::illum::{Light, Material, Specular, Viewer};
        use crate::mesh::shapes;
        use crate::num::{Fast, Precise, Profile};
        use crate::scene::{Camera, Object, Scene, Shading};
        fn run<P: Profile>(seed: u64) -> [usize; 2] {
            let mut next = xorshift(seed);
            let mut seen = [0usize; 2];
            let shadings = [Shading::Flat, Shading::Gouraud, Shading::Phong];
            let mut xy = std::vec![ScreenXy::ZERO; 4000];
            let mut vals = std::vec![P::Lerp::ZERO; 4000 * 7];
            let mut tris = std::vec![Tri::EMPTY; 8000];
            let mut colors = std::vec![Rgb8::BLACK; 8000];
            let mut faces = std::vec![0u8; 8000];
            for i in 0..300 {
                let r = |next: &mut dyn FnMut() -> u64, k: f32| (next() % 1000) as f32 / 1000.0 * k;
                let mesh = shapes::ALL[i % shapes::ALL.len()];
                let angles = [r(&mut next, 6.3), r(&mut next, 6.3), r(&mut next, 6.3)];
                let obj = Object {
                    mesh,
                    transform: Affine::from_parts(
                        P::Real::ONE,
                        Vec3::from_f32(angles),
                        Vec3::from_f32([r(&mut next, 1.0) - 0.5, r(&mut next, 1.0) - 0.5, 0.0]),
                    ),
                    material: Material {
                        color: Vec3::from_f32([1.0, 1.0, 1.0]),
                        ka: P::Real::from_f32(0.2),
                        kd: P::Real::from_f32(0.7),
                        ks: P::Real::from_f32(0.0),
                        shininess: P::Real::from_f32(10.0),
                    },
                    shading: shadings[(i / 6) % shadings.len()],
                    cull_backfaces: i % 3 != 0,
                };
                let objects = [obj];
                let lights = [Light::directional(
                    Vec3::from_f32([-1.0, 0.5, 1.0]),
                    P::Real::ONE,
                )];
                let dist = [1.2, 2.5, 4.0, 8.0, 30.0][i % 5];
                let scene = Scene {
                    camera: Camera::look_at_f32(
                        [0.0, 0.0, dist],
                        [0.0; 3],
                        [0.0, 1.0, 0.0],
                        40.0,
                        0.5,
                        None,
                    )
                    .unwrap(),
                    objects: &objects,
                    lights: &lights,
                    ambient: P::Real::from_f32(0.2),
                    specular: Specular::Phong,
                    viewer: Viewer::Local,
                    background: Rgb8::BLACK,
                };
                let sizes = [
                    (240, 240),
                    (1, 1),
                    (7, 3),
                    (128, 64),
                    (1016, 1000),
                    (1100, 600),
                ];
                let (w, h) = sizes[(i / 2) % sizes.len()];
                let ws = Workspace {
                    xy: &mut xy,
                    vals: &mut vals,
                    tris: &mut tris,
                    colors: &mut colors,
                    faces: &mut faces,
                };
                let Ok(frame) = prepare::<P>(&scene, w, h, ws) else {
                    continue;
                };
                for po in frame.objects() {
                    seen[usize::from(po.kernel_fit())] += 1;
                    if !po.kernel_fit() {
                        continue;
                    }
                    // The depth as the kernel takes it: the first value
                    // (packed grey: the word).
                    let packed =
                        po.layout() == Layout::GouraudMono && Layout::GouraudMono.packed_in::<P>();
                    for t in frame.object_tris(po) {
                        let p = t.v.map(|v| {
                            let [x, y] = frame.xy(usize::from(v)).unwrap();
                            let k = po.val_base() + usize::from(v - po.verts.start) * po.stride();
                            [x, y, frame.ws.vals[k].fixed_raw().unwrap()]
                        });
                        assert!(
                            crate::raster::kernel_fit_holds(p, packed, P::SUBPIXEL_BITS, w, h),
                            "{p:?} on {w}x{h}, case {i}"
                        );
                    }
                }
            }
            seen
        }
        let fast = run::<Fast>(0xf17_0b1e);
        assert!(fast[0] > 20 && fast[1] > 20, "{fast:?}");
        run::<Precise>(0xf17_0b1f);
    }

    /// [`kernel_depth_in`] is exactly the kernel's vertex depth test on
    /// the stored value: packed, on the word `grey_depth(d)` (any level
    /// half) for every `d` near each field's ends and the range's ends;
    /// unpacked, on the profile's depth.
    #[test]
    fn kernel_depth_test_is_exact() {
        use crate::num::{Fast, Precise, Profile};
        use crate::raster::grey_z;
        fn check<P: Profile>() {
            let mut ds = std::vec![i32::MIN, i32::MAX, -1, 0, 1 << 30, (1 << 30) + 1];
            for f in (0..=0x1_0001)
                .step_by(1)
                .filter(|f| f % 97 == 0 || *f < 8 || *f > 65525)
            {
                for e in [-2, -1, 0, 1, 2, (1 << 13), (1 << 14) - 1] {
                    ds.push((f << 14) + e);
                }
            }
            for d in ds {
                let word = crate::render::grey_depth(d) | 0x1234;
                assert_eq!(
                    kernel_depth_in::<P>(d, true),
                    Depth16::vertices_in_range([grey_z(word); 3]),
                    "packed {d}"
                );
                let z = P::depth_q30(d).fixed_raw().unwrap_or(-1);
                assert_eq!(
                    kernel_depth_in::<P>(d, false),
                    Depth16::vertices_in_range([z; 3]),
                    "{d}"
                );
            }
        }
        check::<Fast>();
        check::<Precise>();
    }

    /// [`on_screen`] of the OR of `W | (lim - W)` is exactly "every
    /// position within `0..=xl`, `0..=yl`", on random screens and random
    /// positions within ±[`XY_LIMIT`], most near the box's edges.
    #[test]
    fn screen_word_test_is_exact() {
        let mut next = xorshift(0x5eed_0f5c_7ee2);
        let mut hits = [0u32; 2];
        for _ in 0..20_000 {
            let sub = SubpixelBits::new(1 + (next() % 8) as u32).unwrap();
            let (w, h) = (1 + (next() % 2100) as u32, 1 + (next() % 2100) as u32);
            let Some(lim) = screen_word_limit(w, h, sub) else {
                let s = i64::from(sub.scale());
                assert!(i64::from(w) * s - s / 2 >= 1 << 15 || i64::from(h) * s >= 1 << 15);
                continue;
            };
            let (xl, yl) = ((lim & 0xFFFF) as i32, (lim >> 16) as i32);
            let s = sub.scale();
            assert_eq!((xl, yl), (w as i32 * s - s / 2, h as i32 * s));
            let coord = |next: &mut dyn FnMut() -> u64, l: i32| -> i32 {
                let r = next();
                match r % 4 {
                    0 => (r >> 8) as i32 % (XY_LIMIT + 1) * if r & 16 == 0 { 1 } else { -1 },
                    1 => l + ((r >> 8) % 5) as i32 - 2,
                    2 => ((r >> 8) % 5) as i32 - 2,
                    _ => ((r >> 8) as i32 & 0x7FFF) % (l + 1),
                }
                .clamp(-XY_LIMIT, XY_LIMIT)
            };
            let n = 1 + next() % 4;
            let (mut acc, mut exact) = (0u32, true);
            for _ in 0..n {
                let (x, y) = (coord(&mut next, xl), coord(&mut next, yl));
                let word = ScreenXy::pack(Subpx([x, y]), Subpx([0, 0])).word() as u32;
                assert_eq!(word, ((y as u32) << 16) | (x as u32 & 0xFFFF));
                acc |= word | lim.wrapping_sub(word);
                exact &= (0..=xl).contains(&x) && (0..=yl).contains(&y);
            }
            assert_eq!(on_screen(acc), exact);
            hits[usize::from(exact)] += 1;
        }
        assert!(hits[0] > 1000 && hits[1] > 1000, "{hits:?}");
    }

    /// [`area_words`] equals the area from the coordinates (and the word's
    /// bit 15 the sign of `x`) on random and extreme corners with `0 <= x, y < 2^15` and
    /// edges shorter than `2^15`.
    #[test]
    fn area_from_words_equals_area_from_coordinates() {
        let mut next = xorshift(0x0a4e_a5f0_4d5e);
        let lim = (1 << 15) - 1;
        for _ in 0..200_000 {
            let r = next();
            let v = |r: u64| -> i16 {
                match r % 4 {
                    0 => 0,
                    1 => lim as i16,
                    2 => (lim - (r >> 8) % 3) as i16,
                    _ => ((r >> 8) % (lim + 1)) as i16,
                }
            };
            let p = [0, 1, 2].map(|k| ScreenXy([v(r >> (k * 10)), v(next())]));
            let [a, b, c] = p.map(|p| [i32::from(p.0[0]), i32::from(p.0[1])]);
            let d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
            assert_eq!(area_words(p), (d, [a[1], b[1], c[1]]), "{p:?}");
            assert!(p[0].word() << 16 >= 0);
            assert!(ScreenXy([UNUSED, p[0].0[1]]).word() << 16 < 0);
        }
    }

    /// [`triangles_visible`] keeps exactly the triangles (face bytes and
    /// row counts) of the general [`triangles_inside`] on objects whose
    /// vertices all lie on the screen (random, on the edges, marked
    /// [`UNUSED`]), for every culling and marking.
    #[test]
    fn visible_loop_equals_the_general_loop() {
        let mut next = xorshift(0x07a1_e50f_ace5);
        let mut kept_faces = [0usize; 2];
        for round in 0..400 {
            let sub = SubpixelBits::new(1 + (next() % 5) as u32).unwrap();
            let s = sub.scale();
            let (w, h) = (1 + (next() % 400) as u32, 1 + (next() % 400) as u32);
            let Some(lim) = screen_word_limit(w, h, sub) else {
                continue;
            };
            let (xl, yl) = ((lim & 0xFFFF) as i32, (lim >> 16) as i32);
            let nv = 3 + (next() % 60) as usize;
            let marked = round % 2 == 1;
            let coord = |r: u64, l: i32| match r % 5 {
                0 => 0,
                1 => l,
                2 => (l - ((r >> 8) % (2 * s as u64)) as i32).max(0),
                _ => ((r >> 8) % (l as u64 + 1)) as i32,
            };
            let mut xy: Vec<ScreenXy> = (0..nv)
                .map(|_| {
                    let (x, y) = (coord(next(), xl), coord(next(), yl));
                    ScreenXy([x as i16, y as i16])
                })
                .collect();
            if marked {
                for v in xy.iter_mut() {
                    if next().is_multiple_of(4) {
                        v.0[0] = UNUSED;
                    }
                }
            }
            let nt = 1 + (next() % 120) as usize;
            let tris: Vec<[u16; 3]> = (0..nt)
                .map(|_| {
                    let mut t = [0u16; 3];
                    for c in &mut t {
                        *c = (next() % nv as u64) as u16;
                    }
                    t
                })
                .collect();
            let q = face_shift(h);
            for cull in [false, true] {
                if marked && !cull {
                    continue;
                }
                let (mut fa, mut fb) = (std::vec![0xAAu8; nt], std::vec![0x55u8; nt]);
                let (mut ca, mut cb) =
                    ([0u16; FACE_ROW as usize + 1], [0u16; FACE_ROW as usize + 1]);
                let all = || core::iter::repeat(());
                // One call per (cull, marked) pair (const parameters).
                macro_rules! visible {
                    ($cull:literal, $marked:literal) => {
                        triangles_visible::<$cull, $marked, _>(
                            &tris,
                            &xy,
                            (&mut fa, &mut ca),
                            (sub, q),
                            all(),
                            |_, (), _| true,
                        )
                    };
                }
                let kept = match (cull, marked) {
                    (true, true) => visible!(true, true),
                    (true, false) => visible!(true, false),
                    _ => visible!(false, false),
                };
                assert!(kept.is_some());
                let general = triangles_inside(
                    &tris,
                    (&xy, Subpx([0, 0])),
                    (&mut fb, &mut cb),
                    (w, h, q),
                    sub,
                    (cull, marked),
                    |_, _| true,
                );
                assert!(general.is_some());
                assert_eq!(fa, fb, "round {round} cull {cull}");
                assert_eq!(ca, cb, "round {round} cull {cull}");
                for f in fa {
                    kept_faces[usize::from(f == 0)] += 1;
                }
            }
        }
        assert!(
            kept_faces[0] > 2000 && kept_faces[1] > 2000,
            "{kept_faces:?}"
        );
    }
}
