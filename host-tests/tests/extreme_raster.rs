//! Numerical extremes of the screen-space rasterizer (`fixshade::raster`),
//! each against an exact reference: integer edge functions in i128 for
//! coverage ([`covers`]), and the rasterizer's own f64 twin for
//! interpolated values, within the bound the module docs state: a fixed
//! attribute at a pixel `n = |di| + |dj|` pixels from the pixel centre
//! nearest vertex 0 is within `(n + 2)·(½ + |g|·2^-30)` raw units, `|g|` the
//! larger gradient per pixel.

use crate::support::rng::Rng;
use crate::support::{covers, Counter};
use fixshade::raster::{
    draw_triangle, Fill, Flat, GouraudMono, Lerp, RasterError, Span, Spans, SubpixelBits, Vertex,
    ATTR_LIMIT, DEPTH_ONE,
};
use fixshade::target::{Depth16, Depth32, DepthBuffer, DepthFormat, FrameBuf, Gray8, Rgb8, Window};

fn sub(bits: u32) -> SubpixelBits {
    SubpixelBits::new(bits).unwrap()
}

fn win(w: u32, h: u32) -> Window {
    Window {
        width: w,
        y0: 0,
        y1: h,
    }
}

/// The vertices of `tri` (subpixels, cut to `i32` as they are) with no
/// depth and no attributes.
fn flat_vertices(tri: [(i64, i64); 3]) -> [Vertex<i32, 0>; 3] {
    tri.map(|(x, y)| Vertex {
        x: x as i32,
        y: y as i32,
        z: 0,
        attrs: [],
    })
}

/// Draws a flat triangle (any `N`, attributes ignored) into a counter and
/// checks every pixel against the exact coverage; returns the pixel count.
fn exact_coverage(tri: [(i64, i64); 3], s: SubpixelBits, w: u32, h: u32) -> u64 {
    let mut t = Counter::new(w, h);
    {
        let mut f = Fill::<_, Depth16, _>::new(&mut t, None, Flat(Rgb8::WHITE)).unwrap();
        let v = flat_vertices(tri);
        f.draw(&v, s).unwrap();
    }
    for y in 0..h {
        for x in 0..w {
            let want = covers(&tri, x as i64, y as i64, s.scale() as i64) as u32;
            assert_eq!(
                t.get(x, y),
                want,
                "{tri:?} bits {} pixel ({x},{y})",
                s.get()
            );
        }
    }
    t.total()
}

/// Records attribute 0 at every pixel.
struct Probe<L> {
    values: Vec<(u32, u32, L)>,
}

impl<L: Lerp> Spans<L, 1> for Probe<L> {
    fn span(&mut self, s: &Span<L, 1>) {
        let mut v = s.a[0];
        for x in s.x0..s.x1 {
            self.values.push((x, s.y, v));
            v = v.add(s.da[0]);
        }
    }
}

