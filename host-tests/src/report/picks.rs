//! Picks from a budget (`fixshade pick`, the report's picks table): the
//! most accurate configuration whose measured chip cost fits a clock, a
//! frame rate and a RAM size.
//!
//! A *configuration* is a profile × shading mode (× band rows × depth
//! bits: the measured firmware has one of each, 16 rows and 16 bits, so
//! those are fixed here and printed). Its cost on a chip comes from the
//! committed measurements ([`super::chips`]): cycles per frame (the M0's
//! estimate; on the M4F the instruction count, one cycle each, a lower
//! bound) and the RAM of [`ChipResult::ram`]. Over several scenes the
//! worst case counts. Its error is the host's: the mean absolute error in
//! 8-bit levels of the profile's frame of that firmware scene against the
//! ideal Phong frame of the scene (exact f64 coverage, perspective-correct
//! Phong: the best shading), so a cheaper mode pays for its looks.
//! Nothing here uses host time.

use std::collections::BTreeMap;

use super::Error;
use crate::builtin::load_builtin;
use crate::compare::{core_view, ideal_view};
use crate::core_render::CoreProfile;
use crate::ideal::IdealFrame;
use crate::metrics::compare;

use super::chips::{ChipResult, Measurements};
use super::embedded::Target;
use super::sweep::base_name;
use super::Mode;

/// A part the picks know by name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chip {
    /// Its name on the command line.
    pub name: &'static str,
    /// Other names.
    pub aliases: &'static [&'static str],
    /// For people.
    pub title: &'static str,
    /// Whose measurements apply.
    pub target: Target,
    /// A usual clock, MHz (the picks table's).
    pub mhz: f64,
    /// Its RAM, KiB (the picks table's).
    pub ram_kb: f64,
}

/// The known parts. The Cortex-M0+ ones use the M0's measurements and
/// cycle estimate (the M0+ takes fewer cycles per taken branch: the
/// estimate is on the safe side).
pub const CHIPS: [Chip; 6] = [
    Chip {
        name: "cortex-m0",
        aliases: &["m0", "cortex-m0+", "m0+", "m0plus", "cortex-m0plus"],
        title: "Cortex-M0/M0+ at 48 MHz, 32 KiB RAM",
        target: Target::M0,
        mhz: 48.0,
        ram_kb: 32.0,
    },
    Chip {
        name: "rp2040",
        aliases: &[],
        title: "RP2040 (Cortex-M0+) at 133 MHz, 264 KiB RAM",
        target: Target::M0,
        mhz: 133.0,
        ram_kb: 264.0,
    },
    Chip {
        name: "stm32g0",
        aliases: &["stm32g071"],
        title: "STM32G071 (Cortex-M0+) at 64 MHz, 36 KiB RAM",
        target: Target::M0,
        mhz: 64.0,
        ram_kb: 36.0,
    },
    Chip {
        name: "cortex-m4f",
        aliases: &["m4f", "m4", "cortex-m4", "nrf52840"],
        title: "Cortex-M4F at 64 MHz (e.g. nRF52840), 256 KiB RAM",
        target: Target::M4f,
        mhz: 64.0,
        ram_kb: 256.0,
    },
    Chip {
        name: "stm32f407",
        aliases: &["stm32f4"],
        title: "STM32F407 (Cortex-M4F) at 168 MHz, 192 KiB RAM",
        target: Target::M4f,
        mhz: 168.0,
        ram_kb: 192.0,
    },
    Chip {
        name: "stm32l432",
        aliases: &[],
        title: "STM32L432 (Cortex-M4F) at 80 MHz, 64 KiB RAM",
        target: Target::M4f,
        mhz: 80.0,
        ram_kb: 64.0,
    },
];

/// The parts of the report's picks table.
pub const TABLE_CHIPS: [&str; 4] = ["cortex-m0", "rp2040", "cortex-m4f", "stm32f407"];

/// The part called `name` (any case, or an alias).
pub fn find_chip(name: &str) -> Option<&'static Chip> {
    let n = name.to_ascii_lowercase();
    CHIPS
        .iter()
        .find(|c| c.name == n || c.aliases.contains(&n.as_str()))
}

/// Every part's name, for messages.
pub fn chip_names() -> String {
    CHIPS.iter().map(|c| c.name).collect::<Vec<_>>().join(", ")
}

