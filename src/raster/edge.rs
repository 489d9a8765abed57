//! The edge walker: an exact integer DDA (Bresenham's method).

use super::SubpixelBits;

/// Walks one triangle edge downwards, one scanline at a time, giving for
/// each row the first column whose pixel centre lies at or to the right of
/// the edge (see the [module docs](super) for the formula).
///
/// The column is the exact ceiling of a rational on every row: the walker
/// keeps the integer column and an error term `e` with `numerator =
/// column · D - e`, `0 <= e < D`, and steps both by an integer quotient and
/// remainder. No rounding, no drift, whatever the length.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// The current column (first pixel at or right of the edge).
    pub x: i32,
    e: i32,
    q: i32,
    r: i32,
    d: i32,
}

impl Edge {
    /// The edge from `(x0, y0)` down to `(x1, y1)` (subpixels, `y1 > y0`,
    /// coordinates within the limits of the [module](super)), positioned at
    /// row `j`.
    pub fn new(x0: i32, y0: i32, x1: i32, y1: i32, j: i32, sub: SubpixelBits) -> Self {
        let s = sub.scale();
        let dx = x1 - x0;
        let dy = (y1 - y0).max(1);
        let d = (s * dy).max(1); // in [1, 2^30]
        let yc = j as i64 * s as i64 + (s / 2) as i64;
        let n = (x0 - s / 2) as i64 * dy as i64 + (yc - y0 as i64) * dx as i64;
        // ceil(n / d) and the error term; 32-bit division when n fits (the
        // usual case: a 64-bit division is a long library call on a
        // Cortex-M0).
        let (x, e) = match i32::try_from(n) {
            Ok(n) => {
                let (q, r) = (n.div_euclid(d), n.rem_euclid(d));
                if r == 0 {
                    (q, 0)
                } else {
                    (q + 1, d - r)
                }
            }
            Err(_) => {
                let (q, r) = (n.div_euclid(d as i64), n.rem_euclid(d as i64));
                if r == 0 {
                    (q as i32, 0)
                } else {
                    (q as i32 + 1, d - r as i32)
                }
            }
        };
        Self {
            x,
            e,
            q: dx.div_euclid(dy),
            r: s * dx.rem_euclid(dy),
            d,
        }
    }

    /// Advances one row; returns `true` when the column moved one further
    /// than the quotient (the error term wrapped).
    #[inline(always)]
    pub fn step(&mut self) -> bool {
        self.e -= self.r;
        self.x += self.q;
        if self.e < 0 {
            self.e += self.d;
            self.x += 1;
            true
        } else {
            false
        }
    }

    /// The whole-column part of a step, `⌊DX/DY⌋`.
    pub fn quotient(&self) -> i32 {
        self.q
    }
}
