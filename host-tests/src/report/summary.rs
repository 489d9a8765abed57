//! The written summary, derived from the figures: aggregates per mode and
//! profile, a pick per target, and where the fixed profiles lose accuracy.

use std::collections::BTreeMap;

use crate::core_render::CoreProfile;

use super::embedded::{EmbeddedResult, Target};
use super::plot::pareto_front;
use super::{Mode, Record};

/// A pick may be this many levels (mean absolute error against the ideal
/// Phong frame) worse than the best candidate of its target.
pub const QUALITY_TOLERANCE: f64 = 0.1;
/// Per mode, a pick may be this many levels (mean absolute error against
/// the ideal frame of that mode) worse than the mode's best candidate.
pub const MODE_TOLERANCE: f64 = 0.1;

/// One mode and profile over every scene of the sweep.
#[derive(Clone, Debug, PartialEq)]
pub struct Aggregate {
    /// The mode.
    pub mode: Mode,
    /// The profile.
    pub profile: CoreProfile,
    /// Scenes averaged.
    pub scenes: usize,
    /// Mean over the scenes of the mean error against the ideal.
    pub vs_ideal_mean: f64,
    /// Largest share of pixels more than a level off the ideal.
    pub vs_ideal_share_max: f64,
    /// Mean over the scenes of the mean error against the twin.
    pub vs_twin_mean: f64,
    /// Largest error against the twin.
    pub vs_twin_max: u8,
    /// Pixels covered differently from the twin, all scenes.
    pub vs_twin_coverage: u64,
    /// Mean over the scenes of the mean error against the ideal Phong
    /// frame.
    pub vs_phong_mean: f64,
    /// Mean over the scenes of the median host time per frame, ms.
    pub host_ms: f64,
    /// Pixels shaded per second over all scenes.
    pub pixels_per_s: f64,
    /// Largest RAM (prepared frame + bands), bytes.
    pub ram_max: usize,
}

/// A candidate on one target: a mode and a profile with a cost.
#[derive(Clone, Debug, PartialEq)]
pub struct Point {
    /// The mode.
    pub mode: Mode,
    /// The profile.
    pub profile: CoreProfile,
    /// Cost in the target's unit.
    pub cost: f64,
    /// Mean error against the ideal of the mode.
    pub vs_ideal: f64,
    /// Mean error against the twin.
    pub vs_twin: f64,
    /// Mean error against the ideal Phong frame.
    pub vs_phong: f64,
}

impl Point {
    /// `fast-pc / Phong`.
    pub fn label(&self) -> String {
        format!("{} / {}", self.profile.name(), self.mode.title())
    }
}

/// Where the cost of a target's points comes from.
#[derive(Clone, Debug, PartialEq)]
pub enum CostSource {
    /// Median host time per frame, ms.
    Host,
    /// The firmware's figures: the unit (`est. cycles`, `instructions`)
    /// and how many firmware scenes were averaged per point at most.
    Embedded(&'static str, usize),
    /// The host's time standing in for a target without figures.
    HostProxy,
}

/// The pick for one target.
#[derive(Clone, Debug, PartialEq)]
pub struct Pick {
    /// `None` for the host.
    pub target: Option<Target>,
    /// What the candidates are.
    pub candidates_note: &'static str,
    /// The candidates with their costs.
    pub points: Vec<Point>,
    /// Where the costs come from.
    pub source: CostSource,
    /// The pick: the cheapest within [`QUALITY_TOLERANCE`] of the best
    /// against the ideal Phong frame.
    pub chosen: Option<usize>,
    /// The best against the ideal Phong frame.
    pub best: Option<usize>,
    /// The cheapest.
    pub cheapest: Option<usize>,
    /// Per mode: the cheapest within [`MODE_TOLERANCE`] of the mode's best
    /// against its ideal.
    pub per_mode: Vec<(Mode, usize)>,
}

impl Pick {
    fn new(
        target: Option<Target>,
        candidates_note: &'static str,
        points: Vec<Point>,
        source: CostSource,
    ) -> Self {
        let min_by = |f: &dyn Fn(&Point) -> f64, among: &dyn Fn(&Point) -> bool| {
            points
                .iter()
                .enumerate()
                .filter(|(_, p)| among(p))
                .min_by(|(_, a), (_, b)| f(a).total_cmp(&f(b)))
                .map(|(i, _)| i)
        };
        let best = min_by(&|p| p.vs_phong, &|_| true);
        let bound = best.map_or(f64::INFINITY, |b| points[b].vs_phong + QUALITY_TOLERANCE);
        let chosen = min_by(&|p| p.cost, &|p| p.vs_phong <= bound);
        let cheapest = min_by(&|p| p.cost, &|_| true);
        let per_mode = Mode::ALL
            .into_iter()
            .filter_map(|m| {
                let best = min_by(&|p| p.vs_ideal, &|p| p.mode == m)?;
                let bound = points[best].vs_ideal + MODE_TOLERANCE;
                Some((
                    m,
                    min_by(&|p| p.cost, &|p| p.mode == m && p.vs_ideal <= bound)?,
                ))
            })
            .collect();
        Self {
            target,
            candidates_note,
            points,
            source,
            chosen,
            best,
            cheapest,
            per_mode,
        }
    }

