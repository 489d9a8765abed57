//! Spans: depth test, attribute stepping and shading per pixel.
//!
//! [`Fill`] is the span stage: it receives spans from
//! [`draw_triangle`](super::draw_triangle), tests and writes depth (when a
//! depth buffer is given), asks a [`Shader`] for the colour of each pixel
//! and stores it in the target's format. Rows come from the target's and
//! depth buffer's fast paths ([`Target::row_mut`]) when they have them.

use super::{Lerp, RasterError, Span, Spans, Vals, LEVEL_FRAC_BITS};
use crate::num::wide::NO_LONG_MUL;
use crate::target::{span_range, DepthBuffer, DepthFormat, PixelFormat, Rgb8, Target};

/// Computes a pixel's colour from its interpolated attributes.
pub trait Shader<L: Lerp, const N: usize> {
    /// The colour for attributes `a`.
    fn shade(&self, a: &[L; N]) -> Rgb8;

    /// The colour for attributes `a` stored in format `F`:
    /// `F::encode(self.shade(a))`, or a faster path giving the same bytes.
    #[inline(always)]
    fn shade_raw<F: PixelFormat>(&self, a: &[L; N]) -> F::Raw {
        F::encode(self.shade(a))
    }

    /// Called once per span before its pixels are shaded, with the
    /// attributes at its first pixel, their steps per pixel and its length
    /// in pixels: the place for per-span set-up (e.g. the forward
    /// differences of `n·L`, `n·H` and `|n|²` of per-pixel Phong shading),
    /// so that [`Shader::shade`] only steps them. Not called for
    /// [`Shader::constant`] shaders. [`Persp`] does not forward it (its
    /// inner shader sees attributes divided per pixel). Default: nothing.
    #[inline(always)]
    fn begin_span(&mut self, a: &[L; N], da: &[L; N], len: u32) {
        let _ = (a, da, len);
    }

    /// `true` when [`Shader::shade_raw_in_range`] gives
    /// [`Shader::shade_raw`]'s bytes at every pixel of a span whose
    /// attributes start at `a` and step by `da` for `len` pixels (the
    /// span loop's wrapping additions included): the span stage then
    /// shades without clamps. Checked once per span, at its two ends.
    /// Default: `false`.
    #[inline(always)]
    fn span_in_range(&self, a: &[L; N], da: &[L; N], len: u32) -> bool {
        let _ = (a, da, len);
        false
    }

    /// The attributes `a` at a span's first pixel and their steps `da`
    /// in the form [`Shader::shade_raw_in_range`] takes, for a span for
    /// which [`Shader::span_in_range`] holds: stepped by wrapping
    /// additions as the originals. Default: unchanged.
    #[inline(always)]
    fn in_range_values(&self, a: &[L; N], da: &[L; N]) -> ([L; N], [L; N]) {
        (*a, *da)
    }

    /// [`Shader::shade_raw`] for a span for which
    /// [`Shader::span_in_range`] holds, from the attributes in the form
    /// of [`Shader::in_range_values`]. Default: `shade_raw`.
    #[inline(always)]
    fn shade_raw_in_range<F: PixelFormat>(&self, a: &[L; N]) -> F::Raw {
        self.shade_raw::<F>(a)
    }

    /// `Some(colour)` when the colour does not depend on the attributes:
    /// the span stage then encodes it once per span instead of once per
    /// pixel.
    fn constant(&self) -> Option<Rgb8> {
        None
    }

    /// A span loop of the shader's own (chosen by the shader's type): shades
    /// the pixels of `row`, depth-testing against `drow` (the same length)
    /// when given, from the depth `z` and the attributes `a` at the first
    /// pixel, `at` = `(x, y)` on the screen, stepped per pixel by `dz` and
    /// `da`, and returns the pixels drawn; the depth test and write must be the span stage's own
    /// ([`DepthFormat::from_lerp`], less-than). `None`, the default: the
    /// span stage runs its loop, with [`Shader::begin_span`] and
    /// [`Shader::shade_raw`] per pixel. Per-pixel Phong
    /// (`render::PhongKernelShader`) keeps its forward differences in
    /// registers this way. Called by the band renderer's row kernel.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn span_kernel<F: PixelFormat, D: DepthFormat>(
        &mut self,
        row: &mut [F::Raw],
        drow: Option<&mut [D::Raw]>,
        z: L,
        dz: L,
        a: &[L; N],
        da: &[L; N],
        at: (i32, i32),
    ) -> Option<u32> {
        let _ = (row, drow, z, dz, a, da, at);
        None
    }
}

/// One colour for the whole triangle (flat shading); attributes ignored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Flat(pub Rgb8);

impl<L: Lerp, const N: usize> Shader<L, N> for Flat {
    #[inline(always)]
    fn shade(&self, _a: &[L; N]) -> Rgb8 {
        self.0
    }

    #[inline(always)]
    fn constant(&self) -> Option<Rgb8> {
        Some(self.0)
    }
}

#[inline(always)]
fn level<L: Lerp>(v: L) -> u8 {
    v.round_int(LEVEL_FRAC_BITS).clamp(0, 255) as u8
}

/// Gouraud shading of one grey intensity: attribute 0 is a level in
/// `0..=255` (fixed: `level · 2^16`), rounded to nearest and clamped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct GouraudMono;

