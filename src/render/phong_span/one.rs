//! One directional light, viewer at infinity: the 32-bit span loop.
//!
//! The span is cut into chunks of [`CHUNK`] pixels. At each chunk's first
//! pixel the exact `u64` forward differences of `|n|²` and `Q` (Q60, as
//! [`PhongKernel::begin`] makes them) give 32-bit ones: `|n|²` in Q30 and
//! `Qm = K·Q`, the specular table position before the division by `|n|²`,
//! in Q20 table segments ([`QM_FRAC`]). Rounding the differences down
//! costs at most `1 + 31 + 496` units of the last place after 31 steps:
//! `2^-21` of `|n|²` and `2^-11` of a segment (the table's own
//! interpolation error is `2^-11` of its range). Per pixel: two adds for
//! each quadratic, one for the linear `n·L`, `1/|n|` and `1/|n|²` from
//! one load of [`RN`] (no interpolation), `N·L` one product, the table
//! position `Qm·(1/|n|²)` one product of 16-bit operands, the table with
//! one interpolation, per
//! channel two multiply-adds and a clamp: all 32-bit, products of operands
//! below 2^16 or results below 2^32 (a single `MULS` on ARMv6-M). The
//! depth test, the terms, the channels and the store of a pixel are one
//! loop ([`PhongKernel::run`] through `Out::fused`).
//!
//! A chunk whose `Qm` leaves the 32-bit range (`Q` far from the highlight
//! at high shininess) is proven free of specular light by the convexity of
//! `Q` (`Qm >= min(ends) - d2·k²/8` over `k` pixels) and runs without it;
//! one that can be proven neither way, or whose `|n|²` leaves `[0, 2)`,
//! takes [`PhongKernel::one_exact`] per pixel (the same quantities from the
//! pixel's normal in 64 bits). A span of more than one chunk and at most
//! [`WHOLE_MAX`] pixels that can be proven as one chunk is skips the
//! chunk set-up: one plan, its 32-bit state carried from chunk to chunk
//! ([`Whole`]).

use super::{
    cross, fallback, lin, pack, quad, sq3, unpack, KLight, Out, PhongKernel, CHUNK, RS, RSQRT_N,
    SPEC_SEGMENTS,
};
use crate::num::wide::wmul;
use crate::num::Real;
use crate::target::level_q19;

/// Spans shorter than this run [`PhongKernel::one_exact`] per passing
/// pixel (after its depth test) instead of the chunk set-up.
pub(super) const SHORT_SPAN: u32 = 4;

/// Other than on ARMv6-M, [`PhongKernel::run`] in two passes a piece
/// ([`PhongKernel::run_two_pass`]: light terms into a buffer, then depth
/// mask and colours). Off: the round's redesign of the loop whose live
/// state fits the registers, measured worse on the M4's span sweep (one
/// light, the same frames): 70.38 instructions a pixel against 64.74
/// with the one loop (the terms loop 35.5 a pixel, the colour loop of
/// [`Out::chunk`] 23.75: both still spill, the terms loop unrolled by
/// two, the colour constants split into nine registers), 72.51 against
/// 62.87 with the packed specular table ([`pack_table`]).
const TWO_PASS: bool = false;

/// Other than on ARMv6-M, [`PhongKernel::run`] with the loop's
/// invariants read from memory ([`PhongKernel::run_inv`]): the round's
/// redesign of the loop whose live state fits the registers. Measured on
/// the M4's span sweep (one light, every frame's CRC unchanged): 62.80
/// -> 61.54 instructions a pixel (the pair loop 99 -> 96: the constants
/// reloaded where used, no longer spilled and copied), then 60.61 with
/// `N·L`'s product as one `SMULWT` (its low half no longer masked, so the
/// compiler keeps the 48-bit product's form; in the loop before this
/// one the same source gave 62.80, the mask narrowing it back to `MUL`),
/// then 59.07 with each channel's two constants adjacent (one `LDRD`; the
/// pair loop 89), then 57.97 with the second differences and `n·L`'s
/// step in the order `nd2, dnl, qd2`. The layout of [`Inv`] moves the
/// figure by several instructions a pixel (the compiler's register
/// allocation, not the work): the steps in the orders `nd2, qd2, dnl`
/// 59.07, `dnl, nd2, qd2` 58.45, `dnl, qd2, nd2` 59.07, `qd2, dnl, nd2`
/// 59.24, `qd2, nd2, dnl` 65.12; the colour constants first 62.27; the
/// table addresses first 64.70 (after the steps 66.21, first of all
/// before the steps 61.06), the specular table's address before
/// [`RN`]'s 66.34 (after the colour constants 66.08). Tried with this
/// loop and measured worse: pieces of 64 pixels (two masks, one colour
/// loop) 66.39; the pair loop over `as_chunks_mut` 60.24; each
/// channel's constants in the order `[ambo, ds]` 58.53. The same block
/// for ARMv6-M's one loop (ambient, diffuse and specular constants per
/// channel, the `u16` specular table) measured 127.38 -> 142.66 there:
/// not kept.
/// Tried and measured worse on the same sweep (before this loop): a full
/// piece of [`CHUNK`] pixels that all passed as straight-line code (no
/// counter, constant store offsets) 65.68, the state then stepped
/// through memory; the colour constants kept in the kernel after its
/// specular table (one base address for both) 65.36, the compiler then
/// addressing them from the kernel's address with 12-bit offsets.
#[cfg(not(armv6m))]
const INV_LOOP: bool = true;

/// The stepped values of [`PhongKernel::run_inv`]'s loop: `|n|² - 1/4`
/// and its first difference, `Qm` and its first difference, `n·L`.
#[cfg(not(armv6m))]
#[derive(Clone, Copy)]
struct Carry {
    nn: i32,
    nd1: i32,
    q: i32,
    qd1: i32,
    nl: i32,
}

/// The invariants of [`PhongKernel::run_inv`]'s loop, one block of its
/// frame: [`Colour`]'s packed constants, both tables, the second
/// differences and `n·L`'s step.
#[cfg(not(armv6m))]
#[repr(C)]
struct Inv<'a> {
    nd2: i32,
    dnl: i32,
    qd2: i32,
    /// Per channel `[ds, ambo]` of [`Colour`] (adjacent: one `LDRD`).
    ch: [[i32; 2]; 3],
    rn: &'a [u32; RN_N],
    tab: &'a [u32; SPEC_SEGMENTS + 1],
}

#[cfg(not(armv6m))]
impl Inv<'_> {
    /// The channel sums of the pixel of `s` ([`PhongKernel::terms_rn`]
    /// and [`Colour::of_terms`]: the same values).
    #[inline(always)]
    #[allow(
        clippy::cast_sign_loss,
        clippy::cast_possible_truncation,
        clippy::cast_possible_wrap
    )]
    fn px<const SPEC: bool, const LIT: bool>(&self, s: &Carry) -> [i32; 3] {
        let e = rn_entry(self.rn, s.nn);
        let nl = s.nl;
        let nlp = if LIT { nl } else { nl.max(0) };
        // `floor(x · (e >> 16) / 2^16)` for `x = nlp >> 13` (below
        // 2^18) as the signed 48-bit product's bits 16..48 (one `SMULWT`);
        // below 2^16 (`n·L <= |n|`), so that it needs no mask below.
        let nl15 =
            ((i64::from(((nlp as u32) >> 13) as i32) * i64::from((e as i32) >> 16)) >> 16) as u32;
        let sp = if SPEC && (LIT || nl > 0) {
            let q7 = (s.q >> (QM_FRAC - 7)).clamp(0, (1 << 15) - 1);
            let pos = i32::from(q7 as i16) * i32::from(e as i16);
            let pos = pos.clamp(0, (1 << 27) - 1) as u32;
            let j = (pos >> 20) as usize & (SPEC_SEGMENTS - 1);
            let f = (pos >> 4) & 0xFFFF;
            let t = self.tab[j];
            (t & 0xFFFF).wrapping_sub(((t >> 16) * f) >> 16)
        } else {
            0
        };
        let t = (nl15 | sp << 16) ^ 0x8000_8000;
        let lo = i32::from(t as i16);
        let hi = (t as i32) >> 16;
        let ch = |k: usize| {
            let [ds, ambo] = self.ch[k];
            ambo.wrapping_add(lo.wrapping_mul(i32::from(ds as i16)))
                .wrapping_add(hi.wrapping_mul(ds >> 16))
        };
        [ch(0), ch(1), ch(2)]
    }

    /// One pixel's step ([`Whole::step`]).
    #[inline(always)]
    fn step<const SPEC: bool>(&self, s: &mut Carry) {
        s.nn = s.nn.wrapping_add(s.nd1);
        s.nd1 = s.nd1.wrapping_add(self.nd2);
        if SPEC {
            s.q = s.q.wrapping_add(s.qd1);
            s.qd1 = s.qd1.wrapping_add(self.qd2);
        }
        s.nl = s.nl.wrapping_add(self.dnl);
    }
}