/// Interpolates `vals` (raw fixed units) over `tri` with the fixed and the
/// f64 rasterizer; checks every pixel against the stated bound and returns
/// (pixels, worst error in raw units, worst error / bound).
fn check_gouraud(
    tri: [(i32, i32); 3],
    vals: [i32; 3],
    s: SubpixelBits,
    window: Window,
) -> (usize, f64, f64) {
    let fixed: [Vertex<i32, 1>; 3] = core::array::from_fn(|i| Vertex {
        x: tri[i].0,
        y: tri[i].1,
        z: 0,
        attrs: [vals[i]],
    });
    let float: [Vertex<f64, 1>; 3] = core::array::from_fn(|i| Vertex {
        x: tri[i].0,
        y: tri[i].1,
        z: 0.0,
        attrs: [vals[i] as f64],
    });
    let mut p = Probe { values: vec![] };
    let mut q = Probe { values: vec![] };
    draw_triangle(&fixed, s, window, &mut p).unwrap();
    draw_triangle(&float, s, window, &mut q).unwrap();
    assert_eq!(p.values.len(), q.values.len());
    // Exact gradients per pixel of the plane.
    let sc = s.scale() as f64;
    let (x0, y0) = (tri[0].0 as f64, tri[0].1 as f64);
    let (dx1, dy1) = (tri[1].0 as f64 - x0, tri[1].1 as f64 - y0);
    let (dx2, dy2) = (tri[2].0 as f64 - x0, tri[2].1 as f64 - y0);
    let (d1, d2) = (
        vals[1] as f64 - vals[0] as f64,
        vals[2] as f64 - vals[0] as f64,
    );
    let a = dx1 * dy2 - dx2 * dy1;
    let g = ((d1 * dy2 - d2 * dy1) * sc / a)
        .abs()
        .max(((d2 * dx1 - d1 * dx2) * sc / a).abs());
    let (mut worst, mut ratio) = (0.0f64, 0.0f64);
    for (&(x, y, v), &(qx, qy, e)) in p.values.iter().zip(q.values.iter()) {
        assert_eq!((x, y), (qx, qy));
        // n from the pixel of the anchoring vertex: bounded by the largest
        // distance to any vertex's pixel.
        let n = tri
            .iter()
            .map(|&(vx, vy)| {
                (x as i64 - vx.div_euclid(s.scale()) as i64).abs()
                    + (y as i64 - vy.div_euclid(s.scale()) as i64).abs()
            })
            .max()
            .unwrap() as f64;
        let bound = (n + 2.0) * (0.5 + g / (1u64 << 30) as f64) + 1e-6 * e.abs();
        let err = (v as f64 - e).abs();
        assert!(
            err <= bound,
            "{tri:?} {vals:?} bits {}: ({x},{y}) {v} vs {e}, bound {bound}",
            s.get()
        );
        worst = worst.max(err);
        ratio = ratio.max(err / bound);
    }
    (p.values.len(), worst, ratio)
}

/// Triangles one subpixel wide (vertical, horizontal and diagonal slivers
/// swept across pixel centres), for every subpixel precision 1..=8.
///
/// Bound: coverage is exactly the top-left rule's at every pixel; a
/// Gouraud ramp *across* the sliver (255 levels over one subpixel: up to
/// 2^32 raw units per pixel at 8 bits, past `i32`, stepped modulo 2^32 as
/// the docs say) is within the stated bound of the f64 twin at every
/// covered pixel.
#[test]
fn triangles_one_subpixel_wide() {
    let mut covered = 0;
    let mut worst = 0.0f64;
    for bits in 1..=8 {
        let s = sub(bits);
        let sc = s.scale() as i64;
        let c = |i: i64| i * sc + sc / 2; // pixel centre
        for dx in -2..=2i64 {
            for (len, off) in [(3, 0), (9, 1), (14, -1)] {
                let x = c(5) + dx;
                let (ya, yb) = (c(2) - off, c(2) + len * sc + off);
                let cases = [
                    [(x, ya), (x + 1, ya), (x, yb)],                // vertical
                    [(ya, x), (ya, x + 1), (yb, x)],                // horizontal
                    [(x, ya), (x + 1, ya), (x + 1 + len * sc, yb)], // slanted
                    [(x, ya), (x + len * sc, yb), (x + len * sc + 1, yb)],
                ];
                for tri in cases {
                    covered += exact_coverage(tri, s, 24, 24);
                    let t = tri.map(|(x, y)| (x as i32, y as i32));
                    let (_, err, _) = check_gouraud(t, [0, 255 << 16, 0], s, win(24, 24));
                    worst = worst.max(err);
                    let (_, err, _) = check_gouraud(t, [255 << 16, 0, 77 << 16], s, win(24, 24));
                    worst = worst.max(err);
                }
            }
        }
    }
    assert!(covered > 300, "the slivers hit pixel centres: {covered}");
    println!("1-subpixel slivers: {covered} pixels, worst error {worst} raw units");
}

