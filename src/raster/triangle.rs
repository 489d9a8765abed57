//! Triangle setup and the scanline loop.

use super::wide::{fits_i16, mul_i32, NO_LONG_MUL};
use super::{Edge, Lerp, RasterError, SubpixelBits, Vertex};
use crate::target::Window;

/// Receives the spans of a triangle, top to bottom: the span stage
/// ([`super::Fill`]), or a test probe.
pub trait Spans<L: Lerp, const N: usize> {
    /// Receives one span (never empty, clipped to the window).
    fn span(&mut self, span: &Span<L, N>);
}

/// Pixels `x0..x1` of row `y`, already clipped to the window (`x0 < x1`),
/// with the depth and attributes at the centre of pixel `x0` and their
/// increments per pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Span<L, const N: usize> {
    /// Row.
    pub y: u32,
    /// First column.
    pub x0: u32,
    /// Column after the last.
    pub x1: u32,
    /// Depth at the first pixel.
    pub z: L,
    /// Depth increment per pixel.
    pub dz: L,
    /// Attributes at the first pixel.
    pub a: [L; N],
    /// Attribute increments per pixel.
    pub da: [L; N],
}

/// Depth and attributes together, stepped as one.
#[derive(Clone, Copy)]
struct Vals<L, const N: usize> {
    z: L,
    a: [L; N],
}

impl<L: Lerp, const N: usize> Vals<L, N> {
    #[inline(always)]
    fn add(&mut self, s: &Self) {
        self.z = self.z.add(s.z);
        for (a, d) in self.a.iter_mut().zip(s.a.iter()) {
            *a = a.add(*d);
        }
    }

    #[inline]
    fn add_n(mut self, s: &Self, n: i32) -> Self {
        self.z = self.z.add_n(s.z, n);
        for (a, d) in self.a.iter_mut().zip(s.a.iter()) {
            *a = a.add_n(*d, n);
        }
        self
    }
}

/// First row whose centre is at or below subpixel `y`: `ceil((y - S/2)/S)`.
#[inline]
pub(crate) fn first_row(y: i32, sub: SubpixelBits) -> i32 {
    let s = sub.scale();
    // An arithmetic shift is the floor division by 2^s (no divide).
    (y - s / 2 + s - 1) >> sub.get()
}

/// Rasterizes one triangle into `sink`, clipped to `window`.
///
/// Coverage follows the top-left rule at pixel centres; attributes are
/// interpolated as described in the [module docs](super). A zero-area
/// triangle draws nothing.
///
/// # Errors
/// [`RasterError::OutOfRange`] when a vertex lies outside
/// ±[`super::COORD_LIMIT_PX`] pixels; nothing is drawn then.
pub fn draw_triangle<L: Lerp, const N: usize, S: Spans<L, N>>(
    tri: &[Vertex<L, N>; 3],
    sub: SubpixelBits,
    window: Window,
    sink: &mut S,
) -> Result<(), RasterError> {
    for (i, v) in tri.iter().enumerate() {
        if !in_limits(v.x, v.y, sub) {
            return Err(RasterError::OutOfRange(i as u8));
        }
    }
    let [a, b, c] = sort3([&tri[0], &tri[1], &tri[2]], |v| v.y);
    draw_sorted(a, b, c, sub, window, sink);
    Ok(())
}

/// `true` when subpixel `(x, y)` lies within ±[`super::COORD_LIMIT_PX`]
/// pixels, as [`draw_triangle`] requires of each vertex.
#[inline(always)]
pub(crate) fn in_limits(x: i32, y: i32, sub: SubpixelBits) -> bool {
    let lim = sub.coord_limit();
    !(x < -lim || x > lim || y < -lim || y > lim)
}

/// The three items sorted by `key`, top first, by the sorting network
/// [`draw_triangle`] uses (the same order for equal keys): a caller that
/// sorts vertex indices by it and passes the vertices to [`draw_sorted`]
/// draws what [`draw_triangle`] draws.
#[inline(always)]
pub(crate) fn sort3<T: Copy>(v: [T; 3], key: impl Fn(T) -> i32) -> [T; 3] {
    let [mut a, mut b, mut c] = v;
    if key(b) < key(a) {
        core::mem::swap(&mut a, &mut b);
    }
    if key(c) < key(b) {
        core::mem::swap(&mut b, &mut c);
    }
    if key(b) < key(a) {
        core::mem::swap(&mut a, &mut b);
    }
    [a, b, c]
}

