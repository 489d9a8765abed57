//! Constant tables for the fixed-point kernels in `approx16` and `approx32`.
//!
//! The entries were generated once with 200-bit arithmetic (Python `mpmath`)
//! and rounded to nearest; the unit tests at the bottom re-derive every entry
//! with `f64` maths and check agreement to within `f64` resolution.

/// `1/sqrt(1 + j/64)` for `j` in `0..=192` (that is `f` in `[1, 4]`), Q1.31,
/// rounded to nearest.
pub(crate) const RSQRT: [u32; 193] = [
    0x80000000, 0x7f02f623, 0x7e0bb221, 0x7d19fca0, 0x7c2da123, 0x7b466dd8, 0x7a64336b, 0x7986c4e4,
    0x78adf778, 0x77d9a26e, 0x77099efb, 0x763dc824, 0x7575faa4, 0x74b214d4, 0x73f1f68d, 0x73358118,
    0x727c9717, 0x71c71c72, 0x7114f644, 0x70660acc, 0x6fba415c, 0x6f11824c, 0x6e6bb6e9, 0x6dc8c96e,
    0x6d28a4f0, 0x6c8b355b, 0x6bf06762, 0x6b582874, 0x6ac266ba, 0x6a2f1107, 0x699e16d0, 0x690f682b,
    0x6882f5c0, 0x67f8b0c5, 0x67708af9, 0x66ea769b, 0x66666666, 0x65e44d8c, 0x65641fae, 0x64e5d0da,
    0x64695585, 0x63eea287, 0x6375ad16, 0x62fe6ac2, 0x6288d173, 0x6214d764, 0x61a27320, 0x61319b7c,
    0x60c2479b, 0x60546ee2, 0x5fe808fc, 0x5f7d0dd6, 0x5f137599, 0x5eab38ac, 0x5e444faf, 0x5ddeb37a,
    0x5d7a5d1b, 0x5d1745d1, 0x5cb56711, 0x5c54ba7d, 0x5bf539e5, 0x5b96df46, 0x5b39a4c7, 0x5add84bb,
    0x5a82799a, 0x5a287e03, 0x59cf8cbc, 0x5977a0ac, 0x5920b4df, 0x58cac480, 0x5875cade, 0x5821c364,
    0x57cea99d, 0x577c7930, 0x572b2de0, 0x56dac38e, 0x568b3632, 0x563c81e0, 0x55eea2c4, 0x55a19522,
    0x55555555, 0x5509dfd0, 0x54bf311a, 0x547545d0, 0x542c1aa4, 0x53e3ac5b, 0x539bf7cd, 0x5354f9e7,
    0x530eafa5, 0x52c91618, 0x52842a5f, 0x523fe9ac, 0x51fc5140, 0x51b95e6b, 0x51770e8f, 0x51355f1a,
    0x50f44d89, 0x50b3d768, 0x5073fa50, 0x5034b3e7, 0x4ff601e0, 0x4fb7e1fa, 0x4f7a5202, 0x4f3d4fcf,
    0x4f00d944, 0x4ec4ec4f, 0x4e8986ea, 0x4e4ea718, 0x4e144ae9, 0x4dda7073, 0x4da115da, 0x4d683948,
    0x4d2fd8f4, 0x4cf7f31b, 0x4cc08605, 0x4c899000, 0x4c530f65, 0x4c1d0294, 0x4be767f5, 0x4bb23df9,
    0x4b7d8317, 0x4b4935cf, 0x4b1554a6, 0x4ae1de2a, 0x4aaed0f0, 0x4a7c2b93, 0x4a49ecb3, 0x4a1812fa,
    0x49e69d16, 0x49b589bb, 0x4984d7a4, 0x49548592, 0x49249249, 0x48f4fc97, 0x48c5c34b, 0x4896e53d,
    0x48686148, 0x483a364d, 0x480c6332, 0x47dee6e1, 0x47b1c049, 0x4784ee60, 0x4758701c, 0x472c447c,
    0x47006a81, 0x46d4e130, 0x46a9a794, 0x467ebcba, 0x46541fb4, 0x4629cf98, 0x45ffcb80, 0x45d6128a,
    0x45aca3d5, 0x45837e88, 0x455aa1cb, 0x45320cc8, 0x4509beb0, 0x44e1b6b4, 0x44b9f40b, 0x449275ed,
    0x446b3b96, 0x44444444, 0x441d8f3b, 0x43f71bbf, 0x43d0e917, 0x43aaf68f, 0x43854374, 0x435fcf15,
    0x433a98c6, 0x43159fdc, 0x42f0e3ae, 0x42cc6398, 0x42a81ef6, 0x42841527, 0x4260458e, 0x423caf8d,
    0x4219528b, 0x41f62df2, 0x41d3412a, 0x41b08ba2, 0x418e0cc8, 0x416bc40d, 0x4149b0e5, 0x4127d2c3,
    0x41062920, 0x40e4b374, 0x40c3713b, 0x40a261ef, 0x40818512, 0x4060da22, 0x404060a1, 0x40201814,
    0x40000000,
];
/// `round(2^13 / (1 + j/64))` for `j` in `0..=64`: short reciprocals of the
/// log2 reduction points; the product with a mantissa is exact.
pub(crate) const LOG_INV: [u16; 65] = [
    0x2000, 0x1f82, 0x1f08, 0x1e91, 0x1e1e, 0x1dae, 0x1d42, 0x1cd8, 0x1c72, 0x1c0e, 0x1bad, 0x1b4f,
    0x1af3, 0x1a99, 0x1a42, 0x19ed, 0x199a, 0x1949, 0x18fa, 0x18ad, 0x1862, 0x1818, 0x17d0, 0x178a,
    0x1746, 0x1703, 0x16c1, 0x1681, 0x1643, 0x1606, 0x15ca, 0x158f, 0x1555, 0x151d, 0x14e6, 0x14b0,
    0x147b, 0x1447, 0x1414, 0x13e2, 0x13b1, 0x1381, 0x1352, 0x1324, 0x12f7, 0x12ca, 0x129e, 0x1273,
    0x1249, 0x1220, 0x11f7, 0x11cf, 0x11a8, 0x1181, 0x115b, 0x1136, 0x1111, 0x10ed, 0x10c9, 0x10a7,
    0x1084, 0x1062, 0x1041, 0x1020, 0x1000,
];
/// `log2(2^13 / LOG_INV[j])` in Q2.62, rounded to nearest (entry 0 is 0,
/// entry 64 is exactly 1).
pub(crate) const LOG_T: [u64; 65] = [
    0x0,
    0x16e625317aa9f87,
    0x2d6a1c52f5f99c1,
    0x43b6432b2a266a0,
    0x5995a13fe04213d,
    0x6f33ca6b333c90c,
    0x845a1c728bd4621,
    0x99689f234975b56,
    0xadf54737b6b2caa,
    0xc262cfd61c9ae6a,
    0xd67980195f3c6e6,
    0xea34c204bd78498,
    0xfdc6be122e9cce9,
    0x1112ce25b2972147,
    0x1242c4835c0305ff,
    0x136f90ddb6fff74f,
    0x149906fa396a0dc8,
    0x15bef9b1c239d6f2,
    0x16e13af9f3a146c8,
    0x17ff9befdea5c8b4,
    0x1919ece40d488d44,
    0x1a33d25fcb1fac3b,
    0x1b495d4e9185f753,
    0x1c5a5bc3b12430f1,
    0x1d669b36b069f7d9,
    0x1e71ebad35f088b0,
    0x1f7c3c01293621e5,
    0x20816024b394dec6,
    0x2181232e0309b521,
    0x227f8111cffbd4c5,
    0x237c666e7d61bda6,
    0x2477bf743feaa3ad,
    0x257177e5d7f8f897,
    0x26651b755acf0c89,
    0x2756dd75fbc321f0,
    0x2846a853ae553ba9,
    0x2934661855b76a53,
    0x2a20006e2cb82aec,
    0x2b0960a27cf9c325,
    0x2bf06fa8a85ab682,
    0x2cd5161d8751e5e1,
    0x2db73c4b1ed8a7bf,
    0x2e96ca2cb04dd5c7,
    0x2f73a77325861c6a,
    0x304dbb89daff87ab,
    0x3129d780c95c936f,
    0x32030f581d1c77f8,
    0x32d9499d2e870bdf,
    0x33ac6ca593f5f448,
    0x347c5e95887ec06b,
    0x354e29004a717be4,
    0x361ca4ed6b2696a8,
    0x36e7b7cd16b43761,
    0x37b48d2eecf210b4,
    0x387ddadb4467d53b,
    0x394385a699e05a80,
    0x3a0adb2f97d08884,
    0x3ace6e0b455fc978,
    0x3b93a29d3f2e73b2,
    0x3c4f685d9661dbe8,
    0x3d124611b8a972cf,
    0x3dd11f7bc581f412,
    0x3e8bd82ce8547f87,
    0x3f480d7a4887bd74,
    0x4000000000000000,
];
/// `2^(-j/64)` for `j` in `0..=64`, Q1.63, rounded to nearest.
pub(crate) const EXP2: [u64; 65] = [
    0x8000000000000000,
    0x7e9f06067a4360ba,
    0x7d41d96db915019d,
    0x7be86fb985689ddc,
    0x7a92be8a92436616,
    0x7940bb9e2cffd89d,
    0x77f25ccdee6d7ae6,
    0x76a7980f6cca15c2,
    0x75606373ee921c97,
    0x741cb5281e25ee34,
    0x72dc8373be41a454,
    0x719fc4b95f452d29,
    0x70666f76154a7089,
    0x6f307a412f074892,
    0x6dfddbcbed791bab,
    0x6cce8ae13c57ebdb,
    0x6ba27e656b4eb57a,
    0x6a79ad55e7f6fd10,
    0x69540ec8f895722d,
    0x683199ed779592ca,
    0x6712460a8fc24072,
    0x65f60a7f79393e2e,
    0x64dcdec3371793d1,
    0x63c6ba6455dcd8ae,
    0x62b39508aa836d6f,
    0x61a3666d124bb204,
    0x6096266533384a2b,
    0x5f8bccdb3d398841,
    0x5e8451cfac061b5f,
    0x5d7fad59099f22fe,
    0x5c7dd7a3b17dcf75,
    0x5b7ec8f19468bbc9,
    0x5a827999fcef3242,
    0x5988e20954889245,
    0x5891fac0e95612c8,
    0x579dbc56b48521ba,
    0x56ac1f752150a563,
    0x55bd1cdad49f699c,
    0x54d0ad5a753e077c,
    0x53e6c9da74b29ab5,
    0x52ff6b54d8a89c75,
    0x521a8ad704f3404f,
    0x513821818624b40c,
    0x50582887dcb8a7e1,
    0x4f7a993048d088d7,
    0x4e9f6cd3967fdba8,
    0x4dc69cdceaa72a9c,
    0x4cf022c9905bfd32,
    0x4c1bf828c6dc54b8,
    0x4b4a169b900c2d00,
    0x4a7a77d47f7b84b1,
    0x49ad159789f37496,
    0x48e1e9b9d588e19b,
    0x4818ee218a3358ee,
    0x47521cc5a2e6a9e0,
    0x468d6fadbf2dd4f3,
    0x45cae0f1f545eb73,
    0x450a6abaa4b77ecd,
    0x444c0740496d4294,
    0x438fb0cb4f468808,
    0x42d561b3e6243d8a,
    0x421d1461d66f2023,
    0x4166c34c5615d0ec,
    0x40b268f9de0183ba,
    0x4000000000000000,
];
/// `sin(j*pi/128)` for `j` in `0..=64` (a quarter wave), Q1.63, rounded to
/// nearest; `cos(j*pi/128)` is entry `64 - j`.
pub(crate) const SIN: [u64; 65] = [
    0x0,
    0x3242abef46ccfbf,
    0x647d97c437604fa,
    0x96a9049670cfae6,
    0xc8bd35e14da15f1,
    0xfab272b54b9871a,
    0x12c8106e8e613a22,
    0x15e214448b3fc655,
    0x18f8b83c69a60ab6,
    0x1c0b826a7e4f62fd,
    0x1f19f97b215f1aaf,
    0x2223a4c563eceec1,
    0x25280c5dab3e0b51,
    0x2826b9282ecc0286,
    0x2b1f34eb563fb9fc,
    0x2e110a61f48b3d5e,
    0x30fbc54d5d52c5a3,
    0x33def28751db145b,
    0x36ba2013c2b98057,
    0x398cdd326388bc2d,
    0x3c56ba700dec763c,
    0x3f1749b7f13573f7,
    0x41ce1e648bffb65a,
    0x447acd506d2c8a11,
    0x471cece6b9a321b2,
    0x49b41533744b7aa2,
    0x4c3fdff385c0d384,
    0x4ebfe8a48142e4f2,
    0x5133cc9424775860,
    0x539b2aef8f97a44f,
    0x55f5a4d233b27e8b,
    0x5842dd5474b37b6d,
    0x5a827999fcef3242,
    0x5cb420dfbffe590d,
    0x5ed77c89aabebb78,
    0x60ec382ffe5db748,
    0x62f201ac545d02d4,
    0x64e88926498fed3d,
    0x66cf811fce1d02cf,
    0x68a69e81189e0777,
    0x6a6d98a43a868c0d,
    0x6c2429605407fe6e,
    0x6dca0d1465b8f644,
    0x6f5f02b1be54a67e,
    0x70e2cbc602f6c349,
    0x72552c84d047d3da,
    0x73b5ebd0f31dcbc3,
    0x7504d3453724e6b1,
    0x7641af3cca3518a3,
    0x776c4edb3308f184,
    0x78848413da1b92ff,
    0x798a23b1238447ba,
    0x7a7d055b18b76976,
    0x7b5d039da1258cf4,
    0x7c29fbee48c35ca9,
    0x7ce3ceb193962314,
    0x7d8a5f3fdd72c0ab,
    0x7e1d93e9c52ea4d6,
    0x7e9d55fc22945a86,
    0x7f0991c3867f4d1f,
    0x7f62368f44949678,
    0x7fa736b40620e855,
    0x7fd8878de5b5f78f,
    0x7ff62182133432ed,
    0x8000000000000000,
];

