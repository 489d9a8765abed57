//! Number formats and conversions.

pub(crate) mod approx16;
mod approx32;
mod fixed_point;
mod float;
mod isqrt;
mod lerp;
mod light;
mod profile;
mod real;
mod recip;
mod subpixel;
mod tables;
pub(crate) mod wide;

#[cfg(test)]
mod edge_tests;
#[cfg(test)]
mod testkit;

pub use self::fixed_point::{Q16, Q32};
pub use self::isqrt::isqrt_u64;
pub(crate) use self::isqrt::{isqrt_rem_u128, isqrt_rem_u64};
pub use self::lerp::{Lerp, ATTR_LIMIT, DEPTH_ONE, LEVEL_FRAC_BITS};
pub use self::light::{light_halves, scale255, unit30};
pub use self::profile::{
    F32Pc, F64Pc, Fast, FastPc, FastSub, Precise, PrecisePc, Profile, COORD_FRAC_BITS,
    COORD_FRAC_BITS_PC, DEPTH_FRAC_BITS, F32, F64, UNIT_FRAC_BITS,
};
pub use self::real::{GenericKernels, Kernels, Only, Q16Kernels, Raw16, Real};
pub use self::recip::{InvArea, Recip};
pub use self::subpixel::{BadSubpixelBits, SubpixelBits, COORD_LIMIT_PX};
pub use self::tables::{rsqrt_pair_table, rsqrt_quarter_table, spec_table};
