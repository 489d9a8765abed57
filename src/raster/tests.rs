//! Pixel-exact tests of the rasterizer against an independent exact
//! coverage test.

extern crate std;
use std::{vec, vec::Vec};

use super::*;
use crate::target::{
    Depth16, Depth32, DepthBuffer, FrameBuf, Gray8, PixelFormat, Rgb8, Target, Window,
};

const SUB: SubpixelBits = SubpixelBits::DEFAULT;

/// A target that counts writes per pixel, to find overdraw and holes.
struct Counter {
    w: u32,
    h: u32,
    count: Vec<u32>,
    last: Vec<u8>,
}

impl Counter {
    fn new(w: u32, h: u32) -> Self {
        let n = (w * h) as usize;
        Self {
            w,
            h,
            count: vec![0; n],
            last: vec![0; n],
        }
    }
}

impl Target for Counter {
    type Format = Gray8;
    fn window(&self) -> Window {
        Window {
            width: self.w,
            y0: 0,
            y1: self.h,
        }
    }
    fn write_pixel(&mut self, x: u32, y: u32, p: [u8; 1]) {
        assert!(
            x < self.w && y < self.h,
            "write outside the target at ({x}, {y})"
        );
        let i = (y * self.w + x) as usize;
        self.count[i] += 1;
        self.last[i] = p[0];
    }
}

fn v(x: i32, y: i32) -> Vertex<i32, 0> {
    Vertex {
        x,
        y,
        z: 0,
        attrs: [],
    }
}

/// Pixel centre coordinates to subpixels: (i + 1/2) pixels.
fn c(i: i32) -> i32 {
    i * 16 + 8
}

fn draw_flat(t: &mut Counter, tri: &[Vertex<i32, 0>; 3]) -> Result<(), RasterError> {
    let mut f = Fill::<_, Depth16, _>::new(t, None, Flat(Rgb8::WHITE)).unwrap();
    f.draw(tri, SUB)
}

/// Independent exact coverage: edge functions at pixel centres, top-left
/// rule (y down), any winding.
fn covers(tri: &[(i64, i64); 3], px: i64, py: i64, s: i64) -> bool {
    let (a, mut b, mut c) = (tri[0], tri[1], tri[2]);
    let e = |a: (i64, i64), b: (i64, i64), p: (i64, i64)| {
        (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
    };
    let area = e(a, b, c);
    if area == 0 {
        return false;
    }
    if area < 0 {
        core::mem::swap(&mut b, &mut c);
    }
    let p = (px * s + s / 2, py * s + s / 2);
    [(a, b), (b, c), (c, a)].iter().all(|&(p0, p1)| {
        let v = e(p0, p1, p);
        let (dx, dy) = (p1.0 - p0.0, p1.1 - p0.1);
        v > 0 || (v == 0 && (dy < 0 || (dy == 0 && dx > 0)))
    })
}

/// A xorshift64 sequence from `seed` (not 0): the raw 64-bit values the
/// kernels' own tests (`edge`, `fast`, `span`) draw from.
pub(super) fn xorshift(mut seed: u64) -> impl FnMut() -> u64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    }
}

/// Deterministic pseudo-random numbers (xorshift64*).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }
    fn range(&mut self, lo: i32, hi: i32) -> i32 {
        lo + (self.next() % (hi - lo) as u64) as i32
    }
}

/// Probe recording the intensity (attribute 0) at every pixel.
struct Probe<L> {
    spans: Vec<(u32, u32, u32)>,
    values: Vec<(u32, u32, L)>,
}

impl<L: Lerp> Spans<L, 1> for Probe<L> {
    fn span(&mut self, s: &Span<L, 1>) {
        let Span {
            y,
            x0,
            x1,
            ref a,
            ref da,
            ..
        } = *s;
        self.spans.push((y, x0, x1));
        let mut v = a[0];
        for x in x0..x1 {
            self.values.push((x, y, v));
            v = v.add(da[0]);
        }
    }
}

fn seed_triangle<L: Lerp>(i: [L; 3]) -> [Vertex<L, 1>; 3] {
    [
        Vertex {
            x: c(9),
            y: c(15),
            z: i[0],
            attrs: [i[0]],
        },
        Vertex {
            x: c(3),
            y: c(3),
            z: i[0],
            attrs: [i[1]],
        },
        Vertex {
            x: c(17),
            y: c(7),
            z: i[0],
            attrs: [i[2]],
        },
    ]
}

#[test]
fn seed_gouraud_example_row_11_is_exact() {
    // Shading Techniques, seed 000: intensities 0, 24, 4 at (9,15), (3,3),
    // (17,7); row 11 covers x = 7..=12 with I = 8 - (x - 7).
    let tri = seed_triangle([0, 24 << 16, 4 << 16]);
    let win = Window {
        width: 32,
        y0: 0,
        y1: 32,
    };
    let mut p = Probe {
        spans: vec![],
        values: vec![],
    };
    draw_triangle(&tri, SUB, win, &mut p).unwrap();
    let row11: Vec<_> = p.values.iter().filter(|v| v.1 == 11).collect();
    assert_eq!(row11.len(), 6);
    for &&(x, _, raw) in &row11 {
        assert_eq!(raw, (8 - (x as i32 - 7)) << 16, "x = {x}");
    }
    assert_eq!(row11[0].0, 7);
    assert_eq!(row11[5].0, 12);
    // Exact everywhere: the plane is I = 31.5 - x - 1.5 y at pixel (x, y).
    for &(x, y, raw) in &p.values {
        let want = (63 - 2 * x as i32 - 3 * y as i32) << 15;
        assert_eq!(raw, want, "pixel ({x}, {y})");
    }

    // The f64 twin takes the same decisions with the same values.
    let tri = seed_triangle([0.0f64, 24.0, 4.0]);
    let mut q = Probe {
        spans: vec![],
        values: vec![],
    };
    draw_triangle(&tri, SUB, win, &mut q).unwrap();
    assert_eq!(p.spans, q.spans);
    for (&(x, y, f), &(_, _, i)) in q.values.iter().zip(p.values.iter()) {
        assert!((f - i as f64 / 65536.0).abs() < 1e-12, "({x}, {y})");
    }
}

#[test]
fn seed_gouraud_example_into_gray8_pixels() {
    let tri = seed_triangle([0, 24 << 16, 4 << 16]);
    let mut buf = vec![[0u8; 1]; 32 * 20];
    let mut fb = FrameBuf::<Gray8>::new(&mut buf, 32, 20).unwrap();
    Fill::<_, Depth16, _>::new(&mut fb, None, GouraudMono)
        .unwrap()
        .draw(&tri, SUB)
        .unwrap();
    let row: Vec<u8> = (0..32).map(|x| fb.get(x, 11).unwrap().r).collect();
    assert_eq!(&row[5..15], &[0, 0, 8, 7, 6, 5, 4, 3, 0, 0]);
}

#[test]
fn tall_edges_are_exact_on_every_row() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let s = 16i64;
    for k in 0..200 {
        let x0 = rng.range(-2000 * 16, 2000 * 16);
        let y0 = rng.range(-100 * 16, 100 * 16);
        let dy = 4096 * 16 + rng.range(-15, 16);
        let dx = match k % 4 {
            0 => rng.range(-1, 2),
            1 => rng.range(-4096 * 16, 4096 * 16),
            2 => 7 * 16 + 3,
            _ => -(dy / 3) - 1,
        };
        let (x1, y1) = (x0 + dx, y0 + dy);
        let j0 = (y0 as i64 - s / 2 + s - 1).div_euclid(s) as i32;
        // Started at its first row, or at a later one as a band does.
        let start = j0 + [0, 1, 17, 4000][k % 4];
        let mut e = Edge::new(x0, y0, x1, y1, start, SUB);
        for j in start..j0 + 4097 {
            // Exact: smallest i with (i + 1/2) S >= x(yc), in i128.
            let yc = j as i128 * 16 + 8;
            let num = (x0 as i128 - 8) * dy as i128 + (yc - y0 as i128) * dx as i128;
            let den = 16 * dy as i128;
            let want = num.div_euclid(den) + i128::from(num.rem_euclid(den) != 0);
            assert_eq!(e.x as i128, want, "edge {k}, row {j}");
            e.step();
        }
    }
}