/// Fraction bits of `Qm` (table segments) in the 32-bit loop.
pub(super) const QM_FRAC: u32 = 20;
/// `Qm` at or above this many segments (Q20) gives no specular term:
/// `Qm / |n|² >= SEGMENTS` for `|n|² < 5/4`.
const QM_OFF: i64 = ((SPEC_SEGMENTS as i64) * 5 / 4 + 1) << QM_FRAC;
/// Largest `Qm` the 32-bit loop carries (below 2^31).
pub(super) const QM_MAX: i64 = (1 << 31) - (1 << 24);

/// `floor(x · k / 2^48)` for `k < 2^31` (two 32x32 products).
#[inline(always)]
#[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
pub(super) fn mul_shr48(x: i64, k: u32) -> i64 {
    let hi = (x >> 32) as i32;
    let lo = x as u32;
    let ph = wmul(hi, k as i32);
    let pl = u64::from(lo) * u64::from(k);
    // floor((ph · 2^32 + pl) / 2^48) = (ph + pl / 2^32) >> 16 (the low
    // 32 bits of `pl` add less than one unit of 2^-16).
    (ph + (pl >> 32) as i64) >> 16
}

/// `2^16 / |n|` (`<= 2^17`) from `|n|²` (Q30, within `[1/4, 5/4)`): the
/// table [`RS`] with one interpolation (see [`PhongKernel::terms`]).
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
pub(super) fn rsq(nn: i32) -> u32 {
    // 64 segments of 2^24 (Q30) from 1/4.
    let j = ((nn.wrapping_sub(1 << 28) as u32) >> 24) as usize & 63;
    let (a, b) = (RS[j], RS[j + 1]);
    let t = ((nn as u32) >> 8) & 0xFFFF;
    a - (((a - b) * t) >> 16)
}

/// [`RS`] packed for the 32-bit loop: entry `j` is `RS[j] << 14 |
/// (RS[j] - RS[j + 1])` (`RS[j] <= 2^17`, differences below `2^14`,
/// checked when it is built), one load a pixel for both values.
pub(super) const RS_PACKED: [u32; RSQRT_N] = {
    let mut t = [0u32; RSQRT_N];
    let mut j = 0;
    while j < RSQRT_N {
        let (a, b) = (RS[j], RS[j + 1]);
        assert!(a <= 1 << 17 && b <= a && a - b < 1 << 14);
        t[j] = a << 14 | (a - b);
        j += 1;
    }
    t
};

/// [`rsq`] of `|n|²` from `nb = |n|² - 1/4` (Q30, within `[0, 1)`) and
/// [`RS_PACKED`] (the table passed in, so that its address stays in a
/// register through the loop): the same value.
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
pub(super) fn rsq_biased(rs: &[u32; RSQRT_N], nb: i32) -> u32 {
    let e = rs[((nb as u32) >> 24) as usize & (RSQRT_N - 1)];
    let t = ((nb as u32) >> 8) & 0xFFFF;
    (e >> 14) - (((e & 0x3FFF) * t) >> 16)
}

/// The specular table `t` packed for the one-light loop: entry `j` is
/// `t[j] | (t[j] - t[j + 1]) << 16` (the table is non-increasing,
/// `spec_table_is_non_increasing`: the difference is below `2^16`, and
/// `a - ((d·f) >> 16)` from the entry is the pair form's value).
#[cfg(not(armv6m))]
pub(super) fn pack_table(t: &[u16; SPEC_SEGMENTS + 2]) -> [u32; SPEC_SEGMENTS + 1] {
    let mut p = [0u32; SPEC_SEGMENTS + 1];
    for (j, e) in p.iter_mut().enumerate() {
        let (a, b) = (u32::from(t[j]), u32::from(t[j + 1]));
        *e = a | (a.wrapping_sub(b) & 0xFFFF) << 16;
    }
    p
}

/// Entries of [`RN`].
pub(super) const RN_N: usize = 2048;

/// The one-light loop's `1/|n|` and `1/|n|²` over `|n|² ∈ [1/4, 5/4)`,
/// read without interpolation ([`crate::num::rsqrt_pair_table`] at
/// [`RN_N`] entries, 8 KB of flash): entry `j` holds `2^14/|n|` in its low
/// half and `2^13/|n|²` in its high half at the middle of its segment.
pub(super) const RN: [u32; RN_N] = crate::num::rsqrt_pair_table::<RN_N>();

/// The entry of [`RN`] for `nb = |n|² - 1/4` (Q30, within `[0, 1)`),
/// the table passed in (its address in a register through the loop).
#[inline(always)]
#[allow(clippy::cast_sign_loss)]
pub(super) fn rn_entry(rn: &[u32; RN_N], nb: i32) -> u32 {
    rn[((nb as u32) >> 19) as usize & (RN_N - 1)]
}

/// The normal `n + i·dn` of pixel `i` (wrapping, as the loops step it).
#[inline(always)]
#[allow(clippy::cast_possible_wrap)]
fn normal_at(n: [i32; 3], dn: [i32; 3], i: u32) -> [i32; 3] {
    [0, 1, 2].map(|a| n[a].wrapping_add(dn[a].wrapping_mul(i as i32)))
}

/// A span shorter than [`SHORT_SPAN`] (one light or several): the depth
/// test of each pixel first, then `exact(normal, i)` (the colour `r | g
/// << 8 | b << 16` of pixel `i` in 64 bits) for the passing ones alone,
/// without span or chunk set-up; returns how many passed.
#[inline(always)]
pub(super) fn short_span(
    n: [i32; 3],
    dn: [i32; 3],
    len: u32,
    out: &mut impl Out,
    exact: impl Fn([i32; 3], u32) -> u32,
) -> u32 {
    let mut passed = 0;
    for i in 0..len {
        if out.test(i) {
            out.write(i, unpack(exact(normal_at(n, dn, i), i)));
            passed += 1;
        }
    }
    passed
}

/// A chunk the 32-bit loop cannot prove (one light or several): the
/// colours `exact(normal, j)` of its `k` pixels from pixel `i` into `buf`.
#[inline(always)]
pub(super) fn exact_chunk(
    n: [i32; 3],
    dn: [i32; 3],
    i: u32,
    k: u32,
    buf: &mut [u32; CHUNK],
    exact: impl Fn([i32; 3], u32) -> u32,
) {
    for (j, o) in (i..i + k).zip(buf.iter_mut()) {
        *o = exact(normal_at(n, dn, j), j);
    }
}

/// `v` when it fits `i32`.
#[inline(always)]
fn fit(v: i64) -> Option<i32> {
    i32::try_from(v).ok()
}

/// The `u64` forward-difference triple advanced by `k` steps.
#[inline(always)]
fn advance(v: u64, d1: u64, d2: u64, k: u32) -> (u64, u64) {
    let k = u64::from(k);
    let tri = k * k.saturating_sub(1) / 2;
    (
        v.wrapping_add(d1.wrapping_mul(k))
            .wrapping_add(d2.wrapping_mul(tri)),
        d1.wrapping_add(d2.wrapping_mul(k)),
    )
}

/// The colour constants of one light (copied into the loop's locals).
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(super) struct Colour {
    /// The constants of [`Colour::of_terms`] (other than ARMv6-M): per
    /// channel `d | s << 16` and `amb + 2^15 (d + s)` (wrapping); first,
    /// at the copy's address (`run` loads them with no offset).
    pub(super) ds: [i32; 3],
    pub(super) ambo: [i32; 3],
    pub(super) amb: [i32; 3],
    pub(super) d: [i32; 3],
    pub(super) s: [i32; 3],
}

/// The offset of both halves of the packed light terms `nl15 | sp <<
/// 16` (both below `2^16`) in [`Colour::of_terms`] other than on
/// ARMv6-M: flipping bit 15 of each half (`t ^ 0x8000_8000`) makes a
/// half `x` the signed 16-bit `x - 2^15` (no borrow between the halves),
/// which the M4 multiplies by a packed coefficient with one
/// `SMLABB`/`SMLATT`.
const TERM_OFF: i32 = 1 << 15;

