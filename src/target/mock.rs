//! A test target drawn as ASCII pictures.
//!
//! [`MockTarget`] records every pixel written into a fixed-size grid (no
//! allocation, so it works in `no_std` tests too), notices a pixel written
//! twice (overdraw) or outside the target, and compares itself with a
//! picture, in the manner of `embedded-graphics`' `MockDisplay`:
//!
//! ```
//! use fixshade::raster::{Fill, Flat, SubpixelBits, Vertex};
//! use fixshade::target::{Depth16, MockTarget, Rgb8};
//!
//! // A right triangle with its corners on pixel corners (subpixels, 1/16).
//! let v = |x: i32, y: i32| Vertex::<i32, 0> { x: x * 16, y: y * 16, z: 0, attrs: [] };
//! let mut target = MockTarget::<5, 4>::new();
//! let mut fill = Fill::<_, Depth16, _>::new(&mut target, None, Flat(Rgb8::grey(0xF0)))?;
//! fill.draw(&[v(0, 0), v(4, 0), v(0, 4)], SubpixelBits::DEFAULT)?;
//! target.check_pattern(&[
//!     "FFF..", // the centre of (3, 0) lies on the right edge: not covered
//!     "FF...",
//!     "F....",
//!     ".....",
//! ])?;
//! # Ok::<(), Box<dyn core::error::Error>>(())
//! ```
//!
//! # Pictures
//! One string per row, one character per column: `.` a pixel never
//! written; `#` a pixel written with any level; a hexadecimal digit
//! `0`-`9`, `A`-`F` (or `a`-`f`) a pixel written with a level whose upper
//! four bits are that digit (`F` is 240..=255). The target stores
//! [`Gray8`] pixels: grey shading writes its level, colours their luma.
//!
//! Nothing here panics: a bad picture, a mismatch, overdraw and writes
//! outside the target are all reported by [`MockTarget::check_pattern`] as
//! a [`PatternError`] whose `Display` shows both pictures.

use super::{Gray8, Target, Window};
use core::fmt;

/// A `W × H` test target recording each write (see the [module docs](self)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MockTarget<const W: usize, const H: usize> {
    pixels: [[Option<u8>; W]; H],
    overdraw: Option<(u32, u32)>,
    outside: Option<(u32, u32)>,
}

impl<const W: usize, const H: usize> Default for MockTarget<W, H> {
    fn default() -> Self {
        Self::new()
    }
}

/// Why a [`MockTarget`] does not match a picture.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PatternError<const W: usize, const H: usize> {
    /// The picture does not have `H` rows of `W` characters, or holds a
    /// character other than `.`, `#` and hexadecimal digits.
    BadPattern {
        /// Row of the first problem.
        row: usize,
    },
    /// A pixel was written twice (the first such pixel).
    Overdraw {
        /// Column.
        x: u32,
        /// Row.
        y: u32,
    },
    /// A write outside the target (the first such write).
    Outside {
        /// Column.
        x: u32,
        /// Row.
        y: u32,
    },
    /// The pixels differ from the picture.
    Mismatch {
        /// The first differing pixel, `(x, y)`.
        first: (u32, u32),
        /// What the target holds.
        actual: MockTarget<W, H>,
    },
}

impl<const W: usize, const H: usize> fmt::Display for PatternError<W, H> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::BadPattern { row } => write!(
                f,
                "bad picture at row {row}: want {H} rows of {W} characters from '.', '#', 0-9, A-F"
            ),
            Self::Overdraw { x, y } => write!(f, "pixel ({x}, {y}) was written twice"),
            Self::Outside { x, y } => write!(f, "write outside the {W}x{H} target at ({x}, {y})"),
            Self::Mismatch { first, actual } => {
                writeln!(
                    f,
                    "pixels differ from the picture, first at {first:?}; the target holds:"
                )?;
                write!(f, "{actual}")
            }
        }
    }
}

impl<const W: usize, const H: usize> core::error::Error for PatternError<W, H> {}

/// What a picture's character asks of a pixel.
fn matches(c: u8, p: Option<u8>) -> Option<bool> {
    let digit = match c {
        b'.' => return Some(p.is_none()),
        b'#' => return Some(p.is_some()),
        b'0'..=b'9' => c - b'0',
        b'A'..=b'F' => c - b'A' + 10,
        b'a'..=b'f' => c - b'a' + 10,
        _ => return None,
    };
    Some(p.is_some_and(|l| l >> 4 == digit))
}

impl<const W: usize, const H: usize> MockTarget<W, H> {
    /// An empty target: no pixel written.
    pub const fn new() -> Self {
        Self {
            pixels: [[None; W]; H],
            overdraw: None,
            outside: None,
        }
    }

    /// The level written at `(x, y)`, `None` if never written or outside.
    pub fn pixel(&self, x: u32, y: u32) -> Option<u8> {
        *self.pixels.get(y as usize)?.get(x as usize)?
    }

    /// Pixels written at least once.
    pub fn written(&self) -> usize {
        self.pixels.iter().flatten().filter(|p| p.is_some()).count()
    }