#[test]
fn short_edges_started_at_any_row_are_exact() {
    // Short edges entered a few rows below their top, as bands do (the
    // division-free path for small quotients), and steep and flat ones.
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    for k in 0..3000 {
        let x0 = rng.range(-300 * 16, 300 * 16);
        let y0 = rng.range(-50 * 16, 50 * 16);
        let dy = rng.range(1, [16 * 6, 16 * 40, 3][k % 3]);
        let dx = rng.range(-dy * [1, 5, 300][k % 3], dy * [1, 5, 300][k % 3] + 1);
        let (x1, y1) = (x0 + dx, y0 + dy);
        let j0 = (y0 as i64 + 7).div_euclid(16) as i32;
        let j_end = (y1 as i64 + 7).div_euclid(16) as i32;
        for start in j0..j_end {
            let e = Edge::new(x0, y0, x1, y1, start, SUB);
            let yc = start as i128 * 16 + 8;
            let num = (x0 as i128 - 8) * dy as i128 + (yc - y0 as i128) * dx as i128;
            let den = 16 * dy as i128;
            let want = num.div_euclid(den) + i128::from(num.rem_euclid(den) != 0);
            assert_eq!(e.x as i128, want, "edge {k}, start {start}");
            // The same walker state as stepping from the first row.
            let mut w = Edge::new(x0, y0, x1, y1, j0, SUB);
            for _ in j0..start {
                w.step();
            }
            assert_eq!(w, e, "edge {k}, start {start}");
        }
    }
}

#[test]
fn random_triangles_match_exact_coverage() {
    let mut rng = Rng(12345);
    let (w, h) = (48u32, 40u32);
    for n in 0..600 {
        let span = if n % 3 == 0 { 8 * 16 } else { 70 * 16 };
        let tri: [(i64, i64); 3] = core::array::from_fn(|_| {
            (
                rng.range(-10 * 16, span) as i64,
                rng.range(-10 * 16, span) as i64,
            )
        });
        let mut t = Counter::new(w, h);
        draw_flat(&mut t, &tri.map(|(x, y)| v(x as i32, y as i32))).unwrap();
        for y in 0..h {
            for x in 0..w {
                let want = covers(&tri, x as i64, y as i64, 16) as u32;
                assert_eq!(
                    t.count[(y * w + x) as usize],
                    want,
                    "tri {n} {tri:?} px ({x},{y})"
                );
            }
        }
    }
}

/// Draws every triangle into one counter and checks each pixel against the
/// number of exact covers; returns the counter.
fn tiling(tris: &[[(i64, i64); 3]], w: u32, h: u32) -> Counter {
    let mut t = Counter::new(w, h);
    for tri in tris {
        draw_flat(&mut t, &tri.map(|(x, y)| v(x as i32, y as i32))).unwrap();
    }
    for y in 0..h {
        for x in 0..w {
            let want: u32 = tris
                .iter()
                .map(|tri| covers(tri, x as i64, y as i64, 16) as u32)
                .sum();
            assert!(want <= 1, "the exact reference covers ({x},{y}) twice");
            assert_eq!(t.count[(y * w + x) as usize], want, "pixel ({x},{y})");
        }
    }
    t
}

#[test]
fn jittered_grid_is_watertight() {
    let mut rng = Rng(777);
    let n = 24usize; // 2 * 23 * 23 = 1058 triangles
    let pts: Vec<(i64, i64)> = (0..n * n)
        .map(|k| {
            let (i, j) = ((k % n) as i32, (k / n) as i32);
            let jit = |r: &mut Rng, edge: bool| if edge { 0 } else { r.range(-12, 13) };
            let ex = i == 0 || i == n as i32 - 1;
            let ey = j == 0 || j == n as i32 - 1;
            (
                (8 + i * 40 + jit(&mut rng, ex)) as i64,
                (8 + j * 40 + jit(&mut rng, ey)) as i64,
            )
        })
        .collect();
    let mut tris = vec![];
    for j in 0..n - 1 {
        for i in 0..n - 1 {
            let (a, b, c, d) = (
                pts[j * n + i],
                pts[j * n + i + 1],
                pts[(j + 1) * n + i],
                pts[(j + 1) * n + i + 1],
            );
            if (i + j) % 2 == 0 {
                tris.push([a, b, d]);
                tris.push([a, d, c]);
            } else {
                tris.push([a, b, c]);
                tris.push([b, d, c]);
            }
        }
    }
    assert!(tris.len() >= 1000);
    let t = tiling(&tris, 60, 60);
    // No holes: the grid spans subpixels 8..=928, i.e. pixel centres 1..=57.
    for y in 1..57 {
        for x in 1..57 {
            assert_eq!(t.count[y * 60 + x], 1, "hole or overdraw at ({x},{y})");
        }
    }
}

#[test]
fn fans_around_a_point_are_watertight() {
    let mut rng = Rng(4242);
    for &(cx, cy, k) in &[(400i64, 400i64, 300usize), (408, 391, 64), (413, 397, 7)] {
        let ring: Vec<(i64, i64)> = (0..k)
            .map(|i| {
                let a = i as f64 / k as f64 * core::f64::consts::TAU;
                let r = 300.0 + rng.range(0, 60) as f64;
                (
                    cx + (r * a.cos()).round() as i64,
                    cy + (r * a.sin()).round() as i64,
                )
            })
            .collect();
        let tris: Vec<_> = (0..k)
            .map(|i| [(cx, cy), ring[i], ring[(i + 1) % k]])
            .collect();
        let t = tiling(&tris, 52, 52);
        // Every pixel within 250 subpixels of the centre is inside the fan.
        for y in 0..52i64 {
            for x in 0..52i64 {
                let (dx, dy) = (x * 16 + 8 - cx, y * 16 + 8 - cy);
                if dx * dx + dy * dy < 250 * 250 {
                    assert_eq!(t.count[(y * 52 + x) as usize], 1, "({x},{y})");
                }
            }
        }
    }
}

/// Draws `tri` (flat white) into a `W x H` [`MockTarget`](crate::target::MockTarget),
/// the public test target users draw their pictures with, and compares it
/// with `picture` (`#` drawn once, `.` never; overdraw and writes outside
/// fail too).
fn assert_picture<const W: usize, const H: usize>(tri: [(i32, i32); 3], picture: &[&str]) {
    let mut t = crate::target::MockTarget::<W, H>::new();
    let mut f = Fill::<_, Depth16, _>::new(&mut t, None, Flat(Rgb8::WHITE)).unwrap();
    f.draw(&tri.map(|(x, y)| v(x, y)), SUB).unwrap();
    if let Err(e) = t.check_pattern(picture) {
        panic!("{tri:?}: {e}");
    }
}

#[test]
fn ascii_small_triangles() {
    // Right triangle with its legs on pixel boundaries.
    assert_picture::<7, 7>(
        [(0, 0), (6 * 16, 0), (0, 6 * 16)],
        &[
            "#####..", "####...", "###....", "##.....", "#......", ".......", ".......",
        ],
    );
    // Vertices on pixel centres: the top and left edges are in, the
    // bottom and right out.
    assert_picture::<7, 7>(
        [(c(1), c(1)), (c(5), c(1)), (c(1), c(5))],
        &[
            ".......", ".####..", ".###...", ".##....", ".#.....", ".......", ".......",
        ],
    );
    // The same triangle mirrored: its vertical edge is now on the right,
    // so column 5 is out.
    assert_picture::<7, 7>(
        [(c(5), c(1)), (c(5), c(5)), (c(1), c(1))],
        &[
            ".......", ".####..", "..###..", "...##..", "....#..", ".......", ".......",
        ],
    );
}

