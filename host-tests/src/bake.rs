//! Generator of the built-in meshes: the sources `src/mesh/shapes/*.rs` of
//! the core crate are the output of [`built_in_sources`].
//!
//! Shapes are made in f64 and quantised once, by [`quantize_q14`] (round to
//! nearest, half away from zero), so each stored coordinate and normal
//! component is within 0.5 ulp (2⁻¹⁴) of its f64 value.

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Normals of a mesh to bake, as f64 vectors (normalised when baked).
#[derive(Clone, Debug, PartialEq)]
pub enum BakeNormals {
    /// One normal per vertex: the normal indices are the triangles.
    PerVertex(Vec<[f64; 3]>),
    /// Shared normals and the normal index of each triangle corner.
    PerCorner {
        /// The normals.
        normals: Vec<[f64; 3]>,
        /// Normal indices, one triple per triangle.
        indices: Vec<[u16; 3]>,
    },
}

/// A mesh in f64, ready to bake.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshData {
    /// Vertex positions, within [-2, 2).
    pub positions: Vec<[f64; 3]>,
    /// Counter-clockwise front-facing triangles.
    pub triangles: Vec<[u16; 3]>,
    /// Optional normals.
    pub normals: Option<BakeNormals>,
}

/// A built-in mesh: its constant's name, its file and its data.
#[derive(Clone, Debug, PartialEq)]
pub struct BuiltIn {
    /// Name of the `pub const` in the core crate.
    pub name: &'static str,
    /// File name under `src/mesh/shapes/`.
    pub file: &'static str,
    /// Doc comment of the constant, one string per line.
    pub doc: &'static [&'static str],
    /// The mesh.
    pub data: MeshData,
}

/// Rounds `x · 16384` to the nearest integer (half away from zero),
/// saturated to i16.
pub fn quantize_q14(x: f64) -> i16 {
    // In range after the clamp, so the cast is exact.
    (x * 16384.0).round().clamp(-32768.0, 32767.0) as i16
}

/// `v / |v|`, or `None` for the zero vector.
pub fn normalize(v: [f64; 3]) -> Option<[f64; 3]> {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    (len > 0.0).then(|| v.map(|c| c / len))
}

