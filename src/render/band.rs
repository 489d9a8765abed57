//! Rasterizing a prepared frame into a band (or a whole frame).

use super::phong_span::{PhongFill, PhongKernel, PosPlane};
use super::position::PosFrame;
use super::prepare::eye_lights;
use super::{Frame, Layout, PreparedObject, PreparedTri, RenderError};
use crate::geom::Vec3;
use crate::illum::Shade;
use crate::num::{approx16, Kernels, Profile, Real};
use crate::raster::{
    draw_sorted, in_limits, sort3, Fill, Flat, Gouraud, GouraudMono, Persp, RasterError, Shader,
    Spans,
};
use crate::scene::{Scene, SceneError};
use crate::target::{DepthBuffer, DepthFormat, Rgb8, Target};

/// Per-pixel Phong shading: the interpolated normal (and position)
/// normalised and illuminated.
///
/// For `Q16` ([`Q16Kernels`](crate::num::Q16Kernels), the `Fast` profiles) the pixel runs
/// on raw integers: the normal normalised by 32-bit arithmetic (within
/// `2^-15` per component of the exact unit vector), the light and view
/// vectors likewise, dot products summed exactly and rounded once (see
/// `Shade::at`'s integer path). The other scalars run the generic code.
#[derive(Debug)]
pub struct PhongShader<'a, P: Profile> {
    shade: &'a Shade<P::Real>,
    back: bool,
    pos: Option<&'a PosFrame<P::Real>>,
}

impl<'a, P: Profile> PhongShader<'a, P> {
    /// A shader lighting by `shade`; `back` flips the normal (the back
    /// face of a two-sided object). Its attributes are the interpolated
    /// normal in [`Profile::unit`] form (layout
    /// [`PhongNormal`](super::Layout::PhongNormal), 3 values) or the
    /// normal and the eye-space position in [`Profile::coord`] form (6
    /// values).
    pub fn new(shade: &'a Shade<P::Real>, back: bool) -> Self {
        Self {
            shade,
            back,
            pos: None,
        }
    }

    /// The shader of a prepared object whose positions are stored in
    /// `pos` ([`PosFrame::of_object`], `render::position`), front faces
    /// first.
    pub(super) fn for_object(
        shade: &'a Shade<P::Real>,
        pos: Option<&'a PosFrame<P::Real>>,
    ) -> Self {
        Self {
            shade,
            back: false,
            pos,
        }
    }

    /// Draws back faces (flipped normal) or front faces.
    #[inline(always)]
    pub fn set_back(&mut self, back: bool) {
        self.back = back;
    }

    #[inline(always)]
    fn color(&self, a: &[P::Lerp], p: Vec3<P::Real>) -> Rgb8 {
        let n = Vec3::new(P::unit_back(a[0]), P::unit_back(a[1]), P::unit_back(a[2]));
        <P::Real as Real>::Kernels::pick(
            |q| {
                let raw = |v: P::Real| q.raw(v);
                let mut u = approx16::unit([raw(n.x), raw(n.y), raw(n.z)]);
                if self.back {
                    u = u.map(i32::saturating_neg);
                }
                let c = self.shade.at_q16(u, [raw(p.x), raw(p.y), raw(p.z)]);
                let level = |c: i32| q.from_raw(c).to_level();
                Rgb8::new(level(c[0]), level(c[1]), level(c[2]))
            },
            || {
                let mut n = n.normalize();
                if self.back {
                    n = -n;
                }
                let c = self.shade.at(n, p);
                Rgb8::new(c.x.to_level(), c.y.to_level(), c.z.to_level())
            },
        )
    }
}

impl<P: Profile> Shader<P::Lerp, 3> for PhongShader<'_, P> {
    #[inline]
    fn shade(&self, a: &[P::Lerp; 3]) -> Rgb8 {
        self.color(a, Vec3::ZERO)
    }
}

impl<P: Profile> Shader<P::Lerp, 6> for PhongShader<'_, P> {
    #[inline]
    fn shade(&self, a: &[P::Lerp; 6]) -> Rgb8 {
        let p = PosFrame::load::<P>(self.pos, [a[3], a[4], a[5]]);
        self.color(a, p)
    }
}

/// What a render call drew.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RenderStats {
    /// Triangle setups: by the band renderer ([`super::Bands`]) each
    /// prepared triangle once (more only when its pool was full); by
    /// [`Frame::render`] each triangle reaching the target's window.
    pub triangles: u32,
    /// Pixels written (passing the depth test).
    pub pixels: u32,
}