    /// `Cortex-M0` or `host`.
    pub fn title(&self) -> &'static str {
        self.target.map_or("host", Target::title)
    }

    /// The cost unit.
    pub fn unit(&self) -> &'static str {
        match self.source {
            CostSource::Host | CostSource::HostProxy => "ms per frame on this host",
            CostSource::Embedded(unit, _) => unit,
        }
    }

    fn cost_text(&self, p: &Point) -> String {
        match self.source {
            CostSource::Host | CostSource::HostProxy => {
                format!("{:.3} ms/frame on the host", p.cost)
            }
            CostSource::Embedded(unit, _) => format!("{:.2} M {unit}/frame", p.cost / 1e6),
        }
    }

    /// The recommendation as one paragraph.
    pub fn sentence(&self) -> String {
        let (Some(c), Some(b), Some(k)) = (self.chosen, self.best, self.cheapest) else {
            return format!("{}: no candidates measured.", self.title());
        };
        let (c, b, k) = (&self.points[c], &self.points[b], &self.points[k]);
        let mut s = format!(
            "{} ({}): pick {} — mean error {:.3} levels against the ideal Phong frame, {}",
            self.title(),
            self.candidates_note,
            c.label(),
            c.vs_phong,
            self.cost_text(c)
        );
        if b != c {
            s += &format!(
                "; the most accurate, {}, reaches {:.3} levels at {}",
                b.label(),
                b.vs_phong,
                self.cost_text(b)
            );
        } else {
            s += " (also the most accurate candidate)";
        }
        if k != c {
            s += &format!(
                "; the cheapest, {}, costs {} but is {:.2} levels off",
                k.label(),
                self.cost_text(k),
                k.vs_phong
            );
        }
        let modes: Vec<String> = self
            .per_mode
            .iter()
            .map(|&(m, i)| {
                let p = &self.points[i];
                format!(
                    "{} {} ({:.3} levels vs its ideal, {})",
                    m.title(),
                    p.profile.name(),
                    p.vs_ideal,
                    self.cost_text(p)
                )
            })
            .collect();
        s += &format!(". Per mode: {}.", modes.join("; "));
        match self.source {
            CostSource::HostProxy => s += " Cost: host time as a proxy — embedded figures are not available for this target.",
            CostSource::Embedded(unit, n) => {
                s += &format!(" Cost: the firmware's {unit}, mean of up to {n} firmware scene(s) measured in every mode; errors from the host sweep (the same arithmetic). Only the {} mode × profile combination(s) with embedded figures are candidates.", self.points.len())
            }
            CostSource::Host => {}
        }
        s
    }
}

