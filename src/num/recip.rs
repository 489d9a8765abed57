//! The reciprocal of a triangle's doubled area, without a division per
//! gradient: [`Recip`] (general, 64-bit numerators) and [`InvArea`] (the
//! `i32` interpolation's gradients), from one exact `round(2^63 / x)`
//! ([`recip63`]: a table-seeded Newton iteration on ARMv6-M, two hardware
//! divisions elsewhere).

use super::wide::{
    clz32, clz64, mulhi, shl64, shr64, wmul, wmul_u32, CLZ8, NO_DIVIDE, NO_LONG_MUL,
};

/// The reciprocal of a doubled triangle area in fixed point:
/// `1/|a| ≈ m · 2^-k`, `m` rounded to 32 significant bits.
///
/// Error: `a` is first truncated to 32 significant bits (relative error
/// < 2^-31) and `m` rounded (< 2^-32), and a numerator it multiplies is
/// truncated to 31 significant bits (< 2^-31): a product is within a
/// relative 2^-30 of the exact quotient, plus ½ of its last place from the
/// final rounding.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Recip {
    /// `round(2^63 / norm)` for the normalised magnitude, in `[2^31,
    /// 2^32)` (a power-of-two magnitude, whose reciprocal would be 2^32,
    /// is kept as `2^31` with `k` one less: the same value).
    m: u32,
    k: u32,
    negative: bool,
}

impl Recip {
    /// The reciprocal of `a` (`a != 0`; zero gives a reciprocal of 1/1
    /// rather than a panic, and the rasterizer never asks for it).
    ///
    /// No division: `m` comes from a table-seeded Newton iteration and an
    /// exact remainder correction (`recip63`), so it is the very value
    /// `round(2^63 / norm)` a division would give, on every target.
    pub fn new(a: i64) -> Self {
        let negative = a < 0;
        let mag = a.unsigned_abs().max(1);
        let n = 63 - clz64(mag); // 2^n <= mag < 2^(n+1)
        let norm = if n >= 31 {
            shr64(mag, n - 31)
        } else {
            shl64(mag, 31 - n)
        }; // in [2^31, 2^32)
        let m = recip63(norm as u32);
        // m <= 2^32; m == 2^32 only for norm == 2^31: halve it exactly.
        let (m, k) = if m > u32::MAX as u64 {
            ((m >> 1) as u32, 31 + n)
        } else {
            (m as u32, 32 + n)
        };
        Self { m, k, negative }
    }

    /// `round(num · 2^s / a)` within the error stated on [`Recip`];
    /// saturates at `i64` bounds.
    ///
    /// The numerator is normalised to its top 31 bits `v` (one leading-zero
    /// count over the 64-bit value; exact when it has at most 31
    /// significant bits), multiplied once (`v·m`, 32 × 32 → 64 bits) and
    /// shifted right with rounding; when the quotient is below 2^31, only
    /// the high word of the product takes part (the usual case in the
    /// rasterizer).
    #[inline]
    pub fn mul_shift(&self, num: i64, s: u32) -> i64 {
        if num == 0 {
            return 0;
        }
        let neg = (num < 0) != self.negative;
        let mag = num.unsigned_abs();
        let (hi, lo) = ((mag >> 32) as u32, mag as u32);
        // top: mag shifted left by z leading zeros (its bit 31 set).
        let (top, z) = if hi != 0 {
            let c = clz32(hi);
            ((hi << c) | ((lo >> 1) >> (31 - c)), c)
        } else {
            let c = clz32(lo);
            (lo << c, 32 + c)
        };
        let v = top >> 1; // top 31 bits: mag ≈ v · 2^(33 - z)
        let p = wmul_u32(v, self.m); // < 2^63
                                     // result = p · 2^(33 - z + s - k) = p >> sh, rounded half up
        let sh = (self.k + z) as i32 - 33 - s as i32;
        let r: u64 = if sh >= 33 {
            // (p >> (sh - 1)) from the high word only.
            let e = (sh - 33) as u32;
            let h = if e >= 32 { 0 } else { (p >> 32) as u32 >> e };
            ((h >> 1) + (h & 1)) as u64
        } else if sh >= 1 {
            let h = shr64(p, (sh - 1) as u32);
            (h >> 1) + (h & 1)
        } else {
            let up = (-sh) as u32;
            if up >= 63 || clz64(p) <= up {
                i64::MAX as u64
            } else {
                shl64(p, up)
            }
        };
        let r = r.min(i64::MAX as u64) as i64;
        if neg {
            -r
        } else {
            r
        }
    }
}

impl Recip {
    /// [`Recip::mul_shift`] of a numerator within an `i32`: the same value,
    /// with one 32 × 32 → 64-bit product and no normalisation.
    ///
    /// Why the same: a magnitude `n <= 2^31` loses no bit when
    /// [`Recip::mul_shift`] normalises it to 31 bits (`v = n·2^(c-1)` for
    /// `c >= 1` leading zeros; `n = 2^31` has a zero bit 0), so its
    /// rounded `p >> sh` equals `round(n·m / 2^(k - s))`, which for
    /// `e = k - s - 33` in `0..32` is `(h >> 1) + (h & 1)` with `h =
    /// ⌊n·m / 2^32⌋ >> e` (the high word alone holds every bit down to
    /// the rounding bit). Other shifts (areas below about `2^(s+1)` or
    /// beyond `2^(s+32)`) take [`Recip::mul_shift`]. Tested equal on
    /// random and extreme values.
    #[inline(always)]
    pub fn mul_shift_i32(&self, num: i32, s: u32) -> i64 {
        let e = self.k.wrapping_sub(s).wrapping_sub(33);
        if e >= 32 {
            return self.mul_shift(num as i64, s);
        }
        let h = (wmul_u32(num.unsigned_abs(), self.m) >> 32) as u32 >> e;
        // h < 2^31 (n·m < 2^63): no carry.
        let r = ((h >> 1) + (h & 1)) as i64;
        if (num < 0) != self.negative {
            -r
        } else {
            r
        }
    }
}