/// The one-light Phong span loop's `1/|n|` table read without
/// interpolation, `E` entries (a power of two from 4 to 2^12) over
/// `|n|² ∈ [1/4, 5/4)`: entry `j` covers `[1/4 + j/E, 1/4 + (j + 1)/E)`
/// and holds, at its middle `f = 1/4 + (j + 1/2)/E`, `2^13 / f`
/// rounded in its low half and `2^14 / sqrt(f)` rounded in its high half (both
/// below `2^15`). The one-light Phong span loop ships `E = 2048` (8 KB of
/// flash), where over each segment `2^14/|n|` is within `2^-10.97` of
/// the entry relative (at `|n|² = 1/4`; `2^-12.38` for `|n|² >= 3/4`) and
/// `2^13/|n|²` within `2^-9.98` (`2^-11.40`): tested in the kernel's
/// module (`rn_table_within_bound`). An `E`
/// outside the range gives a table of zeros.
pub const fn rsqrt_pair_table<const E: usize>() -> [u32; E] {
    let mut t = [0u32; E];
    if E < 4 || E > 1 << 12 || !E.is_power_of_two() {
        return t;
    }
    let e = E as u64;
    let mut j = 0;
    while j < E {
        // f = (E + 4j + 2) / (4E).
        let d = e + 4 * j as u64 + 2;
        // 2^14 / sqrt(f) = sqrt(2^30 E / d); rounded from twice it.
        let r = super::isqrt_u64((1u64 << 32) * e / d).div_ceil(2);
        // 2^13 / f = 2^15 E / d, rounded.
        let rr = ((1u64 << 16) * e / d).div_ceil(2);
        t[j] = (rr | r << 16) as u32;
        j += 1;
    }
    t
}

