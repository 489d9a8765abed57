//! The pipeline: prepare a frame once, then rasterize it band by band.
//!
//! [`prepare`] transforms every object's vertices to eye space, lights them
//! (flat, Gouraud) or keeps their normals and positions (Phong), culls back
//! faces, clips against the near plane (and the far plane and guard band),
//! projects and snaps them to the subpixel grid, all into a caller-provided
//! [`Workspace`]. [`Frame::bands`] / [`Frame::render_bands`] then
//! rasterize the prepared triangles band by band into a
//! [`BandBuf`](crate::target::BandBuf), each triangle set up once per
//! frame and kept in an active list while it crosses band borders (see
//! [`Bands`]); [`Frame::render`] rasterizes them into any [`Target`]
//! holding a window of rows (setting up each triangle reaching the
//! window), with a depth buffer of the same window or none. Rendering a
//! 240×240 frame in 16-row bands needs a band buffer of 7 680 bytes
//! (RGB565) and a depth band of 7 680 bytes (16-bit), plus the band state
//! (2 bytes per triangle number and the pool of active triangles), and
//! gives byte for byte the frame a full-screen render gives.
//!
//! [`Target`]: crate::target::Target
//!
//! # Memory (what a prepared frame costs)
//! | part | bytes |
//! |------|-------|
//! | per prepared vertex | 4 (`xy`, a [`ScreenXy`]) + `stride × size_of::<Lerp>()` (4 for fixed profiles) |
//! | stride, flat | 1 (depth) |
//! | stride, Gouraud | 2 (depth, grey level; 1 in `fast`, which packs both in 16 bits each: [`Layout::GouraudMono`]) or 4 (depth, red, green, blue) |
//! | stride, Phong | 4 (depth, normal), or 7 (depth, normal, eye position) when a point light or the local viewer needs the position |
//! | perspective-correct profiles | one more value per vertex (the weight `q = near/w`), but flat |
//! | per triangle number (every mesh triangle of a prepared object, kept or not) | 1 ([`Workspace::faces`]: kept, first row, back face; a mesh triangle's vertices are read from the mesh, never copied), and 3 (an [`Rgb8`] colour) in a flat object |
//! | per made triangle (fans of clipped triangles, two-sided Gouraud back faces) | 6 ([`Tri`]) and a triangle number |
//! | band state ([`BandState`]) | 2 per triangle number (order scratch: the kept triangles by band, the rest a queue) + [`Pool::SLOT_BYTES`] + 4 per active triangle slot |
//! | the [`Frame`] value itself (the caller's stack) | 20 per [`PreparedObject`], [`MAX_OBJECTS`] = 32 of them: 640 (the mesh triangles are read through the scene's object slice) |
//!
//! A prepared vertex is made per mesh vertex (one per distinct position
//! and normal), in one linear pass, so shared vertices are transformed and
//! lit once and no scratch is needed; clipping and the back sides of
//! two-sided objects add vertices. Figures are checked by tests
//! (`size_of`).
//!
//! # The geometry stage, per object
//! 1. The bounding sphere ([`crate::mesh::Bound`]) against the clipping
//!    planes, once: wholly inside (no outcode, no clipping), wholly outside
//!    one plane (nothing), or across (outcodes per vertex).
//! 2. One pass over the vertices: transform, projection, depth and
//!    lighting. Directional lights without a specular term are moved into
//!    the object's space once (normals by the inverse-transpose, uniform
//!    scales only; other transforms light in eye space with the
//!    renormalised inverse-transpose normal), so a vertex costs three
//!    multiply-adds per light. Every vertex is lit, also those used only
//!    by culled triangles: on the bunny (1839 vertices, 3674 triangles,
//!    1498 kept, whose corners use 906 vertices) lighting on first use by
//!    a kept triangle was measured on the Cortex-M4 at 1.059 M geometry
//!    instructions against 0.966 M for lighting all 1839 in the linear
//!    pass: the 933 lightings saved (63 K instructions) cost less than
//!    testing the 4494 corners of the kept triangles in the triangle loop
//!    (+120 K). Outside vertices are marked in `xy` (never read by the
//!    rasterizer: no kept triangle uses them).
//! 3. One pass over the triangles: back-face sign from the projected
//!    subpixel coordinates (32-bit products for edges below 2^15
//!    subpixels, exact), culling, rows, flat colour (baked face normal,
//!    lit once per kept face).

mod active;
mod band;
pub mod clip;
mod phong_span;
mod position;
mod prepare;
mod storage;

pub use active::{BandState, Bands, Pool, Slot};
pub use band::{PhongShader, RenderStats};
pub use phong_span::{
    KernelError, PhongFill, PhongKernel, PhongKernelShader, PhongSpan, QuadSlot, SpecCache,
    TriQuad, RSQRT_N, SPEC_SEGMENTS,
};
pub use prepare::{max_screen, XY_LIMIT};
pub use prepare::{prepare, prepare_in};
pub use storage::{Capacity, Reach, Storage};

