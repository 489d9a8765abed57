//! `fixshade pick`: the most accurate configuration whose measured chip
//! cost fits a budget (see `fixshade_host::report::picks`).
//!
//! Reads the committed firmware measurements (`--measurements FILE`,
//! default `docs/measurements/firmware.json` of the checkout), refuses
//! them when stale (bad input, unless `--allow-stale`), renders the
//! candidates' frames on the host for their error against the ideal, and
//! prints the pick and the runner-up; exit status 1 when nothing fits
//! (with the closest configuration and by how much it misses).

use clap::Args;

use crate::core_render::CoreProfile;
use crate::report::chips;
use crate::report::picks::{
    candidates, chip_names, choose_scenes, describe, find_chip, host_errors, pick, unit,
    user_scene_candidates, Budget, Outcome,
};

use super::common::print_stdout;
use super::error::{CliError, ErrorKind};

/// Arguments of `fixshade pick`.
#[derive(Clone, Debug, Args)]
pub struct PickArgs {
    /// The part: cortex-m0 (m0+, …), rp2040, stm32g0, cortex-m4f
    /// (nrf52840), stm32f407, stm32l432.
    #[arg(long)]
    pub chip: String,
    /// Clock in MHz (default: the part's usual clock).
    #[arg(long, allow_negative_numbers = true)]
    pub mhz: Option<f64>,
    /// Frames per second wanted.
    #[arg(long, allow_negative_numbers = true)]
    pub fps: f64,
    /// RAM for the renderer in KiB (default: the part's RAM).
    #[arg(long = "ram-kb", allow_negative_numbers = true)]
    pub ram_kb: Option<f64>,
    /// A firmware scene, or a base scene (`dodeca-n100`, `bunny`); by
    /// default the scenes measured in every shading mode. A scene file
    /// (`SCENE.toml`) is picked by RAM alone: its cycles are not measured.
    #[arg(long)]
    pub scene: Option<String>,
    /// `--measurements`, `--allow-stale`, `--measure-firmware` (with
    /// `--scene SCENE.toml` only) and `--firmware-profiles`.
    #[command(flatten)]
    pub chips: super::measure::ChipArgs,
}

fn positive(name: &str, v: f64) -> Result<f64, CliError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(CliError::input(format!(
            "--{name}: {v} is not a positive number"
        )))
    }
}

/// Reads the measurements, picks and prints.
pub fn run(args: &PickArgs) -> Result<(), CliError> {
    let chip = find_chip(&args.chip).ok_or_else(|| {
        CliError::input(format!(
            "--chip: unknown chip `{}` (known: {})",
            args.chip,
            chip_names()
        ))
    })?;
    let budget = Budget {
        target: chip.target,
        mhz: positive("mhz", args.mhz.unwrap_or(chip.mhz))?,
        fps: positive("fps", args.fps)?,
        ram_bytes: positive("ram-kb", args.ram_kb.unwrap_or(chip.ram_kb))? * 1024.0,
    };
    let path = args.chips.measurements.path();
    let m = chips::load(&path)?;
    if !args.chips.measurements.allow_stale {
        chips::check_fresh(&m, &chips::repo_root(), &path.display().to_string())?;
    }
    if let Some(file) = args
        .scene
        .as_deref()
        .filter(|s| s.ends_with(".toml") || std::path::Path::new(s).is_file())
    {
        let file = std::path::Path::new(file);
        if args.chips.measure_firmware {
            let profiles = args.chips.firmware_profiles.profiles()?;
            return pick_file_measured(file, chip, &budget, &m, &profiles);
        }
        return pick_file(file, chip, &budget, &m, &path);
    }
    if args.chips.measure_firmware {
        return Err(CliError::input(
            "--measure-firmware measures your scene: give it with --scene SCENE.toml (the built-in scenes' figures are in the measurements file; `fixshade measure-firmware` re-measures them)".to_string(),
        ));
    }
    let choice = choose_scenes(&m, args.scene.as_deref())?;
    let errors = host_errors(&choice.scenes, &CoreProfile::ALL)?;
    let cands = candidates(&m, chip.target, &choice.scenes, &errors);
    let text = format!(
        "{}scenes: {} (worst case over: {})\n\
         figures: {} ({}, {}); errors: mean absolute error in 8-bit levels against the ideal Phong frame, rendered on this host\n",
        budget_line(chip, &budget),
        choice.name,
        choice.scenes.join(", "),
        path.display(),
        m.toolchain,
        m.source_fingerprint,
    );
    let what = format!(
        "{}: no measurements for {} on {}",
        path.display(),
        choice.name,
        chip.target.title()
    );
    print_pick(text, &cands, chip, &budget, &what)
}