impl<L: Lerp> Shader<L, 1> for GouraudMono {
    #[inline(always)]
    fn shade(&self, a: &[L; 1]) -> Rgb8 {
        Rgb8::grey(level(a[0]))
    }

    #[inline(always)]
    fn shade_raw<F: PixelFormat>(&self, a: &[L; 1]) -> F::Raw {
        F::encode_grey(level(a[0]))
    }

    /// Fixed values ([`Lerp::EXACT_STEPS`]) whose rounded levels lie in
    /// `0..=255` at both ends of the span, without wrapping in between
    /// (`levels_in_range`).
    #[inline(always)]
    fn span_in_range(&self, a: &[L; 1], da: &[L; 1], len: u32) -> bool {
        L::EXACT_STEPS && levels_in_range(a[0].round_int(0), da[0].round_int(0), len)
    }

    /// Fixed values: the level with its rounding offset in the top 8 bits,
    /// `(v + 2^15) << 8`, stepped by `s << 8` (wrapping: the top 8 bits
    /// of the `k`-th value are bits 16..24 of `v + 2^15 + k·s`, the
    /// rounded level modulo 256), so that the colour needs one shift and
    /// no mask. Floats (never in range): unchanged.
    #[inline(always)]
    fn in_range_values(&self, a: &[L; 1], da: &[L; 1]) -> ([L; 1], [L; 1]) {
        match (a[0].fixed_raw(), da[0].fixed_raw()) {
            (Some(v), Some(s)) if L::EXACT_STEPS => (
                [L::from_fixed_raw(
                    v.wrapping_add(1 << (LEVEL_FRAC_BITS - 1)) << (24 - LEVEL_FRAC_BITS),
                )],
                [L::from_fixed_raw(s << (24 - LEVEL_FRAC_BITS))],
            ),
            _ => (*a, *da),
        }
    }

    /// The level without its clamp, from the top 8 bits of the form of
    /// [`Shader::in_range_values`]: `round_int` truncated to 8 bits, the
    /// clamped level when it lies in `0..=255`.
    #[inline(always)]
    fn shade_raw_in_range<F: PixelFormat>(&self, a: &[L; 1]) -> F::Raw {
        match a[0].fixed_raw() {
            Some(v) if L::EXACT_STEPS => F::encode_grey((v as u32 >> 24) as u8),
            _ => F::encode_grey(a[0].round_int(LEVEL_FRAC_BITS) as u8),
        }
    }
}

/// `true` when every level `round(v + k·s)` (fixed, `2^16` a level;
/// rounding half up as [`Lerp::round_int`]), `0 <= k < n`, lies in
/// `0..=255` and the `i32` additions of the span loop do not wrap: with
/// `r = v + 2^15` (the rounding offset) in `[0, 256·2^16)` and the offset
/// of the last pixel `|s|·(n - 1)` below `2^31` (`n - 1 < 2^8` and `|s| <
/// 2^23`, or `n - 1 < 2^16` and `|s| < 2^15`: the product in a `u32`,
/// `r` plus it below `2^24 + 2^31`, no wrap), the last rounded value
/// `r + s·(n - 1)` in the same range too; the levels in between lie
/// between the two ends (a linear sequence). Conservative: `false` only
/// selects the clamping loop.
#[inline(always)]
fn levels_in_range(v: i32, s: i32, n: u32) -> bool {
    const LIM: u32 = 256 << LEVEL_FRAC_BITS;
    let r = v.wrapping_add(1 << (LEVEL_FRAC_BITS - 1)) as u32;
    let (m, sa) = (n.wrapping_sub(1), s.unsigned_abs());
    let small = (m < 1 << 8 && sa < 1 << 23) || (m < 1 << 16 && sa < 1 << 15);
    if r >= LIM || n == 0 || !small {
        return false;
    }
    let off = sa * m;
    if s >= 0 {
        r + off < LIM
    } else {
        off <= r
    }
}

/// Gouraud shading in colour: attributes 0, 1, 2 are the red, green and
/// blue levels (fixed: `level · 2^16`), rounded and clamped.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Gouraud;

impl<L: Lerp> Shader<L, 3> for Gouraud {
    #[inline(always)]
    fn shade(&self, a: &[L; 3]) -> Rgb8 {
        Rgb8::new(level(a[0]), level(a[1]), level(a[2]))
    }
}

/// Perspective-correct wrapper: the last attribute is the weight `q =
/// near/w` (affine in screen space) and the others were interpolated as
/// `a · q`; each pixel divides them by `q` and hands them to the inner
/// shader.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Persp<S>(pub S);

macro_rules! persp {
    ($n:literal, $m:literal) => {
        impl<L: Lerp, S: Shader<L, $n>> Shader<L, $m> for Persp<S> {
            #[inline(always)]
            fn shade(&self, a: &[L; $m]) -> Rgb8 {
                let f = L::unweight_factor(a[$n]);
                let mut b = [a[0]; $n];
                for (o, i) in b.iter_mut().zip(a.iter()) {
                    *o = i.unweight(f);
                }
                self.0.shade(&b)
            }

            #[inline(always)]
            fn shade_raw<F: PixelFormat>(&self, a: &[L; $m]) -> F::Raw {
                let f = L::unweight_factor(a[$n]);
                let mut b = [a[0]; $n];
                for (o, i) in b.iter_mut().zip(a.iter()) {
                    *o = i.unweight(f);
                }
                self.0.shade_raw::<F>(&b)
            }
        }
    };
}

