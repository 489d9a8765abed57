//! Flat, Gouraud and Phong shading compared on scenes made to show their
//! differences (seeds 000, 003 and 004): a highlight smaller than a
//! polygon, a point light close to the centre of a large face, Gouraud's
//! dependence on the quad's orientation, and the smoothing groups of the
//! can.
//!
//! The scenes look at the square `[-1, 1]²` (z = 0, facing +z) from
//! (0, 0, 3) with a 45° field of view on a 120 × 120 screen: the square
//! spans the pixel centres 12..=107 on both axes, centred on 60.

mod common;

use common::{render, square_scene, Desc, Image, Lamp, Mat, Obj, WHITE};
use fixshade::illum::{Specular, Viewer};
use fixshade::mesh::CAN;
use fixshade::num::{Precise, F64};
use fixshade::scene::Shading;

const W: u32 = 120;
const UP: [i16; 3] = [0, 0, 16384];
const DOWN: [i16; 3] = [0, 0, -16384];

/// Projection scale in pixels: `H/2 · cot(22.5°)`.
fn k() -> f64 {
    60.0 / (22.5f64).to_radians().tan()
}

/// Screen position (pixels, continuous) of world point `(x, y, 0)` seen
/// from (0, 0, 3).
fn screen(x: f64, y: f64) -> (f64, f64) {
    (60.0 + k() * x / 3.0, 60.0 - k() * y / 3.0)
}

/// The four corner pixels of the square, one pixel inside.
const CORNERS: [(u32, u32); 4] = [(12, 107), (107, 107), (107, 12), (12, 12)];

fn max_level(img: &Image) -> (u32, u32, u8) {
    let (x, y, c) = img.brightest();
    (x, y, c.r)
}

/// A highlight smaller than a polygon (seeds 000 and 003): the square's
/// four normals all face the eye; a point light at (0.8, -0.6, 3) puts the
/// mirror point of the eye, hence the specular peak (n = 200), at world
/// (0.4, -0.3), inside the lower right triangle, 0.49 from the diagonal
/// and at least 0.67 from every vertex. Every vertex sees R·V <= 0.9, so
/// its specular term is below 0.9^200 = 7e-10: Gouraud, which lights
/// vertices only, misses the highlight altogether and peaks at the corner
/// nearest the light (diffuse: 0.1 + 0.5 · 0.989 = 0.595, level 152);
/// Phong finds it: 0.1 + 0.5 · 0.990 + 0.35 = 0.945, level 241.
#[test]
fn highlight_inside_a_triangle() {
    let mat = Mat {
        color: WHITE,
        ka: 1.0,
        kd: 0.5,
        ks: 0.35,
        n: 200.0,
    };
    let lamps = vec![Lamp::Point([0.8, -0.6, 3.0], 1.0, WHITE)];
    let g = render::<Precise>(
        &square_scene([UP; 4], mat, lamps.clone(), Shading::Gouraud, 0.1),
        W,
        W,
    );
    let p = render::<Precise>(
        &square_scene([UP; 4], mat, lamps, Shading::Phong, 0.1),
        W,
        W,
    );
    let (px, py, phong_peak) = max_level(&p);
    let (gx, gy, gouraud_max) = max_level(&g);
    println!("Phong peak {phong_peak} at ({px}, {py}); Gouraud max {gouraud_max} at ({gx}, {gy})");
    // Phong's peak at the mirror point, (79.3, 74.5) on screen (pixel
    // (79, 74) has its centre at (79.5, 74.5)).
    let (sx, sy) = screen(0.4, -0.3);
    assert!((px as f64 + 0.5 - sx).abs() <= 1.0, "{px} vs {sx}");
    assert!((py as f64 + 0.5 - sy).abs() <= 1.0, "{py} vs {sy}");
    assert!((240..=242).contains(&phong_peak), "{phong_peak}");
    // Gouraud's brightest pixel is the corner pixel nearest the corner
    // (1, -1), lit at 152: the plane's maximum over a triangle is at a
    // vertex.
    assert!((151..=152).contains(&gouraud_max), "{gouraud_max}");
    assert_eq!(g.lvl(107, 107), gouraud_max);
    let corner = screen(1.0, -1.0);
    let mut at_max = 0;
    for y in 0..W {
        for x in 0..W {
            if g.is_covered(x, y) && g.lvl(x, y) == gouraud_max {
                at_max += 1;
                let d = (x as f64 + 0.5 - corner.0).hypot(y as f64 + 0.5 - corner.1);
                assert!(
                    d < 10.0,
                    "Gouraud max at ({x}, {y}), {d} px from the corner"
                );
            }
        }
    }
    println!("Gouraud: {at_max} pixels at its max, first at ({gx}, {gy})");
    // Phong's peak is well above anything Gouraud draws, and at the same
    // pixel Gouraud shows the diffuse term only.
    assert!(phong_peak >= gouraud_max + 85);
    let g_at_peak = g.lvl(px, py);
    assert!((140..=150).contains(&g_at_peak), "{g_at_peak}");
    // The highlight is smaller than the triangle: the pixels more than 20
    // levels above Gouraud's maximum lie within 12 pixels of the peak, all
    // inside the lower right triangle (world y < x; the world diagonal
    // y = x is the screen line x + y = 119, pixel centres included).
    let mut bright = 0;
    for y in 0..W {
        for x in 0..W {
            if p.is_covered(x, y) && p.lvl(x, y) > gouraud_max + 20 {
                bright += 1;
                let d2 = (x as f64 - px as f64).powi(2) + (y as f64 - py as f64).powi(2);
                assert!(d2 <= 144.0, "bright pixel ({x}, {y}) far from the peak");
                // World diagonal y = x is the screen line x + y = 119.
                assert!(x + y > 119, "bright pixel ({x}, {y}) in the other triangle");
            }
        }
    }
    assert!(bright > 20 && bright < 450, "{bright} bright pixels");
    // The vertices: Phong and Gouraud agree there (within a level).
    for (x, y) in CORNERS {
        assert!(p.lvl(x, y).abs_diff(g.lvl(x, y)) <= 1, "({x}, {y})");
    }
}

