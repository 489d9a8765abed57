use super::{error_ulps, Shape};
use crate::mesh::{generate_normals, Crease, Mesh, NormalsError, Smoothing, CAN, CUBE, NORMAL_ONE};

/// Outputs of [`run`] for meshes of up to 32 triangles and 32 vertices.
struct Out {
    count: usize,
    normals: [[i16; 3]; 96],
    indices: [[u16; 3]; 32],
}

impl Out {
    fn corner(&self, tri: usize, corner: usize) -> [i16; 3] {
        self.normals[usize::from(self.indices[tri][corner])]
    }

    /// Number of distinct normals on the corners of `vertex`.
    fn distinct_at(&self, mesh: &Mesh<'_>, vertex: u16) -> usize {
        let mut seen = [[0i16; 3]; 32];
        let mut n = 0;
        for (t, tri) in mesh.triangles().iter().enumerate() {
            for c in (0..3).filter(|&c| tri[c] == vertex) {
                let normal = self.corner(t, c);
                if !seen[..n].contains(&normal) {
                    seen[n] = normal;
                    n += 1;
                }
            }
        }
        n
    }
}

fn run(mesh: &Mesh<'_>, smoothing: &Smoothing<'_>) -> Result<Out, NormalsError> {
    let mut out = Out {
        count: 0,
        normals: [[0; 3]; 96],
        indices: [[0; 3]; 32],
    };
    let (mut adjacency, mut offsets) = ([0u16; 96], [0u32; 33]);
    out.count = generate_normals(
        mesh,
        smoothing,
        &mut adjacency,
        &mut offsets,
        &mut out.normals,
        &mut out.indices,
    )?;
    Ok(out)
}

fn crease(degrees: u32) -> Smoothing<'static> {
    Smoothing::crease(Crease::from_degrees(degrees))
}

#[test]
fn cube_below_90_degrees_stays_flat() {
    let shape = Shape::of(&CUBE);
    let cube = shape.mesh();
    let out = run(&cube, &crease(89)).unwrap();
    assert_eq!(out.count, 24);
    for v in 0..8 {
        assert_eq!(out.distinct_at(&cube, v), 3, "vertex {v}");
    }
    for t in 0..12 {
        for c in 0..3 {
            assert_eq!(Some(out.corner(t, c)), CUBE.corner_normal(t, c));
        }
    }
    // Crease 0 gives the same flat normals.
    let flat = run(&cube, &Smoothing::crease(Crease::FLAT)).unwrap();
    assert_eq!(flat.count, 24);
    assert_eq!(flat.indices, out.indices);
}

#[test]
fn cube_at_90_and_180_degrees_is_smooth() {
    let shape = Shape::of(&CUBE);
    let cube = shape.mesh();
    for smoothing in [crease(90), crease(180), Smoothing::SMOOTH] {
        let out = run(&cube, &smoothing).unwrap();
        assert_eq!(out.count, 8);
        for (v, p) in cube.positions().iter().enumerate() {
            // Normal i belongs to vertex i: all vertices are used.
            assert_eq!(out.normals[v], p.map(|c| c.signum() * 9459));
            assert_eq!(out.distinct_at(&cube, v as u16), 1);
        }
        for (t, tri) in cube.triangles().iter().enumerate() {
            assert_eq!(out.indices[t], *tri);
        }
    }
}

/// Smoothing groups of the can's triangles: per side, two side triangles
/// (group 1), a top cap (group 2) and a bottom cap (flat, 0) triangle.
const CAN_GROUPS: [u32; 24] = {
    let mut g = [0u32; 24];
    let mut k = 0;
    while k < 6 {
        g[4 * k] = 1;
        g[4 * k + 1] = 1;
        g[4 * k + 2] = 2;
        k += 1;
    }
    g
};

