//! Depth buffers, 16 or 32 bits per pixel.
//!
//! The rasterizer interpolates a depth `d` in `[0, 1]` that is *affine in
//! screen space* (the projected `z/w`), as a 30-bit
//! fraction: `d30 = round(d × 2^30)`. A buffer keeps its top 16 or 30 bits.
//! The test is *less than*: a fragment is drawn when its depth is strictly
//! smaller than the stored one, so of two fragments at the same depth the
//! first drawn stays (the z-fighting rule), and a cleared buffer holds the
//! largest value. A 16-bit buffer stores `min(d30 >> 14, 65534)`, so every
//! fragment, even at the far plane (`d = 1`), passes a cleared pixel, and
//! the last 2^-15 of the depth range shares one value; a 32-bit buffer
//! stores `d30` itself.

use super::format::fill_u16;
use super::{check_window, span_range, BufferError, Window};
use crate::num::wide::NO_LONG_MUL;
use crate::num::Lerp;

/// Upper end (excluded) of the depths whose 16-bit value needs no clamp:
/// `65535·2^14` ([`Depth16`]'s conversions and its range tests).
pub(crate) const DEPTH16_LIM: u32 = 65535 << 14;

/// A depth value format.
pub trait DepthFormat: Copy + core::fmt::Debug {
    /// One stored depth.
    type Raw: Copy + PartialOrd + core::fmt::Debug;
    /// Value of a cleared buffer (farther than everything).
    const CLEAR: Self::Raw;
    /// Converts a 30-bit depth `0..=2^30` (larger values saturate).
    fn from_d30(d30: u32) -> Self::Raw;

    /// Sets every value of `values` to [`DepthFormat::CLEAR`]:
    /// `values.fill(Self::CLEAR)`, or a faster path storing the same
    /// values.
    #[inline(always)]
    fn clear_slice(values: &mut [Self::Raw]) {
        values.fill(Self::CLEAR);
    }

    /// Converts an interpolated depth: `from_d30(z.depth30())`, with a
    /// faster path where the format allows.
    #[inline(always)]
    fn from_lerp<L: Lerp>(z: L) -> Self::Raw {
        Self::from_d30(z.depth30())
    }

    /// `true` when [`DepthFormat::from_lerp_in_range`] equals
    /// [`DepthFormat::from_lerp`] for every depth `z + k·dz`, `k < n`, of
    /// a span (and the span loop's additions do not wrap): the span stage
    /// then converts without saturating. `false` by default.
    #[inline(always)]
    fn span_in_range<L: Lerp>(z: L, dz: L, n: u32) -> bool {
        let _ = (z, dz, n);
        false
    }

    /// `true` when a triangle whose depths convert to 16 bits without a
    /// clamp (`z16`: its vertex depths and gradients pass [`Depth16`]'s
    /// plane test) has every span in range as
    /// [`DepthFormat::span_in_range`] says (then not asked per span).
    /// `false` by default.
    #[inline(always)]
    fn plane_in_range(z16: bool) -> bool {
        let _ = z16;
        false
    }

    /// The conversion for a span for which [`DepthFormat::span_in_range`]
    /// holds, as a `u32` key ordered as the stored values: the span stage
    /// compares `key < to_key(stored)` and stores `from_key(key)`.
    /// Defaults: unused (`span_in_range` is `false`), so they only need to
    /// be consistent.
    #[inline(always)]
    fn from_lerp_in_range<L: Lerp>(z: L) -> u32 {
        let _ = z;
        0
    }

    /// A stored value as a key (see [`DepthFormat::from_lerp_in_range`]).
    #[inline(always)]
    fn to_key(raw: Self::Raw) -> u32 {
        let _ = raw;
        0
    }

    /// A key back to the stored value.
    #[inline(always)]
    fn from_key(key: u32) -> Self::Raw {
        let _ = key;
        Self::CLEAR
    }
}

/// 16-bit depth: `d30 >> 14`, steps of 2^-16 of the depth range, at most
/// 65534 so that every depth, 1 included, is nearer than the cleared value
/// 65535 (so the last step, `[1 - 2^-15, 1]`, is twice as wide).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Depth16;

impl DepthFormat for Depth16 {
    type Raw = u16;
    const CLEAR: u16 = u16::MAX;