/// Unit normal of the counter-clockwise triangle `a, b, c`, or `None` if
/// its area is zero.
pub fn unit_face_normal(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> Option<[f64; 3]> {
    let d1 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let d2 = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    normalize([
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ])
}

/// Per-vertex normals: the normalised sum of the unit normals of the
/// faces at each vertex (not area-weighted); zero-area faces count for
/// nothing and a vertex whose sum is zero gets (0, 0, 0).
pub fn averaged_normals(positions: &[[f64; 3]], triangles: &[[u16; 3]]) -> Vec<[f64; 3]> {
    let mut sums = vec![[0.0f64; 3]; positions.len()];
    for tri in triangles {
        let [a, b, c] = tri.map(|i| positions[usize::from(i)]);
        if let Some(n) = unit_face_normal(a, b, c) {
            for &i in tri {
                for (s, x) in sums[usize::from(i)].iter_mut().zip(n) {
                    *s += x;
                }
            }
        }
    }
    sums.into_iter()
        .map(|s| normalize(s).unwrap_or([0.0; 3]))
        .collect()
}

/// Six times the signed volume enclosed by the triangles: positive when
/// the front faces of a closed mesh face outwards.
pub fn signed_volume6(positions: &[[f64; 3]], triangles: &[[u16; 3]]) -> f64 {
    triangles
        .iter()
        .map(|tri| {
            let [a, b, c] = tri.map(|i| positions[usize::from(i)]);
            a[0] * (b[1] * c[2] - b[2] * c[1])
                + a[1] * (b[2] * c[0] - b[0] * c[2])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum()
}

/// A mesh in the core's form: quantised positions, one vertex per
/// distinct (position, normal) pair with its normal, triangles indexing
/// the vertices, and the exact face normal of each triangle.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Baked {
    /// Vertex positions, Q1.14.
    pub positions: Vec<[i16; 3]>,
    /// Vertex normals, Q1.14 (empty without normals).
    pub normals: Vec<[i16; 3]>,
    /// Triangles.
    pub triangles: Vec<[u16; 3]>,
    /// Face normals: the core's exact `face_normal` of each triangle.
    pub face_normals: Vec<[i16; 3]>,
    /// Culling cones, one per vertex ([`vertex_cones`]); empty without
    /// normals.
    pub cones: Vec<[i32; 2]>,
}

/// Welds per-corner normals into one vertex per distinct (position,
/// normal) pair with the core's [`fixshade::mesh::weld`]: the vertices'
/// positions and normals and the renumbered triangles.
///
/// # Errors
/// The core's, on bad indices or more than 65535 pairs.
pub fn weld_corners(
    positions: &[[i16; 3]],
    triangles: &[[u16; 3]],
    normals: &[[i16; 3]],
    indices: &[[u16; 3]],
) -> Result<WeldedTables, fixshade::mesh::MeshError> {
    let cap = (3 * triangles.len()).min(fixshade::mesh::MAX_VERTICES);
    let mut pos = vec![[0i16; 3]; cap];
    let mut nrm = vec![[0i16; 3]; cap];
    let mut tris = vec![[0u16; 3]; triangles.len()];
    let mut scratch = vec![0u16; positions.len() + cap];
    let n = fixshade::mesh::weld(
        positions,
        triangles,
        fixshade::mesh::CornerNormals { normals, indices },
        &mut pos,
        &mut nrm,
        &mut tris,
        &mut scratch,
    )?;
    pos.truncate(n);
    nrm.truncate(n);
    Ok((pos, nrm, tris))
}

/// Positions, normals and triangles of a welded mesh.
pub type WeldedTables = (Vec<[i16; 3]>, Vec<[i16; 3]>, Vec<[u16; 3]>);

/// Merges equal positions (a vertex per distinct position, in order of
/// first appearance) and renumbers the triangles: the shape of a mesh
/// whose vertices were split by their normals, as normal generation needs
/// it (faces adjacent through shared vertices).
pub fn merge_positions(
    positions: &[[i16; 3]],
    triangles: &[[u16; 3]],
) -> (Vec<[i16; 3]>, Vec<[u16; 3]>) {
    let mut seen = std::collections::HashMap::new();
    let mut out = Vec::new();
    let map: Vec<u16> = positions
        .iter()
        .map(|p| {
            *seen.entry(*p).or_insert_with(|| {
                out.push(*p);
                index(out.len() - 1)
            })
        })
        .collect();
    let tris = triangles
        .iter()
        .map(|t| t.map(|v| map[usize::from(v)]))
        .collect();
    (out, tris)
}

/// The exact face normal ([`fixshade::mesh::face_normal`]) of each
/// triangle.
pub fn face_normals(positions: &[[i16; 3]], triangles: &[[u16; 3]]) -> Vec<[i16; 3]> {
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| positions[usize::from(i)]);
            fixshade::mesh::face_normal(a, b, c)
        })
        .collect()
}

