//! Storage sized by the compiler: see [`Storage`].

use super::{Layout, ScreenXy, Tri, Workspace};
use crate::mesh::Mesh;
use crate::num::Profile;
use crate::raster::Lerp;
use crate::target::Rgb8;

/// Lengths of a prepared frame's parts: vertices (`Workspace::xy`),
/// values (`Workspace::vals`), triangle numbers (`Workspace::faces`, and
/// one order entry each for the band renderer), triangles made while
/// preparing (`Workspace::tris`) and flat triangles' colours
/// (`Workspace::colors`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Capacity {
    /// Prepared vertices.
    pub vertices: usize,
    /// Interpolated values (the most any profile needs; see
    /// [`Self::in_profile`]).
    pub values: usize,
    /// Interpolated values for the profiles that pack a grey Gouraud
    /// vertex's depth and level into one value
    /// ([`Profile::PACKED_GREY`]): as `values`, but one per vertex of a
    /// [`Layout::GouraudMono`] object instead of two.
    pub packed_values: usize,
    /// Triangle numbers: every object's mesh triangles and the triangles
    /// it can make.
    pub triangles: usize,
    /// Triangles made while preparing: fans of clipped triangles, back
    /// faces of two-sided Gouraud objects.
    pub made: usize,
    /// Colours of the triangles of flat objects (one per number).
    pub colors: usize,
}

/// Where an object lies and how its back faces are drawn: what its
/// prepared frame can grow to (see [`Storage`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reach {
    /// Inside the clipping planes; back faces culled, or drawn with the
    /// front faces' vertices (flat, Phong).
    Inside,
    /// Inside the clipping planes, two-sided Gouraud: each back face lit
    /// in three vertices of its own.
    TwoSided,
    /// The clipping planes may cut it.
    Clipped,
}

/// Corners of a clipped polygon (a triangle cut by the six planes).
const POLY: usize = super::clip::MAX_POLY;

impl Capacity {
    /// Nothing.
    pub const EMPTY: Self = Self {
        vertices: 0,
        values: 0,
        packed_values: 0,
        triangles: 0,
        made: 0,
        colors: 0,
    };