use crate::num::Profile;
use crate::raster::{RasterError, Vertex};
use crate::scene::{Object, SceneError, Shading, MAX_OBJECTS};
use crate::target::{BufferError, Rgb8};
use core::fmt;
use core::ops::Range;

/// Prepared vertices a frame can hold: `2^15` = 32 768 (indices below
/// it fit the 15 low bits of a [`Tri`]'s `u16`s; bit 15 of the first
/// marks a back face).
pub const MAX_VERTICES: usize = 1 << 15;

/// Triangle numbers a frame can hold: `u16::MAX` = 65 535 (each object
/// numbers its mesh's triangles and the triangles it made; the band
/// renderer orders them by `u16` number; [`PreparedObject::tris`] holds
/// them as a `u16` range). [`prepare`] uses at most this many entries of
/// [`Workspace::faces`], [`Workspace::tris`] and [`Workspace::colors`]: a
/// frame that needs more is a [`RenderError::Capacity`] error
/// ([`Part::Triangles`]).
pub const MAX_TRIANGLES: usize = u16::MAX as usize;

/// Bit 15 of a [`Tri`]'s first index: a back face.
const BACK: u16 = 1 << 15;

/// A [`Workspace::faces`] byte: a back face (of an object drawn
/// two-sided).
pub(crate) const FACE_BACK: u8 = 1 << 7;
/// The bits of a [`Workspace::faces`] byte that hold a kept triangle's
/// first row `r` as `(r >> face_shift(height)) + 1` (1 to 127; 0: not
/// kept).
pub(crate) const FACE_ROW: u8 = FACE_BACK - 1;

/// The kept triangles counted by [`Workspace::faces`] row code (entry
/// `c`: the bytes with `b & FACE_ROW == c`; entry 0 unused), as
/// [`prepare`] keeps them: the band sort's counts without a pass of its
/// own over the bytes.
pub(crate) type FaceRows = [u16; FACE_ROW as usize + 1];

/// The shift of the rows in [`Workspace::faces`] bytes for a screen of
/// `height` rows: the least `q` with `(height - 1) >> q` at most 126, so
/// that every first row `r` of a kept triangle (below the height) stores
/// as `(r >> q) + 1` in 7 bits (0 for 127 rows or fewer, 1 for 240, 6 for
/// [`MAX_SCREEN`](crate::target::MAX_SCREEN) = 4096).
#[inline(always)]
pub(crate) const fn face_shift(height: u32) -> u32 {
    let mut q = 0;
    while q < 31 && (height.saturating_sub(1) >> q) > 126 {
        q += 1;
    }
    q
}

/// The [`Workspace::faces`] byte of a kept triangle whose first row is
/// `row` (below the height) on a screen of row shift `q`
/// ([`face_shift`]).
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
pub(crate) const fn face_byte(row: u32, q: u32, back: bool) -> u8 {
    (((row >> q) + 1) as u8 & FACE_ROW) | if back { FACE_BACK } else { 0 }
}

/// One triangle made while preparing (a fan of a clipped triangle, or a
/// back face of a two-sided Gouraud object) as stored: three
/// prepared-vertex indices, 6 bytes. Bit 15 of the first marks a back
/// face (of an object drawn two-sided), so vertex indices stay below
/// [`MAX_VERTICES`]. The rows a triangle can cover are recomputed from its
/// vertices' `y` ([`Frame::tri_rows`]); a flat triangle's colour lies in
/// [`Workspace::colors`]. Mesh triangles are not stored: the frame reads
/// their vertices from the mesh.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tri([u16; 3]);

impl Tri {
    /// An unused slot (for workspace arrays in `static`s: `Default` is not
    /// `const`).
    pub const EMPTY: Self = Self([0; 3]);

    /// Vertices `v` (each below [`MAX_VERTICES`]), a back face or not.
    #[inline(always)]
    pub const fn new(v: [u16; 3], back: bool) -> Self {
        Self([v[0] | if back { BACK } else { 0 }, v[1], v[2]])
    }

    /// The prepared vertices.
    #[inline(always)]
    pub const fn v(self) -> [u16; 3] {
        [self.0[0] & !BACK, self.0[1], self.0[2]]
    }

    /// A back face (of an object drawn two-sided): Phong flips its normal.
    #[inline(always)]
    pub const fn back(self) -> bool {
        self.0[0] & BACK != 0
    }
}

/// One prepared triangle as read ([`Frame::tri`]): three prepared-vertex
/// indices, the flat colour (flat shading; black otherwise) and whether
/// it is a back face drawn two-sided. Read from the mesh and a
/// [`Workspace::faces`] byte (or a made [`Tri`]) and, for a flat object,
/// a colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct PreparedTri {
    /// Prepared vertices.
    pub v: [u16; 3],
    /// Colour of a flat-shaded triangle.
    pub color: Rgb8,
    /// A back face (of an object drawn two-sided): Phong flips its normal.
    pub back: bool,
}

