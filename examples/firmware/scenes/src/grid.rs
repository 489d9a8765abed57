//! The "grid" scenes: many small triangles, standing in for the bunny
//! benchmark (about 1 800 front-facing triangles covering about 14 500
//! pixels) until the core renders 3D meshes.
//!
//! A 30×30 grid of quads, 4 pixels apart (120×120 pixels, 1 800 triangles,
//! each about 8 pixels), its vertices jittered by up to ±6/16 pixel by an
//! integer hash so that edges fall between pixel centres as a mesh's do,
//! diagonals alternating. Depth is a dome (nearest at the centre); levels
//! come from an integer formula: a dome lit from the upper left plus hash
//! noise, standing in for `0.2 + 0.8·max(0, N·L)`.

use crate::{level, meets_rows, Band, BandDepth, SUB};
use fixshade::raster::{Fill, Flat, GouraudMono, RasterError, Vertex, DEPTH_ONE};
use fixshade::target::{Rgb8, Target};

/// Quads per side.
const N: usize = 30;
/// Vertices per side.
const NV: usize = N + 1;
/// Quad pitch in pixels.
const PITCH: i32 = 4;
/// Top-left corner in pixels.
const ORIGIN: i32 = 60;

/// Triangles in the scene.
pub const TRIANGLES: usize = 2 * N * N;

const fn hash(i: usize, j: usize) -> u32 {
    let mut h = (i as u32).wrapping_mul(73_856_093) ^ (j as u32).wrapping_mul(19_349_663);
    h ^= h >> 13;
    h = h.wrapping_mul(0x5bd1_e995);
    h ^ (h >> 15)
}

const fn clamp(v: i32, lo: i32, hi: i32) -> i32 {
    if v < lo {
        lo
    } else if v > hi {
        hi
    } else {
        v
    }
}

const fn vertex(i: usize, j: usize) -> Vertex<i32, 1> {
    let h = hash(i, j);
    let jx = (h % 13) as i32 - 6;
    let jy = ((h >> 8) % 13) as i32 - 6;
    let (u, w) = (i as i32 - N as i32 / 2, j as i32 - N as i32 / 2);
    let r2 = u * u + w * w; // 0..=450
    let lit = clamp(450 - r2 - 8 * (u + w), 0, 450);
    let noise = ((h >> 16) % 17) as i32 - 8;
    let l = clamp(51 + lit * 204 / 450 + noise, 0, 255);
    Vertex {
        x: (ORIGIN + PITCH * i as i32) * 16 + jx,
        y: (ORIGIN + PITCH * j as i32) * 16 + jy,
        z: DEPTH_ONE / 4 + r2 * (DEPTH_ONE / 1024),
        attrs: [level(l)],
    }
}

const fn build() -> [Vertex<i32, 1>; NV * NV] {
    let mut out = [Vertex {
        x: 0,
        y: 0,
        z: 0,
        attrs: [0],
    }; NV * NV];
    let mut j = 0;
    while j < NV {
        let mut i = 0;
        while i < NV {
            out[j * NV + i] = vertex(i, j);
            i += 1;
        }
        j += 1;
    }
    out
}

/// The grid's vertices, row-major.
const VERTICES: [Vertex<i32, 1>; NV * NV] = build();

/// Triangle `k` (0 or 1) of quad `(i, j)`.
#[inline(always)]
pub fn triangle(i: usize, j: usize, k: usize) -> [Vertex<i32, 1>; 3] {
    let at = |di: usize, dj: usize| VERTICES[(j + dj) * NV + i + di];
    match ((i + j) & 1 == 0, k == 0) {
        (true, true) => [at(0, 0), at(1, 0), at(1, 1)],
        (true, false) => [at(0, 0), at(1, 1), at(0, 1)],
        (false, true) => [at(0, 0), at(1, 0), at(0, 1)],
        (false, false) => [at(1, 0), at(1, 1), at(0, 1)],
    }
}

