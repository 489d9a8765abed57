//! Property tests of the screen-space rasterizer over random triangles,
//! fans and grids: no panic and nothing written outside the window, exact
//! coverage, watertight shared edges, and fixed-point Gouraud within the
//! bound the `raster` module docs state.

use crate::support::{covers, Counter};
use fixshade::raster::{
    draw_triangle, Fill, Flat, GouraudMono, Lerp, RasterError, Span, Spans, SubpixelBits, Vertex,
};
use fixshade::target::{Depth16, FrameBuf, Gray8, Rgb8, Window};
use proptest::prelude::*;

fn flat(t: &mut Counter, tri: &[(i64, i64); 3], s: SubpixelBits) -> Result<(), RasterError> {
    let mut f = Fill::<_, Depth16, _>::new(t, None, Flat(Rgb8::WHITE)).unwrap();
    let v = tri.map(|(x, y)| Vertex::<i32, 0> {
        x: x as i32,
        y: y as i32,
        z: 0,
        attrs: [],
    });
    f.draw(&v, s)
}

fn bits() -> impl Strategy<Value = SubpixelBits> {
    (1u32..=8).prop_map(|b| SubpixelBits::new(b).unwrap())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    /// Any `i32` vertices, any precision, any window of a 40-pixel-wide
    /// screen: `Ok` with exactly the top-left rule's pixels when every
    /// vertex is within ±8192 px, otherwise `OutOfRange(first bad vertex)`
    /// and nothing drawn; never a write outside the window (the counter
    /// panics on one).
    #[test]
    fn any_triangle_is_exact_or_refused(
        s in bits(),
        seed in prop::array::uniform6(0u64..4),
        raw in prop::array::uniform6(any::<i32>()),
        near in prop::array::uniform6(-300i64..1200),
        rows in (0u32..40, 0u32..12),
    ) {
        let lim = s.coord_limit() as i64;
        let pick = |k: usize| match seed[k] {
            0 => raw[k] as i64,
            1 => lim + near[k] % 3,
            2 => -lim - near[k] % 3,
            _ => near[k] << s.get() >> 4,
        };
        let tri = [(pick(0), pick(1)), (pick(2), pick(3)), (pick(4), pick(5))];
        let (y0, y1) = (rows.0.min(39), (rows.0 + rows.1).min(40));
        let mut t = Counter::band(40, y0, y1);
        let bad = tri.iter().position(|&(x, y)| x.abs() > lim || y.abs() > lim);
        let r = flat(&mut t, &tri, s);
        match bad {
            Some(i) => {
                prop_assert_eq!(r, Err(RasterError::OutOfRange(i as u8)));
                prop_assert_eq!(t.total(), 0);
            }
            None => {
                prop_assert_eq!(r, Ok(()));
                for y in y0..y1 {
                    for x in 0..40 {
                        let want = covers(&tri, x as i64, y as i64, s.scale() as i64) as u32;
                        prop_assert_eq!(t.get(x, y), want, "({}, {})", x, y);
                    }
                }
            }
        }
    }

    /// Random fans around a point (a star-shaped polygon, closed or open)
    /// with vertices anywhere in the coordinate range: every pixel drawn
    /// at most once, and exactly once where the polygon covers its centre
    /// (the union of the exact covers): no holes along shared edges or at
    /// the shared centre.
    #[test]
    fn fans_are_watertight(
        s in bits(),
        centre in (-40i64..80, -40i64..70),
        spokes in prop::collection::vec((1u32..1000, 1.0f64..400.0), 3..14),
        closed in any::<bool>(),
        far in any::<bool>(),
    ) {
        let sc = s.scale() as i64;
        let lim = s.coord_limit() as f64;
        let c = (centre.0 * sc + sc / 3, centre.1 * sc + sc / 5);
        // Sorted angles with gaps below pi.
        let total: u32 = spokes.iter().map(|p| p.0).sum();
        let span = if closed { std::f64::consts::TAU } else { std::f64::consts::PI };
        let mut acc = 0u32;
        let mut pts = vec![];
        for &(gap, r) in &spokes {
            acc += gap;
            let a = span * acc as f64 / total as f64;
            let r = if far { r * 20.0 } else { r } * sc as f64;
            let p = |v: f64| v.clamp(-lim, lim).round() as i64;
            pts.push((p(c.0 as f64 + r * a.cos()), p(c.1 as f64 + r * a.sin())));
        }
        let gaps_ok = spokes.iter().all(|p| (p.0 as f64 / total as f64) * span < 3.1);
        prop_assume!(gaps_ok);
        let n = pts.len();
        let tris: Vec<[(i64, i64); 3]> = (0..if closed { n } else { n - 1 })
            .map(|i| [c, pts[i], pts[(i + 1) % n]])
            .collect();
        // Snapping to the grid must keep the spokes in order (a fan, not
        // folded triangles, whose exact covers would overlap).
        let turns = |t: &[(i64, i64); 3]| {
            (t[1].0 - c.0) as i128 * (t[2].1 - c.1) as i128
                - (t[1].1 - c.1) as i128 * (t[2].0 - c.0) as i128
                > 0
        };
        prop_assume!(tris.iter().all(turns));
        check_tiling(&tris, s, 48, 40)?;
    }

    /// Random jittered grids (corners moved by up to 1/7 of a cell, which
    /// keeps every quad convex; each split along a random diagonal):
    /// every pixel at most once, and exactly once where a triangle covers
    /// it exactly.
    #[test]
    fn grids_are_watertight(
        s in bits(),
        cell in 2i64..40,
        origin in (-30i64..10, -30i64..10),
        jitter in prop::collection::vec((-100i64..100, -100i64..100), 64),
        diag in prop::collection::vec(any::<bool>(), 49),
    ) {
        let sc = s.scale() as i64;
        let n = 8;
        let p = |i: usize, j: usize| {
            let (jx, jy) = jitter[j * n + i];
            let q = |base: i64, k: usize, jt: i64| {
                (base + k as i64 * cell) * sc + jt * cell * sc / 700
            };
            (q(origin.0, i, jx), q(origin.1, j, jy))
        };
        let mut tris = vec![];
        for j in 0..n - 1 {
            for i in 0..n - 1 {
                let (a, b, c, d) = (p(i, j), p(i + 1, j), p(i + 1, j + 1), p(i, j + 1));
                if diag[j * (n - 1) + i] {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        check_tiling(&tris, s, 48, 40)?;
    }

    /// Fixed-point Gouraud against the f64 twin on random in-range
    /// triangles: at every pixel within `(n + 2)·(½ + |g|·2^-30)` raw units
    /// (the `raster` module's bound) and within 1 level once shaded.
    #[test]
    fn fixed_gouraud_is_within_the_stated_bound(
        s in bits(),
        xy in prop::array::uniform6(-2000i64..3000),
        big in any::<bool>(),
        levels in prop::array::uniform3(0i32..=(255 << 16)),
    ) {
        let sc = s.scale() as i64;
        let lim = s.coord_limit() as i64;
        let c = |v: i64| if big { (v * 3 * sc).clamp(-lim, lim) } else { v * sc / 16 };
        let tri = [(c(xy[0]), c(xy[1])), (c(xy[2]), c(xy[3])), (c(xy[4]), c(xy[5]))];
        let window = Window { width: 48, y0: 0, y1: 40 };
        let fixed: [Vertex<i32, 1>; 3] = core::array::from_fn(|i| Vertex {
            x: tri[i].0 as i32, y: tri[i].1 as i32, z: 0, attrs: [levels[i]],
        });
        let float: [Vertex<f64, 1>; 3] = core::array::from_fn(|i| Vertex {
            x: tri[i].0 as i32, y: tri[i].1 as i32, z: 0.0, attrs: [levels[i] as f64],
        });
        let mut p = Probe(vec![]);
        let mut q = Probe(vec![]);
        draw_triangle(&fixed, s, window, &mut p).unwrap();
        draw_triangle(&float, s, window, &mut q).unwrap();
        prop_assert_eq!(p.0.len(), q.0.len());
        let g = gradient(&tri, &levels, s);
        for (&(x, y, v), &(_, _, e)) in p.0.iter().zip(q.0.iter()) {
            let n = tri
                .iter()
                .map(|&(vx, vy)| (x as i64 - vx.div_euclid(sc)).abs() + (y as i64 - vy.div_euclid(sc)).abs())
                .max()
                .unwrap() as f64;
            let bound = (n + 2.0) * (0.5 + g / (1u64 << 30) as f64);
            prop_assert!((v as f64 - e).abs() <= bound, "({}, {}): {} vs {}, bound {}", x, y, v, e, bound);
            let (lv, le) = (v.round_int(16).clamp(0, 255), (e / 65536.0).round_int(0).clamp(0, 255));
            prop_assert!((lv - le).abs() <= 1, "({}, {}): level {} vs {}", x, y, lv, le);
        }
        // And through the span stage into pixels: the same within 1 level.
        // The float twin's Gouraud shader takes levels, not raw units.
        let levels_f = float.map(|v| Vertex { attrs: [v.attrs[0] / 65536.0], ..v });
        let (a, b) = (shade(&fixed, s), shade(&levels_f, s));
        for (pa, pb) in a.iter().zip(&b) {
            prop_assert!(pa.abs_diff(*pb) <= 1);
        }
    }
}

/// Draws `tris` into one counter: each pixel's count must equal the number
/// of exact covers, which is at most 1.
fn check_tiling(
    tris: &[[(i64, i64); 3]],
    s: SubpixelBits,
    w: u32,
    h: u32,
) -> Result<(), TestCaseError> {
    let mut t = Counter::new(w, h);
    for tri in tris {
        flat(&mut t, tri, s).unwrap();
    }
    // The exact covers, each triangle over its bounding box only.
    let sc = s.scale() as i64;
    let mut want = vec![0u32; (w * h) as usize];
    for tri in tris {
        let lo = |k: fn(&(i64, i64)) -> i64| tri.iter().map(k).min().unwrap().div_euclid(sc).max(0);
        let hi = |k: fn(&(i64, i64)) -> i64, n: u32| {
            (tri.iter().map(k).max().unwrap().div_euclid(sc) + 1).min(n as i64 - 1)
        };
        for y in lo(|p| p.1)..=hi(|p| p.1, h) {
            for x in lo(|p| p.0)..=hi(|p| p.0, w) {
                want[(y * w as i64 + x) as usize] += covers(tri, x, y, sc) as u32;
            }
        }
    }
    let mut inside = 0;
    for y in 0..h {
        for x in 0..w {
            let want = want[(y * w + x) as usize];
            prop_assert!(want <= 1, "the exact covers overlap at ({}, {})", x, y);
            prop_assert_eq!(t.get(x, y), want, "({}, {})", x, y);
            inside += want;
        }
    }
    prop_assert!(t.total() == inside as u64);
    Ok(())
}

struct Probe<L>(Vec<(u32, u32, L)>);

impl<L: Lerp> Spans<L, 1> for Probe<L> {
    fn span(&mut self, s: &Span<L, 1>) {
        let mut v = s.a[0];
        for x in s.x0..s.x1 {
            self.0.push((x, s.y, v));
            v = v.add(s.da[0]);
        }
    }
}

/// The larger exact gradient per pixel of the plane through `vals`.
fn gradient(tri: &[(i64, i64); 3], vals: &[i32; 3], s: SubpixelBits) -> f64 {
    let f = |v: i64| v as f64;
    let (dx1, dy1) = (f(tri[1].0 - tri[0].0), f(tri[1].1 - tri[0].1));
    let (dx2, dy2) = (f(tri[2].0 - tri[0].0), f(tri[2].1 - tri[0].1));
    let d1 = vals[1] as f64 - vals[0] as f64;
    let d2 = vals[2] as f64 - vals[0] as f64;
    let a = dx1 * dy2 - dx2 * dy1;
    if a == 0.0 {
        return 0.0;
    }
    let sc = s.scale() as f64;
    ((d1 * dy2 - d2 * dy1) * sc / a)
        .abs()
        .max(((d2 * dx1 - d1 * dx2) * sc / a).abs())
}

fn shade<L: Lerp>(tri: &[Vertex<L, 1>; 3], s: SubpixelBits) -> Vec<u8> {
    let mut px = vec![[0u8; 1]; 48 * 40];
    let mut fb = FrameBuf::<Gray8>::new(&mut px, 48, 40).unwrap();
    let mut f = Fill::<_, Depth16, _>::new(&mut fb, None, GouraudMono).unwrap();
    f.draw(tri, s).unwrap();
    px.iter().map(|p| p[0]).collect()
}