    /// Room for `meshes`, one object each, in any shading mode (8 values
    /// per vertex: the widest layout with the perspective weight; a colour
    /// per triangle: flat), inside
    /// the clipping planes with back faces culled or not Gouraud
    /// ([`Reach::Inside`]).
    pub const fn of(meshes: &[&Mesh<'_>]) -> Self {
        let mut c = Self::EMPTY;
        let mut i = 0;
        while i < meshes.len() {
            c = c.object(meshes[i], Layout::PhongPosition, Reach::Inside);
            c.values = c.values.saturating_add(meshes[i].vertex_count());
            c.packed_values = c.packed_values.saturating_add(meshes[i].vertex_count());
            c.colors = c.colors.saturating_add(meshes[i].triangle_count());
            i += 1;
        }
        c
    }

    /// Room for one more object: `mesh` with `layout`'s values (affine
    /// profiles; see [`Self::perspective`], and `packed_values` for the
    /// profiles that pack grey vertices: [`Self::in_profile`]) and `reach`
    /// (the table in the docs of [`Storage`]).
    pub const fn object(self, mesh: &Mesh<'_>, layout: Layout, reach: Reach) -> Self {
        let (v, t) = (mesh.vertex_count(), mesh.triangle_count());
        // Saturating: a sum beyond `usize` stays `usize::MAX` (no storage
        // of that size builds, and `prepare` never indexes past `u16`
        // vertices) instead of wrapping to a small capacity.
        let (vertices, made) = match reach {
            Reach::Inside => (v, 0),
            Reach::TwoSided => (v.saturating_add(3usize.saturating_mul(t)), t),
            Reach::Clipped => (
                v.saturating_add(POLY.saturating_mul(t)),
                (POLY - 2).saturating_mul(t),
            ),
        };
        let triangles = t.saturating_add(made);
        Self {
            vertices: self.vertices.saturating_add(vertices),
            values: self
                .values
                .saturating_add(vertices.saturating_mul(layout.stride())),
            packed_values: self.packed_values.saturating_add(vertices.saturating_mul(
                match layout {
                    Layout::GouraudMono => 1,
                    _ => layout.stride(),
                },
            )),
            triangles: self.triangles.saturating_add(triangles),
            made: self.made.saturating_add(made),
            colors: match layout {
                Layout::Flat => self.colors.saturating_add(triangles),
                _ => self.colors,
            },
        }
    }

    /// The same room for a perspective-correct profile: one more value
    /// (the weight `q = near/w`) per vertex (flat objects need none: an
    /// upper bound for them).
    pub const fn perspective(self) -> Self {
        Self {
            values: self.values.saturating_add(self.vertices),
            packed_values: self.packed_values.saturating_add(self.vertices),
            ..self
        }
    }

    /// The room profile `P` needs: [`Self::perspective`] for a
    /// perspective-correct profile, `values` = `packed_values` for one
    /// that packs grey vertices ([`Profile::PACKED_GREY`]), else `self`.
    pub const fn in_profile<P: Profile>(self) -> Self {
        if P::PERSPECTIVE {
            self.perspective()
        } else if P::PACKED_GREY {
            Self {
                values: self.packed_values,
                ..self
            }
        } else {
            self
        }
    }

    /// The larger of each part (one storage for several scenes).
    pub const fn max(self, o: Self) -> Self {
        const fn m(a: usize, b: usize) -> usize {
            if a > b {
                a
            } else {
                b
            }
        }
        Self {
            vertices: m(self.vertices, o.vertices),
            values: m(self.values, o.values),
            packed_values: m(self.packed_values, o.packed_values),
            triangles: m(self.triangles, o.triangles),
            made: m(self.made, o.made),
            colors: m(self.colors, o.colors),
        }
    }

    /// Bytes of a [`Storage`] of these lengths with `value_bytes`-byte
    /// values: 4 per vertex (a [`ScreenXy`]), `value_bytes` per value, 1
    /// (its [`Workspace::faces`] byte) + 2 (its order entry) per triangle
    /// number, 6 per made triangle ([`Tri`]), 3 per colour, the sum
    /// rounded up to the values' alignment (4 bytes, 8 for 8-byte values),
    /// as `size_of` counts it.
    pub const fn bytes(self, value_bytes: usize) -> usize {
        let align = if value_bytes >= 8 { 8 } else { 4 };
        let sum = self
            .vertices
            .saturating_mul(core::mem::size_of::<ScreenXy>())
            .saturating_add(self.values.saturating_mul(value_bytes))
            .saturating_add(self.triangles.saturating_mul(3))
            .saturating_add(self.made.saturating_mul(core::mem::size_of::<Tri>()))
            .saturating_add(self.colors.saturating_mul(core::mem::size_of::<Rgb8>()));
        match sum.checked_add(align - 1) {
            Some(s) => s & !(align - 1),
            None => usize::MAX,
        }
    }
}

/// A prepared frame's memory as arrays: `V` vertices, `N` values of type
/// `L`, `T` triangle numbers (a [`Workspace::faces`] byte each, and an
/// entry of the band renderer's order), `C` flat-triangle colours and `M`
/// triangles made while preparing (clipped fans, two-sided Gouraud back
/// faces; none when the scene's objects lie inside the clipping planes
/// and are culled or not Gouraud), sized by the compiler from a
/// [`Capacity`]. `const` ([`Self::EMPTY`]): it may live in a `static` (in
/// `.bss`).
///
/// Storage sized by the compiler: a prepared frame's memory as arrays
/// whose lengths are const generics, computed by a `const fn` from the
/// meshes a scene uses.
///
/// ```
/// use fixshade::mesh::CUBE;
/// use fixshade::render::{Capacity, Storage};
///
/// const CAP: Capacity = Capacity::of(&[&CUBE, &CUBE]);
/// type CubeStorage = Storage<
///     i32,
///     { CAP.vertices },
///     { CAP.values },
///     { CAP.triangles },
///     { CAP.colors },
///     { CAP.made },
/// >;
/// static STORAGE: CubeStorage = CubeStorage::EMPTY;
/// // The same type, written with the macro:
/// static SAME: fixshade::storage!(i32, CAP) = CubeStorage::EMPTY;
/// assert_eq!(CAP.triangles, 2 * CUBE.triangle_count());
/// ```
///
/// (In a firmware, `static mut STORAGE: CubeStorage = CubeStorage::EMPTY;`
/// in the entry function, which `cortex-m-rt` hands out as
/// `&'static mut`; [`Storage::split`] then lends the [`Workspace`] to
/// [`prepare`](super::prepare) and the order scratch to a
/// [`BandState`](super::BandState).)
///
/// # What the bound covers
/// [`prepare`](super::prepare) takes, per object, room for every mesh
/// vertex (one linear pass) with `stride` values each and a number for
/// every mesh triangle (its [`Workspace::faces`] byte says whether the
/// view keeps it: mesh triangles are read from the mesh, never copied);
/// clipping and the back sides of two-sided Gouraud objects add vertices
/// and made triangles, numbered after the mesh's. A [`Capacity`] adds per
/// object:
///
/// | object ([`Reach`]) | vertices | triangle numbers | made triangles |
/// |--------------------|----------|------------------|----------------|
/// | [`Reach::Inside`]: culled, or two-sided flat or Phong | `V` | `T` | 0 |
/// | [`Reach::TwoSided`]: two-sided Gouraud (back faces lit on their own) | `V + 3T` | `2T` | `T` |
/// | [`Reach::Clipped`]: may be cut by the near, far or guard planes | `V + 9T` | `8T` | `7T` |
///
/// with `V`, `T` the mesh's vertices and triangles, and `stride` values
/// per vertex of the object ([`Layout::stride`]); a clipped triangle
/// becomes a polygon of at most [`MAX_POLY`](super::clip::MAX_POLY) = 9
/// corners, emitted as new vertices, fanned into at most 7 triangles.
/// [`Capacity::perspective`] adds the perspective-correct profiles' weight
/// (one value per vertex); `packed_values` counts one value per grey
/// Gouraud vertex for the profiles that pack its depth and level
/// ([`Capacity::in_profile`] picks what a profile needs). The band order
/// holds the kept triangles (how many a view keeps is known only when
/// the view is: the bunny keeps 1 498 of its 3 674 in the benchmark view)
/// and, in the rest, the triangles put off while the pool is full. A
/// storage smaller than what a frame uses makes `prepare` return
/// [`RenderError::Capacity`](super::RenderError::Capacity), never a panic.
#[derive(Clone, Debug)]
pub struct Storage<
    L,
    const V: usize,
    const N: usize,
    const T: usize,
    const C: usize,
    const M: usize = 0,
> {
    xy: [ScreenXy; V],
    vals: [L; N],
    order: [u16; T],
    faces: [u8; T],
    tris: [Tri; M],
    colors: [Rgb8; C],
}

impl<L: Lerp, const V: usize, const N: usize, const T: usize, const C: usize, const M: usize>
    Storage<L, V, N, T, C, M>
{
    /// Empty storage.
    pub const EMPTY: Self = Self {
        xy: [ScreenXy::ZERO; V],
        vals: [L::ZERO; N],
        order: [0; T],
        faces: [0; T],
        tris: [Tri::EMPTY; M],
        colors: [Rgb8::BLACK; C],
    };

    /// The lengths.
    pub const CAPACITY: Capacity = Capacity {
        vertices: V,
        values: N,
        packed_values: N,
        triangles: T,
        made: M,
        colors: C,
    };

    /// Bytes it takes.
    pub const BYTES: usize = core::mem::size_of::<Self>();

    /// The lengths ([`Self::CAPACITY`]).
    pub const fn capacity(&self) -> Capacity {
        Self::CAPACITY
    }

    /// Empty storage ([`Self::EMPTY`]).
    pub const fn new() -> Self {
        Self::EMPTY
    }

    /// The workspace for [`prepare`](super::prepare).
    pub fn workspace(&mut self) -> Workspace<'_, L> {
        self.split().0
    }