/// Per quad row, the vertical extent of its vertices in subpixels.
const ROWS: [(i32, i32); N] = {
    let mut r = [(0, 0); N];
    let mut j = 0;
    while j < N {
        let (mut top, mut bottom) = (i32::MAX, i32::MIN);
        let mut i = 0;
        while i < NV {
            let (a, b) = (VERTICES[j * NV + i].y, VERTICES[(j + 1) * NV + i].y);
            let lo = if a < b { a } else { b };
            let hi = if a > b { a } else { b };
            if lo < top {
                top = lo;
            }
            if hi > bottom {
                bottom = hi;
            }
            i += 1;
        }
        r[j] = (top, bottom);
        j += 1;
    }
    r
};

/// The level (0..=255) of vertex `(i + di, j + dj)`.
const fn lv(i: usize, j: usize, di: usize, dj: usize) -> i32 {
    VERTICES[(j + dj) * NV + i + di].attrs[0] >> 16
}

/// Flat level per triangle: the mean of its vertices' levels (the face
/// normal's intensity, as a mesh would carry it).
const FLAT: [u8; TRIANGLES] = {
    let mut f = [0u8; TRIANGLES];
    let mut j = 0;
    while j < N {
        let mut i = 0;
        while i < N {
            let (a, b) = if (i + j) & 1 == 0 {
                (
                    lv(i, j, 0, 0) + lv(i, j, 1, 0) + lv(i, j, 1, 1),
                    lv(i, j, 0, 0) + lv(i, j, 1, 1) + lv(i, j, 0, 1),
                )
            } else {
                (
                    lv(i, j, 0, 0) + lv(i, j, 1, 0) + lv(i, j, 0, 1),
                    lv(i, j, 1, 0) + lv(i, j, 1, 1) + lv(i, j, 0, 1),
                )
            };
            f[2 * (j * N + i)] = (a / 3) as u8;
            f[2 * (j * N + i) + 1] = (b / 3) as u8;
            i += 1;
        }
        j += 1;
    }
    f
};

/// The quad rows that can meet the band's rows.
#[inline(always)]
fn rows_in(fb: &Band<'_>) -> impl Iterator<Item = usize> {
    let w = fb.window();
    let s = SUB.get();
    let (y0, y1) = ((w.y0 as i32) << s, (w.y1 as i32) << s);
    (0..N).filter(move |&j| ROWS[j].1 >= y0 && ROWS[j].0 < y1)
}

/// Draws the Gouraud grid into a band.
pub fn draw_gouraud(fb: &mut Band<'_>, db: &mut BandDepth<'_>) -> Result<(), RasterError> {
    let w = fb.window();
    let rows = rows_in(fb);
    let mut fill = Fill::new(fb, Some(db), GouraudMono)?;
    for j in rows {
        for i in 0..N {
            for k in 0..2 {
                let tri = triangle(i, j, k);
                if meets_rows(&tri, w) {
                    fill.draw(&tri, SUB)?;
                }
            }
        }
    }
    Ok(())
}

/// Draws the flat grid into a band.
pub fn draw_flat(fb: &mut Band<'_>, db: &mut BandDepth<'_>) -> Result<(), RasterError> {
    let w = fb.window();
    let rows = rows_in(fb);
    let mut fill = Fill::new(fb, Some(db), Flat(Rgb8::BLACK))?;
    for j in rows {
        for i in 0..N {
            for k in 0..2 {
                let t = triangle(i, j, k);
                if meets_rows(&t, w) {
                    let strip = |v: Vertex<i32, 1>| Vertex {
                        x: v.x,
                        y: v.y,
                        z: v.z,
                        attrs: [],
                    };
                    fill.shader = Flat(Rgb8::grey(FLAT[2 * (j * N + i) + k]));
                    fill.draw(&t.map(strip), SUB)?;
                }
            }
        }
    }
    Ok(())
}

/// Every triangle of the grid, for tests.
#[cfg(test)]
pub fn all() -> impl Iterator<Item = [Vertex<i32, 1>; 3]> {
    (0..N).flat_map(|j| (0..N).flat_map(move |i| (0..2).map(move |k| triangle(i, j, k))))
}
