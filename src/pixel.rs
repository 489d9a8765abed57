//! Pixels as both the scene and the targets speak of them: the colour
//! every shader produces and the largest screen side. The scene holds
//! colours and checks screen sizes, the targets store colours in screens
//! of at most that size; this module sits below both. The public paths of
//! both items are in `fixshade::target`.

/// A colour with 8 bits per channel, the output of every shader.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Rgb8 {
    /// Red level, 0..=255.
    pub r: u8,
    /// Green level, 0..=255.
    pub g: u8,
    /// Blue level, 0..=255.
    pub b: u8,
}

impl Rgb8 {
    /// Black.
    pub const BLACK: Self = Self::grey(0);
    /// White.
    pub const WHITE: Self = Self::grey(255);

    /// A colour from its three levels.
    pub const fn new(r: u8, g: u8, b: u8) -> Self {
        Self { r, g, b }
    }

    /// A grey: all three channels at `level`.
    pub const fn grey(level: u8) -> Self {
        Self::new(level, level, level)
    }
}

/// Largest screen width or height, in pixels: 4096.
///
/// The rasterizer accepts vertex coordinates within
/// ±[`crate::num::COORD_LIMIT_PX`] = ±8192 pixels; a 4096-pixel screen
/// leaves a guard band of at least 4096 pixels on every side.
pub const MAX_SCREEN: u32 = 4096;