    /// Compares the target with `pattern` (see the [module docs](self)).
    ///
    /// # Errors
    /// [`PatternError`]: a malformed picture, overdraw, a write outside the
    /// target, or a pixel that differs.
    pub fn check_pattern(&self, pattern: &[&str]) -> Result<(), PatternError<W, H>> {
        if pattern.len() != H {
            return Err(PatternError::BadPattern {
                row: pattern.len().min(H),
            });
        }
        if let Some((x, y)) = self.outside {
            return Err(PatternError::Outside { x, y });
        }
        if let Some((x, y)) = self.overdraw {
            return Err(PatternError::Overdraw { x, y });
        }
        let mut first = None;
        for (y, (line, row)) in pattern.iter().zip(self.pixels.iter()).enumerate() {
            if line.len() != W {
                return Err(PatternError::BadPattern { row: y });
            }
            for (x, (&c, &p)) in line.as_bytes().iter().zip(row.iter()).enumerate() {
                match matches(c, p) {
                    None => return Err(PatternError::BadPattern { row: y }),
                    Some(false) if first.is_none() => first = Some((x as u32, y as u32)),
                    Some(_) => {}
                }
            }
        }
        match first {
            None => Ok(()),
            Some(first) => Err(PatternError::Mismatch {
                first,
                actual: self.clone(),
            }),
        }
    }
}

/// The picture of what the target holds: `.` or the level's upper hex
/// digit, one line per row.
impl<const W: usize, const H: usize> fmt::Display for MockTarget<W, H> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const HEX: &[u8; 16] = b"0123456789ABCDEF";
        for row in &self.pixels {
            for p in row {
                let c = match p {
                    None => '.',
                    Some(l) => char::from(HEX[usize::from(l >> 4)]),
                };
                write!(f, "{c}")?;
            }
            writeln!(f)?;
        }
        Ok(())
    }
}

impl<const W: usize, const H: usize> Target for MockTarget<W, H> {
    type Format = Gray8;

    /// The whole `W × H` grid (sides above [`super::MAX_SCREEN`] are
    /// clamped to it).
    fn window(&self) -> Window {
        let side = |n: usize| n.min(super::MAX_SCREEN as usize) as u32;
        Window {
            width: side(W),
            y0: 0,
            y1: side(H),
        }
    }

    fn write_pixel(&mut self, x: u32, y: u32, pixel: [u8; 1]) {
        match self
            .pixels
            .get_mut(y as usize)
            .and_then(|r| r.get_mut(x as usize))
        {
            None => {
                self.outside.get_or_insert((x, y));
            }
            Some(p) => {
                if p.is_some() {
                    self.overdraw.get_or_insert((x, y));
                }
                *p = Some(pixel[0]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{MockTarget, PatternError};
    use crate::target::Target;
    use std::string::ToString;

    #[test]
    fn records_and_compares() {
        let mut t = MockTarget::<3, 2>::new();
        t.write_pixel(0, 0, [0x12]);
        t.write_pixel(2, 1, [0xFF]);
        assert_eq!(t.pixel(0, 0), Some(0x12));
        assert_eq!(t.pixel(1, 0), None);
        assert_eq!(t.written(), 2);
        assert_eq!(t.check_pattern(&["1..", "..F"]), Ok(()));
        assert_eq!(t.check_pattern(&["#..", "..f"]), Ok(()));
        assert_eq!(t.to_string(), "1..\n..F\n");
        match t.check_pattern(&["1..", ".F."]) {
            Err(PatternError::Mismatch { first, actual }) => {
                assert_eq!(first, (1, 1));
                assert_eq!(actual, t);
            }
            other => panic!("{other:?}"),
        }
        // A level in another sixteenth is a mismatch.
        assert!(matches!(
            t.check_pattern(&["2..", "..F"]),
            Err(PatternError::Mismatch { first: (0, 0), .. })
        ));
    }

    #[test]
    fn bad_pictures_overdraw_and_outside_are_errors() {
        let mut t = MockTarget::<2, 2>::new();
        assert_eq!(
            t.check_pattern(&[".."]),
            Err(PatternError::BadPattern { row: 1 })
        );
        assert_eq!(
            t.check_pattern(&["..", "..."]),
            Err(PatternError::BadPattern { row: 1 })
        );
        assert_eq!(
            t.check_pattern(&["..", ".x"]),
            Err(PatternError::BadPattern { row: 1 })
        );
        t.write_pixel(1, 1, [0]);
        t.write_pixel(1, 1, [0]);
        assert_eq!(
            t.check_pattern(&["..", ".0"]),
            Err(PatternError::Overdraw { x: 1, y: 1 })
        );
        t.write_pixel(5, 0, [0]);
        assert_eq!(
            t.check_pattern(&["..", ".0"]),
            Err(PatternError::Outside { x: 5, y: 0 })
        );
        assert_eq!(
            PatternError::<2, 2>::Outside { x: 5, y: 0 }.to_string(),
            "write outside the 2x2 target at (5, 0)"
        );
    }
}