/// The culling cone of each vertex, as `Mesh::with_vertex_cones`
/// checks it: `d = a · P` (`a` the vertex normal), the largest
/// `face_plane` slack of its faces, and the smallest spread (Q1.14) that
/// [`fixshade::mesh::cone_covers`] accepts for every face (from the f64
/// distance, raised until the exact check passes).
pub fn vertex_cones(
    positions: &[[i16; 3]],
    normals: &[[i16; 3]],
    triangles: &[[u16; 3]],
) -> Vec<[i32; 2]> {
    let mut slack = vec![0i32; positions.len()];
    let mut spread = vec![0u16; positions.len()];
    for t in triangles {
        let [p, q, r] = t.map(|i| positions[usize::from(i)]);
        let s = fixshade::mesh::face_plane(p, q, r)[1];
        let n = unit_face_normal(p.map(f64::from), q.map(f64::from), r.map(f64::from));
        for &v in t {
            let v = usize::from(v);
            slack[v] = slack[v].max(s);
            if s == i32::from(u16::MAX) {
                // Never decided: no cone needed.
                continue;
            }
            let (Some(n), a) = (n, normals[v]) else {
                continue;
            };
            let d: f64 = (0..3)
                .map(|k| (n[k] - f64::from(a[k]) / 16384.0).powi(2))
                .sum::<f64>()
                .sqrt();
            let mut sp = ((d * 16384.0).ceil() as u16).max(spread[v]);
            while !fixshade::mesh::cone_covers(a, sp, p, q, r) {
                sp += 1;
            }
            spread[v] = sp;
        }
    }
    (0..positions.len())
        .map(|v| {
            let (a, p) = (normals[v], positions[v]);
            let d: i64 = (0..3).map(|k| i64::from(a[k]) * i64::from(p[k])).sum();
            let packed = (u32::from(spread[v]) << 16) | slack[v] as u32;
            [d as i32, packed as i32]
        })
        .collect()
}

/// The core's form of a mesh in f64: positions quantised by
/// [`quantize_q14`], normals normalised then quantised, per-corner normals
/// welded ([`weld_corners`]), face normals from the quantised positions.
pub fn bake_mesh(
    positions: &[[f64; 3]],
    triangles: &[[u16; 3]],
    normals: Option<&BakeNormals>,
) -> Baked {
    let q = |v: &[f64; 3]| v.map(quantize_q14);
    let unit = |v: &[f64; 3]| q(&normalize(*v).unwrap_or([0.0; 3]));
    let pos: Vec<_> = positions.iter().map(q).collect();
    let (positions, normals, triangles) = match normals {
        None => (pos, vec![], triangles.to_vec()),
        Some(BakeNormals::PerVertex(n)) => (pos, n.iter().map(unit).collect(), triangles.to_vec()),
        Some(BakeNormals::PerCorner { normals, indices }) => {
            let n: Vec<_> = normals.iter().map(unit).collect();
            weld_corners(&pos, triangles, &n, indices).expect("weldable built-in normals")
        }
    };
    let face_normals = face_normals(&positions, &triangles);
    let cones = if normals.is_empty() {
        vec![]
    } else {
        vertex_cones(&positions, &normals, &triangles)
    };
    Baked {
        positions,
        normals,
        triangles,
        face_normals,
        cones,
    }
}

