//! The Phong illumination model at one point.
//!
//! ```text
//! I = Ia·ka·C + Σ_lights Ip·Lc·( kd·max(0, N·L)·C + ks·S )
//! S = max(0, R·V)^n   (Phong, R = 2(N·L)N - L)   or   max(0, N·H)^n   (Blinn, H = (L+V)/|L+V|)
//! ```
//!
//! `C` is the material colour, `Lc` the light colour; the specular term
//! takes the *light's* colour, so a red object under a white light gets a
//! white highlight. The specular term is counted only where `N·L > 0`.
//! At shininess 0 it is `max(0, R·V)^0 = 1` there, also where `R·V <= 0`
//! (`0^0 = 1`, as [`Real::powf`] defines it): one rule in the core's
//! profiles (the span kernel leaves shininess below 1 to this code), the
//! ideal renderer (`f64::powf`) and the tests' `f64` reference
//! (`tests/common/mod.rs`, `phong_f64`; the case `N·L > 0 > R·V` at `n = 0`
//! is in `tests/bad_input.rs`).
//! Each channel is clamped to `[0, 1]` after the summation. `L` points
//! from the shaded point to the light (point light) or is the light's
//! direction (directional light); `V` points to the eye (local viewer) or
//! is `(0, 0, 1)` in eye space (viewer at infinity).
//!
//! Everything is in eye space. [`Shade`] folds material and lights into a
//! few products once per object, so a pixel costs the dot products, one
//! normalisation per point light, and a power only when `ks > 0`.
//!
//! Degenerate inputs are defined: a zero normal (faces that cancel when
//! averaged) gives no diffuse or specular light, only ambient; a point
//! light exactly at the shaded point has `L = 0` and contributes nothing.

use crate::geom::Vec3;
use crate::num::approx16;
use crate::num::wide::wmul;
use crate::num::{Kernels, Raw16, Real};
use core::fmt;

/// Raw Q16 one.
const ONE16: i32 = 1 << 16;

/// Raw Q16 bits of a scalar, rounded (exact for `Q16`, the scalar of the
/// integer kernels, [`Q16Kernels`](crate::num::Q16Kernels)).
#[inline(always)]
fn raw<R: Real>(v: R) -> i32 {
    v.to_fixed_i32(16)
}

#[inline(always)]
fn raw3<R: Real>(v: Vec3<R>) -> [i32; 3] {
    [raw(v.x), raw(v.y), raw(v.z)]
}

/// `round(a · b / 2^16)` (ties up), saturated: the `Q16` product.
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn mul16(a: i32, b: i32) -> i32 {
    let p = (wmul(a, b) + (1 << 15)) >> 16;
    p.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

/// `round(a · b / 2^16)` for a dot product, summed exactly and rounded
/// once (ties up), saturated.
#[inline(always)]
#[allow(clippy::cast_possible_truncation)]
fn dot16(a: [i32; 3], b: [i32; 3]) -> i32 {
    let p = (wmul(a[0], b[0]) + wmul(a[1], b[1]) + wmul(a[2], b[2]) + (1 << 15)) >> 16;
    p.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32
}

use crate::num::wide::{mul16_small, SMALL};

#[inline(always)]
fn add3(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    [
        a[0].saturating_add(b[0]),
        a[1].saturating_add(b[1]),
        a[2].saturating_add(b[2]),
    ]
}

/// Which specular model.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Specular {
    /// Phong: `(R·V)^n`.
    #[default]
    Phong,
    /// Blinn-Phong: `(N·H)^n`, `H` halfway between `L` and `V`.
    Blinn,
}

/// Where the viewer is, for the specular term.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Viewer {
    /// At the eye: `V` varies over the surface (exact; costs a
    /// normalisation per point and the interpolated position in Phong
    /// shading).
    #[default]
    Local,
    /// At infinity along +z in eye space: `V` constant (cheaper).
    Infinite,
}

/// A surface material. Coefficients are clamped to `[0, 1]` and the
/// shininess to `[0, MAX_SHININESS]` when a [`Shade`] is built.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material<R> {
    /// Colour `C`, each channel in `[0, 1]`.
    pub color: Vec3<R>,
    /// Ambient reflectance.
    pub ka: R,
    /// Diffuse reflectance.
    pub kd: R,
    /// Specular reflectance.
    pub ks: R,
    /// Shininess `n`.
    pub shininess: R,
}

/// Largest shininess: 10 000 (a highlight narrower than 1/100 radian).
pub const MAX_SHININESS: i32 = 10_000;

/// Kind and place of a light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightKind<R> {
    /// A point light at a position.
    Point(Vec3<R>),
    /// A directional light; the vector points *towards* the light.
    Directional(Vec3<R>),
}

/// A light source.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Light<R> {
    /// Where it is.
    pub kind: LightKind<R>,
    /// Intensity `Ip` (scales the colour).
    pub intensity: R,
    /// Colour `Lc`, each channel in `[0, 1]`.
    pub color: Vec3<R>,
}

impl<R: Real> Light<R> {
    /// A white point light.
    pub fn point(position: Vec3<R>, intensity: R) -> Self {
        Self {
            kind: LightKind::Point(position),
            intensity,
            color: Vec3::new(R::ONE, R::ONE, R::ONE),
        }
    }

    /// A white directional light; `towards` points to the light.
    pub fn directional(towards: Vec3<R>, intensity: R) -> Self {
        Self {
            kind: LightKind::Directional(towards),
            intensity,
            color: Vec3::new(R::ONE, R::ONE, R::ONE),
        }
    }
}

/// Most lights in one [`Shade`].
pub const MAX_LIGHTS: usize = 8;

/// Why a [`Shade`] could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum IllumError {
    /// More than [`MAX_LIGHTS`] lights.
    TooManyLights,
}

impl fmt::Display for IllumError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::TooManyLights => write!(f, "at most {MAX_LIGHTS} lights are supported"),
        }
    }
}

impl core::error::Error for IllumError {}

/// One light folded with one material, in eye space.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Term<R> {
    /// Point light position, or unit direction towards the light.
    at: Vec3<R>,
    point: bool,
    /// `Ip·Lc·kd·C`.
    diffuse: Vec3<R>,
    /// `Ip·Lc·ks`.
    specular: Vec3<R>,
}

