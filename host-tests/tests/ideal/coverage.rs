//! Screen-space coverage: the top-left rule, shared edges, degenerate input.

use std::collections::BTreeMap;

use fixshade_host::ideal::{raster_screen, IdealError};

/// Covered pixels of a screen triangle, grouped by row.
fn rows(v: [[f64; 2]; 3], w: u32, h: u32) -> BTreeMap<u32, Vec<u32>> {
    let mut rows: BTreeMap<u32, Vec<u32>> = BTreeMap::new();
    raster_screen(v, w, h, |x, y, _| rows.entry(y).or_default().push(x)).expect("finite input");
    rows
}

/// The hand-checked triangle (9.5, 15.5), (3.5, 3.5), (17.5, 7.5).
const HAND: [[f64; 2]; 3] = [[9.5, 15.5], [3.5, 3.5], [17.5, 7.5]];

#[test]
fn hand_triangle_rows_follow_the_top_left_rule() {
    let rows = rows(HAND, 24, 24);
    // y = 11.5: left edge at x = 7.5 (covered: left edge), right edge at
    // x = 13.5 (not covered: right edge).
    assert_eq!(rows[&11], (7..=12).collect::<Vec<_>>());
    // y = 7.5: left edge at x = 5.5 (covered); the vertex (17.5, 7.5) lies
    // on two right-hand edges (not covered).
    assert_eq!(rows[&7], (5..=16).collect::<Vec<_>>());
    // y = 3.5 only touches the vertex (3.5, 3.5), which also lies on the
    // upper right edge: not covered. y = 15.5 only touches the bottom vertex.
    assert!(!rows.contains_key(&3));
    assert!(!rows.contains_key(&15));
    assert_eq!(
        rows.keys().copied().collect::<Vec<_>>(),
        (4..=14).collect::<Vec<_>>()
    );
}

#[test]
fn vertex_order_does_not_change_coverage() {
    let forward = rows(HAND, 24, 24);
    let backward = rows([HAND[2], HAND[1], HAND[0]], 24, 24);
    let rotated = rows([HAND[1], HAND[2], HAND[0]], 24, 24);
    assert_eq!(forward, backward);
    assert_eq!(forward, rotated);
}

#[test]
fn barycentrics_reconstruct_the_pixel_centre() {
    let mut seen = 0;
    raster_screen(HAND, 24, 24, |x, y, b| {
        seen += 1;
        assert!((b.iter().sum::<f64>() - 1.0).abs() < 1e-12);
        let centre = [f64::from(x) + 0.5, f64::from(y) + 0.5];
        for (k, c) in centre.into_iter().enumerate() {
            let p: f64 = b.iter().zip(&HAND).map(|(bi, v)| bi * v[k]).sum();
            assert!((p - c).abs() < 1e-12, "{x},{y}: {b:?}");
        }
    })
    .expect("finite input");
    assert!(seen > 50);
}

#[test]
fn square_split_on_pixel_centres_covers_each_pixel_once() {
    // Corners and the diagonal lie exactly on pixel centres.
    let (a, b, c, d) = ([2.5, 2.5], [12.5, 2.5], [12.5, 12.5], [2.5, 12.5]);
    let mut count = vec![0u32; 16 * 16];
    for t in [[a, b, c], [a, c, d]] {
        raster_screen(t, 16, 16, |x, y, _| count[(y * 16 + x) as usize] += 1).expect("finite");
    }
    for y in 0..16u32 {
        for x in 0..16u32 {
            // Left and top sides included, right and bottom excluded.
            let want = u32::from((2..12).contains(&x) && (2..12).contains(&y));
            assert_eq!(count[(y * 16 + x) as usize], want, "pixel {x},{y}");
        }
    }
}

/// Pixels covered by the fan of `poly` around `centre`, with multiplicity.
fn fan_counts(centre: [f64; 2], poly: &[[f64; 2]], w: u32, h: u32) -> Vec<u32> {
    let mut count = vec![0u32; (w * h) as usize];
    for k in 0..poly.len() {
        let t = [centre, poly[k], poly[(k + 1) % poly.len()]];
        raster_screen(t, w, h, |x, y, _| count[(y * w + x) as usize] += 1).expect("finite");
    }
    count
}

