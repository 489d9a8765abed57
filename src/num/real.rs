//! The [`Real`] scalar trait that geometry, lighting and shading are written
//! against.
//!
//! Four implementations exist:
//!
//! | type            | format      | maths                                   |
//! |-----------------|-------------|-----------------------------------------|
//! | [`Q16`](super::Q16) | Q16.16  | integer kernels, 32-bit where possible  |
//! | [`Q32`](super::Q32) | Q32.32  | integer kernels, 64/128-bit             |
//! | `f32`           | IEEE single | `micromath` seed + Newton, `libm`       |
//! | `f64`           | IEEE double | `libm`                                  |
//!
//! For the fixed types every method except the `f32`/`f64` conversions is
//! pure integer arithmetic, saturates instead of overflowing and never
//! panics. The float types follow IEEE arithmetic for `+ - *`; the methods
//! below map NaN and infinities to defined finite results where stated.
//!
//! Error bounds of each approximation are given per method below and are
//! checked against `f64` references over dense sweeps by the tests in the
//! file of each kernel (`approx16.rs`, `approx32.rs`, `float.rs`), next to
//! a constant holding the bound.

use core::fmt::Debug;
use core::marker::PhantomData;
use core::ops::{Add, AddAssign, Mul, MulAssign, Neg, Sub, SubAssign};

