//! The pipeline: prepare a frame once, then rasterize it band by band.
//!
//! [`prepare`] transforms every object's vertices to eye space, lights them
//! (flat, Gouraud) or keeps their normals and positions (Phong), culls back
//! faces, clips against the near plane (and the far plane and guard band),
//! projects and snaps them to the subpixel grid, all into a caller-provided
//! [`Workspace`]. [`Frame::render`] then rasterizes the prepared triangles
//! into a target holding any window of rows, with a depth buffer of the same
//! window or none. Rendering a 240×240 frame in 16-row bands needs a band
//! buffer of 7 680 bytes (RGB565) and a depth band of 7 680 bytes (16-bit),
//! and gives byte for byte the frame a full-screen render gives.
//!
//! # Memory (what a prepared frame costs)
//! | part | bytes |
//! |------|-------|
//! | per prepared vertex | 8 (`xy`) + `stride × size_of::<Lerp>()` (4 for fixed profiles) |
//! | stride, flat | 1 (depth) |
//! | stride, Gouraud | 2 (depth, grey level) or 4 (depth, red, green, blue) |
//! | stride, Phong | 4 (depth, normal), or 7 (depth, normal, eye position) when a point light or the local viewer needs the position |
//! | perspective-correct profiles | one more value per vertex (the weight `q = near/w`), but flat |
//! | per prepared triangle | 14 ([`Tri`]) |
//! | scratch while preparing | 2 per mesh vertex of the largest mesh ([`Workspace::heads`]) + 6 per prepared vertex ([`Link`]) |
//!
//! A prepared vertex is made per distinct (position, normal) corner of a
//! mesh, so shared vertices are transformed and lit once; clipping and the
//! back sides of two-sided objects add vertices. Figures are checked by
//! tests (`size_of`).

mod band;
pub mod clip;
mod phong_span;
mod prepare;

pub use band::PhongShader;
pub use band::{render_in_bands, RenderStats};
pub use phong_span::{KernelError, PhongFill, PhongKernel, PhongSpan, RSQRT_N, SPEC_SEGMENTS};
pub use prepare::prepare;

use crate::num::Profile;
use crate::raster::RasterError;
use crate::scene::{SceneError, Shading, MAX_OBJECTS};
use crate::target::{BufferError, Rgb8};
use core::fmt;
use core::ops::Range;

/// One prepared triangle: three prepared-vertex indices, the rows whose
/// pixel centres it can cover, the flat colour (flat shading) and whether
/// it is a back face drawn two-sided.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tri {
    /// Prepared vertices.
    pub v: [u16; 3],
    /// Rows `rows[0]..rows[1]` of the screen whose centres lie within the
    /// triangle's vertical extent (the rows the rasterizer visits), clamped
    /// to the screen: a band skips the triangle with two comparisons. A
    /// prepared triangle always has `rows[0] < rows[1]`; triangles that
    /// cover no pixel centre of the screen are not kept.
    pub rows: [u16; 2],
    /// Colour of a flat-shaded triangle.
    pub color: Rgb8,
    /// A back face (of an object drawn two-sided): Phong flips its normal.
    pub back: bool,
}

impl Tri {
    /// An unused slot (for workspace arrays in `static`s: `Default` is not
    /// `const`).
    pub const EMPTY: Self = Self {
        v: [0; 3],
        rows: [0; 2],
        color: Rgb8::BLACK,
        back: false,
    };
}

/// Scratch link of a prepared vertex while preparing: the mesh normal it
/// was made with, the next prepared vertex of the same position, its
/// outcode and whether its Gouraud colour is still to be computed (it is
/// computed when a kept triangle first uses the vertex, so vertices of
/// culled triangles only are never lit).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Link {
    normal: u16,
    next: u16,
    code: u8,
    unlit: bool,
}

/// Caller-provided memory for a prepared frame.
#[derive(Debug)]
pub struct Workspace<'a, L> {
    /// Screen positions of prepared vertices (subpixels).
    pub xy: &'a mut [[i32; 2]],
    /// Depth and attributes of prepared vertices, `stride` per vertex.
    pub vals: &'a mut [L],
    /// Prepared triangles.
    pub tris: &'a mut [Tri],
    /// Scratch: one entry per vertex of the largest mesh.
    pub heads: &'a mut [u16],
    /// Scratch: one entry per prepared vertex (as long as `xy`).
    pub links: &'a mut [Link],
}

/// How an object's prepared vertices are laid out and shaded.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// Depth only; colour per triangle.
    Flat,
    /// Depth and one grey level (grey material, white lights).
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

    /// The shading mode.
    pub const fn shading(self) -> Shading {
        match self {
            Self::Flat => Shading::Flat,
            Self::GouraudMono | Self::GouraudRgb => Shading::Gouraud,
            _ => Shading::Phong,
        }
    }
}

/// One object of a prepared frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PreparedObject {
    /// Layout of its vertices.
    pub layout: Layout,
    /// Its prepared vertices.
    pub verts: Range<usize>,
    /// Index of its first value in [`Workspace::vals`].
    pub val_base: usize,
    /// Values per prepared vertex.
    pub stride: usize,
    /// Its prepared triangles.
    pub tris: Range<usize>,
    /// Rows `rows[0]..rows[1]` its triangles can cover (empty when it has
    /// none): a band outside them skips the object.
    pub rows: [u16; 2],
}

/// A prepared frame: the workspace filled for one scene.
#[derive(Debug)]
pub struct Frame<'w, P: Profile> {
    ws: Workspace<'w, P::Lerp>,
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
        self.objects.last().map_or(0, |o| o.verts.end)
    }

    /// Prepared triangles in use.
    pub fn triangle_count(&self) -> usize {
        self.objects.last().map_or(0, |o| o.tris.end)
    }

    /// Bytes of workspace in use (vertices, values and triangles, without
    /// the scratch).
    pub fn bytes_used(&self) -> usize {
        let vals = self
            .objects
            .last()
            .map_or(0, |o| o.val_base + o.verts.len() * o.stride);
        self.vertex_count() * 8
            + vals * core::mem::size_of::<P::Lerp>()
            + self.triangle_count() * core::mem::size_of::<Tri>()
    }

    /// Screen width and height the frame was prepared for.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// The prepared triangles.
    pub fn tris(&self) -> &[Tri] {
        &self.ws.tris[..self.triangle_count()]
    }

    /// Screen position of a prepared vertex (subpixels).
    pub fn xy(&self, v: usize) -> Option<[i32; 2]> {
        self.ws.xy.get(v).copied()
    }
}

/// Which workspace part ran out.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Part {
    /// [`Workspace::xy`] or [`Workspace::links`].
    Vertices,
    /// [`Workspace::vals`].
    Values,
    /// [`Workspace::tris`].
    Triangles,
    /// [`Workspace::heads`] (shorter than a mesh's vertex count).
    Heads,
}

/// Why a frame could not be prepared or rendered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
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