/// The Phong span kernel's `1/|n|` table with `E` entries (`E - 1`
/// segments, a power of two from 4 to 2^12): `1/sqrt(f)` in Q16 at `f =
/// 1/4 + j/(E - 1)`, `j` in `0..E` (the kernel interpolates it over
/// `|n|² ∈ [1/4, 5/4)`), each the floor of the square root of
/// `floor(2^36 · S / (S + 4j))` (that is `(2 r)²`, `S = E - 1`), halved
/// and rounded up: within `2^-16` of `2^16 / sqrt(f)`.
///
/// The Phong span kernel ships `E = 65` (64 segments); other sizes
/// are for the table-size sweep of the report (`fixshade report`), whose
/// model of the kernel's lookup is tested equal to the kernel at 65. An
/// `E` outside the range gives a table of zeros (no panic at compile
/// time or run time).
pub const fn rsqrt_quarter_table<const E: usize>() -> [u32; E] {
    let mut t = [0u32; E];
    let s = E.wrapping_sub(1);
    if s < 4 || s > 1 << 12 || !s.is_power_of_two() {
        return t;
    }
    let s = s as u64;
    let mut j = 0;
    while j < E {
        // (2 r)^2 = 2^36 · S / (S + 4 j) <= 2^38: r below 2^18.
        let v = ((1u64 << 36) * s) / (s + 4 * j as u64);
        t[j] = super::isqrt_u64(v).div_ceil(2) as u32;
        j += 1;
    }
    t
}