/// The reciprocal of a doubled triangle area for the gradients of `i32`
/// values: `1/a ≈ m · 2^-e`, `|m|` in `[2^30, 2^31)` with the sign of `a`.
///
/// A gradient is then one 32 × 32 → 64-bit product and a rounding shift
/// ([`InvArea::quot`]): `⌊n_t · m / 2^(e - s - t) + ½⌋`, where `n_t` keeps
/// the top 31 bits of the numerator (`t = 0` whenever it fits
/// an `i32`, the usual case). The same integer function on every target
/// (the reciprocal from `recip63`, exact everywhere).
///
/// Error: `|a|` is truncated to 32 significant bits (relative < 2^-31),
/// `m` is within 1 of `2^62 / norm` (< 2^-30), `n_t` (`|n| / 2^t`
/// truncated, with the sign of `n`) loses less than one of its units
/// (< 2^-30 relative, only when `t > 0`) and the rounding half a unit:
/// `|quot - n·2^s/a| <= ½ + |n·2^s/a| · 2^-28`. Tested
/// against exact quotients on random and extreme values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct InvArea {
    m: i32,
    e: u32,
}

impl InvArea {
    /// The reciprocal of `a` (`a != 0`; zero is taken as 1, and the
    /// rasterizer never asks for it).
    ///
    /// Magnitudes below `2^16` (nearly every triangle of a small display)
    /// take `InvArea::new_short`, the others `recip63`: the same value.
    pub fn new(a: i64) -> Self {
        let mag = a.unsigned_abs();
        if (1..1 << 16).contains(&mag) {
            return Self::new_short(mag as u32, a < 0);
        }
        Self::new_long(a)
    }

    /// [`InvArea::new`] of an `i32`: the short path inlined (no 64-bit
    /// magnitude on the way), the others out of line.
    #[inline(always)]
    pub(crate) fn new_i32(a: i32) -> Self {
        let mag = a.unsigned_abs();
        if (1..1 << 16).contains(&mag) {
            Self::new_short(mag, a < 0)
        } else {
            Self::new(a as i64)
        }
    }

    /// [`InvArea::new`] through [`recip63`] for any magnitude.
    fn new_long(a: i64) -> Self {
        let mag = a.unsigned_abs().max(1);
        let c = clz64(mag); // 2^(63-c) <= mag < 2^(64-c)
        let norm = if c >= 32 {
            shl64(mag, c - 32)
        } else {
            shr64(mag, 32 - c)
        } as u32; // in [2^31, 2^32)
                  // round(2^63 / norm) in (2^31, 2^32], halved: within 1 of 2^62/norm.
        let m = ((recip63(norm) >> 1) as u32).min(i32::MAX as u32) as i32;
        // 1/|a| ≈ 1/(norm · 2^(32-c)) ≈ m · 2^-(62 + 32 - c)
        Self {
            m: if a < 0 { -m } else { m },
            e: 94 - c,
        }
    }

    /// `n · 2^s / a`, rounded, within the error stated on [`InvArea`]
    /// (saturating at `i64` bounds for quotients beyond them).
    #[inline(always)]
    pub fn quot(&self, n: i64, s: u32) -> i64 {
        let (nt, t) = match i32::try_from(n) {
            Ok(v) => (v, 0),
            Err(_) => {
                // 32 to 64 significant bits: keep the top 31 (truncated
                // toward zero).
                let t = 33 - clz64(n.unsigned_abs());
                let m = shr64(n.unsigned_abs(), t) as i32;
                (if n < 0 { -m } else { m }, t)
            }
        };
        // |p| < 2^31 · 2^31.
        let p = wmul(nt, self.m);
        let sh = self.e as i32 - s as i32 - t as i32;
        if (33..64).contains(&sh) {
            // The usual case, from the high word alone: rounding half up
            // commutes with dropping the low word (whole units of 2^32
            // are added). |h| < 2^30, the half unit at most 2^30.
            let h = (p >> 32) as i32;
            ((h + (1 << (sh - 33))) >> (sh - 32)) as i64
        } else if sh >= 64 {
            // |p| < 2^62: below half a unit.
            0
        } else if sh >= 1 {
            // |p| + 2^(sh-1) < 2^63.
            (p + (1 << (sh - 1))) >> sh
        } else {
            let up = (-sh) as u32;
            if up >= 62 {
                if p < 0 {
                    i64::MIN
                } else if p > 0 {
                    i64::MAX
                } else {
                    0
                }
            } else {
                p.saturating_mul(1 << up)
            }
        }
    }
}