/// The stored screen position of a prepared vertex: `[x, y]` in
/// subpixels (`1/2^s` of a pixel, `s` the profile's
/// [`SubpixelBits`](crate::num::SubpixelBits)), each within
/// ±[`XY_LIMIT`] = ±32 766 so that it fits an `i16` (4 bytes a vertex
/// instead of 8). Profiles with at most 4 subpixel bits store the
/// position from the screen's top-left corner; profiles with more count
/// from the screen's centre (`[w, h] · 2^s / 2`), which
/// [`Frame::xy`] adds back. [`prepare`] narrows the guard band so that
/// every stored position fits (see [`max_screen`]); `i16::MIN` and
/// `i16::MIN + 1` mark vertices that are never drawn.
///
/// Aligned as a word (`repr(C, align(4))`): the triangle loops read a
/// position as one 32-bit load on every ARM target.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(C, align(4))]
pub struct ScreenXy(pub [i16; 2]);

/// A screen position in subpixels (`1/2^s` of a pixel, `s` the profile's
/// [`SubpixelBits`](crate::num::SubpixelBits)), `[x, y]` from the
/// screen's top-left corner unless said otherwise (an origin of stored
/// positions, [`prepare::xy_origin`]): the wide form of a [`ScreenXy`],
/// not to be mixed with raw Q16 bits or depths. Zero-cost (`i32` pairs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(transparent)]
pub(crate) struct Subpx(pub(crate) [i32; 2]);

impl ScreenXy {
    /// The origin.
    pub const ZERO: Self = Self([0; 2]);

    /// The position as one word `y·2^16 | x` (the two 16-bit halves'
    /// bits, `x` low): one load where the target loads unaligned words
    /// (ARMv7-M, x86).
    #[inline(always)]
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
    pub(crate) fn word(self) -> i32 {
        (u32::from(self.0[0] as u16) | (u32::from(self.0[1] as u16) << 16)) as i32
    }

    /// The subpixel position `p` (from the screen's top-left corner)
    /// stored from `origin`, known to lie within ±[`XY_LIMIT`] of it
    /// (the inside kernels: the guard band bounds it). A plain cast.
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    pub(crate) fn pack(Subpx(p): Subpx, Subpx(origin): Subpx) -> Self {
        Self([(p[0] - origin[0]) as i16, (p[1] - origin[1]) as i16])
    }

    /// [`Self::pack`] clamped to ±[`XY_LIMIT`] (positions that rounding
    /// or a saturated scalar may have moved out of the range; a no-op
    /// for the others).
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    pub(crate) fn pack_clamped(Subpx(p): Subpx, Subpx(origin): Subpx) -> Self {
        let c = |v: i32, o: i32| v.saturating_sub(o).clamp(-XY_LIMIT, XY_LIMIT) as i16;
        Self([c(p[0], origin[0]), c(p[1], origin[1])])
    }

    /// The subpixel position from the screen's top-left corner, for a
    /// position stored from `origin`.
    #[inline(always)]
    pub(crate) fn unpack(self, Subpx(origin): Subpx) -> Subpx {
        Subpx([
            i32::from(self.0[0]) + origin[0],
            i32::from(self.0[1]) + origin[1],
        ])
    }
}

/// Caller-provided memory for a prepared frame: slices the caller brings
/// (for arrays sized by the compiler from the scene's meshes, see
/// [`Storage`] and [`Capacity`]). Too short a part makes [`prepare`]
/// return [`RenderError::Capacity`] naming it.
#[derive(Debug)]
pub struct Workspace<'a, L> {
    /// Screen positions of prepared vertices ([`ScreenXy`]).
    pub xy: &'a mut [ScreenXy],
    /// Depth and attributes of prepared vertices, `stride` per vertex.
    pub vals: &'a mut [L],
    /// Triangles made while preparing: the fans of clipped triangles and
    /// the back faces of two-sided Gouraud objects (lit in vertices of
    /// their own). A mesh triangle is never copied here: the frame reads
    /// its vertices from the mesh.
    pub tris: &'a mut [Tri],
    /// Colours of the triangles of flat objects, one per triangle number
    /// (see [`Self::faces`]), object after object.
    pub colors: &'a mut [Rgb8],
    /// One byte per triangle number: each object numbers its mesh's
    /// triangles, then the triangles it made ([`Self::tris`]); the byte
    /// says whether the view keeps the triangle, where it starts (its
    /// first row, coarsened to 7 bits on screens of more than 127 rows:
    /// the band renderer orders the kept triangles by band from it) and
    /// whether it is a back face.
    pub faces: &'a mut [u8],
}