/// The Phong span kernel's specular table with `E` entries (`E - 2`
/// segments, a power of two from 4 to 2^12) for the exponent `m` (Q16,
/// `m > 0`: the shininess, halved for Blinn): entry `j < E - 2` is
/// `(1 - u/m)^m` in Q15 at `u = floor(min(m, 8) · j / (E - 2))` (Q16)
/// (`approx16::spec_entry`, within `2^-11`), the last two are 0 (the
/// table ends where the term drops below `e^-8 < 2^-11`, or at `u = m`
/// where it is 0).
///
/// The Phong span kernel ships `E = 130` (128 segments + 2),
/// built when it is made for a shininess; other sizes are for the
/// report's table-size sweep (see [`rsqrt_quarter_table`]). An `E` or
/// `m` outside the range gives a table of zeros.
pub fn spec_table<const E: usize>(m: u32) -> [u16; E] {
    let mut t = [0u16; E];
    let s = E.wrapping_sub(2);
    if !(4..=1 << 12).contains(&s) || !s.is_power_of_two() || m == 0 {
        return t;
    }
    // The table's reach: u up to min(m, 8) (Q16).
    let t_eff = m.min(8 << 16);
    for (j, e) in t.iter_mut().enumerate().take(s) {
        let u = ((u64::from(t_eff) * j as u64) >> s.trailing_zeros()) as u32;
        *e = super::approx16::spec_entry(u, m);
    }
    t
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::{rsqrt_quarter_table, spec_table, EXP2, LOG_INV, LOG_T, RSQRT, SIN};

    /// `|a - b| <= tol` for a table entry and an `f64` reference.
    fn near(entry: u64, reference: f64, tol: f64) -> bool {
        (entry as f64 - reference).abs() <= tol
    }

    #[test]
    fn tables_match_f64() {
        // Tolerances: a few f64 ulps of the scaled reference.
        let t31 = 2f64.powi(31);
        let t62 = 2f64.powi(62);
        let t63 = 2f64.powi(63);
        for (j, &e) in RSQRT.iter().enumerate() {
            let f = 1.0 + j as f64 / 64.0;
            assert!(near(u64::from(e), t31 / f.sqrt(), 0.5 + 1e-6), "RSQRT[{j}]");
        }
        for j in 0..=64u32 {
            let k = 64 + j;
            let exact = (2 * 524_288 + k) / (2 * k); // round(2^19 / k)
            assert_eq!(u32::from(LOG_INV[j as usize]), exact, "LOG_INV[{j}]");
        }
        for j in 0..=64usize {
            let t = (8192.0 / f64::from(LOG_INV[j])).log2() * t62;
            assert!(near(LOG_T[j], t, 2048.0), "LOG_T[{j}]");
            let e = (-(j as f64) / 64.0).exp2() * t63;
            assert!(near(EXP2[j], e, 4096.0), "EXP2[{j}]");
            let s = (j as f64 * core::f64::consts::PI / 128.0).sin() * t63;
            assert!(near(SIN[j], s, 4096.0), "SIN[{j}]");
        }
        assert_eq!(LOG_T[0], 0);
        assert_eq!(LOG_T[64], 1 << 62);
        assert_eq!(EXP2[0], 1 << 63);
        assert_eq!(SIN[64], 1 << 63);
    }

    /// The builders at other sizes: the `1/|n|` table within `2^-16` of
    /// `2^16 / sqrt(f)` (plus the half unit of its rounding), the
    /// specular table within `2^-11` of `(1 - u/m)^m`, nonsense sizes all
    /// zeros.
    #[test]
    fn builders_at_other_sizes() {
        fn rs<const E: usize>() {
            let t = rsqrt_quarter_table::<E>();
            let s = (E - 1) as f64;
            for (j, &e) in t.iter().enumerate() {
                let want = 65536.0 / (0.25 + j as f64 / s).sqrt();
                assert!(
                    (f64::from(e) - want).abs() <= 1.0,
                    "E {E} j {j}: {e} {want}"
                );
            }
        }
        rs::<17>();
        rs::<65>();
        rs::<1025>();
        assert!(rsqrt_quarter_table::<64>().iter().all(|&e| e == 0));
        assert!(rsqrt_quarter_table::<0>().is_empty());
        fn sp<const E: usize>(n: f64) {
            let m = (n * 65536.0) as u32;
            let t = spec_table::<E>(m);
            let s = E - 2;
            let (mf, tf) = (f64::from(m) / 65536.0, f64::from(m.min(8 << 16)) / 65536.0);
            for (j, &e) in t.iter().enumerate().take(s) {
                let u = (tf * j as f64 / s as f64 * 65536.0).floor() / 65536.0;
                let want = (1.0 - u / mf).max(0.0).powf(mf);
                let got = f64::from(e) / 32768.0;
                assert!((got - want).abs() <= 1.0 / 2048.0, "E {E} n {n} j {j}");
            }
            assert_eq!(t[s..], [0, 0]);
        }
        for n in [0.5, 1.0, 3.3, 100.0, 10_000.0] {
            sp::<18>(n);
            sp::<130>(n);
            sp::<1026>(n);
        }
        assert!(spec_table::<130>(0).iter().all(|&e| e == 0));
        assert!(spec_table::<131>(1 << 20).iter().all(|&e| e == 0));
    }
}
