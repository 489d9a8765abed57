//! Vectors, 3×3 matrices and affine transforms over any [`Real`].
//!
//! Conventions: right-handed, y up; a transform applies its rotation
//! about X first, then Y, then Z ([`Affine::from_parts`]). Everything is
//! generic over the profile's scalar, so a fixed-point firmware builds its
//! matrices with fixed-point trigonometry ([`Real::sin_cos`]) and no float.

use crate::num::{Kernels, Raw16, Real};

pub(crate) mod bound;
pub(crate) mod cull;
pub(crate) mod exact;
pub(crate) mod fused;
pub(crate) mod q16;
#[cfg(test)]
pub(crate) mod testkit;
use core::ops::{Add, Mul, Neg, Sub};

/// Degrees to radians without floating point: `deg · 71 / 4068` (π/180 as
/// 355/(113·180), reduced; relative error 8.5·10⁻⁸), one multiplication by
/// an integer and one rounded division. For `Q16` the product must stay
/// below 32768, so angles are limited to ±461° (beyond, it saturates:
/// reduce the angle first).
pub fn radians<R: Real>(deg: R) -> R {
    deg.mul_i32(71).div(R::from_i32(4068))
}

/// [`Vec3::normalize`] for `Q16` in 32-bit arithmetic, bit for bit: the
/// same rounded products ([`mul16_small`](crate::num::wide::mul16_small))
/// and the same `rsqrt` (the zero vector stays zero); `None` (the generic code runs) unless every
/// component and `1/|v|` are at most 2 in magnitude (vectors of length
/// 1/2 to 2: normals, light directions).
#[inline]
fn unit_q16_small<R: Real>(q: Raw16<R>, v: Vec3<R>) -> Option<Vec3<R>> {
    use crate::num::wide::{mul16_small, SMALL};
    let r = [q.raw(v.x), q.raw(v.y), q.raw(v.z)];
    if r.iter().any(|c| c.unsigned_abs() > SMALL) {
        return None;
    }
    // Each square <= 2^18: the sum neither saturates nor reaches `MAX`.
    let l2 = mul16_small(r[0], r[0]) + mul16_small(r[1], r[1]) + mul16_small(r[2], r[2]);
    let k = crate::num::approx16::rsqrt(l2);
    if k.unsigned_abs() > SMALL {
        return None;
    }
    Some(Vec3::new(
        q.from_raw(mul16_small(r[0], k)),
        q.from_raw(mul16_small(r[1], k)),
        q.from_raw(mul16_small(r[2], k)),
    ))
}

/// A 3-vector.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3<R> {
    /// x component.
    pub x: R,
    /// y component.
    pub y: R,
    /// z component.
    pub z: R,
}

impl<R: Real> Vec3<R> {
    /// The zero vector.
    pub const ZERO: Self = Self {
        x: R::ZERO,
        y: R::ZERO,
        z: R::ZERO,
    };

    /// A vector from its components.
    pub const fn new(x: R, y: R, z: R) -> Self {
        Self { x, y, z }
    }

    /// A vector from `f32` components (saturating; NaN maps to zero: check
    /// finiteness before where that matters).
    pub fn from_f32(v: [f32; 3]) -> Self {
        Self::new(R::from_f32(v[0]), R::from_f32(v[1]), R::from_f32(v[2]))
    }

    /// A vector from Q1.14 components (mesh positions and normals).
    pub fn from_q14(v: [i16; 3]) -> Self {
        Self::new(
            R::from_fixed_i32(v[0] as i32, 14),
            R::from_fixed_i32(v[1] as i32, 14),
            R::from_fixed_i32(v[2] as i32, 14),
        )
    }

    /// Components as `f64` (for tests and reports).
    pub fn to_f64(self) -> [f64; 3] {
        [self.x.to_f64(), self.y.to_f64(), self.z.to_f64()]
    }