#[test]
fn ascii_thin_and_degenerate_triangles() {
    // One pixel thin: a sliver 2 subpixels wide around column 3's centres.
    assert_picture::<7, 6>(
        [(c(3) - 1, 0), (c(3) + 1, 0), (c(3), 6 * 16)],
        &["...#..."; 6],
    );
    // Zero area: collinear points and a repeated point draw nothing.
    assert_picture::<7, 7>([(0, 0), (50, 50), (100, 100)], &["......."; 7]);
    assert_picture::<7, 7>([(c(2), c(2)), (c(2), c(2)), (c(5), c(1))], &["......."; 7]);
    // A thin horizontal sliver between two rows' centres covers nothing.
    assert_picture::<7, 3>([(0, 17), (100, 17), (50, 23)], &["......."; 3]);
}

#[test]
fn huge_and_offscreen_triangles_clip_exactly() {
    let lim = SUB.coord_limit() as i64;
    let cases: [[(i64, i64); 3]; 5] = [
        [(-lim, -lim), (lim, -lim), (-lim, lim)],
        [(lim, lim), (-lim, lim), (lim, -lim)],
        [(-lim, 300), (lim, 200), (0, lim)],
        [(-5000, -7000), (-100, -100), (-9000, 400)],
        [(100_000, 5), (120_000, 60), (110_000, 600)],
    ];
    for tri in cases {
        let mut t = Counter::new(40, 30);
        draw_flat(&mut t, &tri.map(|(x, y)| v(x as i32, y as i32))).unwrap();
        for y in 0..30 {
            for x in 0..40 {
                let want = covers(&tri, x, y, 16) as u32;
                assert_eq!(t.count[(y * 40 + x) as usize], want, "{tri:?} ({x},{y})");
            }
        }
    }
    // Beyond the limit: an error, nothing drawn.
    let mut t = Counter::new(8, 8);
    let bad = [v(0, 0), v(lim as i32 + 1, 0), v(0, 50)];
    assert_eq!(draw_flat(&mut t, &bad), Err(RasterError::OutOfRange(1)));
    let bad = [v(0, 0), v(5, 0), v(0, i32::MIN)];
    assert_eq!(draw_flat(&mut t, &bad), Err(RasterError::OutOfRange(2)));
    assert!(t.count.iter().all(|&c| c == 0));
}

#[test]
fn attributes_of_a_huge_clipped_triangle_stay_accurate() {
    // A triangle 16000 pixels wide with depth and intensity ramps: at the
    // visible pixels the values are those of the exact plane within the
    // bound of the module docs.
    let lim = SUB.coord_limit();
    let tri: [Vertex<i32, 1>; 3] = [
        Vertex {
            x: -lim,
            y: -lim,
            z: 0,
            attrs: [0],
        },
        Vertex {
            x: lim,
            y: -lim + 999,
            z: DEPTH_ONE,
            attrs: [255 << 16],
        },
        Vertex {
            x: 3,
            y: lim,
            z: DEPTH_ONE / 2,
            attrs: [77 << 16],
        },
    ];
    let win = Window {
        width: 64,
        y0: 0,
        y1: 64,
    };
    let mut p = Probe {
        spans: vec![],
        values: vec![],
    };
    draw_triangle(&tri, SUB, win, &mut p).unwrap();
    assert_eq!(p.values.len(), 64 * 64);
    let f = tri.map(|v| Vertex {
        x: v.x,
        y: v.y,
        z: v.z as f64,
        attrs: [v.attrs[0] as f64],
    });
    let mut q = Probe {
        spans: vec![],
        values: vec![],
    };
    draw_triangle(&f, SUB, win, &mut q).unwrap();
    let mut worst = 0.0f64;
    for (&(x, y, i), &(_, _, e)) in p.values.iter().zip(q.values.iter()) {
        // n <= 2 * 8192 pixels from the anchor; |g| <= 2^16 * 255 / 8192 per pixel.
        let bound = (2.0 * 8192.0 + 2.0) * (0.5 + 2040.0 * 65536.0 / (1u64 << 30) as f64);
        let err = (i as f64 - e).abs();
        assert!(err <= bound, "({x},{y}): {i} vs {e}");
        worst = worst.max(err);
    }
    // The bound is a quarter of a level (2^14 raw units) at most here.
    assert!(worst < 16384.0, "worst error {worst} raw units");
    std::println!(
        "worst intensity error {worst} raw units = {} levels",
        worst / 65536.0
    );
}

#[test]
fn depth_test_keeps_the_nearest_and_the_first_of_equals() {
    fn run<D: crate::target::DepthFormat>(vals: &mut [D::Raw]) -> Vec<u8> {
        let mut buf = vec![[0u8; 1]; 16];
        let mut fb = FrameBuf::<Gray8>::new(&mut buf, 4, 4).unwrap();
        let mut db = DepthBuffer::<D>::new(vals, 4, 0, 4).unwrap();
        let quad = |z: i32| -> [[Vertex<i32, 0>; 3]; 2] {
            let p = |x: i32, y: i32| Vertex { x, y, z, attrs: [] };
            [
                [p(0, 0), p(64, 0), p(64, 64)],
                [p(0, 0), p(64, 64), p(0, 64)],
            ]
        };
        for (z, level) in [
            (DEPTH_ONE / 2, 50u8),
            (DEPTH_ONE / 4, 100),
            (DEPTH_ONE / 4, 150),
            (DEPTH_ONE / 3, 200),
        ] {
            let mut f = Fill::new(&mut fb, Some(&mut db), Flat(Rgb8::grey(level))).unwrap();
            for t in quad(z) {
                f.draw(&t, SUB).unwrap();
            }
        }
        buf.iter().map(|p| p[0]).collect()
    }
    assert_eq!(run::<Depth16>(&mut [0u16; 16]), vec![100; 16]);
    assert_eq!(run::<Depth32>(&mut [0u32; 16]), vec![100; 16]);
}

#[test]
fn depth_buffer_must_match_the_target() {
    let mut buf = vec![[0u8; 1]; 16];
    let mut fb = FrameBuf::<Gray8>::new(&mut buf, 4, 4).unwrap();
    let mut vals = [0u16; 8];
    let mut db = DepthBuffer::<Depth16>::new(&mut vals, 4, 0, 2).unwrap();
    assert_eq!(
        Fill::new(&mut fb, Some(&mut db), Flat(Rgb8::WHITE)).unwrap_err(),
        RasterError::DepthWindowMismatch
    );
}

#[test]
fn bands_give_the_same_bytes_as_the_full_frame() {
    let mut rng = Rng(99);
    let tris: Vec<[Vertex<i32, 1>; 3]> = (0..40)
        .map(|_| {
            core::array::from_fn(|_| Vertex {
                x: rng.range(-200, 60 * 16),
                y: rng.range(-200, 50 * 16),
                z: rng.range(0, DEPTH_ONE),
                attrs: [rng.range(0, 256 << 16)],
            })
        })
        .collect();
    let (w, h) = (50u32, 45u32);
    let mut full = vec![[0u8; 1]; (w * h) as usize];
    {
        let mut fb = FrameBuf::<Gray8>::new(&mut full, w, h).unwrap();
        let mut dv = vec![0u16; (w * h) as usize];
        let mut db = DepthBuffer::<Depth16>::new(&mut dv, w, 0, h).unwrap();
        let mut f = Fill::new(&mut fb, Some(&mut db), GouraudMono).unwrap();
        for t in &tris {
            f.draw(t, SUB).unwrap();
        }
    }
    for rows in [1u32, 7, 16, 45] {
        let mut out = vec![];
        let mut band = vec![[0u8; 1]; (w * rows) as usize];
        let mut dv = vec![0u16; (w * rows) as usize];
        let mut y0 = 0;
        while y0 < h {
            let y1 = (y0 + rows).min(h);
            let n = ((y1 - y0) * w) as usize;
            let mut fb = FrameBuf::<Gray8>::band(&mut band[..n], w, y0, y1).unwrap();
            fb.clear(Rgb8::BLACK);
            let mut db = DepthBuffer::<Depth16>::new(&mut dv[..n], w, y0, y1).unwrap();
            let mut f = Fill::new(&mut fb, Some(&mut db), GouraudMono).unwrap();
            for t in &tris {
                f.draw(t, SUB).unwrap();
            }
            out.extend(fb.bytes());
            y0 = y1;
        }
        assert_eq!(
            out,
            full.iter().map(|p| p[0]).collect::<Vec<_>>(),
            "band height {rows}"
        );
    }
    assert!(full.iter().filter(|p| p[0] != 0).count() > 500);
}

