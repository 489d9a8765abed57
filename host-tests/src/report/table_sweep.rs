//! The Phong span kernel's table sizes against its accuracy: the
//! report's error-versus-size sweep (issue 15, part 4).
//!
//! The kernel (`fixshade::render::PhongKernel`) reads two tables of
//! fixed size: `1/|n|` over `|n|² ∈ [1/4, 5/4)` with
//! [`RSQRT_N`] segments (`u32` entries, in flash) and the specular table
//! `(1 - u/m)^m` with [`SPEC_SEGMENTS`] segments (`u16` entries, built in
//! the kernel when it is made for a shininess: RAM, on the stack of the
//! band renderer). [`Model`] evaluates the kernel's per-pixel arithmetic
//! for directional lights and the viewer at infinity (Duff's
//! formulation: `1/|n|` interpolated in the first table, the specular
//! base `w = Q/|n|²` looked up in the second) with tables of any size,
//! built by the core's const-generic builders
//! ([`fixshade::num::rsqrt_quarter_table`], [`fixshade::num::spec_table`]);
//! at the shipped sizes it is tested equal, pixel for pixel, to
//! `PhongKernel::begin(..).next()` (`tests` below). Where a larger table
//! needs a wider intermediate (the table position's scale
//! `m · segments · 2^24` passes 2^64 at 1024 segments and shininess
//! 10 000) the model computes it in 128 bits: the same value wherever the
//! kernel's 64 bits hold it.
//!
//! The set: the highlight-peak set of the kernel's tests (shininess 1 to
//! 10 000, Phong and Blinn, the light straight above the face and 80°
//! off, 64-pixel spans sweeping the normal across the peak), with the
//! normal at four lengths (`|n|` 1, 0.85, 0.7, 0.55: interpolated between
//! vertex normals up to 113° apart) so the `1/|n|` table is read over its
//! range. Errors are in levels of 255 against the same formula in `f64`
//! on the same normal (`Shade::at` of the `f64` twin, which is the ideal
//! renderer's formula at one point: at one pixel the two references
//! agree).
//!
//! The loop of one directional light reads `1/|n|` from its own table
//! instead ([`fixshade::num::rsqrt_pair_table`], 2 048 entries without
//! interpolation); the sweep has no row for it: [`Model`] is the general
//! kernel's arithmetic, and that table's row needs a model of the
//! one-light loop's arithmetic tested equal to the loop (docs/accuracy.md
//! gives its measured figures at 1 024, 2 048 and 4 096 entries).

use fixshade::geom::Vec3;
use fixshade::illum::{Light, Material, Shade, Specular, Viewer};
use fixshade::num::{light_halves, rsqrt_quarter_table, scale255, spec_table, unit30, Real, Q16};
use fixshade::render::{RSQRT_N, SPEC_SEGMENTS};
use maud::{html, Markup, PreEscaped};
use serde::{Deserialize, Serialize};

use super::plot::{line_svg, Series};

fn wmul(a: i32, b: i32) -> i64 {
    i64::from(a) * i64::from(b)
}

/// `round(a·b / 2^30)` summed (the kernel's `lin`).
fn lin(a: [i32; 3], b: [i32; 3]) -> i32 {
    let s = wmul(a[0], b[0])
        .wrapping_add(wmul(a[1], b[1]))
        .wrapping_add(wmul(a[2], b[2]));
    (s.wrapping_add(1 << 29) >> 30) as i32
}

/// `a × b` in Q30 (the kernel's `cross`).
fn cross(a: [i32; 3], b: [i32; 3]) -> [i32; 3] {
    let c = |x: i64| (x.wrapping_add(1 << 29) >> 30) as i32;
    [
        c(wmul(a[1], b[2]) - wmul(a[2], b[1])),
        c(wmul(a[2], b[0]) - wmul(a[0], b[2])),
        c(wmul(a[0], b[1]) - wmul(a[1], b[0])),
    ]
}

/// Entry `i` of a non-increasing table moved toward entry `i + 1` by
/// `f / 2^16` (`a - (a - b)·f >> 16`, both kernel tables' lookup), or
/// `None` past the table's end.
fn between<T: Copy + Into<u32>>(t: &[T], i: usize, f: u32) -> Option<u32> {
    let (a, b) = ((*t.get(i)?).into(), (*t.get(i + 1)?).into());
    Some(a - ((a.saturating_sub(b) * f) >> 16))
}