#[test]
fn two_triangulations_with_edges_through_centres_agree() {
    // An octagon around a pixel centre; its fan edges run horizontally,
    // vertically and diagonally through many pixel centres.
    let c = [10.5, 10.5];
    let poly = [
        [18.5, 10.5],
        [15.5, 15.5],
        [10.5, 18.5],
        [5.5, 15.5],
        [2.5, 10.5],
        [5.5, 5.5],
        [10.5, 2.5],
        [15.5, 5.5],
    ];
    let around_centre = fan_counts(c, &poly, 21, 21);
    let mut from_corner = vec![0u32; 21 * 21];
    for k in 1..poly.len() - 1 {
        raster_screen([poly[0], poly[k], poly[k + 1]], 21, 21, |x, y, _| {
            from_corner[(y * 21 + x) as usize] += 1
        })
        .expect("finite");
    }
    assert!(around_centre.iter().all(|&n| n <= 1));
    assert!(from_corner.iter().all(|&n| n <= 1));
    assert_eq!(around_centre, from_corner);
    // The centre pixel is where all eight fan triangles meet.
    assert_eq!(around_centre[10 * 21 + 10], 1);
}

#[test]
fn fan_with_irregular_coordinates_has_no_gaps_or_overlaps() {
    let (cx, cy, r) = (12.37, 11.71, 9.3);
    let poly: Vec<[f64; 2]> = (0..7)
        .map(|k| {
            let a = 0.3 + f64::from(k) * std::f64::consts::TAU / 7.0;
            [cx + r * a.cos(), cy + r * a.sin()]
        })
        .collect();
    let counts = fan_counts([cx + 0.61, cy - 0.43], &poly, 25, 25);
    for y in 0..25u32 {
        for x in 0..25u32 {
            let p = [f64::from(x) + 0.5, f64::from(y) + 0.5];
            // Signed distance-like value to each polygon side (> 0 inside).
            let side = (0..7)
                .map(|k| {
                    let (a, b) = (poly[k], poly[(k + 1) % 7]);
                    let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
                    ((b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])) / len
                })
                .fold(f64::INFINITY, f64::min);
            let n = counts[(y * 25 + x) as usize];
            assert!(n <= 1, "pixel {x},{y} covered {n} times");
            if side > 1e-9 {
                assert_eq!(n, 1, "gap at {x},{y}");
            } else if side < -1e-9 {
                assert_eq!(n, 0, "outside pixel {x},{y} covered");
            }
        }
    }
}

#[test]
fn zero_area_and_off_screen_triangles_cover_nothing() {
    let line = [[1.5, 1.5], [5.5, 5.5], [9.5, 9.5]];
    assert_eq!(raster_screen(line, 16, 16, |_, _, _| {}), Ok(0));
    let point = [[4.5, 4.5]; 3];
    assert_eq!(raster_screen(point, 16, 16, |_, _, _| {}), Ok(0));
    let left_of_screen = [[-9.0, 0.0], [-1.0, 0.0], [-1.0, 8.0]];
    assert_eq!(raster_screen(left_of_screen, 16, 16, |_, _, _| {}), Ok(0));
    assert_eq!(raster_screen(HAND, 0, 0, |_, _, _| {}), Ok(0));
}

#[test]
fn triangle_larger_than_the_screen_covers_all_of_it() {
    let huge = [[-1e9, -1e9], [1e9, -1e9], [0.0, 1e9]];
    assert_eq!(raster_screen(huge, 7, 5, |_, _, _| {}), Ok(35));
}

#[test]
fn non_finite_vertices_are_an_error() {
    let bad = [[f64::NAN, 0.0], [1.0, 0.0], [0.0, 1.0]];
    assert!(matches!(
        raster_screen(bad, 4, 4, |_, _, _| {}),
        Err(IdealError::NonFinite(_))
    ));
    let inf = [[f64::INFINITY, 0.0], [1.0, 0.0], [0.0, 1.0]];
    assert!(raster_screen(inf, 4, 4, |_, _, _| {}).is_err());
}