#[test]
fn subpixel_bits_are_validated_and_conversions_saturate() {
    assert_eq!(SubpixelBits::new(0), Err(BadSubpixelBits));
    assert_eq!(SubpixelBits::new(9), Err(BadSubpixelBits));
    assert_eq!(
        RasterError::from(BadSubpixelBits),
        RasterError::BadSubpixelBits
    );
    let s = SubpixelBits::new(8).unwrap();
    assert_eq!(s.from_f32(1.5), 384);
    assert_eq!(s.from_f32(-1.5), -384);
    assert_eq!(s.from_f32(f32::NAN), 0);
    assert_eq!(s.from_f32(f32::INFINITY), s.coord_limit() + 1);
    assert_eq!(s.from_f64(-1e300), -(s.coord_limit() + 1));
    assert_eq!(s.from_px(i32::MAX), i32::MAX);
    // Saturated coordinates are rejected, not drawn elsewhere.
    let mut t = Counter::new(4, 4);
    let tri = [v(0, 0), v(SUB.from_f32(1e9), 0), v(0, 40)];
    assert!(draw_flat(&mut t, &tri).is_err());
    let _ = Gray8::encode(Rgb8::WHITE);
}

/// A shader that checks the per-span hook: every span announces its
/// start values, steps and length before its pixels, and each pixel's
/// attribute is the announced start plus whole steps.
struct SpanProbe {
    start: i32,
    step: i32,
    len: u32,
    shaded: std::cell::Cell<u32>,
    spans: u32,
    pixels: u32,
}

impl Shader<i32, 1> for SpanProbe {
    fn shade(&self, a: &[i32; 1]) -> Rgb8 {
        let k = self.shaded.get();
        assert!(k < self.len, "more pixels than the span announced");
        assert_eq!(
            a[0],
            self.start.wrapping_add(self.step.wrapping_mul(k as i32))
        );
        self.shaded.set(k + 1);
        Rgb8::grey(level(a[0]))
    }

    fn begin_span(&mut self, a: &[i32; 1], da: &[i32; 1], len: u32) {
        // Without a depth buffer every pixel of the span above was shaded.
        assert_eq!(self.shaded.get(), self.len);
        self.start = a[0];
        self.step = da[0];
        self.len = len;
        self.shaded.set(0);
        self.spans += 1;
        self.pixels += len;
    }
}

fn level(v: i32) -> u8 {
    (v >> 16).clamp(0, 255) as u8
}

#[test]
fn shaders_see_each_span_before_its_pixels() {
    let (w, h) = (40u32, 30u32);
    let mut buf = vec![[0u8; 1]; (w * h) as usize];
    let mut fb = FrameBuf::<Gray8>::new(&mut buf, w, h).unwrap();
    let probe = SpanProbe {
        start: 0,
        step: 0,
        len: 0,
        shaded: std::cell::Cell::new(0),
        spans: 0,
        pixels: 0,
    };
    let mut f = Fill::<_, Depth16, _>::new(&mut fb, None, probe).unwrap();
    let v = |x: i32, y: i32, l: i32| Vertex {
        x: SUB.from_px(x),
        y: SUB.from_px(y),
        z: 0,
        attrs: [l << 16],
    };
    f.draw(&[v(-5, 2, 10), v(33, 9, 250), v(12, 28, 90)], SUB)
        .unwrap();
    let drawn = f.drawn();
    let p = &f.shader;
    assert_eq!(p.shaded.get(), p.len);
    assert_eq!(p.pixels, drawn);
    assert!(
        p.spans >= 25 && drawn > 300,
        "{} spans, {drawn} pixels",
        p.spans
    );
}

/// Checks every pixel of spans flagged `z16` converts to 16 bits without
/// a clamp; counts the flagged pixels.
struct Z16Probe {
    flagged: u64,
    spans: u64,
}

impl super::RowSpans<i32, 1> for Z16Probe {
    fn span(
        &mut self,
        j: i32,
        x0: i32,
        x1: i32,
        v: &super::Vals<i32, 1>,
        sx: &super::Vals<i32, 1>,
        z16: bool,
    ) {
        self.spans += 1;
        if !z16 {
            return;
        }
        let mut z = v.z as i64;
        for x in x0..x1 {
            assert!(
                (0..65535i64 << 14).contains(&z),
                "row {j} column {x}: depth {z} out of range"
            );
            assert_eq!(v.z.wrapping_add(sx.z.wrapping_mul(x - x0)) as i64, z);
            z += sx.z as i64;
            self.flagged += 1;
        }
    }
}

#[test]
fn triangles_flagged_in_depth_range_convert_without_clamps() {
    let mut rng = Rng(0x5eed_1234_5678_9abc);
    let mut probe = Z16Probe {
        flagged: 0,
        spans: 0,
    };
    let lim = 1i64 << 30;
    for i in 0..6000 {
        let s = [1u32, 4, 8][i % 3];
        let sub = SubpixelBits::new(s).unwrap();
        let cl = sub.coord_limit();
        // Small, large and extreme triangles; depths near both ends.
        let span = match i % 20 {
            0 => cl / 2,
            1 | 2 => 1 << 10,
            _ => 16,
        };
        let (cx, cy) = (
            rng.range(-cl + span, cl - span),
            rng.range(-cl + span, cl - span),
        );
        let mut vs = [Vertex {
            x: 0,
            y: 0,
            z: 0,
            attrs: [0],
        }; 3];
        for v in vs.iter_mut() {
            v.x = (cx + rng.range(-span, span)).clamp(-cl, cl);
            v.y = (cy + rng.range(-span, span)).clamp(-cl, cl);
            v.z = match rng.next() % 4 {
                0 => (1 << 15) + rng.range(0, 1 << 12),
                1 => (65535 << 14) - (1 << 15) - 1 - rng.range(0, 1 << 12),
                _ => rng.range(0, lim as i32),
            };
        }
        let [a, b, c] = super::sort3(vs, |v| v.y);
        // Four rows through the middle (all of a small triangle).
        let (width, j0) = (1 << 14, (cy >> s) - 2);
        if let Some((mut walk, row, sx, sy)) = super::setup(&a, &b, &c, sub, j0, width) {
            walk.rows(&row, &sx, &sy, j0 + 4, width, &mut probe);
        }
    }
    // Most triangles with depths inside the margins are flagged.
    assert!(probe.flagged > 100_000, "{} pixels flagged", probe.flagged);
}

#[test]
fn inv_area_small_equals_the_general_reciprocal() {
    // Every doubled area the 32-bit path takes, both signs.
    for a in 1..1i32 << 16 {
        for v in [a, -a] {
            assert_eq!(
                InvArea::new_small(v),
                Some(InvArea::new(v as i64)),
                "a = {v}"
            );
        }
    }
    assert_eq!(InvArea::new_small(0), None);
    assert_eq!(InvArea::new_small(1 << 16), None);
    assert_eq!(InvArea::new_small(i32::MIN), None);
}

