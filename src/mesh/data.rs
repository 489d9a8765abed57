//! The [`Mesh`] type: checked references to constant mesh tables.

use super::error::MeshError;

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

/// A triangle mesh: references to checked position, triangle and optional
/// normal tables (see the [module docs](super) for the formats).
///
/// Once made by [`Mesh::new`], every index is in range, so lookups through
/// the accessors never fail for in-range triangle numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mesh<'a> {
    positions: &'a [[i16; 3]],
    triangles: &'a [[u16; 3]],
    normals: &'a [[i16; 3]],
    normal_indices: &'a [[u16; 3]],
}

impl<'a> Mesh<'a> {
    /// Checks the tables and makes a mesh.
    ///
    /// Checks, in this order: at least one vertex and one triangle, at most
    /// [`MAX_VERTICES`] vertices, every vertex index in range, then, with
    /// normals, one normal index triple per triangle and every normal index
    /// in range. Normal vectors are not checked for unit length.
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
        normals: Option<CornerNormals<'a>>,
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
        let (normals, normal_indices): (&'a [[i16; 3]], &'a [[u16; 3]]) = match normals {
            None => (&[], &[]),
            Some(corner) => {
                if corner.indices.len() != triangles.len() {
                    return Err(MeshError::NormalCountMismatch {
                        triangles: triangles.len(),
                        normal_indices: corner.indices.len(),
                    });
                }
                if let Some(triangle) = first_out_of_range(corner.indices, corner.normals.len()) {
                    return Err(MeshError::NormalIndexOutOfRange {
                        triangle,
                        index: largest(corner.indices[triangle]),
                    });
                }
                (corner.normals, corner.indices)
            }
        };
        Ok(Mesh {
            positions,
            triangles,
            normals,
            normal_indices,
        })
    }

    /// Vertex positions, Q1.14.
    pub const fn positions(&self) -> &'a [[i16; 3]] {
        self.positions
    }

    /// Triangles as vertex index triples, counter-clockwise front faces.
    pub const fn triangles(&self) -> &'a [[u16; 3]] {
        self.triangles
    }

    /// The per-corner normals, if the mesh has them.
    pub const fn normals(&self) -> Option<CornerNormals<'a>> {
        if self.normal_indices.is_empty() {
            None
        } else {
            Some(CornerNormals {
                normals: self.normals,
                indices: self.normal_indices,
            })
        }
    }

    /// Whether the mesh has per-corner normals.
    pub const fn has_normals(&self) -> bool {
        !self.normal_indices.is_empty()
    }

    /// Number of vertices (positions), at least 1.
    pub const fn vertex_count(&self) -> usize {
        self.positions.len()
    }

    /// Number of triangles, at least 1.
    pub const fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// Number of stored normals, 0 without normals.
    pub const fn normal_count(&self) -> usize {
        self.normals.len()
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
        let index = *self.normal_indices.get(tri)?.get(corner)?;
        self.normals.get(usize::from(index)).copied()
    }
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
