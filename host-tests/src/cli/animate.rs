//! `fixshade animate`: a turn of a scene, rendered by the no_std core
//! frame by frame, as an animated GIF.
//!
//! Frame `i` of `N` adds `360° · i / N` to every object's rotation about
//! Y (the middle of the X, Y, Z rotations: about the world's vertical axis
//! for objects not rotated about Z), the per-frame model transform the
//! firmware's animation uses, so the last frame leads back to the first.
//! Each object turns about its own origin: a built-in mesh's, or an OBJ
//! mesh's bounding-box centre (where the scene file's transform put it).
//! Each frame is rendered as `fixshade render` renders it (16-row bands,
//! 16-bit depth, any profile) and quantised to a 256-colour palette of its
//! own (NeuQuant, `gif`'s `Frame::from_rgb_speed`).

use std::f64::consts::TAU;
use std::io;
use std::path::PathBuf;

use clap::Args;

use crate::core_render::{render_core, CoreFrame, CoreProfile};
use crate::scene_file::SceneDesc;

use super::common::{print_stdout, write_output, SceneArgs};
use super::error::{CliError, ErrorKind};
use super::render::parse_profile;

/// Most frames of an animation: 720 (half a degree per frame), which
/// bounds the work at 720 renders of at most 4096 × 4096 pixels.
pub const MAX_FRAMES: u32 = 720;

/// Arguments of `fixshade animate`.
#[derive(Clone, Debug, Args)]
pub struct AnimateArgs {
    /// The scene.
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Frames in one turn, 1..=720.
    #[arg(long, value_name = "N", default_value_t = 36)]
    pub frames: u32,
    /// The GIF to write (replaced atomically; nothing is written on error).
    #[arg(long, value_name = "FILE.gif")]
    pub out: PathBuf,
    /// Numeric profile (as for `render`); the scene's own by default.
    #[arg(long, value_name = "PROFILE", value_parser = parse_profile)]
    pub profile: Option<CoreProfile>,
    /// Time per frame in hundredths of a second (GIF's unit), 1..=65535.
    #[arg(long, value_name = "CS", default_value_t = 4)]
    pub delay_cs: u16,
}

/// The scene of frame `i` of `n`: every object turned by `360° · i / n`
/// more about Y.
pub fn turned(desc: &SceneDesc, i: u32, n: u32) -> SceneDesc {
    let mut d = desc.clone();
    let angle = TAU * f64::from(i) / f64::from(n.max(1));
    for o in &mut d.objects {
        o.transform.rotation_rad[1] += angle;
    }
    d
}

/// Renders the turn and writes it as an animated GIF looping forever.
/// Bad input (zero or too many frames, a zero delay, a scene the core
/// refuses, an output that cannot be written) is exit status 2 and
/// writes nothing.
pub fn run(args: &AnimateArgs) -> Result<(), CliError> {
    let n = args.frames;
    if !(1..=MAX_FRAMES).contains(&n) {
        return Err(CliError::input(format!(
            "--frames: must be in 1..={MAX_FRAMES}, got {n}"
        )));
    }
    if args.delay_cs == 0 {
        return Err(CliError::input("--delay-cs: must be at least 1"));
    }
    let scene = args.scene.load()?;
    let render = |i: u32| {
        render_core(&turned(&scene, i, n), args.profile)
            .map_err(|e| CliError::input(format!("{} (frame {i}): {e}", scene.source)))
    };
    // The first frame checks the scene before anything is written.
    let first = render(0)?;
    let (w, h) = (first.width, first.height);
    let (Ok(w16), Ok(h16)) = (u16::try_from(w), u16::try_from(h)) else {
        return Err(CliError::input(format!(
            "{}: {w}x{h} is larger than a GIF's 65535x65535",
            scene.source
        )));
    };
    let mut failed: Option<CliError> = None;
    let written = write_output(&args.out, |out| {
        let mut enc = gif::Encoder::new(out, w16, h16, &[]).map_err(gif_io)?;
        enc.set_repeat(gif::Repeat::Infinite).map_err(gif_io)?;
        for i in 0..n {
            let frame = if i == 0 { Ok(first.clone()) } else { render(i) };
            let frame: CoreFrame = match frame {
                Ok(f) => f,
                Err(e) => {
                    failed = Some(e);
                    return Err(io::Error::other("render failed"));
                }
            };
            let rgb: Vec<u8> = frame.rgb.iter().flatten().copied().collect();
            let mut g = gif::Frame::from_rgb_speed(w16, h16, &rgb, 10);
            g.delay = args.delay_cs;
            enc.write_frame(&g).map_err(gif_io)?;
        }
        Ok(())
    });
    if let Some(e) = failed {
        return Err(e);
    }
    // An output that cannot be written is bad input here (exit status 2):
    // a missing folder or a path that is a folder.
    written.map_err(|e| CliError {
        kind: ErrorKind::Input,
        ..e
    })?;
    print_stdout(&format!(
        "wrote {}: {n} frames of {w}x{h}, one turn about Y, profile {}\n",
        args.out.display(),
        args.profile.unwrap_or_else(|| scene.profile.into()).name(),
    ))
}

fn gif_io(e: gif::EncodingError) -> io::Error {
    match e {
        gif::EncodingError::Io(e) => e,
        other => io::Error::other(other),
    }
}