impl Colour {
    /// The constants of light `l` of kernel `k`.
    #[inline(always)]
    pub(super) fn of<R>(k: &PhongKernel<'_, R>, l: &KLight) -> Self {
        let d = l.d4.map(i32::from);
        let s = l.s4.map(i32::from);
        let amb = k.amb19;
        Self {
            amb,
            d,
            s,
            // d, s below 2^14: the halves are d and s again.
            ds: [0, 1, 2].map(|c| d[c] | s[c] << 16),
            ambo: [0, 1, 2].map(|c| amb[c].wrapping_add(TERM_OFF.wrapping_mul(d[c] + s[c]))),
        }
    }

    /// The Q19 channel sums of the packed light terms `nl15 | sp << 16`
    /// ([`PixelFormat::encode_q19`](crate::target::PixelFormat::encode_q19)
    /// clamps and encodes them): [`PhongKernel::channels_q19`] of the two
    /// terms, the same values on every target (the sums agree modulo
    /// 2^32: `amb + d·nl + s·sp = amb + 2^15 (d + s) + d (nl - 2^15) + s
    /// (sp - 2^15)`; tested).
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap)]
    pub(super) fn of_terms(&self, t: u32) -> [i32; 3] {
        if cfg!(armv6m) {
            self.of_terms_plain(t)
        } else {
            self.of_terms_dsp(t)
        }
    }

    /// [`Colour::of_terms`] on ARMv6-M.
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap)]
    fn of_terms_plain(&self, t: u32) -> [i32; 3] {
        PhongKernel::<crate::num::Q16>::channels_q19(self, (t & 0xFFFF) as i32, (t >> 16) as i32)
    }

    /// [`Colour::of_terms`] other than on ARMv6-M: per channel two
    /// signed 16 × 16-bit multiply-adds of the halves.
    #[inline(always)]
    #[allow(clippy::cast_possible_wrap, clippy::cast_sign_loss)]
    fn of_terms_dsp(&self, t: u32) -> [i32; 3] {
        let t = t ^ 0x8000_8000;
        let lo = i32::from(t as i16);
        let hi = (t as i32) >> 16;
        let ch = |k: usize| {
            let ds = self.ds[k];
            self.ambo[k]
                .wrapping_add(lo.wrapping_mul(i32::from(ds as i16)))
                .wrapping_add(hi.wrapping_mul(ds >> 16))
        };
        [ch(0), ch(1), ch(2)]
    }
}

/// The exact state of a span of one light (`u64` forward differences,
/// Q60) and its constant 32-bit second differences.
#[derive(Clone, Copy)]
pub(super) struct OneSpan {
    nn: u64,
    nn_d1: u64,
    nn_d2: u64,
    q: u64,
    q_d1: u64,
    q_d2: u64,
    nl0: i32,
    dnl: i32,
    nh0: i32,
    dnh: i32,
    nd2: Option<i32>,
    qd2: Option<i32>,
    /// `Qm` (Q20 segments) at the next chunk's first pixel.
    qm_a: i64,
}

/// Longest span run with a single plan ([`Whole`]): the 32-bit forward
/// differences, rounded down once at its first pixel, are then at most
/// `k + k(k - 1)/2 < 2^15` units of the last place off after `k` steps:
/// `2^-15` of `|n|²` and `2^-5` of a table segment.
pub(super) const WHOLE_MAX: u32 = 256;

/// The 32-bit state of a span run with a single plan: `|n|² - 1/4` (Q30),
/// `Qm` (Q20 segments) and `n·L` with their differences, and whether the
/// span has a specular term and `n·L > 0` at every pixel.
#[derive(Clone, Copy)]
pub(super) struct Whole {
    pub(super) nn: i32,
    pub(super) nd1: i32,
    pub(super) nd2: i32,
    pub(super) q: i32,
    pub(super) qd1: i32,
    pub(super) qd2: i32,
    pub(super) nl: i32,
    pub(super) dnl: i32,
    pub(super) spec: bool,
    pub(super) lit: bool,
}

impl Whole {
    /// The state of a chunk of `k` pixels run by `plan` (not
    /// [`Plan::Exact`]).
    #[inline(always)]
    fn of(plan: Plan, k: u32) -> Self {
        let lit =
            |nl: i32, dnl: i32| nl > 0 && i64::from(nl) + i64::from(dnl) * i64::from(k - 1) > 0;
        let (nn, q, nl, dnl, spec) = match plan {
            Plan::Spec(nn, q, nl, dnl) => (nn, q, nl, dnl, true),
            Plan::NoSpec(nn, nl, dnl) => (nn, (0, 0, 0), nl, dnl, false),
            Plan::Exact => ((1 << 28, 0, 0), (0, 0, 0), 0, 0, false),
        };
        Self {
            nn: nn.0.wrapping_sub(1 << 28),
            nd1: nn.1,
            nd2: nn.2,
            q: q.0,
            qd1: q.1,
            qd2: q.2,
            nl,
            dnl,
            spec,
            lit: spec && lit(nl, dnl),
        }
    }

    /// One pixel's step (`SPEC`: `Qm` too).
    #[inline(always)]
    fn step<const SPEC: bool>(&mut self) {
        self.nn = self.nn.wrapping_add(self.nd1);
        self.nd1 = self.nd1.wrapping_add(self.nd2);
        if SPEC {
            self.q = self.q.wrapping_add(self.qd1);
            self.qd1 = self.qd1.wrapping_add(self.qd2);
        }
        self.nl = self.nl.wrapping_add(self.dnl);
    }
}

/// How a chunk runs: the 32-bit loop with or without the specular
/// term (`|n|²` and `Qm` as 32-bit forward differences, `n·L` and its
/// step), or pixel by pixel in 64 bits.
#[derive(Clone, Copy)]
pub(super) enum Plan {
    Spec((i32, i32, i32), (i32, i32, i32), i32, i32),
    NoSpec((i32, i32, i32), i32, i32),
    Exact,
}

/// Whether a chunk has a specular term.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Spec,
    NoSpec,
    Exact,
}