/// How an object's prepared vertices are laid out and shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Depth only; colour per triangle.
    Flat,
    /// Depth and one grey level (grey material, white lights).
    ///
    /// In the profiles that pack them ([`Profile::PACKED_GREY`]: `fast`)
    /// both share one `i32` per vertex (the depth's 16 high bits in the high
    /// half, the level in Q8.8 in the low half; 4 bytes of values
    /// instead of 8: the bunny's prepared frame 18 386 bytes instead of
    /// 25 742): the depth keeps its 16 high bits, within `2^-17` of the
    /// depth range at each vertex, and the level 8 fraction bits, within
    /// `2^-9` of a level. A 16-bit depth buffer keeps those 16 bits
    /// anyway; a 32-bit one ([`crate::target::Depth32`]) still gets
    /// depths interpolated in Q2.30 between the vertices, but the vertex
    /// depths themselves are only 16-bit exact, so surfaces closer than
    /// `2^-16` of the depth range (after the projection's `far / (far -
    /// near)` scaling) may order differently than with the profiles that
    /// keep 30 bits (`precise`, the float ones).
    GouraudMono,
    /// Depth and three colour levels.
    GouraudRgb,
    /// Depth and a normal.
    PhongNormal,
    /// Depth, a normal and an eye-space position.
    PhongPosition,
}

impl Layout {
    /// Interpolated values per prepared vertex (affine interpolation).
    pub const fn stride(self) -> usize {
        match self {
            Self::Flat => 1,
            Self::GouraudMono => 2,
            Self::GouraudRgb | Self::PhongNormal => 4,
            Self::PhongPosition => 7,
        }
    }

    /// Interpolated values per prepared vertex; perspective-correct
    /// interpolation adds the weight `q = near/w` to every layout but flat.
    pub const fn stride_for(self, perspective: bool) -> usize {
        match (self, perspective) {
            (Self::Flat, _) | (_, false) => self.stride(),
            (_, true) => self.stride() + 1,
        }
    }

    /// Values per prepared vertex with profile `P`: [`Self::stride_for`]
    /// `(P::PERSPECTIVE)`, but 1 for [`Self::GouraudMono`] in the profiles
    /// that pack depth and grey level into one value
    /// ([`Profile::PACKED_GREY`], see [`Self::GouraudMono`]).
    pub const fn values_in<P: Profile>(self) -> usize {
        match self {
            Self::GouraudMono if P::PACKED_GREY && !P::PERSPECTIVE => 1,
            _ => self.stride_for(P::PERSPECTIVE),
        }
    }

    /// Whether profile `P` stores this layout's depth and grey level
    /// packed in one value (see [`Self::GouraudMono`]).
    #[inline(always)]
    pub const fn packed_in<P: Profile>(self) -> bool {
        matches!(self, Self::GouraudMono) && P::PACKED_GREY && !P::PERSPECTIVE
    }

    /// The shading mode.
    pub const fn shading(self) -> Shading {
        match self {
            Self::Flat => Shading::Flat,
            Self::GouraudMono | Self::GouraudRgb => Shading::Gouraud,
            _ => Shading::Phong,
        }
    }
}

/// The depth half of a packed grey vertex ([`Profile::PACKED_GREY`]):
/// the 16 high bits of a Q2.30 depth `d` in `[0, 2^30]` (`d >> 14`, the
/// bits a 16-bit depth buffer keeps, saturated to `0..=65535`) in the high
/// half of the value. [`unpack_grey`] gives back `d` within `2^13`
/// (half a step of a 16-bit depth buffer, `2^-17` of the depth range).
#[inline(always)]
#[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
pub(crate) fn grey_depth(d: i32) -> i32 {
    (((d >> 14).clamp(0, 0xFFFF) as u32) << 16) as i32
}

/// The level half of a packed grey vertex: a Q16 grey level `l` in
/// `[0, 255 · 2^16]` rounded to Q8.8 in the low half of the value.
/// [`unpack_grey`] gives back `l` within `2^7` (`2^-9` of a level), and
/// never above `255 · 2^16`.
#[inline(always)]
pub(crate) fn grey_level(l: i32) -> i32 {
    (l.saturating_add(1 << 7) >> 8).clamp(0, 0xFFFF)
}

/// Depth and grey level of a packed grey vertex ([`grey_depth`] `|`
/// [`grey_level`]): the depth in Q2.30 (the middle of its 16-bit step:
/// below `2^30`) and the level in Q16.
#[inline(always)]
#[allow(clippy::cast_sign_loss, clippy::cast_possible_wrap)]
pub(crate) fn unpack_grey(v: i32) -> (i32, i32) {
    let u = v as u32;
    (
        (((u >> 16) << 14) | (1 << 13)) as i32,
        ((u & 0xFFFF) << 8) as i32,
    )
}