fn sq_sum(v: &[i32]) -> u64 {
    v.iter()
        .fold(0u64, |s, &c| s.wrapping_add(wmul(c, c) as u64))
}

/// Fraction bits of a specular table position (the kernel's `POS_FRAC`).
const POS_FRAC: u32 = 20;
/// The table's reach, `u <= 8` (Q16).
const U_MAX: u32 = 8 << 16;

/// One directional light folded as the kernel folds it.
#[derive(Clone, Debug)]
struct MLight {
    at: [i32; 3],
    p1: [i32; 3],
    p2: [i32; 3],
    d: [u32; 3],
    s: [u32; 3],
}

/// The kernel's per-pixel arithmetic for directional lights and the
/// viewer at infinity, with a `1/|n|` table of `rs.len() - 1` segments and
/// a specular table of `spec.len() - 2` (see the module docs).
#[derive(Clone, Debug)]
pub struct Model {
    rs: Vec<u32>,
    rs_shift: u32,
    spec: Vec<u16>,
    has_spec: bool,
    blinn: bool,
    amb: [u32; 3],
    lights: Vec<MLight>,
    sq: u32,
    c16: u32,
    cb: u32,
}

/// A `1/|n|` table of `seg` segments (a power of two, 16 to 1024).
pub fn rsqrt_table(seg: usize) -> Option<Vec<u32>> {
    Some(match seg {
        16 => rsqrt_quarter_table::<17>().to_vec(),
        32 => rsqrt_quarter_table::<33>().to_vec(),
        64 => rsqrt_quarter_table::<65>().to_vec(),
        128 => rsqrt_quarter_table::<129>().to_vec(),
        256 => rsqrt_quarter_table::<257>().to_vec(),
        512 => rsqrt_quarter_table::<513>().to_vec(),
        1024 => rsqrt_quarter_table::<1025>().to_vec(),
        _ => return None,
    })
}

/// A specular table of `seg` segments for exponent `m` (Q16).
pub fn spec_table_of(seg: usize, m: u32) -> Option<Vec<u16>> {
    Some(match seg {
        16 => spec_table::<18>(m).to_vec(),
        32 => spec_table::<34>(m).to_vec(),
        64 => spec_table::<66>(m).to_vec(),
        128 => spec_table::<130>(m).to_vec(),
        256 => spec_table::<258>(m).to_vec(),
        512 => spec_table::<514>(m).to_vec(),
        1024 => spec_table::<1026>(m).to_vec(),
        _ => return None,
    })
}

/// The sizes swept (segments): 17 to 1025 entries.
pub const SIZES: [usize; 7] = [16, 32, 64, 128, 256, 512, 1024];

/// The raw Q16 bits of a `Q16`.
fn raw(v: Q16) -> i32 {
    v.to_fixed_i32(16)
}

