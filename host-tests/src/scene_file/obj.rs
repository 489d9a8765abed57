//! Wavefront OBJ loading for scene files and `fixshade bake`.
//!
//! The text is first checked line by line here (so that errors name a line
//! and no malformed index ever reaches the loader), then loaded by `tobj`
//! with `triangulate` and `single_index` (polygons become triangle fans;
//! points and lines are ignored; materials are not read). Several objects
//! or groups are concatenated. The triangles keep the file's winding.
//!
//! Checks: every `v` and `vn` has three finite numbers; every face index is
//! a non-zero integer naming a position, texture coordinate or normal
//! defined before the face (negative indices count back from the last
//! one); at least one triangle; at most [`MAX_VERTICES`] vertices after
//! `single_index` (one vertex per distinct position/texcoord/normal
//! triple).

use std::io::BufReader;
use std::path::Path;

use fixshade::mesh::MAX_VERTICES;

use crate::bake;

/// An OBJ mesh in file coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjData {
    /// Vertex positions as written in the file.
    pub positions: Vec<[f64; 3]>,
    /// Triangles, in the file's winding.
    pub triangles: Vec<[u16; 3]>,
    /// One normal per vertex (as written, not normalised) when every face
    /// corner of the file names a normal; `None` otherwise.
    pub normals: Option<Vec<[f64; 3]>>,
}

/// Why an OBJ file was rejected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ObjError {
    /// One-based line of the OBJ file, if the problem has one.
    pub line: Option<usize>,
    /// What is wrong.
    pub problem: String,
}

impl ObjError {
    fn new(line: Option<usize>, problem: impl Into<String>) -> Self {
        Self {
            line,
            problem: problem.into(),
        }
    }
}

impl std::fmt::Display for ObjError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.line {
            Some(line) => write!(f, "line {line}: {}", self.problem),
            None => f.write_str(&self.problem),
        }
    }
}

impl std::error::Error for ObjError {}

/// Reads and checks the OBJ file at `path` (see the [module docs](self)).
pub fn read_obj(path: &Path) -> Result<ObjData, ObjError> {
    let bytes =
        std::fs::read(path).map_err(|e| ObjError::new(None, format!("cannot read: {e}")))?;
    parse_obj(&String::from_utf8_lossy(&bytes))
}

/// Checks and loads OBJ text (see the [module docs](self)).
pub fn parse_obj(text: &str) -> Result<ObjData, ObjError> {
    let every_corner_has_normal = prescan(text)?;
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let mut reader = BufReader::new(text.as_bytes());
    let (models, _materials) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| ObjError::new(None, format!("not a valid OBJ file: {e}")))?;

    let (mut positions, mut triangles, mut normals) = (Vec::new(), Vec::new(), Vec::new());
    let mut have_normals = every_corner_has_normal;
    for model in &models {
        let mesh = &model.mesh;
        let base = positions.len();
        let count = mesh.positions.len() / 3;
        if base + count > MAX_VERTICES {
            return Err(ObjError::new(
                None,
                format!(
                    "more than {MAX_VERTICES} vertices (distinct position/texcoord/normal triples)"
                ),
            ));
        }
        positions.extend(mesh.positions.chunks_exact(3).map(|p| [p[0], p[1], p[2]]));
        if mesh.normals.len() == mesh.positions.len() {
            normals.extend(mesh.normals.chunks_exact(3).map(|n| [n[0], n[1], n[2]]));
        } else {
            have_normals = false;
        }
        for t in mesh.indices.chunks_exact(3) {
            let mut tri = [0u16; 3];
            for (slot, &i) in tri.iter_mut().zip(t) {
                // base + i < positions.len() <= MAX_VERTICES = 65535.
                *slot = u16::try_from(base + i as usize).map_err(|_| {
                    ObjError::new(None, "a face names a vertex out of range".to_string())
                })?;
                if usize::from(*slot) >= positions.len() {
                    return Err(ObjError::new(None, "a face names a vertex out of range"));
                }
            }
            triangles.push(tri);
        }
    }
    if triangles.is_empty() {
        return Err(ObjError::new(
            None,
            "no triangles (no face with 3 or more corners)",
        ));
    }
    Ok(ObjData {
        positions,
        triangles,
        normals: have_normals.then_some(normals),
    })
}