persp!(1, 2);
persp!(3, 4);
persp!(6, 7);

/// `Ok` when `depth` is none or holds the rows and the width of `target`;
/// [`RasterError::DepthWindowMismatch`] otherwise (the check of a span
/// stage's constructor).
pub(crate) fn same_window<T: Target, D: DepthFormat>(
    target: &T,
    depth: Option<&DepthBuffer<'_, D>>,
) -> Result<(), RasterError> {
    match depth {
        Some(d) if d.window() != target.window() => Err(RasterError::DepthWindowMismatch),
        _ => Ok(()),
    }
}

/// The span stage: a target, an optional depth buffer and a shader.
///
/// Without a depth buffer every covered pixel is drawn, in triangle order
/// (enough for one convex object with back-face culling).
#[derive(Debug)]
pub struct Fill<'t, 'd, 'b, T, D: DepthFormat, S> {
    target: &'t mut T,
    depth: Option<&'d mut DepthBuffer<'b, D>>,
    /// The shader used for the next spans.
    pub shader: S,
    drawn: u32,
}

impl<'t, 'd, 'b, T: Target, D: DepthFormat, S> Fill<'t, 'd, 'b, T, D, S> {
    /// A span stage writing into `target`, testing against `depth`.
    ///
    /// # Errors
    /// [`RasterError::DepthWindowMismatch`] when the depth buffer holds
    /// other rows or another width than the target.
    pub fn new(
        target: &'t mut T,
        depth: Option<&'d mut DepthBuffer<'b, D>>,
        shader: S,
    ) -> Result<Self, RasterError> {
        same_window(target, depth.as_deref())?;
        Ok(Self {
            target,
            depth,
            shader,
            drawn: 0,
        })
    }

    /// Pixels written so far (those that passed the depth test).
    pub fn drawn(&self) -> u32 {
        self.drawn
    }

    /// The target's window (for [`draw_triangle`](super::draw_triangle)).
    pub fn window(&self) -> crate::target::Window {
        self.target.window()
    }
}

impl<T: Target, D: DepthFormat, S> Fill<'_, '_, '_, T, D, S> {
    #[inline(always)]
    fn fill<L: Lerp, const N: usize>(
        &mut self,
        s: &Span<L, N>,
        color: impl Fn(&[L; N]) -> <T::Format as PixelFormat>::Raw,
    ) {
        let (target, depth, drawn) = (
            &mut *self.target,
            self.depth.as_deref_mut(),
            &mut self.drawn,
        );
        fill_span::<L, N, T, D>(target, depth, drawn, s, &color, None, &color);
    }
}

/// The pixel loop of a span: depth test (when a depth buffer is given),
/// attribute stepping, `color` per pixel written.
///
/// With row slices from both buffers (the usual case) the depth loop is
/// [`depth_loop`]; when the span's depths provably stay within the depth
/// format's range ([`DepthFormat::span_in_range`], checked once per span at
/// its two ends, on spans of at least [`SHORT_SPAN`] pixels) the per-pixel
/// conversion skips its clamp. The same bytes either way.
///
/// `color_inr` is the colour for the spans whose attributes the caller
/// found in range ([`Shader::span_in_range`]), taken with the depths in
/// range, from the attributes and steps `inr` in the form of
/// [`Shader::in_range_values`] (ARMv6-M, one attribute: [`in_range_pairs`],
/// as for the in-range spans without attributes there; elsewhere from
/// [`LONG_SPAN`] pixels, as every in-range span of at most one attribute
/// that long: [`long_loop`]).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn fill_span<L: Lerp, const N: usize, T: Target, D: DepthFormat>(
    target: &mut T,
    depth: Option<&mut DepthBuffer<'_, D>>,
    drawn: &mut u32,
    s: &Span<L, N>,
    color: &impl Fn(&[L; N]) -> <T::Format as PixelFormat>::Raw,
    inr: Option<&([L; N], [L; N])>,
    color_inr: &impl Fn(&[L; N]) -> <T::Format as PixelFormat>::Raw,
) {
    let Span {
        y,
        x0,
        x1,
        z,
        dz,
        mut a,
        ref da,
    } = *s;
    let len = x1.saturating_sub(x0);
    let n = match depth {
        Some(d) => {
            // One window check for both buffers (Fill::new checked that
            // they hold the same window).
            let Some(r) = span_range(d.window(), y, x0, x1) else {
                return;
            };
            let Some(drow) = d.values_mut().get_mut(r.clone()) else {
                return;
            };
            let row = if target.pixels_mut().is_some() {
                target.pixels_mut().and_then(|p| p.get_mut(r))
            } else {
                target.span_mut(y, x0, x1)
            };
            if let Some(row) = row {
                let fails = if len >= SHORT_SPAN && D::span_in_range(z, dz, len) {
                    if !NO_LONG_MUL && N <= 1 && len >= LONG_SPAN {
                        len - match inr {
                            Some((ia, ida)) => {
                                long_loop::<L, N, _, D>(row, drow, z, dz, *ia, ida, color_inr)
                            }
                            None => long_loop::<L, N, _, D>(row, drow, z, dz, a, da, color),
                        }
                    } else if N > 1 {
                        pair_loop::<L, N, _, D>(row, drow, z, a, &Vals { z: dz, a: *da }, color)
                    } else if let Some((ia, ida)) = inr {
                        len - in_range_pairs::<L, N, _, D>(row, drow, z, dz, *ia, ida, color_inr)
                    } else if NO_LONG_MUL && N == 0 {
                        len - in_range_pairs::<L, N, _, D>(row, drow, z, dz, a, da, color)
                    } else {
                        len - inr_span::<L, N, _, D>(
                            row,
                            drow,
                            z,
                            a,
                            &Vals { z: dz, a: *da },
                            color,
                        )
                    }
                } else {
                    depth_loop(row, drow, z, dz, a, da, color, clamp_test::<L, D>)
                };
                len - fails
            } else {
                let mut z = z;
                let mut n = 0;
                for (x, zb) in (x0..x1).zip(drow.iter_mut()) {
                    let zd = D::from_lerp(z);
                    if zd < *zb {
                        *zb = zd;
                        target.write_pixel(x, y, color(&a));
                        n += 1;
                    }
                    z = z.add(dz);
                    step_all(&mut a, da);
                }
                n
            }
        }
        None => {
            if let Some(row) = target.span_mut(y, x0, x1) {
                for p in row.iter_mut() {
                    *p = color(&a);
                    step_all(&mut a, da);
                }
            } else {
                for x in x0..x1 {
                    target.write_pixel(x, y, color(&a));
                    step_all(&mut a, da);
                }
            }
            len
        }
    };
    *drawn += n;
}

