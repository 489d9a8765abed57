use crate::mesh::{weld, Bound, CornerNormals, Mesh, MeshError, CUBE, MAX_VERTICES};
use core::fmt::Write;

const P: [[i16; 3]; 4] = [[0, 0, 0], [16384, 0, 0], [0, 16384, 0], [0, 0, 16384]];
const N: [[i16; 3]; 2] = [[0, 0, 16384], [-16384, 0, 0]];

fn text(e: MeshError) -> heapless::String<128> {
    let mut s = heapless::String::new();
    write!(s, "{e}").unwrap();
    s
}

#[test]
fn valid_meshes_and_accessors() {
    let tris = [[0, 1, 2], [0, 2, 3]];
    let normals = [N[0], N[0], N[1], N[1]];
    let mesh = Mesh::new(&P, &tris, Some(&normals)).unwrap();
    assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (4, 2));
    assert_eq!(mesh.normal_count(), 4);
    assert!(mesh.has_normals());
    assert_eq!(
        mesh.normals(),
        Some(CornerNormals {
            normals: &normals,
            indices: &tris
        })
    );
    assert_eq!(mesh.vertex_normals(), Some(&normals[..]));
    assert_eq!(mesh.positions(), &P);
    assert_eq!(mesh.triangles(), &tris);
    assert_eq!(mesh.corner_normal(1, 2), Some([-16384, 0, 0]));
    assert_eq!(mesh.corner_normal(0, 3), None);
    assert_eq!(mesh.corner_normal(2, 0), None);
    assert_eq!(mesh.triangle_positions(1), Some([P[0], P[2], P[3]]));
    assert_eq!(mesh.triangle_positions(2), None);
    assert_eq!(mesh.face_normals(), None);
    // Box [0, 16384]^3: centre 8192 each, farthest corner at 8192·√3.
    assert_eq!(
        mesh.bound(),
        Bound {
            center: [8192; 3],
            radius: 14189,
            half: [8192; 3],
        }
    );
    let faces = [[0, 0, 16384], [16384, 0, 0]];
    let flat = mesh.with_face_normals(&faces).unwrap();
    assert_eq!(flat.face_normals(), Some(&faces[..]));
    assert_eq!(
        mesh.with_face_normals(&faces[..1]),
        Err(MeshError::FaceNormalCountMismatch {
            triangles: 2,
            face_normals: 1
        })
    );
    let bare = Mesh::new(&P, &tris, None).unwrap();
    assert!(!bare.has_normals());
    assert_eq!((bare.normals(), bare.normal_count()), (None, 0));
    assert_eq!(bare.corner_normal(0, 0), None);
    assert_eq!((CUBE.vertex_count(), CUBE.triangle_count()), (24, 12));
}

#[test]
fn the_bound_holds_every_position() {
    let mut rng = super::Rng(0x5eed_1234_abcd_0001);
    for _ in 0..200 {
        let mut pos = [[0i16; 3]; 16];
        for p in &mut pos {
            *p = [rng.i16(), rng.i16(), rng.i16()];
        }
        let m = Mesh::new(&pos, &[[0, 1, 2]], None).unwrap();
        let b = m.bound();
        let mut far = 0f64;
        for p in &pos {
            let d2: f64 = (0..3)
                .map(|k| (f64::from(p[k]) - f64::from(b.center[k])).powi(2))
                .sum();
            far = far.max(libm::sqrt(d2));
        }
        assert!(f64::from(b.radius) >= far && f64::from(b.radius) < far + 1.0);
    }
}

