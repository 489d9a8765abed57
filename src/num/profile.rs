//! Numeric profiles: which number type each quantity uses, and the knobs.
//!
//! The whole pipeline is generic over a [`Profile`]. The fixed-point
//! profiles use no floating point in their per-vertex and per-pixel paths;
//! the float twins run the very same code with `f32` or `f64`, so comparing
//! a fixed profile with [`F64`] isolates quantization error.
//!
//! | profile     | scalar ([`Real`]) | interpolated ([`Lerp`]) | aimed at           |
//! |-------------|-------------------|-------------------------|--------------------|
//! | [`Fast`]    | `Q16` (Q16.16)    | `i32` fixed             | Cortex-M0          |
//! | [`Precise`] | `Q32` (Q32.32)    | `i32` fixed             | Cortex-M3/M4, host |
//! | [`F32`]     | `f32`             | `f32`                   | Cortex-M4F         |
//! | [`F64`]     | `f64`             | `f64`                   | the float twin     |
//!
//! Each has a `…Pc` variant ([`FastPc`], [`PrecisePc`], [`F32Pc`],
//! [`F64Pc`]) that interpolates colours, normals and positions
//! perspective-correctly ([`Profile::PERSPECTIVE`]).
//!
//! Interpolated fixed-point formats (all `i32`, within ±2^30, see
//! [`Lerp`](super::Lerp)): colour levels `l · 2^16` for `l` in `0..=255`;
//! depth `d · 2^30` for `d` in `[0, 1]`; unit-vector components `n · 2^30`;
//! eye-space coordinates `p · 2^16` (±16384 units; `p · 2^22`, ±256 units,
//! in the perspective-correct profiles).
//!
//! All profiles snap vertices to the same subpixel grid
//! ([`SubpixelBits::DEFAULT`], 1/16 pixel), so they cover the same pixels
//! and differ only in the values they compute.

use super::{Lerp, SubpixelBits, LEVEL_FRAC_BITS};
use super::{Real, Q16, Q32};
use core::fmt::Debug;

/// Fraction bits of an interpolated fixed-point unit-vector component.
pub const UNIT_FRAC_BITS: u32 = 30;
/// Fraction bits of an interpolated fixed-point eye-space coordinate
/// (affine profiles: ±16384 units).
pub const COORD_FRAC_BITS: u32 = 16;
/// Fraction bits of an eye-space coordinate in the perspective-correct
/// fixed profiles (±256 units: `2^22 · 256 = 2^30`, the rasterizer's
/// attribute limit). Those interpolate `p · near/w`, which far
/// from the eye is a small fraction of `p`: 16 bits would leave steps of
/// 2^-16·w/near units (1/1300 unit at w = 50·near), enough to move a
/// highlight by several levels.
pub const COORD_FRAC_BITS_PC: u32 = 22;
/// Fraction bits of an interpolated fixed-point depth.
pub const DEPTH_FRAC_BITS: u32 = 30;

