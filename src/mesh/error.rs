//! Errors of mesh checking and normal generation.

use core::fmt;

/// Why [`Mesh::new`](super::Mesh::new) rejected its tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum MeshError {
    /// No vertex or no triangle.
    Empty,
    /// More than [`MAX_VERTICES`](super::MAX_VERTICES) vertices.
    TooManyVertices {
        /// The number of positions given.
        count: usize,
    },
    /// A triangle names a vertex that does not exist.
    VertexIndexOutOfRange {
        /// The offending triangle's index.
        triangle: usize,
        /// The out-of-range vertex index (the largest of the triangle).
        index: u16,
    },
    /// The normal index table does not have one entry per triangle.
    NormalCountMismatch {
        /// The number of triangles.
        triangles: usize,
        /// The number of normal index triples.
        normal_indices: usize,
    },
    /// A triangle corner names a normal that does not exist.
    NormalIndexOutOfRange {
        /// The offending triangle's index.
        triangle: usize,
        /// The out-of-range normal index (the largest of the triangle).
        index: u16,
    },
}

impl fmt::Display for MeshError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Empty => f.write_str("mesh has no vertex or no triangle"),
            Self::TooManyVertices { count } => {
                write!(f, "mesh has {count} vertices, more than 65535")
            }
            Self::VertexIndexOutOfRange { triangle, index } => {
                write!(
                    f,
                    "triangle {triangle} uses vertex {index}, which is out of range"
                )
            }
            Self::NormalCountMismatch {
                triangles,
                normal_indices,
            } => write!(
                f,
                "{normal_indices} normal index triples for {triangles} triangles"
            ),
            Self::NormalIndexOutOfRange { triangle, index } => {
                write!(
                    f,
                    "triangle {triangle} uses normal {index}, which is out of range"
                )
            }
        }
    }
}

impl core::error::Error for MeshError {}

/// Why [`generate_normals`](super::generate_normals) could not run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum NormalsError {
    /// More than [`MAX_TRIANGLES`](super::MAX_TRIANGLES) triangles: face
    /// numbers would not fit the u16 adjacency buffer.
    TooManyTriangles {
        /// The number of triangles.
        count: usize,
    },
    /// The smoothing group table does not have one entry per triangle.
    GroupCountMismatch {
        /// The number of triangles.
        triangles: usize,
        /// The number of group masks.
        groups: usize,
    },
    /// The adjacency scratch buffer is shorter than 3 × triangle count.
    AdjacencyTooSmall {
        /// Entries needed.
        needed: usize,
        /// Entries given.
        len: usize,
    },
    /// The offsets scratch buffer is shorter than vertex count + 1.
    OffsetsTooSmall {
        /// Entries needed.
        needed: usize,
        /// Entries given.
        len: usize,
    },
    /// The normal index output is shorter than the triangle count.
    IndicesTooSmall {
        /// Entries needed.
        needed: usize,
        /// Entries given.
        len: usize,
    },
    /// The normal output filled up (or 65536 normals, the most a u16 index
    /// can name, were not enough). 3 × triangle count entries always
    /// suffice.
    NormalsFull {
        /// Normals stored when the buffer filled up.
        capacity: usize,
        /// The triangle whose corner needed one more normal.
        triangle: usize,
    },
}

impl fmt::Display for NormalsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::TooManyTriangles { count } => {
                write!(f, "{count} triangles, more than 65536")
            }
            Self::GroupCountMismatch { triangles, groups } => {
                write!(f, "{groups} smoothing groups for {triangles} triangles")
            }
            Self::AdjacencyTooSmall { needed, len } => {
                write!(f, "adjacency buffer has {len} entries, needs {needed}")
            }
            Self::OffsetsTooSmall { needed, len } => {
                write!(f, "offsets buffer has {len} entries, needs {needed}")
            }
            Self::IndicesTooSmall { needed, len } => {
                write!(f, "normal index buffer has {len} entries, needs {needed}")
            }
            Self::NormalsFull { capacity, triangle } => write!(
                f,
                "normal buffer full at {capacity} normals, at triangle {triangle}"
            ),
        }
    }
}

impl core::error::Error for NormalsError {}
