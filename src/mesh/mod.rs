//! Triangle meshes as constant data, vertex normal generation and built-in
//! shapes.
//!
//! # Formats
//!
//! Every mesh format here is an integer format, independent of the number
//! profile used to shade it, so one table in flash serves every profile.
//!
//! - **Positions**: `[i16; 3]` in Q1.14, value = raw / 16384
//!   ([`POSITION_FRAC_BITS`]), range [-2, 2). The built-in shapes fit in
//!   [-1, 1]³.
//! - **Triangles**: `[u16; 3]` vertex indices. Front faces are
//!   counter-clockwise when seen from their front, in a right-handed, y-up
//!   frame, so the face normal `(b - a) × (c - a)` points out of the front.
//!   A mesh has at most 65535 vertices ([`MAX_VERTICES`]).
//! - **Normals** (optional, per vertex): unit `[i16; 3]` vectors in Q1.14
//!   ([`NORMAL_FRAC_BITS`], 16384 = 1.0), parallel to the positions: a
//!   vertex is one distinct (position, normal) pair, so a position on a
//!   crease is stored once per normal and the geometry stage runs one
//!   linear pass over the vertices. [`weld`] turns OBJ-style per-corner
//!   normals ([`CornerNormals`], as [`generate_normals`] makes them) into
//!   this form.
//! - **Face normals** (optional, one per triangle): unit Q1.14 vectors,
//!   the exact [`face_normal`] of the corners, baked with the built-in
//!   shapes so that flat shading reads them (6 bytes a triangle of flash)
//!   instead of computing them per frame.
//!
//! [`Mesh::new`] is a `const fn` that checks these rules, so a table built
//! with it in a `const` item is checked at compile time. The built-in
//! shapes in [`shapes`] are made that way.
//!
//! # Vertex normal generation
//!
//! [`generate_normals`] computes per-corner normals from positions alone,
//! with integer arithmetic only and caller-provided buffers:
//!
//! - the face normal is the unit cross product `(b - a) × (c - a)` (not
//!   area-weighted);
//! - a corner's normal is the normalised sum of the unit normals of the
//!   faces around its vertex that it is allowed to share with: its own
//!   face always, another face only if the two faces' smoothing groups
//!   intersect (see [`Smoothing::groups`]) and the angle between the two
//!   face normals is at most the crease angle ([`Crease`]);
//! - equal normals of one vertex are stored once.
//!
//! ## Arithmetic and error bounds
//!
//! Positions are i16, so edge vectors fit i32 (|d| ≤ 65535) and the cross
//! product of two edges fits i64 (|c| ≤ 2³³). Normalising a vector `v` to
//! `F` fractional bits ([`normalize_q14`] with `F = 14`, face normals
//! internally with `F = 30`) works as follows:
//!
//! 1. scale `v` by a power of two so that its largest component magnitude
//!    lies in [2³⁰, 2³¹): exact when scaling up; truncating the magnitudes
//!    when scaling down moves the vector by less than √3, i.e. by less than
//!    √3·2⁻³⁰ of its length;
//! 2. `S = x² + y² + z² < 3·2⁶²` fits u64; `L = ⌊√S⌋` is an exact integer
//!    square root, so `L ≤ √S < L + 1` with `L ≥ 2³⁰`;
//! 3. each component is `round(v·2^F / L)`, rounding half away from zero
//!    (so `-v` gives exactly the negated result).
//!
//! Step 1 turns the direction by at most `2·√3·2⁻³⁰` and step 2 scales by
//! at most `1 + 2⁻³⁰`, so before the final rounding each component is
//! within `2^F · 4.5·2⁻³⁰` of the exact `2^F · v/|v|`. With `F = 14` every
//! component is within **0.5 + 7·10⁻⁵ ulp** (1 ulp = 2⁻¹⁴) of the exact
//! unit vector; with `F = 30` within 5 units of 2⁻³⁰.
//!
//! A vertex normal sums the Q1.30 face normals of `k` faces exactly in i64,
//! then normalises the sum to Q1.14 as above. The sum is within
//! `5k·2⁻³⁰` per component, `8.7k·2⁻³⁰` Euclidean, of the exact sum `s` of
//! the exact unit face normals, which turns its direction by at most
//! `2 · 8.7k·2⁻³⁰ / |s|`. Hence each component of a produced vertex normal
//! is within **0.5 + 7·10⁻⁵ + 2.7·10⁻⁴·k/|s| ulp** of the exact
//! `normalise(Σ normalise((b - a) × (c - a)))` computed from the same
//! integer positions. When the crease angle is at most 90° every face in
//! the sum lies within 90° of the corner's own face, so `|s| ≥ 1` (less
//! the 10⁻⁸ of the Q1.30 dot products); for a valence `k ≤ 36` the bound
//! is then **0.51 ulp**. Larger creases allow `|s| < 1` and so larger
//! errors near cancellation. The host tests measure the error against f64:
//! 0.49987 ulp on the built-in sphere and 0.49986 on the bunny (fully
//! smooth).
//!
//! ## Degenerate cases
//!
//! - A zero-area face (collinear or repeated corners) has the normal
//!   (0, 0, 0): it contributes nothing to its neighbours and its own
//!   corners get (0, 0, 0).
//! - If the sum of the shared face normals has no component of magnitude
//!   at least 1 ulp (2⁻¹⁴), as when two opposite faces cancel, the corner
//!   falls back to its own face normal.
//!
//! Nothing here panics on any input; errors are values.

mod crease;
mod data;
mod error;
mod generate;
pub mod shapes;
#[cfg(test)]
mod tests;

pub use crate::geom::bound::Bound;
pub use crate::geom::exact::{
    cone_covers, face_normal, face_plane, normalize_q14, MAX_AXIS2, SLACK_FRAC_BITS, SLACK_LENGTH,
};
pub use crate::num::isqrt_u64;
pub use crease::Crease;
pub use data::{
    weld, CornerNormals, Mesh, MAX_VERTICES, NORMAL_FRAC_BITS, NORMAL_ONE, POSITION_FRAC_BITS,
};
pub use error::{MeshError, NormalsError};
pub use generate::{generate_normals, Smoothing, MAX_TRIANGLES};
pub use shapes::{BUNNY, CAN, CUBE, DODECAHEDRON, GRID, SPHERE};
