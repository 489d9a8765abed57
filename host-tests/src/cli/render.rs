//! `fixshade render`: renders a scene with the no_std core to PNG.

use std::path::PathBuf;

use clap::Args;

use crate::core_render::{crc32, render_core, CoreProfile};
use crate::image::write_png;

use super::common::{print_stdout, SceneArgs};
use super::error::CliError;

/// Arguments of `fixshade render`.
#[derive(Clone, Debug, Args)]
pub struct RenderArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// The PNG to write (replaced atomically).
    #[arg(long, value_name = "FILE.png")]
    pub out: PathBuf,
    /// Numeric profile (fast, precise, f32, f64, fast-pc, precise-pc,
    /// f32-pc, f64-pc); the scene's own by default.
    #[arg(long, value_name = "PROFILE", value_parser = parse_profile)]
    pub profile: Option<CoreProfile>,
    /// Print the CRC-32 of the raw frame buffer bytes in the scene's pixel
    /// format (RGB565 big-endian), as the firmware prints it.
    #[arg(long)]
    pub crc: bool,
}

/// Parses a profile name for clap.
pub fn parse_profile(s: &str) -> Result<CoreProfile, String> {
    CoreProfile::parse(s).ok_or_else(|| {
        let names: Vec<_> = CoreProfile::ALL.iter().map(|p| p.name()).collect();
        format!("unknown profile `{s}` (one of: {})", names.join(", "))
    })
}

/// Renders the scene with the core, in 16-row bands with a 16-bit depth
/// band as a firmware does, and writes it as 8-bit RGB PNG.
pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let scene = args.scene.load()?;
    let frame = render_core(&scene, args.profile)
        .map_err(|e| CliError::input(format!("{}: {e}", scene.source)))?;
    write_png(&args.out, frame.width, frame.height, &frame.rgb)
        .map_err(|e| CliError::io(&args.out, &e))?;
    let profile = args.profile.unwrap_or_else(|| scene.profile.into());
    let mut text = format!(
        "wrote {}: {}x{} {} with profile {}, {} covered pixels\n",
        args.out.display(),
        frame.width,
        frame.height,
        scene.pixel_format.name(),
        profile.name(),
        frame.covered.iter().filter(|&&c| c).count()
    );
    if args.crc {
        text.push_str(&format!("crc32 {:08x}\n", crc32(&frame.bytes)));
    }
    print_stdout(&text)
}
