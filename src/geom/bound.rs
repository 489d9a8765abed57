//! The bounding sphere and box of a set of Q1.14 positions.

/// A sphere holding every position of a set of Q1.14 positions, in Q1.14:
/// the centre of the positions' bounding box and the distance to the
/// farthest position, rounded up.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Bound {
    /// Centre, Q1.14.
    pub center: [i16; 3],
    /// Radius, Q1.14 (at most `2^15 · √3 < 56756`).
    pub radius: u32,
    /// Half extents of the bounding box about `center`, Q1.14: every
    /// position lies within `center ± half` per axis.
    pub half: [u16; 3],
}

impl Bound {
    /// The bounding sphere of `positions` (non-empty).
    pub(crate) const fn of(positions: &[[i16; 3]]) -> Self {
        let mut lo = [i16::MAX; 3];
        let mut hi = [i16::MIN; 3];
        let mut i = 0;
        while i < positions.len() {
            let mut k = 0;
            while k < 3 {
                let c = positions[i][k];
                if c < lo[k] {
                    lo[k] = c;
                }
                if c > hi[k] {
                    hi[k] = c;
                }
                k += 1;
            }
            i += 1;
        }
        // (lo + hi) / 2 lies within [lo, hi]: fits i16.
        let center = [
            ((lo[0] as i32 + hi[0] as i32) >> 1) as i16,
            ((lo[1] as i32 + hi[1] as i32) >> 1) as i16,
            ((lo[2] as i32 + hi[2] as i32) >> 1) as i16,
        ];
        let mut r2: u64 = 0;
        let mut i = 0;
        while i < positions.len() {
            let mut d2: u64 = 0;
            let mut k = 0;
            while k < 3 {
                // |d| < 2^16: d^2 < 2^32, the sum < 3 · 2^32.
                let d = (positions[i][k] as i32 - center[k] as i32).unsigned_abs() as u64;
                d2 += d * d;
                k += 1;
            }
            if d2 > r2 {
                r2 = d2;
            }
            i += 1;
        }
        // ⌈√r2⌉: the floor root, plus one unless exact.
        let r = crate::num::isqrt_u64(r2);
        let radius = if r * r == r2 { r } else { r + 1 } as u32;
        // The farther box side from the (floored) centre: below 2^16.
        let mut half = [0u16; 3];
        let mut k = 0;
        while k < 3 {
            let up = hi[k] as i32 - center[k] as i32;
            let down = center[k] as i32 - lo[k] as i32;
            half[k] = (if up > down { up } else { down }) as u16;
            k += 1;
        }
        Self {
            center,
            radius,
            half,
        }
    }
}