/// Rust source of a module holding the constant mesh `name`, with
/// `doc` as the constant's doc comment lines: the tables of
/// [`bake_mesh`].
pub fn bake_rs(
    name: &str,
    doc: &[&str],
    positions: &[[f64; 3]],
    triangles: &[[u16; 3]],
    normals: Option<&BakeNormals>,
) -> String {
    let b = bake_mesh(positions, triangles, normals);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "//! Built-in mesh `{name}`, generated by `fixshade_host::bake`: do not edit."
    );
    s.push_str("//!\n//! Regenerate with `MAKE_MESHES=1 cargo test -p fixshade-host --test mesh_data`.\n\n");
    let normals_arg = if b.normals.is_empty() {
        "None"
    } else {
        "Some(NORMALS)"
    };
    let _ = writeln!(s, "use crate::mesh::Mesh;\n");
    for line in doc {
        let _ = writeln!(s, "///{}{line}", if line.is_empty() { "" } else { " " });
    }
    let _ = writeln!(
        s,
        "pub const {name}: Mesh<'static> = match Mesh::new(POSITIONS, TRIANGLES, {normals_arg}) {{"
    );
    let cones = if b.cones.is_empty() {
        "mesh".to_string()
    } else {
        format!(
            "match mesh.with_vertex_cones(CONES) {{\n            \
             Ok(mesh) => mesh,\n            \
             Err(_) => panic!(\"invalid culling cones of {name}\"),\n        \
             }}"
        )
    };
    let _ = writeln!(
        s,
        "    Ok(mesh) => match mesh.with_face_normals(FACE_NORMALS) {{\n        \
         Ok(mesh) => {cones},\n        \
         Err(_) => panic!(\"invalid face normals of {name}\"),\n    \
         }},\n    \
         Err(_) => panic!(\"invalid built-in mesh {name}\"),\n}};"
    );
    table(
        &mut s,
        "Vertex positions, Q1.14: one per distinct (position, normal) pair.",
        "POSITIONS",
        "[i16; 3]",
        &b.positions,
    );
    table(
        &mut s,
        "Triangles, counter-clockwise.",
        "TRIANGLES",
        "[u16; 3]",
        &b.triangles,
    );
    if b.normals == b.positions && !b.normals.is_empty() {
        // A unit sphere about the origin: each normal is its position.
        s.push_str(
            "\n/// Unit vertex normals, Q1.14, one per vertex: the positions \
             themselves\n/// (a unit sphere about the origin).\n\
             const NORMALS: &[[i16; 3]] = POSITIONS;\n",
        );
    } else if !b.normals.is_empty() {
        table(
            &mut s,
            "Unit vertex normals, Q1.14, one per vertex.",
            "NORMALS",
            "[i16; 3]",
            &b.normals,
        );
    }
    table(
        &mut s,
        "Unit face normals, Q1.14: the exact `face_normal` of each triangle.",
        "FACE_NORMALS",
        "[i16; 3]",
        &b.face_normals,
    );
    if !b.cones.is_empty() {
        table(
            &mut s,
            "Culling cones `[d, slack | spread << 16]`, one per vertex (`Mesh::with_vertex_cones`).",
            "CONES",
            "[i32; 2]",
            &b.cones,
        );
    }
    s
}

/// Appends a `#[rustfmt::skip]` constant table, several entries a line.
fn table<T: std::fmt::Display, const N: usize>(
    s: &mut String,
    doc: &str,
    name: &str,
    ty: &str,
    rows: &[[T; N]],
) {
    let _ = write!(
        s,
        "\n/// {doc}\n#[rustfmt::skip]\nconst {name}: &[{ty}] = &[\n"
    );
    let mut line = String::new();
    for row in rows {
        let cells: Vec<String> = row.iter().map(ToString::to_string).collect();
        let item = format!("[{}],", cells.join(", "));
        if !line.is_empty() && 4 + line.len() + 1 + item.len() > 100 {
            let _ = writeln!(s, "    {line}");
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&item);
    }
    if !line.is_empty() {
        let _ = writeln!(s, "    {line}");
    }
    s.push_str("];\n");
}

/// The convex polyhedron with the given vertices whose faces lie on the
/// planes with the given outward unit normals: each face is the polygon of
/// the vertices farthest along its normal, ordered counter-clockwise about
/// it and split into a fan from its lowest-numbered vertex `i` with
/// `apex(i)`. Flat per-corner normals, one per face.
fn convex_polyhedron(
    positions: Vec<[f64; 3]>,
    face_normals: Vec<[f64; 3]>,
    apex: fn(usize) -> bool,
) -> MeshData {
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (mut triangles, mut indices) = (Vec::new(), Vec::new());
    for (f, &n) in face_normals.iter().enumerate() {
        let far = positions
            .iter()
            .map(|&p| dot(p, n))
            .fold(f64::MIN, f64::max);
        let mut face: Vec<usize> = (0..positions.len())
            .filter(|&i| dot(positions[i], n) > far - 1e-9)
            .collect();
        // A tangent basis (u, v = n × u) in which angles grow counter-clockwise.
        let helper = if n[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = normalize(cross(helper, n)).expect("non-parallel helper");
        let v = cross(n, u);
        let angle = |i: usize| dot(positions[i], v).atan2(dot(positions[i], u));
        face.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)));
        let first = (0..face.len())
            .filter(|&k| apex(face[k]))
            .min_by_key(|&k| face[k])
            .expect("an apex on every face");
        face.rotate_left(first);
        for k in 1..face.len() - 1 {
            triangles.push([face[0], face[k], face[k + 1]].map(index));
            indices.push([index(f); 3]);
        }
    }
    MeshData {
        positions,
        triangles,
        normals: Some(BakeNormals::PerCorner {
            normals: face_normals,
            indices,
        }),
    }
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn index(i: usize) -> u16 {
    u16::try_from(i).expect("index fits u16")
}

