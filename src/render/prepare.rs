//! Preparing a frame: transform, light, cull, clip, project.

use super::clip::{ClipVert, Outcode, Planes, CLIP_ATTRS, GUARD_PX, MAX_POLY};
use super::{Frame, Layout, Link, Part, PreparedObject, RenderError, Tri, Workspace};
use crate::geom::q16::{face_normal_q14, Proj16, Xform16};
use crate::geom::{Affine, Vec3};
use crate::illum::{Light, LightKind, Shade, MAX_LIGHTS};
use crate::mesh::{face_normal, Mesh};
use crate::num::approx16;
use crate::num::wide::det_sign;
use crate::num::{Profile, Real};
use crate::raster::{first_row, COORD_LIMIT_PX};
use crate::scene::{Object, Scene, SceneError, Shading};
use crate::target::{Rgb8, MAX_SCREEN};

const NONE: u16 = u16::MAX;

/// The lights of a scene moved to eye space.
pub(super) fn eye_lights<R: Real>(
    scene: &Scene<'_, '_, R>,
) -> Result<heapless::Vec<Light<R>, MAX_LIGHTS>, SceneError> {
    let view = &scene.camera.view;
    let mut out = heapless::Vec::new();
    for l in scene.lights {
        let kind = match l.kind {
            LightKind::Point(p) => LightKind::Point(view.point(p)),
            LightKind::Directional(d) => LightKind::Directional(view.vector(d)),
        };
        out.push(Light { kind, ..*l })
            .map_err(|_| SceneError::TooManyLights)?;
    }
    Ok(out)
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
struct View<R> {
    planes: Planes<R>,
    k: R,
    cx: R,
    cy: R,
    depth_scale: Option<R>,
    /// The integer projection (`Q16` only).
    fast: Option<Proj16>,
}

/// Raw Q16 vector of a `Q16` vector.
#[inline(always)]
fn raw3<R: Real>(v: Vec3<R>) -> [i32; 3] {
    [
        v.x.to_fixed_i32(16),
        v.y.to_fixed_i32(16),
        v.z.to_fixed_i32(16),
    ]
}

/// A `Q16` vector from raw bits.
#[inline(always)]
fn from_raw3<R: Real>(v: [i32; 3]) -> Vec3<R> {
    Vec3::new(
        R::from_fixed_i32(v[0], 16),
        R::from_fixed_i32(v[1], 16),
        R::from_fixed_i32(v[2], 16),
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
/// [`RenderError`]: an invalid scene or screen size, a mesh without
/// normals for smooth shading, or a workspace part too small (naming the
/// part and the object).
pub fn prepare<'w, P: Profile>(
    scene: &Scene<'_, '_, P::Real>,
    width: u32,
    height: u32,
    ws: Workspace<'w, P::Lerp>,
) -> Result<Frame<'w, P>, RenderError> {
    scene.check()?;
    if width > MAX_SCREEN || height > MAX_SCREEN {
        return Err(SceneError::Screen.into());
    }
    let cam = &scene.camera;
    let k = cam.focal.mul_i32(height as i32).half();
    // A saturated projection scale (a field of view too narrow for the
    // screen in this scalar type, e.g. below 0.84° at 240 rows in Q16)
    // would place every vertex wrongly: refuse it.
    if k >= P::Real::MAX.half() {
        return Err(SceneError::Screen.into());
    }
    let view = View {
        planes: Planes {
            near: cam.near,
            far: cam.far,
            guard: P::Real::from_i32(GUARD_PX).div(k),
        },
        k,
        cx: P::Real::from_i32(width as i32).half(),
        cy: P::Real::from_i32(height as i32).half(),
        depth_scale: cam.far.map(|f| f.div(f - cam.near)),
        fast: None,
    };
    let sub = P::SUBPIXEL_BITS.get();
    let view = View {
        fast: (P::Real::Q16_KERNELS && sub <= 15).then(|| Proj16 {
            k: view.k.to_fixed_i32(16),
            near: view.planes.near.to_fixed_i32(16),
            cx: view.cx.to_fixed_i32(sub),
            cy: view.cy.to_fixed_i32(sub),
            lim: COORD_LIMIT_PX << sub,
        }),
        ..view
    };
    let lights = eye_lights(scene)?;
    let mut p = Preparer::<P> {
        ws,
        view,
        nv: 0,
        nval: 0,
        nt: 0,
        object: 0,
        width,
        height,
    };
    let mut objects = heapless::Vec::new();
    for (oi, obj) in scene.objects.iter().enumerate() {
        p.object = oi;
        let po = p.object_pass(scene, obj, &lights)?;
        objects.push(po).map_err(|_| SceneError::TooManyObjects)?;
    }
    Ok(Frame {
        ws: p.ws,
        objects,
        width,
        height,
    })
}

struct Preparer<'w, P: Profile> {
    ws: Workspace<'w, P::Lerp>,
    view: View<P::Real>,
    nv: usize,
    nval: usize,
    nt: usize,
    object: usize,
    width: u32,
    height: u32,
}