impl InvArea {
    /// [`InvArea::new`] for a magnitude `mag` in `1..2^16` (and the sign
    /// `negative`) without a division or a 64-bit product: about 55
    /// instructions on ARMv6-M, where [`recip63`] takes about 250.
    ///
    /// Why the same value: with `k` the leading zeros of `mag` in 32 bits
    /// (`16..=31`), `new` takes `round(2^63 / x)` (half up) for `x =
    /// mag·2^k`, whose low 16 bits are zero, and halves it: with the
    /// 16-bit `d = x / 2^16` in `[2^15, 2^16)` that is `m = ⌊(2^48 + d) /
    /// (4d)⌋ = ⌊2^46/d + ¼⌋` (nested floors), capped at `i32::MAX` (only
    /// `d = 2^15` reaches `2^31`). Found in two base-2^15 digits from
    /// any `A`, `B` with `A·d + B = 2^31`: `m = A·2^15 + ⌊(B·2^15 + ⌊d/4⌋)
    /// / d⌋` (an integer plus a floor; `⌊d/4⌋` for `d/4` since `B·2^15`
    /// is an integer). `A` ≈ `2^31/d` from [`RECIP_SEED256`] (the top
    /// eight bits after the leading one, midpoints; `e = 2^31 - s0·d`
    /// within `±2^22`, so `s0·(e >> 7)` is an `i32`) and one Newton step
    /// biased by one, `s0 + 1 + ⌊s0·(e >> 7) / 2^24⌋`, within `-0.21` and
    /// `+0.999` of `2^31/d` (the step's own error below `¼`, its floor
    /// below 1; checked for every `d`), so its remainder `B = 2^31 - A·d`
    /// (32-bit arithmetic, wrapping) lies in `(-d, d)`; the low digit `L
    /// = ⌊(B·A + 2^14) / 2^16⌋` is `⌊B·2^15/d + ¼⌋` or one below it
    /// (`2^31/d = A + B/d`, so `B·2^15/d = (B·A + B²/d) / 2^16` and `0 <=
    /// B²/d < 2^16`; `|B·A| <= 2 145 124 080 < 2^31 - 2^14`, checked),
    /// corrected by the exact remainder `B·2^15 + ⌊d/4⌋ - L·d` in `[0,
    /// 2d)` (formed modulo 2^32) against `d`. The divisor normalised by a
    /// product (`NORM8`, no masked shift). Tested equal to `new`'s
    /// general path for every magnitude below `2^16`, both signs (which
    /// checks each bound above for every `d`).
    ///
    /// It replaced a 128-entry seed, the exact first digit `⌊2^31/d⌋` by
    /// correcting loops (within 3 after the Newton step), the low digit
    /// `⌊B·2^16/d⌋` by another loop (up to 2 steps) and a rounding test
    /// (about 93 instructions a triangle in the bunny's set-up, the
    /// compiler unrolling the loops by four with their multiples
    /// precomputed, now about 60): exact QEMU counts, bunny-gouraud raster
    /// thumbv6m 2 508 220 -> 2 478 334 (bunny-flat 2 190 189 ->
    /// 2 138 526) with a rounded Newton step (`+ 2^22` before `>> 23`)
    /// and the leading zeros' masked shift; the step biased by one and
    /// the product normalisation 2 473 748 -> 2 470 899 (bunny-flat
    /// 2 138 526 -> 2 130 680). Measured before on the loop form and not
    /// kept: its loops replaced by the steps they take at most (2 556 014
    /// -> 2 564 235, branch-free 2 565 440; later 2 520 390 -> 2 542 829).
    #[inline(always)]
    fn new_short(mag: u32, negative: bool) -> Self {
        // `t = mag·2^8` below 2^8, its top byte `i` (in 1..2^8 for `mag`
        // in 1..2^16) with `c` leading zeros: `k = 16 + c (+ 8)` and `d =
        // t·2^c` in [2^15, 2^16) (a product: no masked shift).
        let (t, k0) = if mag >= 1 << 8 {
            (mag, 16)
        } else {
            (mag << 8, 24)
        };
        let i = (t >> 8) as u8 as usize;
        let c = u32::from(CLZ8[i]);
        let k = k0 + c;
        let d = t.wrapping_mul(u32::from(NORM8[i]));
        let s0 = i32::from(RECIP_SEED256[((d >> 7) & 255) as usize]);
        // |e| <= 2^22: |s0·(e >> 7)| < 2^16·2^15.
        let e = (1u32 << 31).wrapping_sub((s0 as u32).wrapping_mul(d)) as i32;
        let a = s0
            .wrapping_add(1)
            .wrapping_add(s0.wrapping_mul(e >> 7) >> 24);
        // In (-d, d).
        let b = (1u32 << 31).wrapping_sub((a as u32).wrapping_mul(d)) as i32;
        let lo = b.wrapping_mul(a).wrapping_add(1 << 14) >> 16;
        // The remainder, in [0, 2d).
        let r = ((b << 15) as u32)
            .wrapping_add(d >> 2)
            .wrapping_sub((lo as u32).wrapping_mul(d));
        let m = ((a as u32) << 15)
            .wrapping_add(lo as u32)
            .wrapping_add(u32::from(r >= d));
        // 2^31 (d = 2^15) capped at i32::MAX.
        let m = m.wrapping_sub(m >> 31) as i32;
        Self {
            m: if negative { m.wrapping_neg() } else { m },
            e: 62 - k,
        }
    }

    /// [`InvArea::new`] for `0 < |a| < 2^16` (doubled areas below 256
    /// pixels² at 4 subpixel bits: nearly every triangle of a small
    /// display), by two 32-bit divisions (ARMv7-M's `UDIV`; the hosts'
    /// divider): the very value. `None` for other areas.
    ///
    /// Why the same: with `c` the leading zeros of `|a|` in 64 bits (`c >=
    /// 48`) and `k = c - 32`, `new` takes the reciprocal of `x = |a|·2^k`,
    /// `⌊(2^63 + ⌊x/2⌋) / x⌋`, which is `⌊(2^(63-k) + ⌊|a|/2⌋) / |a|⌋`
    /// (dividing numerator and divisor by `2^k` first: `⌊x/2⌋ =
    /// |a|·2^(k-1)` for `k >= 1`). That dividend is below `2^48`, the
    /// divisor below `2^16`: long division in two 16-bit digits, each a
    /// 32-bit division (the first remainder, below `2^16`, shifted by 16
    /// still fits). Tested equal to [`InvArea::new`] for every such `a`.
    /// The quotient halved in 32 bits: `q_hi·2^15 + (q_lo >> 1)` (exact:
    /// `q_hi <= 2^16`, `q_lo < 2^16`, the sum below `2^31 + 2^15`), four
    /// instructions less than the 64-bit sum; it first cost the
    /// bunny-gouraud raster on thumbv7em 1 833 849 -> 1 866 111 (the
    /// registers of the inlined set-up around it), and with the kernel's
    /// set-up as it is now saves: 1 651 052 -> 1 646 369 (bunny-flat
    /// 1 506 174 -> 1 501 491).
    #[inline(always)]
    pub(crate) fn new_small(a: i32) -> Option<Self> {
        let mag = a.unsigned_abs();
        if mag == 0 || mag >= 1 << 16 {
            return None;
        }
        let c = 32 + clz32(mag);
        let k = c - 32;
        // 2^(63-k) + ⌊mag/2⌋ = hi·2^16 + lo, hi = 2^(47-k) (+ carry-free:
        // ⌊mag/2⌋ < 2^15 <= 2^(63-k-16)·... held apart below).
        let top = 1u32 << (47 - k); // 2^(63-k) >> 16, k in 16..=31
        let lo = mag >> 1; // below 2^15: the low digit alone
        let q_hi = top / mag;
        let r_hi = top - q_hi * mag;
        let num_lo = (r_hi << 16) | lo;
        let q_lo = num_lo / mag;
        let m = ((q_hi << 15) + (q_lo >> 1)).min(i32::MAX as u32) as i32;
        Some(Self {
            m: if a < 0 { -m } else { m },
            e: 94 - c,
        })
    }

