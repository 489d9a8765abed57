//! Camera, culling, clipping and depth through the full renderer.

use fixshade_host::ideal::{render, Shading};

use super::{camera, covered, matte, object, scene, square, tri};

/// Pixels `(x, y)` with `x0 <= x <= x1` and `y0 <= y <= y1`, row-major.
fn block(x0: u32, y0: u32, x1: u32, y1: u32) -> Vec<(u32, u32)> {
    (y0..=y1)
        .flat_map(|y| (x0..=x1).map(move |x| (x, y)))
        .collect()
}

#[test]
fn centred_square_covers_exactly_its_pixels() {
    // 90 degrees at distance 1 shows [-1, 1]^2; the square [-0.5, 0.5]^2
    // maps to screen [5, 15]^2 on a 20 x 20 frame: centres 5.5 ..= 14.5.
    let mut s = scene(20, 20, camera([0.0, 0.0, 1.0], [0.0; 3], 90.0, 0.1));
    s.objects.push(object(
        square(-0.5, -0.5, 0.5, 0.5, 0.0),
        Shading::Flat,
        matte(),
        true,
    ));
    let frame = render(&s).expect("valid scene");
    assert_eq!(frame.covered_count(), 100);
    assert_eq!(covered(&frame), block(5, 5, 14, 14));
    assert!(frame
        .object
        .iter()
        .zip(&frame.covered)
        .all(|(o, &c)| (*o == Some(0)) == c));
}

#[test]
fn off_centre_square_lands_where_the_projection_says() {
    // On a 40 x 20 frame (aspect 2) the view at distance 1 spans x in
    // [-2, 2], y in [-1, 1]: [0.5, 1.5] x [-0.5, 0.5] maps to x in [25, 35],
    // y in [5, 15].
    let mut s = scene(40, 20, camera([0.0, 0.0, 1.0], [0.0; 3], 90.0, 0.1));
    s.objects.push(object(
        square(0.5, -0.5, 1.5, 0.5, 0.0),
        Shading::Flat,
        matte(),
        true,
    ));
    let frame = render(&s).expect("valid scene");
    assert_eq!(covered(&frame), block(25, 5, 34, 14));
}

#[test]
fn shared_edge_between_objects_covers_every_pixel_once() {
    let cam = camera([0.3, -0.2, 2.0], [0.1, 0.05, 0.0], 50.0, 0.1);
    let n = [0.0, 0.0, 1.0];
    let (a, b, c, d) = (
        [-0.9, -0.7, 0.1],
        [0.8, -0.6, -0.2],
        [0.7, 0.9, 0.3],
        [-0.6, 0.8, 0.0],
    );
    let first = vec![tri([a, b, c], n)];
    let second = vec![tri([a, c, d], n)];
    let render_with = |tris: Vec<Vec<_>>| {
        let mut s = scene(37, 29, cam.clone());
        for t in tris {
            s.objects.push(object(t, Shading::Flat, matte(), true));
        }
        render(&s).expect("valid scene")
    };
    let only_first = render_with(vec![first.clone()]);
    let only_second = render_with(vec![second.clone()]);
    let both = render_with(vec![first, second]);
    for i in 0..both.covered.len() {
        assert!(
            !(only_first.covered[i] && only_second.covered[i]),
            "pixel {i} covered twice"
        );
        assert_eq!(
            both.covered[i],
            only_first.covered[i] || only_second.covered[i]
        );
    }
    assert!(only_first.covered_count() > 100 && only_second.covered_count() > 100);
}