/// Everything the summary says, with the numbers behind it.
#[derive(Clone, Debug, PartialEq)]
pub struct Summary {
    /// Per mode and profile, in mode then profile order.
    pub aggregates: Vec<Aggregate>,
    /// Host, Cortex-M0, Cortex-M4F.
    pub picks: Vec<Pick>,
    /// Embedded points per target (those with a mode and a profile).
    pub embedded_points: Vec<(Target, Vec<Point>, &'static str)>,
    /// Where the fixed profiles lose accuracy.
    pub findings: Vec<String>,
    /// The profile whose frames the page shows, per mode: the Cortex-M0
    /// pick for that mode.
    pub representative: BTreeMap<Mode, CoreProfile>,
}

fn mean(xs: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = xs.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 {
        0.0
    } else {
        s / n as f64
    }
}

/// The per mode and profile aggregates of `records`.
pub fn aggregate(records: &[Record]) -> Vec<Aggregate> {
    let mut out = Vec::new();
    for mode in Mode::ALL {
        for profile in CoreProfile::ALL {
            let rs: Vec<&Record> = records
                .iter()
                .filter(|r| r.mode == mode && r.profile == profile.name())
                .collect();
            if rs.is_empty() {
                continue;
            }
            let time_s: f64 = rs.iter().map(|r| r.host.median_ms / 1e3).sum();
            let pixels: f64 = rs.iter().map(|r| f64::from(r.host.pixels_shaded)).sum();
            out.push(Aggregate {
                mode,
                profile,
                scenes: rs.len(),
                vs_ideal_mean: mean(rs.iter().map(|r| r.vs_ideal.mean_abs_error)),
                vs_ideal_share_max: rs
                    .iter()
                    .map(|r| r.vs_ideal.share_over_1)
                    .fold(0.0, f64::max),
                vs_twin_mean: mean(rs.iter().map(|r| r.vs_twin.mean_abs_error)),
                vs_twin_max: rs
                    .iter()
                    .map(|r| r.vs_twin.max_abs_error)
                    .max()
                    .unwrap_or(0),
                vs_twin_coverage: rs.iter().map(|r| r.vs_twin.coverage_mismatch).sum(),
                vs_phong_mean: mean(rs.iter().map(|r| r.vs_ideal_phong.mean_abs_error)),
                host_ms: mean(rs.iter().map(|r| r.host.median_ms)),
                pixels_per_s: if time_s > 0.0 { pixels / time_s } else { 0.0 },
                ram_max: rs.iter().map(|r| r.memory.ram_bytes).max().unwrap_or(0),
            });
        }
    }
    out
}

fn point(a: &Aggregate, cost: f64) -> Point {
    Point {
        mode: a.mode,
        profile: a.profile,
        cost,
        vs_ideal: a.vs_ideal_mean,
        vs_twin: a.vs_twin_mean,
        vs_phong: a.vs_phong_mean,
    }
}

/// Per target, the firmware's mean cost per mode and profile, paired with
/// the host's errors; the unit; the most scenes averaged.
fn embedded_points(
    aggs: &[Aggregate],
    embedded: &[EmbeddedResult],
    target: Target,
) -> (Vec<Point>, &'static str, usize) {
    let of_target: Vec<&EmbeddedResult> = embedded.iter().filter(|e| e.target == target).collect();
    // One unit per target: cycles only when every result has them.
    let unit = if !of_target.is_empty() && of_target.iter().all(|e| e.cycles.is_some()) {
        "est. cycles"
    } else {
        "instructions"
    };
    let cost = |e: &EmbeddedResult| {
        if unit == "est. cycles" {
            e.cycles
        } else {
            e.insns
        }
    };
    // Compare modes on the same work: only firmware scenes measured in
    // every mode found for this target (e.g. the dodecahedron in flat,
    // Gouraud and Phong), unless no scene has them all.
    let modes: std::collections::BTreeSet<String> = of_target
        .iter()
        .filter_map(|e| e.mode.map(|m| format!("{m:?}")))
        .collect();
    let complete = |base: &str| {
        let have: std::collections::BTreeSet<String> = of_target
            .iter()
            .filter(|e| super::sweep::base_name(&e.scene) == base)
            .filter_map(|e| e.mode.map(|m| format!("{m:?}")))
            .collect();
        have == modes
    };
    let common: Vec<&EmbeddedResult> = of_target
        .iter()
        .copied()
        .filter(|e| complete(&super::sweep::base_name(&e.scene)))
        .collect();
    let of_target = if common.is_empty() { of_target } else { common };
    let mut most = 0;
    let points = aggs
        .iter()
        .filter_map(|a| {
            let costs: Vec<f64> = of_target
                .iter()
                .filter(|e| e.mode == Some(a.mode) && e.core_profile() == Some(a.profile))
                .filter_map(|e| cost(e).map(|c| c as f64))
                .collect();
            most = most.max(costs.len());
            (!costs.is_empty()).then(|| point(a, mean(costs.into_iter())))
        })
        .collect();
    (points, unit, most)
}

impl Summary {
    /// Derives the summary from the records and the embedded figures.
    pub fn new(records: &[Record], embedded: &[EmbeddedResult]) -> Self {
        let aggregates = aggregate(records);
        let host_points: Vec<Point> = aggregates.iter().map(|a| point(a, a.host_ms)).collect();
        let mut picks = vec![Pick::new(
            None,
            "every profile",
            host_points.clone(),
            CostSource::Host,
        )];
        let mut emb = Vec::new();
        for target in Target::ALL {
            let (points, unit, most) = embedded_points(&aggregates, embedded, target);
            let allowed = |p: &CoreProfile| match target {
                Target::M0 => p.is_fixed(),
                Target::M4f => p.is_fixed() || matches!(p, CoreProfile::F32 | CoreProfile::F32Pc),
            };
            let note = match target {
                Target::M0 => "no FPU: fixed-point profiles only, f32/f64 would be soft-float",
                Target::M4f => "single-precision FPU: fixed-point profiles or f32",
            };
            let measured: Vec<Point> = points
                .iter()
                .filter(|p| allowed(&p.profile))
                .cloned()
                .collect();
            // Host time is never a chip's cost: without figures, no
            // candidates.
            let pick = if measured.is_empty() {
                Pick::new(
                    Some(target),
                    note,
                    Vec::new(),
                    CostSource::Embedded(unit, 0),
                )
            } else {
                Pick::new(
                    Some(target),
                    note,
                    measured,
                    CostSource::Embedded(unit, most),
                )
            };
            picks.push(pick);
            if !points.is_empty() {
                emb.push((target, points, unit));
            }
        }
        let representative = picks[1]
            .per_mode
            .iter()
            .map(|&(m, i)| (m, picks[1].points[i].profile))
            .collect();
        Self {
            findings: findings(records, &aggregates),
            aggregates,
            picks,
            embedded_points: emb,
            representative,
        }
    }

