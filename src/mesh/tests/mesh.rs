use crate::mesh::{CornerNormals, Mesh, MeshError, CUBE, MAX_VERTICES};
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
    let normal_indices = [[0, 0, 0], [1, 1, 1]];
    let corner = CornerNormals {
        normals: &N,
        indices: &normal_indices,
    };
    let mesh = Mesh::new(&P, &tris, Some(corner)).unwrap();
    assert_eq!((mesh.vertex_count(), mesh.triangle_count()), (4, 2));
    assert_eq!(mesh.normal_count(), 2);
    assert!(mesh.has_normals());
    assert_eq!(mesh.normals(), Some(corner));
    assert_eq!(mesh.positions(), &P);
    assert_eq!(mesh.triangles(), &tris);
    assert_eq!(mesh.corner_normal(1, 2), Some([-16384, 0, 0]));
    assert_eq!(mesh.corner_normal(0, 3), None);
    assert_eq!(mesh.corner_normal(2, 0), None);
    assert_eq!(mesh.triangle_positions(1), Some([P[0], P[2], P[3]]));
    assert_eq!(mesh.triangle_positions(2), None);
    let bare = Mesh::new(&P, &tris, None).unwrap();
    assert!(!bare.has_normals());
    assert_eq!((bare.normals(), bare.normal_count()), (None, 0));
    assert_eq!(bare.corner_normal(0, 0), None);
    assert_eq!((CUBE.vertex_count(), CUBE.triangle_count()), (8, 12));
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
    let short = CornerNormals {
        normals: &N,
        indices: &[[0, 0, 0], [1, 1, 1]],
    };
    let err = Mesh::new(&P, good, Some(short)).unwrap_err();
    assert_eq!(
        err,
        MeshError::NormalCountMismatch {
            triangles: 3,
            normal_indices: 2
        }
    );
    assert_eq!(text(err), "2 normal index triples for 3 triangles");
    let bad = CornerNormals {
        normals: &N,
        indices: &[[0, 0, 0], [1, 1, 1], [1, 2, 0]],
    };
    let err = Mesh::new(&P, good, Some(bad)).unwrap_err();
    assert_eq!(
        err,
        MeshError::NormalIndexOutOfRange {
            triangle: 2,
            index: 2
        }
    );
    assert_eq!(text(err), "triangle 2 uses normal 2, which is out of range");
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
