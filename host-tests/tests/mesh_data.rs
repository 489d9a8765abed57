//! The built-in meshes: regenerated from scratch and compared byte for
//! byte with the committed sources, and checked for their stated values.

use fixshade_host::bake;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// With `MAKE_MESHES=1` rewrites the sources instead of comparing.
#[test]
fn committed_sources_are_generator_output() {
    let rewrite = std::env::var("MAKE_MESHES").is_ok_and(|v| v == "1");
    for (path, text) in bake::built_in_sources(&root()).expect("assets/bunny.obj loads") {
        if rewrite {
            std::fs::write(&path, &text).expect("write generated mesh");
            continue;
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            committed == text,
            "{} differs from the generator output; run MAKE_MESHES=1 cargo test -p fixshade-host --test mesh_data",
            path.display()
        );
    }
}

use fixshade::mesh::{
    generate_normals, Mesh, Smoothing, BUNNY, CAN, CUBE, DODECAHEDRON, GRID, SPHERE,
};

const ALL: [(&str, Mesh<'static>); 6] = [
    ("CUBE", CUBE),
    ("DODECAHEDRON", DODECAHEDRON),
    ("SPHERE", SPHERE),
    ("CAN", CAN),
    ("GRID", GRID),
    ("BUNNY", BUNNY),
];

fn f64_positions(mesh: &Mesh<'_>) -> Vec<[f64; 3]> {
    mesh.positions()
        .iter()
        .map(|p| p.map(|c| f64::from(c) / 16384.0))
        .collect()
}

fn length(v: [i16; 3]) -> f64 {
    v.iter().map(|&c| f64::from(c).powi(2)).sum::<f64>().sqrt()
}

/// Largest per-component difference in Q1.14 ulps between `n` and the
/// unit vector along `v`.
fn error_ulps(n: [i16; 3], v: [f64; 3]) -> f64 {
    let u = bake::normalize(v).expect("non-zero reference");
    (0..3)
        .map(|k| (f64::from(n[k]) - 16384.0 * u[k]).abs())
        .fold(0.0, f64::max)
}

#[test]
fn counts() {
    let counts: Vec<_> = ALL
        .iter()
        .map(|(_, m)| (m.vertex_count(), m.triangle_count(), m.normal_count()))
        .collect();
    assert_eq!(
        counts,
        [
            // One vertex per distinct (position, normal) pair: the flat
            // solids have one per face corner, the can's ring positions
            // one per side and cap normal.
            (24, 12, 24),
            (60, 36, 60),
            (212, 420, 212),
            (26, 24, 26),
            (81, 128, 81),
            (1839, 3674, 1839),
        ]
    );
}

#[test]
fn positions_in_the_unit_cube_and_sphere() {
    for (name, mesh) in ALL {
        assert!(
            mesh.positions().iter().flatten().all(|c| c.abs() <= 16384),
            "{name}"
        );
    }
    for mesh in [DODECAHEDRON, SPHERE] {
        for &p in mesh.positions() {
            assert!(length(p) <= 16385.0, "{p:?}");
            assert!(length(p) >= 16383.0, "{p:?}");
        }
    }
}

#[test]
fn stored_normals_are_unit() {
    // Each component is rounded from a unit f64 vector: the length is
    // within sqrt(3)/2 ulp of 16384.
    for (name, mesh) in ALL {
        let normals = mesh.normals().expect("built-ins have normals").normals;
        for &n in normals {
            assert!((length(n) - 16384.0).abs() <= 0.87, "{name} {n:?}");
        }
    }
}

#[test]
fn closed_meshes_face_outwards() {
    for (name, mesh) in [CUBE, DODECAHEDRON, SPHERE, CAN, BUNNY].iter().zip(ALL) {
        let v = bake::signed_volume6(&f64_positions(name), name.triangles());
        assert!(v > 0.0, "{}: {v}", mesh.0);
    }
    // The convex ones: every face normal points away from the origin and
    // agrees with the stored corner normals.
    for mesh in [CUBE, DODECAHEDRON, SPHERE, CAN] {
        let p = f64_positions(&mesh);
        for (t, tri) in mesh.triangles().iter().enumerate() {
            let [a, b, c] = tri.map(|i| p[usize::from(i)]);
            let n = bake::unit_face_normal(a, b, c).expect("no zero-area face");
            let centroid: [f64; 3] = std::array::from_fn(|k| a[k] + b[k] + c[k]);
            assert!((0..3).map(|k| n[k] * centroid[k]).sum::<f64>() > 0.0);
            for corner in 0..3 {
                let s = mesh.corner_normal(t, corner).unwrap();
                assert!((0..3).map(|k| n[k] * f64::from(s[k])).sum::<f64>() > 0.0);
            }
        }
    }
    // The grid faces +z.
    let p = f64_positions(&GRID);
    for tri in GRID.triangles() {
        let [a, b, c] = tri.map(|i| p[usize::from(i)]);
        assert!(bake::unit_face_normal(a, b, c).unwrap()[2] > 0.9);
    }
}

#[test]
fn bunny_fits_the_unit_cube_on_its_largest_axis() {
    let axis = |k: usize| BUNNY.positions().iter().map(move |p| i32::from(p[k]));
    let x = (axis(0).min().unwrap(), axis(0).max().unwrap());
    assert_eq!(x, (-16384, 16384));
    for k in [1, 2] {
        let (lo, hi) = (axis(k).min().unwrap(), axis(k).max().unwrap());
        assert!(
            hi - lo < 32768 && (lo + hi).abs() <= 1,
            "axis {k}: {lo}..{hi}"
        );
    }
    // Normals are the f64 average of unit face normals at each vertex.
    let data = bake::bunny(&root().join("assets/bunny.obj")).unwrap();
    let reference = bake::averaged_normals(&data.positions, &data.triangles);
    let normals = BUNNY.normals().unwrap().normals;
    for (&n, &r) in normals.iter().zip(&reference) {
        assert!(error_ulps(n, r) <= 0.5 + 1e-9);
    }
    assert_eq!(BUNNY.normals().unwrap().indices, BUNNY.triangles());
}

/// Generates smooth normals of `mesh` with the core and returns the worst
/// per-component error (ulps) against the f64 average of the exact unit
/// face normals of the same integer positions.
fn smooth_normal_error(mesh: &Mesh<'_>) -> f64 {
    let (t, v) = (mesh.triangle_count(), mesh.vertex_count());
    let (mut adjacency, mut offsets) = (vec![0; 3 * t], vec![0; v + 1]);
    let (mut normals, mut indices) = (vec![[0; 3]; v], vec![[0; 3]; t]);
    let count = generate_normals(
        mesh,
        &Smoothing::SMOOTH,
        &mut adjacency,
        &mut offsets,
        &mut normals,
        &mut indices,
    )
    .expect("one normal per vertex suffices");
    assert_eq!(count, v);
    assert_eq!(indices, mesh.triangles());
    let reference = bake::averaged_normals(&f64_positions(mesh), mesh.triangles());
    normals
        .iter()
        .zip(&reference)
        .map(|(&n, &r)| error_ulps(n, r))
        .fold(0.0, f64::max)
}

#[test]
fn generated_normals_match_f64_within_the_bound() {
    for (name, mesh) in [("SPHERE", SPHERE), ("BUNNY", BUNNY), ("GRID", GRID)] {
        let err = smooth_normal_error(&mesh);
        eprintln!("{name}: worst generated normal component error {err:.6} ulp");
        assert!(err <= 0.51, "{name}: {err}");
    }
}

#[test]
fn bake_rs_writes_quantised_tables() {
    let text = bake::bake_rs(
        "TRI",
        &["A triangle."],
        &[[0.0, 0.0, 0.0], [0.5, 0.0, 0.0], [0.0, -0.25, 1.0]],
        &[[0, 2, 1]],
        None,
    );
    assert!(text
        .contains("pub const TRI: Mesh<'static> = match Mesh::new(POSITIONS, TRIANGLES, None) {"));
    assert!(text.contains("Ok(mesh) => match mesh.with_face_normals(FACE_NORMALS) {"));
    // The exact face normal of (0, 0, 0), (0, -1/4, 1), (1/2, 0, 0).
    assert!(text.contains("const FACE_NORMALS: &[[i16; 3]] = &[\n    [0, 15895, 3974],\n"));
    assert!(text.contains("    [0, 0, 0], [8192, 0, 0], [0, -4096, 16384],\n"));
    assert!(text.contains("    [0, 2, 1],\n"));
    assert_eq!(bake::quantize_q14(-0.5 / 16384.0), -1);
    assert_eq!(bake::quantize_q14(3.0), i16::MAX);
}

#[test]
fn baked_face_normals_are_the_exact_ones() {
    for (name, mesh) in ALL {
        let f = mesh.face_normals().expect("built-ins bake face normals");
        for (t, &n) in f.iter().enumerate() {
            let [a, b, c] = mesh.triangle_positions(t).unwrap();
            assert_eq!(n, fixshade::mesh::face_normal(a, b, c), "{name} {t}");
        }
    }
}