/// Slivers with aspect ratio 10^4: 4000 pixels long, 0.4 pixel high, at
/// random angles, through a 64×64 window (their ends far outside it).
///
/// Bound: exact coverage at every pixel; Gouraud values along the sliver
/// (0 to 255 levels over its length, and a cross ramp) within the stated
/// bound of the f64 twin.
#[test]
fn slivers_with_aspect_ratio_ten_thousand() {
    let s = SubpixelBits::DEFAULT;
    let mut rng = Rng(0x5eed);
    let mut total = 0;
    let mut worst_ratio = 0.0f64;
    for _ in 0..40 {
        let ang = rng.f() * std::f64::consts::TAU;
        let (cx, cy) = (32.0 + 20.0 * rng.f(), 32.0 + 20.0 * rng.f() - 10.0);
        let (ux, uy) = (ang.cos(), ang.sin());
        let (half, h) = (2000.0, 0.4);
        let p = |x: f64, y: f64| ((x * 16.0).round() as i64, (y * 16.0).round() as i64);
        let a = p(cx - ux * half, cy - uy * half);
        let b = p(cx + ux * half, cy + uy * half);
        let c = p(cx - uy * h, cy + ux * h);
        let tri = [a, b, c];
        total += exact_coverage(tri, s, 64, 64);
        let t = tri.map(|(x, y)| (x as i32, y as i32));
        for vals in [[0, 255 << 16, 128 << 16], [10 << 16, 10 << 16, 250 << 16]] {
            let (_, _, r) = check_gouraud(t, vals, s, win(64, 64));
            worst_ratio = worst_ratio.max(r);
        }
    }
    assert!(total > 200, "the slivers cross the window: {total}");
    println!("aspect 10^4 slivers: {total} pixels, worst error {worst_ratio:.3} of the bound");
}

/// Vertices at the limits of the stated range: ±8192 pixels (±8192·2^s
/// subpixels) for every precision, with attributes at ±2^30; one subpixel
/// beyond, and any `i32`, is `RasterError::OutOfRange(vertex)`.
///
/// Bound: coverage exact on a 32×32 window (and at the window's far
/// corner of a 4096-wide screen); attributes within the stated bound of
/// the f64 twin (n up to 2·8192 + 2 pixels) and inside the vertex range
/// widened by that bound (no wrap-around); nothing drawn on an error.
#[test]
fn vertices_at_and_beyond_the_coordinate_limit() {
    let (mut covered, mut expected) = (0, 0);
    for bits in 1..=8 {
        let s = sub(bits);
        let l = s.coord_limit() as i64;
        let tris = [
            [(-l, -l), (l, -l), (-l, l)],
            [(l, l), (-l, l), (l, -l)],
            [(-l, -l), (l, l), (-l, l)],
            [(-l, 0), (l, 1), (0, l)],
        ];
        for tri in tris {
            let exact = exact_coverage(tri, s, 32, 32) as usize;
            expected += 2 * exact;
            let t = tri.map(|(x, y)| (x as i32, y as i32));
            for vals in [
                [ATTR_LIMIT, -ATTR_LIMIT, 0],
                [-ATTR_LIMIT, ATTR_LIMIT, ATTR_LIMIT],
            ] {
                let (n, _, _) = check_gouraud(t, vals, s, win(32, 32));
                covered += n;
                // The far corner of the largest screen.
                let far = Window {
                    width: 4096,
                    y0: 4080,
                    y1: 4096,
                };
                check_gouraud(t, vals, s, far);
            }
        }
        // One subpixel beyond, at each vertex and each axis, both signs.
        let ok = [(0i64, 0i64), (l, 0), (0, l)];
        for i in 0..3 {
            for bad in [(l + 1, 0), (-l - 1, 0), (0, l + 1), (0, -l - 1)] {
                let mut tri = ok;
                tri[i] = bad;
                let mut t = Counter::new(8, 8);
                let mut f = Fill::<_, Depth16, _>::new(&mut t, None, Flat(Rgb8::WHITE)).unwrap();
                let v = flat_vertices(tri);
                assert_eq!(f.draw(&v, s), Err(RasterError::OutOfRange(i as u8)));
                assert_eq!(t.total(), 0);
            }
        }
        let extreme = [Vertex::<i32, 0> {
            x: i32::MIN,
            y: i32::MAX,
            z: 0,
            attrs: [],
        }; 3];
        let mut p = Probe::<i32> { values: vec![] };
        assert_eq!(
            draw_triangle(&extreme, s, win(8, 8), &mut NoAttr(&mut p)),
            Err(RasterError::OutOfRange(0))
        );
    }
    // The probe saw exactly the covered pixels; three of the four
    // triangles cover (parts of) the window.
    assert_eq!(covered, expected);
    assert!(covered > 8 * 2 * 2 * 1024);
}