    /// [`InvArea::new`] of an `i32` by the target's cheapest exact path:
    /// with a hardware divider (ARMv7-M, the hosts) [`InvArea::new_small`]
    /// (two 32-bit divisions) where it applies; on ARMv6-M, where those
    /// would be library calls, the table and Newton steps of
    /// `InvArea::new_short`; the others through `InvArea::new`. The same
    /// value on every path (each tested equal to `new`).
    #[inline(always)]
    pub(crate) fn new_fast(a: i32) -> Self {
        let small = if NO_DIVIDE { None } else { Self::new_small(a) };
        match small {
            Some(inv) => inv,
            None => Self::new_i32(a),
        }
    }

    /// For the fast path (`raster::fast`): `Some(k)` when [`InvArea::quot`]
    /// of a numerator within an `i32` takes its usual high-word case for
    /// `s` subpixel bits (`sh = e - s` in `33..64`, then `k = sh - 33`):
    /// decided once per triangle.
    #[inline(always)]
    pub(crate) fn high_shift(&self, s: u32) -> Option<u32> {
        let sh = self.e.wrapping_sub(s);
        if (33..64).contains(&sh) {
            Some(sh - 33)
        } else {
            None
        }
    }

    /// [`InvArea::quot`]`(n · 2^sh, s)` for `k` from
    /// [`InvArea::high_shift`]`(s)` and `sh <= 14`: the numerator without
    /// its `sh` low zero bits (of packed depths or levels, whose
    /// differences are multiples of `2^14` or `2^8`), so that it fits an
    /// `i32` where `n · 2^sh` need not. `None` when `n · 2^u` does not fit
    /// an `i32` for `u = sh - k` (none for `k >= sh`; the quotient then
    /// reaches `2^29`).
    ///
    /// `quot` rounds `n·2^sh·m / 2^(k + 33)` half up in every case (in its
    /// high-word case and in its normalised one alike, the bits it drops
    /// being zeros), that is `n·m / 2^q` for `q = k + 33 - sh`, which is
    /// [`InvArea::quot_high`]`(n · 2^u, k')` for `u = max(sh - k, 0)`, `k'
    /// = max(k - sh, 0)` (`k' - u = k - sh`): one product, in 32 bits, the
    /// very value of `quot`, below `2^30` in magnitude.
    #[inline(always)]
    pub(crate) fn quot_scaled(&self, n: i32, k: u32, sh: u32) -> Option<i32> {
        let (u, kk) = (sh.saturating_sub(k) & 31, k.saturating_sub(sh));
        let nu = n << u;
        if nu >> u != n {
            return None;
        }
        Some(self.quot_high(nu, kk))
    }

    /// [`InvArea::quot_scaled`]`(n, k, sh)` for `k <= sh`, given `u = sh -
    /// k` (below 32): the same value, `quot_high(n · 2^u, 0)`, without
    /// selecting the shifts at run time; `None` where `n · 2^u` does not
    /// fit an `i32` (as there). Tested equal to `quot_scaled`.
    /// Returned as the quotient and a flag (`false` for `None`, the
    /// quotient then meaning nothing), without selecting a value for
    /// `None`: so the product stays one high-half multiply (`SMMUL` on
    /// ARMv7-M; with `Option`'s selection the compiler took `UMULL` and two
    /// `MLA` for the grey level's: bunny-gouraud raster thumbv7em
    /// 1 719 996 -> 1 696 696).
    #[inline(always)]
    pub(crate) fn quot_up(&self, n: i32, u: u32) -> (i32, bool) {
        let u = u & 31;
        let nu = n << u;
        // `quot_high(nu, 0)`.
        ((mulhi(nu, self.m) + 1) >> 1, nu >> u == n)
    }

    /// [`InvArea::quot_up`]`(n, u)` for `n` in `-2^16..2^16` and `u <=
    /// 15` (then `n · 2^u` fits an `i32` and the flag of `quot_up`
    /// holds): the very quotient from two 32-bit products instead of the
    /// four of `mulhi` (ARMv6-M). With `n = 2^16·nh + nl` (`nh` in `{-1,
    /// 0}`, `nl` in `0..2^16`) and `m = 2^16·mh + ml` (`|mh| <= 2^15`, `ml`
    /// in `0..2^16`): `X = ⌊n·m / 2^16⌋ = nh·m + nl·mh + ⌊nl·ml / 2^16⌋`
    /// (`nh·m` is `-m` or 0, no product; `|nl·mh| < 2^31`; `|X| < 2^31`,
    /// the sum formed wrapping), and `quot_high(n·2^u, 0) = ⌊(⌊n·m /
    /// 2^(32-u)⌋ + 1) / 2⌋ = ((X >> p) + 1) >> 1` for `p = 16 - u` (nested
    /// floors). Exact, no error of its own; tested equal to `quot_up`.
    /// Outside its bounds the value means nothing (no panic).
    #[inline(always)]
    pub(crate) fn quot_up_short(&self, n: i32, u: u32) -> i32 {
        let (mh, ml) = (self.m >> 16, (self.m & 0xffff) as u32);
        let (nh, nl) = (n >> 16, n & 0xffff);
        let x = (self.m.wrapping_neg() & nh)
            .wrapping_add(nl.wrapping_mul(mh))
            .wrapping_add(((nl as u32).wrapping_mul(ml) >> 16) as i32);
        let p = 16u32.wrapping_sub(u) & 31;
        (x.wrapping_shr(p) + 1) >> 1
    }

