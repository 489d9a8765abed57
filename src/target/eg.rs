//! Sending bands to an `embedded-graphics` display (feature
//! `embedded-graphics`).
//!
//! Render into a [`BandBuf`], then hand the band to any
//! `DrawTarget` whose colour is `Rgb565`, `Rgb888`, `Gray8` or
//! `BinaryColor` with [`draw_band`] ([`draw_frame_buf`] for a
//! [`FrameBuf`]): one `fill_contiguous` call over the band's rectangle,
//! which display drivers such as `mipidsi` turn into one address window
//! and one burst of pixels over SPI. With the band renderer
//! (`Frame::render_bands`) a whole frame goes out band by band:
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
//!
//! # Levels for 1-bit displays
//!
//! A dithered 1-bit frame shows a shape only where neighbouring faces
//! differ by a few sixteenths of full scale: a red material's grey (luma
//! `0.299·r + 0.587·g + 0.114·b`) stays below ~80 of 255, so faces turn
//! into a sparse, even field of dots. [`draw_band_with`] first maps every
//! channel through [`Levels`]: a contrast stretch of `[black, white]` to
//! `[0, 255]` (spreads the faces' levels over the 17 patterns a 4×4 block
//! has), then a tone curve (`Curve::Sqrt`, a gamma of 1/2, lifts dark
//! shades that a 4×4 pattern cannot otherwise tell apart).
//! [`Levels::ONE_BIT`] is the setting the board example and
//! `examples/eg_simulator.rs` use; a bright material matters more than
//! the mapping.

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

/// Tone curve of [`Levels`], applied after the contrast stretch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Curve {
    /// Identity: `out = s`.
    Linear,
    /// Gamma 1/2: `out = round(√(255·s))`, exact to the nearest level
    /// (checked for all 256 inputs); lifts 16 to 64 and 64 to 128.
    Sqrt,
}

/// A level mapping applied to each colour channel before conversion to
/// the display's colour (see the [module docs](self#levels-for-1-bit-displays)):
///
/// 1. contrast stretch: `s = round(255·(v − black) / (white − black))`,
///    clamped to `0..=255` (levels at or below `black` become 0, at or
///    above `white` 255; with `white ≤ black` a hard threshold at `black`);
/// 2. the [`Curve`].
///
/// Integer arithmetic only, exact to the nearest level: the largest
/// intermediate is `2·255·255 + 255 < 2^17`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Levels {
    /// Input level that maps to 0.
    pub black: u8,
    /// Input level that maps to 255.
    pub white: u8,
    /// Tone curve after the stretch.
    pub curve: Curve,
}

impl Levels {
    /// No change.
    pub const IDENTITY: Self = Self {
        black: 0,
        white: 255,
        curve: Curve::Linear,
    };

    /// For ordered dithering of a bright material to 1 bit: a contrast
    /// stretch of `[32, 216]`. Faces lit by the ambient term alone (a
    /// `ka = 0.2` material under ambient 1: level ~40) light 1 pixel in 16
    /// instead of 3, the brightest faces (~200) 15 instead of 13, so faces
    /// 16 levels apart differ by about two pixels per 4×4 block instead of
    /// one. Dark materials want [`Curve::Sqrt`] as well.
    pub const ONE_BIT: Self = Self {
        black: 32,
        white: 216,
        curve: Curve::Linear,
    };

    /// The mapped level of `v`.
    pub const fn map(&self, v: u8) -> u8 {
        let (v, lo, hi) = (v as u32, self.black as u32, self.white as u32);
        let s = if hi <= lo {
            if v > lo {
                255
            } else {
                0
            }
        } else if v <= lo {
            0
        } else if v >= hi {
            255
        } else {
            let d = hi - lo;
            // Round half up: (2·255·(v − lo) + d) / (2d) ≤ 255 here.
            (2 * 255 * (v - lo) + d) / (2 * d)
        };
        match self.curve {
            Curve::Linear => s as u8,
            Curve::Sqrt => {
                let x = 255 * s;
                let r = x.isqrt();
                // round(√x): up when x − r² > r, as (r + ½)² = r² + r + ¼.
                (if x - r * r > r { r + 1 } else { r }) as u8
            }
        }
    }