/// A point light close to the centre of a large face (seed 004, figures
/// 13-7 and 13-10): light at (0, 0, 0.25), diffuse only (kd 0.8, ambient
/// 0.1, ks 0). At the corners N·L = 0.25/1.436 = 0.174: level 61. At the
/// centre N·L = 1: level 230. Gouraud interpolates the corners, so its
/// centre is as dim as they are; Phong lights the centre itself.
#[test]
fn point_light_near_the_centre_of_a_face() {
    let mat = Mat {
        color: WHITE,
        ka: 1.0,
        kd: 0.8,
        ks: 0.0,
        n: 1.0,
    };
    let lamps = vec![Lamp::Point([0.0, 0.0, 0.25], 1.0, WHITE)];
    let g = render::<Precise>(
        &square_scene([UP; 4], mat, lamps.clone(), Shading::Gouraud, 0.1),
        W,
        W,
    );
    let p = render::<Precise>(
        &square_scene([UP; 4], mat, lamps, Shading::Phong, 0.1),
        W,
        W,
    );
    let gc: Vec<u8> = CORNERS.iter().map(|&(x, y)| g.lvl(x, y)).collect();
    let pc: Vec<u8> = CORNERS.iter().map(|&(x, y)| p.lvl(x, y)).collect();
    let (g_mid, p_mid) = (g.lvl(60, 60), p.lvl(60, 60));
    println!("corners Gouraud {gc:?} Phong {pc:?}; centre Gouraud {g_mid}, Phong {p_mid}");
    // Corner pixels (one pixel in) are lit at about 61-63.
    for &c in gc.iter().chain(&pc) {
        assert!((60..=64).contains(&c), "{gc:?} {pc:?}");
    }
    // Gouraud's centre is no brighter than the corners it interpolates.
    assert!(g_mid <= *gc.iter().max().unwrap() + 1, "{g_mid}");
    assert!((60..=63).contains(&g_mid), "{g_mid}");
    // Phong's centre: 0.1 + 0.8 · N·L with N·L = 0.9983 at pixel (60, 60)
    // (its centre is 0.0104 off the light's foot): 0.8986, level 229.
    assert!((228..=230).contains(&p_mid), "{p_mid}");
    assert!(p_mid >= *pc.iter().max().unwrap() + 160);
    assert!(p_mid >= g_mid + 160);
    // Gouraud is flat over the whole square (equal corners), Phong a
    // bright disc fading outwards.
    assert!(g.lvl(30, 60).abs_diff(g_mid) <= 1);
    assert!(p.lvl(30, 60) < p_mid - 60 && p.lvl(30, 60) > pc[0] + 20);
}

