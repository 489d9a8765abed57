//! `fixshade ideal`: renders a scene with the ideal f64 reference to PNG.

use std::path::PathBuf;

use clap::Args;

use crate::ideal::render;
use crate::image::write_png;

use super::common::{print_stdout, SceneArgs};
use super::error::CliError;

/// Arguments of `fixshade ideal`.
#[derive(Clone, Debug, Args)]
pub struct IdealArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The PNG to write (replaced atomically).
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
}

/// Renders the scene with [`render`] and writes it as 8-bit RGB PNG
/// (`round(c * 255)` per channel, not reduced to the scene's pixel
/// format).
pub fn run(args: &IdealArgs) -> Result<(), CliError> {
    let scene = args.scene.load()?;
    let frame =
        render(&scene.to_ideal()).map_err(|e| CliError::input(format!("{}: {e}", scene.source)))?;
    write_png(&args.out, frame.width, frame.height, &frame.to_rgb8())
        .map_err(|e| CliError::io(&args.out, &e))?;
    print_stdout(&format!(
        "wrote {}: {}x{}, {} covered pixels\n",
        args.out.display(),
        frame.width,
        frame.height,
        frame.covered_count()
    ))
}
