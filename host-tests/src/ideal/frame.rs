//! The ideal renderer's output frame.

/// A rendered frame, row-major (`index = y * width + x`, row 0 at the top).
#[derive(Clone, Debug, PartialEq)]
pub struct IdealFrame {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Colour per pixel, each channel in `[0, 1]` (already clamped); the
    /// clamped background where nothing is covered.
    pub color: Vec<[f64; 3]>,
    /// Whether any triangle covers the pixel centre.
    pub covered: Vec<bool>,
    /// Eye-space depth `-z_eye` of the visible fragment (perspective-correct,
    /// between `near` and `far`); `f64::INFINITY` where nothing is covered.
    pub depth: Vec<f64>,
    /// Index (into `IdealScene::objects`) of the visible object.
    pub object: Vec<Option<usize>>,
}

/// Converts a colour channel to an 8-bit level: `round(clamp(c, 0, 1) * 255)`
/// with halves rounded up; NaN maps to 0.
pub fn to_level(c: f64) -> u8 {
    if c.is_nan() {
        return 0;
    }
    // In [0, 255] after the clamp, so the cast is exact.
    (c.clamp(0.0, 1.0) * 255.0).round() as u8
}

impl IdealFrame {
    /// An empty (background-only) frame. `width * height` must be small
    /// enough to allocate; [`super::render`] checks that first.
    pub(crate) fn new(width: u32, height: u32, background: [f64; 3]) -> Self {
        let n = width as usize * height as usize;
        Self {
            width,
            height,
            color: vec![background.map(|c| c.clamp(0.0, 1.0)); n],
            covered: vec![false; n],
            depth: vec![f64::INFINITY; n],
            object: vec![None; n],
        }
    }

    /// Row-major index of pixel `(x, y)`, or `None` outside the frame.
    pub fn index(&self, x: u32, y: u32) -> Option<usize> {
        (x < self.width && y < self.height).then(|| y as usize * self.width as usize + x as usize)
    }

    /// 8-bit colour levels per pixel, `round(c * 255)` (see [`to_level`]).
    pub fn to_rgb8(&self) -> Vec<[u8; 3]> {
        self.color.iter().map(|c| c.map(to_level)).collect()
    }

    /// Number of covered pixels.
    pub fn covered_count(&self) -> usize {
        self.covered.iter().filter(|&&c| c).count()
    }
}
