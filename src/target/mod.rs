//! Pixel formats, frame buffers, depth buffers and bands of rows.
//!
//! A [`Target`] is anything the span stage can write pixels into. It has one
//! required method, [`Target::write_pixel`], and defaulted fast paths
//! ([`Target::row_mut`], [`Target::fill_solid`], [`Target::clear`]) that
//! buffer-backed targets override, in the manner of `embedded-graphics`'
//! `DrawTarget`.
//!
//! Every target holds a *window* of the screen: all of its columns and the
//! rows `y0..y1`. A full frame is the window `0..height`; a *band* is a
//! window of a few rows of a taller screen, so that a 240×240 frame can be
//! rendered 16 rows at a time in a few kilobytes of RAM. The rasterizer
//! clips every span to the window before it writes: nothing is ever written
//! outside a buffer, whatever the triangle.
//!
//! Buffers never allocate: the caller owns the storage and lends it as a
//! slice. A slice of the wrong length is an error value
//! ([`BufferError`]), never a panic.

mod band;
mod buffer;
mod depth;
#[cfg(feature = "embedded-graphics")]
pub mod eg;
mod format;
pub mod mock;

pub use band::BandBuf;
pub use buffer::FrameBuf;
pub use depth::{Depth16, Depth32, DepthBuffer, DepthFormat};
pub use format::{level_q19, Gray8, PixelFormat, RawPixel, Rgb565Be, Rgb565Le, Rgb8, Rgb888};
pub use mock::{MockTarget, PatternError};

use core::fmt;

/// The part of a screen a target holds: every column, rows `y0..y1`.
///
/// Limits: `width` and the screen height are at most [`MAX_SCREEN`] pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    /// Width in pixels (every column of the screen).
    pub width: u32,
    /// First row held (inclusive).
    pub y0: u32,
    /// Row after the last row held (exclusive).
    pub y1: u32,
}

impl Window {
    /// Number of rows held.
    pub const fn rows(&self) -> u32 {
        self.y1.saturating_sub(self.y0)
    }

    /// Number of pixels held.
    pub const fn len(&self) -> usize {
        self.width as usize * self.rows() as usize
    }

    /// `true` when the window holds no pixel.
    pub const fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

pub use crate::pixel::MAX_SCREEN;

/// Why a buffer could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum BufferError {
    /// The slice does not hold exactly `width × rows` elements.
    WrongLength {
        /// Elements the window needs.
        expected: usize,
        /// Elements the slice holds.
        actual: usize,
    },
    /// Width or height above [`MAX_SCREEN`], or `y1 < y0`.
    BadWindow,
}

impl fmt::Display for BufferError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::WrongLength { expected, actual } => write!(
                f,
                "buffer holds {actual} pixels but the window needs {expected}"
            ),
            Self::BadWindow => write!(
                f,
                "window rows must satisfy y0 <= y1 <= {MAX_SCREEN} and width <= {MAX_SCREEN}"
            ),
        }
    }
}

impl core::error::Error for BufferError {}

/// Something the span stage can write pixels of one format into.
///
/// Only [`write_pixel`](Target::write_pixel) and
/// [`window`](Target::window) are required. The rasterizer calls
/// `write_pixel` only for `x < width` and `y0 <= y < y1`.
pub trait Target {
    /// The pixel format stored.
    type Format: PixelFormat;

    /// The part of the screen this target holds.
    fn window(&self) -> Window;

    /// Writes one pixel in screen coordinates. Implementations must ignore
    /// coordinates outside [`window`](Target::window).
    fn write_pixel(&mut self, x: u32, y: u32, pixel: <Self::Format as PixelFormat>::Raw);

    /// Fast path: the pixels of screen row `y` as a mutable slice of
    /// `width` pixels, or `None` when the target has no such memory (the
    /// default) or `y` lies outside the window.
    fn row_mut(&mut self, y: u32) -> Option<&mut [<Self::Format as PixelFormat>::Raw]> {
        let _ = y;
        None
    }

    /// Fast path: pixels `x0..x1` of screen row `y` as a mutable slice, or
    /// `None` when the target has no such memory or they lie outside the
    /// window. Defaults to a slice of [`Target::row_mut`]; the span stage
    /// calls it once per span.
    #[inline]
    fn span_mut(
        &mut self,
        y: u32,
        x0: u32,
        x1: u32,
    ) -> Option<&mut [<Self::Format as PixelFormat>::Raw]> {
        self.row_mut(y)
            .and_then(|r| r.get_mut(x0 as usize..x1 as usize))
    }

    /// Fast path: every pixel of the window as one mutable slice, row-major,
    /// [`Window::width`] pixels per row from row `y0`, or `None` (the
    /// default) when the target has no such memory. The span stage then
    /// finds a span's pixels from the index range it computed for the
    /// depth buffer (same window), with no second window check.
    #[inline]
    fn pixels_mut(&mut self) -> Option<&mut [<Self::Format as PixelFormat>::Raw]> {
        None
    }

    /// Fills `len` pixels of row `y` from column `x` with one colour;
    /// clipped to the window.
    fn fill_solid(&mut self, x: u32, y: u32, len: u32, pixel: <Self::Format as PixelFormat>::Raw) {
        let w = self.window();
        if y < w.y0 || y >= w.y1 || x >= w.width {
            return;
        }
        let end = x.saturating_add(len).min(w.width);
        if let Some(row) = self.row_mut(y) {
            if let Some(span) = row.get_mut(x as usize..end as usize) {
                span.fill(pixel);
            }
            return;
        }
        for xi in x..end {
            self.write_pixel(xi, y, pixel);
        }
    }

    /// Fills the whole window with one colour.
    fn clear(&mut self, color: Rgb8) {
        let w = self.window();
        let raw = Self::Format::encode(color);
        for y in w.y0..w.y1 {
            self.fill_solid(0, y, w.width, raw);
        }
    }
}

/// The index range of pixels `x0..x1` of screen row `y` in a row-major
/// buffer holding window `w`, or `None` outside the window (`x0 > x1`
/// included). With the sides at most [`MAX_SCREEN`] nothing overflows.
#[inline(always)]
pub(crate) fn span_range(w: Window, y: u32, x0: u32, x1: u32) -> Option<core::ops::Range<usize>> {
    // One comparison for both row bounds: rows above y0 wrap to large.
    let row = y.wrapping_sub(w.y0);
    if row >= w.y1.wrapping_sub(w.y0) || x1 > w.width || x0 > x1 {
        return None;
    }
    let start = row as usize * w.width as usize;
    Some(start + x0 as usize..start + x1 as usize)
}

/// Checks a window against [`MAX_SCREEN`] and a slice length.
pub(crate) fn check_window(w: Window, len: usize) -> Result<(), BufferError> {
    if w.width > MAX_SCREEN || w.y1 > MAX_SCREEN || w.y0 > w.y1 {
        return Err(BufferError::BadWindow);
    }
    if len != w.len() {
        return Err(BufferError::WrongLength {
            expected: w.len(),
            actual: len,
        });
    }
    Ok(())
}
