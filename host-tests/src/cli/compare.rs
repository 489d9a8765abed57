//! `fixshade compare`: a profile against its float twin and the ideal.

use std::path::PathBuf;

use clap::Args;

use crate::compare::compare_scene;
use crate::core_render::CoreProfile;

use super::common::{print_stdout, SceneArgs};
use super::error::CliError;
use super::render::parse_profile;

/// Arguments of `fixshade compare`.
#[derive(Clone, Debug, Args)]
pub struct CompareArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The folder to write into (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
    /// Numeric profile; the scene's own by default.
    #[arg(long, value_name = "PROFILE", value_parser = parse_profile)]
    pub profile: Option<CoreProfile>,
}

/// Writes `fixed.png`, `float.png` (the f64 twin), `ideal.png`, `diff.png`
/// (heat-map against the ideal), `diff_float.png` and `metrics.json`.
pub fn run(args: &CompareArgs) -> Result<(), CliError> {
    let scene = args.scene.load()?;
    std::fs::create_dir_all(&args.out).map_err(|e| CliError::io(&args.out, &e))?;
    let profile = args.profile.unwrap_or_else(|| scene.profile.into());
    let c = compare_scene(&scene, profile)
        .map_err(|e| CliError::input(format!("{}: {e}", scene.source)))?;
    c.write(&args.out)
        .map_err(|e| CliError::io(&args.out, &e))?;
    let m = &c.metrics;
    print_stdout(&format!(
        "{} with {}: vs f64 twin max {} mean {:.3} coverage mismatch {}; vs ideal max {} mean {:.3} coverage mismatch {}\nwrote {}\n",
        scene.source,
        profile.name(),
        m.vs_float.max_abs_error,
        m.vs_float.mean_abs_error,
        m.vs_float.coverage_mismatch,
        m.vs_ideal.max_abs_error,
        m.vs_ideal.mean_abs_error,
        m.vs_ideal.coverage_mismatch,
        args.out.display()
    ))
}