    /// [`InvArea::quot`]`(n, s)` for `n` within an `i32` and `k` from
    /// [`InvArea::high_shift`]`(s)`: the very value, with one product and
    /// no normalisation (`t = 0`; `|h| < 2^30` and `k <= 30`, so nothing
    /// wraps and the result fits an `i32`).
    #[inline(always)]
    pub(crate) fn quot_high(&self, n: i32, k: u32) -> i32 {
        // ⌊n·m / 2^32⌋ (ARMv6-M: four `MULS` in 32 bits, no 64-bit sum).
        let h = mulhi(n, self.m);
        (h + (1 << k)) >> (k + 1)
    }
}

/// Seeds of the reciprocal: `round(2^23 / (128 + i + ½))` for the top
/// eight bits `128 + i` of a normalised divisor (relative error < 2^-8).
static RECIP_SEED: [u16; 128] = {
    let mut t = [0u16; 128];
    let mut i = 0;
    while i < 128 {
        let d = 2 * (128 + i as u32) + 1;
        t[i] = (2 * (1u32 << 24) / d).div_ceil(2) as u16;
        i += 1;
    }
    t
};

/// `2^c` for the leading zeros `c` of a byte `i` in `1..2^8` (0 for 0):
/// `i·2^c` has its top bit at 7 ([`InvArea::new_short`]'s
/// normalisation, a product instead of a masked shift). 256 bytes.
static NORM8: [u8; 256] = {
    let mut t = [0u8; 256];
    let mut i = 1;
    while i < 256 {
        t[i] = 1 << (i as u8).leading_zeros();
        i += 1;
    }
    t
};

/// Seeds of [`InvArea::new_short`]: `round(2^31 / (2^15 + 128·i + 64))`
/// for the top eight bits `i` after the leading one of a divisor `d` in
/// `[2^15, 2^16)` (the interval's midpoint; relative error below `2^-9`,
/// `|2^31 - s0·d| <= 2^22`). 512 bytes of flash.
static RECIP_SEED256: [u16; 256] = {
    let mut t = [0u16; 256];
    let mut i = 0;
    while i < 256 {
        let mid = (1u32 << 15) + 128 * i as u32 + 64;
        t[i] = (u32::MAX / mid).div_ceil(2) as u16;
        i += 1;
    }
    t
};

/// `floor((2^63 + floor(x/2)) / x)` (that is `2^63 / x` rounded half up) for
/// `x` in `[2^31, 2^32)`, without a division.
///
/// A seed of 8 bits from [`RECIP_SEED`], one Newton step in 32 bits
/// (`r1 ≈ 2^47 / x`, relative error below 2^-13.5), one third-order step
/// `q = R·(1 + ε + ε²)` with `R = r1·2^16` and `ε = 1 - x·R/2^63`, then the
/// exact remainder `2^63 + x/2 - q·x` moves `q` to the quotient. Checked
/// for every `x` in the range: at most two correction steps, and the
/// intermediate bounds noted below hold (`|E >> 19| < 6·10^8`).
///
/// On ARMv7-M (a 32-bit hardware divider) the same quotient by two 32-bit
/// divisions instead ([`recip63_udiv`]).
fn recip63(x: u32) -> u64 {
    if NO_DIVIDE {
        recip63_newton(x)
    } else if cfg!(target_arch = "arm") {
        recip63_udiv(x)
    } else {
        // One instruction on the host's 64-bit divider.
        ((1u64 << 63) + (x / 2) as u64) / (x as u64).max(1 << 31)
    }
}

/// [`recip63`] by long division in base 2^16 with two 32-bit divisions
/// (Knuth's algorithm D as in Hacker's Delight's `divlu`): the dividend
/// `2^63 + ⌊x/2⌋` is `2^31·2^32 + ⌊x/2⌋` and the divisor `x` is already
/// normalised (bit 31 set, `x > 2^31`), so the quotient fits 32 bits and
/// each digit `q1`, `q0` is estimated from the divisor's top half `vn1`
/// (`>= 2^15`) and corrected at most twice. Bounds: `rhat < vn1 < 2^16`
/// whenever `rhat·2^16 + un` is formed, and a digit is multiplied by
/// `vn0 < 2^16` only once below 2^16: every intermediate fits a `u32`.
/// Exact: the very value of the 64-bit division, tested against it.
fn recip63_udiv(x: u32) -> u64 {
    if x <= 1 << 31 {
        return 1 << 32;
    }
    const B: u32 = 1 << 16;
    let (vn1, vn0) = ((x >> 16).max(1), x & 0xffff);
    let u0 = x / 2;
    let (un1, un0) = (u0 >> 16, u0 & 0xffff);
    // First digit of (2^31·2^16 + un1) / x.
    let mut q1 = (1u32 << 31) / vn1;
    let mut rhat = (1u32 << 31) - q1 * vn1;
    while q1 >= B || q1 * vn0 > (rhat << 16) + un1 {
        q1 -= 1;
        rhat += vn1;
        if rhat >= B {
            break;
        }
    }
    // The remainder (below x) modulo 2^32: 2^31·2^16 vanishes.
    let un21 = un1.wrapping_sub(q1.wrapping_mul(x));
    let mut q0 = un21 / vn1;
    let mut rhat = un21 - q0 * vn1;
    while q0 >= B || q0 * vn0 > (rhat << 16) + un0 {
        q0 -= 1;
        rhat += vn1;
        if rhat >= B {
            break;
        }
    }
    ((q1 as u64) << 16) + q0 as u64
}