/// The first line of a pick: the chip and what the budget allows per
/// frame.
fn budget_line(chip: &crate::report::picks::Chip, budget: &Budget) -> String {
    format!(
        "chip: {} ({}): {} MHz, {} fps, {:.0} bytes RAM: at most {:.3} M {} per frame\n",
        chip.name,
        chip.target.title(),
        budget.mhz,
        budget.fps,
        budget.ram_bytes,
        budget.cycles() / 1e6,
        unit(chip.target),
    )
}

/// Prints the pick of `cands` for `budget` after `text`; nothing fits:
/// the closest and by how much, exit status 1; no candidates: bad input
/// `empty`.
fn print_pick(
    mut text: String,
    cands: &[crate::report::picks::Candidate],
    chip: &crate::report::picks::Chip,
    budget: &Budget,
    empty: &str,
) -> Result<(), CliError> {
    let budget = *budget;
    let u = unit(chip.target);
    match pick(cands, &budget) {
        Outcome::Fit { chosen, runner_up } => {
            text += &format!("pick: {}\n", describe(&cands[chosen], &budget, u));
            match runner_up {
                Some(r) => text += &format!("runner-up: {}\n", describe(&cands[r], &budget, u)),
                None => text += "runner-up: none (no other configuration fits)\n",
            }
            print_stdout(&text)
        }
        Outcome::NoFit { closest } => {
            let c = &cands[closest];
            text += &format!("nothing fits. closest: {}\n", describe(c, &budget, u));
            let mut misses = Vec::new();
            if c.cycles as f64 > budget.cycles() {
                misses.push(format!(
                    "{:.0} % over the cycles ({:.1} fps reachable, or {:.0} MHz for {} fps)",
                    100.0 * (c.cycles as f64 / budget.cycles() - 1.0),
                    c.fps(budget.mhz),
                    c.cycles as f64 * budget.fps / 1e6,
                    budget.fps
                ));
            }
            if c.ram as f64 > budget.ram_bytes {
                misses.push(format!(
                    "{} bytes over the RAM",
                    (c.ram as f64 - budget.ram_bytes).ceil()
                ));
            }
            text += &format!("it misses by: {}\n", misses.join("; "));
            print_stdout(&text)?;
            Err(CliError {
                kind: ErrorKind::Io,
                message: format!(
                    "nothing fits {} at {} MHz, {} fps, {:.0} KiB",
                    chip.name,
                    budget.mhz,
                    budget.fps,
                    budget.ram_bytes / 1024.0
                ),
            })
        }
        Outcome::Empty => Err(CliError::input(empty.to_string())),
    }
}

