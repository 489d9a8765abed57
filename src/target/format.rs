//! Pixel formats: 8-bit grey, RGB565 in both byte orders, RGB888.
//!
//! A format's `Raw` type is the exact bytes of one pixel in memory, so a
//! frame buffer is a byte-exact image of what goes over the wire: SPI
//! displays such as the ST7789 and ILI9341 expect RGB565 big-endian
//! ([`Rgb565Be`]); [`Rgb565Le`] is the little-endian order of a `u16` on a
//! Cortex-M.

pub use crate::pixel::Rgb8;

/// A stored pixel: its bytes in memory.
pub trait RawPixel: Copy + Default + PartialEq + core::fmt::Debug {
    /// The bytes, in memory order.
    type Bytes: AsRef<[u8]> + IntoIterator<Item = u8>;
    /// The pixel's bytes as they lie in memory.
    fn bytes(self) -> Self::Bytes;
}

macro_rules! raw_bytes {
    ($($n:literal),*) => {$(
        impl RawPixel for [u8; $n] {
            type Bytes = [u8; $n];
            #[inline(always)]
            fn bytes(self) -> [u8; $n] {
                self
            }
        }
    )*};
}

raw_bytes!(1, 2, 3, 4);

/// A `u16` pixel's bytes in memory: `to_ne_bytes` (the RGB565 formats
/// store the value whose native bytes are their byte order).
impl RawPixel for u16 {
    type Bytes = [u8; 2];
    #[inline(always)]
    fn bytes(self) -> [u8; 2] {
        self.to_ne_bytes()
    }
}

/// How a colour is stored in a buffer.
pub trait PixelFormat: Copy + core::fmt::Debug {
    /// One pixel, whose bytes in memory ([`RawPixel::bytes`]) are the
    /// format's.
    type Raw: RawPixel;
    /// Bytes per pixel.
    const BYTES: usize;
    /// Converts a colour (exact for `Rgb888`; truncating the low bits for
    /// `Rgb565`, as displays do; luma for `Gray8`).
    fn encode(c: Rgb8) -> Self::Raw;
    /// Converts back, replicating high bits into the low ones for
    /// `Rgb565` (so 0 and full scale map to 0 and 255).
    fn decode(raw: Self::Raw) -> Rgb8;

    /// `encode(Rgb8::grey(level))`; a table lookup for RGB565 (the
    /// Gouraud span loop's per-pixel encoding).
    #[inline(always)]
    fn encode_grey(level: u8) -> Self::Raw {
        Self::encode(Rgb8::grey(level))
    }

    /// The colour of three channel sums in Q19 (`c >> 19` clamped to
    /// `0..=255` per channel), encoded: `encode` of that colour, or a
    /// faster path giving the same value (the Phong span kernel's
    /// channels go straight from their sums to the buffer).
    #[inline(always)]
    fn encode_q19(c: [i32; 3]) -> Self::Raw {
        Self::encode(level_q19(c))
    }

    /// Sets every pixel of `pixels` to `raw`: `pixels.fill(raw)`, or a
    /// faster path storing the same bytes (the byte-array formats fill
    /// bytewise, a `memset`, when all bytes of `raw` are equal, as for
    /// black and white).
    #[inline]
    fn fill_slice(pixels: &mut [Self::Raw], raw: Self::Raw) {
        pixels.fill(raw);
    }
}

/// The colour of three channel sums in Q19: `c >> 19` clamped to
/// `0..=255` per channel ([`PixelFormat::encode_q19`]).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
pub fn level_q19(c: [i32; 3]) -> Rgb8 {
    let l = |v: i32| (v >> 19).clamp(0, 255) as u8;
    Rgb8::new(l(c[0]), l(c[1]), l(c[2]))
}

/// RGB565 (native value, before the byte order) of three channel sums
/// in Q19: the top 5, 6, 5 bits of the clamped levels are the sums
/// shifted by 22, 21, 22 and clamped to the field (`floor` commutes with
/// the clamp), one `USAT` each on ARMv7E-M.
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
fn pack565_q19(c: [i32; 3]) -> u16 {
    let f = |v: i32, s: u32, m: i32| (v >> s).clamp(0, m) as u16;
    (f(c[0], 22, 31) << 11) | (f(c[1], 21, 63) << 5) | f(c[2], 22, 31)
}

