//! Frame buffers and bands in caller-owned memory.

use super::{check_window, span_range, BufferError, PixelFormat, RawPixel, Rgb8, Target, Window};

/// A window of a screen (a whole frame, or a band of rows) in a
/// caller-provided slice, row-major, `width` pixels per row.
///
/// Memory: `width × rows × F::BYTES` bytes; a 240×240 RGB565 frame is
/// 115 200 bytes, a 16-row band of it 7 680 bytes.
#[derive(Debug)]
pub struct FrameBuf<'a, F: PixelFormat> {
    pixels: &'a mut [F::Raw],
    window: Window,
}

impl<'a, F: PixelFormat> FrameBuf<'a, F> {
    /// A whole frame of `width × height` pixels.
    ///
    /// # Errors
    /// [`BufferError`] when the slice length is not `width × height` or a
    /// side exceeds [`super::MAX_SCREEN`].
    pub fn new(pixels: &'a mut [F::Raw], width: u32, height: u32) -> Result<Self, BufferError> {
        Self::band(pixels, width, 0, height)
    }

    /// A band holding rows `y0..y1` of a taller screen.
    ///
    /// # Errors
    /// As [`FrameBuf::new`], and when `y0 > y1`.
    pub fn band(
        pixels: &'a mut [F::Raw],
        width: u32,
        y0: u32,
        y1: u32,
    ) -> Result<Self, BufferError> {
        let window = Window { width, y0, y1 };
        check_window(window, pixels.len())?;
        Ok(Self { pixels, window })
    }

    /// A buffer of a window already checked against the slice (by
    /// [`check_window`]).
    pub(crate) fn from_parts(pixels: &'a mut [F::Raw], window: Window) -> Self {
        Self { pixels, window }
    }

    /// Moves the band so that it holds rows `y0..y0 + rows` (same memory,
    /// same number of rows): the way to walk a screen band by band.
    ///
    /// # Errors
    /// [`BufferError::BadWindow`] when the band would end below row
    /// [`super::MAX_SCREEN`].
    pub fn move_to(&mut self, y0: u32) -> Result<(), BufferError> {
        let rows = self.window.rows();
        let y1 = y0.checked_add(rows).ok_or(BufferError::BadWindow)?;
        let window = Window {
            y0,
            y1,
            ..self.window
        };
        check_window(window, self.pixels.len())?;
        self.window = window;
        Ok(())
    }

    /// The raw pixels, row-major.
    pub fn pixels(&self) -> &[F::Raw] {
        self.pixels
    }

    /// The bytes of the window, row-major, exactly as stored.
    pub fn bytes(&self) -> impl Iterator<Item = u8> + '_ {
        self.pixels.iter().flat_map(|p| RawPixel::bytes(*p))
    }

    /// The colour at screen position `(x, y)`, or `None` outside the window.
    pub fn get(&self, x: u32, y: u32) -> Option<Rgb8> {
        self.index(x, y).map(|i| F::decode(self.pixels[i]))
    }

    fn index(&self, x: u32, y: u32) -> Option<usize> {
        let w = self.window;
        if x < w.width && y >= w.y0 && y < w.y1 {
            Some((y - w.y0) as usize * w.width as usize + x as usize)
        } else {
            None
        }
    }
}