impl<R: Real> PhongKernel<'_, R> {
    /// The span loop of one directional light, viewer at infinity (module
    /// docs); `n`, `dn` already flipped for back faces. A span with a
    /// single plan ([`Whole`]) runs as one loop, else chunk after chunk,
    /// each in one loop ([`PhongKernel::run`]: depth test, light terms,
    /// channels and store of a pixel together), the chunks the 32-bit
    /// loop cannot prove pixel by pixel in 64 bits.
    #[inline(always)]
    pub(super) fn fill_one(
        &self,
        l: &KLight,
        n: [i32; 3],
        dn: [i32; 3],
        len: u32,
        mut out: impl Out,
    ) -> u32 {
        if len < SHORT_SPAN {
            return short_span(n, dn, len, &mut out, |ni, i| {
                self.one_exact(l, ni, n, dn, i)
            });
        }
        let mut st = self.one_begin(l, n, dn);
        let c = Colour::of(self, l);
        if let Some(mut w) = self.one_whole(&st, len) {
            return len - self.run(&c, &mut w, 0, len, &mut out);
        }
        // Failures counted (the rarer case in a frame), passes derived.
        let mut failed = 0;
        let mut i = 0u32;
        while i < len {
            let k = (len - i).min(CHUNK as u32);
            failed += match self.chunk_plan(&mut st, i, k) {
                Plan::Exact => {
                    let mut f = 0;
                    for j in i..i + k {
                        if out.test(j) {
                            let nj = normal_at(n, dn, j);
                            out.write(j, unpack(self.one_exact(l, nj, n, dn, j)));
                        } else {
                            f += 1;
                        }
                    }
                    f
                }
                plan => {
                    let mut w = Whole::of(plan, k);
                    self.run(&c, &mut w, i, k, &mut out)
                }
            };
            i += k;
        }
        len - failed
    }

    /// The `k` pixels from pixel `i` of the 32-bit state `w`: the light
    /// terms of [`PhongKernel::terms_rn`] (`|n|²` stepped less `1/4`,
    /// the entry of [`RN`]; the table's address a constant on ARMv6-M,
    /// opaque, `black_box`, elsewhere: on the M4's span sweep, with the
    /// interpolated table then, 72.29 instructions a pixel as a constant
    /// against 73.11 opaque, with its `UMULL` form 71.84 as a constant,
    /// rebuilt by `MOVW`/`MOVT` at each use, against 71.30 opaque), the
    /// channels of [`Colour::of_terms`] (their constants first in
    /// [`Colour`], loaded from the copy's address: 65.74 -> 64.74; [`RN`]'s
    /// address a constant instead of opaque 65.64); returns how many failed the
    /// depth test. On ARMv6-M one loop ([`Out::fused`]: depth test,
    /// terms, channels and store of a pixel together); elsewhere piece
    /// by piece of [`CHUNK`] pixels ([`Out::masked`]: the piece's depth
    /// tests first, then one loop of terms, channels and stores, without
    /// a test when all passed, two pixels an iteration over a local copy
    /// of the state), the state in registers through the colour loop;
    /// since this round the loop's invariants read from a block of the
    /// frame ([`PhongKernel::run_inv`], [`INV_LOOP`]): 62.80 -> 59.07
    /// instructions a pixel on the M4's span sweep.
    /// Measured on the firmware's span sweep (one light), 64.74
    /// instructions a pixel on the M4 (the pair loop 103 instructions,
    /// 51.5 a pixel, the depth mask 8.6, a piece's set-up 92 a piece of
    /// 32, 2.9 a pixel, the span's ~3.5 with its plan and row fill);
    /// 71.30 before [`RN`] (the colour loop 57: 49 of
    /// arithmetic, loads and store, 8 of spills, reloads and copies;
    /// 72.20 before the interpolation as a `UMULL` and the opaque table
    /// address, with the colour loop 58, the depth
    /// mask 8.6 with its call, a piece's set-up 3.2, the span's 2.3;
    /// 73.48 with the mask inlined and the table's address opaque)
    /// against 77.53 with the one loop; pieces of 64 pixels (two masks, one colour loop)
    /// 73.82, the mode matched once a span instead of a piece 76.46; on the
    /// M0 the pieces cost 158.60 against 141.48, so it keeps the one
    /// loop. Not inlined (one copy per pixel and depth format), the
    /// colour constants copied into its frame: against 79.53 and 147.50
    /// inlined in the row fill, `.text` 5.1 KB and 6.0 KB less. Tried
    /// and measured worse on the M4: a piece's terms into a buffer, then
    /// `Out::chunk`'s mask and paint (span sweep 77.99 against 72.20,
    /// before the `UMULL` form); with it, in the long spans' region
    /// alone (73.70 instructions a pixel kept then): both terms of a
    /// pair before both colours 78.78, the colour constants in the
    /// loop's copied state 82.01, the channels from unpacked terms by
    /// `MLA` 76.34; with the opaque address (73.17 kept), the colour
    /// constants and the specular table copied into one block of the
    /// frame 73.28 (two instructions fewer a pair, a `memcpy` a span).
    /// With the packed specular table (62.87 kept), tried and measured
    /// worse: the depth tests of the whole span first (bit masks of 32
    /// pixels, then one colour loop over the span when all passed; the
    /// run's 96 instructions a piece down to 42, the pair loop up from 97
    /// to 100 with the colour constants loaded through an opaque copy's
    /// address, 108 without) 62.94, with the masks of the span from one
    /// call 64.59 (its loop spilled); the state copied into a local for
    /// the span 64.16; the two terms as one word `(nl15 ^ 2^15) << 16 |
    /// (sp ^ 2^15)` joined by `PKHTB` (no `EOR`) 67.97 (the compiler
    /// split the word's halves and the colour constants into nine
    /// registers again).
    #[inline(never)]
    #[allow(clippy::cast_possible_wrap)]
    fn run(&self, c: &Colour, w: &mut Whole, i: u32, k: u32, out: &mut impl Out) -> u32 {
        let c = *c;
        let c = &c;
        // Other than on ARMv6-M the table's address opaque, in a register
        // (or a spill slot) rather than rebuilt (`MOVW`/`MOVT`) at each use.
        let rs = if cfg!(armv6m) {
            &RN
        } else {
            core::hint::black_box(&RN)
        };
        // On ARMv6-M the channels of the terms as they are, not packed
        // and unpacked again (the same values: both below 2^16): the M0's
        // span sweep 129.38 -> 127.38 a pixel. Other than on ARMv6-M the
        // halves apart, each less `TERM_OFF` (no packing, no `EOR`),
        // measured 68.73 against 64.74 packed; the two second
        // differences packed in one register (`SXTAH`, `ASR`) 68.82.
        let px = |(nl15, sp): (u32, u32)| {
            if cfg!(armv6m) {
                PhongKernel::<crate::num::Q16>::channels_q19(c, (nl15 & 0xFFFF) as i32, sp as i32)
            } else {
                c.of_terms((nl15 & 0xFFFF) | sp << 16)
            }
        };
        // The pixels `j..j + kk` through `out.$loop`.
        macro_rules! pixels {
            ($loop:ident, $j:expr, $kk:expr) => {
                match (w.spec, w.lit) {
                    (true, true) => out.$loop(
                        $j,
                        $kk,
                        w,
                        |w| px(self.terms_rn::<true, true>(rn_entry(rs, w.nn), w.nl, w.q)),
                        Whole::step::<true>,
                    ),
                    (true, false) => out.$loop(
                        $j,
                        $kk,
                        w,
                        |w| px(self.terms_rn::<true, false>(rn_entry(rs, w.nn), w.nl, w.q)),
                        Whole::step::<true>,
                    ),
                    _ => out.$loop(
                        $j,
                        $kk,
                        w,
                        |w| px(self.terms_rn::<false, false>(rn_entry(rs, w.nn), w.nl, 0)),
                        Whole::step::<false>,
                    ),
                }
            };
        }
        if cfg!(armv6m) {
            return pixels!(fused, i, k);
        }
        #[cfg(not(armv6m))]
        if INV_LOOP {
            return self.run_inv(c, w, rs, i, k, out);
        }
        if TWO_PASS {
            return self.run_two_pass(c, w, rs, i, k, out);
        }
        let (end, mut j, mut failed) = (i + k, i, 0);
        while j < end {
            let kk = (end - j).min(CHUNK as u32);
            failed += pixels!(masked, j, kk);
            j += kk;
        }
        failed
    }

    /// [`PhongKernel::run`] other than on ARMv6-M ([`INV_LOOP`]): the
    /// loop's invariants (both tables' addresses, the second differences
    /// and `n·L`'s step, the colour constants) in one block of the frame
    /// read through an opaque address ([`Inv`]: `black_box`, so that the
    /// row's stores may alias it), so that the loop reloads them where it
    /// uses them (in pairs, `LDRD`) instead of holding them in registers
    /// and spilling the stepped values; the stepped values alone
    /// ([`Carry`]) and the block's address live through the loop. The
    /// same values as [`PhongKernel::run`]'s loop (`inv_loop_is_the_general_path`).
    #[cfg(not(armv6m))]
    #[inline(always)]
    fn run_inv(
        &self,
        c: &Colour,
        w: &mut Whole,
        rs: &[u32; RN_N],
        i: u32,
        k: u32,
        out: &mut impl Out,
    ) -> u32 {
        let inv = Inv {
            nd2: w.nd2,
            qd2: w.qd2,
            dnl: w.dnl,
            ch: [0, 1, 2].map(|k| [c.ds[k], c.ambo[k]]),
            rn: rs,
            tab: &self.packed,
        };
        let inv = core::hint::black_box(&inv);
        let mut s = Carry {
            nn: w.nn,
            nd1: w.nd1,
            q: w.q,
            qd1: w.qd1,
            nl: w.nl,
        };
        let (end, mut j, mut failed) = (i + k, i, 0);
        macro_rules! go {
            ($spec:literal, $lit:literal, $kk:expr) => {
                out.masked(
                    j,
                    $kk,
                    &mut s,
                    |s| inv.px::<$spec, $lit>(s),
                    |s| inv.step::<$spec>(s),
                )
            };
        }
        while j < end {
            let kk = (end - j).min(CHUNK as u32);
            failed += match (w.spec, w.lit) {
                (true, true) => go!(true, true, kk),
                (true, false) => go!(true, false, kk),
                _ => go!(false, false, kk),
            };
            j += kk;
        }
        (w.nn, w.nd1, w.q, w.qd1, w.nl) = (s.nn, s.nd1, s.q, s.qd1, s.nl);
        failed
    }

    /// [`PhongKernel::run`] other than on ARMv6-M in two passes a piece
    /// of [`CHUNK`] pixels ([`TWO_PASS`]): the light terms of the
    /// piece's pixels into a buffer (a loop whose state, the stepped
    /// quantities and both tables' addresses, fits the registers), then
    /// the depth mask and the colours of the passing pixels from the
    /// buffer ([`Out::chunk`]: the colour constants in registers).
    #[inline(always)]
    fn run_two_pass(
        &self,
        c: &Colour,
        w: &mut Whole,
        rs: &[u32; RN_N],
        i: u32,
        k: u32,
        out: &mut impl Out,
    ) -> u32 {
        let (end, mut j, mut failed) = (i + k, i, 0);
        let mut buf = [0u32; CHUNK];
        let cc = *c;
        while j < end {
            let kk = (end - j).min(CHUNK as u32);
            let b = &mut buf[..kk as usize];
            match (w.spec, w.lit) {
                (true, true) => self.terms_into::<true, true>(w, rs, b),
                (true, false) => self.terms_into::<true, false>(w, rs, b),
                _ => self.terms_into::<false, false>(w, rs, b),
            }
            failed += out.chunk(j, b, move |t| cc.of_terms(t));
            j += kk;
        }
        failed
    }

    /// The packed light terms `nl15 | sp << 16` of [`PhongKernel::terms_rn`]
    /// of the pixels of `buf`, the state `w` stepped past them.
    #[inline(always)]
    fn terms_into<const SPEC: bool, const LIT: bool>(
        &self,
        w: &mut Whole,
        rs: &[u32; RN_N],
        buf: &mut [u32],
    ) {
        let mut s = *w;
        for o in buf.iter_mut() {
            let (nl15, sp) = self.terms_rn::<SPEC, LIT>(rn_entry(rs, s.nn), s.nl, s.q);
            *o = (nl15 & 0xFFFF) | sp << 16;
            s.step::<SPEC>();
        }
        *w = s;
    }

    /// The span's single plan ([`Whole`]) when the span is longer than a
    /// chunk and at most [`WHOLE_MAX`] pixels long and its whole length can be proven as a
    /// chunk is (the plan of one chunk of `len` pixels), with `|n|²` at
    /// least `2^-13` above `1/4` (the 32-bit stepping's error margin).
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    pub(super) fn one_whole(&self, st: &OneSpan, len: u32) -> Option<Whole> {
        // One chunk or less: its own plan is the whole span's.
        if len <= CHUNK as u32 || len > WHOLE_MAX {
            return None;
        }
        // The plan's own bound on `|n|²` with the margin (one bound,
        // not a second one here).
        match self.plan_above(&mut st.clone(), 0, len, (1 << 58) + (1 << 45)) {
            Plan::Exact => None,
            plan => Some(Whole::of(plan, len)),
        }
    }

    /// The span's exact state (see the module docs).
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    pub(super) fn one_begin(&self, l: &KLight, n: [i32; 3], dn: [i32; 3]) -> OneSpan {
        let (nn, nn_d1, nn_d2) = quad(&[(n, dn)]);
        let f = if self.spec {
            let (c0, c1) = (cross(n, l.p1), cross(dn, l.p1));
            let (k0, k1) = (lin(n, l.p2), lin(dn, l.p2));
            [
                ([c0[0], c0[1], c0[2]], [c1[0], c1[1], c1[2]]),
                ([k0, 0, 0], [k1, 0, 0]),
            ]
        } else {
            [([0; 3], [0; 3]); 2]
        };
        let (q, q_d1, q_d2) = quad(&f);
        let (nh0, dnh) = if self.blinn {
            (lin(n, l.p1), lin(dn, l.p1))
        } else {
            (1, 0)
        };
        OneSpan {
            nn,
            nn_d1,
            nn_d2,
            q,
            q_d1,
            q_d2,
            nl0: lin(n, l.at),
            dnl: lin(dn, l.at),
            nh0,
            dnh,
            // Constant second differences (`d2 >= 0` below 2^63 for steps
            // of normals below 2^30 per pixel; else every chunk is exact).
            nd2: fit((nn_d2 >> 30) as i64),
            qd2: fit(mul_shr48(q_d2 as i64, self.kf)),
            qm_a: mul_shr48(q as i64, self.kf),
        }
    }

    /// [`PhongKernel::one_plan`], with full chunks' `k` a constant: the
    /// products by `k` (64-bit on the M0) fold into shifts and constants.
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    pub(super) fn chunk_plan(&self, st: &mut OneSpan, i: u32, k: u32) -> Plan {
        if k == CHUNK as u32 {
            self.one_plan(st, i, CHUNK as u32)
        } else {
            self.one_plan(st, i, k)
        }
    }

    /// How the chunk of the `k` pixels from pixel `i` runs, and the
    /// state stepped past them.
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    pub(super) fn one_plan(&self, st: &mut OneSpan, i: u32, k: u32) -> Plan {
        self.plan_above(st, i, k, 1 << 58)
    }

    /// [`PhongKernel::one_plan`] with `|n|²` (Q60) proven at least
    /// `nn_min` (at least `1/4`) over the chunk, else [`Plan::Exact`].
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    fn plan_above(&self, st: &mut OneSpan, i: u32, k: u32, nn_min: u64) -> Plan {
        let OneSpan {
            nn,
            nn_d1,
            nn_d2,
            q,
            q_d1,
            q_d2,
            nl0,
            dnl,
            nh0,
            dnh,
            nd2,
            qd2,
            qm_a,
        } = *st;
        let (nn_b, nn_d1_b) = advance(nn, nn_d1, nn_d2, k);
        let (q_b, q_d1_b) = advance(q, q_d1, q_d2, k);
        let qm_b = mul_shr48(q_b as i64, self.kf);
        let nl = nl0.wrapping_add(dnl.wrapping_mul(i as i32));
        // |n|² within [1/4, 5/4) over the chunk: below at both ends
        // (convex: in between too), above `min(ends) - d2·k²/8`.
        let nn_lo = nn
            .min(nn_b)
            .saturating_sub(nn_d2.saturating_mul(u64::from(k * k)) / 8);
        let nn_ok = nn.max(nn_b) < 5 << 58 && nn_lo >= nn_min;
        let nn32 = ((nn >> 30) as i32, fit((nn_d1 as i64) >> 30), nd2);
        let mode = if !self.spec {
            Mode::NoSpec
        } else {
            let nh_a = i64::from(nh0) + i64::from(dnh) * i64::from(i);
            let nh_z = nh_a + i64::from(dnh) * i64::from(k - 1);
            let lo = qm_a.min(qm_b) - i64::from(qd2.unwrap_or(i32::MAX)) * i64::from(k * k) / 8;
            if nh_a <= 0 && nh_z <= 0 || lo >= QM_OFF {
                Mode::NoSpec
            } else if nh_a > 0 && nh_z > 0 && qm_a.max(qm_b) <= QM_MAX && qm_a.min(qm_b) >= 0 {
                Mode::Spec
            } else {
                Mode::Exact
            }
        };
        let q32 = (qm_a as i32, fit(mul_shr48(q_d1 as i64, self.kf)), qd2);
        (st.nn, st.nn_d1, st.q, st.q_d1, st.qm_a) = (nn_b, nn_d1_b, q_b, q_d1_b, qm_b);
        match (mode, nn_ok, nn32, q32) {
            (Mode::Spec, true, (a, Some(b), Some(d)), (qa, Some(qb), Some(qc))) => {
                Plan::Spec((a, b, d), (qa, qb, qc), nl, dnl)
            }
            (Mode::NoSpec, true, (a, Some(b), Some(d)), _) => Plan::NoSpec((a, b, d), nl, dnl),
            _ => Plan::Exact,
        }
    }

    /// One pixel's light terms from `|n|²` (Q30, within `[1/4, 5/4)`),
    /// `n·L` (Q30) and the table position before the division by `|n|²`,
    /// `q7` (Q7 segments: the point loop's `K·w·A`): `N·L` in Q15 (`nl15 <= 2^15 (1 + 2^-11)`,
    /// below 2^16; 0 for `n·L <= 0`) and the specular factor in Q15 (the
    /// table's, `<= 2^15`; 0 for `n·L <= 0`). The per-pixel arithmetic of
    /// both 32-bit loops, before the channels.
    #[inline(always)]
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
    pub(super) fn terms<const SPEC: bool>(&self, nn: i32, nl: i32, q7: i32) -> (u32, u32) {
        self.terms_r::<SPEC>(rsq(nn), nl, q7)
    }

    /// [`PhongKernel::terms`] from `r = 2^16 / |n|` ([`rsq`] of `|n|²`):
    /// the same values (the loop of several lights computes `r` once a
    /// pixel).
    #[inline(always)]
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
    pub(super) fn terms_r<const SPEC: bool>(&self, r: u32, nl: i32, q7: i32) -> (u32, u32) {
        // N·L in Q15: (n·L)/|n| <= 1 (within 2^-11 relative: no clamp
        // needed below, the products stay below 2^30).
        let nl15 = ((nl.max(0) as u32) >> 15).wrapping_mul(r) >> 16;
        let sp = if SPEC && nl > 0 {
            self.spec_r(r, q7)
        } else {
            0
        };
        (nl15, sp)
    }

    /// The specular factor of [`PhongKernel::terms_r`] (`n·L > 0`).
    #[inline(always)]
    #[allow(clippy::cast_sign_loss, clippy::cast_possible_truncation)]
    pub(super) fn spec_r(&self, r: u32, q7: i32) -> u32 {
        let r14 = r >> 2;
        // 2^14 / |n|² <= 2^16.
        let rr14 = (r14 * r14) >> 14;
        // The position (Q7 segments) saturated below 2^15 (256
        // segments, beyond the table's 1.25 · 128); divided by |n|²
        // in Q21 segments below 2^31, saturated at the table's end.
        let qs = q7.clamp(0, (1 << 15) - 1) as u32;
        let pos = ((qs * rr14) as i32).clamp(0, (1 << 28) - 1) as u32;
        let j = (pos >> 21) as usize & (SPEC_SEGMENTS - 1);
        let f = (pos >> 5) & 0xFFFF;
        let (a, b) = (u32::from(self.table[j]), u32::from(self.table[j + 1]));
        a - (((a - b) * f) >> 16)
    }

    /// The light terms of the one-light loop from `e`, the entry of
    /// [`RN`] for the pixel's `|n|²` ([`rn_entry`]), `n·L` (Q30) and `Qm`
    /// (Q20 segments): `N·L` in Q15, `floor((n·L / 2^13) · (2^14/|n|) /
    /// 2^16)` (below `2^15 (1 + 2^-10)`: `n·L <= |n|`), and the specular
    /// factor in Q15, the table [`PhongKernel`]'s `table` interpolated at
    /// `min(Qm/2^13 · 2^13/|n|², 2^27 - 1)` (Q20 segments: `Qm/2^13`
    /// saturated to `0..2^15`, the product below `2^30`); 0 for `n·L <=
    /// 0` (`LIT`: `n·L > 0` known, not tested). Products of 32-bit
    /// operands whose results stay below `2^32` (one `MULS` on ARMv6-M);
    /// other than on ARMv6-M the position's product written on signed
    /// 16-bit operands (the same value: both below `2^15`), measured on
    /// the M4's span sweep 64.74 instructions a pixel against 69.40
    /// written as on ARMv6-M (the loop's registers allocated otherwise).
    /// Against [`PhongKernel::terms`] (the interpolated table of the
    /// other loops): `N·L` within `2^-10.97` relative instead of
    /// `2^-11.4`, the position within `2^-9.98` instead of `2^-10.4`
    /// ([`RN`]'s bounds, `rn_table_within_bound`). Other than on ARMv6-M
    /// the specular table's two entries from one load of the kernel's
    /// packed table ([`pack_table`]: the same value), measured on the M4's
    /// span sweep 64.74 -> 62.87 instructions a pixel (the pair loop 103
    /// -> 99 instructions; the kernel 516 bytes larger, built only for one
    /// directional light with a specular term: the dodecahedron Phong
    /// raster 1 611 934 -> 1 617 508).
    #[inline(always)]
    #[allow(
        clippy::cast_sign_loss,
        clippy::cast_possible_truncation,
        clippy::cast_possible_wrap
    )]
    pub(super) fn terms_rn<const SPEC: bool, const LIT: bool>(
        &self,
        e: u32,
        nl: i32,
        qm: i32,
    ) -> (u32, u32) {
        let nlp = if LIT { nl } else { nl.max(0) };
        let nl15 = (((nlp as u32) >> 13).wrapping_mul(e >> 16)) >> 16;
        let sp = if SPEC && (LIT || nl > 0) {
            let q7 = (qm >> (QM_FRAC - 7)).clamp(0, (1 << 15) - 1);
            // Below 2^30: both operands below 2^15 (signed 16-bit
            // operands other than on ARMv6-M: the same product).
            let pos = if cfg!(armv6m) {
                (q7 as u32).wrapping_mul(e & 0xFFFF) as i32
            } else {
                i32::from(q7 as i16) * i32::from(e as i16)
            };
            let pos = pos.clamp(0, (1 << 27) - 1) as u32;
            let j = (pos >> 20) as usize & (SPEC_SEGMENTS - 1);
            let f = (pos >> 4) & 0xFFFF;
            #[cfg(not(armv6m))]
            {
                let e = self.packed[j];
                (e & 0xFFFF).wrapping_sub(((e >> 16) * f) >> 16)
            }
            #[cfg(armv6m)]
            {
                let (a, b) = (u32::from(self.table[j]), u32::from(self.table[j + 1]));
                a - (((a - b) * f) >> 16)
            }
        } else {
            0
        };
        (nl15, sp)
    }

    /// The colour (`r | g << 8 | b << 16`) of the light terms of
    /// [`PhongKernel::terms`]: per channel ambient plus diffuse times
    /// `N·L` plus specular times the factor, clamped to `0..=255`.
    #[inline(always)]
    pub(super) fn channels(c: &Colour, nl15: i32, sp: i32) -> u32 {
        pack(level_q19(Self::channels_q19(c, nl15, sp)))
    }

    /// The channel sums (Q19, before the clamp) of [`PhongKernel::channels`].
    #[inline(always)]
    pub(super) fn channels_q19(c: &Colour, nl15: i32, sp: i32) -> [i32; 3] {
        let ch = |k: usize| {
            c.amb[k]
                .wrapping_add(c.d[k].wrapping_mul(nl15))
                .wrapping_add(c.s[k].wrapping_mul(sp))
        };
        [ch(0), ch(1), ch(2)]
    }

    /// One pixel of normal `n` (Q30) in 64 bits: the chunks the 32-bit
    /// loop cannot prove (`n0`, `dn`, `i` for the generic fallback).
    #[cold]
    #[inline(never)]
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    pub(super) fn one_exact(
        &self,
        l: &KLight,
        n: [i32; 3],
        n0: [i32; 3],
        dn: [i32; 3],
        i: u32,
    ) -> u32 {
        let nn = sq3(n);
        let nl = lin(n, l.at);
        let cl = Colour::of(self, l);
        let e = rn_entry(&RN, ((nn >> 30) as i32).wrapping_sub(1 << 28));
        if !(1 << 58..5 << 58).contains(&nn) {
            pack(fallback(self.shade, n0, dn, [0; 3], [0; 3], i))
        } else if self.spec && (!self.blinn || lin(n, l.p1) > 0) {
            let k = lin(n, l.p2);
            let q = sq3(cross(n, l.p1)).wrapping_add(wmul(k, k) as u64);
            let qm = mul_shr48(q as i64, self.kf).clamp(0, QM_MAX) as i32;
            let (nl15, sp) = self.terms_rn::<true, false>(e, nl, qm);
            Self::channels(&cl, nl15 as i32, sp as i32)
        } else {
            let (nl15, sp) = self.terms_rn::<false, false>(e, nl, 0);
            Self::channels(&cl, nl15 as i32, sp as i32)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shade of the one-light tests: one directional light, shininess
    /// 40, Phong, viewer at infinity.
    fn test_shade() -> crate::illum::Shade<crate::num::Q16> {
        use crate::geom::Vec3;
        use crate::illum::{Light, Material, Shade, Specular, Viewer};
        use crate::num::Q16;
        let q = Q16::from_f64;
        let mat = Material {
            color: Vec3::new(q(1.0), q(0.8), q(0.6)),
            ka: q(0.1),
            kd: q(0.7),
            ks: q(0.5),
            shininess: q(40.0),
        };
        let lights = [Light::directional(
            Vec3::new(q(0.3), q(0.4), q(0.866)),
            q(1.0),
        )];
        Shade::new(&mat, q(0.2), &lights, Specular::Phong, Viewer::Infinite).unwrap()
    }

    /// Both packings of the light terms give the colour of
    /// [`PhongKernel::channels`] over the terms' whole range (`N·L` to
    /// `2^15 (1 + 2^-11)`, the specular factor to `2^15`), coefficients
    /// to `2^14 - 1` and ambient levels up to the clamp and beyond.
    #[test]
    fn packed_terms_give_the_channels() {
        let mut rng = crate::geom::testkit::xorshift(0x9E37_79B9_7F4A_7C15);
        let mut next = |m: u32| (rng() >> 16) as u32 % m;
        let nl_max = (1u32 << 15) + (1 << 4);
        let mut checked = 0;
        for case in 0..2000 {
            let coef = |next: &mut dyn FnMut(u32) -> u32| match case % 4 {
                0 => [0, (1 << 14) - 1, 1 << 13],
                _ => [
                    next(1 << 14) as i32,
                    next(1 << 14) as i32,
                    next(1 << 14) as i32,
                ],
            };
            let d = coef(&mut next);
            let s = coef(&mut next);
            let amb = [0, 1, 2].map(|_| (next(300 << 19) as i32) + (1 << 18));
            let c = Colour {
                amb,
                d,
                s,
                ds: [0, 1, 2].map(|k| d[k] | s[k] << 16),
                ambo: [0, 1, 2].map(|k| amb[k].wrapping_add(TERM_OFF.wrapping_mul(d[k] + s[k]))),
            };
            let terms = [
                (0, 0),
                (nl_max, 1 << 15),
                (nl_max, 0),
                (0, 1 << 15),
                (next(nl_max + 1), next((1 << 15) + 1)),
                (next(nl_max + 1), next((1 << 15) + 1)),
            ];
            for (nl, sp) in terms {
                let want = PhongKernel::<crate::num::Q16>::channels_q19(&c, nl as i32, sp as i32);
                let t = (nl & 0xFFFF) | sp << 16;
                assert_eq!(c.of_terms_plain(t), want);
                assert_eq!(c.of_terms_dsp(t), want, "{nl} {sp}");
                assert_eq!(c.of_terms(t), want);
                checked += 1;
            }
        }
        assert_eq!(checked, 12_000);
    }

    /// [`RN`] over `|n|² ∈ [1/4, 5/4)`: at both ends and the middle of
    /// every segment ([`rn_entry`]'s index), `2^14/|n|` within `2^-10.97`
    /// of the entry's high half relative (`2^-12.38` for `|n|² >= 3/4`),
    /// `2^13/|n|²` within `2^-9.98` of its low half (`2^-11.40`), both
    /// halves below `2^15`; the largest errors measured at those bounds.
    #[test]
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    fn rn_table_within_bound() {
        let mut worst = [[0f64; 2]; 2];
        for j in 0..RN_N as u32 {
            for nb in [j << 19, (j << 19) + (1 << 18), ((j + 1) << 19) - 1] {
                let e = rn_entry(&RN, nb as i32);
                assert_eq!(e, RN[j as usize]);
                let (r, rr) = (f64::from(e >> 16), f64::from(e & 0xFFFF));
                assert!(r < 32768.0 && rr < 32768.0, "{j}");
                let f = 0.25 + f64::from(nb) / f64::from(1u32 << 30);
                let er = (r / (16384.0 / f.sqrt()) - 1.0).abs();
                let err = (rr / (8192.0 / f) - 1.0).abs();
                let w = &mut worst[usize::from(f >= 0.75)];
                w[0] = w[0].max(er);
                w[1] = w[1].max(err);
            }
        }
        let bits = worst.map(|w| w.map(|x| -x.log2()));
        extern crate std;
        std::println!("RN: relative error 2^-{bits:.2?}");
        assert!(bits[0][0] >= 10.97 && bits[0][1] >= 9.98, "{bits:?}");
        assert!(bits[1][0] >= 12.38 && bits[1][1] >= 11.40, "{bits:?}");
        assert!(bits[0][0] < 11.0 && bits[1][1] < 11.5, "{bits:?}");
    }

    /// [`PhongKernel::terms_rn`] against `f64` on random normals of
    /// `|n|²` in `[1/4, 5/4)`, light directions and table positions:
    /// `N·L` within `2^15 · 2^-10.97 + 2` units of `2^15 (n·L)/|n|` and
    /// below `2^16`; the specular factor within one unit plus the table's
    /// largest step times the position's error (`2^-9.98` relative,
    /// plus `2^-5` segments from `Qm`'s truncation to Q7) of the table
    /// interpolated at the exact position `Qm/|n|²`; `LIT` the same
    /// values for `n·L > 0`; 0 for `n·L <= 0`.
    #[test]
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_possible_wrap,
        clippy::cast_sign_loss
    )]
    fn terms_rn_against_f64() {
        let shade = test_shade();
        let k = PhongKernel::new(&shade).unwrap();
        let step = (0..SPEC_SEGMENTS)
            .map(|j| f64::from(k.table[j]) - f64::from(k.table[j + 1]))
            .fold(0f64, f64::max);
        let mut next = crate::geom::testkit::uniform(0x9E37_79B9_7F4A_7C15);
        let (mut worst_nl, mut worst_sp, mut checked) = (0f64, 0f64, 0);
        for _ in 0..200_000 {
            let v = [next() - 0.5, next() - 0.5, next() - 0.5];
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            if len < 1e-3 {
                continue;
            }
            let nn = 0.25 + next() * (1.0 - 1e-9);
            let n = v.map(|c| c / len * nn.sqrt());
            let l = {
                let w = [next() - 0.5, next() - 0.5, next() - 0.5];
                let m = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt().max(1e-9);
                w.map(|c| c / m)
            };
            let nl_f = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
            let nl = (nl_f * f64::from(1u32 << 30)) as i32;
            let nb = ((nn - 0.25) * f64::from(1u32 << 30)) as i32;
            let e = rn_entry(&RN, nb);
            let qm = (next() * 200.0 * f64::from(1u32 << QM_FRAC)) as i32;
            let (nl15, sp) = k.terms_rn::<true, false>(e, nl, qm);
            let (nl15_ns, sp_ns) = k.terms_rn::<false, false>(e, nl, qm);
            assert_eq!((nl15_ns, sp_ns), (nl15, 0));
            if nl <= 0 {
                assert_eq!((nl15, sp), (0, 0));
                continue;
            }
            assert_eq!(k.terms_rn::<true, true>(e, nl, qm), (nl15, sp));
            assert!(nl15 < 1 << 16);
            let want = f64::from(1u32 << 15) * nl_f / nn.sqrt();
            let d = (f64::from(nl15) - want).abs();
            assert!(d <= 32768.0 * 2f64.powf(-10.97) + 2.0, "{d}");
            worst_nl = worst_nl.max(d);
            // The table interpolated at the exact position (segments).
            let pos = f64::from(qm) / f64::from(1u32 << QM_FRAC) / nn;
            let at = |p: f64| {
                let p = p.clamp(0.0, SPEC_SEGMENTS as f64 - 1e-9);
                let j = p as usize;
                let (a, b) = (f64::from(k.table[j]), f64::from(k.table[j + 1]));
                a - (a - b) * (p - j as f64)
            };
            let dpos = pos * 2f64.powf(-9.98) + 1.0 / 32.0;
            let d = (f64::from(sp) - at(pos)).abs();
            assert!(d <= step * dpos + 1.0, "{d} at {pos}");
            worst_sp = worst_sp.max(d / (step * dpos + 1.0));
            checked += 1;
        }
        extern crate std;
        std::println!("terms_rn: N·L {worst_nl:.2} units, specular {worst_sp:.3} of its bound");
        assert!(checked > 90_000, "{checked}");
    }

    /// The packed table from `|n|² - 1/4` ([`rsq_biased`])
    /// gives [`rsq`]'s value at every `|n|²` of `[1/4, 5/4)` on a grid
    /// of `2^6` (Q30) and at each segment's ends.
    #[test]
    fn packed_rsq_is_rsq() {
        let mut checked = 0u32;
        let mut nn = 1i32 << 28;
        while nn < 5 << 28 {
            for v in [nn, nn + 63, nn | 0xFF_FFFF] {
                if v < 5 << 28 {
                    let want = rsq(v);
                    assert_eq!(rsq_biased(&RS_PACKED, v - (1 << 28)), want, "{v}");
                    checked += 1;
                }
            }
            nn += 1 << 6;
        }
        assert_eq!(checked, 3 << 24);
        // 2^16 / |n| at |n|² = 1/4 and 1 (RS's ends of the range).
        assert_eq!(rsq_biased(&RS_PACKED, 0), 1 << 17);
        assert_eq!(rsq_biased(&RS_PACKED, 3 << 28), 1 << 16);
    }

    /// [`Inv::px`] (the loop of [`PhongKernel::run_inv`]) gives the
    /// channel sums of [`PhongKernel::terms_rn`] and [`Colour::of_terms`]
    /// (the general path), and [`Inv::step`] [`Whole::step`]'s values, for
    /// each plan's `SPEC`/`LIT`: over every entry of [`RN`], random and
    /// extreme `n·L` (up to `|n|`, the `n·L <= |n|` bound the unmasked
    /// `N·L` relies on, and negative), `Qm` (negative, at the table's
    /// end, at the saturation of its Q7 form and beyond) and random
    /// colours of two shininesses.
    #[cfg(not(armv6m))]
    #[test]
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_possible_wrap,
        clippy::cast_sign_loss
    )]
    fn inv_loop_is_the_general_path() {
        use crate::geom::Vec3;
        use crate::illum::{Light, Material, Shade, Specular, Viewer};
        use crate::num::Q16;
        let mut rng = crate::geom::testkit::xorshift(0x2545_F491_4F6C_DD1D);
        let mut next = move || rng() as u32;
        let q = Q16::from_f64;
        let mut checked = 0u32;
        for (shin, col) in [(20.0, [0.9, 0.7, 0.5]), (5000.0, [1.0, 1.0, 1.0])] {
            let mat = Material {
                color: Vec3::new(q(col[0]), q(col[1]), q(col[2])),
                ka: q(0.3),
                kd: q(0.9),
                ks: q(0.9),
                shininess: q(shin),
            };
            let lights = [Light::directional(
                Vec3::new(q(0.3), q(0.4), q(0.866)),
                q(1.0),
            )];
            let shade =
                Shade::new(&mat, q(0.5), &lights, Specular::Phong, Viewer::Infinite).unwrap();
            let k = PhongKernel::new(&shade).unwrap();
            let c = Colour::of(&k, &k.lights[0]);
            let inv = Inv {
                nd2: next() as i32,
                qd2: next() as i32,
                dnl: next() as i32,
                ch: [0, 1, 2].map(|j| [c.ds[j], c.ambo[j]]),
                rn: &RN,
                tab: &k.packed,
            };
            let qms = [
                -1,
                0,
                1 << 20,
                QM_OFF as i32,
                (1 << 28) - 1,
                1 << 28,
                QM_MAX as i32,
                i32::MAX,
                i32::MIN,
            ];
            for j in 0..RN_N as u32 {
                for r in 0..8u32 {
                    let nb = ((j << 19) | (next() & 0x7_FFFF)) as i32;
                    // |n| of the entry's segment end: n·L at most |n|.
                    let nn = 0.25 + f64::from(nb) / f64::from(1u32 << 30);
                    let top = (nn.sqrt() * f64::from(1u32 << 30)) as i32;
                    let nl = match r {
                        0 => top,
                        1 => 0,
                        2 => -1,
                        3 => i32::MIN,
                        _ => {
                            (next() % (top as u32 + 1)) as i32
                                - (next() % 4 == 0) as i32 * (next() >> 2) as i32
                        }
                    };
                    let qm = if r < 4 {
                        qms[(j as usize + r as usize) % qms.len()]
                    } else {
                        next() as i32 >> (next() % 8)
                    };
                    let s = Carry {
                        nn: nb,
                        nd1: next() as i32,
                        q: qm,
                        qd1: next() as i32,
                        nl,
                    };
                    let e = rn_entry(&RN, nb);
                    let want = |(a, b): (u32, u32)| c.of_terms((a & 0xFFFF) | b << 16);
                    assert_eq!(
                        inv.px::<true, false>(&s),
                        want(k.terms_rn::<true, false>(e, nl, qm)),
                        "{nb} {nl} {qm}"
                    );
                    assert_eq!(
                        inv.px::<false, false>(&s),
                        want(k.terms_rn::<false, false>(e, nl, qm)),
                        "{nb} {nl} {qm}"
                    );
                    if nl > 0 {
                        assert_eq!(
                            inv.px::<true, true>(&s),
                            want(k.terms_rn::<true, true>(e, nl, qm)),
                            "{nb} {nl} {qm}"
                        );
                    }
                    for spec in [false, true] {
                        let mut w = Whole {
                            nn: s.nn,
                            nd1: s.nd1,
                            nd2: inv.nd2,
                            q: s.q,
                            qd1: s.qd1,
                            qd2: inv.qd2,
                            nl: s.nl,
                            dnl: inv.dnl,
                            spec,
                            lit: false,
                        };
                        let mut t = s;
                        if spec {
                            w.step::<true>();
                            inv.step::<true>(&mut t);
                        } else {
                            w.step::<false>();
                            inv.step::<false>(&mut t);
                        }
                        assert_eq!(
                            (t.nn, t.nd1, t.q, t.qd1, t.nl),
                            (w.nn, w.nd1, w.q, w.qd1, w.nl)
                        );
                    }
                    checked += 1;
                }
            }
        }
        assert_eq!(checked, 2 * 8 * RN_N as u32);
    }

    /// `advance` by `k` steps is `k` single steps, wrapping (the set-up
    /// of a full chunk, `k` a constant, and of a partial one).
    /// A span run with a single plan ([`Whole`]): its 32-bit `|n|²` and
    /// `Qm` within `k + k(k - 1)/2` units of the last place below the
    /// exact values (`u64` forward differences) after `k` steps, over
    /// spans of [`WHOLE_MAX`] pixels.
    #[test]
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    fn whole_span_stepping_within_bound() {
        let shade = test_shade();
        let k = PhongKernel::new(&shade).unwrap();
        let l = &k.lights[0];
        let mut runs = 0;
        for (n, dn) in [
            ([0, 0, 1 << 30], [1 << 21, -(1 << 20), -(1 << 18)]),
            ([-(1 << 28), 1 << 27, 1 << 30], [1 << 20, 3 << 18, 1 << 16]),
            (
                [300_000_000, 400_000_000, 880_000_000],
                [-777_777, 123_457, 54_321],
            ),
        ] {
            let st = k.one_begin(l, n, dn);
            let Some(mut w) = k.one_whole(&st, WHOLE_MAX) else {
                continue;
            };
            runs += 1;
            let (mut nn, mut nn_d1) = (st.nn, st.nn_d1);
            let (mut qx, mut q_d1) = (st.q, st.q_d1);
            for i in 0..WHOLE_MAX {
                let bound = i64::from(i + i * i.saturating_sub(1) / 2) + 1;
                let e_nn = i64::from(((nn >> 30) as i32).wrapping_sub(1 << 28)) - i64::from(w.nn);
                assert!((0..=bound).contains(&e_nn), "|n|² {i}: {e_nn}");
                if w.spec {
                    let e_q = mul_shr48(qx as i64, k.kf) - i64::from(w.q);
                    assert!((0..=bound).contains(&e_q), "Qm {i}: {e_q}");
                }
                (nn, nn_d1) = advance(nn, nn_d1, st.nn_d2, 1);
                (qx, q_d1) = advance(qx, q_d1, st.q_d2, 1);
                let (a, b, c, d, e) = (w.nd1, w.nd2, w.qd1, w.qd2, w.dnl);
                (w.nn, w.nd1, w.q, w.qd1, w.nl) = (
                    w.nn.wrapping_add(a),
                    a.wrapping_add(b),
                    w.q.wrapping_add(c),
                    c.wrapping_add(d),
                    w.nl.wrapping_add(e),
                );
            }
        }
        assert!(runs >= 2, "{runs}");
    }

    #[test]
    fn advance_by_constant_and_variable_k_agree() {
        for &(v, d1, d2) in &[
            (1u64 << 60, 3u64 << 40, 5u64 << 30),
            (u64::MAX / 3, 12_345, 678),
        ] {
            for k in [1u32, 7, 31, 32] {
                let (a, b) = advance(v, d1, d2, k);
                let (mut x, mut y) = (v, d1);
                for _ in 0..k {
                    x = x.wrapping_add(y);
                    y = y.wrapping_add(d2);
                }
                assert_eq!((a, b), (x, y));
            }
        }
    }
}