/// [`draw_triangle`] of vertices already sorted by [`sort3`] on `y` and
/// within the limits ([`in_limits`]): the band loop sorts vertex indices
/// before fetching the vertices, so that each vertex here has a fixed
/// place instead of being selected (a chain of conditional moves per
/// field on ARM).
pub(crate) fn draw_sorted<L: Lerp, const N: usize, S: Spans<L, N>>(
    a: &Vertex<L, N>,
    b: &Vertex<L, N>,
    c: &Vertex<L, N>,
    sub: SubpixelBits,
    window: Window,
    sink: &mut S,
) {
    let d = [b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y];
    // Offsets within an i16: each product is within ±2^30 and their
    // difference within ±(2^31 - 2^15), exact in 32 bits (two `MULS` on
    // ARMv6-M instead of two 64-bit products; elsewhere the check would
    // cost more than the long multiplies it saves).
    let area2 = if NO_LONG_MUL && d.iter().all(|&v| fits_i16(v)) {
        (d[0] * d[3] - d[2] * d[1]) as i64
    } else {
        mul_i32(d[0], d[3]) - mul_i32(d[2], d[1])
    };
    if area2 == 0 {
        return;
    }
    let (j_top, j_mid, j_bot) = (
        first_row(a.y, sub),
        first_row(b.y, sub),
        first_row(c.y, sub),
    );
    let js = j_top.max(window.y0 as i32);
    let je = j_bot.min(window.y1 as i32);
    if js >= je {
        return;
    }

    // Gradients once per triangle, anchored at the pixel centre nearest
    // vertex 0 (within half a pixel in each direction).
    let setup = L::setup(area2);
    let s = sub.scale();
    let (ia, ja) = (a.x >> sub.get(), a.y >> sub.get());
    let (ox, oy) = (ia * s + s / 2 - a.x, ja * s + s / 2 - a.y);
    let zero = Vals { z: a.z, a: a.attrs };
    let (mut anchor, mut sx, mut sy) = (zero, zero, zero);
    {
        let (gx, gy) = L::gradients([a.z, b.z, c.z], d, &setup, sub);
        anchor.z = L::anchor(a.z, gx, gy, ox, oy, sub);
        sx.z = L::step(gx);
        sy.z = L::step(gy);
    }
    for k in 0..N {
        let (gx, gy) = L::gradients([a.attrs[k], b.attrs[k], c.attrs[k]], d, &setup, sub);
        anchor.a[k] = L::anchor(a.attrs[k], gx, gy, ox, oy, sub);
        sx.a[k] = L::step(gx);
        sy.a[k] = L::step(gy);
    }

    // area2 > 0: vertex 1 lies right of the long edge, so the long edge is
    // the left one.
    let long_left = area2 > 0;
    let mut long = Edge::new(a.x, a.y, c.x, c.y, js, sub);
    let halves = [(a, b, js, j_mid.min(je)), (b, c, j_mid.max(js), je)];
    // Exact steps (integers, wrapping): the values at column 0 of the row,
    // stepped by `sy` per row; a span's start is then one multiply-add
    // away, `row + sx·x0`, the very value `anchor + sx·(x0 - ia) +
    // sy·(j - ja)` modulo 2^32, however the left edge moved. (Stepping
    // the left-edge value instead needed a carry-selected step per row
    // and four more live values in the scanline loop.)
    let col0 = anchor.add_n(&sx, ia.wrapping_neg());
    for (top, bot, r0, r1) in halves {
        if r0 >= r1 {
            continue;
        }
        let mut short = Edge::new(top.x, top.y, bot.x, bot.y, r0, sub);
        let mut row = col0.add_n(&sy, r0 - ja);
        for j in r0..r1 {
            let (xl, xr) = if long_left {
                (long.x, short.x)
            } else {
                (short.x, long.x)
            };
            let x0 = xl.max(0);
            let x1 = xr.min(window.width as i32);
            if x0 < x1 {
                let v = if L::EXACT_STEPS {
                    row.add_n(&sx, x0)
                } else {
                    // Floats: afresh from the anchor on every row (see
                    // `Lerp::EXACT_STEPS`).
                    let vl = anchor.add_n(&sx, xl - ia).add_n(&sy, j - ja);
                    if x0 == xl {
                        vl
                    } else {
                        vl.add_n(&sx, x0 - xl)
                    }
                };
                sink.span(&Span {
                    y: j as u32,
                    x0: x0 as u32,
                    x1: x1 as u32,
                    z: v.z,
                    dz: sx.z,
                    a: v.a,
                    da: sx.a,
                });
            }
            long.step();
            short.step();
            if L::EXACT_STEPS {
                row.add(&sy);
            }
        }
    }
}
