//! Sending bands to an `embedded-graphics` display (feature
//! `embedded-graphics`).
//!
//! Render into a [`BandBuf`], then hand the band to any
//! `DrawTarget` whose colour is `Rgb565`, `Rgb888`, `Gray8` or
//! `BinaryColor` with [`draw_band`] ([`draw_frame_buf`] for a
//! [`FrameBuf`]): one `fill_contiguous` call over the band's rectangle,
//! which display drivers such as `mipidsi` turn into one address window
//! and one burst of pixels over SPI. With
//! [`Frame::render_bands`](crate::render::Frame::render_bands) a whole
//! frame goes out band by band:
//!
//! ```text
//! frame.render_bands(&scene, &mut state, &mut band,
//!     |b| draw_band(b, &mut display).map_err(MyError::Display))?;
//! ```
//!
//! `BinaryColor` (1-bit OLEDs such as the SSD1306) is made by *ordered
//! dithering*: a pixel is on when its grey level exceeds the 4×4 Bayer
//! threshold of its screen position, `(16·B(x, y) + 8)·255/256` for `B` the
//! Bayer index 0..=15, so a uniform grey `g` lights exactly `⌈16·g/255 − ½⌉`
//! of every 4×4 block (tested for all 256 levels): 0 lights none, 255 all.

use super::{BandBuf, DepthFormat, FrameBuf, Gray8 as Gray8Format, PixelFormat, Rgb8};
use embedded_graphics_core::{
    draw_target::DrawTarget,
    geometry::{Point, Size},
    pixelcolor::{BinaryColor, Gray8, PixelColor, Rgb565, Rgb888},
    primitives::Rectangle,
};

/// A display colour made from a shaded colour at a screen position (the
/// position matters only for dithering).
pub trait FromShaded: PixelColor {
    /// The display colour of `c` at `(x, y)`.
    fn from_shaded(c: Rgb8, x: u32, y: u32) -> Self;
}

impl FromShaded for Rgb565 {
    #[inline]
    fn from_shaded(c: Rgb8, _x: u32, _y: u32) -> Self {
        Rgb565::new(c.r >> 3, c.g >> 2, c.b >> 3)
    }
}

impl FromShaded for Rgb888 {
    #[inline]
    fn from_shaded(c: Rgb8, _x: u32, _y: u32) -> Self {
        Rgb888::new(c.r, c.g, c.b)
    }
}

impl FromShaded for Gray8 {
    #[inline]
    fn from_shaded(c: Rgb8, _x: u32, _y: u32) -> Self {
        Gray8::new(Gray8Format::encode(c)[0])
    }
}

/// The 4×4 Bayer matrix, indices 0..=15.
const BAYER: [[u8; 4]; 4] = [[0, 8, 2, 10], [12, 4, 14, 6], [3, 11, 1, 9], [15, 7, 13, 5]];

impl FromShaded for BinaryColor {
    #[inline]
    fn from_shaded(c: Rgb8, x: u32, y: u32) -> Self {
        let g = Gray8Format::encode(c)[0] as u32;
        let b = BAYER[(y & 3) as usize][(x & 3) as usize] as u32;
        // threshold (16 b + 8) · 255 / 256, compared as g·256 > (16b+8)·255
        if g * 256 > (16 * b + 8) * 255 {
            BinaryColor::On
        } else {
            BinaryColor::Off
        }
    }
}