/// A real-number scalar: fixed point ([`Q16`](super::Q16),
/// [`Q32`](super::Q32)) or floating point (`f32`, `f64`).
///
/// For the fixed types `+`, `-`, `*` and unary `-` saturate at
/// [`MIN`](Real::MIN)/[`MAX`](Real::MAX); products round to nearest.
pub trait Real:
    Copy
    + Debug
    + PartialEq
    + PartialOrd
    + Default
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
{
    /// Zero.
    const ZERO: Self;
    /// One.
    const ONE: Self;
    /// Largest finite value.
    const MAX: Self;
    /// Smallest (most negative) finite value.
    const MIN: Self;
    /// Resolution: one ulp for fixed types, `f32::EPSILON`/`f64::EPSILON`
    /// for floats.
    const EPSILON: Self;

    /// The kernels this type runs ([`Kernels`]): [`Q16Kernels`] for
    /// [`Q16`](super::Q16) (the integer kernels of the `fast` profiles),
    /// [`GenericKernels`] for the other types. Chosen by type: each
    /// monomorphised caller compiles one path.
    type Kernels: Kernels<Self>;

    /// Saturating conversion, rounded to nearest; NaN maps to
    /// [`ZERO`](Real::ZERO), infinities saturate.
    fn from_f32(v: f32) -> Self;
    /// Saturating conversion, rounded to nearest; NaN maps to
    /// [`ZERO`](Real::ZERO), infinities saturate.
    fn from_f64(v: f64) -> Self;
    /// Saturating conversion from an integer.
    fn from_i32(v: i32) -> Self;
    /// `num / den` rounded to nearest (ties away from zero). `den == 0`
    /// gives [`MAX`](Real::MAX)/[`MIN`](Real::MIN) by the sign of `num`,
    /// `0/0` gives [`ZERO`](Real::ZERO). Integer-only for the fixed types.
    fn from_ratio(num: i32, den: i32) -> Self;
    /// Conversion to `f32` (rounded to nearest).
    fn to_f32(self) -> f32;
    /// Conversion to `f64` (exact for `Q16` and `f32`).
    fn to_f64(self) -> f64;
    /// Raw value in a fixed-point format with `frac` fraction bits (values
    /// above 30 are treated as 30), rounded to nearest, saturated to `i32`.
    /// NaN gives 0.
    fn to_fixed_i32(self, frac: u32) -> i32;
    /// Value of `raw / 2^frac` (`frac` above 30 is treated as 30), rounded
    /// to nearest and saturated.
    fn from_fixed_i32(raw: i32, frac: u32) -> Self;

    /// Absolute value (saturating: `|MIN|` gives `MAX` for fixed types).
    fn abs(self) -> Self;
    /// The smaller of two values.
    fn min(self, o: Self) -> Self;
    /// The larger of two values.
    fn max(self, o: Self) -> Self;
    /// `self.max(lo).min(hi)`: never panics, gives `hi` if `lo > hi`.
    fn clamp(self, lo: Self, hi: Self) -> Self;
    /// `self * k`, saturating.
    fn mul_i32(self, k: i32) -> Self;
    /// `self / 2` (fixed types: rounded toward zero).
    fn half(self) -> Self;
    /// Saturating division rounded to nearest; `x/0` saturates by the sign
    /// of `x`, `0/0 = 0` (floats: results beyond the finite range saturate
    /// too; NaN gives 0). Fixed types use integer division: per-vertex or
    /// per-triangle use only.
    fn div(self, d: Self) -> Self;
    /// `1/x`, as [`div`](Real::div): `1/0` gives `MAX`.
    fn recip(self) -> Self;
    /// Square root; negative input (and NaN) gives zero.
    ///
    /// Fixed types: exact digit-by-digit root, correctly rounded (<= 1/2
    /// ulp). `f32`: <= 2^-22 relative (measured 2^-22.6, about 1.3 ulp).
    /// `f64`: correctly rounded (`libm`). Per-vertex use for fixed types
    /// (a bit-by-bit loop); per-pixel code should use `rsqrt`.
    fn sqrt(self) -> Self;
    /// `1/sqrt(x)`; `x <= 0` (and NaN, `+inf`) gives zero, so normalising a
    /// zero vector yields the zero vector: defined, no NaN.
    ///
    /// Error, tested over dense sweeps of the whole positive range:
    /// `Q16` <= 2^-15 relative + 1/2 ulp (measured 2^-15.46 + 1/2 ulp;
    /// the half ulp is the rounding of the output, which dominates for
    /// `x > 8`); `Q32` <= 2^-30 relative + 1/2 ulp (measured 2^-30.28);
    /// `f32` <= 2^-22 relative (measured 2^-22.44); `f64` <= 1.5 ulp
    /// (measured 1.47: `1 / sqrt(x)`, two correctly rounded operations).
    fn rsqrt(self) -> Self;
    /// `x^n` for `x` in `[0, 1]` and `n >= 0` (specular power); `x <= 0`
    /// gives 0 except `0^0 = 1`; `x >= 1` or `n <= 0` (or NaN `n`) gives 1.
    /// No division.
    ///
    /// Error of the output (absolute) for the given, representable `x`,
    /// tested for every Q16 `x` in `[0, 1]` (random for Q32) and `n` in
    /// {0, 0.5, 1, 2, 3.3, 10, 25, 100, 800, 1000, 10000, 32767}: `Q16` <=
    /// 2^-14 (measured 2^-14.79), `Q32` <= 2^-31 (measured 2^-32.99, i.e.
    /// rounding), `f32` <= 2^-23 (measured 2^-24.3), `f64` <= 2^-51.
    ///
    /// The rounding of `x` itself, done by the caller, is not included:
    /// near `x = 1` it moves the output by `n x^(n-1) dx`, up to
    /// `n / e * dx`. With `dx` = 1/2 ulp that is 2^-8.8 for Q16 and 2^-24.8
    /// for Q32 at `n = 800` (Q16 `0.999^800` = 0.4466 instead of 0.4491).
    fn powf(self, n: Self) -> Self;
    /// `(sin x, cos x)` of an angle in radians (any finite angle, reduced
    /// internally; non-finite floats give `(0, 1)`).
    ///
    /// Error (absolute), over all representable angles: `Q16` <= 2^-16
    /// (measured 2^-16.44; 2^-17, the output rounding, for `|x| < 8`);
    /// `Q32` <= 2^-32 (measured 2^-32.97); `f32` <= 2^-24 (`libm`,
    /// measured 2^-25); `f64` <= 2^-52 (`libm`).
    fn sin_cos(self) -> (Self, Self);
    /// 8-bit level: `clamp(self, 0, 1) * 255` rounded to nearest (NaN gives
    /// 0).
    fn to_level(self) -> u8;
}