#[test]
fn weld_makes_one_vertex_per_pair() {
    // Two triangles sharing the edge 0-2, a crease along it: corners of
    // positions 0 and 2 get two normals each.
    let tris = [[0, 1, 2], [0, 2, 3]];
    let corner = CornerNormals {
        normals: &N,
        indices: &[[0, 0, 0], [1, 1, 1]],
    };
    let mut pos = [[0i16; 3]; 6];
    let mut nrm = [[0i16; 3]; 6];
    let mut out = [[0u16; 3]; 2];
    let mut scratch = [0u16; 4 + 6];
    let n = weld(
        &P,
        &tris,
        corner,
        &mut pos,
        &mut nrm,
        &mut out,
        &mut scratch,
    )
    .unwrap();
    assert_eq!(n, 6);
    assert_eq!(out, [[0, 1, 2], [3, 4, 5]]);
    assert_eq!(pos, [P[0], P[1], P[2], P[0], P[2], P[3]]);
    assert_eq!(nrm, [N[0], N[0], N[0], N[1], N[1], N[1]]);
    let mesh = Mesh::new(&pos, &out, Some(&nrm)).unwrap();
    for (t, n) in N.iter().enumerate() {
        for c in 0..3 {
            assert_eq!(mesh.corner_normal(t, c), Some(*n));
        }
    }
    // Smooth: one normal per position, shared.
    let smooth = CornerNormals {
        normals: &N,
        indices: &[[0, 0, 0], [0, 0, 0]],
    };
    let n = weld(
        &P,
        &tris,
        smooth,
        &mut pos,
        &mut nrm,
        &mut out,
        &mut scratch,
    )
    .unwrap();
    assert_eq!(n, 4);
    assert_eq!(out, [[0, 1, 2], [0, 2, 3]]);
    let mut small = [[0i16; 3]; 5];
    assert_eq!(
        weld(
            &P,
            &tris,
            corner,
            &mut pos,
            &mut small,
            &mut out,
            &mut scratch
        ),
        Err(MeshError::OutputTooSmall)
    );
    let bad = CornerNormals {
        normals: &N,
        indices: &[[0, 0, 0], [1, 2, 1]],
    };
    let err = weld(&P, &tris, bad, &mut pos, &mut nrm, &mut out, &mut scratch).unwrap_err();
    assert_eq!(
        err,
        MeshError::NormalIndexOutOfRange {
            triangle: 1,
            index: 2
        }
    );
    assert_eq!(text(err), "triangle 1 uses normal 2, which is out of range");
}

#[test]
fn bad_tables_are_rejected_with_the_triangle() {
    let tris = [[0, 1, 2], [0, 2, 3], [1, 2, 3], [3, 4, 1]];
    let err = Mesh::new(&P, &tris, None).unwrap_err();
    assert_eq!(
        err,
        MeshError::VertexIndexOutOfRange {
            triangle: 3,
            index: 4
        }
    );
    assert_eq!(text(err), "triangle 3 uses vertex 4, which is out of range");
    assert_eq!(Mesh::new(&[], &tris, None), Err(MeshError::Empty));
    assert_eq!(Mesh::new(&P, &[], None), Err(MeshError::Empty));

    let good = &tris[..3];
    let err = Mesh::new(&P, good, Some(&N)).unwrap_err();
    assert_eq!(
        err,
        MeshError::NormalCountMismatch {
            vertices: 4,
            normals: 2
        }
    );
    assert_eq!(text(err), "2 vertex normals for 4 vertices");
}

static MANY: [[i16; 3]; MAX_VERTICES + 1] = [[0; 3]; MAX_VERTICES + 1];

#[test]
fn at_most_65535_vertices() {
    let tris = [[0, 1, 2]];
    assert!(Mesh::new(&MANY[..MAX_VERTICES], &tris, None).is_ok());
    assert_eq!(
        Mesh::new(&MANY, &tris, None),
        Err(MeshError::TooManyVertices { count: 65536 })
    );
}

/// Checked at compile time: a bad table here would not build.
const CHECKED: Mesh<'static> = match Mesh::new(&P, &[[3, 2, 1]], None) {
    Ok(mesh) => mesh,
    Err(_) => panic!("bad mesh"),
};

#[test]
fn const_meshes() {
    assert_eq!(CHECKED.triangles(), &[[3, 2, 1]]);
}
