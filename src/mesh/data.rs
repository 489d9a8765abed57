//! The [`Mesh`] type: checked references to constant mesh tables.

use super::error::MeshError;
use crate::geom::bound::Bound;
use crate::geom::exact::{cone_covers, face_plane, MAX_AXIS2};

/// Fractional bits of a position coordinate: Q1.14, value = raw / 16384.
pub const POSITION_FRAC_BITS: u32 = 14;

/// Fractional bits of a normal component: Q1.14, value = raw / 16384.
pub const NORMAL_FRAC_BITS: u32 = 14;

/// 1.0 in Q1.14, the length of a unit normal.
pub const NORMAL_ONE: i16 = 1 << NORMAL_FRAC_BITS;

/// Largest vertex count of a [`Mesh`].
pub const MAX_VERTICES: usize = u16::MAX as usize;

/// Per-corner normals of a mesh, OBJ style.
///
/// `indices[t][c]` is the index in `normals` of the normal of corner `c`
/// of triangle `t`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CornerNormals<'a> {
    /// Unit normals, Q1.14 (16384 = 1.0).
    pub normals: &'a [[i16; 3]],
    /// Normal index of each triangle corner, one entry per triangle.
    pub indices: &'a [[u16; 3]],
}

/// A triangle mesh: references to checked tables (see the
/// [module docs](super) for the formats).
///
/// One entry per distinct (position, normal) pair: `positions[i]` and
/// `normals[i]` describe vertex `i`, and triangles index them, so the
/// geometry stage transforms, projects and lights each vertex once in one
/// pass over the arrays. A vertex on a crease appears once per normal.
/// Optional face normals (one unit normal per triangle, the exact
/// [`face_normal`](super::face_normal) of its corners) spare flat shading
/// the per-face cross product and square root.
///
/// Once made by [`Mesh::new`], every index is in range, so lookups through
/// the accessors never fail for in-range triangle numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mesh<'a> {
    positions: &'a [[i16; 3]],
    triangles: &'a [[u16; 3]],
    normals: &'a [[i16; 3]],
    face_normals: &'a [[i16; 3]],
    cones: &'a [[i32; 2]],
    bound: Bound,
}