/// `CUBE`: side 2, centred, vertex `i` at (±1, ±1, ±1) with bit 0, 1, 2 of
/// `i` giving the sign of x, y, z; each face split along the diagonal
/// joining its two vertices of even bit parity; flat faces.
pub fn cube() -> MeshData {
    let sign = |i: usize, bit: usize| if i >> bit & 1 == 1 { 1.0 } else { -1.0 };
    let positions = (0..8)
        .map(|i| [sign(i, 0), sign(i, 1), sign(i, 2)])
        .collect();
    let mut normals = Vec::new();
    for axis in 0..3 {
        for s in [1.0, -1.0] {
            let mut n = [0.0; 3];
            n[axis] = s;
            normals.push(n);
        }
    }
    // Diagonals join the vertices of even bit parity, so every vertex has
    // the same number of triangles on each of its three faces and the
    // smooth average of the triangle normals is along (±1, ±1, ±1).
    convex_polyhedron(positions, normals, |i| i.count_ones() % 2 == 0)
}

/// `DODECAHEDRON`: the regular dodecahedron inscribed in the unit sphere,
/// vertices (±1, ±1, ±1), (0, ±1/φ, ±φ), (±1/φ, ±φ, 0), (±φ, 0, ±1/φ)
/// over √3, faces split in three triangles, flat faces.
pub fn dodecahedron() -> MeshData {
    let phi = (1.0 + 5.0f64.sqrt()) / 2.0;
    let r = 3.0f64.sqrt();
    let signs = [[1.0, 1.0], [1.0, -1.0], [-1.0, 1.0], [-1.0, -1.0]];
    let mut positions = Vec::new();
    for i in 0..8 {
        let s = |bit: usize| if i >> bit & 1 == 1 { 1.0 } else { -1.0 };
        positions.push([s(0) / r, s(1) / r, s(2) / r]);
    }
    let cyclic = |a: f64, b: f64, rot: usize| {
        let mut v = [0.0; 3];
        v[(rot + 1) % 3] = a;
        v[(rot + 2) % 3] = b;
        v
    };
    let mut normals = Vec::new();
    for rot in 0..3 {
        for [s1, s2] in signs {
            positions.push(cyclic(s1 / phi / r, s2 * phi / r, rot));
            normals.push(normalize(cyclic(s1 * phi, s2, rot)).expect("non-zero"));
        }
    }
    convex_polyhedron(positions, normals, |_| true)
}

/// `SPHERE`: UV sphere of radius 1, `slices` meridians and `stacks` bands,
/// poles on ±y; 2 + slices · (stacks - 1) vertices, 2 · slices ·
/// (stacks - 1) triangles; smooth normals = positions.
pub fn sphere(slices: usize, stacks: usize) -> MeshData {
    let mut positions = vec![[0.0, 1.0, 0.0]];
    for i in 1..stacks {
        let theta = PI * i as f64 / stacks as f64;
        for j in 0..slices {
            let phi = 2.0 * PI * j as f64 / slices as f64;
            positions.push([
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ]);
        }
    }
    positions.push([0.0, -1.0, 0.0]);
    let south = positions.len() - 1;
    let ring = |i: usize, j: usize| 1 + (i - 1) * slices + j % slices;
    let mut triangles = Vec::new();
    for j in 0..slices {
        triangles.push([0, ring(1, j + 1), ring(1, j)].map(index));
    }
    for i in 1..stacks - 1 {
        for j in 0..slices {
            triangles.push([ring(i, j), ring(i, j + 1), ring(i + 1, j)].map(index));
            triangles.push([ring(i, j + 1), ring(i + 1, j + 1), ring(i + 1, j)].map(index));
        }
    }
    for j in 0..slices {
        triangles.push([ring(stacks - 1, j), ring(stacks - 1, j + 1), south].map(index));
    }
    let normals = positions.clone();
    MeshData {
        positions,
        triangles,
        normals: Some(BakeNormals::PerVertex(normals)),
    }
}