    /// Word stores on ARMv7-M (the pixel formats' 16-bit fill).
    #[inline(always)]
    fn clear_slice(values: &mut [u16]) {
        fill_u16(values, u16::MAX);
    }
    #[inline]
    fn from_d30(d30: u32) -> u16 {
        let v = d30 >> 14;
        if v >= u16::MAX as u32 {
            u16::MAX - 1
        } else {
            v as u16
        }
    }

    /// Fixed values: the clamp of `z >> 14` to `0..=65534` (one `USAT` and
    /// two ALU operations on ARMv7-M); floats: `from_d30(z.depth30())`.
    #[inline(always)]
    fn from_lerp<L: Lerp>(z: L) -> u16 {
        match z.fixed_raw() {
            Some(v) => depth16_fixed(v),
            None => Self::from_d30(z.depth30()),
        }
    }

    /// Fixed values: every depth `z + k·dz`, `k < n`, within `[0,
    /// 65535·2^14)` exactly, without wrapping (the last value in 32-bit
    /// arithmetic on ARMv6-M, conservative; in 64 bits elsewhere);
    /// always `false` for floats.
    #[inline(always)]
    fn span_in_range<L: Lerp>(z: L, dz: L, n: u32) -> bool {
        match (z.fixed_raw(), dz.fixed_raw()) {
            (Some(z), Some(dz)) if L::EXACT_STEPS => {
                if NO_LONG_MUL {
                    span_in_range32(z, dz, n)
                } else {
                    span_in_range64(z, dz, n)
                }
            }
            _ => false,
        }
    }

    #[inline(always)]
    fn plane_in_range(z16: bool) -> bool {
        z16
    }

    /// `z >> 14` without the clamp: at most 65534 in range, so the key is
    /// the stored value.
    #[inline(always)]
    fn from_lerp_in_range<L: Lerp>(z: L) -> u32 {
        match z.fixed_raw() {
            Some(v) => v as u32 >> 14,
            None => Self::from_lerp(z) as u32,
        }
    }

    #[inline(always)]
    fn to_key(raw: u16) -> u32 {
        raw as u32
    }

    #[inline(always)]
    fn from_key(key: u32) -> u16 {
        key as u16
    }
}

/// [`Depth16::from_d30`] of a fixed depth `d·2^30` (`i32`), with one clamp
/// instead of two: `clamp(v >> 14, 0, 65534)`; on ARMv7-M the clamp to
/// `0..=65535` is one `USAT` and 65535 then becomes 65534 by subtracting
/// `(u + 1) >> 16` (two ALU operations instead of a compare and a
/// conditional move). The same value (tested).
#[inline(always)]
fn depth16_fixed(v: i32) -> u16 {
    if NO_LONG_MUL {
        (v >> 14).clamp(0, u16::MAX as i32 - 1) as u16
    } else {
        let u = (v >> 14).clamp(0, u16::MAX as i32) as u32;
        (u - ((u + 1) >> 16)) as u16
    }
}

/// [`Depth16::span_in_range`] for fixed depths in 64 bits (a long
/// multiply-accumulate is one instruction where there is one): the last
/// value exactly. Values between the two ends lie between them (affine),
/// hence in range too, and no partial sum of the span loop wraps.
#[inline(always)]
fn span_in_range64(z: i32, step: i32, n: u32) -> bool {
    let last = z as i64 + step as i64 * (n as i64 - 1);
    n != 0 && (z as u32) < DEPTH16_LIM && (0..DEPTH16_LIM as i64).contains(&last)
}

/// [`span_in_range64`] in 32 bits (ARMv6-M): the offset of the last
/// value, `|step|·(n - 1)`, is computed only when it is below 2^31
/// (either factor bound below), and the first value lies in `[0, 2^30)`,
/// so the last one is exact in a `u32`. Conservative: `false` for the
/// rare spans beyond both bounds.
#[inline(always)]
fn span_in_range32(z: i32, step: i32, n: u32) -> bool {
    let (z, m, s) = (z as u32, n.wrapping_sub(1), step.unsigned_abs());
    let small = (m < 1 << 13 && s < 1 << 18) || (m < 1 << 4 && s < 1 << 27);
    if z >= DEPTH16_LIM || n == 0 || !small {
        return false;
    }
    let off = s * m;
    if step >= 0 {
        z + off < DEPTH16_LIM
    } else {
        off <= z
    }
}