/// Depth and grey level packed in one value: [`grey_depth`] `|`
/// [`grey_level`].
#[inline(always)]
pub(crate) fn pack_grey(d: i32, l: i32) -> i32 {
    grey_depth(d) | grey_level(l)
}

/// One object of a prepared frame: 20 bytes (indices as `u16`: below
/// [`MAX_VERTICES`] vertices and [`MAX_TRIANGLES`] triangle numbers;
/// values below `MAX_VERTICES × 8` = 2^18, packed in one word with the
/// stride, the layout and the object's index), so that a frame's object
/// list ([`MAX_OBJECTS`] of them) stays small on the stack.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PreparedObject {
    /// Its prepared vertices.
    pub verts: Range<u16>,
    /// Its triangle numbers: its mesh's triangles (those the view keeps
    /// are marked in [`Workspace::faces`]), then the triangles it made
    /// (all kept). Empty when it keeps none.
    pub tris: Range<u16>,
    /// Index of its first made triangle in [`Workspace::tris`].
    pub made_base: u16,
    /// Index of its first triangle's colour in [`Workspace::colors`] (flat
    /// objects; the others have none): triangle number `t`'s colour is at
    /// `color_base + t - tris.start`.
    pub color_base: u16,
    /// Rows `rows[0]..rows[1]` that hold every row its triangles can cover
    /// (possibly more: for an object wholly on screen, every row of the
    /// screen; empty when it has no triangle): a band
    /// outside them skips the object.
    pub rows: [u16; 2],
    /// [`Self::val_base`] (bits 0 to 17), [`Self::stride`] (bits 18 to
    /// 21), [`Self::layout`] (bits 22 to 24) and [`Self::object`] (bits 25
    /// to 29).
    packed: u32,
}

/// Bits of [`PreparedObject::val_base`] in its packed word.
const VAL_BITS: u32 = 18;

/// The bit of [`PreparedObject::kernel_fit`] in its packed word (above the
/// object's index).
const FIT_BIT: u32 = 1 << 30;

impl PreparedObject {
    /// An object of layout `layout` whose `stride` values per vertex start
    /// at `val_base` (below 2^18; `stride` below 16), object `object`
    /// (below [`MAX_OBJECTS`]) of its scene.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        layout: Layout,
        stride: usize,
        val_base: usize,
        object: usize,
        verts: Range<u16>,
        tris: Range<u16>,
        made_base: u16,
        color_base: u16,
        rows: [u16; 2],
    ) -> Self {
        const _: () = assert!(MAX_VERTICES * 8 <= 1 << VAL_BITS && MAX_OBJECTS <= 32);
        let packed = (val_base as u32 & ((1 << VAL_BITS) - 1))
            | (stride as u32 & 15) << VAL_BITS
            | (layout as u32) << (VAL_BITS + 4)
            | (object as u32 & 31) << (VAL_BITS + 7);
        Self {
            verts,
            tris,
            made_base,
            color_base,
            rows,
            packed,
        }
    }

    /// Layout of its vertices.
    #[inline(always)]
    pub fn layout(&self) -> Layout {
        match (self.packed >> (VAL_BITS + 4)) & 7 {
            0 => Layout::Flat,
            1 => Layout::GouraudMono,
            2 => Layout::GouraudRgb,
            3 => Layout::PhongNormal,
            _ => Layout::PhongPosition,
        }
    }

    /// Values per prepared vertex.
    #[inline(always)]
    pub fn stride(&self) -> usize {
        ((self.packed >> VAL_BITS) & 15) as usize
    }

    /// Index of its first value in [`Workspace::vals`].
    #[inline(always)]
    pub fn val_base(&self) -> usize {
        (self.packed & ((1 << VAL_BITS) - 1)) as usize
    }

    /// Its index in the scene (whose mesh holds its triangles).
    #[inline(always)]
    pub fn object(&self) -> usize {
        ((self.packed >> (VAL_BITS + 7)) & 31) as usize
    }

    /// Every triangle it keeps is fit for the small-triangle kernel's
    /// fast head ([`crate::raster::fast`]'s `draw_small` with `fit`): its
    /// corners within the screen's box as `prepare` proved them (`0 <= x
    /// <= width·S - S/2`, `0 <= y <= height·S`, both bounds below `2^14`
    /// and `height·S` within the coordinate limit, stored from the
    /// screen's corner), every depth within the kernel's vertex test, a
    /// non-zero area and at least one row. Bit 30 of its packed word: no
    /// RAM of its own.
    #[inline(always)]
    pub(crate) fn kernel_fit(&self) -> bool {
        self.packed & FIT_BIT != 0
    }

    /// Marks it [`Self::kernel_fit`] (prepare only, for an object whose
    /// every kept triangle is).
    #[inline(always)]
    pub(crate) fn set_kernel_fit(&mut self) {
        self.packed |= FIT_BIT;
    }

    /// Flat-triangle colours it holds (one per triangle number when flat,
    /// else none).
    pub fn color_count(&self) -> usize {
        if self.layout() == Layout::Flat {
            self.tris.len()
        } else {
            0
        }
    }
}

