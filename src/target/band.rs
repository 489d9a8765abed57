//! A band buffer: the colour and (optional) depth memory of one band of
//! rows, moved down the screen by the band renderer.

use super::{
    check_window, BufferError, Depth16, DepthFormat, FrameBuf, PixelFormat, RawPixel, Rgb8, Window,
};

/// The memory of one band of `rows` rows of a `width`-pixel screen: colour
/// in format `F`, and depth in format `D` or none (drawing in triangle
/// order, enough for one convex object with back-face culling).
///
/// The band renderer moves it to each band in
/// turn (the last band may hold fewer rows), clears it and renders into
/// it; [`BandBuf::pixels`] / [`BandBuf::bytes`] then give the band's
/// pixels to send to a display. Two band buffers make double buffering:
/// render into one while the other is sent.
///
/// Memory: `width × rows × (F::BYTES + D::BYTES)` bytes; a 16-row band of
/// a 240-pixel-wide screen in RGB565 with a 16-bit depth band is 15 360
/// bytes.
#[derive(Debug)]
pub struct BandBuf<'a, F: PixelFormat, D: DepthFormat = Depth16> {
    pixels: &'a mut [F::Raw],
    depth: Option<&'a mut [D::Raw]>,
    rows: u32,
    window: Window,
}

impl<'a, F: PixelFormat> BandBuf<'a, F> {
    /// A band buffer of `rows` rows, `width` wide, with a 16-bit depth
    /// band or none.
    ///
    /// # Errors
    /// [`BufferError`] when a slice does not hold `width × rows` values, or
    /// a side is 0 rows or above [`super::MAX_SCREEN`].
    pub fn new(
        pixels: &'a mut [F::Raw],
        depth: Option<&'a mut [u16]>,
        width: u32,
        rows: u32,
    ) -> Result<Self, BufferError> {
        Self::with_depth(pixels, depth, width, rows)
    }
}

impl<'a, F: PixelFormat, D: DepthFormat> BandBuf<'a, F, D> {
    /// A band buffer with a depth band of format `D` (or none).
    ///
    /// # Errors
    /// As [`BandBuf::new`].
    pub fn with_depth(
        pixels: &'a mut [F::Raw],
        depth: Option<&'a mut [D::Raw]>,
        width: u32,
        rows: u32,
    ) -> Result<Self, BufferError> {
        let window = Window {
            width,
            y0: 0,
            y1: rows,
        };
        if rows == 0 {
            return Err(BufferError::BadWindow);
        }
        check_window(window, pixels.len())?;
        if let Some(d) = &depth {
            check_window(window, d.len())?;
        }
        Ok(Self {
            pixels,
            depth,
            rows,
            window,
        })
    }

    /// Rows of a full band.
    pub fn rows(&self) -> u32 {
        self.rows
    }

    /// The rows of the screen the band holds now.
    pub fn window(&self) -> Window {
        self.window
    }

    /// The band's pixels, row-major (`width × window rows`).
    pub fn pixels(&self) -> &[F::Raw] {
        let n = self.window.len();
        self.pixels.get(..n).unwrap_or(&[])
    }

    /// The band's bytes, row-major, exactly as stored (for a display).
    pub fn bytes(&self) -> impl Iterator<Item = u8> + '_ {
        self.pixels().iter().flat_map(|p| RawPixel::bytes(*p))
    }

    /// The band's depth values, when it has a depth band.
    pub fn depth(&self) -> Option<&[D::Raw]> {
        let n = self.window.len();
        self.depth.as_deref().and_then(|d| d.get(..n))
    }

    /// The colour at screen position `(x, y)`, or `None` outside the band.
    pub fn get(&self, x: u32, y: u32) -> Option<Rgb8> {
        let w = self.window;
        if x < w.width && y >= w.y0 && y < w.y1 {
            let i = (y - w.y0) as usize * w.width as usize + x as usize;
            self.pixels.get(i).map(|&p| F::decode(p))
        } else {
            None
        }
    }

    /// The band as a [`FrameBuf`] (to draw more into it, or hand it to
    /// code that takes a target).
    pub fn frame_buf(&mut self) -> FrameBuf<'_, F> {
        let w = self.window;
        // The window was checked against the slice when it was set.
        match self.pixels.get_mut(..w.len()) {
            Some(p) => FrameBuf::from_parts(p, w),
            None => FrameBuf::from_parts(&mut [], Window { y1: w.y0, ..w }),
        }
    }

    /// Moves the band to rows `y0..y1` (`y1 - y0 <= rows`) and clears its
    /// colour to `background` and its depth to the cleared value; returns
    /// the colour and depth slices of exactly the window's pixels.
    #[allow(clippy::type_complexity)]
    pub(crate) fn start(
        &mut self,
        y0: u32,
        y1: u32,
        background: Rgb8,
    ) -> Option<(&mut [F::Raw], Option<&mut [D::Raw]>)> {
        let window = Window {
            y0,
            y1,
            ..self.window
        };
        let n = window.len();
        if y1 < y0 || y1 - y0 > self.rows || check_window(window, n).is_err() {
            return None;
        }
        self.window = window;
        let px = self.pixels.get_mut(..n)?;
        F::fill_slice(px, F::encode(background));
        let z = match self.depth.as_deref_mut() {
            Some(d) => {
                let d = d.get_mut(..n)?;
                D::clear_slice(d);
                Some(d)
            }
            None => None,
        };
        Some((px, z))
    }
}