#[test]
fn clockwise_triangle_is_culled_and_both_sides_match_without_culling() {
    let cam = camera([0.0, 0.0, 3.0], [0.0; 3], 60.0, 0.1);
    // Counter-clockwise seen from +z (the eye): front face, normal +z.
    let front = tri(
        [[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]],
        [0.0, 0.0, 1.0],
    );
    // Same corners clockwise seen from the eye: back face, normal -z.
    let back = tri(
        [[-1.0, -1.0, 0.0], [0.0, 1.0, 0.0], [1.0, -1.0, 0.0]],
        [0.0, 0.0, -1.0],
    );
    let render_one = |t, shading, cull| {
        let mut s = scene(24, 24, cam.clone());
        s.lights
            .push(super::light(fixshade_host::ideal::LightKind::Directional {
                direction: [0.3, 0.2, 1.0],
            }));
        s.objects.push(object(vec![t], shading, matte(), cull));
        render(&s).expect("valid scene")
    };
    assert!(render_one(front, Shading::Flat, true).covered_count() > 50);
    assert_eq!(render_one(back, Shading::Flat, true).covered_count(), 0);
    for shading in [Shading::Flat, Shading::Gouraud, Shading::Phong] {
        let f = render_one(front, shading, false);
        let b = render_one(back, shading, false);
        assert_eq!(f.covered, b.covered);
        assert_eq!(f.to_rgb8(), b.to_rgb8(), "{shading:?}");
        // Lit, not ambient-only: the flipped normal faces the light.
        assert!(f
            .color
            .iter()
            .zip(&f.covered)
            .all(|(c, &cov)| !cov || c[0] > 0.5));
    }
}

#[test]
fn near_clipping_keeps_exactly_the_part_beyond_the_near_plane() {
    // Eye at the origin looking down -z. Corner c is behind the eye; the
    // edges to it cross z = -1 at (-0.5, 0.5, -1) and (0.5, 0.5, -1).
    let cam = camera([0.0; 3], [0.0, 0.0, -1.0], 90.0, 1.0);
    let n = [0.0, 0.0, 1.0];
    let (a, b, c) = ([-1.0, -0.5, -3.0], [1.0, -0.5, -3.0], [0.0, 1.5, 1.0]);
    let (p, q) = ([0.5, 0.5, -1.0], [-0.5, 0.5, -1.0]);
    let render_tris = |tris| {
        let mut s = scene(20, 20, cam.clone());
        s.objects.push(object(tris, Shading::Flat, matte(), true));
        render(&s).expect("valid scene")
    };
    let crossing = render_tris(vec![tri([a, b, c], n)]);
    let by_hand = render_tris(vec![tri([a, b, p], n), tri([a, p, q], n)]);
    assert_eq!(crossing.covered, by_hand.covered);
    assert!(crossing.covered_count() > 40);
    for (d, e) in crossing.depth.iter().zip(&by_hand.depth) {
        assert!(d == e || (d - e).abs() < 1e-12, "{d} vs {e}");
    }
    // Screen rows: the near edge projects to y = 5, the far edge to 11.67.
    let rows: Vec<u32> = covered(&crossing).iter().map(|p| p.1).collect();
    assert_eq!((rows[0], rows[rows.len() - 1]), (5, 11));
    // A triangle entirely between the eye and the near plane is invisible.
    let too_close = render_tris(vec![tri(
        [[-0.1, -0.1, -0.5], [0.1, -0.1, -0.5], [0.0, 0.1, -0.5]],
        n,
    )]);
    assert_eq!(too_close.covered_count(), 0);
}

#[test]
fn far_clipping_keeps_the_near_part() {
    let mut cam = camera([0.0; 3], [0.0, 0.0, -1.0], 90.0, 1.0);
    cam.far = Some(4.0);
    let n = [0.0, 1.0, 0.0];
    // A floor strip at y = -1 from z = -2 to z = -8, cut at z = -4.
    let strip = vec![
        tri(
            [[-1.0, -1.0, -2.0], [1.0, -1.0, -2.0], [1.0, -1.0, -8.0]],
            n,
        ),
        tri(
            [[-1.0, -1.0, -2.0], [1.0, -1.0, -8.0], [-1.0, -1.0, -8.0]],
            n,
        ),
    ];
    let cut = vec![
        tri(
            [[-1.0, -1.0, -2.0], [1.0, -1.0, -2.0], [1.0, -1.0, -4.0]],
            n,
        ),
        tri(
            [[-1.0, -1.0, -2.0], [1.0, -1.0, -4.0], [-1.0, -1.0, -4.0]],
            n,
        ),
    ];
    let render_tris = |tris, far| {
        let mut s = scene(32, 32, cam.clone());
        s.camera.far = far;
        s.objects.push(object(tris, Shading::Flat, matte(), true));
        render(&s).expect("valid scene")
    };
    let clipped = render_tris(strip.clone(), Some(4.0));
    assert_eq!(clipped.covered, render_tris(cut, None).covered);
    assert!(clipped
        .depth
        .iter()
        .all(|&d| d == f64::INFINITY || (2.0 - 1e-9..=4.0 + 1e-9).contains(&d)));
    assert!(render_tris(strip, None).covered_count() > clipped.covered_count());
}