#[test]
fn first_row_edges_equal_the_general_walker() {
    let mut rng = Rng(0x5eed_0e06);
    let mut short = 0;
    for sub in [1, 4, 8].map(|b| SubpixelBits::new(b).unwrap()) {
        let lim = sub.coord_limit();
        for i in 0..20_000 {
            // Extreme coordinates on one in eight edges.
            let r = if i % 8 == 0 { lim } else { 4000 };
            let (x0, y0) = (rng.range(-r, r + 1), rng.range(-r, r + 1));
            let (x1, y1) = (
                rng.range(-r, r + 1),
                y0 + rng.range(1, r + 1).min(lim - y0).max(1),
            );
            let j0 = first_row(y0, sub);
            assert_eq!(
                Edge::at_first_row(x0, y0, x1, y1, sub),
                Edge::new(x0, y0, x1, y1, j0, sub),
                "({x0}, {y0}) -> ({x1}, {y1}) at its first row"
            );
            // The kernel's short edges, within their bounds.
            if (x1 - x0).abs() < 1 << 16 && y1 - y0 < 1 << 15 {
                short += 1;
                assert_eq!(
                    Edge::at_first_row_short(x0, y0, x1, y1, sub),
                    Edge::new(x0, y0, x1, y1, j0, sub),
                    "({x0}, {y0}) -> ({x1}, {y1}) short, at its first row"
                );
            }
            // The first row, and rows after it (the general fallback).
            for j in [j0, j0 + 1, j0 + rng.range(0, 40)] {
                assert_eq!(
                    Edge::new_first(x0, y0, x1, y1, j, sub),
                    Edge::new(x0, y0, x1, y1, j, sub),
                    "({x0}, {y0}) -> ({x1}, {y1}) row {j}"
                );
            }
        }
        // The short edges' bounds at their ends.
        for (x0, y0, x1, y1) in [
            (0, 0, (1 << 16) - 1, 1),
            (0, 0, 1 - (1 << 16), 1),
            (5, -3, 5 - (1 << 16) + 1, (1 << 15) - 4),
            (-7, 9, (1 << 16) - 8, 9 + (1 << 15) - 1),
            (0, 0, 0, 1),
        ] {
            assert_eq!(
                Edge::at_first_row_short(x0, y0, x1, y1, sub),
                Edge::new(x0, y0, x1, y1, first_row(y0, sub), sub),
                "({x0}, {y0}) -> ({x1}, {y1}) short"
            );
        }
    }
    assert!(short > 50_000, "{short}");
}

/// `setup_fast` against `setup` for one sorted triangle.
fn check_setup_fast<const N: usize>(v: [Vertex<i32, N>; 3], sub: SubpixelBits, j0: i32, w: i32) {
    let [a, b, c] = sort3(v, |v| v.y);
    let want = setup::<i32, N>(&a, &b, &c, sub, j0, w);
    let (mut walk, mut vals) = (Walk::EMPTY, [[0x5a5a_5a5a; 3]; 4]);
    let got = setup_fast::<N, 4>(&a, &b, &c, sub, j0, w, &mut walk, &mut vals);
    match want {
        Some((want_walk, row, sx, sy)) => {
            assert!(got, "{a:?} {b:?} {c:?}");
            let mut want_vals = [[0x5a5a_5a5a; 3]; 4];
            pack_vals(&mut want_vals, &row, &sx, &sy);
            assert_eq!(
                (walk, vals),
                (want_walk, want_vals),
                "{a:?} {b:?} {c:?} j0 {j0}"
            );
            assert_eq!(unpack_fixed::<N, 4>(&vals), [row, sx, sy]);
        }
        None => assert!(!got, "{a:?} {b:?} {c:?}"),
    }
}

#[test]
fn fast_setup_equals_the_general_setup() {
    let mut rng = Rng(0xfa57_5e70);
    let sub = SubpixelBits::new(4).unwrap();
    let lim = sub.coord_limit();
    for i in 0..60_000 {
        // Small triangles (the 32-bit path), larger ones, and some at the
        // coordinate limits (the general fallbacks).
        let (r, span) = match i % 10 {
            0 => (lim, lim),
            1 | 2 => (4000 * 16, 600 * 16),
            _ => (300 * 16, 24 * 16),
        };
        let (cx, cy) = (rng.range(-r, r + 1), rng.range(-r, r + 1));
        let mut p = || {
            let x = (cx + rng.range(-span, span + 1)).clamp(-lim, lim);
            let y = (cy + rng.range(-span, span + 1)).clamp(-lim, lim);
            (x, y)
        };
        let (p0, p1, p2) = (p(), p(), p());
        // Depths near the ends of the range or anywhere; levels 0..=255.
        let z = |rng: &mut Rng| match rng.range(0, 4) {
            0 => rng.range(0, 1 << 16),
            1 => (1 << 30) - rng.range(0, 1 << 16),
            2 => rng.range(i32::MIN / 2, i32::MAX / 2) * 2,
            _ => rng.range(0, 1 << 30),
        };
        let l = |rng: &mut Rng| rng.range(0, 256 << 16);
        let vert = |(x, y): (i32, i32), rng: &mut Rng| Vertex {
            x,
            y,
            z: z(rng),
            attrs: [l(rng)],
        };
        let v = [vert(p0, &mut rng), vert(p1, &mut rng), vert(p2, &mut rng)];
        let j0 = if i % 3 == 0 {
            first_row(v[0].y.min(v[1].y).min(v[2].y), sub) + rng.range(0, 8)
        } else {
            i32::MIN / 2
        };
        let w = [240, 4096, 16][i % 3];
        check_setup_fast::<1>(v, sub, j0, w);
        let flat = v.map(|v| Vertex {
            x: v.x,
            y: v.y,
            z: v.z,
            attrs: [],
        });
        check_setup_fast::<0>(flat, sub, j0, w);
    }
    // Degenerate and extreme: zero area, flat tops and bottoms, values at
    // the ends of i32.
    let vx = |x, y, z, a| Vertex {
        x,
        y,
        z,
        attrs: [a],
    };
    for t in [
        [vx(0, 0, 0, 0), vx(16, 0, 0, 0), vx(32, 0, 0, 0)],
        [
            vx(0, 0, 5, 0),
            vx(160, 0, 9, 1 << 20),
            vx(80, 160, 1 << 30, 255 << 16),
        ],
        [
            vx(0, 0, i32::MAX, i32::MIN),
            vx(16, 16, i32::MIN, i32::MAX),
            vx(0, 32, 0, 0),
        ],
        [
            vx(-lim, -lim, 0, 0),
            vx(lim, -lim, 1 << 30, 0),
            vx(0, lim, 1 << 29, 255 << 16),
        ],
        [vx(8, 8, 1, 2), vx(9, 9, 3, 4), vx(8, 40, 5, 6)],
    ] {
        for j0 in [i32::MIN / 2, 0, 1, 2] {
            check_setup_fast::<1>(t, sub, j0, 240);
        }
    }
}

