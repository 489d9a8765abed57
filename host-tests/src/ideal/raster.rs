//! Screen-space triangle coverage with the top-left rule.
//!
//! Conventions (screen `y` grows downward, pixel `(i, j)` has its centre at
//! `(i + 0.5, j + 0.5)`):
//!
//! * The edge function of the directed edge `a -> b` at `p` is
//!   `(b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x)`. It is always
//!   evaluated with the endpoints in one canonical order (by `(y, x)`) and
//!   negated if needed, so the two triangles sharing an edge see exactly
//!   opposite values (negation is exact in `f64`).
//! * A triangle is first brought to positive orientation (signed area
//!   `E(v0 -> v1, v2) > 0`, i.e. clockwise as drawn on the y-down screen);
//!   both orientations are rasterised. Zero-area triangles cover nothing.
//! * A pixel centre is covered when every edge function is `> 0`, or `== 0`
//!   on an edge that is *top* (horizontal, `b.x > a.x`, triangle below it) or
//!   *left* (`b.y < a.y`, going up the screen, interior to its right).
//!   Two triangles sharing an edge therefore never both cover, nor both
//!   miss, a centre on that edge.

use super::error::IdealError;

/// Edge function of `a -> b` at `p`, evaluated in canonical order.
fn edge(a: [f64; 2], b: [f64; 2], p: [f64; 2]) -> f64 {
    let raw =
        |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    if (a[1], a[0]) <= (b[1], b[0]) {
        raw(a, b)
    } else {
        -raw(b, a)
    }
}

/// Top-left rule for the directed edge `a -> b` of a positively oriented
/// triangle.
fn is_top_left(a: [f64; 2], b: [f64; 2]) -> bool {
    let dy = b[1] - a[1];
    let dx = b[0] - a[0];
    (dy == 0.0 && dx > 0.0) || dy < 0.0
}

/// Inclusive range of pixel indices whose centres `k + 0.5` lie in
/// `[lo, hi]`, clipped to `0..n`; `None` if empty.
fn centre_range(lo: f64, hi: f64, n: u32) -> Option<(u32, u32)> {
    let first = (lo - 0.5).ceil().max(0.0);
    let last = (hi - 0.5).floor().min(f64::from(n) - 1.0);
    if n == 0 || first > last {
        return None;
    }
    // Both are integral and within [0, n - 1], so the casts are exact.
    Some((first as u32, last as u32))
}

/// Calls `visit(x, y, bary)` for every covered pixel centre of the screen
/// triangle `v`, where `bary[i]` is the screen-space barycentric weight of
/// `v[i]` at that centre (they sum to 1). Input must be finite.
pub(crate) fn for_each_covered(
    v: [[f64; 2]; 3],
    width: u32,
    height: u32,
    mut visit: impl FnMut(u32, u32, [f64; 3]),
) {
    // Orient positively; `order[k]` is the caller's index of vertex k.
    let area = edge(v[0], v[1], v[2]);
    let order = if area > 0.0 {
        [0, 1, 2]
    } else if area < 0.0 {
        [0, 2, 1]
    } else {
        return;
    };
    let p = [v[order[0]], v[order[1]], v[order[2]]];
    let min = |k: usize| p[0][k].min(p[1][k]).min(p[2][k]);
    let max = |k: usize| p[0][k].max(p[1][k]).max(p[2][k]);
    let Some((x0, x1)) = centre_range(min(0), max(0), width) else {
        return;
    };
    let Some((y0, y1)) = centre_range(min(1), max(1), height) else {
        return;
    };
    // Edge k is opposite vertex k: its function is vertex k's weight.
    let edges = [(p[1], p[2]), (p[2], p[0]), (p[0], p[1])];
    let top_left = edges.map(|(a, b)| is_top_left(a, b));
    for y in y0..=y1 {
        for x in x0..=x1 {
            let c = [f64::from(x) + 0.5, f64::from(y) + 0.5];
            let e = edges.map(|(a, b)| edge(a, b, c));
            let inside = (0..3).all(|k| e[k] > 0.0 || (e[k] == 0.0 && top_left[k]));
            if !inside {
                continue;
            }
            let sum = e[0] + e[1] + e[2];
            let mut bary = [0.0; 3];
            for k in 0..3 {
                bary[order[k]] = e[k] / sum;
            }
            visit(x, y, bary);
        }
    }
}

/// Public, checked entry point to the coverage rule: calls
/// `visit(x, y, bary)` for every pixel of a `width x height` screen whose
/// centre the screen-space triangle `vertices` covers (see the module docs
/// for the exact rule), and returns how many pixels it visited.
///
/// `bary[i]` is the screen-space barycentric weight of `vertices[i]`.
/// Non-finite coordinates are rejected with [`IdealError::NonFinite`].
pub fn raster_screen(
    vertices: [[f64; 2]; 3],
    width: u32,
    height: u32,
    mut visit: impl FnMut(u32, u32, [f64; 3]),
) -> Result<usize, IdealError> {
    if vertices.iter().flatten().any(|c| !c.is_finite()) {
        return Err(IdealError::NonFinite("raster_screen vertices".into()));
    }
    let mut count = 0;
    for_each_covered(vertices, width, height, |x, y, b| {
        count += 1;
        visit(x, y, b);
    });
    Ok(count)
}