#[test]
fn can_has_smooth_sides_and_flat_caps() {
    let shape = Shape::of(&CAN);
    let can = shape.mesh();
    let groups = Smoothing {
        crease: Crease::SMOOTH,
        groups: Some(&CAN_GROUPS),
    };
    let out = run(&can, &groups).unwrap();
    // 12 ring vertices with a side and a cap normal, 2 cap centres.
    assert_eq!(out.count, 26);
    let mut sides = [[0i16; 3]; 12];
    let mut n_sides = 0;
    for (t, &g) in CAN_GROUPS.iter().enumerate() {
        for c in 0..3 {
            let n = out.corner(t, c);
            let stored = CAN.corner_normal(t, c).unwrap();
            if g == 1 {
                // Radial: y = 0, and within 1 ulp of the exact radial
                // direction stored in CAN (the quantised hexagon is not
                // exactly regular).
                assert_eq!(n[1], 0);
                assert!(
                    (0..3).all(|k| (n[k] - stored[k]).abs() <= 1),
                    "{n:?} {stored:?}"
                );
                if !sides[..n_sides].contains(&n) {
                    sides[n_sides] = n;
                    n_sides += 1;
                }
            } else {
                assert_eq!(n, stored);
                let y = if t % 4 == 2 { NORMAL_ONE } else { -NORMAL_ONE };
                assert_eq!(n, [0, y, 0]);
            }
        }
    }
    assert_eq!(n_sides, 6);
    // A crease of 89 degrees finds the same split: sides meet at 60°, caps
    // at 90°.
    let by_angle = run(&can, &crease(89)).unwrap();
    assert_eq!(by_angle.count, out.count);
    assert_eq!(by_angle.normals, out.normals);
    assert_eq!(by_angle.indices, out.indices);
}

/// A saddle: vertex 0 at the centre of four faces whose rims go up and
/// down; groups make its corners average chosen neighbours only.
const SADDLE_POSITIONS: [[i16; 3]; 5] = [
    [0, 0, 0],
    [16384, 0, 8192],
    [0, 16384, -8192],
    [-16384, 0, 8192],
    [0, -16384, -8192],
];
const SADDLE_TRIANGLES: [[u16; 3]; 4] = [[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 1]];

#[test]
fn saddle_with_groups_averages_chosen_neighbours() {
    let mesh = Mesh::new(&SADDLE_POSITIONS, &SADDLE_TRIANGLES, None).unwrap();
    // Face 1 shares with 0 and 2, which do not share with each other;
    // face 3 is flat.
    let groups = [0b01, 0b11, 0b10, 0];
    let smoothing = Smoothing {
        crease: Crease::SMOOTH,
        groups: Some(&groups),
    };
    let out = run(&mesh, &smoothing).unwrap();
    assert_eq!(out.distinct_at(&mesh, 0), 4);
    // Exact unit face normals in f64.
    let face = |t: usize| {
        let p = SADDLE_TRIANGLES[t].map(|i| SADDLE_POSITIONS[usize::from(i)].map(f64::from));
        let (d1, d2) = (
            [0, 1, 2].map(|k| p[1][k] - p[0][k]),
            [0, 1, 2].map(|k| p[2][k] - p[0][k]),
        );
        let c = [
            d1[1] * d2[2] - d1[2] * d2[1],
            d1[2] * d2[0] - d1[0] * d2[2],
            d1[0] * d2[1] - d1[1] * d2[0],
        ];
        let len = libm::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        c.map(|x| x / len)
    };
    let sum = |faces: &[usize]| {
        let mut s = [0.0; 3];
        for &f in faces {
            for (sk, nk) in s.iter_mut().zip(face(f)) {
                *sk += nk;
            }
        }
        s
    };
    let expected: [&[usize]; 4] = [&[0, 1], &[0, 1, 2], &[1, 2], &[3]];
    for (t, faces) in expected.iter().enumerate() {
        let err = error_ulps(out.corner(t, 0), sum(faces));
        assert!(err <= 0.51, "triangle {t}: {err} ulps");
    }
    // Rim corners average the faces at the rim vertex within their groups:
    // vertex 2 is on faces 0 and 1, which share.
    assert_eq!(out.corner(0, 2), out.corner(1, 1));
    // Vertex 1 is on faces 0 and 3; face 3 is flat.
    assert_ne!(out.corner(0, 1), out.corner(3, 2));
    assert!(error_ulps(out.corner(3, 2), face(3)) <= 0.51);
}