/// [`pack565_q19`] in the high half of a `u32` (low half zero): its byte
/// swap (one `REV`) has the big-endian `u16` in the low half, without
/// the shift a `u16` byte swap takes (ARMv7E-M: the fields' shifts fold
/// into `USAT` and `ORR`; on ARMv6-M, without `USAT`, the `u16` form and
/// its `REV16` cost less: span sweep `phong-k1` 2 instructions a pixel).
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
fn pack565_q19_high(c: [i32; 3]) -> u32 {
    let f = |v: i32, s: u32, m: i32| (v >> s).clamp(0, m) as u32;
    (f(c[0], 22, 31) << 27) | (f(c[1], 21, 63) << 21) | (f(c[2], 22, 31) << 16)
}

/// [`PixelFormat::fill_slice`] for a byte-array format: one byte fill
/// (`memset`) when all bytes of `raw` are equal.
#[inline]
fn fill_bytes<const N: usize>(pixels: &mut [[u8; N]], raw: [u8; N]) {
    match raw.first() {
        Some(&b) if raw.iter().all(|&v| v == b) => pixels.as_flattened_mut().fill(b),
        _ => pixels.fill(raw),
    }
}

/// [`PixelFormat::fill_slice`] for a `u16` format, and the 16-bit depth
/// clear: `pixels.fill(raw)`, the same values. On ARMv7-M
/// [`fill_u16_words`], on ARMv6-M [`fill_u16_aligned`]. Elsewhere black
/// and white (the usual backgrounds) as constant fills, which the
/// compiler turns into a `memset`, other colours as a loop.
#[inline(always)]
pub(crate) fn fill_u16(pixels: &mut [u16], raw: u16) {
    if cfg!(all(target_arch = "arm", not(armv6m))) {
        fill_u16_words(pixels, raw);
    } else if cfg!(armv6m) {
        fill_u16_aligned(pixels, raw);
    } else {
        match raw {
            0 => pixels.fill(0),
            u16::MAX => pixels.fill(u16::MAX),
            _ => pixels.fill(raw),
        }
    }
}

/// `pixels.fill(raw)` as word stores: one halfword first when the slice
/// starts between two words, then 32 values (64 bytes) a step as 16 word
/// stores (the stores of a value's two halves merge into one), then pairs
/// and the last value. The word goes through [`core::hint::black_box`]
/// so that the loop stays a loop: a constant fill becomes a call to
/// `memset`, whose loop stores 16 bytes in 6 instructions. On ARMv7E-M a
/// 240 × 16 band clear (7 680 bytes) then takes about 1 000 instructions
/// instead of 2 900 when the optimiser sees a word-aligned start (the
/// firmware's static bands: the stores pair into `STRD`, 512 bytes in 67
/// instructions, unrolled 4 times), about 2 000 otherwise (`STR`, 256
/// bytes in 67).
#[inline(always)]
fn fill_u16_words(pixels: &mut [u16], raw: u16) {
    let pixels = if (pixels.as_ptr() as usize) & 2 != 0 {
        match pixels.split_first_mut() {
            Some((first, rest)) => {
                *first = raw;
                rest
            }
            None => return,
        }
    } else {
        pixels
    };
    let w = core::hint::black_box(u32::from(raw) * 0x1_0001);
    let (lo, hi) = (w as u16, (w >> 16) as u16);
    let (blocks, rest) = pixels.as_chunks_mut::<32>();
    #[allow(clippy::needless_range_loop)]
    for k in 0..blocks.len() {
        let b = &mut blocks[k];
        for j in 0..16 {
            b[2 * j] = lo;
            b[2 * j + 1] = hi;
        }
    }
    let (pairs, last) = rest.as_chunks_mut::<2>();
    #[allow(clippy::needless_range_loop)]
    for k in 0..pairs.len() {
        pairs[k] = [lo, hi];
    }
    if let [l] = last {
        *l = lo;
    }
}

