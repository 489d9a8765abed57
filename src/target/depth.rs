//! Depth buffers, 16 or 32 bits per pixel.
//!
//! The rasterizer interpolates a depth `d` in `[0, 1]` that is *affine in
//! screen space* (the projected `z/w`; see [`crate::raster`]), as a 30-bit
//! fraction: `d30 = round(d × 2^30)`. A buffer keeps its top 16 or 30 bits.
//! The test is *less than*: a fragment is drawn when its depth is strictly
//! smaller than the stored one, so of two fragments at the same depth the
//! first drawn stays (the z-fighting rule), and a cleared buffer holds the
//! largest value. A 16-bit buffer stores `min(d30 >> 14, 65534)`, so every
//! fragment, even at the far plane (`d = 1`), passes a cleared pixel, and
//! the last 2^-15 of the depth range shares one value; a 32-bit buffer
//! stores `d30` itself.

use super::{check_window, span_range, BufferError, Window};

/// A depth value format.
pub trait DepthFormat: Copy + core::fmt::Debug {
    /// One stored depth.
    type Raw: Copy + PartialOrd + core::fmt::Debug;
    /// Value of a cleared buffer (farther than everything).
    const CLEAR: Self::Raw;
    /// Converts a 30-bit depth `0..=2^30` (larger values saturate).
    fn from_d30(d30: u32) -> Self::Raw;

    /// Converts an interpolated depth: `from_d30(z.depth30())`, with a
    /// faster path where the format allows.
    #[inline(always)]
    fn from_lerp<L: crate::num::Lerp>(z: L) -> Self::Raw {
        Self::from_d30(z.depth30())
    }

    /// `true` when [`DepthFormat::from_lerp_in_range`] equals
    /// [`DepthFormat::from_lerp`] for every depth `z + k·dz`, `k < n`, of
    /// a span (and the span loop's additions do not wrap): the span stage
    /// then converts without saturating. `false` by default.
    #[inline(always)]
    fn span_in_range<L: crate::num::Lerp>(z: L, dz: L, n: u32) -> bool {
        let _ = (z, dz, n);
        false
    }

    /// `true` when a triangle whose depths convert to 16 bits without a
    /// clamp (`z16`, [`crate::num::Lerp::depth16_plane_in_range`]) has
    /// every span in range as [`DepthFormat::span_in_range`] says (then
    /// not asked per span). `false` by default.
    #[inline(always)]
    fn plane_in_range(z16: bool) -> bool {
        let _ = z16;
        false
    }

    /// The conversion for a span for which [`DepthFormat::span_in_range`]
    /// holds, as a `u32` key ordered as the stored values: the span stage
    /// compares `key < to_key(stored)` and stores `from_key(key)`.
    /// Defaults: unused (`span_in_range` is `false`), so they only need to
    /// be consistent.
    #[inline(always)]
    fn from_lerp_in_range<L: crate::num::Lerp>(z: L) -> u32 {
        let _ = z;
        0
    }

    /// A stored value as a key (see [`DepthFormat::from_lerp_in_range`]).
    #[inline(always)]
    fn to_key(raw: Self::Raw) -> u32 {
        let _ = raw;
        0
    }

    /// A key back to the stored value.
    #[inline(always)]
    fn from_key(key: u32) -> Self::Raw {
        let _ = key;
        Self::CLEAR
    }
}

/// 16-bit depth: `d30 >> 14`, steps of 2^-16 of the depth range, at most
/// 65534 so that every depth, 1 included, is nearer than the cleared value
/// 65535 (so the last step, `[1 - 2^-15, 1]`, is twice as wide).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Depth16;

impl DepthFormat for Depth16 {
    type Raw = u16;
    const CLEAR: u16 = u16::MAX;
    #[inline]
    fn from_d30(d30: u32) -> u16 {
        let v = d30 >> 14;
        if v >= u16::MAX as u32 {
            u16::MAX - 1
        } else {
            v as u16
        }
    }

    #[inline(always)]
    fn from_lerp<L: crate::num::Lerp>(z: L) -> u16 {
        z.depth16()
    }

    #[inline(always)]
    fn span_in_range<L: crate::num::Lerp>(z: L, dz: L, n: u32) -> bool {
        z.depth16_span_in_range(dz, n)
    }

    #[inline(always)]
    fn plane_in_range(z16: bool) -> bool {
        z16
    }

    #[inline(always)]
    fn from_lerp_in_range<L: crate::num::Lerp>(z: L) -> u32 {
        // At most 65534 in range: the key is the stored value.
        z.depth16_unclamped()
    }

    #[inline(always)]
    fn to_key(raw: u16) -> u32 {
        raw as u32
    }

    #[inline(always)]
    fn from_key(key: u32) -> u16 {
        key as u16
    }
}

/// 32-bit depth: the full 30-bit value.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Depth32;

impl DepthFormat for Depth32 {
    type Raw = u32;
    const CLEAR: u32 = u32::MAX;
    #[inline]
    fn from_d30(d30: u32) -> u32 {
        d30.min(1 << 30)
    }
}