/// [`recip63`] without a division (the Cortex-M0 has no divider, the M4 only
/// a 32-bit one: a `u64` division is a library call of hundreds of
/// instructions on both).
fn recip63_newton(x: u32) -> u64 {
    if x <= 1 << 31 {
        return 1 << 32;
    }
    let xh = x >> 16;
    let r0 = RECIP_SEED[((x >> 24) & 127) as usize] as u32;
    // xh·r0 is within 2^31·(1 ± 2^-8): e0 within ±2^23, r0·(e0 >> 9) < 2^30.
    let e0 = (1u32 << 31).wrapping_sub(xh.wrapping_mul(r0)) as i32;
    let r1 = (r0 as i32).wrapping_add((r0 as i32).wrapping_mul(e0 >> 9) >> 22) as u32;
    // E = 2^63 - x·r1·2^16, |E| < 2^49.2, so E >> 19 fits an i32.
    let e19 = if NO_LONG_MUL {
        e19_halves(wmul_u32(x, r1))
    } else {
        e19_wide(wmul_u32(x, r1))
    };
    let c = wmul(r1 as i32, e19) >> 28; // R·ε, |c| < 2^20
    let c2 = wmul(c as i32, e19) >> 44; // R·ε²
    let q = (((r1 as i64) << 16) + c + c2).clamp(1 << 31, u32::MAX as i64) as u32;
    let n = (1u64 << 63) + (x / 2) as u64;
    // |q - quotient| <= 2: the remainder is small and signed.
    let mut rem = n.wrapping_sub(wmul_u32(q, x)) as i64;
    let mut q = q as u64;
    while rem < 0 {
        q -= 1;
        rem += x as i64;
    }
    while rem >= x as i64 {
        q += 1;
        rem -= x as i64;
    }
    q
}

/// `((2^63 - p·2^16) as i64 >> 19) as i32` (bits 19..50 of the wrapping
/// difference), as written.
#[inline(always)]
fn e19_wide(p: u64) -> i32 {
    ((1u64 << 63).wrapping_sub(p << 16) as i64 >> 19) as i32
}