impl<'a> Mesh<'a> {
    /// Checks the tables and makes a mesh.
    ///
    /// Checks, in this order: at least one vertex and one triangle, at most
    /// [`MAX_VERTICES`] vertices, every vertex index in range, then, with
    /// normals, one normal per vertex. Normal vectors are not checked for
    /// unit length. Computes the bounding sphere ([`Mesh::bound`]).
    ///
    /// Usable in a `const` item, where an error can become a compile error:
    ///
    /// ```
    /// use fixshade::mesh::Mesh;
    /// const TRI: Mesh = match Mesh::new(&[[0, 0, 0], [16384, 0, 0], [0, 16384, 0]], &[[0, 1, 2]], None) {
    ///     Ok(mesh) => mesh,
    ///     Err(_) => panic!("bad mesh"),
    /// };
    /// assert_eq!(TRI.triangle_count(), 1);
    /// ```
    ///
    /// A bad index in such a constant fails the build:
    ///
    /// ```compile_fail
    /// use fixshade::mesh::Mesh;
    /// const BAD: Mesh = match Mesh::new(&[[0, 0, 0]], &[[0, 0, 1]], None) {
    ///     Ok(mesh) => mesh,
    ///     Err(_) => panic!("bad mesh"),
    /// };
    /// let _ = BAD;
    /// ```
    pub const fn new(
        positions: &'a [[i16; 3]],
        triangles: &'a [[u16; 3]],
        normals: Option<&'a [[i16; 3]]>,
    ) -> Result<Self, MeshError> {
        if positions.is_empty() || triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if positions.len() > MAX_VERTICES {
            return Err(MeshError::TooManyVertices {
                count: positions.len(),
            });
        }
        if let Some(triangle) = first_out_of_range(triangles, positions.len()) {
            return Err(MeshError::VertexIndexOutOfRange {
                triangle,
                index: largest(triangles[triangle]),
            });
        }
        let normals: &'a [[i16; 3]] = match normals {
            None => &[],
            Some(n) => {
                if n.len() != positions.len() {
                    return Err(MeshError::NormalCountMismatch {
                        vertices: positions.len(),
                        normals: n.len(),
                    });
                }
                n
            }
        };
        Ok(Mesh {
            positions,
            triangles,
            normals,
            face_normals: &[],
            cones: &[],
            bound: Bound::of(positions),
        })
    }

    /// The mesh with baked face normals: one unit normal per triangle,
    /// Q1.14 (what [`face_normal`](super::face_normal) gives for its
    /// corners: flat shading then reads it instead of computing it).
    ///
    /// # Errors
    /// [`MeshError::FaceNormalCountMismatch`] unless there is one per
    /// triangle.
    pub const fn with_face_normals(self, face_normals: &'a [[i16; 3]]) -> Result<Self, MeshError> {
        if face_normals.len() != self.triangles.len() {
            return Err(MeshError::FaceNormalCountMismatch {
                triangles: self.triangles.len(),
                face_normals: face_normals.len(),
            });
        }
        Ok(Self {
            face_normals,
            ..self
        })
    }

    /// The mesh with baked culling cones, one `[d, slack | spread << 16]`
    /// per vertex, with which the geometry stage skips the vertices all
    /// of whose faces it can prove back-facing in object space, before
    /// transforming them. For vertex `v` with position `P` and vertex
    /// normal `a` (the cone's axis, `|a|² <=` [`MAX_AXIS2`](super::MAX_AXIS2)):
    ///
    /// - `d = a · P` exactly (Q2.28, `|d| < 2^30`);
    /// - `slack` (bits 0..16) at least the [`face_plane`](super::face_plane)
    ///   slack of every face using `v`, 65 535 when none can be bounded;
    /// - `spread` (bits 16..32) such that every face using `v` has its unit
    ///   normal within `spread / 2^14` of `a / 2^14`
    ///   ([`cone_covers`](super::cone_covers)).
    ///
    /// `fixshade bake` and the built-in meshes compute them; this checks
    /// them against the corners (in a `const` item: at compile time).
    ///
    /// # Errors
    /// [`MeshError::ConeCountMismatch`] unless the mesh has vertex normals
    /// and one cone per vertex; [`MeshError::ConeMismatch`] naming the first
    /// vertex whose cone does not hold.
    pub const fn with_vertex_cones(self, cones: &'a [[i32; 2]]) -> Result<Self, MeshError> {
        let nv = self.positions.len();
        if cones.len() != nv || self.normals.len() != nv {
            return Err(MeshError::ConeCountMismatch {
                vertices: nv,
                cones: cones.len(),
            });
        }
        let mut v = 0;
        while v < nv {
            let a = self.normals[v];
            let p = self.positions[v];
            let aa =
                a[0] as i64 * a[0] as i64 + a[1] as i64 * a[1] as i64 + a[2] as i64 * a[2] as i64;
            let d =
                a[0] as i64 * p[0] as i64 + a[1] as i64 * p[1] as i64 + a[2] as i64 * p[2] as i64;
            if aa > MAX_AXIS2 || d != cones[v][0] as i64 {
                return Err(MeshError::ConeMismatch { vertex: v });
            }
            v += 1;
        }
        let mut t = 0;
        while t < self.triangles.len() {
            // Indices were checked by `Mesh::new`.
            let tri = self.triangles[t];
            let (p, q, r) = (
                self.positions[tri[0] as usize],
                self.positions[tri[1] as usize],
                self.positions[tri[2] as usize],
            );
            let slack = face_plane(p, q, r)[1];
            let mut k = 0;
            while k < 3 {
                let v = tri[k] as usize;
                let c = cones[v][1];
                let (s, spread) = (c & 0xFFFF, ((c >> 16) & 0xFFFF) as u16);
                if s < slack || !cone_covers(self.normals[v], spread, p, q, r) {
                    return Err(MeshError::ConeMismatch { vertex: v });
                }
                k += 1;
            }
            t += 1;
        }
        Ok(Self { cones, ..self })
    }

    /// The baked culling cones (one per vertex, see
    /// [`Mesh::with_vertex_cones`]), if the mesh has them.
    pub const fn vertex_cones(&self) -> Option<&'a [[i32; 2]]> {
        if self.cones.is_empty() {
            None
        } else {
            Some(self.cones)
        }
    }

    /// Vertex positions, Q1.14.
    pub const fn positions(&self) -> &'a [[i16; 3]] {
        self.positions
    }

    /// Triangles as vertex index triples, counter-clockwise front faces.
    pub const fn triangles(&self) -> &'a [[u16; 3]] {
        self.triangles
    }

    /// The vertex normals (one per position), if the mesh has them.
    pub const fn vertex_normals(&self) -> Option<&'a [[i16; 3]]> {
        if self.normals.is_empty() {
            None
        } else {
            Some(self.normals)
        }
    }

    /// The baked face normals (one per triangle), if the mesh has them.
    pub const fn face_normals(&self) -> Option<&'a [[i16; 3]]> {
        if self.face_normals.is_empty() {
            None
        } else {
            Some(self.face_normals)
        }
    }

    /// The normals seen per corner, OBJ style: the vertex normals, indexed
    /// by the triangles.
    pub const fn normals(&self) -> Option<CornerNormals<'a>> {
        if self.normals.is_empty() {
            None
        } else {
            Some(CornerNormals {
                normals: self.normals,
                indices: self.triangles,
            })
        }
    }

    /// Whether the mesh has vertex normals.
    pub const fn has_normals(&self) -> bool {
        !self.normals.is_empty()
    }

    /// Number of vertices (positions), at least 1.
    pub const fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles, at least 1.
    pub const fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of stored vertex normals: the vertex count, or 0 without
    /// normals.
    pub const fn normal_count(&self) -> usize {
        self.normals.len()
    }

    /// The bounding sphere of the positions.
    pub const fn bound(&self) -> Bound {
        self.bound
    }

    /// The three corner positions of triangle `tri`, or `None` if `tri` is
    /// out of range.
    pub fn triangle_positions(&self, tri: usize) -> Option<[[i16; 3]; 3]> {
        let [a, b, c] = *self.triangles.get(tri)?;
        // Indices were checked by `Mesh::new`: `get` never fails.
        let p = |i: u16| self.positions.get(usize::from(i)).copied();
        Some([p(a)?, p(b)?, p(c)?])
    }

    /// The Q1.14 normal of corner `corner` (0, 1 or 2) of triangle `tri`;
    /// `None` without normals or if `tri` or `corner` is out of range.
    pub fn corner_normal(&self, tri: usize, corner: usize) -> Option<[i16; 3]> {
        let index = *self.triangles.get(tri)?.get(corner)?;
        self.normals.get(usize::from(index)).copied()
    }
}