/// Checks numbers and face indices line by line; returns whether every
/// face corner names a normal.
fn prescan(text: &str) -> Result<bool, ObjError> {
    let (mut v, mut vt, mut vn) = (0usize, 0usize, 0usize);
    let mut all_normals = true;
    for (number, line) in text.lines().enumerate() {
        let line_no = Some(number + 1);
        let mut words = line.split_whitespace();
        match words.next() {
            Some(kind @ ("v" | "vn")) => {
                let what = if kind == "v" {
                    "vertex position"
                } else {
                    "normal"
                };
                for _ in 0..3 {
                    let Some(word) = words.next() else {
                        return Err(ObjError::new(
                            line_no,
                            format!("{what} has fewer than 3 numbers"),
                        ));
                    };
                    let x: f64 = word.parse().map_err(|_| {
                        ObjError::new(
                            line_no,
                            format!("{what} has `{word}`, which is not a number"),
                        )
                    })?;
                    if !x.is_finite() {
                        return Err(ObjError::new(
                            line_no,
                            format!("{what} has `{word}`, which is not finite"),
                        ));
                    }
                }
                if kind == "v" {
                    v += 1;
                } else {
                    vn += 1;
                }
            }
            Some("vt") => vt += 1,
            Some("f") => {
                for corner in words {
                    let parts: Vec<&str> = corner.split('/').collect();
                    if parts.len() > 3 {
                        return Err(ObjError::new(
                            line_no,
                            format!("face corner `{corner}` has more than 3 indices"),
                        ));
                    }
                    for (k, (part, defined, what)) in parts
                        .iter()
                        .zip([(v, "vertex"), (vt, "texture coordinate"), (vn, "normal")])
                        .map(|(p, (d, w))| (p, d, w))
                        .enumerate()
                    {
                        if part.is_empty() {
                            if k == 0 {
                                return Err(ObjError::new(
                                    line_no,
                                    format!("face corner `{corner}` has no vertex index"),
                                ));
                            }
                            continue;
                        }
                        check_index(part, defined, what, line_no)?;
                    }
                    if !matches!(parts.get(2), Some(p) if !p.is_empty()) {
                        all_normals = false;
                    }
                }
            }
            _ => {}
        }
    }
    Ok(all_normals)
}

/// Checks one face index against the number of items defined so far.
fn check_index(
    word: &str,
    defined: usize,
    what: &str,
    line: Option<usize>,
) -> Result<(), ObjError> {
    let bad = |why: String| ObjError::new(line, format!("face {what} index `{word}` {why}"));
    let i: i64 = word
        .parse()
        .map_err(|_| bad("is not an integer".to_string()))?;
    let defined_i = i64::try_from(defined).unwrap_or(i64::MAX);
    let ok = if i > 0 {
        i <= defined_i
    } else if i < 0 {
        i >= -defined_i
    } else {
        return Err(bad("is 0 (indices start at 1)".to_string()));
    };
    if ok {
        Ok(())
    } else {
        Err(bad(format!(
            "is out of range: {defined} {what}(s) defined before this face"
        )))
    }
}

/// Positions centred on their bounding-box centre and scaled by
/// 2 / largest extent, so that they fit [-1, 1]³ (as the bunny).
#[derive(Clone, Debug, PartialEq)]
pub struct Normalized {
    /// `(p - centre) * factor` for every position `p`.
    pub positions: Vec<[f64; 3]>,
    /// The bounding-box centre.
    pub centre: [f64; 3],
    /// `2 / largest extent`.
    pub factor: f64,
}