/// White at corners `white` (indices into (-1,-1), (1,-1), (1,1), (-1,1)),
/// black elsewhere: white corners have their normal towards the light
/// (+z), black ones away from it, and there is no ambient light.
fn two_tone(white: [usize; 2], shading: Shading) -> Image {
    let mut n = [DOWN; 4];
    for w in white {
        n[w] = UP;
    }
    let mat = Mat {
        color: WHITE,
        ka: 0.0,
        kd: 1.0,
        ks: 0.0,
        n: 1.0,
    };
    let lamps = vec![Lamp::Dir([0.0, 0.0, 1.0], 1.0, WHITE)];
    render::<F64>(&square_scene(n, mat, lamps, shading, 0.0), W, W)
}

/// The pixel that pixel `(x, y)` goes to when the square turns by 90°
/// counter-clockwise (world y up) about its centre: corner k goes to
/// corner k + 1. Pixel centres map to pixel centres.
fn turned(x: u32, y: u32) -> (u32, u32) {
    let (dx, dy) = (x as f64 + 0.5 - 60.0, 60.0 - (y as f64 + 0.5));
    let (rx, ry) = (-dy, dx);
    ((60.0 + rx - 0.5) as u32, (60.0 - ry - 0.5) as u32)
}

/// Gouraud shading is not invariant under rotation (seed 000 §7): the
/// square is two triangles split along the diagonal (-1,-1)-(1,1). With
/// white corners on that diagonal each triangle interpolates white, black,
/// white, and the image is `1 - |u - v|`: a white ridge along the
/// diagonal, white at the centre. Turn the square by 90° (the same colours
/// on the turned corners, the triangulation unchanged): the white corners
/// are now the other two, each triangle interpolates black, white, black,
/// and the image is `|u - v|`: a black valley, black at the centre. A
/// rotation-invariant interpolation (bilinear, say) gives 0.5 at the centre
/// in both. The `Shading::Gouraud` docs state this artifact.
#[test]
fn gouraud_depends_on_the_quad_orientation() {
    let a = two_tone([0, 2], Shading::Gouraud);
    let b = two_tone([1, 3], Shading::Gouraud);
    // Pixels whose centres lie on the triangulation diagonal (world y = x,
    // the screen line x + y = 119).
    for x in [30u32, 45, 59, 60, 74, 89] {
        let y = 119 - x;
        let (tx, ty) = turned(x, y);
        let (va, vb) = (a.lvl(x, y), b.lvl(tx, ty));
        println!("({x}, {y}): {va}; turned ({tx}, {ty}): {vb}");
        // On the diagonal: white before turning; after turning, the same
        // point of the square (now at (tx, ty)) should be white too.
        assert!(va >= 253, "({x}, {y}): {va}");
        // It is not: on the turned square (tx, ty) lies on the other
        // diagonal, across the black valley: `|u - v|` there is the
        // distance from the valley's bottom.
        assert!(vb < 255 - 60, "turned ({tx}, {ty}): {vb}");
    }
    // At the centre the two differ by the full range.
    assert!(a.lvl(59, 60) >= 250 && b.lvl(59, 60) <= 5);
    // Pixel for pixel, most interior pixels differ.
    let mut differ = 0;
    for y in 14..106 {
        for x in 14..106 {
            let (tx, ty) = turned(x, y);
            if a.lvl(x, y).abs_diff(b.lvl(tx, ty)) > 2 {
                differ += 1;
            }
        }
    }
    println!("{differ} of {} interior pixels differ", 92 * 92);
    assert!(differ > 92 * 92 / 2);
}

/// The control: two *adjacent* white corners give a plane over the whole
/// square (each triangle's plane is the same `1 - v`), and so does the
/// turned assignment: the turned image is the image turned, to within the
/// rounding of the interpolation. So the test above measures the
/// orientation artifact, not the turning of pixels.
#[test]
fn adjacent_white_corners_turn_cleanly() {
    let a = two_tone([0, 1], Shading::Gouraud);
    let b = two_tone([1, 2], Shading::Gouraud);
    let mut worst = 0;
    for y in 14..106 {
        for x in 14..106 {
            let (tx, ty) = turned(x, y);
            worst = worst.max(a.lvl(x, y).abs_diff(b.lvl(tx, ty)));
        }
    }
    println!("adjacent corners: largest difference {worst}");
    assert!(worst <= 1, "{worst}");
    // And the gradient is real: 0 at one edge, 255 at the other.
    assert!(a.lvl(60, 14) <= 20 && a.lvl(60, 105) >= 235);
}