/// `CAN`: six-sided prism of radius 0.6 and height 1.6 about the y axis;
/// vertices: top ring (y = 0.8, angle 60°·k from +x towards +z), bottom
/// ring, top centre, bottom centre. The side quads' diagonals alternate so
/// that every ring vertex has as many triangles on each of its two side
/// quads, and the smooth average of the triangle normals is radial.
/// Smooth sides (radial normals at the ring vertices), flat caps (±y).
pub fn can() -> MeshData {
    let mut positions = Vec::new();
    for y in [0.8, -0.8] {
        for k in 0..6 {
            let a = PI / 3.0 * f64::from(k);
            positions.push([0.6 * a.cos(), y, 0.6 * a.sin()]);
        }
    }
    positions.extend([[0.0, 0.8, 0.0], [0.0, -0.8, 0.0]]);
    let mut normals: Vec<[f64; 3]> = (0..6)
        .map(|k| {
            let a = PI / 3.0 * f64::from(k);
            [a.cos(), 0.0, a.sin()]
        })
        .collect();
    normals.extend([[0.0, 1.0, 0.0], [0.0, -1.0, 0.0]]);
    let (mut triangles, mut indices) = (Vec::new(), Vec::new());
    for k in 0..6u16 {
        let k1 = (k + 1) % 6;
        if k % 2 == 0 {
            triangles.extend([[k, k1, 6 + k1], [k, 6 + k1, 6 + k]]);
            indices.extend([[k, k1, k1], [k, k1, k]]);
        } else {
            triangles.extend([[k, k1, 6 + k], [k1, 6 + k1, 6 + k]]);
            indices.extend([[k, k1, k], [k1, k1, k]]);
        }
        triangles.extend([[12, k1, k], [6 + k, 6 + k1, 13]]);
        indices.extend([[6; 3], [7; 3]]);
    }
    MeshData {
        positions,
        triangles,
        normals: Some(BakeNormals::PerCorner { normals, indices }),
    }
}

/// `GRID`: 9 × 9 vertices over [-1, 1]² in x and y, bent into the shallow
/// dome z = 0.1 - 0.1 (x² + y²), facing +z; vertex `9 j + i` at
/// x = i/4 - 1, y = j/4 - 1; smooth analytic normals ∝ (0.2 x, 0.2 y, 1).
pub fn grid() -> MeshData {
    let mut positions = Vec::new();
    let mut normals = Vec::new();
    for j in 0..9 {
        for i in 0..9 {
            let (x, y) = (f64::from(i) / 4.0 - 1.0, f64::from(j) / 4.0 - 1.0);
            positions.push([x, y, 0.1 - 0.1 * (x * x + y * y)]);
            normals.push(normalize([0.2 * x, 0.2 * y, 1.0]).expect("non-zero"));
        }
    }
    let mut triangles = Vec::new();
    for j in 0..8u16 {
        for i in 0..8u16 {
            let a = 9 * j + i;
            triangles.extend([[a, a + 1, a + 10], [a, a + 10, a + 9]]);
        }
    }
    MeshData {
        positions,
        triangles,
        normals: Some(BakeNormals::PerVertex(normals)),
    }
}