impl Model {
    /// The model for `material` (colour, `ka`, `kd`, `ks` multiples of
    /// 1/256 at most 1: the products the kernel's shade folds are then
    /// exact) under white directional lights of intensity 1 pointing to
    /// `dirs`, ambient `ambient`, with tables of `rs_seg` and `spec_seg`
    /// segments; `None` for a size not swept or a shininess below 1.
    pub fn new(
        material: &Material<Q16>,
        ambient: Q16,
        dirs: &[Vec3<Q16>],
        specular: Specular,
        rs_seg: usize,
        spec_seg: usize,
    ) -> Option<Self> {
        let blinn = specular == Specular::Blinn;
        let c = material.color;
        let amb_k = ambient * material.ka;
        let amb = [c.x, c.y, c.z].map(|v| scale255(raw(v * amb_k), 13) as u32);
        let lights = dirs
            .iter()
            .map(|d| {
                let at = d.normalize();
                let l = unit30([raw(at.x), raw(at.y), raw(at.z)].map(i64::from));
                let (p1, p2) = light_halves(l, blinn);
                let dif = [c.x, c.y, c.z].map(|v| scale255(raw(v * material.kd), 6) as u32);
                let s = scale255(raw(material.ks), 6) as u32;
                MLight {
                    at: l,
                    p1,
                    p2,
                    d: dif,
                    s: [s; 3],
                }
            })
            .collect();
        let shin = raw(Real::clamp(
            material.shininess,
            Q16::ZERO,
            Q16::from_i32(10_000),
        ));
        let has_spec = material.ks > Q16::ZERO && !dirs.is_empty();
        if has_spec && shin < 1 << 16 {
            return None;
        }
        let m = if blinn { shin as u32 / 2 } else { shin as u32 }.max(1);
        let t_eff = m.min(U_MAX);
        let spec = if has_spec {
            spec_table_of(spec_seg, m)?
        } else {
            vec![0; spec_seg + 2]
        };
        let rs = rsqrt_table(rs_seg)?;
        // As `PhongKernel::new`: Q (Q28) at or above 2^(15 + sq) gives no
        // specular term; the position scale c16 · 2^-cb.
        let qlim = (u64::from(t_eff) * (5 << 28) / 4) / u64::from(m) + 1;
        let mut sq = 0u32;
        while (1u64 << (15 + sq)) < qlim {
            sq += 1;
        }
        let num = u128::from(m) * spec_seg as u128;
        let top = (num << 24) / u128::from(t_eff);
        let (mut c16, mut cb, mut found) = (0u32, 0u32, false);
        for b in (0..48u32).rev() {
            let e = i64::from(POS_FRAC + sq + b) - 42;
            if e > 24 {
                continue;
            }
            let v = top.checked_shr((24 - e) as u32).unwrap_or(0);
            if v < 1 << 16 {
                c16 = v as u32;
                cb = b;
                found = v <= 1 << b;
                break;
            }
        }
        if has_spec && !found {
            return None;
        }
        Some(Self {
            rs_shift: 28 - rs_seg.trailing_zeros(),
            rs,
            spec,
            has_spec,
            blinn,
            amb,
            lights,
            sq,
            c16,
            cb,
        })
    }

    /// `2^16 / |n|` from `|n|²` (Q28) in `[1/4, 5/4)`.
    fn rsqrt_n(&self, f: i32) -> Option<u32> {
        let j = (f.wrapping_sub(1 << 26) >> self.rs_shift) as u32 as usize;
        between(&self.rs, j, ((f >> (self.rs_shift - 16)) & 0xFFFF) as u32)
    }

    /// The specular factor (Q15) for `qs` (Q28 of `Q`) and `rr14`.
    fn spec_of(&self, qs: i32, rr14: u32) -> u32 {
        let qs = qs.max(0) as u32 >> self.sq;
        if qs >= 1 << 15 {
            return 0;
        }
        let pos = qs.wrapping_mul(rr14.wrapping_mul(self.c16) >> self.cb);
        let f = (pos >> (POS_FRAC - 16)) & 0xFFFF;
        between(&self.spec, (pos >> POS_FRAC) as usize, f).unwrap_or(0)
    }

    /// The colour at a pixel whose interpolated normal is `n` (Q30), or
    /// `None` where the kernel takes the generic path (`|n|²` outside
    /// `[1/4, 5/4)`).
    pub fn pixel(&self, n: [i32; 3]) -> Option<[u8; 3]> {
        let f = (sq_sum(&n) >> 32) as i32;
        let r = self.rsqrt_n(f)?;
        let r14 = r >> 2;
        let rr14 = (r14 * r14) >> 14;
        let mut acc = self.amb;
        for l in &self.lights {
            let nl = lin(n, l.at);
            if nl <= 0 {
                continue;
            }
            let sp = if self.has_spec && (!self.blinn || lin(n, l.p1) > 0) {
                let c0 = cross(n, l.p1);
                let q = sq_sum(&[c0[0], c0[1], c0[2], lin(n, l.p2)]);
                self.spec_of((q >> 32) as i32, rr14)
            } else {
                0
            };
            let nl15 = ((nl as u32 >> 15).wrapping_mul(r) >> 16).min(1 << 15);
            for ((a, d), s) in acc.iter_mut().zip(l.d).zip(l.s) {
                *a = a.wrapping_add((d * nl15).wrapping_add(s * sp) >> 8);
            }
        }
        Some(acc.map(|a| ((a as i32).wrapping_add(1 << 12) >> 13).clamp(0, 255) as u8))
    }
}