impl Depth16 {
    /// `true` when every pixel of a triangle whose vertex depths are `z`
    /// and whose depth gradients per pixel are `gx`, `gy` gets a depth
    /// within `[0, 65535·2^14)` as the walker computes it (fixed; the
    /// conversions then need no clamp, and the span loop no per-span
    /// check). Conservative: `false` (always for floats) selects the
    /// checks.
    ///
    /// Fixed: every vertex depth within `[2^15, 65535·2^14 - 2^15)`
    /// ([`Depth16::vertices_in_range`]) and both gradients below 2^24 per
    /// pixel. A covered pixel centre lies in the triangle, so the exact
    /// plane there lies between the vertex depths; the walker's value is
    /// `origin + gx·x + gy·y` with the rounded gradients
    /// ([`InvArea::quot`](crate::num::InvArea::quot), within `½ +
    /// |g|·2^-28` of the exact ones) through the rounded origin (`½`), so
    /// it is within `½ + (½ + 2^-4)·(|Δx| + |Δy|) < 2^15` of the plane
    /// for pixels at most 2^14 apart (vertices within ±2^13 pixels,
    /// `COORD_LIMIT_PX`): in range, without wrapping.
    #[inline(always)]
    pub(crate) fn plane_in_range<L: Lerp>(z: [L; 3], gx: L::Grad, gy: L::Grad) -> bool {
        match (z.map(L::fixed_raw), L::fixed_grad(gx), L::fixed_grad(gy)) {
            ([Some(z0), Some(z1), Some(z2)], Some(gx), Some(gy)) => {
                Self::vertices_in_range([z0, z1, z2])
                    && gx.unsigned_abs() < 1 << 24
                    && gy.unsigned_abs() < 1 << 24
            }
            _ => false,
        }
    }

    /// [`Depth16::plane_in_range`] for fixed depths and `i32` gradients:
    /// the same test.
    #[inline(always)]
    pub(crate) fn plane_in_range32(z: [i32; 3], gx: i32, gy: i32) -> bool {
        Self::vertices_in_range(z) & Self::gradients_in_range(gx, gy)
    }

    /// The vertex part of [`Depth16::plane_in_range`]: every depth within
    /// `[2^15, 2^15 + 65535·2^14 - 2^16)`, so that their differences lie
    /// below `2^30` in magnitude (nothing wraps).
    #[inline(always)]
    pub(crate) fn vertices_in_range(z: [i32; 3]) -> bool {
        const M: u32 = 1 << 15;
        let ok = |v: i32| (v.wrapping_sub(M as i32) as u32) < DEPTH16_LIM - 2 * M;
        ok(z[0]) & ok(z[1]) & ok(z[2])
    }

    /// The gradient part of [`Depth16::plane_in_range32`].
    #[inline(always)]
    pub(crate) fn gradients_in_range(gx: i32, gy: i32) -> bool {
        (gx.unsigned_abs() < 1 << 24) & (gy.unsigned_abs() < 1 << 24)
    }
}

/// 32-bit depth: the full 30-bit value.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Depth32;

impl DepthFormat for Depth32 {
    type Raw = u32;
    const CLEAR: u32 = u32::MAX;
    #[inline]
    fn from_d30(d30: u32) -> u32 {
        d30.min(1 << 30)
    }
}

/// A depth buffer for a window (a frame or a band), in caller memory.
///
/// Memory: 2 (16-bit) or 4 (32-bit) bytes per pixel of the window; a
/// 16-row band of a 240-pixel-wide screen in 16 bits is 7 680 bytes.
#[derive(Debug)]
pub struct DepthBuffer<'a, D: DepthFormat> {
    values: &'a mut [D::Raw],
    window: Window,
}

impl<'a, D: DepthFormat> DepthBuffer<'a, D> {
    /// A depth buffer for rows `y0..y1`, `width` wide, cleared.
    ///
    /// # Errors
    /// [`BufferError`] when the slice length is not `width × (y1 - y0)` or
    /// the window is too big.
    pub fn new(
        values: &'a mut [D::Raw],
        width: u32,
        y0: u32,
        y1: u32,
    ) -> Result<Self, BufferError> {
        let window = Window { width, y0, y1 };
        check_window(window, values.len())?;
        let mut b = Self { values, window };
        b.clear();
        Ok(b)
    }