/// Adapts a one-attribute probe to zero attributes.
struct NoAttr<'a>(&'a mut Probe<i32>);
impl Spans<i32, 0> for NoAttr<'_> {
    fn span(&mut self, s: &Span<i32, 0>) {
        self.0.values.push((s.x0, s.y, 0));
    }
}

/// Collects spans.
struct Rows(Vec<(u32, u32, u32)>);
impl Spans<i32, 1> for Rows {
    fn span(&mut self, s: &Span<i32, 1>) {
        self.0.push((s.y, s.x0, s.x1));
    }
}

/// Edges 4096 rows tall (the tallest screen), and 16384 rows (from -8192
/// to +8192 pixels, the whole coordinate range) at 8 subpixel bits.
///
/// Bound: on every row the span's ends are exactly the top-left rule's
/// (`ceil` of the edge's rational crossing, computed here in i128); the
/// Gouraud values on all 4096 rows are within the stated bound of the f64
/// twin.
#[test]
fn edges_4096_rows_tall() {
    for (bits, top, bot) in [(4, 0i64, 4096i64), (8, -8192, 8192), (1, -3, 4099)] {
        let s = sub(bits);
        let sc = s.scale() as i64;
        // A steep left edge and a less steep right one, odd subpixel
        // offsets, so the DDA's error term wraps on many rows.
        let tri = [
            (3 * sc + 5 % sc, top * sc + 1),
            (7 * sc + 3 % sc, bot * sc - 1),
            (3000 * sc + 7 % sc, top * sc + 1),
        ];
        let window = Window {
            width: 4096,
            y0: 0,
            y1: 4096,
        };
        let v: [Vertex<i32, 1>; 3] = core::array::from_fn(|i| Vertex {
            x: tri[i].0 as i32,
            y: tri[i].1 as i32,
            z: 0,
            attrs: [0],
        });
        let mut rows = Rows(vec![]);
        draw_triangle(&v, s, window, &mut rows).unwrap();
        assert!(rows.0.len() >= 4090, "{} rows", rows.0.len());
        // First column at or right of the edge a -> b on row j: centre
        // (i + 1/2)·S >= X0 + (Yc - Y0)·DX/DY.
        let first = |(x0, y0): (i64, i64), (x1, y1): (i64, i64), j: i64| -> i64 {
            let (dx, dy) = ((x1 - x0) as i128, (y1 - y0) as i128);
            let yc = (j * sc + sc / 2) as i128;
            let n = (x0 as i128 - (sc / 2) as i128) * dy + (yc - y0 as i128) * dx;
            let d = sc as i128 * dy;
            (n.div_euclid(d) + (n.rem_euclid(d) != 0) as i128) as i64
        };
        for &(y, x0, x1) in &rows.0 {
            let j = y as i64;
            let l = first(tri[0], tri[1], j).max(0);
            let r = first(tri[2], tri[1], j).min(4096);
            assert_eq!((x0 as i64, x1 as i64), (l, r), "bits {bits} row {y}");
        }
        // Values along the tall edge: check a 16-column strip of all rows.
        let strip = Window {
            width: 16,
            y0: 0,
            y1: 4096,
        };
        let t = tri.map(|(x, y)| (x as i32, y as i32));
        let (n, worst, _) = check_gouraud(t, [0, 255 << 16, 100 << 16], s, strip);
        assert!(n > 4000);
        println!("{bits} bits, rows {top}..{bot}: worst error {worst} raw units");
    }
}