/// A budget: a chip family, its clock, the frame rate, the RAM.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Budget {
    /// Whose measurements apply.
    pub target: Target,
    /// Clock, MHz (> 0).
    pub mhz: f64,
    /// Frames per second (> 0).
    pub fps: f64,
    /// RAM, bytes (> 0).
    pub ram_bytes: f64,
}

impl Budget {
    /// Cycles per frame the clock allows.
    pub fn cycles(&self) -> f64 {
        self.mhz * 1e6 / self.fps
    }
}

/// A configuration with its worst-case cost over the chosen scenes.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// The profile.
    pub profile: CoreProfile,
    /// The mode (`None`: the scene's own, mixed, shading).
    pub mode: Option<Mode>,
    /// The firmware scenes it was measured on.
    pub scenes: Vec<String>,
    /// Most cycles per frame.
    pub cycles: u64,
    /// Most RAM, bytes.
    pub ram: u64,
    /// Mean error against the ideal Phong frames, levels.
    pub error: f64,
}

impl Candidate {
    /// `fast / Gouraud`.
    pub fn label(&self) -> String {
        format!(
            "{} / {}",
            self.profile.name(),
            self.mode.map_or("as in the scene", Mode::title)
        )
    }

    /// Frames per second at `mhz`.
    pub fn fps(&self, mhz: f64) -> f64 {
        mhz * 1e6 / self.cycles.max(1) as f64
    }

    /// How far over the budget, as a factor (≤ 1: fits).
    pub fn over(&self, b: &Budget) -> f64 {
        (self.cycles as f64 / b.cycles()).max(self.ram as f64 / b.ram_bytes)
    }

    /// Whether it fits.
    pub fn fits(&self, b: &Budget) -> bool {
        self.cycles as f64 <= b.cycles() && self.ram as f64 <= b.ram_bytes
    }
}

/// Which firmware scenes a pick looks at.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneChoice {
    /// The name asked for (or the default's).
    pub name: String,
    /// The firmware scenes.
    pub scenes: Vec<String>,
}