/// The material of the set: dyadic coefficients (exact in `Q16`).
fn material(n: f64) -> Material<Q16> {
    let q = Q16::from_f64;
    Material {
        color: Vec3::new(q(1.0), q(0.75), q(0.5)),
        ka: q(0.5),
        kd: q(0.25),
        ks: q(0.75),
        shininess: q(n),
    }
}

/// The shininess values of the set.
pub const SHININESS: [f64; 9] = [1.0, 2.0, 5.0, 10.0, 50.0, 100.0, 800.0, 2000.0, 10_000.0];

/// One case of the set: shininess, model, light direction and the
/// pixels' normals (Q30).
pub struct Case {
    /// Shininess.
    pub n: f64,
    /// Specular model.
    pub specular: Specular,
    /// Towards the light.
    pub dir: Vec3<Q16>,
    /// The normals along the span.
    pub normals: Vec<[i32; 3]>,
}

/// The highlight-peak set (see the module docs).
pub fn peak_set() -> Vec<Case> {
    let mut out = Vec::new();
    for &n in &SHININESS {
        for specular in [Specular::Phong, Specular::Blinn] {
            for graze in [false, true] {
                let ang: f64 = if graze { 80f64.to_radians() } else { 0.0 };
                let ldir = [ang.sin(), 0.0, ang.cos()];
                let len = (ldir[0] * ldir[0] + (ldir[2] + 1.0) * (ldir[2] + 1.0)).sqrt();
                let h = [ldir[0] / len, 0.0, (ldir[2] + 1.0) / len];
                let width = (2.0 / n.sqrt()).clamp(0.005, 0.5);
                let mut normals = Vec::new();
                for scale in [1.0, 0.85, 0.7, 0.55] {
                    for i in 0..64 {
                        let t = -width + 2.0 * width * f64::from(i) / 64.0;
                        let v = [h[0] + t, h[1] + 0.01, h[2]];
                        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                        normals
                            .push(v.map(|c| (c / l * scale * f64::from(1 << 30)).round() as i32));
                    }
                }
                out.push(Case {
                    n,
                    specular,
                    dir: Vec3::new(
                        Q16::from_f64(ldir[0]),
                        Q16::from_f64(ldir[1]),
                        Q16::from_f64(ldir[2]),
                    ),
                    normals,
                });
            }
        }
    }
    out
}

/// The `f64` reference colour (levels, unrounded) of a case at normal `n`.
fn reference(c: &Case, n: [i32; 3]) -> [f64; 3] {
    let m = material(c.n);
    let m64 = Material {
        color: Vec3::new(m.color.x.to_f64(), m.color.y.to_f64(), m.color.z.to_f64()),
        ka: m.ka.to_f64(),
        kd: m.kd.to_f64(),
        ks: m.ks.to_f64(),
        shininess: m.shininess.to_f64(),
    };
    let d = Vec3::new(c.dir.x.to_f64(), c.dir.y.to_f64(), c.dir.z.to_f64());
    let shade = Shade::new(
        &m64,
        AMBIENT,
        &[Light::directional(d, 1.0)],
        c.specular,
        Viewer::Infinite,
    )
    .expect("one light");
    let nv = Vec3::new(f64::from(n[0]), f64::from(n[1]), f64::from(n[2])).normalize();
    let e = shade.at(nv, Vec3::ZERO);
    [e.x, e.y, e.z].map(|v| v.clamp(0.0, 1.0) * 255.0)
}

/// The ambient intensity of the set.
const AMBIENT: f64 = 0.25;

/// Max and mean error (levels) of the model with the given sizes over
/// the set; pixels the kernel leaves to the generic path are skipped
/// (none in the set: `|n|² >= 0.3`). `None` when the kernel's arithmetic
/// cannot address a table of that size at some shininess of the set
/// (the specular table from 256 segments on: its argument has 15 bits,
/// `qs < 2^15`, and its position scale is at most 1, `c16 <= 2^cb`, so
/// `PhongKernel::new` would refuse the low shininesses).
pub fn set_error(
    set: &[Case],
    refs: &[Vec<[f64; 3]>],
    rs_seg: usize,
    spec_seg: usize,
) -> Option<(f64, f64)> {
    let (mut worst, mut sum, mut count) = (0f64, 0f64, 0usize);
    for (c, r) in set.iter().zip(refs) {
        let model = Model::new(
            &material(c.n),
            Q16::from_f64(AMBIENT),
            &[c.dir],
            c.specular,
            rs_seg,
            spec_seg,
        )?;
        for (n, want) in c.normals.iter().zip(r) {
            let Some(got) = model.pixel(*n) else {
                continue;
            };
            for (g, w) in got.iter().zip(want) {
                let e = (f64::from(*g) - w).abs();
                worst = worst.max(e);
                sum += e;
                count += 1;
            }
        }
    }
    (count > 0).then(|| (worst, sum / count as f64))
}