/// Draws `tris` (flat, one grey level each) into a 4×4 Gray8 frame with a
/// depth buffer of format `D`; returns the grey levels.
fn depth_run<D: DepthFormat, L: Lerp>(tris: &[(L, u8)]) -> Vec<u8> {
    let mut buf = vec![[0u8; 1]; 16];
    let mut vals = vec![D::CLEAR; 16];
    let mut fb = FrameBuf::<Gray8>::new(&mut buf, 4, 4).unwrap();
    let mut db = DepthBuffer::<D>::new(&mut vals, 4, 0, 4).unwrap();
    for &(z, level) in tris {
        let mut f = Fill::new(&mut fb, Some(&mut db), Flat(Rgb8::grey(level))).unwrap();
        let p = |x: i32, y: i32| Vertex { x, y, z, attrs: [] };
        for t in [
            [p(0, 0), p(64, 0), p(64, 64)],
            [p(0, 0), p(64, 64), p(0, 64)],
        ] {
            f.draw(&t, SubpixelBits::DEFAULT).unwrap();
        }
    }
    buf.iter().map(|p| p[0]).collect()
}

/// Depth values near both ends of the range, in both depth formats, fixed
/// and float: the less-than test keeps the strictly nearer fragment and
/// the first of equals; out-of-range depths saturate to 0 and 1.
///
/// Bound: Depth32 resolves one step of 2^-30 at both ends; Depth16 steps
/// are 2^-16 (depths closer than that tie: first drawn wins).
///
/// This found a bug, fixed in `target/depth.rs`: Depth16 stored a depth
/// of `1 - 2^-16` or more as 65535, the cleared value, so the less-than
/// test dropped every fragment in the last 2^-16 of the range (objects
/// right at the far plane were not drawn with a 16-bit buffer but were
/// with a 32-bit one). Depth16 now stores at most 65534.
#[test]
fn depth_near_both_ends_of_the_range() {
    const ONE: i32 = DEPTH_ONE;
    // Near end: a tie at 0 keeps the first.
    assert_eq!(depth_run::<Depth16, i32>(&[(0, 10), (0, 20)]), vec![10; 16]);
    assert_eq!(depth_run::<Depth32, i32>(&[(0, 10), (0, 20)]), vec![10; 16]);
    let near = [(1, 10), (0, 20), (0, 30), (-5, 40)];
    assert_eq!(depth_run::<Depth32, i32>(&near), vec![20; 16]);
    // 1 and 0 are the same 16-bit depth: the first wins.
    assert_eq!(depth_run::<Depth16, i32>(&near), vec![10; 16]);
    // Far end: depth exactly 1 is drawn against a cleared buffer (the
    // regression), one step nearer wins in Depth32, ties in Depth16.
    let far = [(ONE, 50), (ONE - 1, 60), (ONE + 1000, 70), (i32::MAX, 80)];
    assert_eq!(depth_run::<Depth32, i32>(&far), vec![60; 16]);
    assert_eq!(depth_run::<Depth16, i32>(&far), vec![50; 16]);
    assert_eq!(depth_run::<Depth16, i32>(&[(ONE, 90)]), vec![90; 16]);
    // The last 16-bit step is [1 - 2^-15, 1]: a tie; one step before wins.
    let far16 = [(ONE - (1 << 14), 50), (ONE - (2 << 14), 60)];
    assert_eq!(depth_run::<Depth16, i32>(&far16), vec![50; 16]);
    let far16 = [(ONE - (1 << 14), 50), (ONE - (3 << 14), 60)];
    assert_eq!(depth_run::<Depth16, i32>(&far16), vec![60; 16]);
    // Float twins: the same rules, depth in [0, 1].
    let eps = 1.0 / (1u64 << 30) as f64;
    let f = [(1.0, 50), (1.0 - eps, 60), (1.5, 70), (2.0, 80)];
    assert_eq!(depth_run::<Depth32, f64>(&f), vec![60; 16]);
    assert_eq!(depth_run::<Depth16, f64>(&f), vec![50; 16]);
    let n = [(eps, 10), (0.0, 20), (-1.0, 30), (f64::NAN, 40)];
    assert_eq!(depth_run::<Depth32, f64>(&n), vec![20; 16]);
    // Non-finite float depths are defined: NaN (and infinite vertex
    // depths, whose gradients are NaN) count as depth 0, the nearest.
    assert_eq!(
        depth_run::<Depth32, f64>(&[(0.5, 10), (f64::INFINITY, 20)]),
        vec![20; 16]
    );
    assert_eq!(
        depth_run::<Depth16, f32>(&[(0.5, 10), (f32::NAN, 20)]),
        vec![20; 16]
    );
    assert_eq!(depth_run::<Depth16, f32>(&[(1.0f32, 90)]), vec![90; 16]);
    // The saturating conversions themselves.
    assert_eq!(Depth16::from_d30(0), 0);
    assert_eq!(Depth16::from_d30(1 << 30), u16::MAX - 1);
    assert_eq!(Depth16::from_d30(u32::MAX), u16::MAX - 1);
    assert_eq!(Depth32::from_d30(u32::MAX), 1 << 30);
    assert!(Depth16::from_d30(1 << 30) < Depth16::CLEAR);
    assert!(Depth32::from_d30(1 << 30) < Depth32::CLEAR);
}