/// [`e19_wide`] on 32-bit halves, the same bits: LLVM turns the 64-bit
/// form into a call of `__aeabi_lmul` by a constant on ARMv6-M.
#[inline(always)]
fn e19_halves(p: u64) -> i32 {
    let (ph, pl) = ((p >> 32) as u32, p as u32);
    // v = p << 16 (mod 2^64); e = 2^63 - v (mod 2^64).
    let (vh, vl) = ((ph << 16) | (pl >> 16), pl << 16);
    let el = 0u32.wrapping_sub(vl);
    let eh = (1u32 << 31).wrapping_sub(vh).wrapping_sub((vl != 0) as u32);
    ((el >> 19) | (eh << 13)) as i32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recip_products_within_stated_error() {
        let areas = [
            1i64,
            2,
            3,
            7,
            255,
            4096,
            99_991,
            1 << 31,
            (1 << 45) - 3,
            -5,
            -123_456_789,
        ];
        let nums = [
            1i64,
            -1,
            3,
            1000,
            -77_777,
            1 << 40,
            (1 << 54) - 1,
            -(1 << 53) + 17,
        ];
        for &a in &areas {
            let r = Recip::new(a);
            for &n in &nums {
                for s in [0u32, 4, 8] {
                    let exact = (n as f64) * (1u64 << s) as f64 / a as f64;
                    if exact.abs() > 9.0e18 {
                        continue;
                    }
                    let got = r.mul_shift(n, s) as f64;
                    let bound = 0.5 + exact.abs() * (1.0 / (1u64 << 30) as f64) + 1e-6;
                    assert!(
                        (got - exact).abs() <= bound,
                        "a={a} n={n} s={s}: got {got}, exact {exact}"
                    );
                }
            }
        }
    }

    /// The previous `mul_shift` (64-bit shifts, `m` up to 2^32), kept as
    /// the reference the lean version must equal bit for bit.
    fn mul_shift_reference(a: i64, num: i64, s: u32) -> i64 {
        if num == 0 {
            return 0;
        }
        let negative = a < 0;
        let amag = a.unsigned_abs().max(1);
        let n = 63 - amag.leading_zeros();
        let norm = if n >= 31 {
            amag >> (n - 31)
        } else {
            amag << (31 - n)
        };
        let m = ((1u64 << 63) + norm / 2) / norm;
        let k = 32 + n;
        let neg = (num < 0) != negative;
        let mag = num.unsigned_abs();
        let bits = 64 - mag.leading_zeros();
        let t = bits.saturating_sub(31);
        let v = (mag >> t) as u32;
        let p = if m > u32::MAX as u64 {
            (v as u64) << 32
        } else {
            v as u64 * m
        };
        let up = t as i32 + s as i32 - k as i32;
        let r: u64 = if up >= 0 {
            if up >= 63 || p.leading_zeros() <= up as u32 {
                i64::MAX as u64
            } else {
                p << up
            }
        } else {
            let sh = (-up) as u32;
            if sh >= 64 {
                0
            } else {
                let h = p >> (sh - 1);
                (h >> 1) + (h & 1)
            }
        };
        let r = r.min(i64::MAX as u64) as i64;
        if neg {
            -r
        } else {
            r
        }
    }

    #[test]
    fn lean_mul_shift_equals_the_reference() {
        let mut g = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            g ^= g << 13;
            g ^= g >> 7;
            g ^= g << 17;
            g
        };
        let specials = [
            1i64,
            -1,
            2,
            3,
            1 << 20,
            -(1 << 31),
            1 << 45,
            (1 << 45) - 1,
            i64::MAX,
            i64::MIN + 1,
        ];
        for i in 0..200_000u32 {
            let (x, y) = (next(), next());
            let a = if i % 50 == 0 {
                specials[(x % specials.len() as u64) as usize]
            } else {
                ((x as i64) >> (x % 63)).max(i64::MIN + 1)
            };
            let num = if i % 37 == 0 {
                specials[(y % specials.len() as u64) as usize]
            } else {
                ((y as i64) >> (y % 64)).max(i64::MIN + 1)
            };
            if a == 0 {
                continue;
            }
            let r = Recip::new(a);
            for s in [0u32, 1, 4, 8] {
                assert_eq!(
                    r.mul_shift(num, s),
                    mul_shift_reference(a, num, s),
                    "a={a} num={num} s={s}"
                );
            }
        }
    }

    #[test]
    fn e19_on_halves_equals_the_wide_form() {
        let mut g = 0x9e37_79b9_7f4a_7c15u64;
        for i in 0..100_000u32 {
            g ^= g << 13;
            g ^= g >> 7;
            g ^= g << 17;
            let p = g >> (i % 64);
            assert_eq!(e19_halves(p), e19_wide(p), "{p:#x}");
        }
        for p in [
            0u64,
            1,
            0xffff,
            0x1_0000,
            u64::MAX,
            1 << 47,
            (1 << 48) - 1,
            1 << 63,
        ] {
            assert_eq!(e19_halves(p), e19_wide(p), "{p:#x}");
        }
    }

    #[test]
    fn recip63_is_the_rounded_quotient() {
        // Every x was checked once (2^31 values, a few seconds); here a
        // stride that visits every seed interval, plus the ends.
        let check = |x: u32| {
            let want = ((1u64 << 63) + (x / 2) as u64) / x as u64;
            assert_eq!(recip63(x), want, "x={x}");
            assert_eq!(recip63_newton(x), want, "x={x}");
            assert_eq!(recip63_udiv(x), want, "x={x}");
        };
        for x in [
            1u32 << 31,
            (1 << 31) + 1,
            (1 << 31) + 2,
            u32::MAX,
            u32::MAX - 1,
            0xc000_0000,
            0xbfff_ffff,
        ] {
            check(x);
        }
        let mut x = 1u32 << 31;
        while let Some(n) = x.checked_add(997) {
            check(x);
            x = n;
        }
        // Every top half of the divisor (the digit estimates of
        // recip63_udiv) with the extreme low halves.
        for vn1 in 0x8000u32..=0xffff {
            for vn0 in [0u32, 1, 2, 0x7fff, 0x8000, 0xfffe, 0xffff] {
                let x = (vn1 << 16) | vn0;
                if x > 1 << 31 {
                    check(x);
                }
            }
        }
        // Every seed boundary and its neighbours.
        for top in 128u32..256 {
            for d in [0u32, 1, 2, 0xffff, 0x10000] {
                check((top << 24) | d);
                check(((top << 24) | 0x00ff_ffff) - d);
            }
        }
    }

    /// `n·2^s/a` (from the exact product in i128).
    fn exact_quot(n: i64, s: u32, a: i64) -> f64 {
        ((n as i128) << s) as f64 / a as f64
    }

    #[test]
    fn inv_area_quotients_within_stated_error() {
        let mut g = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            g ^= g << 13;
            g ^= g >> 7;
            g ^= g << 17;
            g
        };
        let mut areas = [0i64; 2015];
        let fixed = [1i64, -1, 2, 3, 7, 255, 4096, 99_991, 1 << 31, (1 << 31) - 1];
        let fixed2 = [
            (1 << 32) + 1,
            (1 << 37) - 1,
            -(1 << 37) + 3,
            -5,
            -123_456_789,
        ];
        for (i, a) in areas.iter_mut().enumerate() {
            let r = next();
            let rand = ((r >> 1) as i64 >> (26 + r % 37)).max(1) * if r & 1 == 0 { 1 } else { -1 };
            *a = *fixed
                .get(i)
                .or(fixed2.get(i.wrapping_sub(10)))
                .unwrap_or(&rand);
        }
        let mut nums = [0i64; 213];
        let fixed = [
            0i64,
            1,
            -1,
            3,
            1000,
            -77_777,
            i32::MAX as i64,
            i32::MIN as i64,
        ];
        let fixed2 = [
            1 << 31,
            -(1 << 31) - 1,
            1 << 40,
            (1 << 54) - 1,
            -(1 << 53) + 17,
        ];
        for (i, n) in nums.iter_mut().enumerate() {
            let r = next();
            let rand = (r as i64) >> (10 + r % 50);
            *n = *fixed
                .get(i)
                .or(fixed2.get(i.wrapping_sub(8)))
                .unwrap_or(&rand);
        }
        for &a in &areas {
            let r = InvArea::new(a);
            for &n in &nums {
                for s in [0u32, 4, 8] {
                    let exact = exact_quot(n, s, a);
                    if exact.abs() > 4.0e18 {
                        continue;
                    }
                    let got = r.quot(n, s) as f64;
                    let rel = exact.abs() * (1.0 / (1u64 << 28) as f64);
                    assert!(
                        (got - exact).abs() <= 0.5 + rel,
                        "a={a} n={n} s={s}: got {got}, exact {exact}"
                    );
                }
            }
        }
    }

    #[test]
    fn short_reciprocal_equals_the_long_one() {
        // Every magnitude of the short path, both signs.
        for mag in 1i64..1 << 16 {
            for a in [mag, -mag] {
                assert_eq!(InvArea::new(a), InvArea::new_long(a), "a={a}");
            }
        }
        // Above it `new` is the long path itself; a few values around the
        // border.
        for a in [(1i64 << 16) - 1, 1 << 16, (1 << 16) + 1, -(1 << 16) + 1] {
            assert_eq!(InvArea::new(a), InvArea::new_long(a), "a={a}");
        }
        for a in [1, -1, 3, 65535, -65535, 65536, -65536, i32::MAX, i32::MIN] {
            assert_eq!(InvArea::new_i32(a), InvArea::new_long(a as i64), "a={a}");
            assert_eq!(InvArea::new_fast(a), InvArea::new_long(a as i64), "a={a}");
        }
        // The target's constructor (the hosts: the two divisions below
        // 2^16) on every magnitude up to 2^17, both signs.
        for mag in 1i32..1 << 17 {
            for a in [mag, -mag] {
                assert_eq!(InvArea::new_fast(a), InvArea::new_long(a as i64), "a={a}");
            }
        }
        assert_eq!(
            InvArea::new(1),
            InvArea {
                m: i32::MAX,
                e: 62 - 31
            }
        );
        // round(2^63 / (3·2^30)) = 2 863 311 531, halved.
        assert_eq!(
            InvArea::new(-3),
            InvArea {
                m: -1_431_655_765,
                e: 62 - 30
            }
        );
    }

    #[test]
    fn mul_shift_i32_equals_mul_shift() {
        let mut g = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            g ^= g << 13;
            g ^= g >> 7;
            g ^= g << 17;
            g
        };
        let nums = [
            0i32,
            1,
            -1,
            2,
            3,
            i32::MAX,
            i32::MIN,
            i32::MIN + 1,
            1 << 30,
            -(1 << 30),
        ];
        let areas = [
            1i64,
            -1,
            2,
            3,
            16,
            17,
            255,
            256,
            257,
            1 << 20,
            (1 << 31) - 1,
            1 << 31,
            1 << 40,
            (1 << 45) - 1,
            -(1 << 45),
        ];
        for &a in &areas {
            let r = Recip::new(a);
            for &n in &nums {
                for s in 1..=8 {
                    assert_eq!(
                        r.mul_shift_i32(n, s),
                        r.mul_shift(n as i64, s),
                        "a={a} n={n} s={s}"
                    );
                }
            }
        }
        for i in 0..200_000u32 {
            let x = next();
            let a = ((x as i64) >> (19 + x % 45)).max(1) * if x & 1 == 0 { 1 } else { -1 };
            let y = next();
            let n = (y as i32) >> (y % 32);
            let s = 1 + i % 8;
            let r = Recip::new(a);
            assert_eq!(
                r.mul_shift_i32(n, s),
                r.mul_shift(n as i64, s),
                "a={a} n={n} s={s}"
            );
        }
    }

    #[test]
    fn recip_exact_on_small_values() {
        // Quotients that are exact small integers come out exact.
        let r = Recip::new(-12);
        assert_eq!(r.mul_shift(24, 4), -32);
        assert_eq!(Recip::new(3).mul_shift(9, 0), 3);
        assert_eq!(Recip::new(1).mul_shift(-(1 << 40), 8), -(1 << 48));
        assert_eq!(Recip::new(0).mul_shift(5, 0), 5);
    }

    /// [`InvArea::quot_up_short`] is [`InvArea::quot_up`] for every
    /// numerator in `-2^16..2^16` and every shift `u <= 15`, on
    /// random and extreme reciprocals.
    #[test]
    fn quot_up_short_equals_quot_up() {
        let mut rng = crate::num::testkit::Rng(0x2545_f491_4f6c_dd1d);
        let mut next = || rng.next() as u32;
        let areas = [
            1,
            -1,
            2,
            3,
            0xffff,
            -0xffff,
            0x8000,
            -0x8000,
            0x7fff,
            i32::MAX,
            -i32::MAX,
        ];
        let nums = [
            0,
            1,
            -1,
            (1 << 15) - 1,
            -(1 << 15) + 1,
            -(1 << 15),
            12345,
            -12345,
        ];
        for i in 0..200_000u32 {
            let a = if i < 2_000 {
                areas[(i as usize) % areas.len()]
            } else {
                let a = ((next() as i32) >> (next() % 32)).max(1);
                if i & 1 == 0 {
                    a
                } else {
                    -a
                }
            };
            let inv = InvArea::new_fast(a);
            let r = next();
            let n = if i % 4 == 0 {
                nums[(r % nums.len() as u32) as usize]
            } else {
                (r as i32) >> (15 + r % 17)
            };
            for u in 0..=15 {
                let (q, ok) = inv.quot_up(n, u);
                assert!(ok, "a={a} n={n} u={u}");
                assert_eq!(inv.quot_up_short(n, u), q, "a={a} n={n} u={u}");
            }
        }
    }

    /// [`InvArea::quot_up`] is [`InvArea::quot_scaled`] wherever `k <= sh`.
    #[test]
    fn quot_up_equals_quot_scaled() {
        let mut g = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            g ^= g << 13;
            g ^= g >> 7;
            g ^= g << 17;
            g as u32
        };
        let ends = [
            0,
            1,
            -1,
            i32::MAX,
            i32::MIN,
            0xffff,
            -0x10000,
            1 << 17,
            -(1 << 17),
        ];
        for i in 0..300_000u32 {
            let a = ((next() as i32) >> (next() % 32)).max(1);
            let inv = InvArea::new_fast(if i & 1 == 0 { a } else { -a });
            let Some(k) = inv.high_shift(4) else {
                continue;
            };
            let r = next();
            let n = match i % 3 {
                0 => ends[(r % ends.len() as u32) as usize],
                1 => (r as i32) >> (r % 32),
                _ => r as i32,
            };
            for sh in [8, 14] {
                if k <= sh {
                    let (q, ok) = inv.quot_up(n, sh - k);
                    assert_eq!(
                        ok.then_some(q),
                        inv.quot_scaled(n, k, sh),
                        "a={a} n={n} k={k} sh={sh}"
                    );
                }
            }
        }
    }
}