/// One size of one table.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SizeRow {
    /// Segments.
    pub segments: usize,
    /// Entries.
    pub entries: usize,
    /// Bytes of the table.
    pub bytes: usize,
    /// Max error, levels (`None`: the kernel cannot address the size).
    pub max: Option<f64>,
    /// Mean error, levels.
    pub mean: Option<f64>,
}

/// The sweep's results.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TableSweep {
    /// The `1/|n|` table's sizes (specular table as shipped).
    pub rsqrt: Vec<SizeRow>,
    /// The specular table's sizes (`1/|n|` table as shipped).
    pub spec: Vec<SizeRow>,
    /// Pixels × channels of the set.
    pub samples: usize,
    #[serde(skip)]
    plot: String,
}

impl TableSweep {
    /// Runs the sweep (milliseconds: 14 sizes × 8 192 pixels).
    pub fn run() -> Self {
        let set = peak_set();
        let refs: Vec<Vec<[f64; 3]>> = set
            .iter()
            .map(|c| c.normals.iter().map(|&n| reference(c, n)).collect())
            .collect();
        let samples = set.iter().map(|c| c.normals.len() * 3).sum();
        // One row per size: `s` segments of a table of `s + extra`
        // entries of `width` bytes, measured with the other table shipped.
        let rows = |extra: usize, width: usize, error: &dyn Fn(usize) -> Option<(f64, f64)>| {
            SIZES
                .iter()
                .map(|&s| {
                    let e = error(s);
                    SizeRow {
                        segments: s,
                        entries: s + extra,
                        bytes: width * (s + extra),
                        max: e.map(|e| e.0),
                        mean: e.map(|e| e.1),
                    }
                })
                .collect::<Vec<SizeRow>>()
        };
        let rsqrt = rows(1, 4, &|s| set_error(&set, &refs, s, SPEC_SEGMENTS));
        let spec = rows(2, 2, &|s| set_error(&set, &refs, RSQRT_N, s));
        let series = |name: &str, rows: &[SizeRow], f: fn(&SizeRow) -> Option<f64>| -> Series {
            (
                name.to_string(),
                rows.iter()
                    .filter_map(|r| {
                        Some(((r.segments as f64).log2(), f(r)?, r.segments.to_string()))
                    })
                    .collect(),
            )
        };
        let all: Vec<Series> = vec![
            series("1/|n| table, max", &rsqrt, |r| r.max),
            series("specular table, max", &spec, |r| r.max),
            series("1/|n| table, mean ×10", &rsqrt, |r| {
                r.mean.map(|m| m * 10.0)
            }),
            series("specular table, mean ×10", &spec, |r| {
                r.mean.map(|m| m * 10.0)
            }),
        ];
        let plot = line_svg(
            "Phong kernel error against table size",
            "log2 segments",
            "levels of 255",
            &all,
        );
        Self {
            rsqrt,
            spec,
            samples,
            plot,
        }
    }

    fn rows(rows: &[SizeRow], shipped: usize) -> Vec<Vec<String>> {
        rows.iter()
            .map(|r| {
                vec![
                    format!(
                        "{}{}",
                        r.segments,
                        if r.segments == shipped {
                            " (shipped)"
                        } else {
                            ""
                        }
                    ),
                    r.entries.to_string(),
                    r.bytes.to_string(),
                    r.max.map_or("n/a".into(), |v| format!("{v:.3}")),
                    r.mean.map_or("n/a".into(), |v| format!("{v:.4}")),
                ]
            })
            .collect()
    }

    const HEAD: [&str; 5] = ["segments", "entries", "bytes", "max error", "mean error"];

