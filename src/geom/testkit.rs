//! Test helpers shared by the integer kernels' tests ([`super::fused`],
//! [`super::cull`], [`super::q16`]): one random source and the random
//! objects they are checked on.

use super::q16::Proj16;

/// A xorshift64 sequence from `seed` (not 0): raw 64-bit values.
pub(crate) fn xorshift(mut s: u64) -> impl FnMut() -> u64 {
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    }
}

/// Uniform values in `[0, 1)` from [`xorshift`] (53 bits).
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f64 {
    let mut next = xorshift(seed);
    move || (next() >> 11) as f64 / (1u64 << 53) as f64
}

/// The rotation `Rz(c) Ry(b) Rx(a)`.
pub(crate) fn rotation(a: f64, b: f64, c: f64) -> [[f64; 3]; 3] {
    let (sa, ca, sb, cb, sc, cc) = (a.sin(), a.cos(), b.sin(), b.cos(), c.sin(), c.cos());
    [
        [cc * cb, cc * sb * sa - sc * ca, cc * sb * ca + sc * sa],
        [sc * cb, sc * sb * sa + cc * ca, sc * sb * ca - cc * sa],
        [-sb, cb * sa, cb * ca],
    ]
}

/// The projection of scale `k` (pixels per unit at unit depth) and near
/// plane `near`, centred at `(120, cy)` pixels in `sub`-bit subpixels,
/// with the rasterizer's 8 192-pixel limit.
pub(crate) fn proj(k: f64, near: f64, sub: u32, cy: i32) -> Proj16 {
    Proj16 {
        k: (k * 65536.0) as i32,
        near: (near * 65536.0) as i32,
        cx: 120 << sub,
        cy: cy << sub,
        lim: 8192 << sub,
    }
}