/// The pixels of one span of the band renderer's row kernel: `row` and
/// `drow` (the same length, `x1 - x0`) are the span's colour and depth
/// slices, `v` the values at its first pixel and `sx` their steps. The
/// same loops, hence the same bytes, as [`Fill`]'s; `at` is the first
/// pixel's `(x, y)` on the screen. Returns the pixels written.
#[inline(always)]
pub(crate) fn span_pixels<L, const N: usize, F, D, S>(
    row: &mut [F::Raw],
    drow: Option<&mut [D::Raw]>,
    v: &Vals<L, N>,
    sx: &Vals<L, N>,
    plane_in_range: bool,
    shader: &mut S,
    at: (i32, i32),
) -> u32
where
    L: Lerp,
    F: PixelFormat,
    D: DepthFormat,
    S: Shader<L, N>,
{
    if let Some(c) = shader.constant() {
        let raw = F::encode(c);
        row_pixels::<L, N, F::Raw, D>(row, drow, v, sx, plane_in_range, move |_| raw)
    } else {
        let mut drow = drow;
        if let Some(drawn) =
            shader.span_kernel::<F, D>(row, drow.as_deref_mut(), v.z, sx.z, &v.a, &sx.a, at)
        {
            return drawn;
        }
        shader.begin_span(&v.a, &sx.a, row.len() as u32);
        let shader = &*shader;
        row_pixels::<L, N, F::Raw, D>(row, drow, v, sx, plane_in_range, |a| {
            shader.shade_raw::<F>(a)
        })
    }
}

#[inline(always)]
fn row_pixels<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: Option<&mut [D::Raw]>,
    v: &Vals<L, N>,
    sx: &Vals<L, N>,
    plane_in_range: bool,
    color: impl Fn(&[L; N]) -> R,
) -> u32 {
    let (z, dz, a, da) = (v.z, sx.z, v.a, &sx.a);
    let len = row.len() as u32;
    match drow {
        Some(drow) => {
            // A triangle whose depths are all in range (`plane_in_range`)
            // takes the loop without clamps on every span, without the
            // per-span check. Two loops inlined where the in-range loop
            // is (ARMv6-M, several attributes); on ARMv7-M with at most
            // one attribute, the outlined in-range loop only for long
            // spans (its call costs more than it saves on short ones).
            let long = len >= SHORT_SPAN;
            let fails = if NO_LONG_MUL || N != 1 {
                if plane_in_range || (long && D::span_in_range(z, dz, len)) {
                    depth_loop(row, drow, z, dz, a, da, color, in_range_test::<L, D>)
                } else {
                    depth_loop(row, drow, z, dz, a, da, color, clamp_test::<L, D>)
                }
            } else if long && (plane_in_range || D::span_in_range(z, dz, len)) {
                len - in_range_loop::<L, N, _, D>(row, drow, z, a, sx, &color)
            } else if plane_in_range {
                depth_loop(row, drow, z, dz, a, da, color, in_range_test::<L, D>)
            } else {
                depth_loop(row, drow, z, dz, a, da, color, clamp_test::<L, D>)
            };
            len - fails
        }
        None => {
            let mut a = a;
            for p in row.iter_mut() {
                *p = color(&a);
                step_all(&mut a, da);
            }
            len
        }
    }
}