    /// The workspace for [`prepare`](super::prepare) and the order scratch
    /// for a [`BandState`](super::BandState) (one entry per triangle
    /// number).
    pub fn split(&mut self) -> (Workspace<'_, L>, &mut [u16]) {
        (
            Workspace {
                xy: &mut self.xy,
                vals: &mut self.vals,
                tris: &mut self.tris,
                colors: &mut self.colors,
                faces: &mut self.faces,
            },
            &mut self.order,
        )
    }
}

/// The [`Storage`] of a [`Capacity`] constant: `storage!(i32, CAP)` is
/// `Storage<i32, { CAP.vertices }, { CAP.values }, { CAP.triangles }, {
/// CAP.colors }, { CAP.made }>`.
///
/// ```
/// use fixshade::mesh::CUBE;
/// use fixshade::render::Capacity;
///
/// const CAP: Capacity = Capacity::of(&[&CUBE]);
/// static STORAGE: fixshade::storage!(i32, CAP) = <fixshade::storage!(i32, CAP)>::EMPTY;
/// assert_eq!(STORAGE.capacity(), CAP);
/// ```
#[macro_export]
macro_rules! storage {
    ($l:ty, $cap:path) => {
        $crate::render::Storage<
            $l,
            { $cap.vertices },
            { $cap.values },
            { $cap.triangles },
            { $cap.colors },
            { $cap.made },
        >
    };
}