/// The firmware scenes called `name` (a firmware scene, or a base scene:
/// the name without its shading word, e.g. `dodeca-n100` for the
/// dodecahedron in all three modes); without a name, the base scenes
/// measured in every mode.
///
/// # Errors
/// An unknown name (bad input, listing the known ones).
pub fn choose_scenes(m: &Measurements, name: Option<&str>) -> Result<SceneChoice, Error> {
    let mut names: Vec<String> = Vec::new();
    for r in &m.results {
        if !names.contains(&r.scene) {
            names.push(r.scene.clone());
        }
    }
    let bases: Vec<String> = {
        let mut b: Vec<String> = names.iter().map(|n| base_name(n)).collect();
        b.dedup();
        b
    };
    let pick = |base: &str| -> Vec<String> {
        names
            .iter()
            .filter(|n| n.as_str() == base || base_name(n) == base)
            .cloned()
            .collect()
    };
    match name {
        Some(n) => {
            let scenes = pick(n);
            if scenes.is_empty() {
                return Err(Error::input(format!(
                    "--scene: no firmware measurements for `{n}` (measured: {}; base scenes: {})",
                    names.join(", "),
                    bases.join(", ")
                )));
            }
            Ok(SceneChoice {
                name: n.to_string(),
                scenes,
            })
        }
        None => {
            let complete: Vec<&String> = bases
                .iter()
                .filter(|b| {
                    let modes: Vec<Option<Mode>> = pick(b)
                        .iter()
                        .map(|s| s.split('-').find_map(Mode::parse))
                        .collect();
                    Mode::ALL.iter().all(|m| modes.contains(&Some(*m)))
                })
                .collect();
            let chosen: Vec<String> = if complete.is_empty() {
                names.clone()
            } else {
                complete.iter().flat_map(|b| pick(b)).collect()
            };
            Ok(SceneChoice {
                name: complete
                    .iter()
                    .map(|s| s.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
                scenes: chosen,
            })
        }
    }
}

/// Mean absolute error (levels) of each profile's frame of each firmware
/// scene against the scene's ideal Phong frame, rendered on the host
/// from the built-in scene files.
///
/// # Errors
/// A scene that is not built in, or that a renderer refuses (bad input).
pub fn host_errors(
    scenes: &[String],
    profiles: &[CoreProfile],
) -> Result<BTreeMap<(String, CoreProfile), f64>, Error> {
    use rayon::prelude::*;
    let jobs: Vec<(String, CoreProfile)> = scenes
        .iter()
        .flat_map(|s| profiles.iter().map(move |p| (s.clone(), *p)))
        .collect();
    // One ideal Phong frame per scene.
    let ideals: BTreeMap<String, (IdealFrame, Vec<[u8; 3]>)> = scenes
        .par_iter()
        .map(|s| {
            let mut d = load_builtin(s)?;
            for o in &mut d.objects {
                o.shading = Mode::Phong.shading();
            }
            let f = super::sweep::ideal_frame(&d)?;
            let rgb = f.to_rgb8();
            Ok((s.clone(), (f, rgb)))
        })
        .collect::<Result<_, Error>>()?;
    jobs.par_iter()
        .map(|(s, p)| {
            let d = load_builtin(s)?;
            let frame = super::sweep::rgb_frame(&d, *p)?;
            let (f, rgb) = &ideals[s];
            let m = compare(&core_view(&frame), &ideal_view(f, rgb))
                .map_err(|e| Error::input(format!("{s}: {e}")))?;
            Ok(((s.clone(), *p), m.mean_abs_error))
        })
        .collect()
}

/// The configurations measured on `target` for `scenes`, with their
/// worst-case costs and mean errors (`errors` from [`host_errors`]), in
/// profile then mode order.
pub fn candidates(
    m: &Measurements,
    target: Target,
    scenes: &[String],
    errors: &BTreeMap<(String, CoreProfile), f64>,
) -> Vec<Candidate> {
    let mut by: BTreeMap<(CoreProfile, Option<Mode>), Vec<&ChipResult>> = BTreeMap::new();
    for r in m.of(target).filter(|r| scenes.contains(&r.scene)) {
        if let Some(p) = r.core_profile() {
            by.entry((p, r.mode)).or_default().push(r);
        }
    }
    by.into_iter()
        .map(|((profile, mode), rs)| {
            let errs: Vec<f64> = rs
                .iter()
                .filter_map(|r| errors.get(&(r.scene.clone(), profile)).copied())
                .collect();
            Candidate {
                profile,
                mode,
                scenes: rs.iter().map(|r| r.scene.clone()).collect(),
                cycles: rs.iter().map(|r| r.frame_cycles()).max().unwrap_or(0),
                ram: rs.iter().map(|r| r.ram).max().unwrap_or(0),
                error: if errs.is_empty() {
                    f64::INFINITY
                } else {
                    errs.iter().sum::<f64>() / errs.len() as f64
                },
            }
        })
        .collect()
}

/// The outcome of a pick.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// The most accurate fitting candidate and the next one.
    Fit {
        /// Index of the pick.
        chosen: usize,
        /// Index of the runner-up, if another fits.
        runner_up: Option<usize>,
    },
    /// Nothing fits: the closest candidate (least over the budget).
    NoFit {
        /// Its index.
        closest: usize,
    },
    /// No candidates at all.
    Empty,
}

/// The configurations of a user's scene file on `target`, for a pick by
/// RAM alone: the firmware renders the built-in scenes only, so their
/// cycles are not measured (`cycles` is 0 here). RAM: the host's prepared
/// frame (the bytes the chip's would take), the colour and 16-bit depth
/// bands of 16 rows, and the largest stack measured on `target` with the
/// profile; error: against the scene's ideal Phong frame.
///
/// # Errors
/// A file that does not load or that a renderer refuses (bad input).
pub fn user_scene_candidates(
    path: &std::path::Path,
    ms: &Measurements,
    target: Target,
) -> Result<Vec<Candidate>, Error> {
    use rayon::prelude::*;
    let desc = crate::scene_file::SceneDesc::load(path)?;
    let with = |m: Mode| {
        let mut d = desc.clone();
        for o in &mut d.objects {
            o.shading = m.shading();
        }
        d
    };
    let phong = super::sweep::ideal_frame(&with(Mode::Phong))?;
    let prgb = phong.to_rgb8();
    let bands = u64::from(desc.width) * u64::from(crate::core_render::BAND_ROWS) * 2 * 2;
    let jobs: Vec<(CoreProfile, Mode)> = CoreProfile::ALL
        .into_iter()
        .flat_map(|p| Mode::ALL.into_iter().map(move |m| (p, m)))
        .collect();
    jobs.par_iter()
        .filter_map(|&(p, m)| {
            let stack = ms
                .of(target)
                .filter(|r| r.profile == p.name())
                .map(|r| r.stack)
                .max()?;
            Some((p, m, stack))
        })
        .map(|(p, m, stack)| {
            let f = super::sweep::rgb_frame(&with(m), p)?;
            let e = compare(&core_view(&f), &ideal_view(&phong, &prgb))
                .map_err(|e| Error::input(format!("{}: {e}", path.display())))?;
            Ok(Candidate {
                profile: p,
                mode: Some(m),
                scenes: vec![path.display().to_string()],
                cycles: 0,
                ram: f.prepared_bytes as u64 + bands + stack,
                error: e.mean_abs_error,
            })
        })
        .collect()
}