/// Centres and scales `positions` (see [`Normalized`]). Fails when the
/// positions are all equal or so spread out that the extent overflows.
pub fn normalize_positions(positions: &[[f64; 3]]) -> Result<Normalized, ObjError> {
    let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let centre: [f64; 3] = std::array::from_fn(|k| lo[k] / 2.0 + hi[k] / 2.0);
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    if !(extent.is_finite() && extent > 0.0) {
        return Err(ObjError::new(
            None,
            "vertex positions have no extent (all equal) or an extent too large for f64",
        ));
    }
    let factor = 2.0 / extent;
    if !factor.is_finite() {
        return Err(ObjError::new(
            None,
            "vertex positions span too small an extent",
        ));
    }
    let positions = positions
        .iter()
        .map(|p| std::array::from_fn(|k| (p[k] - centre[k]) * factor))
        .collect();
    Ok(Normalized {
        positions,
        centre,
        factor,
    })
}

/// Per-corner normals in f64: the normals and the normal index of each
/// triangle corner.
pub type CornerNormalsF64 = (Vec<[f64; 3]>, Vec<[u16; 3]>);

/// Per-corner normals in f64 with a crease angle: the corner of face `f`
/// at vertex `v` gets the normalised sum of the unit face normals of the
/// faces `g` at `v` with `g == f` or an angle to `f` of at most
/// `crease_deg` (not area-weighted; zero-area faces count for nothing and
/// their corners get (0, 0, 0)). Equal normals of a vertex are stored
/// once. These are the rules of the core's `generate_normals`, in f64.
///
/// Fails if more than 65536 normals would be needed (u16 indices).
pub fn crease_normals(
    positions: &[[f64; 3]],
    triangles: &[[u16; 3]],
    crease_deg: f64,
) -> Result<CornerNormalsF64, ObjError> {
    let face: Vec<Option<[f64; 3]>> = triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| positions.get(usize::from(i)).copied().unwrap_or([0.0; 3]));
            bake::unit_face_normal(a, b, c)
        })
        .collect();
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); positions.len()];
    for (f, t) in triangles.iter().enumerate() {
        for &i in t {
            if let Some(list) = around.get_mut(usize::from(i)) {
                if list.last() != Some(&f) {
                    list.push(f);
                }
            }
        }
    }
    let cos_crease = crease_deg.to_radians().cos();
    let smooth = crease_deg >= 180.0;
    let mut normals: Vec<[f64; 3]> = Vec::new();
    let mut indices = vec![[0u16; 3]; triangles.len()];
    for (vertex, faces) in around.iter().enumerate() {
        let first = normals.len();
        for &f in faces {
            let n = match face[f] {
                None => [0.0; 3],
                Some(own) => {
                    let mut sum = [0.0; 3];
                    for &g in faces {
                        let Some(other) = face[g] else { continue };
                        let cos = own[0] * other[0] + own[1] * other[1] + own[2] * other[2];
                        if g == f || smooth || cos >= cos_crease {
                            for k in 0..3 {
                                sum[k] += other[k];
                            }
                        }
                    }
                    bake::normalize(sum)
                        .filter(|s| s.iter().all(|c| c.is_finite()))
                        .unwrap_or(own)
                }
            };
            let index = match normals[first..].iter().position(|&m| m == n) {
                Some(k) => first + k,
                None => {
                    normals.push(n);
                    normals.len() - 1
                }
            };
            let index = u16::try_from(index)
                .map_err(|_| ObjError::new(None, "more than 65536 distinct corner normals"))?;
            for (slot, &v) in indices[f].iter_mut().zip(&triangles[f]) {
                if usize::from(v) == vertex {
                    *slot = index;
                }
            }
        }
    }
    Ok((normals, indices))
}

#[cfg(test)]
mod tests {
    use super::*;

    const QUAD: &str = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n";