/// Welds OBJ-style per-corner normals into a [`Mesh`]'s form: one vertex
/// per distinct (position, normal) pair, numbered in order of first use by
/// the triangles (corner by corner). Writes the vertices' positions and
/// normals and the renumbered triangles; returns the vertex count.
///
/// `scratch` needs one entry per position plus one per output vertex:
/// the vertices made from each position are chained through it, so each
/// corner is looked up among the vertices of its own position only.
///
/// # Errors
/// [`MeshError::NormalCountMismatch`] when `corner.indices` does not have
/// one triple per triangle (its fields name triangles and triples),
/// [`MeshError::NormalIndexOutOfRange`] and
/// [`MeshError::VertexIndexOutOfRange`] for bad indices,
/// [`MeshError::OutputTooSmall`] when an output or `scratch` is too short,
/// [`MeshError::TooManyVertices`] beyond [`MAX_VERTICES`] pairs.
pub fn weld(
    positions: &[[i16; 3]],
    triangles: &[[u16; 3]],
    corner: CornerNormals<'_>,
    out_positions: &mut [[i16; 3]],
    out_normals: &mut [[i16; 3]],
    out_triangles: &mut [[u16; 3]],
    scratch: &mut [u16],
) -> Result<usize, MeshError> {
    const NONE: u16 = u16::MAX;
    if corner.indices.len() != triangles.len() {
        return Err(MeshError::NormalCountMismatch {
            vertices: triangles.len(),
            normals: corner.indices.len(),
        });
    }
    if let Some(triangle) = first_out_of_range(triangles, positions.len()) {
        return Err(MeshError::VertexIndexOutOfRange {
            triangle,
            index: largest(triangles[triangle]),
        });
    }
    if let Some(triangle) = first_out_of_range(corner.indices, corner.normals.len()) {
        return Err(MeshError::NormalIndexOutOfRange {
            triangle,
            index: largest(corner.indices[triangle]),
        });
    }
    if out_triangles.len() < triangles.len() || scratch.len() < positions.len() {
        return Err(MeshError::OutputTooSmall);
    }
    let (heads, next) = scratch.split_at_mut(positions.len());
    heads.fill(NONE);
    let cap = out_positions.len().min(out_normals.len()).min(next.len());
    let mut count = 0usize;
    for ((tri, nidx), out) in triangles
        .iter()
        .zip(corner.indices)
        .zip(out_triangles.iter_mut())
    {
        for c in 0..3 {
            let (p, n) = (usize::from(tri[c]), usize::from(nidx[c]));
            let normal = corner.normals.get(n).copied().unwrap_or([0; 3]);
            let mut v = heads.get(p).copied().unwrap_or(NONE);
            while v != NONE && out_normals.get(usize::from(v)) != Some(&normal) {
                v = next.get(usize::from(v)).copied().unwrap_or(NONE);
            }
            if v == NONE {
                if count >= MAX_VERTICES {
                    return Err(MeshError::TooManyVertices { count: count + 1 });
                }
                if count >= cap {
                    return Err(MeshError::OutputTooSmall);
                }
                out_positions[count] = positions.get(p).copied().unwrap_or([0; 3]);
                out_normals[count] = normal;
                next[count] = heads.get(p).copied().unwrap_or(NONE);
                if let Some(h) = heads.get_mut(p) {
                    // count < MAX_VERTICES = u16::MAX: fits, and differs from NONE.
                    *h = count as u16;
                }
                v = count as u16;
                count += 1;
            }
            out[c] = v;
        }
    }
    Ok(count)
}

/// Index of the first triple with an entry `>= len`.
const fn first_out_of_range(triples: &[[u16; 3]], len: usize) -> Option<usize> {
    let mut t = 0;
    while t < triples.len() {
        if largest(triples[t]) as usize >= len {
            return Some(t);
        }
        t += 1;
    }
    None
}

/// Largest entry of a triple.
const fn largest(triple: [u16; 3]) -> u16 {
    let mut m = triple[0];
    if triple[1] > m {
        m = triple[1];
    }
    if triple[2] > m {
        m = triple[2];
    }
    m
}
