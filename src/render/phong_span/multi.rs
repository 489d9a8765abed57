//! Several directional lights, viewer at infinity: the 32-bit loop of
//! module `one` for each light, `1/|n|` once a pixel.
//!
//! Per span, each light's exact state ([`PhongKernel::one_begin`]); per
//! chunk of [`CHUNK`] pixels, each light's plan ([`PhongKernel::one_plan`],
//! the same proofs and the same 32-bit forward differences as one light
//! alone); when every light's chunk is proven, `1/|n|` once a pixel
//! ([`rsq`]) and then, light after light, the light terms of
//! [`PhongKernel::terms_r`] added to the pixel's channel sums (Q19, as
//! one light's [`Colour`](super::one::Colour) gives them). A chunk that
//! one light cannot prove runs every light per pixel in 64 bits
//! ([`PhongKernel::multi_exact`]). The sums are saturated at [`SAT`] before
//! each light is added (every term is non-negative and every channel at or
//! above `SAT` is level 255), so that eight lights of coefficient 4 stay
//! within `u32`. The colour of each pixel is then the sum of what each
//! light alone adds in the loop of one light, every light's error that
//! loop's (tests: `random_spans_against_f64`, one to four lights).

use super::one::{mul_shr48, rsq, OneSpan, Plan, QM_FRAC, QM_MAX, SHORT_SPAN};
use super::{
    cross, drive, fallback, lin, pack, sq3, unpack, unpack_q19, KLight, Out, PhongKernel, CHUNK,
    MAX_LIGHTS,
};
use crate::num::wide::wmul;
use crate::num::Real;
use crate::target::level_q19;

/// Channel sums (Q19) are saturated at this value (level 255 from
/// `255.5 · 2^19` on) before a light's terms are added: below `2^30 +
/// 2^31` with them (`d, s < 2^14`, `N·L`, the specular factor `<= 2^15 (1
/// + 2^-11)`).
const SAT: u32 = 1 << 30;

/// The exact states of a span's lights (`None` past the last light).
type States = [Option<OneSpan>; MAX_LIGHTS];