/// A numeric profile: the number types and knobs of the whole pipeline.
pub trait Profile: Copy + Debug + Default + 'static {
    /// Scalar of geometry, lighting and per-pixel shading.
    type Real: Real;
    /// Interpolated attributes (depth, colour, normals, positions).
    type Lerp: Lerp;
    /// Short name (`"fast"`, `"precise"`, `"f32"`, `"f64"`).
    const NAME: &'static str;
    /// Subpixel precision of screen coordinates.
    const SUBPIXEL_BITS: SubpixelBits = SubpixelBits::DEFAULT;
    /// Perspective-correct interpolation of colours, normals and positions
    /// (one division per pixel) instead of affine (screen-space linear,
    /// the classic Gouraud and Phong). Depth is affine in screen space
    /// either way.
    const PERSPECTIVE: bool = false;
    /// Phong's interpolated eye-space positions stored per object relative
    /// to the centre of its bounding sphere, with as many fraction bits as
    /// its radius leaves (up to 30), instead of absolute [`Profile::coord`]
    /// values: the rounded steps of the rasterizer then drift by `2^-12`
    /// of the object's size over 4096 pixels rather than `2^-5` units
    /// (see `render::position`). Affine fixed profiles only (`precise`);
    /// the others keep [`Profile::coord`].
    const POSITION_FRAME: bool = false;
    /// Grey Gouraud vertices keep their depth and grey level in one
    /// interpolated value, 16 bits each (`render::Layout::values_in`: 4
    /// bytes of values per vertex instead of 8): the depth's 16 high bits
    /// (those a 16-bit depth buffer keeps) and the level in Q8.8. Affine
    /// `i32` profiles only (`fast`); see `render::Layout::GouraudMono`
    /// for what it costs.
    const PACKED_GREY: bool = false;

    /// A colour level in `[0, 1]` (not clamped) as an interpolated value.
    fn level(r: Self::Real) -> Self::Lerp;
    /// A depth in `[0, 1]` as an interpolated value.
    fn depth(r: Self::Real) -> Self::Lerp;
    /// A depth given in Q2.30 (`2^30` is 1) as an interpolated value.
    /// (Default: through [`Profile::depth`], rounded to the scalar.)
    #[inline]
    fn depth_q30(d: i32) -> Self::Lerp {
        Self::depth(Self::Real::from_fixed_i32(d, 30))
    }
    /// A colour level given in Q16 levels (`255 · 2^16` is full) as an
    /// interpolated value. (Default: through [`Profile::level`], rounded
    /// to the scalar.)
    #[inline]
    fn level_q16(l: i32) -> Self::Lerp {
        Self::level(Self::Real::from_fixed_i32(l, 16).div(Self::Real::from_i32(255)))
    }
    /// A unit-vector component as an interpolated value.
    fn unit(r: Self::Real) -> Self::Lerp;
    /// An interpolated unit-vector component back as a scalar.
    fn unit_back(l: Self::Lerp) -> Self::Real;
    /// An eye-space coordinate as an interpolated value.
    fn coord(r: Self::Real) -> Self::Lerp;
    /// An interpolated eye-space coordinate back as a scalar.
    fn coord_back(l: Self::Lerp) -> Self::Real;
}

macro_rules! fixed_profile {
    ($name:ident, $real:ty, $label:literal, $pc:literal, $frame:literal, $grey:literal, $doc:literal) => {
        #[doc = $doc]
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        pub struct $name;

        fixed_profile_impl!([] $name, $real, $label, $pc, $frame, $grey, SubpixelBits::DEFAULT);
    };
}

/// The `Profile` impl of a fixed profile: type `$ty` with generics
/// `[$g]`, scalar `$real`, perspective `$pc`, position frame `$frame`,
/// packed grey values `$grey` and subpixel bits `$sub`.
macro_rules! fixed_profile_impl {
    ([$($g:tt)*] $ty:ty, $real:ty, $label:literal, $pc:literal, $frame:literal, $grey:literal, $sub:expr) => {
        impl<$($g)*> Profile for $ty {
            type Real = $real;
            type Lerp = i32;
            const NAME: &'static str = $label;
            const SUBPIXEL_BITS: SubpixelBits = $sub;
            const PERSPECTIVE: bool = $pc;
            const POSITION_FRAME: bool = $frame;
            const PACKED_GREY: bool = $grey;

            #[inline]
            fn level(r: $real) -> i32 {
                r.mul_i32(255).to_fixed_i32(LEVEL_FRAC_BITS)
            }
            #[inline]
            fn depth(r: $real) -> i32 {
                r.to_fixed_i32(DEPTH_FRAC_BITS)
            }
            #[inline(always)]
            fn depth_q30(d: i32) -> i32 {
                d >> (30 - DEPTH_FRAC_BITS)
            }
            #[inline(always)]
            fn level_q16(l: i32) -> i32 {
                l >> (16 - LEVEL_FRAC_BITS)
            }
            #[inline]
            fn unit(r: $real) -> i32 {
                r.to_fixed_i32(UNIT_FRAC_BITS)
            }
            #[inline]
            fn unit_back(l: i32) -> $real {
                <$real>::from_fixed_i32(l, UNIT_FRAC_BITS)
            }
            #[inline]
            fn coord(r: $real) -> i32 {
                r.to_fixed_i32(if $pc {
                    COORD_FRAC_BITS_PC
                } else {
                    COORD_FRAC_BITS
                })
            }
            #[inline]
            fn coord_back(l: i32) -> $real {
                <$real>::from_fixed_i32(
                    l,
                    if $pc {
                        COORD_FRAC_BITS_PC
                    } else {
                        COORD_FRAC_BITS
                    },
                )
            }
        }
    };
}

