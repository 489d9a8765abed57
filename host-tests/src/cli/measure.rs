//! `fixshade measure-firmware`: the chip costs of every profile, measured
//! under QEMU (see `fixshade_host::report::measure`), written to or
//! checked against the committed file (`docs/measurements/firmware.json`).

use std::path::PathBuf;

use clap::Args;

use crate::core_render::CoreProfile;
use crate::report::chips::{self, REGENERATE};
use crate::report::measure::{
    measure_firmware, measure_user_scenes, MeasureOptions, UserMeasureOptions, TARGETS,
};

use super::common::{print_stdout, write_output};
use super::error::{CliError, ErrorKind};

/// Arguments of `fixshade measure-firmware` (`--write` also rewrites the
/// generated tables of `README.md` and `docs/accuracy.md`).
#[derive(Clone, Debug, Args)]
pub struct MeasureArgs {
    /// Write the measurements to FILE (e.g.
    /// docs/measurements/firmware.json).
    #[arg(long, value_name = "FILE", conflicts_with = "check")]
    pub write: Option<PathBuf>,
    /// Re-measure and fail (exit status 1) when any figure differs from
    /// FILE's. With --profiles, only those profiles' figures are
    /// re-measured and compared; FILE must still have been measured from
    /// these sources (its source fingerprint, toolchain and QEMU equal to
    /// the checkout's), so the other profiles' figures are current too.
    #[arg(long, value_name = "FILE")]
    pub check: Option<PathBuf>,
    /// Only these profiles (comma-separated; all by default).
    #[arg(long, value_delimiter = ',', value_name = "NAMES")]
    pub profiles: Vec<String>,
    /// Measure your scene files instead of the built-in scenes (each in
    /// flat, Gouraud and Phong; their OBJ meshes baked into the
    /// firmware). Repeatable.
    #[arg(long = "scene", value_name = "SCENE.toml", conflicts_with = "check")]
    pub scenes: Vec<PathBuf>,
    /// Only these targets (comma-separated: thumbv6m-none-eabi,
    /// thumbv7em-none-eabihf; both by default). With --scene only.
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "TARGETS",
        requires = "scenes"
    )]
    pub targets: Vec<String>,
}

/// The chip measurements' options of `fixshade report` and `fixshade
/// pick`: flatten it into their arguments with `#[command(flatten)]`.
#[derive(Clone, Debug, Default, Args)]
pub struct ChipArgs {
    /// `--measurements` and `--allow-stale`.
    #[command(flatten)]
    pub measurements: MeasurementsArgs,
    /// Measure under QEMU (needs qemu-system-arm, gcc and the thumb
    /// targets; minutes). `report`: re-measure every profile on both
    /// chips; with scene files, generate the firmware for your scenes
    /// (their OBJ meshes baked in), build it for both chips and measure
    /// it. `pick --scene SCENE.toml`: the same for your scene on the
    /// chip's target, so the pick weighs its measured cycles too.
    #[arg(long)]
    pub measure_firmware: bool,
    /// `--firmware-profiles`: what --measure-firmware measures.
    #[command(flatten)]
    pub firmware_profiles: FirmwareProfilesArgs,
}

/// `--measurements FILE` and `--allow-stale` of `fixshade report` and
/// `fixshade pick`: flatten it into their arguments with
/// `#[command(flatten)]`.
#[derive(Clone, Debug, Default, Args)]
pub struct MeasurementsArgs {
    /// The chip measurements (default: docs/measurements/firmware.json of
    /// the checkout; refused when stale).
    #[arg(long, value_name = "FILE")]
    pub measurements: Option<PathBuf>,
    /// Use chip measurements made from other sources (their source
    /// fingerprint differs from the tree's; a report's page says so).
    #[arg(long)]
    pub allow_stale: bool,
}

impl MeasurementsArgs {
    /// The measurements file: `--measurements`, else the checkout's
    /// [`chips::DEFAULT_PATH`].
    pub fn path(&self) -> PathBuf {
        self.measurements
            .clone()
            .unwrap_or_else(|| chips::repo_root().join(chips::DEFAULT_PATH))
    }
}

/// `--firmware-profiles NAMES` of `fixshade report` and `fixshade pick`
/// (with `--measure-firmware` only): flatten it into their arguments with
/// `#[command(flatten)]`.
#[derive(Clone, Debug, Default, Args)]
pub struct FirmwareProfilesArgs {
    /// The profiles --measure-firmware measures (comma-separated; all by
    /// default).
    #[arg(
        long,
        value_delimiter = ',',
        value_name = "NAMES",
        requires = "measure_firmware"
    )]
    pub firmware_profiles: Vec<String>,
}