impl<P: Profile> Frame<'_, P> {
    fn draw_object<const N: usize, T, D, S>(
        &self,
        po: &PreparedObject,
        fill: &mut Fill<'_, '_, '_, T, D, S>,
        stats: &mut RenderStats,
        mut per_tri: impl FnMut(&mut S, &PreparedTri),
    ) -> Result<(), RenderError>
    where
        T: Target,
        D: DepthFormat,
        S: Shader<P::Lerp, N>,
    {
        let win = fill.window();
        self.draw_spans(po, win, fill, stats, |f, t| per_tri(&mut f.shader, t))
    }

    /// [`Frame::draw_object`] into any span stage.
    fn draw_spans<const N: usize, F: Spans<P::Lerp, N>>(
        &self,
        po: &PreparedObject,
        win: crate::target::Window,
        fill: &mut F,
        stats: &mut RenderStats,
        mut per_tri: impl FnMut(&mut F, &PreparedTri),
    ) -> Result<(), RenderError> {
        let sub = P::SUBPIXEL_BITS;
        let (y0, y1) = (
            win.y0.min(u16::MAX as u32) as u16,
            win.y1.min(u16::MAX as u32) as u16,
        );
        if po.rows[1] <= y0 || po.rows[0] >= y1 {
            return Ok(());
        }
        for tri in self.object_tris(po) {
            // Reject triangles outside the band before fetching attributes.
            let rows = self.tri_rows(tri.v);
            if rows[1] <= y0 || rows[0] >= y1 {
                continue;
            }
            // The vertex indices sorted by y (as `draw_triangle` sorts its
            // vertices) before the vertices are fetched; the coordinate
            // limits checked in the triangle's own order (the error names
            // the vertex).
            let xy = |i: u16| self.xy(usize::from(i));
            let (Some(p0), Some(p1), Some(p2)) = (xy(tri.v[0]), xy(tri.v[1]), xy(tri.v[2])) else {
                continue;
            };
            let out = [p0, p1, p2]
                .iter()
                .position(|&[x, y]| !in_limits(x, y, sub));
            let [(i0, q0), (i1, q1), (i2, q2)] =
                sort3([(tri.v[0], p0), (tri.v[1], p1), (tri.v[2], p2)], |v| v.1[1]);
            let (Some(a), Some(b), Some(c)) = (
                self.vertex::<N>(po, i0, q0),
                self.vertex::<N>(po, i1, q1),
                self.vertex::<N>(po, i2, q2),
            ) else {
                continue;
            };
            per_tri(fill, &tri);
            stats.triangles += 1;
            if let Some(i) = out {
                return Err(RasterError::OutOfRange(i as u8).into());
            }
            draw_sorted(&a, &b, &c, sub, win, fill);
        }
        Ok(())
    }

    /// Rasterizes the prepared frame into `target` (any window of rows of
    /// the screen it was prepared for), depth-testing against `depth` when
    /// given. Neither is cleared here.
    ///
    /// # Errors
    /// [`RenderError::Window`] when the target's width differs from the
    /// frame's or its rows extend below it; a depth buffer holding other
    /// rows than the target; a scene other than the prepared one may give
    /// [`RenderError::Scene`].
    // Not inlined into the caller: merged with a caller's frame (e.g. a
    // firmware's band loop) its locals grew that frame by 1.8 KB of stack.
    #[inline(never)]
    pub fn render<T: Target, D: DepthFormat>(
        &self,
        scene: &Scene<'_, '_, P::Real>,
        target: &mut T,
        depth: Option<&mut DepthBuffer<'_, D>>,
    ) -> Result<RenderStats, RenderError> {
        let win = target.window();
        if win.width != self.width || win.y1 > self.height {
            return Err(RenderError::Window);
        }
        let lights = eye_lights(scene)?;
        let mut stats = RenderStats::default();
        let mut depth = depth;
        // The Phong kernels' specular table, kept from one object to the
        // next of the same shininess (built once a call, not once an
        // object).
        let mut spec_cache = None;
        for (po, obj) in self.objects.iter().zip(scene.objects.iter()) {
            let d = depth.as_deref_mut();
            match po.layout() {
                Layout::Flat => {
                    let mut f = Fill::new(target, d, Flat(Rgb8::BLACK))?;
                    self.draw_object::<0, _, _, _>(po, &mut f, &mut stats, |s, t| s.0 = t.color)?;
                    stats.pixels += f.drawn();
                }
                Layout::GouraudMono if P::PERSPECTIVE => {
                    let mut f = Fill::new(target, d, Persp(GouraudMono))?;
                    self.draw_object::<2, _, _, _>(po, &mut f, &mut stats, |_, _| {})?;
                    stats.pixels += f.drawn();
                }
                Layout::GouraudMono => {
                    let mut f = Fill::new(target, d, GouraudMono)?;
                    self.draw_object::<1, _, _, _>(po, &mut f, &mut stats, |_, _| {})?;
                    stats.pixels += f.drawn();
                }
                Layout::GouraudRgb if P::PERSPECTIVE => {
                    let mut f = Fill::new(target, d, Persp(Gouraud))?;
                    self.draw_object::<4, _, _, _>(po, &mut f, &mut stats, |_, _| {})?;
                    stats.pixels += f.drawn();
                }
                Layout::GouraudRgb => {
                    let mut f = Fill::new(target, d, Gouraud)?;
                    self.draw_object::<3, _, _, _>(po, &mut f, &mut stats, |_, _| {})?;
                    stats.pixels += f.drawn();
                }
                Layout::PhongNormal | Layout::PhongPosition => {
                    let shade = Shade::new(
                        &obj.material,
                        scene.ambient,
                        &lights,
                        scene.specular,
                        scene.viewer,
                    )
                    .map_err(|_| SceneError::TooManyLights)?;
                    let frame = PosFrame::of_object::<P>(scene, obj);
                    let sh = PhongShader::<P>::for_object(&shade, frame.as_ref());
                    // The span kernel (`phong_span`) for the affine Q16
                    // profiles, built only for objects in this window.
                    let kernel = if P::PERSPECTIVE
                        || po.rows[1] <= win.y0.min(u16::MAX as u32) as u16
                        || po.rows[0] >= win.y1.min(u16::MAX as u32) as u16
                    {
                        None
                    } else {
                        <P::Real as Real>::Kernels::pick(
                            |q| PhongKernel::new_cached(q, &shade, &mut spec_cache).ok(),
                            || None,
                        )
                    };
                    if let Some(k) = &kernel {
                        let mut f = PhongFill::new(&mut *target, d, k)?;
                        let w = f.window();
                        if po.layout() == Layout::PhongNormal {
                            let set =
                                |f: &mut PhongFill<'_, '_, '_, '_, '_, T, D, P::Real>,
                                 t: &PreparedTri| f.back = t.back;
                            self.draw_spans::<3, _>(po, w, &mut f, &mut stats, set)?;
                        } else {
                            // The exact position plane per triangle
                            // (`PosPlane`).
                            let plane = k.wants_plane();
                            let quad = k.wants_tri();
                            let set = |f: &mut PhongFill<'_, '_, '_, '_, '_, T, D, P::Real>,
                                       t: &PreparedTri| {
                                f.back = t.back;
                                if plane {
                                    f.plane = PosPlane::of_tri(self, po, t);
                                }
                                if quad {
                                    f.tri.set_of_tri(self, po, t);
                                }
                            };
                            self.draw_spans::<6, _>(po, w, &mut f, &mut stats, set)?;
                        }
                        stats.pixels += f.drawn();
                    } else if P::PERSPECTIVE {
                        let mut f = Fill::new(target, d, Persp(sh))?;
                        let set =
                            |s: &mut Persp<PhongShader<'_, P>>, t: &PreparedTri| s.0.back = t.back;
                        if po.layout() == Layout::PhongNormal {
                            self.draw_object::<4, _, _, _>(po, &mut f, &mut stats, set)?;
                        } else {
                            self.draw_object::<7, _, _, _>(po, &mut f, &mut stats, set)?;
                        }
                        stats.pixels += f.drawn();
                    } else {
                        let mut f = Fill::new(target, d, sh)?;
                        let set = |s: &mut PhongShader<'_, P>, t: &PreparedTri| s.back = t.back;
                        if po.layout() == Layout::PhongNormal {
                            self.draw_object::<3, _, _, _>(po, &mut f, &mut stats, set)?;
                        } else {
                            self.draw_object::<6, _, _, _>(po, &mut f, &mut stats, set)?;
                        }
                        stats.pixels += f.drawn();
                    }
                }
            }
        }
        Ok(stats)
    }
}