impl<R: Real> PhongKernel<'_, R> {
    /// [`PhongKernel::fill`] for two or more directional lights, viewer
    /// at infinity (module docs); `n`, `dn` already flipped for back
    /// faces. Not inlined: the lights' states (up to eight) stay in its
    /// own frame.
    #[inline(never)]
    pub(super) fn fill_multi(&self, n: [i32; 3], dn: [i32; 3], len: u32, mut out: impl Out) -> u32 {
        if len < SHORT_SPAN {
            let mut passed = 0;
            for i in 0..len {
                if out.test(i) {
                    let ni = [0, 1, 2].map(|a| n[a].wrapping_add(dn[a].wrapping_mul(i as i32)));
                    out.write(i, unpack(self.multi_exact(ni, n, dn, i)));
                    passed += 1;
                }
            }
            return passed;
        }
        let mut st: States =
            core::array::from_fn(|j| self.lights.get(j).map(|l| self.one_begin(l, n, dn)));
        drive(
            len,
            |i, k, buf| self.multi_chunk(n, dn, &mut st, i, k, buf),
            unpack_q19,
            &mut out,
        )
    }

    /// The colours (`r | g << 8 | b << 16`) of the `k` pixels from pixel
    /// `i` into `buf` (returns `false`: colours, not light terms), and the
    /// lights' states stepped past them.
    #[inline(never)]
    #[allow(clippy::too_many_arguments, clippy::cast_possible_wrap)]
    fn multi_chunk(
        &self,
        n: [i32; 3],
        dn: [i32; 3],
        st: &mut States,
        i: u32,
        k: u32,
        buf: &mut [u32; CHUNK],
    ) -> bool {
        let mut plans: [Option<Plan>; MAX_LIGHTS] = [None; MAX_LIGHTS];
        let mut exact = false;
        for (p, s) in plans.iter_mut().zip(st.iter_mut()) {
            if let Some(s) = s {
                let plan = if k == CHUNK as u32 {
                    self.one_plan(s, i, CHUNK as u32)
                } else {
                    self.one_plan(s, i, k)
                };
                exact |= matches!(plan, Plan::Exact);
                *p = Some(plan);
            }
        }
        let nn32 = match plans[0] {
            Some(Plan::Spec(nn, ..) | Plan::NoSpec(nn, ..)) if !exact => nn,
            _ => {
                for (j, o) in (i..i + k).zip(buf.iter_mut()) {
                    let nj = [0, 1, 2].map(|a| n[a].wrapping_add(dn[a].wrapping_mul(j as i32)));
                    *o = self.multi_exact(nj, n, dn, j);
                }
                return false;
            }
        };
        let k = (k as usize).min(CHUNK);
        // 2^16/|n| per pixel, the sums from the ambient term.
        let mut rb = [0u32; CHUNK];
        let mut acc = [[0u32; 3]; CHUNK];
        let amb = self.amb19.map(i32::cast_unsigned);
        let (mut nn, mut nd1, nd2) = nn32;
        for (r, a) in rb.iter_mut().zip(acc.iter_mut()).take(k) {
            *r = rsq(nn);
            *a = amb;
            nn = nn.wrapping_add(nd1);
            nd1 = nd1.wrapping_add(nd2);
        }
        for (plan, l) in plans.iter().zip(self.lights.iter()) {
            match *plan {
                Some(Plan::Spec(_, q32, nl, dnl)) => {
                    self.multi_light::<true>(l, q32, (nl, dnl), &rb, &mut acc, k);
                }
                Some(Plan::NoSpec(_, nl, dnl)) => {
                    self.multi_light::<false>(l, (0, 0, 0), (nl, dnl), &rb, &mut acc, k);
                }
                _ => {}
            }
        }
        for (o, a) in buf.iter_mut().zip(acc.iter()).take(k) {
            *o = pack(level_q19(a.map(|c| c.min(SAT).cast_signed())));
        }
        false
    }

    /// One light's terms over a chunk (`qm`: `Qm` in Q20 segments and its
    /// differences, `nl`: `n·L` and its step) added to the sums `acc`
    /// from `1/|n|` in `rb`.
    #[inline(always)]
    fn multi_light<const SPEC: bool>(
        &self,
        l: &KLight,
        qm: (i32, i32, i32),
        (mut nl, dnl): (i32, i32),
        rb: &[u32; CHUNK],
        acc: &mut [[u32; 3]; CHUNK],
        k: usize,
    ) {
        let d = l.d4.map(i16::cast_unsigned).map(u32::from);
        let s = l.s4.map(i16::cast_unsigned).map(u32::from);
        let (mut q, mut qd1, qd2) = qm;
        for (&r, a) in rb.iter().zip(acc.iter_mut()).take(k) {
            let (nl15, sp) = self.terms_r::<SPEC>(r, nl, q >> (QM_FRAC - 7));
            for c in 0..3 {
                a[c] = a[c].min(SAT) + d[c] * nl15 + s[c] * sp;
            }
            nl = nl.wrapping_add(dnl);
            if SPEC {
                q = q.wrapping_add(qd1);
                qd1 = qd1.wrapping_add(qd2);
            }
        }
    }

    /// One pixel of normal `n` (Q30) in 64 bits, every light (`n0`, `dn`,
    /// `i` for the generic fallback): the chunks some light's loop cannot
    /// prove, and the short spans.
    #[cold]
    #[inline(never)]
    #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)]
    pub(super) fn multi_exact(&self, n: [i32; 3], n0: [i32; 3], dn: [i32; 3], i: u32) -> u32 {
        let nn = sq3(n);
        if !(1 << 58..5 << 58).contains(&nn) {
            return pack(fallback(self.shade, n0, dn, [0; 3], [0; 3], i));
        }
        let r = rsq((nn >> 30) as i32);
        let mut acc = self.amb19.map(i32::cast_unsigned);
        for l in &self.lights {
            let nl = lin(n, l.at);
            let (nl15, sp) = if self.spec && (!self.blinn || lin(n, l.p1) > 0) {
                let k = lin(n, l.p2);
                let q = sq3(cross(n, l.p1)).wrapping_add(wmul(k, k) as u64);
                let qm = mul_shr48(q as i64, self.kf).clamp(0, QM_MAX) as i32;
                self.terms_r::<true>(r, nl, qm >> (QM_FRAC - 7))
            } else {
                self.terms_r::<false>(r, nl, 0)
            };
            let d = l.d4.map(i16::cast_unsigned).map(u32::from);
            let s = l.s4.map(i16::cast_unsigned).map(u32::from);
            for c in 0..3 {
                acc[c] = acc[c].min(SAT) + d[c] * nl15 + s[c] * sp;
            }
        }
        pack(level_q19(acc.map(|c| c.min(SAT).cast_signed())))
    }
}
