//! Vertex normal generation with crease angles and smoothing groups.

use super::crease::Crease;
use super::data::Mesh;
use super::error::NormalsError;
use crate::geom::exact::{face_normal_q30, unit};

/// Largest triangle count [`generate_normals`] accepts: face numbers are
/// stored in u16 adjacency entries.
pub const MAX_TRIANGLES: usize = u16::MAX as usize + 1;

/// Face normals of up to this many faces around one vertex are computed
/// once and kept on the stack; beyond it they are recomputed as needed.
const CACHE: usize = 16;

/// A sum of Q1.30 normals whose largest component is below this (1 ulp of
/// Q1.14) counts as cancelled.
const CANCELLED_Q30: i64 = 1 << 16;

/// Which faces around a vertex are smoothed together.
///
/// A corner of face `f` averages the unit normals of the faces `g` around
/// its vertex with `g == f`, or with both
/// - `groups[f] & groups[g] != 0` (when `groups` is given), and
/// - an angle between the normals of `f` and `g` of at most `crease`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Smoothing<'a> {
    /// The crease angle.
    pub crease: Crease,
    /// Optional smoothing group bitmask per triangle, 3ds/OBJ style: faces
    /// share a normal only if their masks intersect; mask 0 is flat and
    /// shares with no other face. `None` puts every face in one group.
    pub groups: Option<&'a [u32]>,
}

impl Smoothing<'_> {
    /// Every face at a vertex counts: one normal per vertex.
    pub const SMOOTH: Smoothing<'static> = Smoothing {
        crease: Crease::SMOOTH,
        groups: None,
    };

    /// Smoothing by crease angle only, no groups.
    pub const fn crease(crease: Crease) -> Smoothing<'static> {
        Smoothing {
            crease,
            groups: None,
        }
    }
}

/// Generates per-corner unit normals (Q1.14) for `mesh` from its positions;
/// returns the number of normals written to `normals`.
///
/// See the [module docs](super#vertex-normal-generation) for the rules and
/// error bounds. Buffers (T = triangle count, V = vertex count):
///
/// - `adjacency`: scratch, at least 3·T entries (the faces around each
///   vertex, filled by a counting sort);
/// - `offsets`: scratch, at least V + 1 entries (where each vertex's faces
///   start in `adjacency`);
/// - `normals`: output, 3·T entries always suffice; a fully smooth mesh
///   needs one per used vertex;
/// - `normal_indices`: output, at least T entries; entry `t` names the
///   normals of the corners of triangle `t`, as in
///   [`CornerNormals`](super::CornerNormals).
///
/// Normals are written vertex by vertex, each distinct normal of a vertex
/// once, in the order of the vertex's faces; for a fully smooth mesh whose
/// vertices are all used, normal `i` belongs to vertex `i`.
///
/// The work is O(T · valence) face normal computations (each with one
/// integer square root) and no allocation. Mesh normals already present
/// are ignored.
pub fn generate_normals(
    mesh: &Mesh<'_>,
    smoothing: &Smoothing<'_>,
    adjacency: &mut [u16],
    offsets: &mut [u32],
    normals: &mut [[i16; 3]],
    normal_indices: &mut [[u16; 3]],
) -> Result<usize, NormalsError> {
    let tris = mesh.triangles();
    let (t_count, v_count) = (tris.len(), mesh.vertex_count());
    check_buffers(
        t_count,
        v_count,
        smoothing,
        adjacency,
        offsets,
        normal_indices,
    )?;
    let adjacency = &mut adjacency[..3 * t_count];
    let offsets = &mut offsets[..=v_count];
    build_adjacency(tris, adjacency, offsets);

    let positions = mesh.positions();
    let face_n = |f: u16| {
        let [a, b, c] = tris[usize::from(f)];
        face_normal_q30(
            positions[usize::from(a)],
            positions[usize::from(b)],
            positions[usize::from(c)],
        )
    };
    let capacity = normals.len().min(MAX_TRIANGLES);
    let mut count = 0;
    for vertex in 0..v_count {
        // Offsets are at most 3·T, which fits usize.
        let faces = &adjacency[offsets[vertex] as usize..offsets[vertex + 1] as usize];
        let mut cache = [[0i32; 3]; CACHE];
        let cached = faces.len() <= CACHE;
        if cached {
            for (slot, &f) in cache.iter_mut().zip(faces) {
                *slot = face_n(f);
            }
        }
        let normal_at = |i: usize| if cached { cache[i] } else { face_n(faces[i]) };
        let first = count;
        for (i, &f) in faces.iter().enumerate() {
            if i > 0 && faces[i - 1] == f {
                // A face listed twice: its corners were set the first time.
                continue;
            }
            let own = normal_at(i);
            let mut sum = [0i64; 3];
            if own != [0; 3] {
                for (j, &g) in faces.iter().enumerate() {
                    if j > 0 && faces[j - 1] == g {
                        continue;
                    }
                    let other = normal_at(j);
                    if g == f || shares(smoothing, f, g, own, other) {
                        for (s, o) in sum.iter_mut().zip(other) {
                            *s += i64::from(o);
                        }
                    }
                }
                if sum.iter().all(|s| s.abs() < CANCELLED_Q30) {
                    sum = own.map(i64::from);
                }
            }
            let n = to_q14(sum);
            let index = match normals[first..count].iter().position(|&m| m == n) {
                Some(k) => first + k,
                None if count < capacity => {
                    normals[count] = n;
                    count += 1;
                    count - 1
                }
                None => {
                    return Err(NormalsError::NormalsFull {
                        capacity,
                        triangle: usize::from(f),
                    })
                }
            };
            let tri = tris[usize::from(f)];
            for (slot, &v) in normal_indices[usize::from(f)].iter_mut().zip(&tri) {
                if usize::from(v) == vertex {
                    // index < capacity <= 65536.
                    *slot = index as u16;
                }
            }
        }
    }
    Ok(count)
}