    fn why(&self) -> String {
        let at = |rows: &[SizeRow], s: usize| rows.iter().find(|r| r.segments == s).cloned();
        let f = |v: Option<f64>, d: usize| v.map_or("n/a".to_string(), |v| format!("{v:.d$}"));
        let (Some(r), Some(r2), Some(s), Some(s2)) = (
            at(&self.rsqrt, RSQRT_N / 2),
            at(&self.rsqrt, RSQRT_N),
            at(&self.spec, SPEC_SEGMENTS / 2),
            at(&self.spec, SPEC_SEGMENTS),
        ) else {
            return String::new();
        };
        let s3 = at(&self.spec, SPEC_SEGMENTS * 2);
        format!(
            "The shipped sizes: the 1/|n| table has {} segments ({} bytes of flash; max {}, mean {} levels; half of it, {} bytes, gives {} / {}); the specular table has {} segments ({} bytes of RAM in the kernel, built per shininess, one entry a segment; max {}, mean {}; half of it gives {} / {}, twice {} / {}). n/a: a size the kernel cannot address at every shininess of the set (its table argument has 15 bits and its position scale is at most 1, so PhongKernel::new would refuse the low shininesses).",
            r2.segments, r2.bytes, f(r2.max, 3), f(r2.mean, 4), r.bytes, f(r.max, 3), f(r.mean, 4),
            s2.segments, s2.bytes, f(s2.max, 3), f(s2.mean, 4), f(s.max, 3), f(s.mean, 4),
            f(s3.as_ref().and_then(|r| r.max), 3), f(s3.as_ref().and_then(|r| r.mean), 4),
        )
    }

    /// The section's HTML.
    pub fn html(&self) -> Markup {
        let t = |rows: &[SizeRow], shipped: usize| {
            html! {
                table {
                    thead { tr { @for h in Self::HEAD { th { (h) } } } }
                    tbody {
                        @for row in Self::rows(rows, shipped) {
                            tr { @for c in row { td { (c) } } }
                        }
                    }
                }
            }
        };
        html! {
            h2 id="tables" { "Phong kernel: table sizes against error" }
            p.note { (NOTE) " " (self.samples) " samples (pixel × channel)." }
            div.plots {
                (PreEscaped(self.plot.find("<svg").map_or(self.plot.as_str(), |i| &self.plot[i..])))
            }
            h3 { "1/|n| table (specular table as shipped)" }
            (t(&self.rsqrt, RSQRT_N))
            h3 { "Specular table (1/|n| table as shipped)" }
            (t(&self.spec, SPEC_SEGMENTS))
            p { (self.why()) }
        }
    }

    /// The section in Markdown.
    pub fn markdown(&self) -> String {
        let md = |rows: &[SizeRow], shipped: usize| {
            let mut s = format!("| {} |\n|{}\n", Self::HEAD.join(" | "), "---|".repeat(5));
            for r in Self::rows(rows, shipped) {
                s += &format!("| {} |\n", r.join(" | "));
            }
            s
        };
        format!(
            "## Phong kernel: table sizes against error\n\n{NOTE} {} samples (pixel × channel).\n\n### 1/|n| table (specular table as shipped)\n\n{}\n### Specular table (1/|n| table as shipped)\n\n{}\n{}\n",
            self.samples,
            md(&self.rsqrt, RSQRT_N),
            md(&self.spec, SPEC_SEGMENTS),
            self.why()
        )
    }
}

const NOTE: &str = "The fast profile's Phong span kernel (directional lights, viewer at infinity) evaluated with each table at sizes from 16 to 1024 segments, the other as shipped, by a model of its per-pixel arithmetic tested equal to the kernel at the shipped sizes; on the highlight-peak set (shininess 1 to 10 000, Phong and Blinn, light overhead and 80° off, the normal swept across the peak at lengths 1 to 0.55); errors in levels against the same formula in f64 on the same normal (the twin's and the ideal's formula: at one pixel the two references agree).";

#[cfg(test)]
mod tests {
    use super::*;
    use fixshade::render::PhongKernel;

    /// Material, light directions, model and normals.
    type KernelCase = (Material<Q16>, Vec<Vec3<Q16>>, Specular, Vec<[i32; 3]>);

    fn xorshift(s: &mut u64) -> u64 {
        *s ^= *s << 13;
        *s ^= *s >> 7;
        *s ^= *s << 17;
        *s
    }