    /// Sets every value to [`DepthFormat::CLEAR`].
    pub fn clear(&mut self) {
        D::clear_slice(self.values);
    }

    /// The window held.
    pub fn window(&self) -> Window {
        self.window
    }

    /// Moves to rows `y0..y0 + rows` and clears.
    ///
    /// # Errors
    /// [`BufferError::BadWindow`] when the window would end below row
    /// [`super::MAX_SCREEN`].
    pub fn move_to(&mut self, y0: u32) -> Result<(), BufferError> {
        let y1 = y0
            .checked_add(self.window.rows())
            .ok_or(BufferError::BadWindow)?;
        let window = Window {
            y0,
            y1,
            ..self.window
        };
        check_window(window, self.values.len())?;
        self.window = window;
        self.clear();
        Ok(())
    }

    /// The values of screen row `y`, or `None` outside the window.
    pub fn row_mut(&mut self, y: u32) -> Option<&mut [D::Raw]> {
        let w = self.window;
        if y < w.y0 || y >= w.y1 {
            return None;
        }
        let start = (y - w.y0) as usize * w.width as usize;
        self.values.get_mut(start..start + w.width as usize)
    }

    /// All values, row-major (for the span stage, which computes the index
    /// range of a span once for the depth buffer and the target).
    #[inline]
    pub(crate) fn values_mut(&mut self) -> &mut [D::Raw] {
        self.values
    }

    /// The values of columns `x0..x1` of screen row `y`, or `None` outside
    /// the window.
    #[inline]
    pub fn span_mut(&mut self, y: u32, x0: u32, x1: u32) -> Option<&mut [D::Raw]> {
        span_range(self.window, y, x0, x1).and_then(|r| self.values.get_mut(r))
    }