/// The depth-tested pixel loop over a row slice and its depth slice (the
/// same length); `test` compares and stores the depth. Returns the pixels that *failed* the test, so that the
/// common passing path does not count (`drawn = len - fails`).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn depth_loop<L: Lerp, const N: usize, R, Z>(
    row: &mut [R],
    drow: &mut [Z],
    mut z: L,
    dz: L,
    mut a: [L; N],
    da: &[L; N],
    color: impl Fn(&[L; N]) -> R,
    test: impl Fn(L, &mut Z) -> bool,
) -> u32 {
    let mut fails = 0u32;
    let mut it = row.iter_mut().zip(drow.iter_mut());
    while let Some((p, zb)) = it.next() {
        if test(z, zb) {
            *p = color(&a);
        } else {
            fails += 1;
            // Never taken (a slice holds fewer than u32::MAX depths; the
            // iterator never reports usize::MAX left), but two more loop
            // exits keep LLVM's ARM M-profile runtime unroller (4×, with a
            // remainder loop) off this loop: its per-span prologue cost
            // more than it saved on the scenes' spans of a few pixels
            // (bunny-gouraud raster, both thumb targets). On the failing
            // path only, so the passing pixel pays nothing.
            if fails == u32::MAX || it.len() == usize::MAX {
                break;
            }
        }
        z = z.add(dz);
        step_all(&mut a, da);
    }
    fails
}

/// [`depth_loop`] for a span whose depths stay in range (no clamp), two
/// pixels a step ([`pair_loop`]), in a function of its own that returns
/// the pixels written (the caller then keeps no length across the call): the spans of
/// three pixels or more of [`inr_span`] on ARMv7-M and the hosts, and the
/// long spans of the generic row kernel's single-attribute shaders there
/// (inlined next to the clamping loop of the short spans, its depth step
/// lost its register to a stack reload on ARMv7-M; the call costs
/// bunny-gouraud raster 0.6 %). Spans of more than one attribute inline
/// [`pair_loop`] instead (their outlined loop spilled its steps:
/// dodeca-gouraud raster +11 % on the M4).
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn in_range_loop<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    z: L,
    a: [L; N],
    sx: &Vals<L, N>,
    color: &impl Fn(&[L; N]) -> R,
) -> u32 {
    row.len() as u32 - pair_loop::<L, N, _, D>(row, drow, z, a, sx, color)
}

/// The depth-tested pixels of a long span ([`LONG_SPAN`] pixels or more)
/// whose depths stay in range, of at most one attribute, on ARMv7-M and
/// the hosts: [`unrolled_loop`] for fixed values, [`pair_loop`]
/// otherwise. Returns the pixels written. [`Fill`]'s loop for those
/// spans (flat, and [`GouraudMono`] with its levels in range in the form
/// of [`Shader::in_range_values`]); in a function of its own, as
/// [`in_range_loop`], so that the short spans keep their registers.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn long_loop<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    z: L,
    dz: L,
    a: [L; N],
    da: &[L; N],
    color: &impl Fn(&[L; N]) -> R,
) -> u32 {
    if let (Some(zr), Some(dzr)) = (z.fixed_raw(), dz.fixed_raw()) {
        let ar = a.map(|v| v.fixed_raw().unwrap_or(0));
        let dar = da.map(|v| v.fixed_raw().unwrap_or(0));
        unrolled_loop::<L, N, R, D>(row, drow, zr, dzr, ar, dar, color)
    } else {
        row.len() as u32 - pair_loop::<L, N, _, D>(row, drow, z, a, &Vals { z: dz, a: *da }, color)
    }
}

/// [`pair_loop`] eight pixels a step, for fixed values (their raw
/// `i32`s, stepped by wrapping additions as [`Lerp::add`] steps them),
/// then the remainder one a step: the loop's pointer steps, compare and
/// branch are paid once per eight pixels. Per passing pixel on ARMv7-M:
/// load the stored depth, compare it with the depth shifted, branch,
/// shift, store depth and colour, step the depth (7 instructions; plus
/// the level's shift, table load and step with one attribute in the
/// form of [`GouraudMono`]'s [`Shader::in_range_values`]), and 5 a step:
/// span loops on thumbv7em flat 9.23 -> 7.88, Gouraud 12.22 -> 11.09
/// instructions a pixel (by four: Gouraud 11.72).
///
/// A failed test steps the depth and the attributes by subtracting their
/// negated steps, read through [`core::hint::black_box`] (the same
/// values, wrapping): the sequences are then no induction variables to
/// LLVM, whose loop strength reduction otherwise rewrote the pixels'
/// depths as `z + k·dz` with the multiples of `dz` spilled to the stack
/// (flat 9.5, Gouraud 15.8 instructions a pixel by four). On the failing
/// path only, and the failed count is kept out of the registers
/// ([`failed`]). The same pixels tested against the same stored values
/// with the same conversions ([`DepthFormat::from_lerp_in_range`],
/// less-than), in the same order, hence the same bytes.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
fn unrolled_loop<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    z: i32,
    dz: i32,
    mut a: [i32; N],
    da: [i32; N],
    color: &impl Fn(&[L; N]) -> R,
) -> u32 {
    const K: usize = 8;
    let n = row.len().min(drow.len());
    let (row, drow) = (row.split_at_mut(n).0, drow.split_at_mut(n).0);
    let (row_m, row_t) = row.split_at_mut(n - n % K);
    let (drow_m, drow_t) = drow.split_at_mut(n - n % K);
    let mut z = z;
    let mut fails = 0u32;
    let ndz = core::hint::black_box(dz.wrapping_neg());
    let nda = core::hint::black_box(da.map(i32::wrapping_neg));
    for (pc, zc) in row_m.chunks_exact_mut(K).zip(drow_m.chunks_exact_mut(K)) {
        for (p, zb) in pc.iter_mut().zip(zc.iter_mut()) {
            let key = D::from_lerp_in_range(L::from_fixed_raw(z));
            if key < D::to_key(*zb) {
                *zb = D::from_key(key);
                *p = color(&a.map(L::from_fixed_raw));
                z = z.wrapping_add(dz);
                for (v, d) in a.iter_mut().zip(da) {
                    *v = v.wrapping_add(d);
                }
            } else {
                fails = failed(fails);
                z = z.wrapping_sub(ndz);
                for (v, d) in a.iter_mut().zip(nda) {
                    *v = v.wrapping_sub(d);
                }
            }
        }
    }
    for (p, zb) in row_t.iter_mut().zip(drow_t.iter_mut()) {
        let key = D::from_lerp_in_range(L::from_fixed_raw(z));
        if key < D::to_key(*zb) {
            *zb = D::from_key(key);
            *p = color(&a.map(L::from_fixed_raw));
        } else {
            fails += 1;
        }
        z = z.wrapping_add(dz);
        for (v, d) in a.iter_mut().zip(da) {
            *v = v.wrapping_add(d);
        }
    }
    n as u32 - fails
}

