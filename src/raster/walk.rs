//! A triangle set up once and walked in pieces: the scanline loop that the
//! band renderer resumes band after band.
//!
//! [`setup`] computes everything a triangle needs (its edge walkers, the
//! gradients, the values at pixel (0, 0)); [`Walk::rows`] walks it down to
//! any row and stops there, keeping its edge walkers, so that the next band
//! continues where this one stopped (the values do not change while
//! walking).
//! Every quantity is stepped exactly (integer DDA, wrapping integer
//! attribute steps), so a triangle walked in pieces gives the very columns
//! and values of one walked in one go: a banded frame equals the full frame
//! byte for byte by construction.
//!
//! # The row kernel
//! Per row: two edge steps, the `x0 < x1` test, and for a non-empty row the
//! span's start values (two multiply-adds per value from the values at
//! pixel (0, 0)),
//! the span handed to an inlined [`RowSpans`] sink (no call, no `Span`
//! value). A triangle whose
//! column range lies inside the window (decided once at setup) walks
//! without clipping; the others clamp each span to `0..width`.

use super::triangle::row_range;
use super::{Edge, Lerp, SubpixelBits, Vertex};
use crate::num::wide::{fits_i16, wmul, NO_LONG_MUL};
use crate::target::Depth16;

/// Depth and attributes together, stepped as one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Vals<L, const N: usize> {
    /// Depth.
    pub z: L,
    /// Attributes.
    pub a: [L; N],
}

impl<L: Lerp, const N: usize> Vals<L, N> {
    #[inline(always)]
    pub(crate) fn add_n(mut self, s: &Self, n: i32) -> Self {
        self.z = self.z.add_n(s.z, n);
        for (a, d) in self.a.iter_mut().zip(s.a.iter()) {
            *a = a.add_n(*d, n);
        }
        self
    }
}

/// Receives the spans of a walked triangle. Implementations are inlined
/// into the row loop (`#[inline(always)]`).
pub(crate) trait RowSpans<L: Lerp, const N: usize> {
    /// Pixels `x0..x1` (`0 <= x0 < x1 <= width`) of screen row `j`, with
    /// the values at the centre of pixel `x0` and their steps per pixel;
    /// `z16`: every depth converts to 16 bits without a clamp.
    fn span(&mut self, j: i32, x0: i32, x1: i32, v: &Vals<L, N>, sx: &Vals<L, N>, z16: bool);
}

/// The edge and row state of a triangle being walked (its values are kept
/// beside it, see [`Walk::rows`]): 80 bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Walk {
    /// Left and right edge walkers of the current half.
    pub(super) left: Edge,
    pub(super) right: Edge,
    /// The lower short edge, positioned at row `max(mid, first row)`.
    pub(super) low: Edge,
    /// Next row to walk.
    pub(super) j: i32,
    /// First row of the lower half.
    pub(super) mid: i32,
    /// Row after the last.
    pub(super) end: i32,
    /// Anchor pixel (the float twins start each row from the anchor).
    pub(super) ia: i32,
    pub(super) ja: i32,
    /// The long edge is the left one (the lower short edge replaces the
    /// right one at `mid`).
    pub(super) long_left: bool,
    /// The triangle's columns lie within `0..=width`: no clipping.
    pub(super) inside: bool,
    /// Every pixel's depth converts to 16 bits without a clamp
    /// ([`Depth16::plane_in_range`]).
    pub(super) z16: bool,
}

impl Walk {
    /// A walk with no rows (a placeholder for pools in `static`s).
    pub(crate) const EMPTY: Self = Self {
        left: Edge::EMPTY,
        right: Edge::EMPTY,
        low: Edge::EMPTY,
        j: 0,
        mid: 0,
        end: 0,
        ia: 0,
        ja: 0,
        long_left: false,
        inside: false,
        z16: false,
    };

    /// `true` when every row has been walked.
    #[inline(always)]
    pub(crate) fn done(&self) -> bool {
        self.j >= self.end
    }