/// `pixels.fill(raw)` through the slice's word-aligned middle as `u32`
/// words ([`bytemuck::pod_align_to_mut`]: one halfword before it and
/// after it at most), eight words (the four registers twice) a step.
/// For ARMv6-M, which has no unaligned word store: there a `u16` slice's
/// halfword stores do not merge into words (a loop of them took 1.75
/// instructions a pixel), and a constant fill becomes a call to the
/// library `memset` (1 instruction a pixel: the bunny firmware's band
/// clears, 230 400 bytes a frame, took 115 884). The four words go
/// through [`core::hint::black_box`] so that the loop stays a loop of
/// stores, from four registers, which the compiler merges into `STM`s:
/// bunny-gouraud raster thumbv6m 2 734 554 -> 2 674 061 (the clears ~0.47
/// instructions a pixel; one word register, 32 `STR`s a loop: 2 681 261).
/// Eight words a step rather than four: the compiler's unrolled loop then
/// stores 128 bytes in 27 instructions instead of 64 in 15 (it rebuilds
/// the base of each `STM` from an offset): the band clears of the bunny
/// firmware (the probe's part of `raster_bands_in`) 42 013 -> 39 373
/// instructions on the Cortex-M0 (sixteen words a step: 52 055). On
/// ARMv7-M [`fill_u16_words`] costs less (this form: thumbv7em
/// bunny-gouraud raster +12.8 K).
#[inline(always)]
fn fill_u16_aligned(pixels: &mut [u16], raw: u16) {
    let (head, mid, tail) = bytemuck::pod_align_to_mut::<u16, u32>(pixels);
    head.fill(raw);
    tail.fill(raw);
    let [w0, w1, w2, w3] = core::hint::black_box([u32::from(raw) * 0x1_0001; 4]);
    let (blocks, rest) = mid.as_chunks_mut::<8>();
    for b in blocks {
        *b = [w0, w3, w2, w1, w0, w3, w2, w1];
    }
    for r in rest {
        *r = w0;
    }
}

/// `pack565(Rgb8::grey(l))` for every level, as the `u16` whose bytes in
/// memory (`to_ne_bytes`) are the given byte order: an aligned table, so
/// that a level costs one halfword load on ARMv6-M too (a table of
/// `[u8; 2]` took two byte loads and a merge: span loops Gouraud on
/// thumbv6m -3 instructions per pixel).
const fn grey565_table(big_endian: bool) -> [u16; 256] {
    let mut t = [0u16; 256];
    let mut l = 0;
    while l < 256 {
        let v = pack565(Rgb8::grey(l as u8));
        t[l] = u16::from_ne_bytes(if big_endian {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        });
        l += 1;
    }
    t
}

/// Grey levels in RGB565 big-endian (512 bytes).
static GREY565_BE: [u16; 256] = grey565_table(true);
/// Grey levels in RGB565 little-endian (512 bytes).
static GREY565_LE: [u16; 256] = grey565_table(false);

/// 8-bit grey, one byte per pixel.
///
/// A colour's grey level is its luma `(77 r + 150 g + 29 b + 128) >> 8`
/// (ITU-R BT.601 weights in 1/256ths, summing to 256, so a grey stays
/// exactly the same level).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Gray8;

impl PixelFormat for Gray8 {
    type Raw = [u8; 1];
    #[inline]
    fn fill_slice(pixels: &mut [[u8; 1]], raw: [u8; 1]) {
        fill_bytes(pixels, raw);
    }
    const BYTES: usize = 1;
    #[inline]
    fn encode(c: Rgb8) -> [u8; 1] {
        let y = (77 * c.r as u32 + 150 * c.g as u32 + 29 * c.b as u32 + 128) >> 8;
        [y as u8]
    }
    #[inline]
    fn decode(raw: [u8; 1]) -> Rgb8 {
        Rgb8::grey(raw[0])
    }
}

#[inline]
const fn pack565(c: Rgb8) -> u16 {
    ((c.r as u16 >> 3) << 11) | ((c.g as u16 >> 2) << 5) | (c.b as u16 >> 3)
}

#[inline]
const fn unpack565(v: u16) -> Rgb8 {
    let r = (v >> 11) as u8 & 0x1f;
    let g = (v >> 5) as u8 & 0x3f;
    let b = v as u8 & 0x1f;
    Rgb8::new(
        (r << 3) | (r >> 2),
        (g << 2) | (g >> 4),
        (b << 3) | (b >> 2),
    )
}