/// Draws sorted triangle `v` into a band (rows `y0..y0 + rows`, `w`
/// columns, colour `px`, depth `z`) with the small-triangle kernel and
/// with the general fused walk (from fresh copies of the buffers): `None`
/// when the kernel declines (then it wrote nothing), else the pixel
/// counts, which must agree, as must every byte of both buffers.
fn check_small<const N: usize>(
    v: &[Vertex<i32, N>; 3],
    y0: i32,
    rows: i32,
    w: i32,
    px: &[u32],
    z: &[u16],
    packed: bool,
) -> Option<(u32, bool)> {
    let color = |a: &[i32; N]| {
        a.iter()
            .fold(0x9e37_79b9u32, |h, &x| h.rotate_left(5) ^ x as u32)
    };
    // Packed: the kernel takes the vertices' packed grey words.
    let words = packed.then(|| words_of(v));
    let kv_in = words.as_ref().unwrap_or(v);
    let run_small = |fit: bool| {
        let (mut p, mut d) = (px.to_vec(), z.to_vec());
        let (mut pr, mut dr) = (&mut p[..], Some(&mut d[..]));
        let mut mem = BandMem::<u32, u16> {
            px: &mut pr,
            z: &mut dr,
            y0,
            width: w,
        };
        let (mut carry, mut kv) = (Walk::EMPTY, [[0; 3]; 4]);
        let n = draw_small::<N, 4, u32, Depth16, false>(
            kv_in,
            SUB,
            y0 + rows,
            &mut mem,
            &mut carry,
            &mut kv,
            packed,
            fit,
            color,
        );
        (n, p, d, carry, kv)
    };
    let (n, p, d, carry, kv) = run_small(false);
    // A triangle within the fit contract (on a screen of `w` columns and
    // 256 rows): the kernel's fast head (`fit`) does exactly what the
    // tests do.
    let corners = kv_in.map(|q| [q.x, q.y, q.z]);
    if kernel_fit_holds(corners, packed, SUB, w as u32, 256) {
        let fast = run_small(true);
        assert!(fast == (n, p.clone(), d.clone(), carry, kv), "fit: {v:?}");
    }
    let Some((n, more)) = n else {
        assert_eq!((&p[..], &d[..]), (px, z), "declined but wrote: {v:?}");
        return None;
    };
    let (mut gp, mut gd) = (px.to_vec(), z.to_vec());
    let (mut walk, mut vals) = (Walk::EMPTY, [[0; 3]; 4]);
    let mut drawn = 0;
    if setup_fast::<N, 4>(&v[0], &v[1], &v[2], SUB, y0, w, &mut walk, &mut vals) {
        let (mut pr, mut dr) = (&mut gp[..], Some(&mut gd[..]));
        let mut mem = BandMem::<u32, u16> {
            px: &mut pr,
            z: &mut dr,
            y0,
            width: w,
        };
        drawn = walk.rows_fused::<N, 4, u32, Depth16>(&vals, y0 + rows, &mut mem, color);
    }
    // A triangle continuing below the band: the very walk and values.
    assert_eq!(more, !walk.done(), "{v:?}");
    if more {
        // Past the middle row the walk never reads its lower short edge
        // (the kernel leaves it empty).
        if walk.j > walk.mid {
            walk.low = Edge::EMPTY;
        }
        assert_eq!(carry, walk, "{v:?}");
        assert_eq!(kv[..=N], vals[..=N], "{v:?}");
    }
    assert_eq!(n, drawn, "{v:?}");
    assert!(p == gp && d == gd, "pixels differ: {v:?} y0 {y0}");
    Some((n, more))
}

/// Random pixels and depths for a band of `n` pixels: the depths mostly
/// far (most pixels pass), some near.
fn band_buffers(rng: &mut Rng, n: i32) -> (Vec<u32>, Vec<u16>) {
    let px = (0..n).map(|_| rng.next() as u32).collect();
    let zb = (0..n)
        .map(|_| {
            if rng.range(0, 4) == 0 {
                rng.range(0, 65535) as u16
            } else {
                65534
            }
        })
        .collect();
    (px, zb)
}

#[test]
fn small_kernel_equals_the_fused_walk() {
    let mut rng = Rng(0x5a11_7e57);
    let (w, rows) = (240, 16);
    let lim = SUB.coord_limit();
    let mut taken = 0;
    let mut pixels = 0;
    let mut carried = 0;
    for i in 0..20_000 {
        let y0 = [0, 16, 112, 224][i % 4];
        let (px, zb) = band_buffers(&mut rng, w * rows);
        // Mostly small triangles around the band (in it, across its
        // edges, at the window's sides), some large or at the limits.
        let (cx, cy, span) = match i % 8 {
            0 => (rng.range(-lim, lim), rng.range(-lim, lim), lim / 4),
            1 => (
                rng.range(-64, w * 16 + 64),
                y0 * 16 + rng.range(-64, rows * 16 + 64),
                300 * 16,
            ),
            2 => (rng.range(0, 32), y0 * 16 + rng.range(0, rows * 16), 48),
            _ => (
                rng.range(0, w * 16),
                y0 * 16 + rng.range(0, rows * 16),
                6 * 16,
            ),
        };
        let mut p = || {
            (
                (cx + rng.range(-span, span + 1)).clamp(-lim, lim),
                (cy + rng.range(-span, span + 1)).clamp(-lim, lim),
            )
        };
        let (p0, p1, p2) = (p(), p(), p());
        // Depths and levels near a per-triangle base (planes of a mesh),
        // or anywhere (the general path's cases).
        let (zbase, abase, k) = (
            rng.range(1 << 20, (1 << 30) - (1 << 20)),
            rng.range(0, 255 << 16),
            rng.range(0, 8),
        );
        let depth = |rng: &mut Rng| match k {
            0 => rng.range(i32::MIN / 2, i32::MAX / 2) * 2,
            1 => rng.range(0, 1 << 30),
            _ => zbase + rng.range(-(1 << 19), 1 << 19),
        };
        let level = |rng: &mut Rng| match k {
            0 | 2 => rng.range(0, 256 << 16),
            _ => abase + rng.range(0, 1 << 16),
        };
        let vert = |(x, y): (i32, i32), rng: &mut Rng| Vertex {
            x,
            y,
            z: depth(rng),
            attrs: [level(rng)],
        };
        let v = sort3(
            [vert(p0, &mut rng), vert(p1, &mut rng), vert(p2, &mut rng)],
            |v| v.y,
        );
        if let Some((n, more)) = check_small::<1>(&v, y0, rows, w, &px, &zb, false) {
            taken += 1;
            pixels += n;
            carried += more as u32;
        }
        let flat = v.map(|v| Vertex {
            x: v.x,
            y: v.y,
            z: v.z,
            attrs: [],
        });
        let _ = check_small::<0>(&flat, y0, rows, w, &px, &zb, false);
    }
    assert!(
        taken > 5_000 && pixels > 40_000 && carried > 1_000,
        "{taken} {pixels} {carried}"
    );
    // Extremes: zero area, flat tops and bottoms, one-row and one-column
    // triangles, the band's first and last rows, the window's sides,
    // values at the ends of the ranges.
    let px = vec![7u32; (w * rows) as usize];
    let zb = vec![65534u16; (w * rows) as usize];
    let vx = |x, y, z, a| Vertex {
        x,
        y,
        z,
        attrs: [a],
    };
    let (wx, b) = (w * 16, rows * 16);
    let mut small = 0;
    for t in [
        [
            vx(0, 0, 1 << 20, 0),
            vx(16, 0, 1 << 20, 0),
            vx(32, 0, 1 << 20, 0),
        ],
        [
            vx(0, 0, 1 << 20, 0),
            vx(wx, 0, (1 << 20) + (1 << 17), 1 << 12),
            vx(0, b, 1 << 20 | 1 << 16, 1 << 11),
        ],
        [
            vx(0, 0, 1 << 20, 0),
            vx(wx, 8, (1 << 20) + 99, 1 << 10),
            vx(wx, b - 9, (1 << 20) + 4000, 3 << 14),
        ],
        [
            vx(8, 8, 1 << 20, 2),
            vx(wx, 8, 1 << 20, 4),
            vx(8, 9, 1 << 20, 6),
        ],
        [
            vx(8, 7, 1 << 20, 2),
            vx(wx, 8, 1 << 20, 4),
            vx(8, 24, 1 << 20, 6),
        ],
        [
            vx(100, b - 9, 1 << 20, 0),
            vx(300, b - 8, (1 << 20) + 777, 1 << 16),
            vx(90, b + 7, (1 << 20) - 5000, 1 << 15),
        ],
        [
            vx(0, 0, 1 << 20, i32::MIN),
            vx(16, 16, 1 << 20, i32::MAX),
            vx(0, 32, 1 << 20, 0),
        ],
        [
            vx(wx - 1, 0, 1 << 16, 0),
            vx(wx, 0, 1 << 16, 0),
            vx(wx, b - 9, 1 << 30, 0),
        ],
        [
            vx(-1, 0, 1 << 20, 0),
            vx(16, 0, 1 << 20, 0),
            vx(0, 32, 1 << 20, 0),
        ],
        [
            vx(0, 8, 1 << 20, 0),
            vx(wx + 1, 8, 1 << 20, 0),
            vx(0, 40, 1 << 20, 0),
        ],
        // Across the band's end, in its upper and its lower half there.
        [
            vx(100, b - 9, 1 << 20, 0),
            vx(300, b + 30, (1 << 20) + 777, 1 << 16),
            vx(90, b + 70, (1 << 20) - 5000, 1 << 15),
        ],
        [
            vx(100, 3, 1 << 20, 0),
            vx(300, b - 30, (1 << 20) + 777, 1 << 16),
            vx(90, b + 70, (1 << 20) - 5000, 1 << 15),
        ],
        [
            vx(100, 3, 1 << 20, 0),
            vx(300, b + 8, (1 << 20) + 777, 1 << 16),
            vx(90, b + 70, (1 << 20) - 5000, 1 << 15),
        ],
    ] {
        let t = sort3(t, |v| v.y);
        small = small << 1 | check_small::<1>(&t, 0, rows, w, &px, &zb, false).is_some() as u32;
    }
    assert_eq!(small, 0b1_1111_1000_0111, "{small:013b}");
}

