//! A small scene with all three shading modes, checked against the stored
//! reference image `tests/images/ideal_three_shadings.png` (regenerate with
//! `MAKE_REF=1`).

use fixshade_host::ideal::{render, IdealScene, Light, LightKind, Shading, Vertex};
use fixshade_host::image::check_reference;

use super::{camera, material, object, scene, tri};

/// Cross product.
fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// `a - b`.
fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Orders `t` counter-clockwise seen from outside a convex solid around
/// `centre`; `None` for degenerate triangles.
fn outward(mut t: [Vertex; 3], centre: [f64; 3]) -> Option<[Vertex; 3]> {
    let p = t.map(|v| v.position);
    let n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    let out: f64 = (0..3).map(|k| n[k] * (p[0][k] - centre[k])).sum();
    if n.iter().map(|c| c * c).sum::<f64>() < 1e-18 {
        return None;
    }
    if out < 0.0 {
        t.swap(1, 2);
    }
    Some(t)
}

/// A UV sphere with outward vertex normals.
fn sphere(centre: [f64; 3], r: f64, stacks: u32, slices: u32) -> Vec<[Vertex; 3]> {
    let vertex = |i: u32, j: u32| {
        let theta = std::f64::consts::PI * f64::from(i) / f64::from(stacks);
        let phi = std::f64::consts::TAU * f64::from(j) / f64::from(slices);
        let n = [
            theta.sin() * phi.cos(),
            theta.cos(),
            theta.sin() * phi.sin(),
        ];
        Vertex {
            position: [0, 1, 2].map(|k| centre[k] + r * n[k]),
            normal: n,
        }
    };
    let mut tris = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let (a, b, c, d) = (
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i + 1, j + 1),
                vertex(i, j + 1),
            );
            tris.extend(outward([a, b, c], centre));
            tris.extend(outward([a, c, d], centre));
        }
    }
    tris
}

/// A square pyramid standing on `y = 0` (flat shading ignores normals).
fn pyramid(x: f64, z: f64, half: f64, height: f64) -> Vec<[Vertex; 3]> {
    let apex = [x, height, z];
    let base = [
        [x - half, 0.0, z - half],
        [x + half, 0.0, z - half],
        [x + half, 0.0, z + half],
        [x - half, 0.0, z + half],
    ];
    let centre = [x, height / 4.0, z];
    (0..4)
        .filter_map(|k| outward(tri([base[k], base[(k + 1) % 4], apex], [0.0; 3]), centre))
        .collect()
}

/// The reference scene; `cull` applies to every object.
fn three_shadings(cull: bool) -> IdealScene {
    let mut s = scene(32, 32, camera([0.0, 1.2, 3.5], [0.0, 0.2, 0.0], 45.0, 0.5));
    s.background = [0.05, 0.05, 0.1];
    s.ambient = 0.3;
    s.lights.push(Light {
        kind: LightKind::Point {
            position: [2.0, 3.0, 2.0],
        },
        intensity: 0.8,
        color: [1.0; 3],
    });
    s.lights.push(Light {
        kind: LightKind::Directional {
            direction: [-1.0, 0.5, 0.3],
        },
        intensity: 0.4,
        color: [0.3, 0.4, 1.0],
    });
    let up = [0.0, 1.0, 0.0];
    let floor = vec![
        tri([[-2.0, 0.0, 2.0], [2.0, 0.0, 2.0], [2.0, 0.0, -2.0]], up),
        tri([[-2.0, 0.0, 2.0], [2.0, 0.0, -2.0], [-2.0, 0.0, -2.0]], up),
    ];
    let floor_m = material([0.6, 0.6, 0.55], 0.5, 0.7, 0.1, 4.0);
    s.objects
        .push(object(floor, Shading::Gouraud, floor_m, cull));
    let stone = material([0.9, 0.5, 0.2], 0.4, 0.8, 0.2, 8.0);
    s.objects.push(object(
        pyramid(-0.9, 0.0, 0.4, 0.9),
        Shading::Flat,
        stone,
        cull,
    ));
    let plastic = material([0.2, 0.5, 0.9], 0.4, 0.7, 0.6, 30.0);
    s.objects.push(object(
        sphere([0.7, 0.5, 0.0], 0.5, 8, 12),
        Shading::Phong,
        plastic,
        cull,
    ));
    s
}

#[test]
fn three_shadings_scene_matches_the_reference_image() {
    let culled = render(&three_shadings(true)).expect("valid scene");
    let both_sides = render(&three_shadings(false)).expect("valid scene");
    // Closed outward-wound solids look the same with and without culling:
    // back faces are always hidden. (If the culling convention were
    // reversed, the culled frame would show the solids' insides.)
    assert_eq!(culled.to_rgb8(), both_sides.to_rgb8());
    // Every object is visible.
    for id in 0..3 {
        assert!(
            culled.object.iter().filter(|o| **o == Some(id)).count() > 20,
            "object {id}"
        );
    }
    if let Err(e) = check_reference("ideal_three_shadings", 32, 32, &culled.to_rgb8()) {
        panic!("{e}");
    }
}