/// Material and lights folded together for fast evaluation at many points.
#[derive(Clone, Debug)]
pub struct Shade<R> {
    ambient: Vec3<R>,
    terms: heapless::Vec<Term<R>, MAX_LIGHTS>,
    shininess: R,
    has_specular: bool,
    specular: Specular,
    viewer: Viewer,
}

fn clamp01<R: Real>(v: R) -> R {
    v.clamp(R::ZERO, R::ONE)
}

fn mul3<R: Real>(a: Vec3<R>, b: Vec3<R>) -> Vec3<R> {
    Vec3::new(a.x * b.x, a.y * b.y, a.z * b.z)
}

impl<R: Real> Shade<R> {
    /// Folds a material, the ambient intensity `Ia` and the lights (already
    /// in eye space) together.
    ///
    /// # Errors
    /// [`IllumError::TooManyLights`] beyond [`MAX_LIGHTS`].
    pub fn new(
        material: &Material<R>,
        ambient: R,
        lights: &[Light<R>],
        specular: Specular,
        viewer: Viewer,
    ) -> Result<Self, IllumError> {
        let c = Vec3::new(
            clamp01(material.color.x),
            clamp01(material.color.y),
            clamp01(material.color.z),
        );
        let (ka, kd, ks) = (
            clamp01(material.ka),
            clamp01(material.kd),
            clamp01(material.ks),
        );
        let shininess = material
            .shininess
            .clamp(R::ZERO, R::from_i32(MAX_SHININESS));
        let mut terms = heapless::Vec::new();
        for l in lights {
            let lc = Vec3::new(clamp01(l.color.x), clamp01(l.color.y), clamp01(l.color.z))
                .scale(l.intensity.max(R::ZERO));
            let (at, point) = match l.kind {
                LightKind::Point(p) => (p, true),
                LightKind::Directional(d) => (d.normalize(), false),
            };
            terms
                .push(Term {
                    at,
                    point,
                    diffuse: mul3(lc, c).scale(kd),
                    specular: lc.scale(ks),
                })
                .map_err(|_| IllumError::TooManyLights)?;
        }
        Ok(Self {
            ambient: c.scale(clamp01(ambient) * ka),
            terms,
            shininess,
            has_specular: ks > R::ZERO,
            specular,
            viewer,
        })
    }

    /// `true` when some light is a point light (the shaded position is
    /// needed), or the viewer is local.
    pub fn needs_position(&self) -> bool {
        self.viewer == Viewer::Local || self.terms.iter().any(|t| t.point)
    }

    /// `true` when [`Shade::at`]'s result depends on the shaded position:
    /// a point light, or a specular term with a local viewer (unlike
    /// [`Shade::needs_position`], a local viewer without a specular term
    /// does not count).
    pub(crate) fn uses_position(&self) -> bool {
        (self.has_specular && self.viewer == Viewer::Local) || self.terms.iter().any(|t| t.point)
    }

    /// `true` when the specular term is computed (`ks > 0` and a light).
    pub fn has_specular(&self) -> bool {
        self.has_specular && !self.terms.is_empty()
    }

    /// The colour at eye-space point `p` with unit normal `n`, each channel
    /// clamped to `[0, 1]`.
    ///
    /// For `Q16` ([`Q16Kernels`](crate::num::Q16Kernels)) without a specular term the
    /// diffuse sum runs on raw integers with 32-bit products, bit for bit
    /// the generic result. (Vertex and face lighting keep the generic
    /// path with a specular term: `Shade::at_q16` there moved
    /// `dodeca-flat-n100`'s mean error against the `f64` twin to 0.14
    /// level, above its 0.08 budget; the per-pixel Phong shader uses it.)
    ///
    /// Out of line: one call per vertex or face, and its callers keep
    /// their registers (inlined, it cost the `fast` face colour 9
    /// instructions a face).
    #[inline(never)]
    pub fn at(&self, n: Vec3<R>, p: Vec3<R>) -> Vec3<R> {
        R::Kernels::pick(|q| self.at_q16_diffuse(q, &n, &p), || self.at_generic(n, p))
    }

    /// [`Shade::at`] for `Q16`: the diffuse sum by [`Shade::diffuse_q16`]
    /// where it answers, else the generic code. (The vectors by
    /// reference: by value, they cost the `fast` vertex colour of
    /// `dodeca-gouraud-n100` 100 instructions on the M4.)
    #[inline(always)]
    fn at_q16_diffuse(&self, q: Raw16<R>, n: &Vec3<R>, p: &Vec3<R>) -> Vec3<R> {
        let (n, p) = (*n, *p);
        if !self.has_specular {
            if let Some(c) = self.diffuse_q16(raw3(n), p) {
                return Vec3::new(q.from_raw(c[0]), q.from_raw(c[1]), q.from_raw(c[2]));
            }
        }
        self.at_generic(n, p)
    }

    /// [`Shade::at`] without a specular term, for `Q16` on raw values
    /// with 32-bit products ([`mul16_small`]): bit for bit the generic
    /// path's result (the same products, rounded alike, and sums too small
    /// to saturate), or `None` (the generic path then runs) when an
    /// operand is out of [`mul16_small`]'s range: a component of `n`, of a
    /// light direction or of `N·L` above 2, or a diffuse product
    /// `Ip·Lc·kd·C` of 256 or more.
    #[inline]
    fn diffuse_q16(&self, n: [i32; 3], p: Vec3<R>) -> Option<[i32; 3]> {
        let big = |v: [i32; 3], lim: u32| v.iter().any(|c| c.unsigned_abs() > lim);
        if big(n, SMALL) {
            return None;
        }
        let mut sum = raw3(self.ambient);
        for t in &self.terms {
            let l = raw3(if t.point {
                (t.at - p).normalize_geom()
            } else {
                t.at
            });
            if big(l, SMALL) {
                return None;
            }
            // Each product below 2^18: the sum cannot saturate.
            let nl = mul16_small(n[0], l[0]) + mul16_small(n[1], l[1]) + mul16_small(n[2], l[2]);
            if nl <= 0 {
                continue;
            }
            let d = raw3(t.diffuse);
            if nl.unsigned_abs() > SMALL || big(d, (1 << 24) - 1) {
                return None;
            }
            sum = add3(
                sum,
                [
                    mul16_small(d[0], nl),
                    mul16_small(d[1], nl),
                    mul16_small(d[2], nl),
                ],
            );
        }
        Some(sum.map(|c| c.clamp(0, ONE16)))
    }