    /// At the shipped sizes the model is the kernel, pixel for pixel: the
    /// peak set and random normals, materials, shininess and one to four
    /// lights.
    #[test]
    fn model_equals_the_kernel_at_the_shipped_sizes() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut f = |lo: f64, hi: f64| {
            lo + (hi - lo) * ((xorshift(&mut seed) >> 11) as f64 / (1u64 << 53) as f64)
        };
        let mut checked = 0;
        let set = peak_set();
        let mut cases: Vec<KernelCase> = set
            .iter()
            .map(|c| (material(c.n), vec![c.dir], c.specular, c.normals.clone()))
            .collect();
        for it in 0..300 {
            let dy = |v: f64| Q16::from_f64((v * 256.0).round() / 256.0);
            let m = Material {
                color: Vec3::new(dy(f(0.0, 1.0)), dy(f(0.0, 1.0)), dy(f(0.0, 1.0))),
                ka: dy(f(0.0, 1.0)),
                kd: dy(f(0.0, 1.0)),
                ks: dy(f(0.0, 1.0)),
                shininess: Q16::from_f64(f(1.0, 10_000.0).powf(if it % 2 == 0 {
                    1.0
                } else {
                    0.3
                })),
            };
            let lights = (0..1 + it % 4)
                .map(|_| {
                    Vec3::new(
                        Q16::from_f64(f(-1.0, 1.0)),
                        Q16::from_f64(f(-1.0, 1.0)),
                        Q16::from_f64(f(0.05, 1.0)),
                    )
                })
                .collect();
            let normals = (0..40)
                .map(|_| {
                    let s = f(0.5, 1.1);
                    let v = [f(-1.0, 1.0), f(-1.0, 1.0), f(0.0, 1.0)];
                    let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                    v.map(|c| (c / l * s * f64::from(1 << 30)).round() as i32)
                })
                .collect();
            let sp = if it % 3 == 0 {
                Specular::Blinn
            } else {
                Specular::Phong
            };
            cases.push((m, lights, sp, normals));
        }
        for (m, dirs, sp, normals) in &cases {
            let amb = Q16::from_f64(AMBIENT);
            let lights: Vec<Light<Q16>> = dirs
                .iter()
                .map(|&d| Light::directional(d, Q16::ONE))
                .collect();
            let shade = Shade::new(m, amb, &lights, *sp, Viewer::Infinite).unwrap();
            let Ok(k) = PhongKernel::new(&shade) else {
                assert!(Model::new(m, amb, dirs, *sp, RSQRT_N, SPEC_SEGMENTS).is_none());
                continue;
            };
            let model = Model::new(m, amb, dirs, *sp, RSQRT_N, SPEC_SEGMENTS).unwrap();
            for &n in normals {
                let Some(got) = model.pixel(n) else {
                    continue;
                };
                let c = k.begin(n, [0; 3], [0; 3], [0; 3], false).next();
                assert_eq!(got, [c.r, c.g, c.b], "{m:?} {dirs:?} {sp:?} {n:?}");
                checked += 1;
            }
        }
        assert!(checked > 15_000, "{checked}");
    }

    /// The sweep: at the shipped sizes within 1 level of `f64` on the set
    /// (the budget for `fast`: 2); the specular table at half
    /// the shipped size over a level, at 16 segments over 4; the largest
    /// specular tables not addressable by the kernel.
    #[test]
    fn sweep_shows_the_shipped_sizes() {
        let s = TableSweep::run();
        let at =
            |rows: &[SizeRow], seg: usize| rows.iter().find(|r| r.segments == seg).unwrap().clone();
        let (r, r16) = (at(&s.rsqrt, RSQRT_N), at(&s.rsqrt, 16));
        let (p, p64, p16) = (at(&s.spec, SPEC_SEGMENTS), at(&s.spec, 64), at(&s.spec, 16));
        println!("{}", s.markdown());
        let (rm, pm) = (r.max.unwrap(), p.max.unwrap());
        assert!(rm <= 1.0 && pm <= 1.0, "{r:?} {p:?}");
        assert_eq!(rm, pm, "the same configuration");
        assert!(r16.max.unwrap() > rm, "{r16:?}");
        assert!(
            p64.max.unwrap() > 1.0 && p16.max.unwrap() > 4.0,
            "{p64:?} {p16:?}"
        );
        assert_eq!(at(&s.spec, 1024).max, None);
        assert!(s.markdown().contains("| 128 (shipped) |"));
    }
}
