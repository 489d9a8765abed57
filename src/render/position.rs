//! How one object's interpolated eye-space positions are stored (Phong
//! with a point light or a local viewer, the `PhongPosition` layout).
//!
//! The rasterizer steps an `i32` attribute by its gradient rounded to a
//! whole raw unit ([`Lerp::step`](crate::raster::Lerp::step)), so at `k`
//! pixels (along a span plus down the rows) from the triangle's anchor a
//! value is off by up to `k/2` raw units. With absolute eye-space
//! coordinates in `Q16` ([`COORD_FRAC_BITS`](crate::num::COORD_FRAC_BITS),
//! ±16384 units) that is `k · 2^-17` units: 0.003 units at 400 pixels.
//! `L` and `V` turn by that over the distance to the light and the eye,
//! and a highlight of shininess `n` changes by up to `0.61·√n` per radian
//! (the slope of `cos^n θ` at `θ = 1/√n`): 61 at `n = 10 000`, so a
//! 1600 × 1200 Phong sphere under eight lights of `Ip·ks = 0.18` measured
//! 3 levels from its `f64` twin in `precise` (issue 15 reports up to 20
//! on a torus), while the same frame at 400 × 300 stayed within 1.
//!
//! Profiles with [`Profile::POSITION_FRAME`] (`precise`) therefore store
//! `p - c`, with `c` the eye-space centre of the mesh's bounding sphere,
//! in a fixed-point format with `F` fraction bits chosen per object: the
//! largest `F <= 30` with `r · 2^F <= 2^29`, `r` a bound of the sphere's
//! eye-space radius (the mesh radius times a bound of the model-view
//! matrix's stretch, plus 1/64 relative and 2^-10 units for rounding),
//! so every stored value, clipped vertices included (they lie on edges
//! inside the sphere), is within half the rasterizer's `±2^30`. The drift
//! is then `k/2 · 2^-F`, and `2^-F < r · 2^-28` (or `F = 30`), so below
//! `k · r · 2^-29` units: for the unit sphere (`r` 1.02, `F = 28`),
//! `2^-17` units at `k = 4096`. The per-pixel shader adds `c` back in the
//! scalar (`Q32`: exact, `F <= 30 < 32`). Objects whose sphere does not
//! fit (`r > 2^13` units, or a centre beyond half the scalar's range)
//! keep absolute `Q16` coordinates, as the other profiles do. Measured on
//! the 1600 × 1200 sphere under eight lights at `n = 10 000`: 3 levels
//! (Phong) and 2 (Blinn) from the twin before, 0 over the whole frame
//! after; docs/accuracy.md's `precise` Phong group against its twin: max
//! 1 -> 0 levels, mean 0.0064 -> 0.0000 (against the ideal unchanged).
//!
//! # Limits
//! `k` counts pixels from the triangle's anchor (the pixel centre nearest
//! its first vertex, which may lie in the guard band): `|Δx| + |Δy|`, up
//! to `2 · 4096` within a 4096-pixel guard band. A position error `δ` turns
//! `L` by `δ/d` (`d` the distance from the surface to the light) and `V`
//! by `δ/|p|`. Within 1 level of the twin at shininess `n` and a
//! specular coefficient `Ip·Lc·ks = s` needs `255 · s · 0.61·√n · (δ/d +
//! δ/|p|) < ½`; with `δ < k · r · 2^-29` that holds while `k · r · (1/d
//! + 1/|p|) < 2^29 / (311 · s · √n)`: for `s = 1`, `n = 10 000` and
//! `k = 4096`, `r/d + r/|p| < 4.2` (an object up to about four times its
//! distance to the nearest light and to the eye). The extreme suite
//! checks the 1600 × 1200 sphere and a square filling a 2044-pixel
//! screen with lights 0.3 units above it (`r/d` 4.7 at `k` up to 3000:
//! within 1 level measured, the bound being conservative)
//! (`host-tests/tests/extreme_scene.rs`). The affine twin's own model
//! (screen-linear positions) is what both compute; the perspective-correct
//! `precise-pc` keeps its 22-bit coordinates.

