//! Illumination values computed by hand and the three shading modes.

use fixshade_host::ideal::{
    illuminate, render, to_level, IdealFrame, IdealScene, LightKind, Shading, SpecularModel,
};

use super::{camera, color_at, covered, light, material, object, scene, square, tri};

/// Asserts two colours agree to `tol` per channel.
fn close(got: [f64; 3], want: [f64; 3], tol: f64) {
    for c in 0..3 {
        assert!((got[c] - want[c]).abs() <= tol, "{got:?} vs {want:?}");
    }
}

/// Scene with the eye at `(0, 0, 5)` looking at the origin and one light.
fn lit(kind: LightKind) -> IdealScene {
    let mut s = scene(16, 16, camera([0.0, 0.0, 5.0], [0.0; 3], 60.0, 0.1));
    s.lights.push(light(kind));
    s
}

/// A directional light at `deg` degrees from `+z` in the x-z plane.
fn tilted(deg: f64) -> LightKind {
    let a = deg.to_radians();
    LightKind::Directional {
        direction: [a.sin(), 0.0, a.cos()],
    }
}

const UP: [f64; 3] = [0.0, 0.0, 1.0];

#[test]
fn lambert_at_sixty_degrees_is_half_of_kd() {
    let s = lit(tilted(60.0));
    let m = material([1.0, 0.5, 0.3], 0.0, 0.8, 0.0, 1.0);
    close(illuminate(&s, &m, [0.0; 3], UP), [0.4, 0.2, 0.12], 1e-12);
    // The ambient term adds Ia * ka * C.
    let mut s = s;
    s.ambient = 0.5;
    let m = material([1.0, 0.5, 0.3], 0.2, 0.8, 0.0, 1.0);
    close(illuminate(&s, &m, [0.0; 3], UP), [0.5, 0.25, 0.15], 1e-12);
}

#[test]
fn flat_lambert_square_has_the_hand_computed_levels() {
    let mut s = lit(tilted(60.0));
    let m = material([1.0, 0.5, 0.3], 0.0, 0.8, 0.0, 1.0);
    s.objects.push(object(
        square(-1.0, -1.0, 1.0, 1.0, 0.0),
        Shading::Flat,
        m,
        true,
    ));
    let frame = render(&s).expect("valid scene");
    let rgb = frame.to_rgb8();
    // Half-height 5 tan 30 at distance 5: the square spans screen
    // 5.23 ..= 10.77, pixel centres 5.5 ..= 10.5.
    assert_eq!(frame.covered_count(), 36);
    for (x, y) in covered(&frame) {
        // 0.4 * 255 = 102, 0.2 * 255 = 51, 0.12 * 255 = 30.6.
        assert_eq!(rgb[frame.index(x, y).expect("inside")], [102, 51, 31]);
    }
}

#[test]
fn coloured_light_multiplies_the_material_colour() {
    let mut s = lit(tilted(0.0));
    s.lights[0].color = [1.0, 0.25, 0.0];
    s.lights[0].intensity = 0.5;
    let m = material([0.8, 0.8, 0.8], 0.0, 1.0, 0.5, 1.0);
    // Light along N = V: diffuse 0.8 * Lc, specular 0.5 * 1 * Lc, times 0.5.
    close(illuminate(&s, &m, [0.0; 3], UP), [0.65, 0.1625, 0.0], 1e-12);
}

#[test]
fn specular_peaks_where_r_equals_v() {
    let m = material([1.0; 3], 0.0, 0.0, 0.6, 4.0);
    let mut s = lit(tilted(0.0));
    // L = V = N, so R = V and N = H: spec = 1.
    for model in [SpecularModel::Phong, SpecularModel::Blinn] {
        s.specular = model;
        close(illuminate(&s, &m, [0.0; 3], UP), [0.6; 3], 1e-12);
    }
    // Light 30 degrees off N = V: R is 30 degrees off on the other side, so
    // R.V = cos 30 and spec = (3/4)^2 = 9/16; H is halfway: N.H = cos 15.
    let mut s = lit(tilted(30.0));
    close(
        illuminate(&s, &m, [0.0; 3], UP),
        [0.6 * 9.0 / 16.0; 3],
        1e-12,
    );
    s.specular = SpecularModel::Blinn;
    let blinn = 0.6 * 15f64.to_radians().cos().powi(4);
    close(illuminate(&s, &m, [0.0; 3], UP), [blinn; 3], 1e-12);
}