/// [`PixelFormat::encode_q19`] of the RGB565 formats: the value whose
/// bytes in memory are big-endian (`BIG`) or little-endian. Where that
/// order is not the native one, a byte swap: on ARMv7-M of the high-half
/// form ([`pack565_q19_high`], one `REV`), on ARMv6-M of the `u16` (one
/// `REV16`).
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn encode565_q19<const BIG: bool>(c: [i32; 3]) -> u16 {
    let swap = BIG != cfg!(target_endian = "big");
    if swap && cfg!(not(armv6m)) {
        pack565_q19_high(c).swap_bytes() as u16
    } else if swap {
        pack565_q19(c).swap_bytes()
    } else {
        pack565_q19(c)
    }
}

/// An RGB565 format: `$to`/`$from` its byte order, `$grey` its grey
/// table, `$big` whether it is big-endian.
macro_rules! rgb565 {
    ($(#[$doc:meta])* $name:ident, $big:literal, $to:ident, $from:ident, $grey:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        pub struct $name;

        impl PixelFormat for $name {
            type Raw = u16;
            #[inline]
            fn fill_slice(pixels: &mut [u16], raw: u16) {
                fill_u16(pixels, raw);
            }
            const BYTES: usize = 2;
            #[inline]
            fn encode(c: Rgb8) -> u16 {
                pack565(c).$to()
            }
            #[inline(always)]
            fn encode_grey(level: u8) -> u16 {
                $grey[level as usize]
            }
            #[inline(always)]
            fn encode_q19(c: [i32; 3]) -> u16 {
                encode565_q19::<$big>(c)
            }
            #[inline]
            fn decode(raw: u16) -> Rgb8 {
                unpack565(u16::$from(raw))
            }
        }
    };
}

rgb565!(
    /// RGB565, most significant byte first (the order SPI displays expect),
    /// stored as an aligned `u16` whose bytes in memory are that order
    /// (`to_be`: a byte swap, one `REV16`, on a little-endian Cortex-M, done
    /// once per colour or in the grey table; a halfword store per pixel).
    Rgb565Be,
    true,
    to_be,
    from_be,
    GREY565_BE
);

rgb565!(
    /// RGB565, least significant byte first (a `u16` in Cortex-M memory),
    /// stored as an aligned `u16`.
    Rgb565Le,
    false,
    to_le,
    from_le,
    GREY565_LE
);

/// RGB888: red, green, blue bytes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Rgb888;

impl PixelFormat for Rgb888 {
    type Raw = [u8; 3];
    #[inline]
    fn fill_slice(pixels: &mut [[u8; 3]], raw: [u8; 3]) {
        fill_bytes(pixels, raw);
    }
    const BYTES: usize = 3;
    #[inline]
    fn encode(c: Rgb8) -> [u8; 3] {
        [c.r, c.g, c.b]
    }
    #[inline]
    fn decode(raw: [u8; 3]) -> Rgb8 {
        Rgb8::new(raw[0], raw[1], raw[2])
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;

    /// The word fills (and [`fill_u16`]) against `slice::fill` for every
    /// length 0..=70 at every halfword start offset 0..4 (both word
    /// alignments twice), several values: the filled range equal, the
    /// guard values around it untouched.
    #[test]
    fn fill_u16_matches_fill() {
        for raw in [0u16, u16::MAX, 0x1234, 0xF800, 0x00FF] {
            for off in 0..4 {
                for len in 0..=70 {
                    let mut want = [0xA5A5u16; 80];
                    want[off..off + len].fill(raw);
                    let mut got = [0xA5A5u16; 80];
                    fill_u16_words(&mut got[off..off + len], raw);
                    assert_eq!(got, want, "words raw={raw:#x} off={off} len={len}");
                    let mut got = [0xA5A5u16; 80];
                    fill_u16_aligned(&mut got[off..off + len], raw);
                    assert_eq!(got, want, "aligned raw={raw:#x} off={off} len={len}");
                    let mut got = [0xA5A5u16; 80];
                    fill_u16(&mut got[off..off + len], raw);
                    assert_eq!(got, want, "fill_u16 raw={raw:#x} off={off} len={len}");
                }
            }
        }
    }

    #[test]
    fn rgb565_byte_orders() {
        let c = Rgb8::new(0xff, 0x80, 0x08);
        // r 11111, g 100000, b 00001 -> 1111_1100 0000_0001
        assert_eq!(Rgb565Be::encode(c).bytes(), [0xfc, 0x01]);
        assert_eq!(Rgb565Le::encode(c).bytes(), [0x01, 0xfc]);
        assert_eq!(
            Rgb565Be::decode(u16::from_ne_bytes([0xfc, 0x01])),
            Rgb8::new(255, 130, 8)
        );
    }

    #[test]
    fn rgb565_grey_matches_bunny_bench_packing() {
        // g>>3, g>>2, g>>3
        for g in 0..=255u8 {
            let v = u16::from_be_bytes(Rgb565Be::encode(Rgb8::grey(g)).bytes());
            let want = ((g as u16 >> 3) << 11) | ((g as u16 >> 2) << 5) | (g as u16 >> 3);
            assert_eq!(v, want);
        }
        for g in 0..=255u8 {
            assert_eq!(Rgb565Be::encode_grey(g), Rgb565Be::encode(Rgb8::grey(g)));
            assert_eq!(Rgb565Le::encode_grey(g), Rgb565Le::encode(Rgb8::grey(g)));
            assert_eq!(Gray8::encode_grey(g), [g]);
        }
        assert_eq!(Rgb565Le::decode(Rgb565Le::encode(Rgb8::WHITE)), Rgb8::WHITE);
        assert_eq!(Rgb565Le::decode(Rgb565Le::encode(Rgb8::BLACK)), Rgb8::BLACK);
    }

    /// The fast `encode_q19` of every format is `encode` of the clamped
    /// levels, over sums around every level boundary and far outside.
    #[test]
    fn encode_q19_is_encode_of_the_levels() {
        fn check<F: PixelFormat>(c: [i32; 3]) {
            assert_eq!(F::encode_q19(c), F::encode(level_q19(c)), "{c:?}");
            // Both forms of the RGB565 value (the other target's too).
            let v = pack565(level_q19(c));
            assert_eq!(pack565_q19(c), v, "{c:?}");
            assert_eq!(pack565_q19_high(c), u32::from(v) << 16, "{c:?}");
        }
        let mut vals = std::vec![i32::MIN, i32::MAX, -1, 0, 1 << 30, -(1 << 30)];
        for l in -2..=258i32 {
            for d in [-1, 0, 1, 1 << 18] {
                vals.push((l << 19).wrapping_add(d));
            }
        }
        let mut n = 0;
        for (k, &a) in vals.iter().enumerate() {
            let b = vals[(k * 7 + 3) % vals.len()];
            let c = vals[(k * 13 + 5) % vals.len()];
            for t in [[a, b, c], [b, c, a], [c, a, b], [a, a, a]] {
                check::<Rgb565Be>(t);
                check::<Rgb565Le>(t);
                check::<Rgb888>(t);
                check::<Gray8>(t);
                n += 1;
            }
        }
        assert_eq!(n, 4 * vals.len());
        assert_eq!(
            level_q19([255 << 19, (7 << 19) + 5, -3]),
            Rgb8::new(255, 7, 0)
        );
        assert_eq!(
            Rgb565Be::encode_q19([i32::MAX, 0, i32::MAX]),
            0xf81f_u16.to_be()
        );
    }

    #[test]
    fn gray8_keeps_greys_and_weighs_channels() {
        for g in 0..=255u8 {
            assert_eq!(Gray8::encode(Rgb8::grey(g)), [g]);
        }
        assert_eq!(Gray8::encode(Rgb8::new(255, 0, 0)), [77]);
        assert_eq!(Gray8::encode(Rgb8::new(0, 255, 0)), [149]);
        assert_eq!(Gray8::encode(Rgb8::new(0, 0, 255)), [29]);
    }

    #[test]
    fn rgb888_is_exact() {
        let c = Rgb8::new(1, 2, 3);
        assert_eq!(Rgb888::decode(Rgb888::encode(c)), c);
    }
}