    /// Dot product.
    #[inline]
    pub fn dot(self, o: Self) -> R {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product.
    #[inline]
    pub fn cross(self, o: Self) -> Self {
        Self::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Scaled by `k`.
    #[inline]
    pub fn scale(self, k: R) -> Self {
        Self::new(self.x * k, self.y * k, self.z * k)
    }

    /// Squared length.
    #[inline]
    pub fn length_sq(self) -> R {
        self.dot(self)
    }

    /// Length.
    pub fn length(self) -> R {
        self.length_sq().sqrt()
    }

    /// The unit vector in the same direction; the zero vector stays zero
    /// (defined: no NaN, no panic). Error: that of [`Real::rsqrt`] on the
    /// squared length.
    ///
    /// A vector whose squared length does not fit the scalar (longer than
    /// about 181 for `Q16`, 46341 for `Q32`: a point light far away, a
    /// large model scale; `f32` beyond 1.8e19) is first divided by its
    /// largest component magnitude, so it still comes out of unit length.
    #[inline]
    pub fn normalize(self) -> Self {
        let l2 = self.length_sq();
        if l2 >= R::MAX {
            // Saturated (fixed) or overflowed (float): the rare slow path.
            let m = self.x.abs().max(self.y.abs()).max(self.z.abs());
            let v = Self::new(self.x.div(m), self.y.div(m), self.z.div(m));
            return v.scale(v.length_sq().rsqrt());
        }
        self.scale(l2.rsqrt())
    }

    /// [`normalize`](Self::normalize), bit for bit, by 32-bit products
    /// for `Q16` vectors with components up to 2 and lengths from 1/2
    /// (per-vertex and per-face code of the geometry; kept apart from
    /// `normalize` so that the rasterizer's code is not changed).
    #[inline(always)]
    pub(crate) fn normalize_geom(self) -> Self {
        R::Kernels::pick(|q| self.normalize_q16(q), || self.normalize())
    }

    /// [`normalize_geom`](Self::normalize_geom) for `Q16`: the 32-bit
    /// form where it applies, else [`normalize`](Self::normalize).
    #[inline(never)]
    fn normalize_q16(self, q: Raw16<R>) -> Self {
        unit_q16_small(q, self).unwrap_or_else(|| self.normalize())
    }

    /// `true` when every component is exactly zero.
    pub fn is_zero(self) -> bool {
        self.x == R::ZERO && self.y == R::ZERO && self.z == R::ZERO
    }
}

impl<R: Real> Add for Vec3<R> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        Self::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl<R: Real> Sub for Vec3<R> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        Self::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl<R: Real> Neg for Vec3<R> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

/// A 3×3 matrix, rows first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mat3<R> {
    /// The rows.
    pub rows: [Vec3<R>; 3],
}

impl<R: Real> Mat3<R> {
    /// The identity.
    pub const IDENTITY: Self = Self {
        rows: [
            Vec3::new(R::ONE, R::ZERO, R::ZERO),
            Vec3::new(R::ZERO, R::ONE, R::ZERO),
            Vec3::new(R::ZERO, R::ZERO, R::ONE),
        ],
    };

    /// Rotation by `a` radians about X (y towards z).
    pub fn rotation_x(a: R) -> Self {
        let (s, c) = a.sin_cos();
        let (o, z) = (R::ONE, R::ZERO);
        Self::from_rows([[o, z, z], [z, c, -s], [z, s, c]])
    }

    /// Rotation by `a` radians about Y (z towards x).
    pub fn rotation_y(a: R) -> Self {
        let (s, c) = a.sin_cos();
        let (o, z) = (R::ONE, R::ZERO);
        Self::from_rows([[c, z, s], [z, o, z], [-s, z, c]])
    }

    /// Rotation by `a` radians about Z (x towards y).
    pub fn rotation_z(a: R) -> Self {
        let (s, c) = a.sin_cos();
        let (o, z) = (R::ONE, R::ZERO);
        Self::from_rows([[c, -s, z], [s, c, z], [z, z, o]])
    }

    /// A matrix from rows of components.
    pub fn from_rows(r: [[R; 3]; 3]) -> Self {
        Self {
            rows: r.map(|r| Vec3::new(r[0], r[1], r[2])),
        }
    }

