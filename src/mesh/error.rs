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
    /// The vertex normal table does not have one entry per vertex.
    NormalCountMismatch {
        /// The number of vertices (positions).
        vertices: usize,
        /// The number of normals.
        normals: usize,
    },
    /// The face normal table does not have one entry per triangle.
    FaceNormalCountMismatch {
        /// The number of triangles.
        triangles: usize,
        /// The number of face normals.
        face_normals: usize,
    },
    /// Culling cones without vertex normals, or not one per vertex
    /// ([`Mesh::with_vertex_cones`](super::Mesh::with_vertex_cones)).
    ConeCountMismatch {
        /// The number of vertices.
        vertices: usize,
        /// The number of cones.
        cones: usize,
    },
    /// A vertex's culling cone does not hold for its position, normal or
    /// faces ([`Mesh::with_vertex_cones`](super::Mesh::with_vertex_cones)).
    ConeMismatch {
        /// The first such vertex.
        vertex: usize,
    },
    /// [`weld`](super::weld): an output or scratch table is too short.
    OutputTooSmall,
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
            Self::NormalCountMismatch { vertices, normals } => {
                write!(f, "{normals} vertex normals for {vertices} vertices")
            }
            Self::FaceNormalCountMismatch {
                triangles,
                face_normals,
            } => write!(f, "{face_normals} face normals for {triangles} triangles"),
            Self::ConeCountMismatch { vertices, cones } => write!(
                f,
                "{cones} culling cones for {vertices} vertices (vertex normals needed)"
            ),
            Self::ConeMismatch { vertex } => {
                write!(f, "vertex {vertex}: culling cone does not hold")
            }
            Self::OutputTooSmall => f.write_str("an output or scratch table is too short"),
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
