//! Homogeneous clipping of one triangle in eye space.
//!
//! Planes (with `w = −z`, the distance in front of the eye):
//! near `w ≥ near`, optional far `w ≤ far`, and the guard band `|x|, |y| ≤
//! g·w` with `g = G / k` (`G` at most [`GUARD_PX`]), which keeps every
//! projected vertex within `G` pixels of the screen centre, well inside the rasterizer's
//! ±8192-pixel range. Clipping a triangle against the planes its corners
//! violate gives a convex polygon of at most 3 + 6 = 9 corners, whose
//! attributes are interpolated linearly in eye space (exact for the
//! positions and normals; what the pipeline wants for colours).

use crate::geom::Vec3;
use crate::num::Real;

/// Largest half-size of the guard band around the screen centre, in
/// pixels: 4096. [`prepare`](super::prepare) narrows it so that stored
/// positions fit `i16` subpixels (see [`max_screen`](super::max_screen));
/// projected vertices stay within 2048 + 4096 < 8192 pixels of the
/// origin.
pub const GUARD_PX: i32 = 4096;

/// Most attributes a clipped vertex carries (colour or normal: 3).
pub const CLIP_ATTRS: usize = 3;

/// Most corners of a clipped polygon.
pub const MAX_POLY: usize = 9;

/// A vertex before projection: eye-space position and attributes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipVert<R> {
    /// Eye-space position.
    pub pos: Vec3<R>,
    /// Colour (Gouraud) or normal (Phong).
    pub attrs: [R; CLIP_ATTRS],
}

/// The clipping planes of a frame.
#[derive(Clone, Copy, Debug)]
pub struct Planes<R> {
    /// Near plane distance.
    pub near: R,
    /// Far plane distance, if any.
    pub far: Option<R>,
    /// Guard-band slope `g`.
    pub guard: R,
}

/// Bit set of violated planes.
pub type Outcode = u8;

const NEAR: u8 = 1;
const FAR: u8 = 2;
const LEFT: u8 = 4;
const RIGHT: u8 = 8;
const BOTTOM: u8 = 16;
const TOP: u8 = 32;

impl<R: Real> Planes<R> {
    /// Signed distance to plane `bit` (inside when `>= 0`).
    fn dist(&self, bit: u8, p: Vec3<R>) -> R {
        let w = -p.z;
        let gw = self.guard * w;
        match bit {
            NEAR => w - self.near,
            FAR => self.far.map_or(R::ONE, |f| f - w),
            LEFT => gw + p.x,
            RIGHT => gw - p.x,
            BOTTOM => gw + p.y,
            _ => gw - p.y,
        }
    }

    /// The planes `p` lies outside of.
    pub fn outcode(&self, p: Vec3<R>) -> Outcode {
        let mut c = 0;
        for bit in [NEAR, FAR, LEFT, RIGHT, BOTTOM, TOP] {
            if self.dist(bit, p) < R::ZERO {
                c |= bit;
            }
        }
        c
    }

    /// Clips triangle `t` whose corners have outcodes `codes` into `out`;
    /// returns the number of corners (0 when nothing is left).
    pub fn clip(
        &self,
        t: &[ClipVert<R>; 3],
        codes: [Outcode; 3],
        out: &mut [ClipVert<R>; MAX_POLY],
    ) -> usize {
        let mut a = [t[0]; MAX_POLY];
        let mut n = 3;
        a[..3].copy_from_slice(t);
        let any = codes[0] | codes[1] | codes[2];
        for bit in [NEAR, FAR, LEFT, RIGHT, BOTTOM, TOP] {
            if any & bit == 0 {
                continue;
            }
            let mut m = 0;
            for i in 0..n {
                // i < n <= MAX_POLY: `get` never fails (no panic branch).
                let (Some(&p), Some(&q)) = (a.get(i), a.get((i + 1) % n)) else {
                    break;
                };
                let (dp, dq) = (self.dist(bit, p.pos), self.dist(bit, q.pos));
                if dp >= R::ZERO && m < MAX_POLY {
                    out[m] = p;
                    m += 1;
                }
                if (dp >= R::ZERO) != (dq >= R::ZERO) && m < MAX_POLY {
                    out[m] = lerp(p, q, dp.div(dp - dq));
                    m += 1;
                }
            }
            n = m;
            // m <= MAX_POLY; a length-checked copy has no panic branch.
            for (d, s) in a.iter_mut().zip(out.iter()).take(n) {
                *d = *s;
            }
            if n < 3 {
                return 0;
            }
        }
        for (d, s) in out.iter_mut().zip(a.iter()).take(n) {
            *d = *s;
        }
        n
    }
}

fn lerp<R: Real>(p: ClipVert<R>, q: ClipVert<R>, t: R) -> ClipVert<R> {
    let t = t.clamp(R::ZERO, R::ONE);
    let mut attrs = p.attrs;
    for (a, b) in attrs.iter_mut().zip(q.attrs.iter()) {
        *a = *a + (*b - *a) * t;
    }
    ClipVert {
        pos: p.pos + (q.pos - p.pos).scale(t),
        attrs,
    }
}