    /// The recommendations then the findings, one paragraph each.
    pub fn lines(&self) -> Vec<String> {
        self.picks
            .iter()
            .map(Pick::sentence)
            .chain(self.findings.iter().cloned())
            .collect()
    }

    /// The Pareto front of a pick's points on (cost, error vs the ideal
    /// Phong frame).
    pub fn front(points: &[Point]) -> Vec<usize> {
        let xy: Vec<(f64, f64)> = points.iter().map(|p| (p.cost, p.vs_phong)).collect();
        pareto_front(&xy)
    }
}

fn label(r: &Record) -> String {
    format!("{} / {} / {}", r.profile, r.mode.title(), r.scene)
}

/// Where the fixed profiles lose accuracy, from the records.
fn findings(records: &[Record], aggs: &[Aggregate]) -> Vec<String> {
    let mut out = Vec::new();
    let fixed: Vec<&Record> = records.iter().filter(|r| r.fixed_point).collect();
    if fixed.is_empty() {
        return out;
    }
    // 1. The largest departures from the twin.
    let mut worst = fixed.clone();
    worst.sort_by(|a, b| {
        b.vs_twin
            .max_abs_error
            .cmp(&a.vs_twin.max_abs_error)
            .then(b.places_vs_twin.pixels.cmp(&a.places_vs_twin.pixels))
    });
    let top: Vec<String> = worst
        .iter()
        .take(3)
        .map(|r| {
            format!(
                "{}: up to {} levels, {} pixel(s) more than a level off or covered differently ({} on silhouettes, {} at edges inside the image), mean {:.4}",
                label(r),
                r.vs_twin.max_abs_error,
                r.places_vs_twin.pixels,
                r.places_vs_twin.at_silhouette,
                r.places_vs_twin.at_edge,
                r.vs_twin.mean_abs_error
            )
        })
        .collect();
    out.push(format!(
        "Largest departures of a fixed profile from its f64 twin (quantization alone): {}.",
        top.join("; ")
    ));

    // 2. Where: silhouettes or interior.
    let pixels: u64 = fixed.iter().map(|r| r.places_vs_twin.pixels).sum();
    let silhouette: u64 = fixed.iter().map(|r| r.places_vs_twin.at_silhouette).sum();
    let edge: u64 = fixed.iter().map(|r| r.places_vs_twin.at_edge).sum();
    let pct = |n: u64| {
        if pixels == 0 {
            0.0
        } else {
            100.0 * n as f64 / pixels as f64
        }
    };
    let by_profile: Vec<String> = CoreProfile::ALL
        .into_iter()
        .filter(|p| p.is_fixed())
        .map(|p| {
            let rs = fixed.iter().filter(|r| r.profile == p.name());
            let cov: u64 = rs.clone().map(|r| r.vs_twin.coverage_mismatch).sum();
            let worst = rs
                .max_by_key(|r| r.vs_twin.coverage_mismatch)
                .filter(|r| r.vs_twin.coverage_mismatch > 0)
                .map(|r| {
                    format!(
                        " (most: {} in {} / {})",
                        r.vs_twin.coverage_mismatch,
                        r.scene,
                        r.mode.title()
                    )
                })
                .unwrap_or_default();
            format!("{} {cov}{worst}", p.name())
        })
        .collect();
    out.push(format!(
        "Which pixels: of the {pixels} pixels (all fixed-profile frames) more than one level off the twin or covered differently, {silhouette} ({:.0} %) lie on silhouettes against the background, {edge} ({:.0} %) at edges inside the image (the twin's colour steps by more than {} levels to a neighbour: occluding contours, flat-shaded triangle edges) and {} ({:.0} %) in smooth areas. Pixels covered differently from the twin, all frames: {}.",
        pct(silhouette),
        pct(edge),
        super::sweep::EDGE_STEP,
        pixels - silhouette - edge,
        pct(pixels - silhouette - edge),
        by_profile.join(", ")
    ));

    // 3. Shininess: the largest family of scenes differing only in it,
    // for the fixed profile with the largest Phong error there.
    let phong: Vec<&Record> = fixed
        .iter()
        .copied()
        .filter(|r| r.mode == Mode::Phong)
        .collect();
    let mut families: BTreeMap<&str, BTreeMap<u64, ()>> = BTreeMap::new();
    for r in &phong {
        families
            .entry(r.shininess_family.as_str())
            .or_default()
            .insert(r.shininess.round() as u64, ());
    }
    let family = families
        .iter()
        .filter(|(_, n)| n.len() >= 2)
        .max_by_key(|(_, n)| n.len())
        .map(|(f, _)| *f);
    let in_family = |r: &&&Record| Some(r.shininess_family.as_str()) == family;
    if let Some(worst) = phong
        .iter()
        .filter(in_family)
        .max_by_key(|r| r.vs_twin.max_abs_error)
    {
        let mut by_n: BTreeMap<u64, (u8, f64)> = BTreeMap::new();
        for r in phong
            .iter()
            .filter(in_family)
            .filter(|r| r.profile == worst.profile)
        {
            let e = by_n.entry(r.shininess.round() as u64).or_default();
            e.0 = e.0.max(r.vs_twin.max_abs_error);
            e.1 = e.1.max(r.vs_twin.mean_abs_error);
        }
        let list: Vec<String> = by_n
            .iter()
            .map(|(n, (e, m))| format!("n = {n}: {e} (mean {m:.4})"))
            .collect();
        let top = by_n.values().map(|v| v.0).max().unwrap_or(0);
        let (lo, hi) = (
            by_n.values().next().map_or(0, |v| v.0),
            by_n.values().last().map_or(0, |v| v.0),
        );
        let trend = if hi == top && hi > lo {
            "is largest at the highest shininess"
        } else {
            "does not grow with the shininess"
        };
        let mut names: Vec<&str> = phong
            .iter()
            .filter(in_family)
            .map(|r| r.scene.as_str())
            .collect();
        names.dedup();
        out.push(format!(
            "Shininess: on the scenes that differ only in it ({}), the largest error of {} against its twin in Phong shading {trend}: {} levels.",
            names.join(", "),
            worst.profile,
            list.join(", ")
        ));
    }

    // 4. Affine interpolation against the ideal.
    let mean_of = |pc: bool| {
        mean(
            aggs.iter()
                .filter(|a| {
                    a.profile.is_fixed() && a.profile.perspective() == pc && a.mode != Mode::Flat
                })
                .map(|a| a.vs_ideal_mean),
        )
    };
    let share_of = |pc: bool| {
        aggs.iter()
            .filter(|a| a.profile.is_fixed() && a.profile.perspective() == pc)
            .map(|a| a.vs_ideal_share_max)
            .fold(0.0, f64::max)
    };
    out.push(format!(
        "Against the ideal (Gouraud and Phong), the fixed affine profiles average {:.3} levels and the perspective-correct ones {:.3}; up to {:.1} % of a frame's pixels are more than a level off with affine interpolation, {:.1} % with -pc. {}",
        mean_of(false),
        mean_of(true),
        100.0 * share_of(false),
        100.0 * share_of(true),
        {
            let precise: Vec<&&Record> = fixed.iter().filter(|r| r.profile.starts_with("precise")).collect();
            let max = precise.iter().map(|r| r.vs_twin.max_abs_error).max().unwrap_or(0);
            let cov: u64 = precise.iter().map(|r| r.vs_twin.coverage_mismatch).sum();
            format!("precise and precise-pc stay within {max} level(s) of their twins in every frame, with {cov} pixel(s) covered differently.")
        }
    ));
    out
}