/// Spans of at least this many pixels whose depths are in range take
/// [`long_loop`] on ARMv7-M and the hosts (its call and set-up cost more
/// than they save on shorter ones; the scenes' spans average a few
/// pixels).
const LONG_SPAN: u32 = 16;

/// The depth-tested pixels of a span whose depths stay in range (no
/// clamp), two a step after one alone when the count is odd, walking both
/// slices by pattern (a pointer each and one count); a failed test is
/// marked cold ([`failed`]). Returns the pixels
/// written. In a function of its own: [`Fill`]'s in-range spans (from
/// [`SHORT_SPAN`] pixels) on ARMv6-M without attributes, and with one
/// whose levels are in range too (the shift-only level of
/// [`GouraudMono`]'s [`Shader::in_range_values`]): span loops on thumbv6m
/// flat 13.16 -> 10.70, Gouraud 22.28 -> 16.91 instructions a pixel (the
/// inlined [`depth_loop`] had its steps, colour and table address
/// reloaded from the stack or the literal pool every pixel). The same
/// pixels in the same order, hence the same bytes.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn in_range_pairs<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    mut z: L,
    dz: L,
    mut a: [L; N],
    da: &[L; N],
    color: &impl Fn(&[L; N]) -> R,
) -> u32 {
    let mut fails = 0u32;
    let n = row.len().min(drow.len());
    let (mut row, mut drow) = (row.split_at_mut(n).0, drow.split_at_mut(n).0);
    if n % 2 == 1 {
        if let ([p, pr @ ..], [zb, zr @ ..]) = (row, drow) {
            if in_range_test::<L, D>(z, zb) {
                *p = color(&a);
            } else {
                fails += 1;
            }
            z = z.add(dz);
            step_all(&mut a, da);
            (row, drow) = (pr, zr);
        } else {
            return 0;
        }
    }
    while let ([p0, p1, pr @ ..], [z0, z1, zr @ ..]) = (row, drow) {
        for (p, zb) in [(p0, z0), (p1, z1)] {
            if in_range_test::<L, D>(z, zb) {
                *p = color(&a);
            } else {
                fails = failed(fails);
            }
            z = z.add(dz);
            step_all(&mut a, da);
        }
        (row, drow) = (pr, zr);
    }
    n as u32 - fails
}

/// `fails + 1` for a failed depth test in [`in_range_pairs`], marked
/// cold (inlined all the same): the optimiser then lays the loop out for
/// the passing pixels and keeps their values in registers, the count in
/// memory (span loops Gouraud on thumbv6m 17.41 -> 16.91 instructions a
/// pixel).
#[cold]
#[inline(always)]
fn failed(fails: u32) -> u32 {
    fails.wrapping_add(1)
}

/// [`depth_loop`] two pixels per iteration (after one pixel alone when
/// the count is odd): the loop's pointer steps, counter and branch are
/// paid once per pair. Span loops on thumbv7em: flat 11.2 -> 9.2
/// instructions per pixel, GouraudMono 14.2 -> 12.2 (by four, LLVM
/// spilled the partial depth sums: 9.7 and 15.3). Taken only for the
/// spans whose depths were checked in range (at least [`SHORT_SPAN`]
/// pixels), hence [`in_range_test`]; the steps `sx` as [`inr_span`] takes
/// them. The same pixels in the same order, hence the same bytes.
#[inline(always)]
pub(super) fn pair_loop<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    mut z: L,
    mut a: [L; N],
    sx: &Vals<L, N>,
    color: impl Fn(&[L; N]) -> R,
) -> u32 {
    let (dz, da) = (sx.z, &sx.a);
    let test = in_range_test::<L, D>;
    let mut fails = 0u32;
    let n = row.len().min(drow.len());
    let (row, drow) = (row.split_at_mut(n).0, drow.split_at_mut(n).0);
    let (row_h, row) = row.split_at_mut(n % 2);
    let (drow_h, drow) = drow.split_at_mut(n % 2);
    if let (Some(p), Some(zb)) = (row_h.first_mut(), drow_h.first_mut()) {
        if test(z, zb) {
            *p = color(&a);
        } else {
            fails += 1;
        }
        z = z.add(dz);
        step_all(&mut a, da);
    }
    for (p, zb) in row.chunks_exact_mut(2).zip(drow.chunks_exact_mut(2)) {
        if let ([p0, p1], [z0, z1]) = (p, zb) {
            for (p, zb) in [(p0, z0), (p1, z1)] {
                if test(z, zb) {
                    *p = color(&a);
                } else {
                    fails += 1;
                }
                z = z.add(dz);
                step_all(&mut a, da);
            }
        }
    }
    fails
}