use crate::geom::{Affine, Vec3};
use crate::mesh::Mesh;
use crate::num::{Profile, Real, COORD_FRAC_BITS};
use crate::raster::Lerp;
use crate::scene::{Object, Scene};

/// Largest fraction bits of a framed position (the scalar conversions'
/// limit, [`Real::to_fixed_i32`]).
const MAX_FRAC: u32 = 30;
/// Framed positions stay within `±2^29` raw at the bounding sphere: half
/// the rasterizer's attribute range (`±2^30`), the rest for the
/// interpolation's rounding.
const LIMIT_LOG2: u32 = 29;

/// One object's position format: `c` and the fraction bits (see the
/// module docs). The identity frame (`c = 0`, [`COORD_FRAC_BITS`]) is
/// [`Profile::coord`]'s format.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PosFrame<R> {
    origin: Vec3<R>,
    frac: u32,
    framed: bool,
}

impl<R: Real> PosFrame<R> {
    /// [`Profile::coord`]'s format.
    pub(crate) fn identity() -> Self {
        Self {
            origin: Vec3::ZERO,
            frac: COORD_FRAC_BITS,
            framed: false,
        }
    }

    /// The frame of `mesh` placed in eye space by `mv`, for profile `P`
    /// (the identity unless [`Profile::POSITION_FRAME`]).
    pub(crate) fn new<P: Profile<Real = R>>(mesh: &Mesh<'_>, mv: &Affine<R>) -> Self {
        let id = Self::identity();
        if !P::POSITION_FRAME || P::PERSPECTIVE {
            return id;
        }
        let b = mesh.bound();
        let c = mv.point(Vec3::from_q14(b.center));
        let half = R::MAX.half();
        if c.x.abs() >= half || c.y.abs() >= half || c.z.abs() >= half {
            return id;
        }
        // The largest stretch of M (see `Mat3::stretch`).
        let Some(stretch) = mv.m.stretch() else {
            return id;
        };
        // The radius (Q1.14, below 2^16) stretched, plus 1/64 relative
        // and 2^-10 units for the rounding of the vertices' transform.
        let r0 = R::from_fixed_i32(b.radius.min(1 << 16) as i32, 14) * stretch;
        let r = r0 + r0.div(R::from_i32(64)) + R::from_ratio(1, 1024);
        // The largest F with r · 2^F <= 2^29, from r's integer bits.
        let mut frac = MAX_FRAC;
        let lim = R::from_i32(1 << 13);
        if r >= half || r > lim {
            return id;
        }
        // r · 2^frac <= 2^29  <=>  r <= 2^(29 - frac).
        while frac > COORD_FRAC_BITS && r > R::from_fixed_i32(1 << LIMIT_LOG2, frac) {
            frac -= 1;
        }
        Self {
            origin: c,
            frac,
            framed: true,
        }
    }

    /// The frame of a scene's object, for the profiles that keep one
    /// (else `None`, without computing anything).
    pub(crate) fn of_object<P: Profile<Real = R>>(
        scene: &Scene<'_, '_, R>,
        obj: &Object<'_, R>,
    ) -> Option<Self> {
        P::POSITION_FRAME
            .then(|| Self::new::<P>(&obj.mesh, &scene.camera.view.then_after(&obj.transform)))
    }

    /// Fraction bits of the stored coordinates.
    #[cfg(test)]
    pub(crate) fn frac(&self) -> u32 {
        self.frac
    }

