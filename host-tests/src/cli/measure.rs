//! `fixshade measure-firmware`: the chip costs of every profile, measured
//! under QEMU (see `fixshade_host::report::measure`), written to or
//! checked against the committed file (`docs/measurements/firmware.json`).

use std::path::PathBuf;

use clap::Args;

use crate::core_render::CoreProfile;
use crate::report::chips::{self, REGENERATE};
use crate::report::measure::{measure_firmware, MeasureOptions};

use super::common::{print_stdout, write_atomically};
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
    /// FILE's.
    #[arg(long, value_name = "FILE")]
    pub check: Option<PathBuf>,
    /// Only these profiles (comma-separated; all by default).
    #[arg(long, value_delimiter = ',', value_name = "NAMES")]
    pub profiles: Vec<String>,
}

/// Measures, then writes or checks.
pub fn run(args: &MeasureArgs) -> Result<(), CliError> {
    let profiles = if args.profiles.is_empty() {
        CoreProfile::ALL.to_vec()
    } else {
        args.profiles
            .iter()
            .map(|p| {
                CoreProfile::parse(p)
                    .ok_or_else(|| CliError::input(format!("--profiles: unknown profile `{p}`")))
            })
            .collect::<Result<_, _>>()?
    };
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
        write_atomically(path, |out| out.write_all(json.as_bytes()))?;
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
        let diff = old.differences(&m);
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
            "{}: every figure agrees with a fresh measurement\n",
            path.display()
        ));
    }
    if args.write.is_none() && args.check.is_none() {
        text.push_str(&json);
    }
    print_stdout(&text)
}
