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
//! ([`PhongKernel::multi_exact`]). Each light adds its terms as the loop
//! of one light does on the M4 ([`Colour`](super::one::Colour)): per
//! channel `2^15 (d + s) + d (N·L - 2^15) + s (sp - 2^15)`, two signed
//! 16-bit multiply-adds of the packed terms, the offsets `2^15 (d + s)`
//! of every light in the sums' start ([`start`]). The sums agree with the
//! true ones modulo `2^32`; the kernel takes this loop only when the
//! largest true sum, every light at its largest terms, stays below `2^31`
//! ([`start`]: four lights of coefficient 1 reach `2^29.6`), else the
//! per-pixel path of [`PhongKernel::begin`]. The colour of each pixel is
//! then the sum of what each light alone adds in the loop of one light,
//! every light's error that
//! loop's (tests: `random_spans_against_f64`, one to four lights).

use super::one::{
    exact_chunk, mul_shr48, rsq, short_span, OneSpan, Plan, Whole, QM_FRAC, QM_MAX, SHORT_SPAN,
};
use super::{
    cross, drive, fallback, lin, pack, sq3, unpack_q19, KLight, Out, PhongKernel, CHUNK, MAX_LIGHTS,
};
use crate::num::wide::wmul;
use crate::num::Real;
use crate::target::level_q19;

/// The channel sums' start for the loop of several lights (module docs):
/// `amb19` plus `2^15 (d + s)` of every light (wrapping), or `None` when a
/// true sum may reach `2^31` (`amb19 + Σ d (2^15 + 2^4) + s 2^15`, `N·L`
/// and the specular factor at their largest).
#[allow(clippy::cast_possible_wrap, clippy::cast_possible_truncation)]
pub(super) fn start(amb19: [i32; 3], lights: &[KLight]) -> Option<[i32; 3]> {
    let mut st = amb19;
    for c in 0..3 {
        let mut hi = i64::from(amb19[c]);
        for l in lights {
            let (d, s) = (i64::from(l.d4[c]), i64::from(l.s4[c]));
            hi += d * ((1 << 15) + (1 << 4)) + s * (1 << 15);
            st[c] = st[c].wrapping_add(((d + s) << 15) as i32);
        }
        if hi >= 1 << 31 {
            return None;
        }
    }
    Some(st)
}

/// The exact states of a span's lights (`None` past the last light).
type States = [Option<OneSpan>; MAX_LIGHTS];
/// Each light's single plan ([`Whole`]).
type Wholes = [Option<Whole>; MAX_LIGHTS];