/// Whether faces `f` and `g` (normals `nf`, `ng`) may share a normal.
fn shares(smoothing: &Smoothing<'_>, f: u16, g: u16, nf: [i32; 3], ng: [i32; 3]) -> bool {
    if ng == [0; 3] {
        return false;
    }
    if let Some(groups) = smoothing.groups {
        if groups[usize::from(f)] & groups[usize::from(g)] == 0 {
            return false;
        }
    }
    smoothing.crease.allows(nf, ng)
}

/// Normalises a sum of Q1.30 normals to Q1.14; zero stays zero.
fn to_q14(sum: [i64; 3]) -> [i16; 3] {
    match unit(sum, 14) {
        // Magnitudes are at most 16384.
        Some(u) => u.map(|c| c as i16),
        None => [0; 3],
    }
}

/// Checks the sizes of all tables and buffers.
fn check_buffers(
    t_count: usize,
    v_count: usize,
    smoothing: &Smoothing<'_>,
    adjacency: &[u16],
    offsets: &[u32],
    normal_indices: &[[u16; 3]],
) -> Result<(), NormalsError> {
    if t_count > MAX_TRIANGLES {
        return Err(NormalsError::TooManyTriangles { count: t_count });
    }
    if let Some(groups) = smoothing.groups {
        if groups.len() != t_count {
            return Err(NormalsError::GroupCountMismatch {
                triangles: t_count,
                groups: groups.len(),
            });
        }
    }
    if adjacency.len() < 3 * t_count {
        return Err(NormalsError::AdjacencyTooSmall {
            needed: 3 * t_count,
            len: adjacency.len(),
        });
    }
    if offsets.len() < v_count + 1 {
        return Err(NormalsError::OffsetsTooSmall {
            needed: v_count + 1,
            len: offsets.len(),
        });
    }
    if normal_indices.len() < t_count {
        return Err(NormalsError::IndicesTooSmall {
            needed: t_count,
            len: normal_indices.len(),
        });
    }
    Ok(())
}

/// Counting sort of the triangle corners by vertex: afterwards the faces
/// around vertex `v` are `adjacency[offsets[v]..offsets[v + 1]]`, in
/// increasing face order (a face with a repeated vertex appears twice, in
/// a row). `adjacency` has 3·T entries, `offsets` V + 1, T <= 65536.
fn build_adjacency(tris: &[[u16; 3]], adjacency: &mut [u16], offsets: &mut [u32]) {
    offsets.fill(0);
    for &v in tris.iter().flatten() {
        offsets[usize::from(v)] += 1;
    }
    // Start of each vertex's run; the last entry is 3·T.
    let mut start = 0;
    for slot in offsets.iter_mut() {
        let n = *slot;
        *slot = start;
        start += n;
    }
    for (f, tri) in tris.iter().enumerate() {
        for &v in tri {
            let slot = &mut offsets[usize::from(v)];
            // f < 65536 as checked by the caller.
            adjacency[*slot as usize] = f as u16;
            *slot += 1;
        }
    }
    // Each entry now holds the end of its run, the start of the next.
    offsets.copy_within(..offsets.len() - 1, 1);
    offsets[0] = 0;
}