fixed_profile!(
    Fast,
    Q16,
    "fast",
    false,
    false,
    true,
    "Fixed point for the Cortex-M0: Q16.16 scalars, `i32` interpolation."
);
fixed_profile!(
    Precise,
    Q32,
    "precise",
    false,
    true,
    false,
    "Fixed point with more bits: Q32.32 scalars, `i32` interpolation."
);
fixed_profile!(
    FastPc,
    Q16,
    "fast-pc",
    true,
    false,
    false,
    "[`Fast`] with perspective-correct interpolation."
);
fixed_profile!(
    PrecisePc,
    Q32,
    "precise-pc",
    true,
    false,
    false,
    "[`Precise`] with perspective-correct interpolation."
);

/// [`Fast`] with `B` subpixel bits instead of [`SubpixelBits::DEFAULT`]
/// (4): the knob that trades coverage accuracy for coordinate range
/// ([`SubpixelBits::coord_limit`]). `B` must lie in
/// `SubpixelBits::MIN..=SubpixelBits::MAX` (`1..=8`); another value is a
/// compile-time error where the profile is used. Everything else, and the
/// name `"fast"`, is [`Fast`]'s; `FastSub<4>` renders exactly as [`Fast`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FastSub<const B: u32>;

fixed_profile_impl!(
    [const B: u32] FastSub<B>,
    Q16,
    "fast",
    false,
    false,
    true,
    match SubpixelBits::new(B) {
        Ok(b) => b,
        Err(_) => panic!("FastSub<B>: B outside SubpixelBits::MIN..=SubpixelBits::MAX"),
    }
);

macro_rules! float_profile {
    ($name:ident, $t:ty, $label:literal, $pc:literal, $doc:literal) => {
        #[doc = $doc]
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        pub struct $name;

        impl Profile for $name {
            type Real = $t;
            type Lerp = $t;
            const NAME: &'static str = $label;
            const PERSPECTIVE: bool = $pc;

            #[inline]
            fn level(r: $t) -> $t {
                r * 255.0
            }
            #[inline]
            fn depth(r: $t) -> $t {
                r
            }
            #[inline]
            fn depth_q30(d: i32) -> $t {
                d as $t / (1u32 << 30) as $t
            }
            #[inline]
            fn level_q16(l: i32) -> $t {
                l as $t / 65536.0
            }
            #[inline]
            fn unit(r: $t) -> $t {
                r
            }
            #[inline]
            fn unit_back(l: $t) -> $t {
                l
            }
            #[inline]
            fn coord(r: $t) -> $t {
                r
            }
            #[inline]
            fn coord_back(l: $t) -> $t {
                l
            }
        }
    };
}

float_profile!(
    F32,
    f32,
    "f32",
    false,
    "The `f32` float twin (for FPUs such as the Cortex-M4F's)."
);
float_profile!(
    F64,
    f64,
    "f64",
    false,
    "The `f64` float twin: the reference for quantization error."
);
float_profile!(
    F32Pc,
    f32,
    "f32-pc",
    true,
    "[`F32`] with perspective-correct interpolation."
);
float_profile!(
    F64Pc,
    f64,
    "f64-pc",
    true,
    "[`F64`] with perspective-correct interpolation: the twin of the `-pc` profiles."
);