/// A depth buffer for a window (a frame or a band), in caller memory.
///
/// Memory: 2 (16-bit) or 4 (32-bit) bytes per pixel of the window; a
/// 16-row band of a 240-pixel-wide screen in 16 bits is 7 680 bytes.
#[derive(Debug)]
pub struct DepthBuffer<'a, D: DepthFormat> {
    values: &'a mut [D::Raw],
    window: Window,
}

impl<'a, D: DepthFormat> DepthBuffer<'a, D> {
    /// A depth buffer for rows `y0..y1`, `width` wide, cleared.
    ///
    /// # Errors
    /// [`BufferError`] when the slice length is not `width × (y1 - y0)` or
    /// the window is too big.
    pub fn new(
        values: &'a mut [D::Raw],
        width: u32,
        y0: u32,
        y1: u32,
    ) -> Result<Self, BufferError> {
        let window = Window { width, y0, y1 };
        check_window(window, values.len())?;
        let mut b = Self { values, window };
        b.clear();
        Ok(b)
    }

    /// Sets every value to [`DepthFormat::CLEAR`].
    pub fn clear(&mut self) {
        self.values.fill(D::CLEAR);
    }

    /// The window held.
    pub fn window(&self) -> Window {
        self.window
    }

    /// Moves to rows `y0..y0 + rows` and clears.
    ///
    /// # Errors
    /// [`BufferError::BadWindow`] when the window would end below row
    /// [`super::MAX_SCREEN`].
    pub fn move_to(&mut self, y0: u32) -> Result<(), BufferError> {
        let y1 = y0
            .checked_add(self.window.rows())
            .ok_or(BufferError::BadWindow)?;
        let window = Window {
            y0,
            y1,
            ..self.window
        };
        check_window(window, self.values.len())?;
        self.window = window;
        self.clear();
        Ok(())
    }

    /// The values of screen row `y`, or `None` outside the window.
    pub fn row_mut(&mut self, y: u32) -> Option<&mut [D::Raw]> {
        let w = self.window;
        if y < w.y0 || y >= w.y1 {
            return None;
        }
        let start = (y - w.y0) as usize * w.width as usize;
        self.values.get_mut(start..start + w.width as usize)
    }

    /// All values, row-major (for the span stage, which computes the index
    /// range of a span once for the depth buffer and the target).
    #[inline]
    pub(crate) fn values_mut(&mut self) -> &mut [D::Raw] {
        self.values
    }

    /// The values of columns `x0..x1` of screen row `y`, or `None` outside
    /// the window.
    #[inline]
    pub fn span_mut(&mut self, y: u32, x0: u32, x1: u32) -> Option<&mut [D::Raw]> {
        span_range(self.window, y, x0, x1).and_then(|r| self.values.get_mut(r))
    }

    /// The stored value at `(x, y)`, or `None` outside the window.
    pub fn get(&self, x: u32, y: u32) -> Option<D::Raw> {
        let w = self.window;
        if x < w.width && y >= w.y0 && y < w.y1 {
            Some(self.values[(y - w.y0) as usize * w.width as usize + x as usize])
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn conversions_saturate() {
        assert_eq!(Depth16::from_d30(0), 0);
        // Never the cleared value: a depth of 1 still passes the test.
        assert_eq!(Depth16::from_d30(1 << 30), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - 1), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - (1 << 14)), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - (2 << 14)), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - (3 << 14)), u16::MAX - 2);
        assert_eq!(Depth16::from_d30(u32::MAX), u16::MAX - 1);
        assert_eq!(Depth16::from_d30(1 << 14), 1);
        assert_eq!(Depth32::from_d30(u32::MAX), 1 << 30);
        // The far end: every depth, 1 included, is nearer than CLEAR.
        assert_eq!(Depth16::from_d30((1 << 30) - (1 << 14) - 1), 65534);
        assert_eq!(Depth16::from_d30(1 << 30), 65534);
        assert!(Depth32::from_d30(1 << 30) < Depth32::CLEAR);
    }

    #[test]
    fn cleared_and_banded() {
        let mut v = [0u16; 6];
        let mut d = DepthBuffer::<Depth16>::new(&mut v, 3, 4, 6).unwrap();
        assert_eq!(d.get(2, 5), Some(u16::MAX));
        assert_eq!(d.get(2, 6), None);
        d.row_mut(4).unwrap()[1] = 5;
        d.move_to(6).unwrap();
        assert_eq!(d.get(1, 6), Some(u16::MAX));
        assert!(DepthBuffer::<Depth32>::new(&mut [0u32; 5], 3, 0, 2).is_err());
    }

    #[test]
    fn fast_depth16_equals_the_general_conversion() {
        use crate::num::Lerp;
        let mut z = i32::MIN;
        for _ in 0..200_000 {
            assert_eq!(z.depth16(), Depth16::from_d30(z.depth30()), "{z}");
            z = z.wrapping_add(21_467 + (z as u32 % 977) as i32);
        }
        for z in [
            -1,
            0,
            1,
            (1 << 14) - 1,
            1 << 14,
            (65534 << 14) - 1,
            65534 << 14,
            (1 << 30) - (1 << 14) - 1,
            (1 << 30) - (1 << 14),
            (1 << 30) - 1,
            1 << 30,
            i32::MAX,
        ] {
            assert_eq!(z.depth16(), Depth16::from_d30(z.depth30()), "{z}");
        }
    }
}