/// Picks the most accurate fitting candidate (ties: fewer cycles).
pub fn pick(cands: &[Candidate], b: &Budget) -> Outcome {
    let mut fit: Vec<usize> = (0..cands.len()).filter(|&i| cands[i].fits(b)).collect();
    fit.sort_by(|&i, &j| {
        cands[i]
            .error
            .total_cmp(&cands[j].error)
            .then(cands[i].cycles.cmp(&cands[j].cycles))
    });
    if let Some(&chosen) = fit.first() {
        return Outcome::Fit {
            chosen,
            runner_up: fit.get(1).copied(),
        };
    }
    (0..cands.len())
        .min_by(|&i, &j| cands[i].over(b).total_cmp(&cands[j].over(b)))
        .map_or(Outcome::Empty, |closest| Outcome::NoFit { closest })
}

/// A candidate in one line for `budget`.
pub fn describe(c: &Candidate, b: &Budget, unit: &str) -> String {
    format!(
        "{}, band rows 16, depth 16 bits: {:.3} levels from the ideal Phong frame; {:.3} M {unit}/frame ({:.1} fps at {} MHz), RAM {} bytes ({:.1} KiB)",
        c.label(),
        c.error,
        c.cycles as f64 / 1e6,
        c.fps(b.mhz),
        b.mhz,
        c.ram,
        c.ram as f64 / 1024.0
    )
}

/// The cost unit of a chip family.
pub fn unit(target: Target) -> &'static str {
    match target {
        Target::M0 => "est. M0 cycles",
        Target::M4f => "instructions (= cycles at CPI 1, a lower bound)",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cand(p: CoreProfile, cycles: u64, ram: u64, error: f64) -> Candidate {
        Candidate {
            profile: p,
            mode: Some(Mode::Gouraud),
            scenes: vec!["s".into()],
            cycles,
            ram,
            error,
        }
    }

    #[test]
    fn picks_the_most_accurate_that_fits() {
        let b = Budget {
            target: Target::M0,
            mhz: 48.0,
            fps: 10.0,
            ram_bytes: 32.0 * 1024.0,
        };
        assert_eq!(b.cycles(), 4.8e6);
        let cs = vec![
            cand(CoreProfile::Fast, 1_000_000, 20_000, 1.5),
            cand(CoreProfile::Precise, 4_800_000, 20_000, 1.2),
            cand(CoreProfile::F64, 40_000_000, 30_000, 1.0),
            cand(CoreProfile::F32, 2_000_000, 40_000, 1.1),
        ];
        // F64 too slow, F32 too big: precise (exactly at the budget).
        assert_eq!(
            pick(&cs, &b),
            Outcome::Fit {
                chosen: 1,
                runner_up: Some(0)
            }
        );
        let tight = Budget { fps: 100.0, ..b };
        // 480 000 cycles: nothing fits; fast is 2.08x over, the least.
        assert_eq!(pick(&cs, &tight), Outcome::NoFit { closest: 0 });
        assert!((cs[0].over(&tight) - 1_000_000.0 / 480_000.0).abs() < 1e-12);
        assert_eq!(pick(&[], &b), Outcome::Empty);
        assert!((cs[0].fps(48.0) - 48.0).abs() < 1e-12);
    }

    #[test]
    fn chips_are_found_by_name_and_alias() {
        assert_eq!(find_chip("Cortex-M0").unwrap().target, Target::M0);
        assert_eq!(find_chip("m0+").unwrap().name, "cortex-m0");
        assert_eq!(find_chip("rp2040").unwrap().mhz, 133.0);
        assert_eq!(find_chip("STM32F4").unwrap().target, Target::M4f);
        assert!(find_chip("cortex-m7").is_none());
        for n in TABLE_CHIPS {
            assert!(find_chip(n).is_some(), "{n}");
        }
    }
}