/// The small-triangle kernel on packed grey vertices (depth `f·2^14 +
/// 2^13`, level `f·2^8` for 16-bit fields `f`, as the packed layout
/// gives them), its planes from the fields: the very pixels, walk and
/// values of the general fused walk, on random triangles (depth fields
/// near a base or anywhere in `0..=65535`, sizes up to beyond the `2^14`
/// subpixel offsets of the field planes) and extreme ones; and taken for
/// depth differences the 32-bit numerators of the unpacked values refuse.
#[test]
fn small_kernel_on_packed_values_equals_the_fused_walk() {
    let mut rng = Rng(0x9ac4_ed00);
    let (w, rows) = (240, 16);
    let (mut taken, mut taken_unpacked) = (0, 0);
    let zdepth = |f: i32| (f << 14) | (1 << 13);
    for i in 0..20_000 {
        let y0 = [0, 16, 112, 224][i % 4];
        let (px, zb) = band_buffers(&mut rng, w * rows);
        let span = match i % 4 {
            0 => 1100 * 16,
            1 => 40 * 16,
            _ => 6 * 16,
        };
        let (cx, cy) = (rng.range(0, w * 16), y0 * 16 + rng.range(0, rows * 16));
        let mut p = || {
            (
                cx + rng.range(-span, span + 1),
                cy + rng.range(-span, span + 1),
            )
        };
        let (p0, p1, p2) = (p(), p(), p());
        let (zbase, k) = (rng.range(0, 65536), rng.range(0, 4));
        let field = |rng: &mut Rng| match k {
            0 => rng.range(0, 65536),
            1 => [0, 65535][rng.range(0, 2) as usize],
            _ => (zbase + rng.range(-300, 301)).clamp(0, 65535),
        };
        let vert = |(x, y): (i32, i32), rng: &mut Rng| Vertex {
            x,
            y,
            z: zdepth(field(rng)),
            attrs: [field(rng) << 8],
        };
        let v = sort3(
            [vert(p0, &mut rng), vert(p1, &mut rng), vert(p2, &mut rng)],
            |v| v.y,
        );
        taken += check_small::<1>(&v, y0, rows, w, &px, &zb, true).is_some() as u32;
        taken_unpacked += check_small::<1>(&v, y0, rows, w, &px, &zb, false).is_some() as u32;
    }
    assert!(taken > taken_unpacked + 500, "{taken} {taken_unpacked}");
    // Extremes: the ends of the fields, offsets at the 2^14 bound.
    let px = vec![7u32; (w * rows) as usize];
    let zb = vec![65534u16; (w * rows) as usize];
    let vx = |x, y, f: i32, l: i32| Vertex {
        x,
        y,
        z: zdepth(f),
        attrs: [l << 8],
    };
    let e = (1 << 14) - 1;
    for t in [
        [vx(0, 0, 0, 0), vx(16, 0, 65535, 65535), vx(0, 40, 65535, 0)],
        [vx(0, 8, 65535, 0), vx(e, 8, 0, 65535), vx(0, 200, 0, 65535)],
        [vx(0, 8, 65535, 65535), vx(e + 1, 8, 0, 0), vx(0, 200, 0, 0)],
        [vx(8, 8, 1, 2), vx(9, 9, 3, 4), vx(8, 40, 5, 6)],
        [
            vx(3000, 8, 65535, 0),
            vx(3001, 9, 0, 65535),
            vx(3000, 9, 65535, 1),
        ],
    ] {
        let t = sort3(t, |v| v.y);
        let _ = check_small::<1>(&t, 0, rows, w, &px, &zb, true);
    }
}

/// Draws sorted grey triangle `v` into a band with
/// [`draw_small`] with `LEVELS` (the unclamped level of [`GouraudMono`]) and with
/// the general fused walk (the clamped one), from fresh copies of the
/// buffers: `None` when the kernel declines (then it wrote nothing), else
/// the pixel counts, which must agree, as must every byte of both
/// buffers and the walk and values left for the next band.
fn check_small_levels(
    v: &[Vertex<i32, 1>; 3],
    y0: i32,
    rows: i32,
    w: i32,
    z: &[u16],
    packed: bool,
) -> Option<(u32, bool)> {
    let words = packed.then(|| words_of(v));
    let kv_in = words.as_ref().unwrap_or(v);
    let px = vec![[0x5au8]; z.len()];
    let (mut p, mut d) = (px.clone(), z.to_vec());
    let (mut carry, mut kv) = (Walk::EMPTY, [[0; 3]; 4]);
    let small = {
        let (mut pr, mut dr) = (&mut p[..], Some(&mut d[..]));
        let mut mem = BandMem::<[u8; 1], u16> {
            px: &mut pr,
            z: &mut dr,
            y0,
            width: w,
        };
        draw_small::<1, 4, [u8; 1], Depth16, true>(
            kv_in,
            SUB,
            y0 + rows,
            &mut mem,
            &mut carry,
            &mut kv,
            packed,
            false,
            |a| GouraudMono.shade_raw_in_range::<Gray8>(a),
        )
    };
    let Some((n, more)) = small else {
        assert!(p == px && d == z, "declined but wrote: {v:?}");
        return None;
    };
    let (mut gp, mut gd) = (px.clone(), z.to_vec());
    let (mut walk, mut vals) = (Walk::EMPTY, [[0; 3]; 4]);
    let mut drawn = 0;
    if setup_fast::<1, 4>(&v[0], &v[1], &v[2], SUB, y0, w, &mut walk, &mut vals) {
        let (mut pr, mut dr) = (&mut gp[..], Some(&mut gd[..]));
        let mut mem = BandMem::<[u8; 1], u16> {
            px: &mut pr,
            z: &mut dr,
            y0,
            width: w,
        };
        drawn = walk.rows_fused::<1, 4, [u8; 1], Depth16>(&vals, y0 + rows, &mut mem, |a| {
            GouraudMono.shade_raw::<Gray8>(a)
        });
    }
    assert_eq!(more, !walk.done(), "{v:?}");
    if more {
        if walk.j > walk.mid {
            walk.low = Edge::EMPTY;
        }
        assert_eq!(carry, walk, "{v:?}");
        assert_eq!(kv[..2], vals[..2], "{v:?}");
    }
    assert_eq!(n, drawn, "{v:?}");
    assert!(p == gp && d == gd, "pixels differ: {v:?} y0 {y0}");
    Some((n, more))
}