impl FirmwareProfilesArgs {
    /// The profiles named (all when none).
    ///
    /// # Errors
    /// An unknown name (bad input).
    pub fn profiles(&self) -> Result<Vec<CoreProfile>, CliError> {
        parse_profiles(&self.firmware_profiles, "firmware-profiles")
    }
}

/// The profiles named on a command line (all when none).
///
/// # Errors
/// An unknown name (bad input).
pub fn parse_profiles(names: &[String], option: &str) -> Result<Vec<CoreProfile>, CliError> {
    if names.is_empty() {
        return Ok(CoreProfile::ALL.to_vec());
    }
    names
        .iter()
        .map(|p| {
            CoreProfile::parse(p)
                .ok_or_else(|| CliError::input(format!("--{option}: unknown profile `{p}`")))
        })
        .collect()
}

/// The user's scenes measured, written to `--write` or printed.
fn run_scenes(args: &MeasureArgs, profiles: Vec<CoreProfile>) -> Result<(), CliError> {
    let targets = if args.targets.is_empty() {
        TARGETS.iter().map(|t| t.0.to_string()).collect()
    } else {
        args.targets.clone()
    };
    let m = measure_user_scenes(&UserMeasureOptions {
        root: chips::repo_root(),
        files: args.scenes.clone(),
        profiles,
        targets,
        progress: true,
    })?;
    let json = serde_json::to_string_pretty(&m)
        .map_err(|e| CliError::input(format!("cannot serialise the measurements: {e}")))?
        + "\n";
    let mut text = String::new();
    for r in &m.results {
        text.push_str(&format!(
            "{} {} {}: {} instructions{}, RAM {} B (stack {} B), flash {} B, CRC {} (host {})\n",
            r.scene,
            r.profile,
            r.target,
            r.insns,
            r.cycles
                .map(|c| format!(", {c} est. M0 cycles"))
                .unwrap_or_default(),
            r.ram,
            r.stack,
            r.flash,
            r.crc,
            r.host_crc
        ));
    }
    match &args.write {
        Some(path) => {
            write_output(path, |out| out.write_all(json.as_bytes()))?;
            text.push_str(&format!("wrote {}\n", path.display()));
        }
        None => text.push_str(&json),
    }
    print_stdout(&text)
}

/// Measures, then writes or checks.
pub fn run(args: &MeasureArgs) -> Result<(), CliError> {
    let profiles = parse_profiles(&args.profiles, "profiles")?;
    let names: Vec<&str> = profiles.iter().map(|p| p.name()).collect();
    if !args.scenes.is_empty() {
        return run_scenes(args, profiles);
    }
    // Read the file to check first: bad input before minutes of work.
    let committed = match &args.check {
        Some(path) => Some(chips::load(path)?),
        None => None,
    };
    let m = measure_firmware(&MeasureOptions {
        root: chips::repo_root(),
        profiles,
        progress: true,
    })?;
    let json = serde_json::to_string_pretty(&m)
        .map_err(|e| CliError::input(format!("cannot serialise the measurements: {e}")))?
        + "\n";
    let mut text = format!(
        "{} results ({} builds), {}, sources {}\n",
        m.results.len(),
        m.builds.len(),
        m.toolchain,
        m.source_fingerprint
    );
    if let Some(path) = &args.write {
        write_output(path, |out| out.write_all(json.as_bytes()))?;
        text.push_str(&format!("wrote {}\n", path.display()));
        // The tables generated from it (README, docs/accuracy.md), so one
        // command regenerates every figure: only from a whole measurement
        // written to the committed file.
        let root = chips::repo_root();
        let committed_file = std::fs::canonicalize(path).ok()
            == std::fs::canonicalize(root.join(chips::DEFAULT_PATH)).ok();
        let tables = if committed_file && args.profiles.is_empty() {
            crate::report::docs_tables::write_blocks(&root, &m)?
        } else {
            Vec::new()
        };
        for f in tables {
            text.push_str(&format!(
                "rewrote the generated tables of {}\n",
                f.display()
            ));
        }
    }
    if let (Some(path), Some(old)) = (&args.check, committed) {
        let diff = old.restricted_to(&names).differences(&m);
        if !diff.is_empty() {
            return Err(CliError {
                kind: ErrorKind::Io,
                message: format!(
                    "{}: stale: {} figure(s) differ from a fresh measurement: {}; regenerate with `{REGENERATE}` and commit it",
                    path.display(),
                    diff.len(),
                    diff.iter().take(12).cloned().collect::<Vec<_>>().join("; ")
                ),
            });
        }
        text.push_str(&format!(
            "{}: every figure {}agrees with a fresh measurement (sources {})\n",
            path.display(),
            if args.profiles.is_empty() {
                String::new()
            } else {
                format!("of {} ", names.join(", "))
            },
            m.source_fingerprint
        ));
    }
    if args.write.is_none() && args.check.is_none() {
        text.push_str(&json);
    }
    print_stdout(&text)
}