/// The pixels of a span whose depths all convert without a clamp (the
/// triangle's [`DepthFormat::plane_in_range`] flag, or
/// [`DepthFormat::span_in_range`] for the span): returns the pixels
/// written. The span kernel of the band renderer's fused row loop
/// (`raster::fast`), and [`Fill`]'s for the in-range spans of at most one
/// attribute, so that the firmware's span-loop figures are the loop the
/// renderer runs. On ARMv6-M the one-pixel-a-step [`depth_loop`], inlined
/// (a call costs more there than it saves on spans of a few pixels);
/// elsewhere a single pixel inline (frequent on small triangles:
/// bunny-gouraud raster -0.5 % on thumbv7em), two without attributes, and
/// longer spans through the outlined [`pair_loop`] ([`in_range_loop`]).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn inr_span<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    z: L,
    a: [L; N],
    sx: &Vals<L, N>,
    color: &impl Fn(&[L; N]) -> R,
) -> u32 {
    if NO_LONG_MUL {
        inr_span_inline::<L, N, R, D>(row, drow, z, a, sx, color)
    } else if let ([p], [zb]) = (&mut *row, &mut *drow) {
        let pass = in_range_test::<L, D>(z, zb);
        if pass {
            *p = color(&a);
        }
        pass as u32
    } else if let (0, [p0, p1], [z0, z1]) = (N, &mut *row, &mut *drow) {
        // Two pixels inline as well, without attributes (flat: bunny-flat
        // raster on thumbv7em 2.110 -> 2.075 M; with one attribute the
        // row loop lost registers to it, bunny-gouraud +0.4 %).
        let pass0 = in_range_test::<L, D>(z, z0);
        if pass0 {
            *p0 = color(&a);
        }
        let mut a = a;
        step_all(&mut a, &sx.a);
        let pass1 = in_range_test::<L, D>(z.add(sx.z), z1);
        if pass1 {
            *p1 = color(&a);
        }
        pass0 as u32 + pass1 as u32
    } else {
        in_range_loop::<L, N, R, D>(row, drow, z, a, sx, color)
    }
}

/// [`inr_span`] with the pixel loop inline, one pixel a step
/// ([`depth_loop`] with [`in_range_test`]): no call per span.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(super) fn inr_span_inline<L: Lerp, const N: usize, R, D: DepthFormat>(
    row: &mut [R],
    drow: &mut [D::Raw],
    z: L,
    a: [L; N],
    sx: &Vals<L, N>,
    color: &impl Fn(&[L; N]) -> R,
) -> u32 {
    row.len() as u32 - depth_loop(row, drow, z, sx.z, a, &sx.a, color, in_range_test::<L, D>)
}

/// The depth test and write of a pixel, its depth converted with the
/// format's clamp ([`DepthFormat::from_lerp`]).
#[inline(always)]
pub(super) fn clamp_test<L: Lerp, D: DepthFormat>(z: L, zb: &mut D::Raw) -> bool {
    let zd = D::from_lerp(z);
    let pass = zd < *zb;
    if pass {
        *zb = zd;
    }
    pass
}

/// The depth test and write of a pixel whose depth is in range
/// ([`DepthFormat::span_in_range`]): no clamp.
#[inline(always)]
pub(super) fn in_range_test<L: Lerp, D: DepthFormat>(z: L, zb: &mut D::Raw) -> bool {
    let k = D::from_lerp_in_range(z);
    let pass = k < D::to_key(*zb);
    if pass {
        *zb = D::from_key(k);
    }
    pass
}

#[inline(always)]
fn step_all<L: Lerp, const N: usize>(a: &mut [L; N], da: &[L; N]) {
    for (v, d) in a.iter_mut().zip(da.iter()) {
        *v = v.add(*d);
    }
}