    /// Walks rows from the next one down to `until` (excluded) or the
    /// triangle's last row, whichever comes first, handing each non-empty
    /// span to `sink`. `row` holds the values at pixel (0, 0) (integers) or
    /// at the anchor (floats); `sx`, `sy` their steps.
    /// `width` is the window's width (spans are clamped to it unless the
    /// triangle lies inside).
    #[inline(always)]
    pub(crate) fn rows<L: Lerp, const N: usize, K: RowSpans<L, N>>(
        &mut self,
        row: &Vals<L, N>,
        sx: &Vals<L, N>,
        sy: &Vals<L, N>,
        until: i32,
        width: i32,
        sink: &mut K,
    ) {
        if self.inside {
            self.rows_in::<L, N, K, false>(row, sx, sy, until, width, sink);
        } else {
            self.rows_in::<L, N, K, true>(row, sx, sy, until, width, sink);
        }
    }

    /// The end of the rows of the current half below `stop`, at the top
    /// of a run of rows: at the middle row the lower short edge first
    /// replaces the upper (the lower half). Shared by [`Walk::rows`] and
    /// the fixed-point kernel's row loops at no cost (every count of the
    /// firmware unchanged).
    #[inline(always)]
    pub(crate) fn half_end(&mut self, stop: i32) -> i32 {
        if self.j == self.mid {
            if self.long_left {
                self.right = self.low;
            } else {
                self.left = self.low;
            }
        }
        if self.j < self.mid {
            self.mid.min(stop)
        } else {
            stop
        }
    }

    #[inline(always)]
    fn rows_in<L: Lerp, const N: usize, K: RowSpans<L, N>, const CLIP: bool>(
        &mut self,
        row: &Vals<L, N>,
        sx: &Vals<L, N>,
        sy: &Vals<L, N>,
        until: i32,
        width: i32,
        sink: &mut K,
    ) {
        let stop = until.min(self.end);
        while self.j < stop {
            let r1 = self.half_end(stop);
            let (mut l, mut r) = (self.left, self.right);
            for j in self.j..r1 {
                let (xl, xr) = (l.x, r.x);
                let (x0, x1) = if CLIP {
                    (xl.max(0), xr.min(width))
                } else {
                    (xl, xr)
                };
                if x0 < x1 {
                    if L::EXACT_STEPS {
                        // From the values at pixel (0, 0): two
                        // multiply-adds per value, and no work at all on
                        // an empty row.
                        sink.span(j, x0, x1, &row.add_n(sx, x0).add_n(sy, j), sx, self.z16);
                    } else {
                        // Floats: afresh from the anchor on every row (see
                        // `Lerp::EXACT_STEPS`).
                        let vl = row.add_n(sx, xl - self.ia).add_n(sy, j - self.ja);
                        let v = if x0 == xl { vl } else { vl.add_n(sx, x0 - xl) };
                        sink.span(j, x0, x1, &v, sx, self.z16);
                    }
                }
                l.step();
                r.step();
            }
            self.left = l;
            self.right = r;
            self.j = r1;
        }
    }
}