impl<L: Lerp, const V: usize, const N: usize, const T: usize, const C: usize, const M: usize>
    Default for Storage<L, V, N, T, C, M>
{
    fn default() -> Self {
        Self::EMPTY
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    extern crate std;
    use crate::geom::{Affine, Vec3};
    use crate::illum::{Light, Material, Specular, Viewer};
    use crate::mesh::{BUNNY, CUBE};
    use crate::num::{Fast, FastPc, Precise, Real, Q16};
    use crate::render::{prepare, Part, RenderError};
    use crate::scene::{Camera, Object, Scene, Shading};
    use crate::target::Rgb8;
    use std::boxed::Box;

    fn q(v: f64) -> Q16 {
        Q16::from_f64(v)
    }

    fn object(shading: Shading, cull: bool, z: f64, color: [f64; 3]) -> Object<'static, Q16> {
        Object {
            mesh: CUBE,
            transform: Affine::from_parts(
                q(1.0),
                Vec3::new(q(0.4), q(0.6), q(0.0)),
                Vec3::new(q(0.0), q(0.0), q(z)),
            ),
            material: Material {
                color: Vec3::new(q(color[0]), q(color[1]), q(color[2])),
                ka: q(0.1),
                kd: q(0.7),
                ks: q(0.0),
                shininess: q(8.0),
            },
            shading,
            cull_backfaces: cull,
        }
    }

    fn scene<'a>(
        objects: &'a [Object<'static, Q16>],
        lights: &'a [Light<Q16>],
    ) -> Scene<'a, 'static, Q16> {
        let camera = Camera::look_at(
            Vec3::new(q(0.0), q(0.0), q(5.0)),
            Vec3::new(q(0.0), q(0.0), q(0.0)),
            Vec3::new(q(0.0), q(1.0), q(0.0)),
            q(0.8),
            q(1.0),
            None,
        )
        .unwrap();
        Scene {
            camera,
            objects,
            lights,
            ambient: q(0.2),
            specular: Specular::Phong,
            viewer: Viewer::Infinite,
            background: Rgb8::BLACK,
        }
    }

    const CUBE_GREY: Capacity = Capacity::EMPTY.object(&CUBE, Layout::GouraudMono, Reach::Inside);
    type Grey = crate::storage!(i32, CUBE_GREY);

    #[test]
    fn capacities_follow_the_table() {
        let (v, t) = (CUBE.vertex_count(), CUBE.triangle_count());
        assert_eq!(
            CUBE_GREY,
            Capacity {
                vertices: v,
                values: 2 * v,
                packed_values: v,
                triangles: t,
                made: 0,
                colors: 0
            }
        );
        // `fast` packs the grey level with the depth; `precise` does not.
        assert_eq!(CUBE_GREY.in_profile::<Fast>().values, v);
        assert_eq!(CUBE_GREY.in_profile::<Precise>().values, 2 * v);
        assert_eq!(CUBE_GREY.in_profile::<FastPc>().values, 3 * v);
        let c = Capacity::EMPTY.object(&CUBE, Layout::GouraudRgb, Reach::TwoSided);
        assert_eq!(
            (c.vertices, c.values, c.triangles, c.made),
            (v + 3 * t, 4 * (v + 3 * t), 2 * t, t)
        );
        let c = Capacity::EMPTY.object(&CUBE, Layout::Flat, Reach::Clipped);
        assert_eq!(
            (c.vertices, c.values, c.triangles, c.made, c.colors),
            (v + 9 * t, v + 9 * t, 8 * t, 7 * t, 8 * t)
        );
        let all = Capacity::of(&[&BUNNY, &CUBE]);
        assert_eq!(
            all,
            Capacity {
                vertices: BUNNY.vertex_count() + v,
                values: 8 * (BUNNY.vertex_count() + v),
                packed_values: 8 * (BUNNY.vertex_count() + v),
                triangles: BUNNY.triangle_count() + t,
                made: 0,
                colors: BUNNY.triangle_count() + t
            }
        );
        assert_eq!(CUBE_GREY.perspective().values, 3 * v);
        assert_eq!(
            Grey::BYTES,
            CUBE_GREY.bytes(4),
            "4 per vertex, 4 per value, 3 per triangle number"
        );
        assert_eq!(CUBE_GREY.bytes(4), (4 * v + 8 * v + 3 * t + 3) & !3);
        // Made triangles (6 bytes) and colours (3) counted as `size_of`
        // counts them, padding included.
        const CLIPPED: Capacity = Capacity::EMPTY.object(&CUBE, Layout::Flat, Reach::Clipped);
        type Clipped = crate::storage!(i32, CLIPPED);
        assert_eq!(Clipped::BYTES, CLIPPED.bytes(4));
        const ALL: Capacity = Capacity::of(&[&CUBE, &CUBE]);
        type All = crate::storage!(i32, ALL);
        assert_eq!(All::BYTES, ALL.bytes(4));
        assert_eq!(CUBE_GREY.max(all), all);
        // Beyond `usize`: saturated, never wrapped to a small capacity.
        let huge = Capacity {
            vertices: usize::MAX - 1,
            values: usize::MAX - 1,
            packed_values: usize::MAX - 1,
            triangles: usize::MAX / 2,
            made: 0,
            colors: 0,
        };
        let c = huge
            .object(&CUBE, Layout::PhongPosition, Reach::Clipped)
            .perspective();
        assert_eq!(
            (c.vertices, c.values, c.triangles),
            (usize::MAX, usize::MAX, usize::MAX / 2 + 8 * t)
        );
        assert_eq!(huge.bytes(4), usize::MAX);
    }

    #[test]
    fn a_storage_of_the_capacity_prepares_the_scene_and_one_less_fails() {
        let light = [Light::directional(
            Vec3::new(q(0.3), q(0.4), q(0.866)),
            q(1.0),
        )];
        let objects = [object(Shading::Gouraud, true, 0.0, [0.5, 0.5, 0.5])];
        let s = scene(&objects, &light);
        let mut st = Box::new(Grey::new());
        let frame = prepare::<Fast>(&s, 64, 64, st.workspace()).unwrap();
        assert_eq!(frame.vertex_count(), CUBE.vertex_count());
        assert!(frame.triangle_count() > 0);
        // `fast` needs one value per grey vertex: its own capacity
        // prepares the scene, one value less fails.
        const FAST: Capacity = CUBE_GREY.in_profile::<Fast>();
        let mut fast = Box::new(<crate::storage!(i32, FAST)>::new());
        prepare::<Fast>(&s, 64, 64, fast.workspace()).unwrap();
        type Short = Storage<
            i32,
            { FAST.vertices },
            { FAST.values - 1 },
            { FAST.triangles },
            { FAST.colors },
        >;
        let mut short = Box::new(Short::new());
        assert_eq!(
            prepare::<Fast>(&s, 64, 64, short.workspace()).unwrap_err(),
            RenderError::Capacity {
                part: Part::Values,
                object: 0
            }
        );
        // A perspective-correct profile needs the weight too.
        assert!(matches!(
            prepare::<FastPc>(&s, 64, 64, st.workspace()),
            Err(RenderError::Capacity {
                part: Part::Values,
                ..
            })
        ));
        const PC: Capacity = CUBE_GREY.perspective();
        let mut pc = Box::new(<crate::storage!(i32, PC)>::new());
        prepare::<FastPc>(&s, 64, 64, pc.workspace()).unwrap();
    }

    #[test]
    fn two_sided_and_clipped_objects_fit_their_bounds() {
        let light = [Light::directional(
            Vec3::new(q(0.3), q(0.4), q(0.866)),
            q(1.0),
        )];
        // Two-sided colour Gouraud, one cube cut by the near plane (the eye
        // at z = 5, near 1: a cube at z = 4 reaches z = 4.9).
        let objects = [
            object(Shading::Gouraud, false, 0.0, [0.9, 0.5, 0.2]),
            object(Shading::Gouraud, false, 4.0, [0.9, 0.5, 0.2]),
        ];
        let s = scene(&objects, &light);
        const C: Capacity = Capacity::EMPTY
            .object(&CUBE, Layout::GouraudRgb, Reach::TwoSided)
            .object(&CUBE, Layout::GouraudRgb, Reach::Clipped);
        let mut st = Box::new(<crate::storage!(i32, C)>::new());
        let (ws, order) = st.split();
        assert_eq!(order.len(), C.triangles);
        let frame = prepare::<Fast>(&s, 64, 64, ws).unwrap();
        // The clipped cube added vertices beyond its mesh's, and made
        // triangles; the two-sided one made its back faces.
        assert!(frame.objects()[1].verts.len() > CUBE.vertex_count());
        assert!(frame.made_count() > 0 && frame.made_count() <= C.made);
        assert!(frame.vertex_count() <= C.vertices && frame.triangle_count() <= C.triangles);
        assert!(frame.triangle_numbers() <= C.triangles);
        // Sized as if both were inside: too small.
        const IN: Capacity = Capacity::EMPTY
            .object(&CUBE, Layout::GouraudRgb, Reach::Inside)
            .object(&CUBE, Layout::GouraudRgb, Reach::Inside);
        let mut small = Box::new(<crate::storage!(i32, IN)>::new());
        // No room for the two-sided cube's back faces.
        assert_eq!(
            prepare::<Fast>(&s, 64, 64, small.workspace()).unwrap_err(),
            RenderError::Capacity {
                part: Part::Made,
                object: 0
            }
        );
        // Room for them, but the clipped cube's vertices do not fit.
        const MADE: Capacity = Capacity {
            made: C.made,
            triangles: C.triangles,
            ..IN
        };
        let mut small = Box::new(<crate::storage!(i32, MADE)>::new());
        assert_eq!(
            prepare::<Fast>(&s, 64, 64, small.workspace()).unwrap_err(),
            RenderError::Capacity {
                part: Part::Vertices,
                object: 1
            }
        );
    }
}