impl<L, const N: usize, T, D, S> Spans<L, N> for Fill<'_, '_, '_, T, D, S>
where
    L: Lerp,
    T: Target,
    D: DepthFormat,
    S: Shader<L, N>,
{
    // On ARMv6-M inlined into the scanline loop (the span is not stored
    // and reloaded): bunny-gouraud raster -0.4 %, span loops flat 15 -> 14
    // and Gouraud 28 -> 26 insns/px. On ARMv7E-M the same inlining cost
    // 4 % (register pressure in the scanline loop): a call there.
    #[cfg_attr(armv6m, inline(always))]
    fn span(&mut self, s: &Span<L, N>) {
        if let Some(c) = self.shader.constant() {
            let raw = T::Format::encode(c);
            self.fill(s, move |_| raw);
        } else {
            let len = s.x1.saturating_sub(s.x0);
            self.shader.begin_span(&s.a, &s.da, len);
            let shader = &self.shader;
            // From SHORT_SPAN pixels on ARMv6-M; elsewhere only for the
            // long spans of `long_loop`, whose attribute is no induction
            // variable to LLVM (its level's rounding offset is then added
            // per pixel: span loops Gouraud on thumbv7em 12.79 with the
            // clamped level, 11.09 with the shifted one). On the shorter
            // spans of ARMv7-M the clamp is one `USAT`, and the unclamped
            // level took one more instruction (12.21 -> 12.38).
            let inr = (N == 1
                && len >= if NO_LONG_MUL { SHORT_SPAN } else { LONG_SPAN }
                && shader.span_in_range(&s.a, &s.da, len))
            .then(|| shader.in_range_values(&s.a, &s.da));
            // Safe split borrow: the closures only read the shader.
            let shade = |a: &[L; N]| shader.shade_raw::<T::Format>(a);
            let shade_inr = |a: &[L; N]| shader.shade_raw_in_range::<T::Format>(a);
            let (target, depth, drawn) = (
                &mut *self.target,
                self.depth.as_deref_mut(),
                &mut self.drawn,
            );
            fill_span::<L, N, T, D>(target, depth, drawn, s, &shade, inr.as_ref(), &shade_inr);
        }
    }
}

impl<T: Target, D: DepthFormat, S> Fill<'_, '_, '_, T, D, S> {
    /// Rasterizes one triangle into this span stage (see
    /// [`draw_triangle`](super::draw_triangle)).
    ///
    /// # Errors
    /// As [`draw_triangle`](super::draw_triangle).
    pub fn draw<L: Lerp, const N: usize>(
        &mut self,
        tri: &[super::Vertex<L, N>; 3],
        sub: super::SubpixelBits,
    ) -> Result<(), RasterError>
    where
        S: Shader<L, N>,
    {
        let w = self.window();
        super::draw_triangle(tri, sub, w, self)
    }
}

/// Spans shorter than this take the clamping depth loop without the
/// per-span range check: on a few pixels the check costs more than the
/// clamps it saves (the same bytes either way). bunny-gouraud raster
/// (about 2.5 pixels per span): M4 3.171 -> 3.132 M instructions, M0
/// 5.149 -> 5.108 M; 4 to 6 are within 0.1 % of each other.
const SHORT_SPAN: u32 = 5;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::target::Rgb565Be;

    /// Every level of a span for which [`levels_in_range`] holds, stepped
    /// as the span loop steps it: the unclamped colour equals the clamped
    /// one, and the values do not wrap.
    fn check(v: i32, s: i32, n: u32) -> bool {
        let ok = levels_in_range(v, s, n);
        if ok {
            let mut a = v;
            let ([mut ia], [is]) = Shader::<i32, 1>::in_range_values(&GouraudMono, &[v], &[s]);
            for k in 0..n {
                let exact = v as i64 + s as i64 * k as i64;
                assert_eq!(a as i64, exact, "wrapped: {v} {s} {n} at {k}");
                let l = (exact + (1 << 15)) >> 16;
                assert!((0..=255).contains(&l), "level {l}: {v} {s} {n} at {k}");
                assert_eq!(
                    GouraudMono.shade_raw_in_range::<Rgb565Be>(&[ia]),
                    Shader::<i32, 1>::shade_raw::<Rgb565Be>(&GouraudMono, &[a])
                );
                a = a.add(s);
                ia = ia.add(is);
            }
        }
        ok
    }

    #[test]
    fn gouraud_levels_in_range_need_no_clamp() {
        // The span table's Gouraud span: level 40, +1/4 a pixel.
        assert!(check(40 << 16, 1 << 14, 200));
        // Both ends exactly at the rounding limits: -0.5 and 255.5 - 2^-16.
        assert!(check(-(1 << 15), 0, 1));
        assert!(check((255 << 16) + (1 << 15) - 1, 0, 1));
        assert!(!check(-(1 << 15) - 1, 0, 1));
        assert!(!check((255 << 16) + (1 << 15), 0, 1));
        // Up to level 255.499 and down to level 0 at the last pixel.
        assert!(check(0, (255 << 16) / 199, 200));
        assert!(check(
            (255 << 16) + (1 << 15) - 1,
            -((255 << 16) / 199),
            200
        ));
        // One step past the end: 250 + 9 (the 10th pixel) is 259.
        assert!(!check(250 << 16, 1 << 16, 10));
        assert!(!check(5 << 16, -(1 << 16), 10));
        // Steps beyond the bounds (conservative) and an empty span.
        assert!(!check(0, 1 << 23, 2));
        assert!(check(0, (1 << 23) - 1, 2));
        assert!(!check(0, 1 << 15, 1 << 16));
        assert!(!check(0, 0, 0));
        // Random spans, near and far from the bounds.
        let mut next = super::super::tests::xorshift(0x2545_f491_4f6c_dd1d);
        let mut taken = 0;
        for i in 0..20_000 {
            let r = next();
            let v = (r as i32) >> (r >> 59);
            let s = ((r >> 32) as i32) >> ((r >> 40) % 32);
            let n = (next() % if i % 2 == 0 { 300 } else { 70_000 }) as u32;
            taken += check(v, s, n) as u32;
        }
        assert!(taken > 100, "{taken}");
    }
}