/// The can (`CAN`: smooth sides, flat caps by smoothing groups), Gouraud,
/// seen from above the side: across the middle row, the six side faces'
/// shared edges show no step (every pixel-to-pixel change is within the
/// interpolation's own gradient), while the flat-shaded can steps at each
/// edge; the top cap is one uniform level, and meets the sides with a
/// crease.
#[test]
fn can_sides_smooth_caps_flat() {
    let desc = |shading| Desc {
        eye: [0.0, 1.8, 3.0],
        target: [0.0; 3],
        fov_deg: 45.0,
        objects: vec![Obj {
            mesh: CAN,
            scale: 1.0,
            angles: [0.0, 0.3, 0.0],
            offset: [0.0; 3],
            mat: Mat {
                color: WHITE,
                ka: 1.0,
                kd: 0.9,
                ks: 0.0,
                n: 1.0,
            },
            shading,
            cull: true,
        }],
        lamps: vec![Lamp::Dir([1.0, 0.6, 0.8], 1.0, WHITE)],
        ambient: 0.1,
        specular: Specular::Phong,
        viewer: Viewer::Infinite,
    };
    let g = render::<Precise>(&desc(Shading::Gouraud), W, W);
    let f = render::<Precise>(&desc(Shading::Flat), W, W);
    // The middle row of the sides: world y = 0 projects near row 60 + a
    // bit; take the row through the object's centre on screen.
    let row = 66;
    let xs: Vec<u32> = (0..W).filter(|&x| g.is_covered(x, row)).collect();
    assert!(xs.len() > 40, "{} pixels", xs.len());
    // Leave out two pixels at each silhouette: a side face seen nearly
    // edge-on spans its whole range of levels within a pixel or two.
    let xs = &xs[2..xs.len() - 2];
    let steps = |img: &Image| {
        xs.windows(2)
            .map(|w| img.lvl(w[0], row).abs_diff(img.lvl(w[1], row)))
            .max()
            .unwrap()
    };
    let (sg, sf) = (steps(&g), steps(&f));
    let g_row: Vec<u8> = xs.iter().map(|&x| g.lvl(x, row)).collect();
    let f_row: Vec<u8> = xs.iter().map(|&x| f.lvl(x, row)).collect();
    println!("row {row}: Gouraud {g_row:?}\nflat {f_row:?}\nlargest step: Gouraud {sg}, flat {sf}");
    // Gouraud: the level climbs by at most 6 per pixel (its gradient), and
    // the gradient itself changes by at most 2 from pixel to pixel, also
    // where the row crosses a shared edge (the slope of a piecewise plane
    // changes there, its value does not).
    assert!(sg <= 6, "Gouraud step {sg}");
    let d: Vec<i32> = xs
        .windows(2)
        .map(|w| g.lvl(w[1], row) as i32 - g.lvl(w[0], row) as i32)
        .collect();
    let kink = d.windows(2).map(|w| (w[1] - w[0]).abs()).max().unwrap();
    assert!(kink <= 2, "Gouraud slope change {kink}");
    // Flat: one level per face, a step of 171 at the edge.
    assert!(sf >= 100, "flat step {sf}");
    // The top cap: the pixels that flat shading paints with the cap's
    // colour (normal +y: N·L = 0.6/|(1, 0.6, 0.8)| = 0.4240, level
    // (0.1 + 0.9 · 0.424) · 255 = 122.8, 123) are the same level in
    // Gouraud: all cap vertices share the +y normal.
    let cap = f.lvl(60, 28);
    assert!((122..=124).contains(&cap), "{cap}");
    let mut n = 0;
    for y in 0..W {
        for x in 0..W {
            if f.is_covered(x, y) && f.lvl(x, y) == cap && y < 60 {
                n += 1;
                assert_eq!(g.lvl(x, y), cap, "({x}, {y})");
            }
        }
    }
    assert!(n > 600, "{n} cap pixels");
    // The crease at the rim: down column 60 the side changes by at most a
    // level per row (its normals are radial, the same at the top and the
    // bottom of a side edge; the column drifts across the face in
    // perspective), but the last cap pixel and the first side pixel differ
    // by 24 levels (123 and 147).
    let last_cap = (20..60).filter(|&y| f.lvl(60, y) == cap).max().unwrap();
    let (top, side) = (g.lvl(60, last_cap), g.lvl(60, last_cap + 1));
    println!("rim at row {last_cap}: cap {top}, side {side}");
    assert!(top.abs_diff(side) >= 20, "{top} {side}");
    for y in last_cap + 1..last_cap + 40 {
        assert!(
            g.lvl(60, y).abs_diff(g.lvl(60, y + 1)) <= 1,
            "side at (60, {y})"
        );
    }
}