#[test]
fn no_specular_from_lights_behind_the_surface() {
    // L slightly below the surface, V above: N.H is close to 1 but N.L < 0.
    let mut s = lit(LightKind::Directional {
        direction: [1.0, 0.0, -0.05],
    });
    s.camera.eye = [-5.0, 0.0, 2.0];
    s.specular = SpecularModel::Blinn;
    let m = material([1.0; 3], 0.0, 1.0, 1.0, 1.0);
    assert_eq!(illuminate(&s, &m, [0.0; 3], UP), [0.0; 3]);
}

#[test]
fn degenerate_directions_give_defined_colours() {
    let mut s = lit(LightKind::Point {
        position: [0.0, 0.0, 1.0],
    });
    s.ambient = 1.0;
    let m = material([0.5, 0.25, 1.0], 0.4, 1.0, 1.0, 8.0);
    // Zero normal: ambient only.
    close(illuminate(&s, &m, [0.0; 3], [0.0; 3]), [0.2, 0.1, 0.4], 0.0);
    // Light exactly at the shaded point contributes nothing.
    close(
        illuminate(&s, &m, [0.0, 0.0, 1.0], UP),
        [0.2, 0.1, 0.4],
        0.0,
    );
    // Non-unit normals are normalised.
    let a = illuminate(&s, &m, [0.3, 0.1, 0.0], [0.0, 0.0, 7.0]);
    let b = illuminate(&s, &m, [0.3, 0.1, 0.0], UP);
    close(a, b, 1e-15);
}

#[test]
fn specular_highlight_lands_on_the_mirror_point() {
    // Eye (0, 0, 1), light (0.4, 0, 1): the mirror point on z = 0 is
    // (0.2, 0, 0), which projects to x = 12.6, y = 10.5 on a 21 x 21 frame.
    let mut s = scene(21, 21, camera([0.0, 0.0, 1.0], [0.0; 3], 90.0, 0.1));
    s.lights.push(light(LightKind::Point {
        position: [0.4, 0.0, 1.0],
    }));
    let m = material([1.0; 3], 0.0, 0.0, 1.0, 50.0);
    s.objects.push(object(
        square(-2.0, -2.0, 2.0, 2.0, 0.0),
        Shading::Phong,
        m,
        true,
    ));
    let frame = render(&s).expect("valid scene");
    assert_eq!(frame.covered_count(), 21 * 21);
    let brightest = covered(&frame)
        .into_iter()
        .max_by(|&(ax, ay), &(bx, by)| {
            color_at(&frame, ax, ay)[0].total_cmp(&color_at(&frame, bx, by)[0])
        })
        .expect("covered pixels");
    assert_eq!(brightest, (12, 10));
    assert!(color_at(&frame, 12, 10)[0] > 0.98);
}

/// The same Phong-shaded, Phong-lit square under light `kind`.
fn shiny_square(kind: LightKind) -> IdealFrame {
    let mut s = scene(24, 24, camera([0.5, 0.3, 3.0], [0.0; 3], 50.0, 0.1));
    s.lights.push(light(kind));
    s.ambient = 0.2;
    let m = material([0.9, 0.6, 0.3], 0.5, 0.7, 0.3, 10.0);
    let mut tris = square(-1.0, -1.0, 1.0, 1.0, 0.0);
    // Bend the normals so N.L varies over the square.
    for t in &mut tris {
        for v in t.iter_mut() {
            v.normal = [v.position[0] * 0.4, v.position[1] * 0.4, 1.0];
        }
    }
    s.objects.push(object(tris, Shading::Phong, m, true));
    render(&s).expect("valid scene")
}