    /// [`Shade::at`] by the generic scalar code.
    fn at_generic(&self, n: Vec3<R>, p: Vec3<R>) -> Vec3<R> {
        let mut sum = self.ambient;
        // V only matters for the specular term: no normalisation without it.
        let v = match (self.has_specular, self.viewer) {
            (false, _) => Vec3::ZERO,
            (true, Viewer::Local) => (-p).normalize(),
            (true, Viewer::Infinite) => Vec3::new(R::ZERO, R::ZERO, R::ONE),
        };
        for t in &self.terms {
            let l = if t.point {
                (t.at - p).normalize()
            } else {
                t.at
            };
            let nl = n.dot(l);
            if nl <= R::ZERO {
                continue;
            }
            sum = sum + t.diffuse.scale(nl);
            if self.has_specular {
                let base = match self.specular {
                    Specular::Phong => {
                        // R·V = 2(N·L)(N·V) - L·V, R = 2(N·L)N - L.
                        (nl + nl) * n.dot(v) - l.dot(v)
                    }
                    Specular::Blinn => n.dot((l + v).normalize()),
                };
                if base > R::ZERO {
                    sum = sum + t.specular.scale(base.min(R::ONE).powf(self.shininess));
                } else if self.shininess == R::ZERO {
                    // max(0, base)^0 = 0^0 = 1, as `Real::powf` defines it.
                    sum = sum + t.specular;
                }
            }
        }
        Vec3::new(clamp01(sum.x), clamp01(sum.y), clamp01(sum.z))
    }

    /// [`Shade::at`] on raw Q16 values (unit normal `n`, eye-space `p`);
    /// channels in `[0, 2^16]`. Dot products are summed exactly and
    /// rounded once (<= 1/2 ulp, where the generic path rounds each
    /// product), light and view vectors normalised by `approx16::unit`
    /// (within 2^-15 per component), the specular power by
    /// `approx16::pow` (2^-14.79 measured, the `Q16` `powf`). Tested
    /// against `f64` on the same inputs, highlight peaks included: within
    /// 4 levels (of 255) per channel up to shininess 100, 12 up to 800
    /// (the generic path: 5.8 and 32 on the same inputs).
    pub(crate) fn at_q16(&self, n: [i32; 3], p: [i32; 3]) -> [i32; 3] {
        let mut sum = raw3(self.ambient);
        let v = match (self.has_specular, self.viewer) {
            (false, _) => [0; 3],
            (true, Viewer::Local) => approx16::unit(p.map(i32::saturating_neg)),
            (true, Viewer::Infinite) => [0, 0, ONE16],
        };
        for t in &self.terms {
            let at = raw3(t.at);
            let l = if t.point {
                approx16::unit([
                    at[0].saturating_sub(p[0]),
                    at[1].saturating_sub(p[1]),
                    at[2].saturating_sub(p[2]),
                ])
            } else {
                at
            };
            let nl = dot16(n, l);
            if nl <= 0 {
                continue;
            }
            let d = raw3(t.diffuse);
            sum = add3(sum, [mul16(d[0], nl), mul16(d[1], nl), mul16(d[2], nl)]);
            if self.has_specular {
                let base = match self.specular {
                    Specular::Phong => {
                        mul16(nl.saturating_add(nl), dot16(n, v)).saturating_sub(dot16(l, v))
                    }
                    Specular::Blinn => dot16(n, approx16::unit(add3(l, v))),
                };
                let sp = raw3(t.specular);
                if base > 0 {
                    let f = approx16::pow(base.min(ONE16), raw(self.shininess));
                    sum = add3(sum, [mul16(sp[0], f), mul16(sp[1], f), mul16(sp[2], f)]);
                } else if self.shininess == R::ZERO {
                    sum = add3(sum, sp);
                }
            }
        }
        sum.map(|c| c.clamp(0, ONE16))
    }
}

/// Directional lights without a specular term, moved into one object's
/// space once per object ([`Shade::object_light`]): a vertex or face
/// colour is then `ambient + Σ diffuse · max(0, n·L')` with `n` the stored
/// Q1.14 unit normal, three multiply-adds per light and no normalisation.
///
/// For a model-view linear part `M = s·Q` (uniform scale `s`, `Q`
/// orthogonal), the eye-space unit normal is `Q n` and `Q n · L = n · Qᵀ L`,
/// so `L' = Mᵀ L / s`. For `Q16` `L'` is kept in Q1.14 (`l14`, within
/// `2^-15` per component after the rounded products) and `n · L'` summed
/// exactly in 32 bits (three products below `2^29`), rounded once to Q16:
/// `N·L` within `2^-13` of the exact renormalised eye-space product of
/// the same normal under the same matrix (0.031 of a level; measured
/// `2^-13.2` by `object_light_q16_within_its_bound`). A `Q16` matrix whose
/// Gram matrix misses the uniform test (scales below about 0.3, where its
/// entries keep too few bits) is lit in eye space instead.
#[derive(Clone, Debug)]
pub(crate) struct ObjectLight<R> {
    ambient: Vec3<R>,
    terms: heapless::Vec<ObjTerm<R>, MAX_LIGHTS>,
}

/// Whether a component of `v` (raw Q16) exceeds `lim` in magnitude.
fn big3<R: Real>(v: Vec3<R>, lim: u32) -> bool {
    raw3(v).iter().any(|c| c.unsigned_abs() > lim)
}

#[derive(Clone, Copy, Debug)]
struct ObjTerm<R> {
    /// `L'` (generic path).
    l: Vec3<R>,
    /// `L'` in Q1.14 (`Q16` path).
    l14: [i32; 3],
    /// `Ip·Lc·kd·C`.
    diffuse: Vec3<R>,
}