/// Phong shading per pixel is the illumination model at the normalised
/// interpolated normal (and the interpolated eye position): on the square
/// with four different corner normals, a point light and the local
/// viewer, pixels on a grid match the f64 formula evaluated at the pixel
/// centre's point of the square with the barycentric blend of its
/// triangle's corner normals, normalised. (The square faces the eye, so
/// screen-affine and world-affine interpolation agree.)
#[test]
fn phong_pixels_follow_the_normalised_interpolated_normal() {
    let raw: [[f64; 3]; 4] = [
        [-0.5, -0.5, 0.707],
        [0.6, -0.3, 0.742],
        [0.4, 0.5, 0.768],
        [-0.6, 0.4, 0.693],
    ];
    let q = raw.map(|n| {
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        n.map(|c| common::q14(c / l))
    });
    let mat = Mat {
        color: [0.9, 0.8, 0.6],
        ka: 1.0,
        kd: 0.7,
        ks: 0.4,
        n: 10.0,
    };
    let lamp = Lamp::Point([1.0, 1.0, 2.0], 1.0, WHITE);
    let d = square_scene(q, mat, vec![lamp], Shading::Phong, 0.1);
    let imgs = [
        ("fast", render::<fixshade::num::Fast>(&d, W, W)),
        ("precise", render::<Precise>(&d, W, W)),
        ("f64", render::<F64>(&d, W, W)),
    ];
    let nq = q.map(|n| n.map(|c| c as f64 / 16384.0));
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut worst = [0f64; 3];
    let mut checked = 0;
    for j in (14..106).step_by(6) {
        for i in (14..106).step_by(6) {
            let x = (i as f64 + 0.5 - 60.0) * 3.0 / k();
            let y = (60.0 - (j as f64 + 0.5)) * 3.0 / k();
            if (x - y).abs() < 0.05 {
                continue;
            }
            // Triangle (0, 1, 2) below the diagonal y = x, (0, 2, 3) above.
            let t = if y < x { [0, 1, 2] } else { [0, 2, 3] };
            let area = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
                (b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)
            };
            let [a, b, c] = t.map(|v| corners[v]);
            let s = area(a, b, c);
            let w = [
                area((x, y), b, c) / s,
                area(a, (x, y), c) / s,
                area(a, b, (x, y)) / s,
            ];
            let n = [0, 1, 2].map(|k| (0..3).map(|v| w[v] * nq[t[v]][k]).sum::<f64>());
            let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let n = n.map(|c| c / l);
            // Eye space: the eye at (0, 0, 3) looking down -z.
            let want = common::phong_f64(
                &mat,
                0.1,
                &[Lamp::Point([1.0, 1.0, -1.0], 1.0, WHITE)],
                Specular::Phong,
                Viewer::Local,
                n,
                [x, y, -3.0],
            )
            .map(|v| v * 255.0);
            for (m, (_, img)) in imgs.iter().enumerate() {
                let got = img.at(i, j);
                for (g, w) in [got.r, got.g, got.b].into_iter().zip(want) {
                    let e = (g as f64 - w).abs();
                    worst[m] = worst[m].max(e);
                    // 1/2 level of output rounding, plus (measured) at most
                    // 0.34 for Fast's quantisation and the 1/16-pixel
                    // snapping of the corners (0.16 before the integer
                    // projection of `geom::q16`, which snaps a corner of
                    // this square differently; precise and f64: 0.06).
                    let bound = if m == 0 { 0.85 } else { 0.75 };
                    assert!(e <= bound, "{} ({i}, {j}): {got:?} vs {want:?}", imgs[m].0);
                }
            }
            checked += 1;
        }
    }
    println!("{checked} pixels; largest error (levels) fast/precise/f64: {worst:.3?}");
    assert!(checked > 200);
}