/// `BUNNY`: the OBJ at `obj` (loaded by tobj, triangulated, single index),
/// centred on its bounding-box centre and scaled by 2 / largest extent;
/// triangles flipped if needed so that the signed volume is positive;
/// normals by [`averaged_normals`] on the scaled f64 positions.
pub fn bunny(obj: &Path) -> Result<MeshData, tobj::LoadError> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let (models, _) = tobj::load_obj(obj, &options)?;
    let (mut raw, mut triangles) = (Vec::new(), Vec::new());
    for model in &models {
        let base = raw.len();
        raw.extend(
            model
                .mesh
                .positions
                .chunks_exact(3)
                .map(|p| [p[0], p[1], p[2]]),
        );
        for t in model.mesh.indices.chunks_exact(3) {
            triangles.push([t[0], t[1], t[2]].map(|i| index(base + i as usize)));
        }
    }
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in &raw {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let centre: [f64; 3] = std::array::from_fn(|k| (lo[k] + hi[k]) / 2.0);
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let scale = 2.0 / extent;
    let positions: Vec<[f64; 3]> = raw
        .iter()
        .map(|p| std::array::from_fn(|k| (p[k] - centre[k]) * scale))
        .collect();
    if signed_volume6(&positions, &triangles) < 0.0 {
        for t in &mut triangles {
            t.swap(1, 2);
        }
    }
    let normals = averaged_normals(&positions, &triangles);
    Ok(MeshData {
        positions,
        triangles,
        normals: Some(BakeNormals::PerVertex(normals)),
    })
}

/// Every built-in mesh, the bunny read from `root/assets/bunny.obj`
/// (`root` is the repository root).
pub fn built_ins(root: &Path) -> Result<Vec<BuiltIn>, tobj::LoadError> {
    Ok(vec![
        BuiltIn {
            name: "CUBE",
            file: "cube.rs",
            doc: &[
                "Cube of side 2 centred on the origin: 8 corners, 12 triangles,",
                "flat faces (6 normals, one per face): 24 vertices, one per face",
                "corner.",
            ],
            data: cube(),
        },
        BuiltIn {
            name: "DODECAHEDRON",
            file: "dodecahedron.rs",
            doc: &[
                "Regular dodecahedron inscribed in the unit sphere: 20 corners,",
                "36 triangles (3 per pentagon), flat faces (12 normals): 60",
                "vertices, one per face corner.",
            ],
            data: dodecahedron(),
        },
        BuiltIn {
            name: "SPHERE",
            file: "sphere.rs",
            doc: &[
                "UV sphere of radius 1, 15 slices by 15 stacks, poles on ±y:",
                "212 vertices, 420 triangles, smooth normals (one per vertex).",
            ],
            data: sphere(15, 15),
        },
        BuiltIn {
            name: "CAN",
            file: "can.rs",
            doc: &[
                "Six-sided can of radius 0.6 and height 1.6 about the y axis:",
                "14 positions, 24 triangles; smooth sides (6 radial normals) and",
                "flat caps (±y): 26 vertices (ring positions once per side and",
                "cap normal).",
            ],
            data: can(),
        },
        BuiltIn {
            name: "GRID",
            file: "grid.rs",
            doc: &[
                "9 × 9 vertex grid over [-1, 1]² in x and y, bent into the shallow",
                "dome z = 0.1 - 0.1 (x² + y²) facing +z, for hot-spot scenes: 81",
                "vertices, 128 triangles, smooth analytic normals.",
            ],
            data: grid(),
        },
        BuiltIn {
            name: "BUNNY",
            file: "bunny.rs",
            doc: &[
                "The Stanford bunny (`assets/bunny.obj`, public domain, from the npm",
                "package \"bunny\" 1.0.1): 1839 vertices, 3674 triangles, centred on",
                "its bounding-box centre and scaled by 2 / largest extent into",
                "[-1, 1]³; per-vertex normals are the normalised sums of the unit",
                "face normals (no area weighting), computed in f64.",
            ],
            data: bunny(&root.join("assets/bunny.obj"))?,
        },
    ])
}

/// The path of each built-in's source file under `root` and its text.
pub fn built_in_sources(root: &Path) -> Result<Vec<(PathBuf, String)>, tobj::LoadError> {
    Ok(built_ins(root)?
        .into_iter()
        .map(|b| {
            let MeshData {
                positions,
                triangles,
                normals,
            } = &b.data;
            let text = bake_rs(b.name, b.doc, positions, triangles, normals.as_ref());
            (root.join("src/mesh/shapes").join(b.file), text)
        })
        .collect())
}