#[test]
fn depth_is_perspective_correct_on_a_tilted_plane() {
    // Eye at the origin looking down -z: eye space is world space. Plane
    // z = -5 + 0.3 x + 0.2 y; the ray through a pixel centre with direction
    // (dx, dy, -1) meets it at depth t = 5 / (1 + 0.3 dx + 0.2 dy).
    let (w, h, fov) = (16u32, 12u32, 60.0f64);
    let plane = |x: f64, y: f64| [x, y, -5.0 + 0.3 * x + 0.2 * y];
    let mut s = scene(w, h, camera([0.0; 3], [0.0, 0.0, -1.0], fov, 0.5));
    let corners = [plane(-6.0, -6.0), plane(6.0, -6.0), plane(0.0, 8.0)];
    s.objects.push(object(
        vec![tri(corners, [0.0, 0.0, 1.0])],
        Shading::Flat,
        matte(),
        false,
    ));
    let frame = render(&s).expect("valid scene");
    let half_h = (fov.to_radians() / 2.0).tan();
    let half_w = half_h * f64::from(w) / f64::from(h);
    let mut checked = 0;
    for (x, y) in covered(&frame) {
        let dx = ((f64::from(x) + 0.5) / f64::from(w) * 2.0 - 1.0) * half_w;
        let dy = (1.0 - (f64::from(y) + 0.5) / f64::from(h) * 2.0) * half_h;
        let want = 5.0 / (1.0 + 0.3 * dx + 0.2 * dy);
        let got = frame.depth[frame.index(x, y).expect("inside")];
        assert!((got - want).abs() < 1e-9 * want, "{x},{y}: {got} vs {want}");
        checked += 1;
    }
    assert!(checked > 100, "{checked}");
}

#[test]
fn nearest_fragment_wins_and_ties_go_to_the_first_drawn() {
    let cam = camera([0.0, 0.0, 2.0], [0.0; 3], 90.0, 0.1);
    let near_sq = square(-0.5, -0.5, 0.5, 0.5, 0.5);
    let far_sq = square(-1.0, -1.0, 1.0, 1.0, 0.0);
    let render_objs = |objs: Vec<Vec<_>>| {
        let mut s = scene(16, 16, cam.clone());
        for t in objs {
            s.objects.push(object(t, Shading::Flat, matte(), true));
        }
        render(&s).expect("valid scene")
    };
    // Near square maps to screen [16/3, 32/3]^2 -> pixels 5 ..= 10.
    let near_pixels = block(5, 5, 10, 10);
    for (order, near_id) in [
        (vec![near_sq.clone(), far_sq.clone()], 0),
        (vec![far_sq.clone(), near_sq.clone()], 1),
    ] {
        let f = render_objs(order);
        for (x, y) in covered(&f) {
            let i = f.index(x, y).expect("inside");
            let is_near = near_pixels.contains(&(x, y));
            assert_eq!(f.object[i] == Some(near_id), is_near, "{x},{y}");
            let want = if is_near { 1.5 } else { 2.0 };
            assert!((f.depth[i] - want).abs() < 1e-12);
        }
    }
    // Coplanar duplicates: object 0 keeps every pixel.
    let tie = render_objs(vec![far_sq.clone(), far_sq]);
    assert!(tie.covered_count() > 0);
    assert!(tie.object.iter().all(|o| *o != Some(1)));
}