/// The kernels of a scalar type ([`Real::Kernels`]), chosen at compile
/// time: [`Q16Kernels`] for [`Q16`](super::Q16), [`GenericKernels`] for
/// the others. Sealed: no other implementation exists.
///
/// Code generic over the scalar hands [`Kernels::pick`] its two forms of
/// a computation: the integer form (32-bit products where ranges allow,
/// exact widening products elsewhere, table reciprocals instead of
/// division) on the raw Q16.16 values that [`Raw16`] reads and writes,
/// and the generic form on the scalar's own operations. The type picks
/// one; the other is never instantiated for it, so no branch and no dead
/// path is compiled into either.
///
/// Values that only the integer form uses (its constants, built once and
/// kept in a generic caller's state) are held as [`Kernels::Only`]: the
/// value itself for [`Q16Kernels`], nothing (`()`) for
/// [`GenericKernels`], so generic code stores no `Option` field that is
/// `None` by type, and the other types neither compute nor store the
/// integer constants. [`Kernels::only`] builds one, [`Kernels::map`]
/// makes one from another, [`Kernels::get`] reads it.
pub trait Kernels<R: Real>: sealed::Sealed {
    /// A value of the integer form: `T` for [`Q16Kernels`], `()` for
    /// [`GenericKernels`].
    type Only<T>;

    /// `q16(Raw16)` for [`Q16Kernels`], `generic()` for
    /// [`GenericKernels`].
    fn pick<T>(q16: impl FnOnce(Raw16<R>) -> T, generic: impl FnOnce() -> T) -> T;

    /// The integer form's value `q16(Raw16)` for [`Q16Kernels`]; nothing
    /// (`q16` not called) for [`GenericKernels`].
    fn only<T>(q16: impl FnOnce(Raw16<R>) -> T) -> Self::Only<T>;

    /// The integer form's value `f(Raw16, v)` made from its value `v`
    /// ([`Q16Kernels`]); nothing for [`GenericKernels`].
    fn map<T, U>(v: &Self::Only<T>, f: impl FnOnce(Raw16<R>, &T) -> U) -> Self::Only<U>;

    /// The integer form's value with the raw access: `Some` for
    /// [`Q16Kernels`], `None` for [`GenericKernels`]. A constant of the
    /// type, so each type compiles one arm of a `match` on it (unlike a
    /// closure handed to [`Kernels::pick`], the arm is inlined where it
    /// stands: the vertex paths that read an object's constants per
    /// vertex use this).
    fn get<T>(v: &Self::Only<T>) -> Option<(Raw16<R>, &T)>;
}

/// [`Kernels::Only`] of scalar `R`: `T` for `Q16`, `()` for the others.
pub type Only<R, T> = <<R as Real>::Kernels as Kernels<R>>::Only<T>;

mod sealed {
    /// Only the two kernel sets of `num` implement [`Kernels`](super::Kernels).
    pub trait Sealed {}
    impl Sealed for super::GenericKernels {}
    impl Sealed for super::Q16Kernels {}
}

/// The generic kernels: the scalar's own operations (`Q32`, `f32`, `f64`).
#[derive(Clone, Copy, Debug)]
pub enum GenericKernels {}

impl<R: Real> Kernels<R> for GenericKernels {
    type Only<T> = ();

    #[inline(always)]
    fn pick<T>(_: impl FnOnce(Raw16<R>) -> T, generic: impl FnOnce() -> T) -> T {
        generic()
    }

    #[inline(always)]
    fn only<T>(_: impl FnOnce(Raw16<R>) -> T) {}

    #[inline(always)]
    fn map<T, U>(_: &(), _: impl FnOnce(Raw16<R>, &T) -> U) {}

    #[inline(always)]
    fn get<T>(_: &()) -> Option<(Raw16<R>, &T)> {
        None
    }
}

/// The integer kernels of the `fast` profiles, on raw Q16.16 values
/// ([`Raw16`]): the kernels of [`Q16`](super::Q16) only.
#[derive(Clone, Copy, Debug)]
pub enum Q16Kernels {}

impl Kernels<super::Q16> for Q16Kernels {
    type Only<T> = T;

