//! `fixshade report`: the accuracy-versus-speed report.

use std::path::PathBuf;

use clap::Args;

use crate::report::{run_report, ReportOptions};

use super::common::print_stdout;
use super::error::CliError;

/// Arguments of `fixshade report`.
#[derive(Clone, Debug, Args)]
pub struct ReportArgs {
    /// Your scene files (TOML) to sweep instead of the built-in scenes.
    #[arg(value_name = "SCENE.toml")]
    pub scenes: Vec<PathBuf>,
    /// The folder to write `index.html`, `report.md`, `results.json` and
    /// `img/` into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// A short run: three scenes at half size, three timed runs each.
    #[arg(long)]
    pub quick: bool,
    /// The firmware's results (`RESULT key=value` lines or JSON, see
    /// `fixshade_host::report`); without it the report says embedded
    /// figures are not available.
    #[arg(long, value_name = "FILE")]
    pub firmware_results: Option<PathBuf>,
    /// `--measurements`, `--allow-stale`, `--measure-firmware` and
    /// `--firmware-profiles`.
    #[command(flatten)]
    pub chips: super::measure::ChipArgs,
}

/// Runs the sweep and writes the report; prints the summary and the files.
pub fn run(args: &ReportArgs) -> Result<(), CliError> {
    let out = run_report(&ReportOptions {
        out: args.out.clone(),
        quick: args.quick,
        firmware_results: args.firmware_results.clone(),
        progress: true,
        measurements: args.chips.measurements.measurements.clone(),
        allow_stale: args.chips.measurements.allow_stale,
        measure_firmware: args.chips.measure_firmware,
        firmware_profiles: args.chips.firmware_profiles.profiles()?,
        scene_files: args.scenes.clone(),
    })?;
    let mut text = String::new();
    for line in &out.data.summary {
        text.push_str("* ");
        text.push_str(line);
        text.push('\n');
    }
    text.push_str(&format!(
        "{} records in {:.1} s{}\n",
        out.data.records.len(),
        out.data.meta.elapsed_s,
        if out.data.meta.debug_build {
            " (debug build)"
        } else {
            ""
        }
    ));
    for f in &out.files {
        text.push_str(&format!("wrote {}\n", f.display()));
    }
    print_stdout(&text)
}