/// Sends a rendered band to `display`: one `fill_contiguous` over the
/// rectangle of the band's rows.
///
/// # Errors
/// The display's error.
pub fn draw_band<F, Z, D>(band: &BandBuf<'_, F, Z>, display: &mut D) -> Result<(), D::Error>
where
    F: PixelFormat,
    Z: DepthFormat,
    D: DrawTarget,
    D::Color: FromShaded,
{
    draw_pixels::<F, D>(band.pixels(), band.window(), display)
}

/// [`draw_band`] for a [`FrameBuf`] (a band or a whole frame).
///
/// # Errors
/// The display's error.
pub fn draw_frame_buf<F, D>(band: &FrameBuf<'_, F>, display: &mut D) -> Result<(), D::Error>
where
    F: PixelFormat,
    D: DrawTarget,
    D::Color: FromShaded,
{
    draw_pixels::<F, D>(band.pixels(), super::Target::window(band), display)
}

fn draw_pixels<F, D>(pixels: &[F::Raw], w: super::Window, display: &mut D) -> Result<(), D::Error>
where
    F: PixelFormat,
    D: DrawTarget,
    D::Color: FromShaded,
{
    if w.is_empty() {
        return Ok(());
    }
    let area = Rectangle::new(Point::new(0, w.y0 as i32), Size::new(w.width, w.rows()));
    let width = w.width.max(1);
    let colors = pixels.iter().enumerate().map(|(i, &p)| {
        let (x, y) = (i as u32 % width, w.y0 + i as u32 / width);
        D::Color::from_shaded(F::decode(p), x, y)
    });
    display.fill_contiguous(&area, colors)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::{Rgb565Be, Target};
    use embedded_graphics_core::{geometry::OriginDimensions, Pixel};

    extern crate std;
    use std::vec::Vec;

    /// A display that records fill_contiguous calls and pixels.
    struct Mock<C> {
        w: u32,
        h: u32,
        px: Vec<Option<C>>,
        fills: usize,
    }

    impl<C: PixelColor> OriginDimensions for Mock<C> {
        fn size(&self) -> Size {
            Size::new(self.w, self.h)
        }
    }

    impl<C: PixelColor> DrawTarget for Mock<C> {
        type Color = C;
        type Error = core::convert::Infallible;
        fn draw_iter<I: IntoIterator<Item = Pixel<C>>>(
            &mut self,
            it: I,
        ) -> Result<(), Self::Error> {
            for Pixel(p, c) in it {
                if p.x >= 0 && p.y >= 0 && (p.x as u32) < self.w && (p.y as u32) < self.h {
                    self.px[(p.y as u32 * self.w + p.x as u32) as usize] = Some(c);
                }
            }
            Ok(())
        }
        fn fill_contiguous<I: IntoIterator<Item = C>>(
            &mut self,
            area: &Rectangle,
            colors: I,
        ) -> Result<(), Self::Error> {
            self.fills += 1;
            let (x0, y0, w) = (
                area.top_left.x,
                area.top_left.y,
                area.size.width.max(1) as i32,
            );
            let pts = (0..(area.size.width * area.size.height) as i32)
                .map(|i| Point::new(x0 + i % w, y0 + i / w));
            self.draw_iter(pts.zip(colors).map(|(p, c)| Pixel(p, c)))
        }
    }

    fn mock<C: PixelColor>(w: u32, h: u32) -> Mock<C> {
        Mock {
            w,
            h,
            px: std::vec![None; (w * h) as usize],
            fills: 0,
        }
    }

    #[test]
    fn a_band_lands_on_its_rows_in_one_fill() {
        let mut buf = [[0u8; 2]; 8 * 3];
        let mut band = FrameBuf::<Rgb565Be>::band(&mut buf, 8, 5, 8).unwrap();
        band.clear(Rgb8::new(255, 128, 8));
        band.write_pixel(2, 6, Rgb565Be::encode(Rgb8::new(0, 255, 0)));
        let mut d = mock::<Rgb565>(8, 10);
        draw_frame_buf(&band, &mut d).unwrap();
        assert_eq!(d.fills, 1);
        assert!(
            d.px[..40].iter().all(|p| p.is_none()),
            "rows above the band untouched"
        );
        assert!(
            d.px[64..].iter().all(|p| p.is_none()),
            "rows below the band untouched"
        );
        assert_eq!(d.px[5 * 8], Some(Rgb565::new(31, 32, 1)));
        assert_eq!(d.px[6 * 8 + 2], Some(Rgb565::new(0, 63, 0)));
        let mut g = mock::<Gray8>(8, 10);
        draw_frame_buf(&band, &mut g).unwrap();
        assert_eq!(g.px[6 * 8 + 2], Some(Gray8::new(149)));
    }

    #[test]
    fn dithering_lights_the_share_of_the_grey_level() {
        for level in 0..=255u8 {
            // ceil(16 g / 255 - 1/2) in integers: ceil((32 g - 255) / 510).
            let on = (32 * level as i32 - 255 + 509).div_euclid(510).max(0) as usize;
            let mut buf = [[0u8; 3]; 16];
            let mut band = FrameBuf::<crate::target::Rgb888>::new(&mut buf, 4, 4).unwrap();
            band.clear(Rgb8::grey(level));
            let mut d = mock::<BinaryColor>(4, 4);
            draw_frame_buf(&band, &mut d).unwrap();
            let lit = d.px.iter().filter(|p| **p == Some(BinaryColor::On)).count();
            assert_eq!(lit, on, "level {level}");
        }
    }
}