/// Per-object constants while preparing.
struct ObjCtx<'a, 'm, R> {
    mesh: Mesh<'m>,
    /// The mesh's triangles, normal indices (empty for flat shading or
    /// without normals) and normals (empty without normals), taken out
    /// of the mesh once per object.
    tris: &'m [[u16; 3]],
    nidx: &'m [[u16; 3]],
    normals: &'m [[i16; 3]],
    mv: Affine<R>,
    shade: &'a Shade<R>,
    layout: Layout,
    stride: usize,
    cull: bool,
    val_base: usize,
    v_start: usize,
    /// The integer transform (`Q16`, moderate scales).
    fast: Option<Xform16>,
}

impl<P: Profile> Preparer<'_, P> {
    fn cap(&self, part: Part) -> RenderError {
        RenderError::Capacity {
            part,
            object: self.object,
        }
    }

    // Not inlined (one call per object): kept out of the caller, the
    // triangle loop does not change how the caller's own code (e.g. a
    // firmware's band loop) is optimised.
    #[inline(never)]
    fn object_pass(
        &mut self,
        scene: &Scene<'_, '_, P::Real>,
        obj: &Object<'_, P::Real>,
        lights: &[Light<P::Real>],
    ) -> Result<PreparedObject, RenderError> {
        let shade = Shade::new(
            &obj.material,
            scene.ambient,
            lights,
            scene.specular,
            scene.viewer,
        )
        .map_err(|_| SceneError::TooManyLights)?;
        let layout = layout_of(obj, &shade, lights);
        let mesh = obj.mesh;
        if layout != Layout::Flat && !mesh.has_normals() {
            return Err(RenderError::MissingNormals {
                object: self.object,
            });
        }
        let heads = self
            .ws
            .heads
            .get_mut(..mesh.vertex_count())
            .ok_or(RenderError::Capacity {
                part: Part::Heads,
                object: self.object,
            })?;
        heads.fill(NONE);
        let mv = scene.camera.view.then_after(&obj.transform);
        let corner_normals = mesh.normals();
        let ctx = ObjCtx {
            mesh,
            tris: mesh.triangles(),
            nidx: match (layout, corner_normals) {
                (Layout::Flat, _) | (_, None) => &[],
                (_, Some(n)) => n.indices,
            },
            normals: corner_normals.map_or(&[], |n| n.normals),
            fast: Xform16::new(&mv),
            mv,
            shade: &shade,
            layout,
            stride: layout.stride_for(P::PERSPECTIVE),
            cull: obj.cull_backfaces,
            val_base: self.nval,
            v_start: self.nv,
        };
        let t_start = self.nt;
        for t in 0..mesh.triangle_count() {
            self.triangle(&ctx, t)?;
        }
        let tris = t_start..self.nt;
        let rows = self
            .ws
            .tris
            .get(tris.clone())
            .unwrap_or(&[])
            .iter()
            .fold([u16::MAX, 0], |[lo, hi], t| {
                [lo.min(t.rows[0]), hi.max(t.rows[1])]
            });
        Ok(PreparedObject {
            layout,
            verts: ctx.v_start..self.nv,
            val_base: ctx.val_base,
            stride: ctx.stride,
            tris,
            rows: if rows[0] < rows[1] { rows } else { [0; 2] },
        })
    }

    /// Corner `c` of triangle `t`: its position and normal indices.
    fn corner_keys(ctx: &ObjCtx<'_, '_, P::Real>, t: usize) -> ([u16; 3], [u16; 3]) {
        let pos = ctx.tris.get(t).copied().unwrap_or([0; 3]);
        let nrm = ctx.nidx.get(t).copied().unwrap_or([0; 3]);
        (pos, nrm)
    }

    /// The eye-space position of mesh position `p`.
    #[inline]
    fn eye_pos(ctx: &ObjCtx<'_, '_, P::Real>, p: u16) -> Vec3<P::Real> {
        let pos = ctx
            .mesh
            .positions()
            .get(p as usize)
            .copied()
            .unwrap_or([0; 3]);
        match &ctx.fast {
            Some(x) => from_raw3(x.point(pos)),
            None => ctx.mv.point(Vec3::from_q14(pos)),
        }
    }

    /// The attributes of a corner at eye-space `pos` with mesh normal `n`:
    /// its colour (Gouraud) or its normal (Phong); zero for flat.
    fn attrs(
        ctx: &ObjCtx<'_, '_, P::Real>,
        pos: Vec3<P::Real>,
        n: u16,
        flip: bool,
    ) -> [P::Real; CLIP_ATTRS] {
        if ctx.layout == Layout::Flat {
            return [P::Real::ZERO; CLIP_ATTRS];
        }
        let raw = ctx.normals.get(n as usize).copied().unwrap_or([0; 3]);
        let mut nrm = match &ctx.fast {
            Some(x) => from_raw3(approx16::unit(x.vector(raw))),
            None => ctx.mv.vector(Vec3::from_q14(raw)).normalize(),
        };
        if flip {
            nrm = -nrm;
        }
        let v = match ctx.layout {
            Layout::GouraudMono | Layout::GouraudRgb => ctx.shade.at(nrm, pos),
            _ => nrm,
        };
        [v.x, v.y, v.z]
    }

    /// The eye-space vertex of a mesh corner, lit or with its normal.
    fn clip_vert(ctx: &ObjCtx<'_, '_, P::Real>, p: u16, n: u16, flip: bool) -> ClipVert<P::Real> {
        let pos = Self::eye_pos(ctx, p);
        ClipVert {
            pos,
            attrs: Self::attrs(ctx, pos, n, flip),
        }
    }

    /// Whether the corners of this object are lit on first use by a kept
    /// triangle rather than when made (Gouraud, affine profiles: the
    /// colours are stored as computed).
    #[inline(always)]
    fn lazy(ctx: &ObjCtx<'_, '_, P::Real>) -> bool {
        !P::PERSPECTIVE && matches!(ctx.layout, Layout::GouraudMono | Layout::GouraudRgb)
    }

    /// Computes and stores the colour of prepared vertex `v` (made unlit
    /// from corner `c` of triangle `t`): the values
    /// [`Preparer::emit`] would have stored. Once per lit vertex: kept
    /// out of the triangle loop.
    #[inline(never)]
    fn light(&mut self, ctx: &ObjCtx<'_, '_, P::Real>, v: u16, t: usize, c: usize) {
        let (pk, nk) = Self::corner_keys(ctx, t);
        let (p, n) = (pk[c % 3], nk[c % 3]);
        let Some(link) = self.ws.links.get_mut(v as usize) else {
            return;
        };
        if !link.unlit {
            return;
        }
        link.unlit = false;
        let pos = if ctx.shade.uses_position() {
            Self::eye_pos(ctx, p)
        } else {
            Vec3::ZERO
        };
        let a = Self::attrs(ctx, pos, n, false);
        let stride = ctx.layout.stride_for(P::PERSPECTIVE);
        let base = ctx.val_base + (v as usize).wrapping_sub(ctx.v_start) * stride;
        let count = if ctx.layout == Layout::GouraudMono {
            1
        } else {
            3
        };
        if let Some(vals) = self.ws.vals.get_mut(base + 1..base + 1 + count) {
            for (d, x) in vals.iter_mut().zip(a) {
                *d = P::level(x);
            }
        }
    }

    /// Appends a prepared vertex for an eye-space vertex inside the planes.
    fn emit(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        cv: &ClipVert<P::Real>,
        link: Link,
        code: Outcode,
    ) -> Result<u16, RenderError> {
        let i = self.nv;
        if i >= NONE as usize || i >= self.ws.xy.len() || i >= self.ws.links.len() {
            return Err(self.cap(Part::Vertices));
        }
        // `ctx.stride`, recomputed so the optimiser sees `stride >= 1`.
        let stride = ctx.layout.stride_for(P::PERSPECTIVE);
        let base = ctx.val_base + (i - ctx.v_start) * stride;
        let vals = self
            .ws
            .vals
            .get_mut(base..base + stride)
            .ok_or(RenderError::Capacity {
                part: Part::Values,
                object: self.object,
            })?;
        self.ws.links[i] = Link { code, ..link };
        if code != 0 {
            // Outside: never drawn directly; triangles using it are clipped.
            self.ws.xy[i] = [0, 0];
            vals.fill(P::level(P::Real::ZERO));
        } else {
            let sub = P::SUBPIXEL_BITS.get();
            let (xy, d, q) = if let Some(pj) = &self.view.fast {
                // Q16: integer projection, clamped to the rasterizer's range.
                let (xy, q) = pj.project(raw3(cv.pos), sub);
                let q = P::Real::from_fixed_i32(q, 16);
                let d = P::Real::ONE - q;
                // `*`, inlined (`*=` measured as a call on the M0).
                let d = self.view.depth_scale.map_or(d, |s| d * s);
                (xy, d.clamp(P::Real::ZERO, P::Real::ONE), q)
            } else {
                let (sx, sy, d, q) = self.view.project(cv.pos);
                // Clipping keeps a corner within the guard band, but
                // saturated Q16 arithmetic or float precision lost on huge
                // coordinates can move a clipped corner out of the
                // rasterizer's range: clamp to it (NaN to its lower end)
                // rather than have the rasterizer refuse the whole frame.
                // No-op for in-range corners.
                let lim = P::Real::from_i32(COORD_LIMIT_PX);
                let (sx, sy) = (sx.clamp(-lim, lim), sy.clamp(-lim, lim));
                ([sx.to_fixed_i32(sub), sy.to_fixed_i32(sub)], d, q)
            };
            self.ws.xy[i] = xy;
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
                Layout::GouraudMono | Layout::GouraudRgb if link.unlit => {}
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
                        let p = [pos.x, pos.y, pos.z];
                        for (v, x) in vals.iter_mut().skip(4).zip(p) {
                            *v = P::coord(x);
                        }
                    }
                }
            }
        }
        self.nv += 1;
        self.nval = base + stride;
        Ok(i as u16)
    }

    /// The prepared vertex of a mesh corner if it was made already, with
    /// its outcode (the one stored in its link).
    #[inline(always)]
    fn find(&self, p: u16, n: u16) -> Option<(u16, Outcode)> {
        let mut v = *self.ws.heads.get(p as usize)?;
        while v != NONE {
            let l = self.ws.links.get(v as usize)?;
            if l.normal == n {
                return Some((v, l.code));
            }
            v = if l.next == v { NONE } else { l.next };
        }
        None
    }

    /// The prepared vertex of a mesh corner, made on first use, with its
    /// outcode (the one stored in its link).
    #[inline(always)]
    fn corner(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        p: u16,
        n: u16,
    ) -> Result<(u16, Outcode), RenderError> {
        match self.find(p, n) {
            Some(found) => Ok(found),
            None => self.new_corner(ctx, p, n),
        }
    }

    /// Makes the prepared vertex of a mesh corner used for the first time
    /// (once per vertex: kept out of the triangle loop).
    #[inline(never)]
    fn new_corner(
        &mut self,
        ctx: &ObjCtx<'_, '_, P::Real>,
        p: u16,
        n: u16,
    ) -> Result<(u16, Outcode), RenderError> {
        let head = self.ws.heads.get(p as usize).copied().unwrap_or(NONE);
        let lazy = Self::lazy(ctx);
        let cv = if lazy {
            ClipVert {
                pos: Self::eye_pos(ctx, p),
                attrs: [P::Real::ZERO; CLIP_ATTRS],
            }
        } else {
            Self::clip_vert(ctx, p, n, false)
        };
        let code = self.view.outcode(cv.pos);
        let i = self.emit(
            ctx,
            &cv,
            Link {
                normal: n,
                next: head,
                code: 0,
                unlit: lazy,
            },
            code,
        )?;
        if let Some(h) = self.ws.heads.get_mut(p as usize) {
            *h = i;
        }
        Ok((i, code))
    }

    /// Keeps `tri` when it can cover a pixel centre of the screen, with
    /// the rows it can cover (the rows the rasterizer would visit).
    fn push_tri(&mut self, tri: Tri) -> Result<(), RenderError> {
        let xy = tri
            .v
            .map(|v| self.ws.xy.get(v as usize).copied().unwrap_or([0; 2]));
        self.push_tri_at(tri, xy)
    }

    /// [`Preparer::push_tri`] with the screen positions `xy` of the
    /// corners already read.
    fn push_tri_at(&mut self, tri: Tri, xy: [[i32; 2]; 3]) -> Result<(), RenderError> {
        match self.rows_of(xy) {
            Some(rows) => self.store_tri(tri.v, rows, tri.color, tri.back),
            None => Ok(()),
        }
    }

    /// The rows a triangle with corners at `xy` can cover (the rows the
    /// rasterizer would visit), or `None` when it covers no pixel centre
    /// of the screen.
    #[inline(always)]
    fn rows_of(&self, xy: [[i32; 2]; 3]) -> Option<[u16; 2]> {
        let sub = P::SUBPIXEL_BITS;
        let span = |k: usize| {
            let (a, b, c) = (xy[0][k], xy[1][k], xy[2][k]);
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
            clamp(first_row(y_lo, sub), self.height),
            clamp(first_row(y_hi, sub), self.height),
        ];
        let cols = [
            clamp(first_row(x_lo, sub), self.width),
            clamp(first_row(x_hi, sub).saturating_add(1), self.width),
        ];
        if rows[0] >= rows[1] || cols[0] >= cols[1] {
            return None;
        }
        Some(rows)
    }

    /// Appends a kept triangle. Field by field: the 14-byte `Tri` built
    /// and copied whole was a `memcpy` call on the M0 (64 instructions).
    #[inline(always)]
    fn store_tri(
        &mut self,
        v: [u16; 3],
        rows: [u16; 2],
        color: Rgb8,
        back: bool,
    ) -> Result<(), RenderError> {
        let Some(slot) = self.ws.tris.get_mut(self.nt) else {
            return Err(self.cap(Part::Triangles));
        };
        slot.v = v;
        slot.rows = rows;
        slot.color = color;
        slot.back = back;
        self.nt += 1;
        Ok(())
    }

    /// Flat colour of triangle `t`: face normal (exact integer cross
    /// product in model space, then rotated) at the centroid.
    fn flat_color(&self, ctx: &ObjCtx<'_, '_, P::Real>, t: usize, back: bool) -> Rgb8 {
        if ctx.layout != Layout::Flat {
            return Rgb8::BLACK;
        }
        let pos = ctx.mesh.triangle_positions(t).unwrap_or([[0; 3]; 3]);
        let mut n = match &ctx.fast {
            Some(x) => from_raw3::<P::Real>(x.vector(face_normal_q14(pos[0], pos[1], pos[2])))
                .normalize_geom(),
            None => ctx
                .mv
                .vector(Vec3::from_q14(face_normal(pos[0], pos[1], pos[2])))
                .normalize(),
        };
        if back {
            n = -n;
        }
        // The centroid only when the lighting depends on the position.
        let c = if ctx.shade.uses_position() {
            let e = pos.map(|q| match &ctx.fast {
                Some(x) => from_raw3(x.point(q)),
                None => ctx.mv.point(Vec3::from_q14(q)),
            });
            (e[0] + e[1] + e[2]).scale(P::Real::from_ratio(1, 3))
        } else {
            Vec3::ZERO
        };
        let col = ctx.shade.at(n, c);
        Rgb8::new(col.x.to_level(), col.y.to_level(), col.z.to_level())
    }

    #[inline(always)]
    fn triangle(&mut self, ctx: &ObjCtx<'_, '_, P::Real>, t: usize) -> Result<(), RenderError> {
        let (pk, nk) = Self::corner_keys(ctx, t);
        let (v0, c0) = self.corner(ctx, pk[0], nk[0])?;
        let (v1, c1) = self.corner(ctx, pk[1], nk[1])?;
        let (v2, c2) = self.corner(ctx, pk[2], nk[2])?;
        let vs = [v0, v1, v2];
        if c0 | c1 | c2 != 0 {
            // The cold paths read the keys again rather than keep them
            // live (spilled) across the hot one.
            return self.clipped(ctx, t, [c0, c1, c2]);
        }
        let xy = vs.map(|v| self.ws.xy.get(v as usize).copied().unwrap_or([0; 2]));
        let [a, b, c] = xy;
        // Twice the signed area; only its sign is used.
        let sign = det_sign(b[0] - a[0], c[1] - a[1], c[0] - a[0], b[1] - a[1]);
        if sign == 0 {
            return Ok(());
        }
        // Front faces are counter-clockwise in the y-up world, hence
        // clockwise (negative area) on the y-down screen.
        let back = sign > 0;
        if back {
            if ctx.cull {
                return Ok(());
            }
            if matches!(ctx.layout, Layout::GouraudMono | Layout::GouraudRgb) {
                return self.back_gouraud(ctx, t);
            }
        }
        let Some(rows) = self.rows_of(xy) else {
            return Ok(());
        };
        // Only kept triangles need their colour (flat) or lit corners
        // (lazy Gouraud).
        let color = if ctx.layout == Layout::Flat {
            self.flat_color(ctx, t, back)
        } else {
            Rgb8::BLACK
        };
        self.store_tri(vs, rows, color, back)?;
        if !back && Self::lazy(ctx) {
            for (c, v) in vs.into_iter().enumerate() {
                if self.ws.links.get(v as usize).is_some_and(|l| l.unlit) {
                    self.light(ctx, v, t, c);
                }
            }
        }
        Ok(())
    }

    /// A back face of a two-sided Gouraud object: lit with reversed
    /// normals, in vertices of its own.
    #[inline(never)]
    fn back_gouraud(&mut self, ctx: &ObjCtx<'_, '_, P::Real>, t: usize) -> Result<(), RenderError> {
        let (pk, nk) = Self::corner_keys(ctx, t);
        let mut vs = [0u16; 3];
        for c in 0..3 {
            let cv = Self::clip_vert(ctx, pk[c], nk[c], true);
            vs[c] = self.emit(
                ctx,
                &cv,
                Link {
                    normal: NONE,
                    next: NONE,
                    code: 0,
                    unlit: false,
                },
                0,
            )?;
        }
        let color = self.flat_color(ctx, t, true);
        // New vertices: read their positions.
        self.push_tri(Tri {
            v: vs,
            color,
            back: true,
            ..Tri::EMPTY
        })
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
        let (pk, nk) = Self::corner_keys(ctx, t);
        if codes[0] & codes[1] & codes[2] != 0 {
            return Ok(());
        }
        // Clip in eye space. Facing from the eye-space plane: front when
        // the normal points towards the eye (at the origin).
        let keys = [(pk[0], nk[0]), (pk[1], nk[1]), (pk[2], nk[2])];
        let mut cvs = keys.map(|(p, n)| Self::clip_vert(ctx, p, n, false));
        let nf = (cvs[1].pos - cvs[0].pos).cross(cvs[2].pos - cvs[0].pos);
        let facing = nf.dot(cvs[0].pos);
        if facing == P::Real::ZERO {
            return Ok(());
        }
        let back = facing > P::Real::ZERO;
        if back && ctx.cull {
            return Ok(());
        }
        if back && matches!(ctx.layout, Layout::GouraudMono | Layout::GouraudRgb) {
            cvs = keys.map(|(p, n)| Self::clip_vert(ctx, p, n, true));
        }
        let mut poly = [cvs[0]; MAX_POLY];
        let n = self.view.planes.clip(&cvs, codes, &mut poly);
        if n < 3 {
            return Ok(());
        }
        let color = self.flat_color(ctx, t, back);
        let free = Link {
            normal: NONE,
            next: NONE,
            code: 0,
            unlit: false,
        };
        let first = self.emit(ctx, &poly[0], free, 0)?;
        let mut prev = self.emit(ctx, &poly[1], free, 0)?;
        for q in poly.iter().take(n).skip(2) {
            let cur = self.emit(ctx, q, free, 0)?;
            self.push_tri(Tri {
                v: [first, prev, cur],
                color,
                back,
                ..Tri::EMPTY
            })?;
            prev = cur;
        }
        Ok(())
    }
}