/// A prepared frame: the workspace filled for one scene.
#[derive(Debug)]
pub struct Frame<'w, P: Profile> {
    ws: Workspace<'w, P::Lerp>,
    /// [`Workspace::faces`].
    faces: &'w [u8],
    /// The kept triangles by row code of [`Self::faces`].
    face_rows: FaceRows,
    /// The scene's objects, whose meshes hold the triangles.
    scene: &'w [Object<'w, P::Real>],
    objects: heapless::Vec<PreparedObject, MAX_OBJECTS>,
    width: u32,
    height: u32,
}

impl<P: Profile> Frame<'_, P> {
    /// The prepared objects.
    pub fn objects(&self) -> &[PreparedObject] {
        &self.objects
    }

    /// Prepared vertices in use.
    pub fn vertex_count(&self) -> usize {
        self.objects.last().map_or(0, |o| usize::from(o.verts.end))
    }

    /// Prepared triangles: the triangles the view keeps (those the band
    /// renderer orders), counted from their [`Workspace::faces`] bytes,
    /// four at a time (about two instructions per triangle number).
    pub fn triangle_count(&self) -> usize {
        let faces = self.faces.get(..self.triangle_numbers()).unwrap_or(&[]);
        let mut quads = faces.chunks_exact(4);
        let mut n = 0;
        // Per byte lane: 1 when the byte is a kept triangle's (its low 7
        // bits plus 0x7F carry into bit 7, never into the next lane);
        // summed over at most 255 words per lane before folding.
        let rows = u32::from_le_bytes([FACE_ROW; 4]);
        loop {
            let mut lanes = 0u32;
            let mut words = 0;
            for q in quads.by_ref() {
                let w = u32::from_le_bytes([q[0], q[1], q[2], q[3]]) & rows;
                lanes += ((w + rows) >> 7) & 0x0101_0101;
                words += 1;
                if words == 255 {
                    break;
                }
            }
            n += (lanes & 0xFF) + ((lanes >> 8) & 0xFF) + ((lanes >> 16) & 0xFF) + (lanes >> 24);
            if words < 255 {
                break;
            }
        }
        n as usize
            + quads
                .remainder()
                .iter()
                .filter(|&&b| b & FACE_ROW != 0)
                .count()
    }

    /// Triangle numbers in use (the kept ones among them: see
    /// [`Workspace::faces`]).
    pub fn triangle_numbers(&self) -> usize {
        self.objects.last().map_or(0, |o| usize::from(o.tris.end))
    }

    /// Triangles made while preparing in use ([`Workspace::tris`]).
    pub fn made_count(&self) -> usize {
        self.objects
            .iter()
            .map(|o| o.tris.len().saturating_sub(self.mesh_tris(o).len()))
            .sum()
    }

    /// Flat-triangle colours in use.
    fn color_count(&self) -> usize {
        self.objects.iter().map(PreparedObject::color_count).sum()
    }

    /// Bytes of workspace in use: the prepared vertices' positions,
    /// values, the triangle numbers' bytes ([`Workspace::faces`]), the made
    /// triangles and flat colours, each counted at its stored size
    /// (`size_of`), without the band renderer's order scratch.
    pub fn bytes_used(&self) -> usize {
        use core::mem::size_of;
        let vals = self
            .objects
            .last()
            .map_or(0, |o| o.val_base() + o.verts.len() * o.stride());
        self.vertex_count() * size_of::<ScreenXy>()
            + vals * size_of::<P::Lerp>()
            + self.triangle_numbers()
            + self.made_count() * size_of::<Tri>()
            + self.color_count() * size_of::<Rgb8>()
    }

    /// Screen width and height the frame was prepared for.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Whether the view keeps triangle number `i`.
    #[inline(always)]
    pub fn kept(&self, i: usize) -> bool {
        self.faces.get(i).is_some_and(|f| f & FACE_ROW != 0)
    }

    /// Triangle number `i` of object `po` (a number in `po.tris`; read
    /// whether the view keeps it or not: [`Self::kept`]): a mesh
    /// triangle's vertices from the mesh (offset by the object's first
    /// vertex), its back-face bit from [`Workspace::faces`]; a made
    /// triangle from [`Workspace::tris`].
    #[inline(always)]
    pub fn tri(&self, po: &PreparedObject, i: usize) -> Option<PreparedTri> {
        self.tri_of(po, self.mesh_tris(po), i)
    }

    /// [`Self::tri`] with `po`'s mesh triangles ([`Self::mesh_tris`])
    /// looked up by the caller, once per object rather than per triangle.
    #[inline(always)]
    pub(crate) fn tri_of(
        &self,
        po: &PreparedObject,
        mesh: &[[u16; 3]],
        i: usize,
    ) -> Option<PreparedTri> {
        self.tri_in(po, mesh, i, po.layout() == Layout::Flat)
    }

    /// [`Self::tri_of`] for an object whose layout the caller knows: `flat`
    /// when it is [`Layout::Flat`] (the colour read), else not (black).
    #[inline(always)]
    pub(crate) fn tri_in(
        &self,
        po: &PreparedObject,
        mesh: &[[u16; 3]],
        i: usize,
        flat: bool,
    ) -> Option<PreparedTri> {
        let k = i.checked_sub(usize::from(po.tris.start))?;
        // An object that keeps a triangle numbers its mesh's triangles
        // from `tris.start` on, its made ones from `made` =
        // `tris.start + mesh.len()` on.
        let (v, back) = match mesh.get(k) {
            Some(t) => {
                let b = po.verts.start;
                // Below `MAX_VERTICES` (checked by the vertex pass).
                (
                    t.map(|x| b.wrapping_add(x)),
                    self.faces.get(i).is_some_and(|f| f & FACE_BACK != 0),
                )
            }
            None => {
                let m = k - mesh.len();
                let p = *self.ws.tris.get(usize::from(po.made_base) + m)?;
                (p.v(), p.back())
            }
        };
        let color = if flat {
            self.ws
                .colors
                .get(usize::from(po.color_base) + k)
                .copied()?
        } else {
            Rgb8::BLACK
        };
        Some(PreparedTri { v, color, back })
    }

    /// The triangles of object `po`'s mesh.
    #[inline(always)]
    pub(crate) fn mesh_tris(&self, po: &PreparedObject) -> &[[u16; 3]] {
        self.scene
            .get(po.object())
            .map_or(&[], |o| o.mesh.triangles())
    }

    /// The object of triangle number `i` (`None` past the last).
    pub fn object_of(&self, i: usize) -> Option<&PreparedObject> {
        self.objects
            .iter()
            .find(|o| i >= usize::from(o.tris.start) && i < usize::from(o.tris.end))
    }

    /// The prepared vertices of triangle number `i` (below
    /// [`Self::triangle_numbers`]).
    pub fn tri_vertices(&self, i: usize) -> Option<[u16; 3]> {
        self.tri(self.object_of(i)?, i).map(|t| t.v)
    }

    /// Rows `rows[0]..rows[1]` of the screen whose centres lie within the
    /// vertical extent of the triangle of vertices `v` (the rows the
    /// rasterizer visits), clamped to the screen: recomputed from the
    /// vertices' `y`, the same rows `prepare` kept the triangle for (a
    /// kept triangle has `rows[0] < rows[1]`).
    #[inline(always)]
    pub fn tri_rows(&self, v: [u16; 3]) -> [u16; 2] {
        let y = |k: usize| self.xy(usize::from(v[k])).map_or(0, |p| p[1]);
        let (a, b, c) = (y(0), y(1), y(2));
        let sub = P::SUBPIXEL_BITS;
        // `max`/`min` rather than `clamp` (no panic branch); the height is
        // at most `MAX_SCREEN` = 4096 rows.
        let h = self.height.min(u32::from(u16::MAX)) as i32;
        let r = |y: i32| crate::raster::first_row(y, sub).max(0).min(h) as u16;
        [r(a.min(b).min(c)), r(a.max(b).max(c))]
    }

    /// The first row of [`Self::tri_rows`] alone.
    #[inline(always)]
    pub fn tri_first_row(&self, v: [u16; 3]) -> u16 {
        let y = |k: usize| self.xy(usize::from(v[k])).map_or(0, |p| p[1]);
        let h = self.height.min(u32::from(u16::MAX)) as i32;
        let top = y(0).min(y(1)).min(y(2));
        crate::raster::first_row(top, P::SUBPIXEL_BITS)
            .max(0)
            .min(h) as u16
    }

    /// The kept triangles of object `po`, in order.
    #[inline(always)]
    pub fn object_tris(&self, po: &PreparedObject) -> impl Iterator<Item = PreparedTri> + '_ {
        let po = po.clone();
        po.tris
            .clone()
            .filter(move |&i| self.kept(usize::from(i)))
            .map_while(move |i| self.tri(&po, usize::from(i)))
    }

    /// Every kept triangle, object after object.
    pub fn tris(&self) -> impl Iterator<Item = PreparedTri> + '_ {
        self.objects.iter().flat_map(|po| self.object_tris(po))
    }

    /// Screen position of prepared vertex `v` (subpixels from the
    /// screen's top-left corner; stored as a [`ScreenXy`]).
    pub fn xy(&self, v: usize) -> Option<[i32; 2]> {
        let o = prepare::xy_origin::<P>(self.width, self.height);
        self.ws.xy.get(v).map(|p| p.unpack(o).0)
    }

    /// Prepared vertex `i` of object `po` (depth and the first `N`
    /// interpolated values), whose screen position `[x, y]` the caller
    /// fetched ([`Self::xy`]); `None` when `i` is not one of `po`'s.
    pub fn vertex<const N: usize>(
        &self,
        po: &PreparedObject,
        i: u16,
        [x, y]: [i32; 2],
    ) -> Option<Vertex<P::Lerp, N>> {
        let i = usize::from(i);
        let base = po.val_base() + i.checked_sub(usize::from(po.verts.start))? * po.stride();
        // (Grey objects read one value besides the depth: the other
        // readers need no test.)
        if N == 1 && po.layout().packed_in::<P>() {
            let (z, l) = unpack_grey(crate::raster::Lerp::fixed_raw(*self.ws.vals.get(base)?)?);
            let l = <P::Lerp as crate::raster::Lerp>::from_fixed_raw(l);
            return Some(Vertex {
                x,
                y,
                z: <P::Lerp as crate::raster::Lerp>::from_fixed_raw(z),
                attrs: [l; N],
            });
        }
        let vals = self.ws.vals.get(base..base + 1 + N)?;
        let mut attrs = [vals[0]; N];
        attrs.copy_from_slice(&vals[1..]);
        Some(Vertex {
            x,
            y,
            z: vals[0],
            attrs,
        })
    }
}