    /// `self · v`.
    #[inline]
    pub fn apply(&self, v: Vec3<R>) -> Vec3<R> {
        Vec3::new(
            self.rows[0].dot(v),
            self.rows[1].dot(v),
            self.rows[2].dot(v),
        )
    }

    /// The transpose (the inverse of a rotation).
    pub fn transpose(&self) -> Self {
        let r = &self.rows;
        Self::from_rows([
            [r[0].x, r[1].x, r[2].x],
            [r[0].y, r[1].y, r[2].y],
            [r[0].z, r[1].z, r[2].z],
        ])
    }

    /// The product `self · o`.
    pub fn compose(&self, o: &Self) -> Self {
        let t = o.transpose();
        let r = |i: usize| {
            [
                self.rows[i].dot(t.rows[0]),
                self.rows[i].dot(t.rows[1]),
                self.rows[i].dot(t.rows[2]),
            ]
        };
        Self::from_rows([r(0), r(1), r(2)])
    }

    /// Every component scaled by `k`.
    pub fn scale(&self, k: R) -> Self {
        Self {
            rows: self.rows.map(|r| r.scale(k)),
        }
    }
}

impl<R: Real> Mat3<R> {
    /// Largest entry magnitude.
    pub(crate) fn max_abs(&self) -> R {
        let r = &self.rows;
        [r[0], r[1], r[2]]
            .iter()
            .map(|v| v.x.abs().max(v.y.abs()).max(v.z.abs()))
            .fold(R::ZERO, R::max)
    }

    /// An upper bound of how far the matrix stretches a vector (its
    /// spectral norm): the square root of the largest row sum of
    /// magnitudes of `MᵀM`, computed on `M` divided by its largest entry
    /// (entries up to 1, so `MᵀM` does not saturate) and scaled back.
    /// `None` for the zero matrix.
    pub(crate) fn stretch(&self) -> Option<R> {
        let m = self.max_abs();
        if m == R::ZERO {
            return None;
        }
        let t = self
            .transpose()
            .rows
            .map(|r| Vec3::new(r.x.div(m), r.y.div(m), r.z.div(m)));
        let g = |i: usize, j: usize| t[i].dot(t[j]).abs();
        let row = |i: usize| g(i, 0) + g(i, 1) + g(i, 2);
        Some(m * row(0).max(row(1)).max(row(2)).sqrt())
    }

    /// How this linear part of a model-view transform acts on normals:
    /// `(k, s, uniform)`. `k` is the matrix to apply to an object-space
    /// normal before normalising it; `uniform` tells whether the matrix
    /// is a uniform scale `s` of a rotation (then `k` is the matrix
    /// divided by its largest entry, and `s` that scale: the columns of
    /// `k` have length `s`), else `k` is the cofactor matrix of that
    /// quotient, signed by its determinant (the inverse-transpose up to a
    /// positive factor, which the normalisation removes), and `s` is one.
    ///
    /// Uniform means: the Gram matrix `kᵀk` lies within `2^-12 · s²` of
    /// `s² I` entry by entry (a rotation rounded to `Q16` is well inside;
    /// an object-space light then gives `N·L` within `2^-12` relative of
    /// the exact renormalised product, 0.06 of a level at most).
    pub(crate) fn normal_matrix(&self) -> (Self, R, bool) {
        let m = self.max_abs();
        if m == R::ZERO {
            return (*self, R::ONE, false);
        }
        let k = Self {
            rows: self
                .rows
                .map(|r| Vec3::new(r.x.div(m), r.y.div(m), r.z.div(m))),
        };
        let t = k.transpose();
        let c = |i: usize, j: usize| t.rows[i].dot(t.rows[j]);
        let d = (c(0, 0) + c(1, 1) + c(2, 2)).div(R::from_i32(3));
        let tol = d.div(R::from_i32(4096));
        let near = |a: R, b: R| (a - b).abs() <= tol;
        let uniform = d > R::ZERO
            && near(c(0, 0), d)
            && near(c(1, 1), d)
            && near(c(2, 2), d)
            && near(c(0, 1), R::ZERO)
            && near(c(0, 2), R::ZERO)
            && near(c(1, 2), R::ZERO);
        if uniform {
            return (k, d.sqrt(), true);
        }
        let r = &k.rows;
        let cof = Self::from_rows([
            [
                r[1].y * r[2].z - r[1].z * r[2].y,
                r[1].z * r[2].x - r[1].x * r[2].z,
                r[1].x * r[2].y - r[1].y * r[2].x,
            ],
            [
                r[0].z * r[2].y - r[0].y * r[2].z,
                r[0].x * r[2].z - r[0].z * r[2].x,
                r[0].y * r[2].x - r[0].x * r[2].y,
            ],
            [
                r[0].y * r[1].z - r[0].z * r[1].y,
                r[0].z * r[1].x - r[0].x * r[1].z,
                r[0].x * r[1].y - r[0].y * r[1].x,
            ],
        ]);
        let det = r[0].dot(cof.rows[0]);
        let cof = if det < R::ZERO {
            cof.scale(-R::ONE)
        } else {
            cof
        };
        (cof, R::ONE, false)
    }
}

/// An affine transform `p -> m·p + t`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Affine<R> {
    /// The linear part.
    pub m: Mat3<R>,
    /// The translation.
    pub t: Vec3<R>,
}