/// `--scene FILE --measure-firmware`: the firmware generated for the
/// user's scene, measured on the chip's target in every mode and in
/// `profiles`; picked by its measured cycles and RAM and its error
/// against the ideal Phong frame (host).
fn pick_file_measured(
    file: &std::path::Path,
    chip: &crate::report::picks::Chip,
    budget: &Budget,
    m: &chips::Measurements,
    profiles: &[CoreProfile],
) -> Result<(), CliError> {
    use crate::report::measure::{measure_user_scenes, UserMeasureOptions, TARGETS};
    // Errors against the ideal Phong frame, per profile and mode (the
    // RAM-only candidates carry them): bad scene files fail here first.
    let host = user_scene_candidates(file, m, chip.target)?;
    let target = TARGETS
        .iter()
        .find(|t| chips::target_of(t.0) == Some(chip.target))
        .map(|t| t.0.to_string())
        .unwrap_or_default();
    let um = measure_user_scenes(&UserMeasureOptions {
        root: chips::repo_root(),
        files: vec![file.to_path_buf()],
        profiles: profiles.to_vec(),
        targets: vec![target],
        progress: true,
    })?;
    let errors = um
        .results
        .iter()
        .filter_map(|r| {
            let p = r.core_profile()?;
            let e = host
                .iter()
                .find(|c| c.profile == p && c.mode == r.mode)?
                .error;
            Some(((r.scene.clone(), p), e))
        })
        .collect();
    let mut names: Vec<String> = um.results.iter().map(|r| r.scene.clone()).collect();
    names.dedup();
    let cands = candidates(&um, chip.target, &names, &errors);
    let text = format!(
        "{}scene: {} (your scene file), measured: the firmware generated for it, run under QEMU ({}, {})\n\
         figures: RAM = colour band + depth band (none for one convex culled object) + storage + pool + stack, as the firmware reports it; errors: mean absolute error in 8-bit levels against the ideal Phong frame, rendered on this host\n",
        budget_line(chip, budget),
        file.display(),
        um.toolchain,
        um.qemu,
    );
    let empty = format!(
        "{}: nothing measured on {}",
        file.display(),
        chip.target.title()
    );
    print_pick(text, &cands, chip, budget, &empty)
}

/// `--scene FILE`: the user's scene, picked by RAM alone (its cycles are
/// not measured: the firmware renders the built-in scenes).
fn pick_file(
    file: &std::path::Path,
    chip: &crate::report::picks::Chip,
    budget: &Budget,
    m: &chips::Measurements,
    path: &std::path::Path,
) -> Result<(), CliError> {
    let cands = user_scene_candidates(file, m, chip.target)?;
    let ram_only = Budget {
        fps: f64::MIN_POSITIVE,
        ..*budget
    };
    let line = |c: &crate::report::picks::Candidate| {
        format!(
            "{}, band rows 16, depth 16 bits: {:.3} levels from the ideal Phong frame; RAM {} bytes ({:.1} KiB)",
            c.label(),
            c.error,
            c.ram,
            c.ram as f64 / 1024.0
        )
    };
    let mut text = format!(
        "chip: {} ({}): {:.0} bytes RAM\nscene: {} (your scene file)\ncycles: not measured for your scene (add --measure-firmware to build the firmware for it and measure it under QEMU), so this pick is by RAM and accuracy alone; the built-in scenes' cycles: `fixshade pick --chip {} --fps {}`\nfigures: stacks from {}; RAM = prepared frame (host, the same bytes as on the chip) + colour and depth bands + stack\n",
        chip.name,
        chip.target.title(),
        budget.ram_bytes,
        file.display(),
        chip.name,
        budget.fps,
        path.display()
    );
    match pick(&cands, &ram_only) {
        Outcome::Fit { chosen, runner_up } => {
            text += &format!("pick: {}\n", line(&cands[chosen]));
            if let Some(r) = runner_up {
                text += &format!("runner-up: {}\n", line(&cands[r]));
            }
            print_stdout(&text)
        }
        Outcome::NoFit { closest } => {
            let c = &cands[closest];
            text += &format!(
                "nothing fits: your scene is too big for {:.0} bytes of RAM. closest: {}; {} bytes over\n",
                budget.ram_bytes,
                line(c),
                (c.ram as f64 - budget.ram_bytes).ceil()
            );
            print_stdout(&text)?;
            Err(CliError {
                kind: ErrorKind::Io,
                message: format!(
                    "{}: too big for {:.0} KiB of RAM (needs at least {} bytes)",
                    file.display(),
                    budget.ram_bytes / 1024.0,
                    c.ram
                ),
            })
        }
        Outcome::Empty => Err(CliError::input(format!(
            "{}: no stack measurements for {}",
            path.display(),
            chip.target.title()
        ))),
    }
}