#[test]
fn far_point_light_matches_directional_light() {
    // At distance 1e8 the light directions differ by under 2e-8 radians over
    // the unit square; the colour changes by at most (kd + ks * n) * 2e-8.
    let d = [1.0, 2.0, 3.0];
    let len = (14f64).sqrt();
    let far = d.map(|c| c / len * 1e8);
    let a = shiny_square(LightKind::Directional { direction: d });
    let b = shiny_square(LightKind::Point { position: far });
    assert_eq!(a.covered, b.covered);
    assert!(a.covered_count() > 100);
    let worst = a
        .color
        .iter()
        .zip(&b.color)
        .flat_map(|(p, q)| (0..3).map(move |c| (p[c] - q[c]).abs()))
        .fold(0.0, f64::max);
    assert!(worst < 1e-6, "{worst}");
}

#[test]
fn phong_shows_a_highlight_inside_a_triangle_that_gouraud_misses() {
    // One big triangle, light at the eye straight above its interior point
    // (0, 0, 0). At the corners R.V < 0, so Gouraud has no specular at all.
    let corners = [[-3.0, -2.0, 0.0], [3.0, -2.0, 0.0], [0.0, 3.0, 0.0]];
    let frame_for = |shading| {
        let mut s = scene(21, 21, camera([0.0, 0.0, 2.0], [0.0; 3], 90.0, 0.1));
        s.lights.push(light(LightKind::Point {
            position: [0.0, 0.0, 2.0],
        }));
        let m = material([1.0; 3], 0.0, 0.2, 0.8, 100.0);
        s.objects
            .push(object(vec![tri(corners, UP)], shading, m, true));
        render(&s).expect("valid scene")
    };
    let phong = frame_for(Shading::Phong);
    let gouraud = frame_for(Shading::Gouraud);
    assert_eq!(phong.covered, gouraud.covered);
    // Centre pixel (10, 10) looks exactly at (0, 0, 0): spec 1 + diffuse 0.2.
    assert!(color_at(&phong, 10, 10)[0] > 0.99);
    // Gouraud: at most 0.2 * the largest corner N.L (2 / sqrt(13) < 0.56).
    let gouraud_max = gouraud.color.iter().map(|c| c[0]).fold(0.0, f64::max);
    assert!(gouraud_max < 0.2 * 0.56, "{gouraud_max}");
    assert!(color_at(&gouraud, 10, 10)[0] > 0.0);
}

#[test]
fn constant_lighting_is_identical_in_all_modes() {
    let frames: Vec<Vec<[u8; 3]>> = [Shading::Flat, Shading::Gouraud, Shading::Phong]
        .into_iter()
        .map(|shading| {
            let mut s = lit(tilted(40.0));
            s.ambient = 0.3;
            let m = material([0.2, 0.7, 0.9], 0.5, 0.6, 0.0, 1.0);
            s.objects
                .push(object(square(-1.0, -1.0, 1.0, 1.0, 0.0), shading, m, true));
            render(&s).expect("valid scene").to_rgb8()
        })
        .collect();
    assert_eq!(frames[0], frames[1]);
    assert_eq!(frames[0], frames[2]);
}

#[test]
fn eight_bit_levels_round_and_clamp() {
    assert_eq!(
        [0.0, 0.5, 1.0, 0.998, 0.001].map(to_level),
        [0, 128, 255, 254, 0]
    );
    assert_eq!([-0.5, 1.5, f64::NAN, 0.2].map(to_level), [0, 255, 0, 51]);
    let mut s = scene(2, 1, camera([0.0, 0.0, 5.0], [0.0; 3], 60.0, 0.1));
    s.background = [2.0, -1.0, 0.5];
    let frame = render(&s).expect("valid scene");
    assert_eq!(frame.to_rgb8(), vec![[255, 0, 128]; 2]);
    assert_eq!(frame.covered, vec![false; 2]);
    assert_eq!(frame.depth, vec![f64::INFINITY; 2]);
}