/// The unclamped grey kernel ([`draw_small`] with `LEVELS`) draws the very
/// pixels of the clamped general path, on triangles whose levels reach
/// 0 and 255 exactly, lie near them, or beyond (then declined).
#[test]
fn small_levels_equal_the_clamped_walk() {
    let mut rng = Rng(0x1e7e_15ed);
    let (w, rows) = (240, 16);
    let (mut taken, mut declined, mut pixels, mut carried, mut dark, mut bright) =
        (0, 0, 0u32, 0, 0, 0);
    let mut packed_taken = 0;
    for i in 0..20_000 {
        let y0 = [0, 16, 112, 224][i % 4];
        let (_, zb) = band_buffers(&mut rng, w * rows);
        let span = if i % 5 == 0 { 40 * 16 } else { 6 * 16 };
        let (cx, cy) = (rng.range(0, w * 16), y0 * 16 + rng.range(0, rows * 16));
        let mut p = || {
            (
                (cx + rng.range(-span, span + 1)).clamp(0, w * 16),
                cy + rng.range(-span, span + 1),
            )
        };
        let (p0, p1, p2) = (p(), p(), p());
        let top = 255 << 16;
        let level = |rng: &mut Rng| match i % 6 {
            0 => 0,
            1 => top,
            2 => rng.range(0, 1 << 16),
            3 => top - rng.range(0, 1 << 16),
            4 => rng.range(-(1 << 16), top + (1 << 16)),
            _ => rng.range(0, top + 1),
        };
        let zbase = rng.range(1 << 20, (1 << 30) - (1 << 20));
        let vert = |(x, y): (i32, i32), rng: &mut Rng| Vertex {
            x,
            y,
            z: zbase + rng.range(-(1 << 19), 1 << 19),
            attrs: [level(rng)],
        };
        let v = sort3(
            [vert(p0, &mut rng), vert(p1, &mut rng), vert(p2, &mut rng)],
            |v| v.y,
        );
        // The same triangle with packed grey values (depth fields, levels
        // in steps of 2^8 within 0..=255·2^16), as words and as values.
        let vp = v.map(|p| Vertex {
            z: grey_z(((p.z >> 14) as u32 as i32) << 16),
            attrs: [p.attrs[0].clamp(0, top) & !0xff],
            ..p
        });
        packed_taken += check_small_levels(&vp, y0, rows, w, &zb, true).is_some() as u32;
        let _ = check_small_levels(&vp, y0, rows, w, &zb, false);
        match check_small_levels(&v, y0, rows, w, &zb, false) {
            Some((n, more)) => {
                taken += 1;
                pixels += n;
                carried += more as u32;
                dark += (n > 0 && v.iter().any(|v| v.attrs[0] == 0)) as u32;
                bright += (n > 0 && v.iter().any(|v| v.attrs[0] == top)) as u32;
            }
            None => declined += 1,
        }
    }
    assert!(
        taken > 8_000 && declined > 1_000 && pixels > 100_000 && carried > 1_000,
        "{taken} {declined} {pixels} {carried}"
    );
    assert!(dark > 1_000 && bright > 1_000, "{dark} {bright}");
    assert!(packed_taken > 8_000, "{packed_taken}");
}

/// The packed grey words ([`grey_z`], [`grey_l`]) of packed grey vertices
/// (`N = 1`; each depth `f·2^14 + 2^13`, each level `f·2^8` for 16-bit
/// fields `f`), as [`draw_small`] takes them with `packed`: the word as
/// the depth and as the value.
fn words_of<const N: usize>(v: &[Vertex<i32, N>; 3]) -> [Vertex<i32, N>; 3] {
    assert_eq!(N, 1);
    v.map(|p| {
        let w = ((p.z as u32 >> 14) << 16) as i32 | (p.attrs[0] >> 8);
        assert_eq!(
            (grey_z(w), grey_l(w)),
            (p.z, p.attrs[0]),
            "not packed: {p:?}"
        );
        Vertex {
            z: w,
            attrs: [w; N],
            ..p
        }
    })
}

/// [`words_in_range`](super::fast) on the words equals
/// [`Depth16::vertices_in_range`] on their depths, for every depth field
/// (through the kernel: a triangle is taken exactly when its unpacked
/// twin is, checked by the packed tests above).
#[test]
fn packed_depth_fields_in_range() {
    for f in 0..=0xffffu32 {
        let w = (f << 16 | 0x1234) as i32;
        let z = grey_z(w);
        assert_eq!(z, ((f << 14) | (1 << 13)) as i32);
        assert_eq!(grey_l(w), 0x1234 << 8);
        let ok = Depth16::vertices_in_range([z; 3]);
        assert_eq!(super::fast::words_in_range([w; 3]), ok, "{f}");
    }
}

/// [`Fill`]'s span loops against a one-pixel-a-step reference (depth
/// with the clamping conversion, less-than, colour from the attributes
/// stepped one pixel at a time): spans of 1 to 90 pixels, so that the
/// long spans take the unrolled loop (with every remainder of 8), over
/// stored depths that let some pixels fail, tie (equal key: fails) or
/// pass by one; flat and Gouraud, depths and levels in and out of range.
#[test]
fn span_loops_match_the_one_pixel_reference() {
    use crate::target::{DepthFormat, Rgb565Be};
    const W: usize = 96;
    fn check<const N: usize, S: Shader<i32, N> + Copy>(
        shader: S,
        rng: &mut Rng,
        z: i32,
        dz: i32,
        a: [i32; N],
        da: [i32; N],
        len: u32,
    ) -> u32 {
        let mut stored = [0u16; W];
        for (k, s) in stored.iter_mut().enumerate() {
            let key = Depth16::from_lerp(z.wrapping_add(dz.wrapping_mul(k as i32)));
            *s = match rng.next() % 5 {
                0 => key,
                1 => key.saturating_add(1),
                2 => key.saturating_sub(1),
                3 => rng.next() as u16,
                _ => u16::MAX,
            };
        }
        let x0 = (rng.next() % (W as u64 - len as u64 + 1)) as u32;
        let (mut want_px, mut want_z) = ([0u16; W], stored);
        let mut want_drawn = 0;
        for k in 0..len {
            let i = (x0 + k) as usize;
            let zk = z.wrapping_add(dz.wrapping_mul(k as i32));
            let mut ak = a;
            for (v, d) in ak.iter_mut().zip(da) {
                *v = v.wrapping_add(d.wrapping_mul(k as i32));
            }
            let key = Depth16::from_lerp(zk);
            if key < want_z[i] {
                want_z[i] = key;
                want_px[i] = Rgb565Be::encode(shader.shade(&ak));
                want_drawn += 1;
            }
        }
        let mut px = [0u16; W];
        let mut zs = [0u16; W];
        let mut fb = FrameBuf::<Rgb565Be>::new(&mut px, W as u32, 1).unwrap();
        let mut db = DepthBuffer::<Depth16>::new(&mut zs, W as u32, 0, 1).unwrap();
        db.values_mut().copy_from_slice(&stored);
        let mut f = Fill::new(&mut fb, Some(&mut db), shader).unwrap();
        f.span(&Span {
            y: 0,
            x0,
            x1: x0 + len,
            z,
            dz,
            a,
            da,
        });
        assert_eq!(f.drawn(), want_drawn, "{z} {dz} {a:?} {da:?} {len}");
        assert_eq!(zs, want_z, "{z} {dz} {a:?} {da:?} {len}");
        assert_eq!(px, want_px, "{z} {dz} {a:?} {da:?} {len}");
        want_drawn
    }
    let mut rng = Rng(0x0dd5_9a11_7e57_cafe);
    let lim = 65535 << 14;
    let mut drawn = 0;
    for i in 0..6000u32 {
        let len = 1 + i % 90;
        // Depths mostly in range, sometimes past either end.
        let z = match i % 7 {
            0 => rng.range(-(1 << 20), 1 << 20),
            1 => rng.range(lim - (1 << 20), lim + (1 << 20)),
            _ => rng.range(0, lim),
        };
        let dz = rng.range(-(1 << 22), 1 << 22) >> (rng.next() % 20);
        let lv = rng.range(-(8 << 16), 263 << 16);
        let dl = rng.range(-(1 << 20), 1 << 20) >> (rng.next() % 16);
        drawn += check(Flat(Rgb8::new(200, 100, 50)), &mut rng, z, dz, [], [], len);
        drawn += check(GouraudMono, &mut rng, z, dz, [lv], [dl], len);
    }
    assert!(drawn > 100_000, "{drawn}");
}