impl<R: Real> Affine<R> {
    /// The identity.
    pub const IDENTITY: Self = Self {
        m: Mat3::IDENTITY,
        t: Vec3::ZERO,
    };

    /// Uniform scale `s`, then rotations about X, Y and Z by `angles`
    /// (radians, in that order), then the translation `t`.
    pub fn from_parts(s: R, angles: Vec3<R>, t: Vec3<R>) -> Self {
        let r = Mat3::rotation_z(angles.z)
            .compose(&Mat3::rotation_y(angles.y))
            .compose(&Mat3::rotation_x(angles.x));
        Self { m: r.scale(s), t }
    }

    /// Transforms a point.
    #[inline]
    pub fn point(&self, p: Vec3<R>) -> Vec3<R> {
        self.m.apply(p) + self.t
    }

    /// Transforms a direction (no translation).
    #[inline]
    pub fn vector(&self, v: Vec3<R>) -> Vec3<R> {
        self.m.apply(v)
    }

    /// `self ∘ o`: `o` first, then `self`.
    pub fn then_after(&self, o: &Self) -> Self {
        Self {
            m: self.m.compose(&o.m),
            t: self.m.apply(o.t) + self.t,
        }
    }
}

impl<R: Real> Mul<Vec3<R>> for Mat3<R> {
    type Output = Vec3<R>;
    fn mul(self, v: Vec3<R>) -> Vec3<R> {
        self.apply(v)
    }
}

#[cfg(test)]
mod tests {
    use super::{unit_q16_small, Vec3};
    use crate::num::{Raw16, Real, Q16};

    /// The 32-bit normalisation gives the generic code's bits, and takes
    /// every vector of components up to 2 with a length from 1/2.
    #[test]
    fn unit_q16_small_matches_generic() {
        let mut next = crate::geom::testkit::xorshift(0x0123_4567_89ab_cdef);
        let mut taken = 0;
        for i in 0..500_000 {
            let lim: u64 = if i % 3 == 0 { 1 << 18 } else { 1 << 17 };
            let c = [0; 3].map(|_| Q16::from_bits((next() % (2 * lim + 1)) as i32 - lim as i32));
            let v = Vec3::new(c[0], c[1], c[2]);
            let generic = v.scale(v.length_sq().rsqrt());
            if let Some(u) = unit_q16_small(Raw16::Q16, v) {
                assert_eq!(u, generic, "{v:?}");
                taken += 1;
            } else {
                let m = c.iter().map(|x| x.to_bits().unsigned_abs()).max().unwrap();
                let len = v.to_f64().iter().map(|x| x * x).sum::<f64>().sqrt();
                assert!(m > 1 << 17 || len < 0.5 + 1e-3, "{v:?}");
            }
        }
        assert!(taken > 200_000);
        let z = Vec3::<Q16>::ZERO;
        assert_eq!(unit_q16_small(Raw16::Q16, z), Some(z));
    }
}
