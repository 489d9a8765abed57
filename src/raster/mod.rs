//! Screen-space triangle rasterization: setup, edge walking, spans.
//!
//! # Conventions
//! Screen `x` grows to the right and `y` downwards. Vertices are given in
//! *subpixel* units: integers, `2^s` per pixel, with `s` the subpixel bits
//! ([`SubpixelBits`], 4 by default, 1..=8). Pixel `(i, j)` has its centre at
//! `(i + ½, j + ½)` pixels. A pixel is covered when its centre lies inside
//! the triangle; a centre exactly on an edge is covered only for a *left*
//! edge or a *top* edge (the top-left rule), so triangles sharing an edge
//! never leave a gap between them and never draw a pixel twice. Both
//! windings are drawn (culling happens before this stage); a triangle of
//! zero area draws nothing.
//!
//! # Edge walking
//! For an edge from `(X0, Y0)` down to `(X1, Y1)` (subpixels, `DY = Y1 - Y0
//! > 0`, `S = 2^s`), the first column whose centre is at or right of the
//! edge on row `j` (centre `Yc = jS + S/2`) is
//!
//! ```text
//! i(j) = ceil( ((X0 - S/2)·DY + (Yc - Y0)·DX) / (S·DY) )
//! ```
//!
//! and a span covers the columns `i_left(j) .. i_right(j)` (right one
//! excluded), which is exactly the top-left rule. The walker evaluates the
//! numerator once (64-bit) at the first row, then per row adds the integer
//! quotient `⌊DX/DY⌋` and the remainder `S·(DX mod DY)` to an error term
//! (Bresenham's method): the column is exact on every row, whatever the
//! edge length, with no drift. See [`Edge`].
//!
//! # Attributes
//! Depth and the shading attributes are interpolated with gradients
//! computed once per triangle (one reciprocal of the doubled area, see
//! [`Lerp`]), anchored at vertex 0 and *pre-stepped* to the centre of the
//! first pixel of each span; along a span they advance by one addition per
//! pixel. Fixed-point attributes (`i32`) step with wrapping additions: every
//! value used at a covered pixel is the exact sum of the anchor and whole
//! multiples of the rounded gradients, correct modulo 2^32, and since it
//! lies within the vertex values (plus the rounding error below) it is
//! correct. The error of a fixed attribute at a pixel `n = |di| + |dj|`
//! pixels from the pixel centre nearest vertex 0 is at most
//! `(n + 2)·(½ + |g|·2^-30)` units of its last place, `|g|` the larger
//! gradient per pixel (the `2^-30` is the reciprocal's relative error).
//!
//! # Numeric limits (why every intermediate fits)
//! With `s ≤ 8` and vertex coordinates within ±[`COORD_LIMIT_PX`] = ±2^13
//! pixels, a subpixel coordinate is at most 2^21 in magnitude and an edge
//! delta at most 2^22:
//!
//! - DDA denominator `S·DY ≤ 2^8·2^22 = 2^30`; error term `< 2·2^30 ≤
//!   2^31 - 2`: `i32`.
//! - DDA numerator at the first row: `|X0 - S/2|·DY + |Yc - Y0|·|DX| ≤
//!   2^21·2^22 + 2^22·2^22 < 2^45`: `i64`.
//! - Doubled area: `2·2^22·2^22 = 2^45`: `i64`.
//! - Fixed attributes are `i32` raw values within ±2^30 (see [`ATTR_LIMIT`]),
//!   so a difference is below 2^31; a gradient numerator `d1·DY2 - d2·DY1`
//!   is below `2·2^31·2^22 = 2^54`, times `S` below 2^62: `i64`.
//! - Columns and rows are within ±2^13 + 1: `i32`; the screen is at most
//!   [`crate::target::MAX_SCREEN`] = 4096 pixels a side.
//!
//! A triangle with a vertex outside the limits is rejected with
//! [`RasterError::OutOfRange`]; the scene stage clips to this guard band
//! before it gets here.

mod edge;
mod fast;
mod span;
mod triangle;
mod walk;

pub use edge::Edge;
#[cfg(test)]
use fast::unpack_fixed;
pub(crate) use fast::{draw_small, grey_l, grey_z, pack_vals, setup_fast, BandMem};
pub(crate) use span::span_pixels;
pub use span::{Fill, Flat, Gouraud, GouraudMono, Persp, Shader};
#[cfg(test)]
pub(crate) use triangle::kernel_fit_holds;
pub(crate) use triangle::{draw_sorted, first_row, in_limits, kernel_fit_screen, sort3};
pub use triangle::{draw_triangle, Span, Spans};
pub(crate) use walk::{setup, RowSpans, Vals, Walk};

pub use crate::num::{
    BadSubpixelBits, InvArea, Lerp, Recip, SubpixelBits, ATTR_LIMIT, COORD_LIMIT_PX, DEPTH_ONE,
    LEVEL_FRAC_BITS,
};
use core::fmt;

/// One triangle corner in screen space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex<L, const N: usize> {
    /// x in subpixel units.
    pub x: i32,
    /// y in subpixel units (downwards).
    pub y: i32,
    /// Depth, affine in screen space; smaller is nearer. Fixed point: `d ·
    /// 2^30` for `d` in `[0, 1]` ([`DEPTH_ONE`]).
    pub z: L,
    /// Shading attributes, interpreted by the [`Shader`].
    pub attrs: [L; N],
}

/// Why a triangle was not drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum RasterError {
    /// A vertex lies outside ±[`COORD_LIMIT_PX`] pixels (index of the vertex).
    OutOfRange(u8),
    /// Subpixel bits outside `1..=8`.
    BadSubpixelBits,
    /// The depth buffer's window differs from the target's.
    DepthWindowMismatch,
}

impl fmt::Display for RasterError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::OutOfRange(i) => write!(
                f,
                "vertex {i} lies outside the supported range of +-{COORD_LIMIT_PX} pixels"
            ),
            Self::BadSubpixelBits => write!(
                f,
                "subpixel bits must be within {}..={}",
                SubpixelBits::MIN,
                SubpixelBits::MAX
            ),
            Self::DepthWindowMismatch => {
                write!(
                    f,
                    "the depth buffer holds other rows or columns than the target"
                )
            }
        }
    }
}

impl core::error::Error for RasterError {}

impl From<BadSubpixelBits> for RasterError {
    fn from(_: BadSubpixelBits) -> Self {
        Self::BadSubpixelBits
    }
}

#[cfg(test)]
mod tests;