    /// The stored value at `(x, y)`, or `None` outside the window.
    pub fn get(&self, x: u32, y: u32) -> Option<D::Raw> {
        let w = self.window;
        if x < w.width && y >= w.y0 && y < w.y1 {
            Some(self.values[(y - w.y0) as usize * w.width as usize + x as usize])
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plane test's bounds, at their edges: vertex depths in `[2^15,
    /// 65535·2^14 - 2^15)`, gradients below 2^24; the 32-bit form agrees
    /// with the 64-bit one; floats always take the checks.
    #[test]
    fn plane_in_range_bounds() {
        const M: i32 = 1 << 15;
        let hi = (DEPTH16_LIM as i32) - M;
        let g = (1 << 24) - 1;
        for (z, gx, gy, want) in [
            ([M, M, M], 0, 0, true),
            ([M - 1, M, M], 0, 0, false),
            ([M, hi - 1, M], g, -g, true),
            ([M, M, hi], 0, 0, false),
            ([-1, M, M], 0, 0, false),
            ([M, M, M], g + 1, 0, false),
            ([M, M, M], 0, -(g + 1), false),
            ([1 << 29; 3], -g, g, true),
        ] {
            let wide = Depth16::plane_in_range::<i32>(z, i64::from(gx), i64::from(gy));
            assert_eq!(wide, want, "{z:?} {gx} {gy}");
            assert_eq!(Depth16::plane_in_range32(z, gx, gy), want);
        }
        // Gradients beyond `i32`: only the 64-bit form sees them.
        assert!(!Depth16::plane_in_range::<i32>([M; 3], 1 << 32, 0));
        assert!(!Depth16::plane_in_range::<f32>([0.5; 3], 0.0, 0.0));
        assert!(!Depth16::plane_in_range::<f64>([0.5; 3], 0.0, 0.0));
    }

    #[test]
    fn conversions_saturate() {
        assert_eq!(Depth16::from_d30(0), 0);
        // Never the cleared value: a depth of 1 still passes the test.
        assert_eq!(Depth16::from_d30(1 << 30), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - 1), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - (1 << 14)), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - (2 << 14)), u16::MAX - 1);
        assert_eq!(Depth16::from_d30((1 << 30) - (3 << 14)), u16::MAX - 2);
        assert_eq!(Depth16::from_d30(u32::MAX), u16::MAX - 1);
        assert_eq!(Depth16::from_d30(1 << 14), 1);
        assert_eq!(Depth32::from_d30(u32::MAX), 1 << 30);
        // The far end: every depth, 1 included, is nearer than CLEAR.
        assert_eq!(Depth16::from_d30((1 << 30) - (1 << 14) - 1), 65534);
        assert_eq!(Depth16::from_d30(1 << 30), 65534);
        assert!(Depth32::from_d30(1 << 30) < Depth32::CLEAR);
    }

    #[test]
    fn cleared_and_banded() {
        let mut v = [0u16; 6];
        let mut d = DepthBuffer::<Depth16>::new(&mut v, 3, 4, 6).unwrap();
        assert_eq!(d.get(2, 5), Some(u16::MAX));
        assert_eq!(d.get(2, 6), None);
        d.row_mut(4).unwrap()[1] = 5;
        d.move_to(6).unwrap();
        assert_eq!(d.get(1, 6), Some(u16::MAX));
        assert!(DepthBuffer::<Depth32>::new(&mut [0u32; 5], 3, 0, 2).is_err());
    }

    #[test]
    fn fast_depth16_equals_the_general_conversion() {
        let mut z = i32::MIN;
        for _ in 0..200_000 {
            assert_eq!(Depth16::from_lerp(z), Depth16::from_d30(z.depth30()), "{z}");
            z = z.wrapping_add(21_467 + (z as u32 % 977) as i32);
        }
        for z in [
            -1,
            0,
            1,
            (1 << 14) - 1,
            1 << 14,
            (65534 << 14) - 1,
            65534 << 14,
            (1 << 30) - (1 << 14) - 1,
            (1 << 30) - (1 << 14),
            (1 << 30) - 1,
            1 << 30,
            i32::MAX,
        ] {
            assert_eq!(Depth16::from_lerp(z), Depth16::from_d30(z.depth30()), "{z}");
            // The ARMv6-M form of the fixed conversion too.
            assert_eq!(
                (z >> 14).clamp(0, u16::MAX as i32 - 1) as u16,
                Depth16::from_d30(z.depth30()),
                "{z}"
            );
        }
        assert_eq!(Depth16::from_lerp(0.5f64), 1 << 15);
        assert!(!Depth16::span_in_range(0.5f32, 0.0, 1));
    }

    #[test]
    fn depth16_span_range_checks_are_sound() {
        // When a check says "in range", every value of the span converts
        // without the clamp to the clamped value, and no step wraps.
        let lim = DEPTH16_LIM as i32;
        let zs = [0, 1, 1 << 14, 1 << 28, lim - 1, lim, -1, i32::MIN, i32::MAX];
        let steps = [
            0,
            1,
            -1,
            1 << 16,
            -(1 << 16),
            1 << 20,
            -(1 << 20),
            1 << 27,
            i32::MIN,
        ];
        for &z in &zs {
            for &dz in &steps {
                for n in [0u32, 1, 2, 15, 16, 17, 240, 4096] {
                    let r64 = span_in_range64(z, dz, n);
                    let r32 = span_in_range32(z, dz, n);
                    assert!(!r32 || r64, "{z} {dz} {n}");
                    assert_eq!(
                        Depth16::span_in_range(z, dz, n),
                        if NO_LONG_MUL { r32 } else { r64 }
                    );
                    if r64 {
                        let mut v = z;
                        for k in 0..n {
                            let exact = z as i64 + dz as i64 * k as i64;
                            assert_eq!(v as i64, exact, "{z} {dz} {n}");
                            assert_eq!(
                                Depth16::from_lerp_in_range(v),
                                Depth16::from_lerp(v) as u32
                            );
                            v = v.wrapping_add(dz);
                        }
                    }
                }
            }
        }
        assert!(span_in_range32(1 << 28, 1 << 16, 200));
        assert!(span_in_range32(lim - 1, -(1 << 20), 16));
        assert!(!span_in_range32(lim - 1, 1, 2));
        assert!(!span_in_range64(0, -1, 2));
        assert!(span_in_range64(0, -1, 1));
    }
}