impl<F: PixelFormat> Target for FrameBuf<'_, F> {
    type Format = F;

    fn window(&self) -> Window {
        self.window
    }

    #[inline]
    fn write_pixel(&mut self, x: u32, y: u32, pixel: F::Raw) {
        // `index` is below `pixels.len()` (checked by `check_window`); `get_mut`
        // states it without a panic branch.
        if let Some(p) = self.index(x, y).and_then(|i| self.pixels.get_mut(i)) {
            *p = pixel;
        }
    }

    #[inline]
    fn row_mut(&mut self, y: u32) -> Option<&mut [F::Raw]> {
        let w = self.window;
        if y < w.y0 || y >= w.y1 {
            return None;
        }
        let start = (y - w.y0) as usize * w.width as usize;
        self.pixels.get_mut(start..start + w.width as usize)
    }

    #[inline]
    fn pixels_mut(&mut self) -> Option<&mut [F::Raw]> {
        Some(self.pixels)
    }

    #[inline]
    fn span_mut(&mut self, y: u32, x0: u32, x1: u32) -> Option<&mut [F::Raw]> {
        span_range(self.window, y, x0, x1).and_then(|r| self.pixels.get_mut(r))
    }
    /// The whole buffer at once (it holds exactly the window's pixels):
    /// [`PixelFormat::fill_slice`], a `memset` for black or white.
    fn clear(&mut self, color: Rgb8) {
        F::fill_slice(self.pixels, F::encode(color));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::{Gray8, Rgb565Be};

    #[test]
    fn wrong_length_is_an_error() {
        let mut buf = [[0u8; 1]; 10];
        assert_eq!(
            FrameBuf::<Gray8>::new(&mut buf, 4, 3).unwrap_err(),
            BufferError::WrongLength {
                expected: 12,
                actual: 10
            }
        );
        assert_eq!(
            FrameBuf::<Gray8>::band(&mut buf, 5, 3, 1).unwrap_err(),
            BufferError::BadWindow
        );
    }

    #[test]
    fn band_writes_only_its_rows() {
        let mut buf = [0u16; 8];
        let mut band = FrameBuf::<Rgb565Be>::band(&mut buf, 4, 10, 12).unwrap();
        band.write_pixel(1, 9, 0x0101);
        band.write_pixel(1, 12, 0x0101);
        band.write_pixel(4, 10, 0x0101);
        band.write_pixel(3, 11, u16::from_ne_bytes([0xab, 0xcd]));
        band.fill_solid(2, 10, 100, 0x0707);
        assert_eq!(band.pixels()[7].bytes(), [0xab, 0xcd]);
        assert_eq!(band.bytes().filter(|&b| b == 7).count(), 4);
        assert_eq!(band.bytes().filter(|&b| b == 1).count(), 0);
        band.move_to(12).unwrap();
        assert_eq!(
            band.window(),
            Window {
                width: 4,
                y0: 12,
                y1: 14
            }
        );
        assert_eq!(band.get(0, 11), None);
        assert!(band.move_to(4095).is_err());
    }

    /// `clear` (a whole-slice fill, bytewise for uniform bytes) stores
    /// what encoding the colour into each pixel stores.
    fn clear_equals_encode<F: PixelFormat>(fill: F::Raw) {
        let colors = [
            Rgb8::BLACK,
            Rgb8::WHITE,
            Rgb8::new(12, 200, 7),
            Rgb8::grey(0x84),
            Rgb8::new(255, 0, 255),
        ];
        for c in colors {
            let mut buf = [fill; 12];
            FrameBuf::<F>::band(&mut buf, 4, 3, 6).unwrap().clear(c);
            assert!(buf.iter().all(|&p| p == F::encode(c)), "{c:?}");
        }
    }

    #[test]
    fn clear_fills_every_pixel_in_every_format() {
        use crate::target::{Rgb565Le, Rgb888};
        clear_equals_encode::<Gray8>([0x5a]);
        clear_equals_encode::<Rgb565Be>(0x5a5a);
        clear_equals_encode::<Rgb565Le>(0x5a5a);
        clear_equals_encode::<Rgb888>([0x5a; 3]);
    }

    #[test]
    fn zero_sized_targets_are_valid_and_empty() {
        let mut buf: [[u8; 1]; 0] = [];
        let mut fb = FrameBuf::<Gray8>::new(&mut buf, 0, 0).unwrap();
        fb.clear(Rgb8::WHITE);
        fb.write_pixel(0, 0, [1]);
        assert_eq!(fb.bytes().count(), 0);
    }
}