    #[test]
    fn quad_is_two_triangles() {
        let obj = parse_obj(QUAD).unwrap();
        assert_eq!(obj.positions.len(), 4);
        assert_eq!(obj.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(obj.normals, None);
        let n = normalize_positions(&obj.positions).unwrap();
        assert_eq!(n.centre, [1.0, 0.5, 0.0]);
        assert_eq!(n.factor, 1.0);
        assert_eq!(n.positions[0], [-1.0, -0.5, 0.0]);
    }

    #[test]
    fn normals_when_every_corner_has_one() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 2\nf 1//1 2//1 3//1\n";
        let obj = parse_obj(text).unwrap();
        assert_eq!(obj.normals, Some(vec![[0.0, 0.0, 2.0]; 3]));
        let partial = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2 3\n";
        assert_eq!(parse_obj(partial).unwrap().normals, None);
    }

    #[test]
    fn objects_are_concatenated_and_materials_ignored() {
        let text = "mtllib none.mtl\no a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n\
                    o b\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf 4 5 6\np 1\n";
        let obj = parse_obj(text).unwrap();
        assert_eq!(obj.positions.len(), 6);
        assert_eq!(obj.positions[3], [0.0, 0.0, 1.0]);
        assert_eq!(obj.triangles, vec![[0, 1, 2], [3, 4, 5]]);
    }

    #[test]
    fn negative_indices_count_back() {
        let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
        assert_eq!(parse_obj(text).unwrap().triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn errors_name_the_line() {
        let cases = [
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
                4,
                "out of range: 3 vertex(s)",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4, "is 0"),
            ("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", 2, "not finite"),
            ("v 0 0 0\nv 1 0\n", 2, "fewer than 3"),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2 3\n",
                4,
                "texture coordinate index",
            ),
            (
                "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//x 2 3\n",
                4,
                "not an integer",
            ),
            ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", 4, "out of range"),
        ];
        for (text, line, needle) in cases {
            let e = parse_obj(text).unwrap_err();
            assert_eq!(e.line, Some(line), "{text}");
            assert!(e.to_string().contains(needle), "{e} lacks {needle}");
        }
    }

    #[test]
    fn no_triangles() {
        let e = parse_obj("v 0 0 0\nv 1 0 0\nl 1 2\n").unwrap_err();
        assert!(e.problem.contains("no triangles"), "{e}");
        let e = normalize_positions(&[[1.0, 2.0, 3.0]; 3]).unwrap_err();
        assert!(e.problem.contains("no extent"), "{e}");
    }

    #[test]
    fn crease_normals_of_a_folded_pair() {
        // Two triangles sharing the edge 0-1, folded by 90 degrees.
        let p = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let t = [[0, 1, 2], [1, 0, 3]];
        let (n, i) = crease_normals(&p, &t, 180.0).unwrap();
        let s = std::f64::consts::FRAC_1_SQRT_2;
        // Face normals (0, 0, 1) and (0, 1, 0). Vertex 0: the smooth
        // (0, 1, 1) / sqrt 2 shared by both faces.
        assert_eq!(i[0][0], i[1][1]);
        let shared = n[usize::from(i[0][0])];
        assert!(shared[0] == 0.0 && (shared[1] - s).abs() < 1e-15 && (shared[2] - s).abs() < 1e-15);
        // Each lone corner keeps its face normal.
        assert_eq!(n[usize::from(i[0][2])], [0.0, 0.0, 1.0]);
        assert_eq!(n[usize::from(i[1][2])], [0.0, 1.0, 0.0]);
        let (n, i) = crease_normals(&p, &t, 89.0).unwrap();
        assert_ne!(i[0][0], i[1][1]);
        assert_eq!(n[usize::from(i[0][0])], [0.0, 0.0, 1.0]);
        assert_eq!(n[usize::from(i[1][1])], [0.0, 1.0, 0.0]);
        assert_eq!(n.len(), 6);
    }
}