impl<R: Real> PhongKernel<'_, R> {
    /// [`PhongKernel::fill`] for two or more directional lights, viewer
    /// at infinity (module docs); `n`, `dn` already flipped for back
    /// faces. Not inlined: the lights' states (up to eight) stay in its
    /// own frame.
    #[inline(never)]
    pub(super) fn fill_multi(
        &self,
        start: [i32; 3],
        n: [i32; 3],
        dn: [i32; 3],
        len: u32,
        mut out: impl Out,
    ) -> u32 {
        if len < SHORT_SPAN {
            return short_span(n, dn, len, &mut out, |ni, i| self.multi_exact(ni, n, dn, i));
        }
        let mut st: States =
            core::array::from_fn(|j| self.lights.get(j).map(|l| self.one_begin(l, n, dn)));
        let mut wholes = self.multi_whole(&st, len);
        drive(
            len,
            |i, k, buf| match &mut wholes {
                Some(w) => self.multi_whole_chunk(start, w, k, buf),
                None => self.multi_chunk(start, n, dn, &mut st, i, k, buf),
            },
            unpack_q19,
            &mut out,
        )
    }

    /// Every light's single plan ([`PhongKernel::one_whole`]) when each
    /// has one.
    fn multi_whole(&self, st: &States, len: u32) -> Option<Wholes> {
        let mut w: Wholes = [const { None }; MAX_LIGHTS];
        for (o, s) in w.iter_mut().zip(st.iter()) {
            if let Some(s) = s {
                *o = Some(self.one_whole(s, len)?);
            }
        }
        Some(w)
    }

    /// [`PhongKernel::multi_chunk`] of a span whose lights all run with a
    /// single plan: their 32-bit states stepped on, no chunk set-up.
    #[inline(never)]
    fn multi_whole_chunk(
        &self,
        start: [i32; 3],
        ws: &mut Wholes,
        k: u32,
        buf: &mut [u32; CHUNK],
    ) -> bool {
        let k = (k as usize).min(CHUNK);
        let mut rb = [0u32; CHUNK];
        let mut acc = [[0i32; 3]; CHUNK];
        if let Some(w) = ws[0].as_mut() {
            let (mut nn, mut nd1, nd2) = (w.nn.wrapping_add(1 << 28), w.nd1, w.nd2);
            for (r, a) in rb.iter_mut().zip(acc.iter_mut()).take(k) {
                *r = rsq(nn);
                *a = start;
                nn = nn.wrapping_add(nd1);
                nd1 = nd1.wrapping_add(nd2);
            }
            (w.nn, w.nd1) = (nn.wrapping_sub(1 << 28), nd1);
        }
        for (w, l) in ws.iter_mut().zip(self.lights.iter()) {
            if let Some(w) = w {
                let qm = (w.q, w.qd1, w.qd2);
                (w.q, w.qd1, w.nl) = if w.spec {
                    self.multi_light::<true>(l, qm, (w.nl, w.dnl), &rb, &mut acc, k)
                } else {
                    self.multi_light::<false>(l, qm, (w.nl, w.dnl), &rb, &mut acc, k)
                };
            }
        }
        for (o, a) in buf.iter_mut().zip(acc.iter()).take(k) {
            *o = pack(level_q19(*a));
        }
        false
    }

    /// The colours (`r | g << 8 | b << 16`) of the `k` pixels from pixel
    /// `i` into `buf` (returns `false`: colours, not light terms), and the
    /// lights' states stepped past them.
    #[inline(never)]
    #[allow(clippy::too_many_arguments, clippy::cast_possible_wrap)]
    fn multi_chunk(
        &self,
        start: [i32; 3],
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
                let plan = self.chunk_plan(s, i, k);
                exact |= matches!(plan, Plan::Exact);
                *p = Some(plan);
            }
        }
        let nn32 = match plans[0] {
            Some(Plan::Spec(nn, ..) | Plan::NoSpec(nn, ..)) if !exact => nn,
            _ => {
                exact_chunk(n, dn, i, k, buf, |nj, j| self.multi_exact(nj, n, dn, j));
                return false;
            }
        };
        let k = (k as usize).min(CHUNK);
        // 2^16/|n| per pixel, the sums from the ambient term.
        let mut rb = [0u32; CHUNK];
        let mut acc = [[0i32; 3]; CHUNK];
        let (mut nn, mut nd1, nd2) = nn32;
        for (r, a) in rb.iter_mut().zip(acc.iter_mut()).take(k) {
            *r = rsq(nn);
            *a = start;
            nn = nn.wrapping_add(nd1);
            nd1 = nd1.wrapping_add(nd2);
        }
        for (plan, l) in plans.iter().zip(self.lights.iter()) {
            match *plan {
                Some(Plan::Spec(_, q32, nl, dnl)) => {
                    let _ = self.multi_light::<true>(l, q32, (nl, dnl), &rb, &mut acc, k);
                }
                Some(Plan::NoSpec(_, nl, dnl)) => {
                    let _ = self.multi_light::<false>(l, (0, 0, 0), (nl, dnl), &rb, &mut acc, k);
                }
                _ => {}
            }
        }
        for (o, a) in buf.iter_mut().zip(acc.iter()).take(k) {
            *o = pack(level_q19(*a));
        }
        false
    }

    /// One light's terms over a chunk (`qm`: `Qm` in Q20 segments and its
    /// differences, `nl`: `n·L` and its step) added to the sums `acc`
    /// (module docs) from `1/|n|` in `rb`; returns `Qm`, its difference
    /// and `n·L` stepped past the `k` pixels.
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    fn multi_light<const SPEC: bool>(
        &self,
        l: &KLight,
        qm: (i32, i32, i32),
        (mut nl, dnl): (i32, i32),
        rb: &[u32; CHUNK],
        acc: &mut [[i32; 3]; CHUNK],
        k: usize,
    ) -> (i32, i32, i32) {
        let ds = [0, 1, 2].map(|c| i32::from(l.d4[c]) | i32::from(l.s4[c]) << 16);
        let (mut q, mut qd1, qd2) = qm;
        for (&r, a) in rb.iter().zip(acc.iter_mut()).take(k) {
            let (nl15, sp) = self.terms_r::<SPEC>(r, nl, q >> (QM_FRAC - 7));
            let t = ((nl15 & 0xFFFF) | sp << 16) ^ 0x8000_8000;
            let (lo, hi) = (i32::from(t as i16), (t as i32) >> 16);
            for c in 0..3 {
                a[c] = a[c]
                    .wrapping_add(lo.wrapping_mul(i32::from(ds[c] as i16)))
                    .wrapping_add(hi.wrapping_mul(ds[c] >> 16));
            }
            nl = nl.wrapping_add(dnl);
            if SPEC {
                q = q.wrapping_add(qd1);
                qd1 = qd1.wrapping_add(qd2);
            }
        }
        (q, qd1, nl)
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
        let mut acc = self.amb19;
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
            for ((a, &d), &s) in acc.iter_mut().zip(&l.d4).zip(&l.s4) {
                *a = a
                    .wrapping_add(i32::from(d).wrapping_mul(nl15 as i32))
                    .wrapping_add(i32::from(s).wrapping_mul(sp as i32));
            }
        }
        pack(level_q19(acc))
    }
}