impl<R: Real> Shade<R> {
    /// The object-space form of these lights for an object whose
    /// model-view linear part is `k · s` with `k` of orthogonal columns of
    /// length `s` (see [`Mat3::normal_matrix`](crate::geom::Mat3)), or
    /// `None` when a point light or a specular term needs eye-space
    /// positions (the caller then lights in eye space).
    pub(crate) fn object_light(&self, k: &crate::geom::Mat3<R>, s: R) -> Option<ObjectLight<R>> {
        if self.has_specular || self.terms.iter().any(|t| t.point) || s <= R::ZERO {
            return None;
        }
        let kt = k.transpose();
        let mut terms = heapless::Vec::new();
        for t in &self.terms {
            // The Q16 products `diffuse · N·L` by `mul16_small`: diffuse
            // below 256 (else the eye-space path lights the object).
            if R::Kernels::pick(|_| big3(t.diffuse, (1 << 24) - 1), || false) {
                return None;
            }
            let l = kt.apply(t.at);
            let l = Vec3::new(l.x.div(s), l.y.div(s), l.z.div(s));
            // |L'| ≈ 1: the Q1.14 components fit easily.
            let l14 = [l.x, l.y, l.z].map(|c| c.to_fixed_i32(14).clamp(-(1 << 15), 1 << 15));
            terms
                .push(ObjTerm {
                    l,
                    l14,
                    diffuse: t.diffuse,
                })
                .ok()?;
        }
        Some(ObjectLight {
            ambient: self.ambient,
            terms,
        })
    }
}

impl<R: Real> ObjectLight<R> {
    /// `N·L'` of Q1.14 normal `n` (reversed when `flip`).
    #[inline(always)]
    fn nl(t: &ObjTerm<R>, n: [i16; 3], flip: bool) -> R {
        let nl = R::Kernels::pick(
            |q| {
                // |n_k| <= 2^15, |l14_k| <= 2^14 (unit L'): each product
                // below 2^29 and the sum below 3 · 2^29 (no overflow).
                let l = t.l14;
                let s = i32::from(n[0]) * l[0] + i32::from(n[1]) * l[1] + i32::from(n[2]) * l[2];
                // Q28 to Q16, rounded (ties up).
                q.from_raw((s + (1 << 11)) >> 12)
            },
            || Vec3::from_q14(n).dot(t.l),
        );
        if flip {
            -nl
        } else {
            nl
        }
    }

    /// The colour, each channel clamped to `[0, 1]`, of a surface with
    /// object-space Q1.14 unit normal `n` (reversed when `flip`); only the
    /// first channel when `mono` (the others are then copies of it).
    #[inline]
    pub(crate) fn at(&self, n: [i16; 3], flip: bool, mono: bool) -> Vec3<R> {
        let mut sum = self.ambient;
        for t in &self.terms {
            let nl = Self::nl(t, n, flip);
            if nl <= R::ZERO {
                continue;
            }
            // The term `diffuse · N·L` (only its first channel when
            // `mono`): for `Q16` in 32-bit products, bit for bit `*`
            // (|diffuse| < 2^24 checked when built, |N·L| <= 2^17 for unit
            // vectors), where `N·L` is in that range.
            let generic = || {
                if mono {
                    Vec3::new(t.diffuse.x * nl, R::ZERO, R::ZERO)
                } else {
                    t.diffuse.scale(nl)
                }
            };
            let term = R::Kernels::pick(
                |q| {
                    let nlr = q.raw(nl);
                    if nlr.unsigned_abs() > SMALL {
                        return generic();
                    }
                    let d = raw3(t.diffuse);
                    let p = |c: i32| q.from_raw(mul16_small(c, nlr));
                    if mono {
                        Vec3::new(p(d[0]), R::ZERO, R::ZERO)
                    } else {
                        Vec3::new(p(d[0]), p(d[1]), p(d[2]))
                    }
                },
                generic,
            );
            if mono {
                sum.x += term.x;
            } else {
                sum = sum + term;
            }
        }
        if mono {
            let x = clamp01(sum.x);
            Vec3::new(x, x, x)
        } else {
            Vec3::new(clamp01(sum.x), clamp01(sum.y), clamp01(sum.z))
        }
    }
}

impl<R: Real> ObjectLight<R> {
    /// The integer form of these `Q16` lights (`q`: the raw access that
    /// [`Kernels`](crate::num::Kernels) hands out for `Q16` only) for the
    /// `fast` vertex kernel: colour levels (Q16, `255 = 255 · 2^16`)
    /// straight from a Q1.14 normal, or `None` unless every diffuse
    /// factor is below `2^8 / 255 ≈ 1.004` (brighter lights use
    /// [`ObjectLight::at`]).
    pub(crate) fn levels(&self, q: Raw16<R>) -> Option<LevelLight> {
        let raw3 = |v: Vec3<R>| [q.raw(v.x), q.raw(v.y), q.raw(v.z)];
        #[allow(clippy::cast_possible_truncation)]
        let ambient =
            raw3(self.ambient).map(|a| (i64::from(a) * 255).clamp(-(1 << 29), 1 << 29) as i32);
        let mut terms = heapless::Vec::new();
        for t in &self.terms {
            // dq = round(diffuse · 255 · 2^8), below 2^16.
            let dq = raw3(t.diffuse).map(|c| (i64::from(c) * 255 + (1 << 7)) >> 8);
            if dq.iter().any(|v| v.unsigned_abs() >= 1 << 16) {
                return None;
            }
            #[allow(clippy::cast_possible_truncation)]
            terms
                .push(LevelTerm {
                    l14: t.l14,
                    dq: dq.map(|v| v as i32),
                })
                .ok()?;
        }
        Some(LevelLight { ambient, terms })
    }
}

/// [`ObjectLight`] as integers ([`ObjectLight::levels`]): a colour level
/// per channel is `ambient + Σ max(0, n·L') · dq >> 6`, with `n·L'` the
/// exact 32-bit sum of [`ObjectLight`] cut to Q1.14 (at most `2^15`).
///
/// Error against [`ObjectLight::at`]'s exact value `255 · (ambient + Σ
/// diffuse · max(0, n·L'))` before clamping: per light, the cut of `n·L'`
/// (`2^-14`, times `255 · diffuse <= 256`: `2^-6` level), the rounding of
/// `dq` (`1/2 · 2^15 / 2^6` Q16, `2^-8` level) and of the shift (`2^-16`
/// level): within `0.02` level per light (tested by
/// `level_light_within_its_bound`).
#[derive(Clone, Debug)]
pub(crate) struct LevelLight {
    ambient: [i32; 3],
    terms: heapless::Vec<LevelTerm, MAX_LIGHTS>,
}

#[derive(Clone, Copy, Debug)]
struct LevelTerm {
    l14: [i32; 3],
    dq: [i32; 3],
}