/// Two coplanar overlapping faces (z-fighting), fixed and float: the same
/// sloped triangle twice, and a constant-depth square split along both
/// diagonals. Rule: "first drawn wins ties" (less-than test) at every
/// pixel, in both depth formats.
#[test]
fn coplanar_faces_first_drawn_wins() {
    fn run<D: DepthFormat>(clear: D::Raw) {
        let (w, h) = (24u32, 20u32);
        let mut buf = vec![[0u8; 1]; (w * h) as usize];
        let mut vals = vec![clear; (w * h) as usize];
        let mut fb = FrameBuf::<Gray8>::new(&mut buf, w, h).unwrap();
        let mut db = DepthBuffer::<D>::new(&mut vals, w, 0, h).unwrap();
        let sloped = [
            Vertex {
                x: 5,
                y: 3,
                z: 1000,
                attrs: [],
            },
            Vertex {
                x: 370,
                y: 40,
                z: DEPTH_ONE - 7,
                attrs: [],
            },
            Vertex {
                x: 60,
                y: 310,
                z: DEPTH_ONE / 3 + 1,
                attrs: [],
            },
        ];
        let z = DEPTH_ONE / 5 + 12_345;
        let p = |x: i32, y: i32| Vertex { x, y, z, attrs: [] };
        let (a, b, c, d) = (p(-40, -40), p(500, -40), p(500, 400), p(-40, 400));
        for (level, tris) in [
            (10u8, vec![sloped]),
            (20, vec![sloped]),
            (30, vec![[a, b, c], [a, c, d]]),
            (40, vec![[a, b, d], [b, c, d]]),
        ] {
            let mut f = Fill::new(&mut fb, Some(&mut db), Flat(Rgb8::grey(level))).unwrap();
            for t in tris {
                f.draw(&t, SubpixelBits::DEFAULT).unwrap();
            }
        }
        let mut t = Counter::new(w, h);
        {
            let mut f = Fill::<_, Depth16, _>::new(&mut t, None, Flat(Rgb8::WHITE)).unwrap();
            f.draw(&sloped, SubpixelBits::DEFAULT).unwrap();
        }
        for y in 0..h {
            for x in 0..w {
                let got = buf[(y * w + x) as usize][0];
                // The sloped triangle is nearer than the square where it
                // lies in front; elsewhere the first square wins.
                if t.get(x, y) == 1 {
                    assert!(got == 10 || got == 30, "({x},{y}) {got}");
                } else {
                    assert_eq!(got, 30, "({x},{y})");
                }
            }
        }
        assert!(buf.iter().filter(|p| p[0] == 10).count() > 20);
    }
    run::<Depth16>(u16::MAX);
    run::<Depth32>(u32::MAX);
}