    #[inline(always)]
    fn pick<T>(q16: impl FnOnce(Raw16<super::Q16>) -> T, _: impl FnOnce() -> T) -> T {
        q16(Raw16::Q16)
    }

    #[inline(always)]
    fn only<T>(q16: impl FnOnce(Raw16<super::Q16>) -> T) -> T {
        q16(Raw16::Q16)
    }

    #[inline(always)]
    fn map<T, U>(v: &T, f: impl FnOnce(Raw16<super::Q16>, &T) -> U) -> U {
        f(Raw16::Q16, v)
    }

    #[inline(always)]
    fn get<T>(v: &T) -> Option<(Raw16<super::Q16>, &T)> {
        Some((Raw16::Q16, v))
    }
}

/// Exact access to the raw Q16.16 bits of a scalar that runs
/// [`Q16Kernels`]: [`raw`](Raw16::raw) and [`from_raw`](Raw16::from_raw)
/// read and write them without rounding. It exists for `Q16` only
/// ([`Raw16::Q16`], which [`Q16Kernels::pick`] hands out), so an integer
/// path taken with it runs on `Q16` values only.
#[derive(Debug)]
pub struct Raw16<R>(PhantomData<R>);

impl Raw16<super::Q16> {
    /// The access to `Q16`'s own bits.
    pub const Q16: Self = Self(PhantomData);
}

impl<R> Clone for Raw16<R> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<R> Copy for Raw16<R> {}

impl<R: Real> Raw16<R> {
    /// The raw Q16.16 bits of `v` (exact).
    #[inline(always)]
    pub fn raw(self, v: R) -> i32 {
        v.to_fixed_i32(16)
    }

    /// The value of raw Q16.16 bits `b` (exact).
    #[inline(always)]
    pub fn from_raw(self, b: i32) -> R {
        R::from_fixed_i32(b, 16)
    }
}

#[cfg(test)]
mod tests {
    use super::{Kernels, Raw16, Real};
    use crate::num::{Q16, Q32};

    fn kernels<R: Real>() -> &'static str {
        R::Kernels::pick(|_| "q16", || "generic")
    }

    /// Each scalar type runs its own kernels: the integer ones for `Q16`
    /// only.
    #[test]
    fn kernels_by_type() {
        assert_eq!(kernels::<Q16>(), "q16");
        assert_eq!(kernels::<Q32>(), "generic");
        assert_eq!(kernels::<f32>(), "generic");
        assert_eq!(kernels::<f64>(), "generic");
    }

    /// The integer form's value: built and read for `Q16` only.
    fn only_sum<R: Real>() -> i32 {
        let v = R::Kernels::only(|q| q.raw(R::ONE) + 1);
        let v = R::Kernels::map(&v, |_, v| v * 2);
        match R::Kernels::get(&v) {
            Some((_, v)) => 5 + v,
            None => -5,
        }
    }

    /// An integer-form value exists for `Q16` (read by the integer form)
    /// and is nothing for the other types (only the generic form runs).
    #[test]
    fn only_by_type() {
        assert_eq!(only_sum::<Q16>(), 5 + 2 * 65_537);
        assert_eq!(only_sum::<Q32>(), -5);
        assert_eq!(only_sum::<f32>(), -5);
        assert_eq!(only_sum::<f64>(), -5);
        let size = |n| n * core::mem::size_of::<i32>();
        assert_eq!(core::mem::size_of::<super::Only<Q16, [i32; 8]>>(), size(8));
        assert_eq!(core::mem::size_of::<super::Only<Q32, [i32; 8]>>(), size(0));
        assert_eq!(core::mem::size_of::<super::Only<f32, [i32; 8]>>(), size(0));
    }

    /// `Raw16` reads and writes `Q16`'s bits exactly.
    #[test]
    fn raw16_is_exact() {
        let q = Raw16::<Q16>::Q16;
        for b in [
            i32::MIN,
            -65_537,
            -1,
            0,
            1,
            3,
            65_536,
            0x1234_5678,
            i32::MAX,
        ] {
            assert_eq!(q.raw(Q16::from_bits(b)), b);
            assert_eq!(q.from_raw(b), Q16::from_bits(b));
        }
    }
}