/// Sets up the triangle `a`, `b`, `c` (sorted top to bottom by
/// [`super::triangle::sort3`], within the coordinate limits) to be walked
/// from row `max(first row, j0)`: the walk, the values at pixel (0, 0)
/// (integers) or at the anchor (floats), and their steps per
/// pixel along x and y. `None` for a zero-area triangle or one with no
/// row at or below `j0`.
///
/// `width` decides once whether the triangle's columns all lie within
/// `0..=width` (every vertex within `[0, width·S]` subpixels): then every
/// span lies inside the window and the row loop does not clip.
#[inline]
#[allow(clippy::type_complexity)]
pub(crate) fn setup<L: Lerp, const N: usize>(
    a: &Vertex<L, N>,
    b: &Vertex<L, N>,
    c: &Vertex<L, N>,
    sub: SubpixelBits,
    j0: i32,
    width: i32,
) -> Option<(Walk, Vals<L, N>, Vals<L, N>, Vals<L, N>)> {
    let d = [b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y];
    // Offsets within an i16: each product is within ±2^30 and their
    // difference within ±(2^31 - 2^15), exact in 32 bits (two `MULS` on
    // ARMv6-M instead of two 64-bit products; elsewhere the check would
    // cost more than the long multiplies it saves).
    let area2 = if NO_LONG_MUL && d.iter().all(|&v| fits_i16(v)) {
        (d[0] * d[3] - d[2] * d[1]) as i64
    } else {
        wmul(d[0], d[3]) - wmul(d[2], d[1])
    };
    if area2 == 0 {
        return None;
    }
    let [js, j_mid, j_bot] = row_range([a.y, b.y, c.y], sub, j0)?;

    // Gradients once per triangle. Integers: the values at the centre of
    // pixel (0, 0), fixed for the whole walk; a span's start is two
    // multiply-adds away, `row + sx·x0 + sy·j`, the very value `anchor +
    // sx·(x0 - ia) + sy·(j - ja)` modulo 2^32 (anchored at the pixel
    // centre nearest vertex 0, within half a pixel in each direction),
    // however the left edge moved. Floats: the values at that anchor.
    let setup = L::setup(area2);
    let s = sub.scale();
    let (ia, ja) = (a.x >> sub.get(), a.y >> sub.get());
    let (ox, oy) = (ia * s + s / 2 - a.x, ja * s + s / 2 - a.y);
    let start = |a0: L, gx: L::Grad, gy: L::Grad| {
        if L::EXACT_STEPS {
            L::origin(a0, gx, gy, a.x, a.y, sub)
        } else {
            L::anchor(a0, gx, gy, ox, oy, sub)
        }
    };
    let zero = Vals { z: a.z, a: a.attrs };
    let (mut row, mut sx, mut sy) = (zero, zero, zero);
    let z16;
    {
        let (gx, gy) = L::gradients([a.z, b.z, c.z], d, &setup, sub);
        z16 = Depth16::plane_in_range([a.z, b.z, c.z], gx, gy);
        row.z = start(a.z, gx, gy);
        sx.z = L::step(gx);
        sy.z = L::step(gy);
    }
    for k in 0..N {
        let (gx, gy) = L::gradients([a.attrs[k], b.attrs[k], c.attrs[k]], d, &setup, sub);
        row.a[k] = start(a.attrs[k], gx, gy);
        sx.a[k] = L::step(gx);
        sy.a[k] = L::step(gy);
    }

    // area2 > 0: vertex 1 lies right of the long edge, so the long edge is
    // the left one.
    let long_left = area2 > 0;
    let long = Edge::new(a.x, a.y, c.x, c.y, js, sub);
    let low = if j_mid < j_bot {
        Edge::new(b.x, b.y, c.x, c.y, j_mid.max(js), sub)
    } else {
        Edge::EMPTY
    };
    let short = if js < j_mid {
        Edge::new(a.x, a.y, b.x, b.y, js, sub)
    } else {
        low
    };
    let (left, right) = if long_left {
        (long, short)
    } else {
        (short, long)
    };
    let (xmin, xmax) = (a.x.min(b.x).min(c.x), a.x.max(b.x).max(c.x));
    let inside = xmin >= 0 && xmax <= width.saturating_mul(s);
    let walk = Walk {
        left,
        right,
        low,
        j: js,
        mid: j_mid,
        end: j_bot,
        ia,
        ja,
        long_left,
        inside,
        z16,
    };
    Some((walk, row, sx, sy))
}

impl Walk {
    /// Copies the walk into `dst` field by field (each edge read whole
    /// before it is stored: no library `memmove` call).
    #[inline(always)]
    pub(crate) fn copy_to(&self, dst: &mut Walk) {
        let e = |g: &Edge| Edge {
            x: g.x,
            e: g.e,
            q: g.q,
            r: g.r,
            d: g.d,
        };
        let (l, r, low) = (e(&self.left), e(&self.right), e(&self.low));
        dst.left = l;
        dst.right = r;
        dst.low = low;
        dst.j = self.j;
        dst.mid = self.mid;
        dst.end = self.end;
        dst.ia = self.ia;
        dst.ja = self.ja;
        dst.long_left = self.long_left;
        dst.inside = self.inside;
        dst.z16 = self.z16;
    }
}