/// Targets of 0×0, 0×N, N×0 and 1×1 pixels.
///
/// Bound: nothing is written into an empty target (the counter panics on
/// any write outside its window) and drawing returns `Ok`; a 1×1 target
/// gets its pixel exactly when the top-left rule covers its centre: a
/// centre on a left or top edge is covered, on a right or bottom edge not.
#[test]
fn targets_of_zero_and_one_pixel() {
    let s = SubpixelBits::DEFAULT;
    let huge = [(-100_000i64, -100_000i64), (100_000, -90_000), (0, 100_000)];
    for (w, h) in [(0, 0), (0, 5), (5, 0)] {
        let mut t = Counter::new(w, h);
        let mut f = Fill::<_, Depth16, _>::new(&mut t, None, Flat(Rgb8::WHITE)).unwrap();
        let v = flat_vertices(huge);
        f.draw(&v, s).unwrap();
        assert_eq!(f.drawn(), 0);
        let mut empty: [[u8; 1]; 0] = [];
        let mut fb = FrameBuf::<Gray8>::new(&mut empty, w, h).unwrap();
        let mut f = Fill::<_, Depth16, _>::new(&mut fb, None, Flat(Rgb8::WHITE)).unwrap();
        f.draw(&v, s).unwrap();
    }
    // 1×1: the centre is (8, 8) in subpixels.
    // Each case with whether the pixel is covered, by the rule alone.
    let cases: [([(i64, i64); 3], bool); 6] = [
        ([(0, 0), (16, 0), (0, 16)], false), // centre on the hypotenuse (a right edge)
        ([(8, 0), (16, 16), (8, 16)], true), // on a left edge
        ([(0, 0), (8, 0), (8, 16)], false),  // on a right edge
        ([(0, 8), (16, 8), (8, 16)], true),  // on a top edge
        ([(0, 8), (16, 8), (8, 0)], false),  // on a bottom edge
        ([(7, 7), (9, 7), (8, 9)], true),    // tiny, around the centre
    ];
    for (i, (tri, covered)) in cases.into_iter().enumerate() {
        // The independent exact coverage agrees with the stated rule ...
        assert_eq!(
            exact_coverage(tri, s, 1, 1),
            u64::from(covered),
            "case {i}: exact coverage"
        );
        // ... and so does the rasterizer.
        let mut px = [[0u8; 1]; 1];
        let mut fb = FrameBuf::<Gray8>::new(&mut px, 1, 1).unwrap();
        let mut f = Fill::<_, Depth16, _>::new(&mut fb, None, GouraudMono).unwrap();
        let v = tri.map(|(x, y)| Vertex::<i32, 1> {
            x: x as i32,
            y: y as i32,
            z: 0,
            attrs: [200 << 16],
        });
        f.draw(&v, s).unwrap();
        assert_eq!(f.drawn(), u32::from(covered), "case {i}: drawn");
        assert_eq!(px[0][0], if covered { 200 } else { 0 }, "case {i}: pixel");
    }
}

