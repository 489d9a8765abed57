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
    /// The rows from the buffer's top known to hold `background` and
    /// the cleared depth, when a band left the buffer as
    /// [`BandBuf::start`] cleared it ([`BandBuf::untouched`]): the next
    /// start then needs no clear.
    clean: Option<(u32, Rgb8)>,
    /// The clean rows as of the last [`BandBuf::start`] (made
    /// [`BandBuf::clean`] by [`BandBuf::untouched`]).
    started: Option<(u32, Rgb8)>,
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
            clean: None,
            started: None,
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
        // Drawn into from outside: cleared in full at the next start.
        self.clean = None;
        self.started = None;
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
    ///
    /// The clear is skipped when the buffer is known to hold it already:
    /// the band before left it untouched ([`BandBuf::untouched`], no
    /// triangle drawn), over at least these rows, with the same
    /// background (and [`BandBuf::frame_buf`] not taken since). The
    /// bunny's 240 × 240 frame in 16-row bands draws nothing in 5 of its
    /// 15 bands: 4 of its 15 clears (7 680 bytes each) skipped, exact QEMU
    /// counts, bunny-gouraud raster thumbv7em 1 642 170 -> 1 634 450,
    /// thumbv6m 2 508 220 -> 2 491 561 (a clear: about 2 000 and 3 400
    /// instructions; with the fills after both slices were taken the
    /// ARMv6-M colour fill lost its 4-register `STM`s: 2 499 291).
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
        let rows = y1 - y0;
        // Until the renderer says otherwise, drawn into.
        let clean = self.clean.take();
        let kept = matches!(clean, Some((r, bg)) if r >= rows && bg == background);
        self.started = if kept {
            clean
        } else {
            Some((rows, background))
        };
        let px = self.pixels.get_mut(..n)?;
        if !kept {
            F::fill_slice(px, F::encode(background));
        }
        let z = match self.depth.as_deref_mut() {
            Some(d) => {
                let d = d.get_mut(..n)?;
                if !kept {
                    D::clear_slice(d);
                }
                Some(d)
            }
            None => None,
        };
        Some((px, z))
    }

    /// Records that nothing was drawn into the band since
    /// [`BandBuf::start`]: it still holds the clear, which the next start
    /// then skips.
    pub(crate) fn untouched(&mut self) {
        self.clean = self.started;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::Rgb565Be;

    /// A start clears the band unless the band before was left untouched
    /// over at least as many rows with the same background; a band drawn
    /// into from outside ([`BandBuf::frame_buf`]) is cleared again.
    #[test]
    fn a_start_skips_only_a_clear_the_band_still_holds() {
        let (mut px, mut z) = ([7u16; 12], [9u16; 12]);
        let mut band = BandBuf::<Rgb565Be>::new(&mut px, Some(&mut z), 4, 3).unwrap();
        let (red, blue) = (Rgb8::new(255, 0, 0), Rgb8::new(0, 0, 255));
        let (r, b) = (Rgb565Be::encode(red), Rgb565Be::encode(blue));
        // Marks pixel 0 (colour and depth) as if drawn; `true` when the
        // next start cleared it.
        let cleared = |band: &mut BandBuf<'_, Rgb565Be>, y0: u32, y1: u32, bg: Rgb8| {
            let (p, d) = band.start(y0, y1, bg).unwrap();
            let d = d.unwrap();
            let was = (p[0], d[0]);
            (p[0], d[0]) = (1, 2);
            match was {
                (1, 2) => false,
                (c, u16::MAX) => c == Rgb565Be::encode(bg),
                _ => panic!("half cleared"),
            }
        };
        // A new buffer is cleared: every value.
        let (p, d) = band.start(0, 3, red).unwrap();
        assert!(p.iter().all(|&v| v == r));
        assert!(d.unwrap().iter().all(|&v| v == u16::MAX));
        // Drawn into (not marked untouched): cleared.
        assert!(cleared(&mut band, 3, 6, red));
        assert_eq!(band.pixels()[0], 1);
        // Marked untouched (here falsely, to see the skip): kept.
        band.untouched();
        assert!(!cleared(&mut band, 6, 9, red));
        // Once: the start above was not marked.
        assert!(cleared(&mut band, 9, 12, red));
        // Another background: cleared.
        band.untouched();
        assert!(cleared(&mut band, 12, 15, blue));
        assert_eq!(band.pixels()[1], b);
        // A shorter band keeps the clear, and the rows below it stay
        // known: a taller band after it keeps it too.
        band.untouched();
        assert!(!cleared(&mut band, 15, 17, blue));
        band.untouched();
        assert!(!cleared(&mut band, 0, 3, blue));
        // A short band cleared after a drawn one: a taller one clears.
        assert!(cleared(&mut band, 0, 1, blue));
        band.untouched();
        assert!(cleared(&mut band, 0, 3, blue));
        // Drawn into from outside: cleared.
        band.untouched();
        let _ = band.frame_buf();
        assert!(cleared(&mut band, 0, 3, red));
        band.untouched();
        let _ = band.frame_buf();
        band.untouched();
        assert!(cleared(&mut band, 0, 3, red));
    }
}