    /// `c` with every channel mapped.
    pub const fn apply(&self, c: Rgb8) -> Rgb8 {
        Rgb8::new(self.map(c.r), self.map(c.g), self.map(c.b))
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
    draw_pixels::<F, D>(band.pixels(), band.window(), display, |c| c)
}

/// [`draw_band`] with every pixel's channels mapped through `levels`
/// first (for 1-bit displays: [`Levels::ONE_BIT`]).
///
/// # Errors
/// The display's error.
pub fn draw_band_with<F, Z, D>(
    band: &BandBuf<'_, F, Z>,
    display: &mut D,
    levels: &Levels,
) -> Result<(), D::Error>
where
    F: PixelFormat,
    Z: DepthFormat,
    D: DrawTarget,
    D::Color: FromShaded,
{
    draw_pixels::<F, D>(band.pixels(), band.window(), display, |c| levels.apply(c))
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
    draw_pixels::<F, D>(band.pixels(), super::Target::window(band), display, |c| c)
}

/// [`draw_band_with`] for a [`FrameBuf`] (a band or a whole frame).
///
/// # Errors
/// The display's error.
pub fn draw_frame_buf_with<F, D>(
    band: &FrameBuf<'_, F>,
    display: &mut D,
    levels: &Levels,
) -> Result<(), D::Error>
where
    F: PixelFormat,
    D: DrawTarget,
    D::Color: FromShaded,
{
    draw_pixels::<F, D>(band.pixels(), super::Target::window(band), display, |c| {
        levels.apply(c)
    })
}

/// One `fill_contiguous` of `pixels` (the window `w`), each colour mapped
/// by `map` before it is converted.
fn draw_pixels<F, D>(
    pixels: &[F::Raw],
    w: super::Window,
    display: &mut D,
    map: impl Fn(Rgb8) -> Rgb8,
) -> Result<(), D::Error>
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
        D::Color::from_shaded(map(F::decode(p)), x, y)
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
        let mut buf = [0u16; 8 * 3];
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
    fn levels_are_exact_to_the_nearest_level() {
        let cases = [
            Levels::IDENTITY,
            Levels::ONE_BIT,
            Levels {
                black: 0,
                white: 255,
                curve: Curve::Sqrt,
            },
            Levels {
                black: 40,
                white: 41,
                curve: Curve::Linear,
            },
        ];
        for l in cases {
            for v in 0..=255u8 {
                let (lo, hi) = (f64::from(l.black), f64::from(l.white));
                let s = ((f64::from(v) - lo) * 255.0 / (hi - lo)).clamp(0.0, 255.0);
                // Round half up, as the integer code.
                let s = (s + 0.5).floor();
                let want = match l.curve {
                    Curve::Linear => s,
                    Curve::Sqrt => (255.0 * s).sqrt().round(),
                };
                assert_eq!(f64::from(l.map(v)), want, "{l:?} level {v}");
            }
        }
        // The documented anchor points and the hard threshold.
        let sqrt = Levels {
            black: 0,
            white: 255,
            curve: Curve::Sqrt,
        };
        assert_eq!((sqrt.map(16), sqrt.map(64), sqrt.map(255)), (64, 128, 255));
        let step = Levels {
            black: 100,
            white: 100,
            curve: Curve::Linear,
        };
        assert_eq!((step.map(100), step.map(101)), (0, 255));
        assert_eq!(Levels::ONE_BIT.map(32), 0);
        assert_eq!(Levels::ONE_BIT.map(216), 255);
        assert_eq!(
            Levels::ONE_BIT.apply(Rgb8::new(0, 116, 255)),
            Rgb8::new(0, 116, 255)
        );
        assert_eq!(
            Levels::ONE_BIT.apply(Rgb8::new(40, 128, 200)),
            Rgb8::new(11, 133, 233)
        );
    }

    #[test]
    fn mapped_bands_dither_the_mapped_level() {
        // A flat band of level 200: unmapped 13 of 16 pixels light, after
        // ONE_BIT (200 -> 233) 15 of 16.
        let mut buf = [[0u8; 3]; 16];
        let mut band = FrameBuf::<crate::target::Rgb888>::new(&mut buf, 4, 4).unwrap();
        band.clear(Rgb8::grey(200));
        let lit = |levels: Option<&Levels>| {
            let mut d = mock::<BinaryColor>(4, 4);
            match levels {
                Some(l) => draw_frame_buf_with(&band, &mut d, l).unwrap(),
                None => draw_frame_buf(&band, &mut d).unwrap(),
            }
            assert_eq!(d.fills, 1);
            d.px.iter().filter(|p| **p == Some(BinaryColor::On)).count()
        };
        assert_eq!(Levels::ONE_BIT.map(200), 233);
        assert_eq!(lit(None), 13);
        assert_eq!(lit(Some(&Levels::ONE_BIT)), 15);
        assert_eq!(lit(Some(&Levels::IDENTITY)), 13);
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