impl LevelLight {
    /// The colour levels (Q16, clamped to `[0, 255 · 2^16]`) of Q1.14
    /// normal `n`; only the first channel when `MONO`.
    #[inline(always)]
    pub(crate) fn at<const MONO: bool>(&self, n: [i16; 3]) -> [i32; 3] {
        let mut sum = self.ambient;
        let n = n.map(i32::from);
        for t in &self.terms {
            // |n_k| <= 2^15, |l14_k| <= 2^14: below 3 · 2^29.
            let nl = n[0] * t.l14[0] + n[1] * t.l14[1] + n[2] * t.l14[2];
            if nl <= 0 {
                continue;
            }
            // nl14 <= 2^15, |dq| < 2^16: the products fit.
            let nl14 = (nl >> 14).min(1 << 15);
            sum[0] += (nl14 * t.dq[0]) >> 6;
            if !MONO {
                sum[1] += (nl14 * t.dq[1]) >> 6;
                sum[2] += (nl14 * t.dq[2]) >> 6;
            }
        }
        sum.map(|v| v.clamp(0, 255 << 16))
    }

    /// The lights when there is exactly one (the common case: its
    /// constants stay in registers across a vertex loop).
    pub(crate) fn one(&self) -> Option<OneLight> {
        match self.terms.as_slice() {
            [t] => Some(OneLight {
                ambient: self.ambient,
                t: *t,
            }),
            _ => None,
        }
    }
}

/// A [`LevelLight`] of one light: the same values.
#[derive(Clone, Copy, Debug)]
pub(crate) struct OneLight {
    ambient: [i32; 3],
    t: LevelTerm,
}

impl OneLight {
    /// [`LevelLight::at`], bit for bit.
    #[inline(always)]
    pub(crate) fn at<const MONO: bool>(&self, n: [i16; 3]) -> [i32; 3] {
        let (t, n) = (&self.t, n.map(i32::from));
        let nl = n[0] * t.l14[0] + n[1] * t.l14[1] + n[2] * t.l14[2];
        let nl14 = if nl <= 0 { 0 } else { (nl >> 14).min(1 << 15) };
        let mut sum = self.ambient;
        sum[0] += (nl14 * t.dq[0]) >> 6;
        if !MONO {
            sum[1] += (nl14 * t.dq[1]) >> 6;
            sum[2] += (nl14 * t.dq[2]) >> 6;
        }
        sum.map(|v| v.clamp(0, 255 << 16))
    }

    /// Whether [`OneLight::at_bounded`] equals [`OneLight::at`] for every
    /// normal of squared length at most `n2` (raw Q1.14): `N·L <= |N| |L|
    /// < 2^29` (Cauchy-Schwarz, checked as `n2 |L|² < 2^58`) keeps `N·L >>
    /// 14` below `2^15` (the `min` idle), and a light and ambient term of
    /// no negative channel keep every sum at least 0 (the lower clamp
    /// idle).
    pub(crate) fn bounded(&self, n2: i64) -> bool {
        let t = &self.t;
        let l2: i64 = t.l14.iter().map(|&v| i64::from(v) * i64::from(v)).sum();
        i128::from(n2.max(0)) * i128::from(l2) < 1i128 << 58
            && self.ambient.iter().all(|&a| a >= 0)
            && t.dq.iter().all(|&d| d >= 0)
    }

    /// [`OneLight::at`] without the clamps that [`OneLight::bounded`]
    /// proves idle: the same values for every normal it covers.
    #[inline(always)]
    pub(crate) fn at_bounded<const MONO: bool>(&self, n: [i16; 3]) -> [i32; 3] {
        let (t, n) = (&self.t, n.map(i32::from));
        let nl = n[0] * t.l14[0] + n[1] * t.l14[1] + n[2] * t.l14[2];
        // Below 2^29 (`bounded`): at most 2^15.
        let nl14 = nl.max(0) >> 14;
        let mut sum = self.ambient;
        sum[0] += (nl14 * t.dq[0]) >> 6;
        if !MONO {
            sum[1] += (nl14 * t.dq[1]) >> 6;
            sum[2] += (nl14 * t.dq[2]) >> 6;
        }
        // At least 0 (`bounded`).
        sum.map(|v| v.min(255 << 16))
    }
}

/// One light of a [`Shade`] as raw `Q16` bits, for the Phong span kernel
/// (`render::phong_span`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct RawTerm {
    /// Point light position, or unit direction towards the light (Q16).
    pub(crate) at: [i32; 3],
    /// A point light.
    pub(crate) point: bool,
    /// `Ip·Lc·kd·C` (Q16).
    pub(crate) diffuse: [i32; 3],
    /// `Ip·Lc·ks` (Q16).
    pub(crate) specular: [i32; 3],
}

/// A [`Shade`] as raw `Q16` bits ([`Shade::raw_q16`]): ambient, lights,
/// shininess (Q16), whether the specular term is on, its model and the
/// viewer.
pub(crate) type RawShade = (
    [i32; 3],
    heapless::Vec<RawTerm, MAX_LIGHTS>,
    i32,
    bool,
    Specular,
    Viewer,
);

