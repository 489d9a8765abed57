//! Unit tests of the private pieces (clipping, facing, projection).

use super::clip::{clip_triangle, ClipVertex};
use super::render::{facing, Facing};
use super::scene::Camera;
use super::view::View;

/// A clip vertex with only an eye position (other attributes copy it).
fn cv(eye: [f64; 3]) -> ClipVertex {
    ClipVertex {
        eye,
        world: eye,
        normal: [0.0, 0.0, 1.0],
        color: [0.5; 3],
    }
}

/// Camera at `(0, 0, 5)` looking at the origin, 90 degree field of view.
fn camera() -> Camera {
    Camera {
        eye: [0.0, 0.0, 5.0],
        target: [0.0; 3],
        up: [0.0, 1.0, 0.0],
        fov_y_deg: 90.0,
        near: 0.5,
        far: None,
    }
}

#[test]
fn triangle_in_front_of_near_is_unchanged() {
    let tri = [
        cv([0.0, 0.0, -2.0]),
        cv([1.0, 0.0, -3.0]),
        cv([0.0, 1.0, -4.0]),
    ];
    assert_eq!(clip_triangle(tri, 1.0, Some(10.0)), tri.to_vec());
}

#[test]
fn triangle_behind_near_or_beyond_far_vanishes() {
    let behind = [
        cv([0.0, 0.0, -0.5]),
        cv([1.0, 0.0, 2.0]),
        cv([0.0, 1.0, -0.9]),
    ];
    assert!(clip_triangle(behind, 1.0, None).is_empty());
    let beyond = [
        cv([0.0, 0.0, -11.0]),
        cv([1.0, 0.0, -12.0]),
        cv([0.0, 1.0, -30.0]),
    ];
    assert!(clip_triangle(beyond, 1.0, Some(10.0)).is_empty());
}

#[test]
fn one_corner_behind_near_gives_a_quad_on_the_plane() {
    // Corner c is behind the eye; edges a-c and b-c cross z = -1 at t = 0.5.
    let tri = [
        cv([-1.0, -0.5, -3.0]),
        cv([1.0, -0.5, -3.0]),
        cv([0.0, 1.5, 1.0]),
    ];
    let poly = clip_triangle(tri, 1.0, None);
    let eyes: Vec<[f64; 3]> = poly.iter().map(|v| v.eye).collect();
    assert_eq!(
        eyes,
        vec![
            [-1.0, -0.5, -3.0],
            [1.0, -0.5, -3.0],
            [0.5, 0.5, -1.0],
            [-0.5, 0.5, -1.0]
        ]
    );
    // Attributes follow the same interpolation.
    assert_eq!(poly[2].world, [0.5, 0.5, -1.0]);
}

#[test]
fn near_and_far_together_cut_a_band() {
    let tri = [
        cv([0.0, 0.0, 0.0]),
        cv([3.0, 0.0, -20.0]),
        cv([0.0, 3.0, -20.0]),
    ];
    let poly = clip_triangle(tri, 1.0, Some(10.0));
    assert_eq!(poly.len(), 4);
    for v in &poly {
        assert!(v.eye[2] <= -1.0 && v.eye[2] >= -10.0, "{:?}", v.eye);
    }
}

#[test]
fn shared_edge_clips_to_bit_identical_points_in_both_directions() {
    let a = cv([0.1, 0.3, -2.7]);
    let b = cv([-0.7, 0.9, 0.3]);
    let c = cv([0.4, -0.8, -3.1]);
    let d = cv([-1.3, -0.2, -2.9]);
    let near = 0.37;
    let first = clip_triangle([a, b, c], near, None);
    let second = clip_triangle([b, a, d], near, None);
    let on_plane = |p: &Vec<ClipVertex>| -> Vec<[f64; 3]> {
        p.iter()
            .filter(|v| v.eye[2] == -near)
            .map(|v| v.eye)
            .collect()
    };
    let shared: Vec<_> = on_plane(&first)
        .into_iter()
        .filter(|e| on_plane(&second).contains(e))
        .collect();
    assert_eq!(shared.len(), 1, "{first:?} {second:?}");
}

#[test]
fn facing_follows_the_right_hand_rule() {
    let ccw = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let cw = [ccw[0], ccw[2], ccw[1]];
    assert_eq!(facing(ccw, [0.0, 0.0, 5.0]), Facing::Front);
    assert_eq!(facing(cw, [0.0, 0.0, 5.0]), Facing::Back);
    assert_eq!(facing(ccw, [0.0, 0.0, -5.0]), Facing::Back);
    assert_eq!(facing(ccw, [3.0, 2.0, 0.0]), Facing::EdgeOn);
}

#[test]
fn front_face_has_negative_screen_edge_function() {
    let view = View::new(&camera(), 20, 10).expect("valid camera");
    let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let s = tri.map(|p| view.project(view.eye_space(p)).0);
    let e = (s[1][0] - s[0][0]) * (s[2][1] - s[0][1]) - (s[1][1] - s[0][1]) * (s[2][0] - s[0][0]);
    assert!(e < 0.0, "{s:?}");
}

#[test]
fn projection_maps_the_view_frustum_to_the_viewport() {
    // 90 degrees: at distance 5 the visible half-height is 5 (half-width 10
    // for a 2:1 frame).
    let view = View::new(&camera(), 20, 10).expect("valid camera");
    let project = |p| {
        let (s, w) = view.project(view.eye_space(p));
        (s.map(|c| (c * 1e9).round() / 1e9), w)
    };
    assert_eq!(project([0.0, 0.0, 0.0]), ([10.0, 5.0], 5.0));
    assert_eq!(project([10.0, 5.0, 0.0]), ([20.0, 0.0], 5.0));
    assert_eq!(project([-10.0, -5.0, 0.0]), ([0.0, 10.0], 5.0));
}