#[test]
fn degenerate_faces_get_zero_normals() {
    let positions = [[0, 0, 0], [16384, 0, 0], [0, 16384, 0], [8192, 0, 0]];
    // Triangle 1 is collinear, triangle 2 repeats a vertex.
    let triangles = [[0, 1, 2], [0, 3, 1], [2, 2, 1]];
    let mesh = Mesh::new(&positions, &triangles, None).unwrap();
    let out = run(&mesh, &Smoothing::SMOOTH).unwrap();
    for c in 0..3 {
        assert_eq!(out.corner(0, c), [0, 0, NORMAL_ONE]);
        assert_eq!(out.corner(1, c), [0; 3]);
        assert_eq!(out.corner(2, c), [0; 3]);
    }
}

#[test]
fn cancelling_faces_fall_back_to_their_own_normal() {
    let positions = [[0, 0, 0], [16384, 0, 0], [0, 16384, 0]];
    let triangles = [[0, 1, 2], [0, 2, 1]];
    let mesh = Mesh::new(&positions, &triangles, None).unwrap();
    let out = run(&mesh, &Smoothing::SMOOTH).unwrap();
    assert_eq!(out.count, 6);
    for c in 0..3 {
        assert_eq!(out.corner(0, c), [0, 0, NORMAL_ONE]);
        assert_eq!(out.corner(1, c), [0, 0, -NORMAL_ONE]);
    }
}

#[test]
fn small_buffers_and_bad_groups_are_errors() {
    let shape = Shape::of(&CUBE);
    let cube = shape.mesh();
    let s = Smoothing::SMOOTH;
    let (mut adj, mut off) = ([0u16; 36], [0u32; 9]);
    let (mut normals, mut idx) = ([[0i16; 3]; 36], [[0u16; 3]; 12]);
    let mut call = |a: usize, o: usize, n: usize, i: usize, s: &Smoothing<'_>| {
        generate_normals(
            &cube,
            s,
            &mut adj[..a],
            &mut off[..o],
            &mut normals[..n],
            &mut idx[..i],
        )
    };
    assert_eq!(
        call(35, 9, 36, 12, &s),
        Err(NormalsError::AdjacencyTooSmall {
            needed: 36,
            len: 35
        })
    );
    assert_eq!(
        call(36, 8, 36, 12, &s),
        Err(NormalsError::OffsetsTooSmall { needed: 9, len: 8 })
    );
    assert_eq!(
        call(36, 9, 36, 11, &s),
        Err(NormalsError::IndicesTooSmall {
            needed: 12,
            len: 11
        })
    );
    assert!(matches!(
        call(36, 9, 7, 12, &s),
        Err(NormalsError::NormalsFull { capacity: 7, .. })
    ));
    assert!(matches!(
        call(36, 9, 23, 12, &crease(89)),
        Err(NormalsError::NormalsFull { capacity: 23, .. })
    ));
    assert_eq!(call(36, 9, 8, 12, &s), Ok(8));
    assert_eq!(call(36, 9, 24, 12, &crease(89)), Ok(24));
    let short = [1u32; 11];
    let grouped = Smoothing {
        crease: Crease::SMOOTH,
        groups: Some(&short),
    };
    assert_eq!(
        call(36, 9, 36, 12, &grouped),
        Err(NormalsError::GroupCountMismatch {
            triangles: 12,
            groups: 11
        })
    );
}