impl<R: Real> Shade<R> {
    /// The folded material and lights of a `Q16` shade as raw bits (`q`:
    /// the raw access that [`Kernels`](crate::num::Kernels) hands out for
    /// `Q16` only): ambient, lights, shininess (Q16), whether the
    /// specular term is on, its model and the viewer.
    pub(crate) fn raw_q16(&self, q: Raw16<R>) -> RawShade {
        let raw3 = |v: Vec3<R>| [q.raw(v.x), q.raw(v.y), q.raw(v.z)];
        let mut terms = heapless::Vec::new();
        for t in &self.terms {
            // Never fails: as many terms as `self.terms` holds.
            let _ = terms.push(RawTerm {
                at: raw3(t.at),
                point: t.point,
                diffuse: raw3(t.diffuse),
                specular: raw3(t.specular),
            });
        }
        (
            raw3(self.ambient),
            terms,
            q.raw(self.shininess),
            self.has_specular(),
            self.specular,
            self.viewer,
        )
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::{
        mul16, mul16_small, raw3, LevelLight, LevelTerm, Light, Material, OneLight, Shade,
        Specular, Viewer, SMALL,
    };
    use crate::geom::Vec3;
    use crate::num::{Real, Q16};

    /// Uniform values in `[lo, hi)` from a [`xorshift`] sequence.
    fn range(mut st: u64) -> impl FnMut(f64, f64) -> f64 {
        move |lo, hi| {
            let r = xorshift(&mut st);
            lo + (hi - lo) * ((r >> 11) as f64 / (1u64 << 53) as f64)
        }
    }

    fn xorshift(s: &mut u64) -> u64 {
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        *s
    }

    #[test]
    fn mul16_small_matches_mul16() {
        let mut s = 0x1357_9bdf_2468_ace0u64;
        let a_lim = (1i64 << 24) - 1;
        let b_lim = i64::from(SMALL);
        let edges_a = [0, 1, -1, 0xFFFF, -0xFFFF, 0x8000, -0x8000, a_lim, -a_lim];
        let edges_b = [0, 1, -1, 0xFFFF, 0x1_0000, -0x1_0000, b_lim, -b_lim, 0x8000];
        for &a in &edges_a {
            for &b in &edges_b {
                let (a, b) = (a as i32, b as i32);
                assert_eq!(mul16_small(a, b), mul16(a, b), "{a} {b}");
            }
        }
        for _ in 0..1_000_000 {
            let r = xorshift(&mut s);
            let a = ((r >> 32) % (2 * a_lim as u64 + 1)) as i64 - a_lim;
            let b = ((r & 0xFFFF_FFFF) % (2 * b_lim as u64 + 1)) as i64 - b_lim;
            let (a, b) = (a as i32, b as i32);
            assert_eq!(mul16_small(a, b), mul16(a, b), "{a} {b}");
        }
    }

    /// The 32-bit diffuse path, called directly, gives the generic path's
    /// bits whenever it answers, and answers for most inputs (it declines
    /// only out-of-range operands: big normals and huge intensities).
    #[test]
    fn diffuse_q16_matches_generic() {
        let (mut taken, mut total, mut declined_in_range) = (0usize, 0usize, 0usize);
        let mut s = 0xdead_beef_1234_5678u64;
        let mut f = |lo: f64, hi: f64| {
            lo + (hi - lo) * ((xorshift(&mut s) >> 11) as f64 / (1u64 << 53) as f64)
        };
        for i in 0..3000 {
            let v3 = |f: &mut dyn FnMut(f64, f64) -> f64, lo: f64, hi: f64| {
                Vec3::<Q16>::new(
                    Q16::from_f64(f(lo, hi)),
                    Q16::from_f64(f(lo, hi)),
                    Q16::from_f64(f(lo, hi)),
                )
            };
            let mat = Material {
                color: v3(&mut f, 0.0, 1.0),
                ka: Q16::from_f64(f(0.0, 1.0)),
                kd: Q16::from_f64(f(0.0, 1.0)),
                ks: Q16::ZERO,
                shininess: Q16::from_f64(f(0.0, 100.0)),
            };
            let mut lights = [Light::directional(v3(&mut f, -1.0, 1.0), Q16::ONE); 3];
            for l in &mut lights {
                if f(0.0, 1.0) < 0.5 {
                    *l = Light::point(v3(&mut f, -50.0, 50.0), Q16::ONE);
                }
                // Intensities up to 400: some diffuse products out of range.
                l.intensity = Q16::from_f64(f(0.0, if i % 10 == 0 { 400.0 } else { 3.0 }));
                l.color = v3(&mut f, 0.0, 1.0);
            }
            let nl = 1 + i % 3;
            let shade = Shade::new(
                &mat,
                Q16::from_f64(f(0.0, 1.0)),
                &lights[..nl],
                Specular::Phong,
                Viewer::Local,
            )
            .unwrap();
            for _ in 0..20 {
                // Unit normals, and a few beyond the fast path's range.
                let span = if i % 7 == 0 { 3.0 } else { 1.0 };
                let n = v3(&mut f, -span, span);
                let n = if span == 1.0 { n.normalize() } else { n };
                let p = v3(&mut f, -20.0, 20.0);
                let generic = shade.at_generic(n, p);
                assert_eq!(shade.at(n, p), generic, "{n:?} {p:?}");
                total += 1;
                match shade.diffuse_q16(raw3(n), p) {
                    Some(c) => {
                        taken += 1;
                        let c = c.map(|v| Q16::from_fixed_i32(v, 16));
                        assert_eq!(Vec3::new(c[0], c[1], c[2]), generic, "{n:?} {p:?}");
                    }
                    None => declined_in_range += usize::from(span == 1.0 && i % 10 != 0),
                }
            }
        }
        std::println!(
            "diffuse_q16: {taken} of {total} taken, {declined_in_range} declined in range"
        );
        // 1 in 7 objects has big normals and 1 in 10 huge intensities;
        // every other sample takes the fast path (measured: 53 741 of the
        // 60 000 in all).
        assert_eq!(declined_in_range, 0);
        assert!(taken * 100 >= total * 85, "{taken} of {total}");
    }

    /// `at_q16` (the `Fast` per-pixel Phong path) against the same model
    /// in `f64` for the same `Q16` inputs: random materials, one or two
    /// point or directional lights, Phong and Blinn, local and infinite
    /// viewer; a third of the normals near the highlight's peak, where
    /// `x^n` multiplies the base's error by up to `n/e`. Bound per channel:
    /// 4 levels up to shininess 100, 12 up to 800 (measured 3.41 and
    /// 10.56; the generic `Shade::at` on the same inputs: 5.83 and 32.4).
    #[test]
    fn at_q16_against_f64() {
        let mut s = 0x0123_4567_89ab_cdefu64;
        let mut f = |lo: f64, hi: f64| {
            lo + (hi - lo) * ((xorshift(&mut s) >> 11) as f64 / (1u64 << 53) as f64)
        };
        let mut worst = [0f64; 2];
        let mut generic = [0f64; 2];
        for i in 0..4000 {
            let q = |v: f64| Q16::from_f64(v);
            let v3 = |f: &mut dyn FnMut(f64, f64) -> f64, lo: f64, hi: f64| {
                Vec3::new(q(f(lo, hi)), q(f(lo, hi)), q(f(lo, hi)))
            };
            let to64 = |v: Vec3<Q16>| Vec3::new(v.x.to_f64(), v.y.to_f64(), v.z.to_f64());
            let high = i % 4 == 0;
            let mat = Material {
                color: v3(&mut f, 0.0, 1.0),
                ka: q(f(0.0, 1.0)),
                kd: q(f(0.0, 1.0)),
                ks: q(f(0.0, 1.0)),
                shininess: q(f(1.0, if high { 800.0 } else { 100.0 })),
            };
            let mut lights = [Light::directional(v3(&mut f, -1.0, 1.0), Q16::ONE); 2];
            for l in &mut lights {
                if f(0.0, 1.0) < 0.5 {
                    *l = Light::point(v3(&mut f, -30.0, 30.0), Q16::ONE);
                }
                l.intensity = q(f(0.0, 1.0));
                l.color = v3(&mut f, 0.0, 1.0);
            }
            let nl = 1 + i % 2;
            let specular = if i % 3 == 0 {
                Specular::Blinn
            } else {
                Specular::Phong
            };
            let viewer = if i % 5 == 0 {
                Viewer::Infinite
            } else {
                Viewer::Local
            };
            let ambient = q(f(0.0, 0.5));
            let fixed = Shade::new(&mat, ambient, &lights[..nl], specular, viewer).unwrap();
            let mat64 = Material {
                color: to64(mat.color),
                ka: mat.ka.to_f64(),
                kd: mat.kd.to_f64(),
                ks: mat.ks.to_f64(),
                shininess: mat.shininess.to_f64(),
            };
            let lights64 = lights.map(|l| Light {
                kind: match l.kind {
                    super::LightKind::Point(p) => super::LightKind::Point(to64(p)),
                    super::LightKind::Directional(d) => super::LightKind::Directional(to64(d)),
                },
                color: to64(l.color),
                intensity: l.intensity.to_f64(),
            });
            let float =
                Shade::new(&mat64, ambient.to_f64(), &lights64[..nl], specular, viewer).unwrap();
            for k in 0..25 {
                let p = v3(&mut f, -20.0, 20.0);
                let n = if k % 3 == 0 {
                    // Near the highlight's peak (halfway between L and V,
                    // slightly perturbed), where x^n amplifies errors most.
                    let l = match lights[0].kind {
                        super::LightKind::Point(at) => (at - p).normalize(),
                        super::LightKind::Directional(d) => d.normalize(),
                    };
                    let v = match viewer {
                        Viewer::Local => (-p).normalize(),
                        Viewer::Infinite => Vec3::new(Q16::ZERO, Q16::ZERO, Q16::ONE),
                    };
                    (l + v + v3(&mut f, -0.05, 0.05)).normalize()
                } else {
                    v3(&mut f, -1.0, 1.0).normalize()
                };
                let c = fixed.at_q16(super::raw3(n), super::raw3(p));
                let g = fixed.at_generic(n, p);
                let e = float.at(to64(n).normalize(), to64(p));
                for (k, want) in [e.x, e.y, e.z].into_iter().enumerate() {
                    let err = (f64::from(c[k]) / 65536.0 - want).abs() * 255.0;
                    let w = &mut worst[usize::from(high)];
                    *w = w.max(err);
                    let got = [g.x, g.y, g.z][k].to_f64();
                    let w = &mut generic[usize::from(high)];
                    *w = w.max((got - want).abs() * 255.0);
                }
            }
        }
        std::println!(
            "at_q16 vs f64: {:.3} levels (n <= 100), {:.3} (n <= 800); generic {:.3}, {:.3}",
            worst[0],
            worst[1],
            generic[0],
            generic[1]
        );
        assert!(worst[0] <= 4.0, "{worst:?}");
        assert!(worst[1] <= 12.0, "{worst:?}");
        // The reason the Phong pixel uses it: closer than the generic path.
        assert!(worst[0] < generic[0] && worst[1] < generic[1]);
    }

    /// [`ObjectLight`]'s `N·L` for `Q16`, against the exact renormalised
    /// eye-space product of the same Q1.14 normal under the same `Q16`
    /// model-view matrix (random rotations, uniform scales 0.5 to 200,
    /// random light directions): within `2^-13` (0.031 of a level).
    /// [`LevelLight::at`] within 0.02 level per light of the exact
    /// `255 · (ambient + Σ diffuse · max(0, n·L'))` of the same Q1.14
    /// normal and the same `L'` (clamped to `[0, 255]`), on random lights,
    /// diffuse factors up to the accepted limit and random normals.
    #[test]
    fn level_light_within_its_bound() {
        let mut f = range(0x1e7e_1b0d);
        let mut worst = 0f64;
        for _ in 0..2000 {
            let nl = 1 + (f(0.0, 2.999) as usize);
            let mut terms = heapless::Vec::new();
            let mut exact_terms = std::vec::Vec::new();
            for _ in 0..nl {
                let v = [f(-1.0, 1.0), f(-1.0, 1.0), f(-1.0, 1.0)];
                let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(0.1);
                let l14 = v.map(|c| (c / len * 16384.0).round() as i32);
                let d = [f(0.0, 1.0), f(0.0, 1.0), f(0.0, 1.0)];
                let draw = d.map(|c| (c * 65536.0).round() as i64);
                let dq = draw.map(|c| ((c * 255 + 128) >> 8) as i32);
                terms.push(LevelTerm { l14, dq }).unwrap();
                exact_terms.push((l14, draw.map(|c| c as f64 / 65536.0)));
            }
            let amb = [f(0.0, 0.5), f(0.0, 0.5), f(0.0, 0.5)];
            let ambient = amb.map(|a| ((a * 65536.0).round() as i32) * 255);
            let ll = LevelLight { ambient, terms };
            for _ in 0..50 {
                let v = [f(-1.0, 1.0), f(-1.0, 1.0), f(-1.0, 1.0)];
                let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(0.1);
                let n = v.map(|c| (c / len * 16384.0).round() as i16);
                let got = ll.at::<false>(n);
                let mono = ll.at::<true>(n);
                assert_eq!(got[0], mono[0]);
                if let Some(one) = ll.one() {
                    assert_eq!(one.at::<false>(n), got);
                    assert_eq!(one.at::<true>(n)[0], got[0]);
                }
                for ch in 0..3 {
                    let mut e = f64::from(ambient[ch]) / 65536.0 / 255.0;
                    for (l14, d) in &exact_terms {
                        let dot = (0..3)
                            .map(|j| f64::from(n[j]) * f64::from(l14[j]))
                            .sum::<f64>()
                            / 2f64.powi(28);
                        e += d[ch] * dot.max(0.0);
                    }
                    let e = (e * 255.0).clamp(0.0, 255.0);
                    let err = (f64::from(got[ch]) / 65536.0 - e).abs() / nl as f64;
                    worst = worst.max(err);
                }
            }
        }
        std::println!("level light: worst {worst} level per light");
        assert!(worst <= 0.02, "{worst}");
    }

    /// [`OneLight::at_bounded`] equals [`OneLight::at`] whenever
    /// [`OneLight::bounded`] admits the light for normals of squared
    /// length up to [`MAX_AXIS2`](crate::mesh::MAX_AXIS2): random lights
    /// (ambient and diffuse up to 1.5, so the upper clamp is often
    /// reached), random normals of length up to 1.0002 (extreme
    /// components and the axes included); and `bounded` refuses a light
    /// whose products could leave the clamps' range.
    #[test]
    fn bounded_one_light_is_the_clamped_one() {
        use crate::mesh::MAX_AXIS2;
        let mut f = range(0x0b0d_1e55);
        let (mut lights, mut clamped) = (0, 0);
        for i in 0..400 {
            let v = [f(-1.0, 1.0), f(-1.0, 1.0), f(-1.0, 1.0)];
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(0.1);
            let l14 = v.map(|c| (c / len * 16384.0).round() as i32);
            let dq = [0; 3].map(|_| (f(0.0, 1.5) * 65536.0 * 255.0 / 256.0) as i32);
            let ambient = [0; 3].map(|_| (f(0.0, 1.5) * 65536.0) as i32 * 255 / 2);
            let one = OneLight {
                ambient,
                t: LevelTerm { l14, dq },
            };
            assert!(one.bounded(MAX_AXIS2), "light {i}");
            lights += 1;
            for k in 0..200 {
                let n: [i16; 3] = match k {
                    0..=5 => {
                        let mut n = [0i16; 3];
                        n[k % 3] = if k < 3 { 16386 } else { -16386 };
                        n
                    }
                    _ => {
                        let v = [f(-1.0, 1.0), f(-1.0, 1.0), f(-1.0, 1.0)];
                        let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                        let s = f(0.0, 1.0002) * 16384.0;
                        let n = v.map(|c| (c / len * s).round() as i16);
                        let nn: i64 = n.iter().map(|&c| i64::from(c) * i64::from(c)).sum();
                        if nn > MAX_AXIS2 {
                            continue;
                        }
                        n
                    }
                };
                let want = one.at::<false>(n);
                assert_eq!(one.at_bounded::<false>(n), want, "light {i} normal {n:?}");
                assert_eq!(one.at_bounded::<true>(n)[0], want[0]);
                clamped += usize::from(want.contains(&(255 << 16)));
            }
        }
        assert!(lights == 400 && clamped > 1000, "{lights} {clamped}");
        // Refused: a negative diffuse factor or ambient term, or normals
        // long enough for `N·L >> 14` to pass 2^15.
        let base = OneLight {
            ambient: [0; 3],
            t: LevelTerm {
                l14: [16384, 0, 0],
                dq: [100; 3],
            },
        };
        assert!(base.bounded(MAX_AXIS2));
        assert!(!base.bounded(1 << 31));
        let neg = OneLight {
            ambient: [-1, 0, 0],
            ..base
        };
        assert!(!neg.bounded(MAX_AXIS2));
        let neg_dq = OneLight {
            t: LevelTerm {
                dq: [100, -1, 100],
                ..base.t
            },
            ..base
        };
        assert!(!neg_dq.bounded(MAX_AXIS2));
    }

    #[test]
    fn object_light_q16_within_its_bound() {
        use crate::geom::Mat3;
        let mut f = range(0x000b_1ec7_5eed);
        let mut worst = 0f64;
        for _ in 0..400 {
            let a = [f(-3.0, 3.0), f(-3.0, 3.0), f(-3.0, 3.0)];
            let scale = [0.5, 1.0, 7.0, 200.0][(f(0.0, 3.999)) as usize];
            let m = Mat3::<Q16>::rotation_z(Q16::from_f64(a[2]))
                .compose(&Mat3::rotation_y(Q16::from_f64(a[1])))
                .compose(&Mat3::rotation_x(Q16::from_f64(a[0])))
                .scale(Q16::from_f64(scale));
            let (k, sk, uniform) = m.normal_matrix();
            assert!(uniform, "{a:?} {scale}");
            let l = Vec3::new(
                Q16::from_f64(f(-1.0, 1.0)),
                Q16::from_f64(f(-1.0, 1.0)),
                Q16::from_f64(f(0.1, 1.0)),
            );
            let light = Light::directional(l, Q16::ONE);
            let mat = Material {
                color: Vec3::new(Q16::ONE, Q16::ONE, Q16::ONE),
                ka: Q16::ZERO,
                kd: Q16::ONE,
                ks: Q16::ZERO,
                shininess: Q16::ONE,
            };
            let shade =
                Shade::new(&mat, Q16::ZERO, &[light], Specular::Phong, Viewer::Infinite).unwrap();
            let ol = shade.object_light(&k, sk).unwrap();
            let lf = l.to_f64();
            let ll = (lf[0] * lf[0] + lf[1] * lf[1] + lf[2] * lf[2]).sqrt();
            let mf = m.rows.map(|r| r.to_f64());
            for _ in 0..50 {
                let v = [f(-1.0, 1.0), f(-1.0, 1.0), f(-1.0, 1.0)];
                let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                if len < 0.1 {
                    continue;
                }
                let n = v.map(|c| (c / len * 16384.0).round() as i16);
                let nf = n.map(|c| f64::from(c) / 16384.0);
                let e: [f64; 3] = core::array::from_fn(|r| (0..3).map(|c| mf[r][c] * nf[c]).sum());
                let el = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]).sqrt();
                let exact = (0..3).map(|c| e[c] / el * lf[c] / ll).sum::<f64>().max(0.0);
                let got = ol.at(n, false, true).x.to_f64();
                worst = worst.max((got - exact.min(1.0)).abs());
            }
        }
        std::println!(
            "object-space N.L: worst {worst:.3e} (2^{:.2})",
            worst.log2()
        );
        assert!(worst <= 1.0 / 8192.0, "{worst}");
    }
}
