//! Triangle setup and the scanline loop.

use super::walk::{setup, RowSpans, Vals};
use super::{Lerp, RasterError, SubpixelBits, Vertex};
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

/// First row whose centre is at or below subpixel `y`: `ceil((y - S/2)/S)`.
#[inline]
pub(crate) fn first_row(y: i32, sub: SubpixelBits) -> i32 {
    let s = sub.scale();
    // An arithmetic shift is the floor division by 2^s (no divide).
    (y - s / 2 + s - 1) >> sub.get()
}

/// The rows of a triangle whose vertices lie at subpixel rows `ys`
/// (top to bottom) from row `j0` on: `[first row, first row of the lower
/// half, row after the last]`, the first no earlier than `j0`; `None` when
/// no row is left.
#[inline(always)]
pub(crate) fn row_range(ys: [i32; 3], sub: SubpixelBits, j0: i32) -> Option<[i32; 3]> {
    let [j_top, j_mid, j_bot] = ys.map(|y| first_row(y, sub));
    let js = j_top.max(j0);
    (js < j_bot).then_some([js, j_mid, j_bot])
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

/// Whether a `width × height` screen with `sub` subpixel bits allows the
/// small-triangle kernel's fit contract ([`kernel_fit_holds`]): its box
/// `0..=xl` × `0..=yl` (`xl = width·S - S/2`, `yl = height·S`) with both
/// bounds below `2^14` and `yl` within the coordinate limit. A frame
/// constant, decided at prepare.
#[inline(always)]
pub(crate) fn kernel_fit_screen(width: u32, height: u32, sub: SubpixelBits) -> bool {
    let s = i64::from(sub.scale());
    let (xl, yl) = (i64::from(width) * s - s / 2, i64::from(height) * s);
    width > 0 && xl < 1 << 14 && yl < 1 << 14 && yl <= i64::from(sub.coord_limit())
}

/// The contract of a triangle marked fit for the small-triangle kernel
/// (`PreparedObject::kernel_fit` of `render`; the kernel's `fit`): on a
/// screen that allows it ([`kernel_fit_screen`]), corners `p` (`[x, y,
/// z]`, `x` and `y` in subpixels from the screen's corner, `z` the depth
/// as the kernel takes it: the packed grey word when `packed`) within
/// the box `0 <= x <= width·S - S/2`, `0 <= y <= height·S`, every depth
/// within the kernel's vertex test ([`crate::target::Depth16`]'s
/// `vertices_in_range`, on [`super::grey_z`] of a packed word), a
/// non-zero area and at least one row centre within its vertical extent.
/// It implies every per-triangle test of the kernel's head but the
/// band's: the columns within `0..=width·S`, the extents below `2^14`,
/// every `y` within the coordinate limit, the empty test and the
/// depths. Checked by the kernel in `debug_assert!`s and by the tests
/// against every triangle prepare marks.
#[cfg(test)]
pub(crate) fn kernel_fit_holds(
    p: [[i32; 3]; 3],
    packed: bool,
    sub: SubpixelBits,
    width: u32,
    height: u32,
) -> bool {
    let z = p.map(|q| if packed { super::grey_z(q[2]) } else { q[2] });
    let depths = crate::target::Depth16::vertices_in_range(z);
    let s = i64::from(sub.scale());
    let (xl, yl) = (i64::from(width) * s - s / 2, i64::from(height) * s);
    let inside = p
        .iter()
        .all(|&[x, y, _]| (0..=xl).contains(&i64::from(x)) && (0..=yl).contains(&i64::from(y)));
    let [a, b, c] = p.map(|[x, y, _]| [i64::from(x), i64::from(y)]);
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    let ys = p.map(|q| q[1]);
    let (top, bot) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
    kernel_fit_screen(width, height, sub)
        && depths
        && inside
        && area != 0
        && first_row(top, sub) < first_row(bot, sub)
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
    let width = window.width as i32;
    if let Some((mut walk, row, sx, sy)) = setup(a, b, c, sub, window.y0 as i32, width) {
        walk.rows(&row, &sx, &sy, window.y1 as i32, width, &mut ToSpans(sink));
    }
}

/// A [`Spans`] sink as the walker's row sink: each span as a [`Span`].
struct ToSpans<'s, S>(&'s mut S);

impl<L: Lerp, const N: usize, S: Spans<L, N>> RowSpans<L, N> for ToSpans<'_, S> {
    #[inline(always)]
    fn span(&mut self, j: i32, x0: i32, x1: i32, v: &Vals<L, N>, sx: &Vals<L, N>, _z16: bool) {
        self.0.span(&Span {
            y: j as u32,
            x0: x0 as u32,
            x1: x1 as u32,
            z: v.z,
            dz: sx.z,
            a: v.a,
            da: sx.a,
        });
    }
}