    /// The stored form of eye-space point `p` in `frame` (`None`:
    /// [`Profile::coord`]'s, the only form of the profiles without
    /// [`Profile::POSITION_FRAME`], which keep no frame: their callers
    /// pass `None`, so the frame costs them no stack).
    #[inline(always)]
    pub(crate) fn store<P: Profile<Real = R>>(frame: Option<&Self>, p: Vec3<R>) -> [P::Lerp; 3] {
        match frame {
            Some(f) if P::POSITION_FRAME && f.framed => {
                let d = p - f.origin;
                [d.x, d.y, d.z].map(|v| P::Lerp::from_fixed_raw(v.to_fixed_i32(f.frac)))
            }
            _ => [P::coord(p.x), P::coord(p.y), P::coord(p.z)],
        }
    }

    /// The eye-space point of stored values `a` (as [`PosFrame::store`]
    /// made them in `frame`, interpolated).
    #[inline(always)]
    pub(crate) fn load<P: Profile<Real = R>>(frame: Option<&Self>, a: [P::Lerp; 3]) -> Vec3<R> {
        match frame {
            Some(f) if P::POSITION_FRAME && f.framed => {
                let v = |l: P::Lerp| R::from_fixed_i32(l.fixed_raw().unwrap_or(0), f.frac);
                f.origin + Vec3::new(v(a[0]), v(a[1]), v(a[2]))
            }
            _ => Vec3::new(
                P::coord_back(a[0]),
                P::coord_back(a[1]),
                P::coord_back(a[2]),
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Affine;
    use crate::mesh::shapes;
    use crate::num::{Fast, Precise, Q32};

    fn eye(scale: f64, t: [f64; 3]) -> Affine<Q32> {
        let v = |a: [f64; 3]| {
            Vec3::new(
                Q32::from_f64(a[0]),
                Q32::from_f64(a[1]),
                Q32::from_f64(a[2]),
            )
        };
        Affine::from_parts(Q32::from_f64(scale), v([0.3, 0.2, 0.1]), v(t))
    }

    /// The unit sphere 3 units away: 28 fraction bits, and a point within
    /// the sphere back within `2^-29` units.
    #[test]
    fn unit_sphere_gets_28_bits() {
        let f = PosFrame::new::<Precise>(&shapes::SPHERE, &eye(1.0, [0.1, -0.2, -3.0]));
        assert_eq!(f.frac(), 28);
        let p = Vec3::new(Q32::from_f64(0.7), Q32::from_f64(-0.9), Q32::from_f64(-2.6));
        let back = PosFrame::load::<Precise>(Some(&f), PosFrame::store::<Precise>(Some(&f), p));
        for (a, b) in [(back.x, p.x), (back.y, p.y), (back.z, p.z)] {
            assert!((a - b).abs().to_f64() <= 2f64.powi(-29), "{a:?} {b:?}");
        }
    }

    /// Scale 0.01: 30 bits (the limit); scale 1000: 18 (`r` just above 2^10 with the margins); beyond 2^13
    /// units of radius, and for `fast`, absolute `Q16` coordinates.
    #[test]
    fn bits_follow_the_radius() {
        let bits =
            |s: f64| PosFrame::new::<Precise>(&shapes::SPHERE, &eye(s, [0.0, 0.0, -5.0])).frac();
        assert_eq!(bits(0.01), 30);
        assert_eq!(bits(1000.0), 18);
        let big = PosFrame::new::<Precise>(&shapes::SPHERE, &eye(9000.0, [0.0, 0.0, -5.0]));
        assert_eq!(big, PosFrame::identity());
        let p = Vec3::new(
            Q32::from_f64(1.5),
            Q32::from_f64(-2.25),
            Q32::from_f64(-7.0),
        );
        assert_eq!(
            PosFrame::store::<Precise>(Some(&big), p),
            [p.x, p.y, p.z].map(Precise::coord)
        );
        let m = |a: f64| crate::num::Q16::from_f64(a);
        let v = Vec3::new(m(0.3), m(0.2), m(0.1));
        let fast = PosFrame::new::<Fast>(
            &shapes::SPHERE,
            &Affine::from_parts(m(1.0), v, Vec3::new(m(0.0), m(0.0), m(-3.0))),
        );
        assert_eq!(fast, PosFrame::identity());
    }
}
