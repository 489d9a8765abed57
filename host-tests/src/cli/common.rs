//! Helpers shared by the subcommands: choosing a scene and writing output
//! files atomically.

use std::io::{self, Write};
use std::path::{Path, PathBuf};

use clap::Args;

use crate::builtin::load_builtin;
use crate::scene_file::SceneDesc;

use super::error::CliError;

/// A scene given either as a file or as `--scene NAME` (exactly one).
/// Flatten it into a subcommand's arguments with `#[command(flatten)]`.
#[derive(Clone, Debug, Args)]
#[group(required = true, multiple = false)]
pub struct SceneArgs {
    /// Scene file (TOML); OBJ paths in it are relative to its folder.
    #[arg(value_name = "SCENE.toml")]
    pub file: Option<PathBuf>,
    /// A built-in scene instead of a file (see `fixshade scenes`).
    #[arg(long = "scene", value_name = "NAME")]
    pub name: Option<String>,
}

impl SceneArgs {
    /// Loads and checks the scene; errors are bad input.
    pub fn load(&self) -> Result<SceneDesc, CliError> {
        match (&self.file, &self.name) {
            (Some(path), _) => Ok(SceneDesc::load(path)?),
            (None, Some(name)) => Ok(load_builtin(name)?),
            (None, None) => Err(CliError::input(
                "give a scene file or --scene NAME (see `fixshade scenes`)",
            )),
        }
    }
}

/// Writes a subcommand's output file `path` atomically
/// ([`crate::output::write_atomically`]); failures are
/// [`ErrorKind::Io`](super::ErrorKind::Io) errors naming `path`.
pub fn write_output(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), CliError> {
    crate::output::write_atomically(path, write).map_err(|e| CliError::io(path, &e))
}

/// Writes `text` to standard output; a closed pipe (as with `| head`) is
/// not an error.
pub fn print_stdout(text: &str) -> Result<(), CliError> {
    let mut out = io::stdout().lock();
    match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != io::ErrorKind::BrokenPipe => {
            Err(CliError::io(Path::new("<stdout>"), &e))
        }
        _ => Ok(()),
    }
}
