//! The subpixel grid of screen coordinates: [`SubpixelBits`] and the
//! coordinate limit it scales.

use core::fmt;

/// Largest vertex coordinate magnitude, in pixels: 8192 (2^13).
pub const COORD_LIMIT_PX: i32 = 1 << 13;

/// Number of subpixel bits: vertices are snapped to `1/2^bits` of a pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct SubpixelBits(u32);

impl SubpixelBits {
    /// 4 bits: 1/16 of a pixel, the default.
    pub const DEFAULT: Self = Self(4);
    /// Fewest bits: 1 (pixel centres need the half).
    pub const MIN: u32 = 1;
    /// Most bits: 8 (see the numeric limits above).
    pub const MAX: u32 = 8;

    /// Validated subpixel bits.
    ///
    /// # Errors
    /// [`BadSubpixelBits`] outside `1..=8`.
    pub const fn new(bits: u32) -> Result<Self, BadSubpixelBits> {
        if bits < Self::MIN || bits > Self::MAX {
            Err(BadSubpixelBits)
        } else {
            Ok(Self(bits))
        }
    }

    /// The number of bits.
    pub const fn get(self) -> u32 {
        self.0
    }

    /// Subpixels per pixel, `2^bits`.
    pub const fn scale(self) -> i32 {
        1 << self.0
    }

    /// Largest subpixel coordinate magnitude: `COORD_LIMIT_PX · 2^bits`.
    pub const fn coord_limit(self) -> i32 {
        COORD_LIMIT_PX << self.0
    }

    /// Converts a pixel coordinate to subpixels, rounding to nearest
    /// (halves away from zero) and saturating at the coordinate limit; NaN
    /// maps to 0. Saturated coordinates are then rejected by the
    /// rasterizer rather than drawn in a wrong place.
    pub fn from_f32(self, px: f32) -> i32 {
        self.from_f64(px as f64)
    }

    /// As [`SubpixelBits::from_f32`], for `f64`.
    pub fn from_f64(self, px: f64) -> i32 {
        let lim = self.coord_limit() as f64 + 1.0;
        let v = px * self.scale() as f64;
        if v.is_nan() {
            0
        } else if v >= lim {
            lim as i32
        } else if v <= -lim {
            -(lim as i32)
        } else {
            // Round half away from zero without std.
            let r = if v >= 0.0 { v + 0.5 } else { v - 0.5 };
            r as i32
        }
    }

    /// Converts whole pixels to subpixels, saturating.
    pub const fn from_px(self, px: i32) -> i32 {
        px.saturating_mul(self.scale())
    }
}

impl Default for SubpixelBits {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// [`SubpixelBits::new`] was given a number of bits outside
/// `SubpixelBits::MIN..=SubpixelBits::MAX` (`1..=8`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct BadSubpixelBits;

impl fmt::Display for BadSubpixelBits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "subpixel bits must be within {}..={}",
            SubpixelBits::MIN,
            SubpixelBits::MAX
        )
    }
}

impl core::error::Error for BadSubpixelBits {}