/// Bands of one row: rendering random overlapping Gouraud triangles with
/// depth into 1-row bands gives the full frame's bytes, and every
/// pixel's write count of a 1-row counter band equals the full frame's.
#[test]
fn bands_one_row_high_equal_the_full_frame() {
    let s = SubpixelBits::DEFAULT;
    let mut rng = Rng(7);
    let (w, h) = (40u32, 30u32);
    let tris: Vec<[Vertex<i32, 1>; 3]> = (0..30)
        .map(|_| {
            core::array::from_fn(|_| Vertex {
                x: (rng.f() * 60.0 * 16.0) as i32 - 160,
                y: (rng.f() * 50.0 * 16.0) as i32 - 160,
                z: (rng.f() * DEPTH_ONE as f64) as i32,
                attrs: [(rng.f() * (256 << 16) as f64) as i32],
            })
        })
        .collect();
    let draw = |y0: u32, y1: u32| -> (Vec<u8>, Vec<u32>) {
        let n = (w * (y1 - y0)) as usize;
        let mut px = vec![[0u8; 1]; n];
        let mut z = vec![0u32; n];
        let mut fb = FrameBuf::<Gray8>::band(&mut px, w, y0, y1).unwrap();
        let mut db = DepthBuffer::<Depth32>::new(&mut z, w, y0, y1).unwrap();
        let mut f = Fill::new(&mut fb, Some(&mut db), GouraudMono).unwrap();
        let mut t = Counter::band(w, y0, y1);
        let mut c = Fill::<_, Depth16, _>::new(&mut t, None, GouraudMono).unwrap();
        for tri in &tris {
            f.draw(tri, s).unwrap();
            c.draw(tri, s).unwrap();
        }
        (px.iter().map(|p| p[0]).collect(), t.count)
    };
    let (full, full_count) = draw(0, h);
    let (mut bands, mut counts) = (vec![], vec![]);
    for y in 0..h {
        let (b, c) = draw(y, y + 1);
        bands.extend(b);
        counts.extend(c);
    }
    assert_eq!(bands, full);
    assert_eq!(counts, full_count);
    assert!(full.iter().filter(|&&p| p != 0).count() > 500);
}

/// Float-twin attributes beyond the `i32` range (the f32/f64 profiles
/// interpolate unclamped values) shade to the clamped levels: far below 0
/// is black, far above 255 white; NaN (and infinite vertex values, whose
/// gradients are NaN) black.
///
/// This found a bug (by fuzzing), fixed in `src/num/lerp.rs` (then
/// `raster/lerp.rs`): rounding a float below `i32::MIN` overflowed
/// (`i32::MIN - 1`: a panic in debug builds, white instead of black in
/// release).
#[test]
fn float_attributes_beyond_i32_clamp_to_the_levels() {
    for (v, want) in [
        (-1e12, 0u8),
        (f64::NEG_INFINITY, 0),
        (-3e9, 0),
        (1e12, 255),
        // Infinite vertex values give NaN gradients (inf - inf): NaN
        // shades as level 0.
        (f64::INFINITY, 0),
        (f64::NAN, 0),
    ] {
        let tri = [(0, 0), (64, 0), (0, 64)].map(|(x, y)| Vertex::<f64, 1> {
            x,
            y,
            z: 0.5,
            attrs: [v],
        });
        let tri32 = tri.map(|t| Vertex::<f32, 1> {
            x: t.x,
            y: t.y,
            z: 0.5,
            attrs: [t.attrs[0] as f32],
        });
        let mut px = [[7u8; 1]; 16];
        let mut fb = FrameBuf::<Gray8>::new(&mut px, 4, 4).unwrap();
        let mut f = Fill::<_, Depth16, _>::new(&mut fb, None, GouraudMono).unwrap();
        f.draw(&tri, SubpixelBits::DEFAULT).unwrap();
        assert_eq!(px[4][0], want, "f64 {v}");
        let mut fb = FrameBuf::<Gray8>::new(&mut px, 4, 4).unwrap();
        let mut f = Fill::<_, Depth16, _>::new(&mut fb, None, GouraudMono).unwrap();
        f.draw(&tri32, SubpixelBits::DEFAULT).unwrap();
        assert_eq!(px[4][0], want, "f32 {v}");
    }
    assert_eq!(Lerp::round_int(f64::NEG_INFINITY, 16), i32::MIN);
}