/// Which workspace part ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Part {
    /// [`Workspace::xy`].
    Vertices,
    /// [`Workspace::vals`].
    Values,
    /// [`Workspace::faces`]: the triangle numbers.
    Triangles,
    /// [`Workspace::colors`].
    Colors,
    /// The order scratch of a [`BandState`]: shorter than the prepared
    /// triangles ([`Frame::triangle_count`]), or its rest (the queue of
    /// triangles put off while the pool was full) too short for them.
    Order,
    /// [`Workspace::tris`]: the triangles made while preparing (fans of
    /// clipped triangles, back faces of two-sided Gouraud objects).
    Made,
}

/// Why a frame could not be prepared or rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RenderError {
    /// A workspace part is too small (which part, and the object being
    /// prepared).
    Capacity {
        /// The part.
        part: Part,
        /// Index of the object being prepared.
        object: usize,
    },
    /// An object shaded Gouraud or Phong has a mesh without normals.
    MissingNormals {
        /// Index of the object.
        object: usize,
    },
    /// An object exceeds the profile's scalar: a coordinate of its
    /// bounding sphere in eye space (or a partial sum of its transform)
    /// reaches `limit` units, half the scalar's range (16384 for `Q16`,
    /// 2^31 for `Q32`), where saturation would move it silently; or the
    /// clipping planes cut it and it is `limit` units across or more, where
    /// the scalar's resolution could move clipped vertices by more than a
    /// pixel (`2·near / (ε·k)` units, `ε` the resolution, `k` the
    /// projection scale in pixels: 452 units for `Q16` at 240 rows, 45°,
    /// near 1).
    OutOfRange {
        /// Index of the object.
        object: usize,
        /// The limit, in eye-space units.
        limit: i64,
    },
    /// The scene is invalid.
    Scene(SceneError),
    /// A buffer is invalid.
    Buffer(BufferError),
    /// The rasterizer refused a triangle (should not happen after clipping).
    Raster(RasterError),
    /// The target's width differs from the prepared frame's, or its rows
    /// lie below the frame.
    Window,
}

impl fmt::Display for RenderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Capacity { part, object } => {
                write!(
                    f,
                    "workspace too small ({part:?}) while preparing object {object}"
                )
            }
            Self::MissingNormals { object } => write!(
                f,
                "object {object} is shaded Gouraud or Phong but its mesh has no normals"
            ),
            Self::OutOfRange { object, limit } => write!(
                f,
                "object {object} exceeds the {limit}-unit limit of this profile's number format \
                 (eye-space reach, or size of an object the clipping planes cut)"
            ),
            Self::Scene(e) => write!(f, "{e}"),
            Self::Buffer(e) => write!(f, "{e}"),
            Self::Raster(e) => write!(f, "{e}"),
            Self::Window => write!(f, "the target does not match the prepared frame's size"),
        }
    }
}

impl core::error::Error for RenderError {}

impl From<SceneError> for RenderError {
    fn from(e: SceneError) -> Self {
        Self::Scene(e)
    }
}

impl From<BufferError> for RenderError {
    fn from(e: BufferError) -> Self {
        Self::Buffer(e)
    }
}

impl From<RasterError> for RenderError {
    fn from(e: RasterError) -> Self {
        Self::Raster(e)
    }
}

#[cfg(test)]
mod tests;
