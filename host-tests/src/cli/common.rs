//! Helpers shared by the subcommands: choosing a scene and writing output
//! files atomically.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

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

/// Writes `path` through `write`: the data goes to a temporary file in the
/// same folder which is then renamed over `path`, so `path` is either left
/// untouched or replaced by the complete output. Failures are
/// [`ErrorKind::Io`](super::ErrorKind::Io) errors.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> Result<(), CliError> {
    let fail = |e: io::Error| CliError::io(path, &e);
    let name = path
        .file_name()
        .ok_or_else(|| fail(io::Error::new(io::ErrorKind::InvalidInput, "no file name")))?;
    // Unique per process and call.
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let tmp = path.with_file_name(format!(
        ".{}.tmp{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    let result = File::create(&tmp).and_then(|file| {
        let mut out = BufWriter::new(file);
        write(&mut out)?;
        out.into_inner().map_err(|e| e.into_error())?.sync_all()
    });
    match result.and_then(|()| std::fs::rename(&tmp, path)) {
        Ok(()) => Ok(()),
        Err(e) => {
            // Best effort: the temporary file may not exist.
            let _ = std::fs::remove_file(&tmp);
            Err(fail(e))
        }
    }
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
