//! The errors of the report, the pick and the chip measurements.
//!
//! The library names what went wrong; the command line (the `cli` module)
//! decides the exit status: 2 for [`Error::Input`], [`Error::Scene`] and
//! [`Error::Lock`]
//! (bad input, found before any output is written), 1 for
//! [`Error::Write`] and [`Error::Measurement`].

use std::io;
use std::path::{Path, PathBuf};

use crate::scene_file::SceneError;

/// Why a report, a pick or a measurement failed. Displays as one line.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// Bad input: a scene the renderers refuse, a measurements or results
    /// file that is missing, malformed or stale, an unknown name, a
    /// missing tool. The message names the file or option.
    #[error("{0}")]
    Input(String),
    /// A scene file or built-in scene that does not load (bad input).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// Writing `path` (a file or a folder) failed.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// What could not be written.
        path: PathBuf,
        /// Why.
        #[source]
        source: io::Error,
    },
    /// The lock that keeps two measurements from sharing the staged
    /// sources could not be created or taken.
    #[error(
        "{}: cannot create or take the lock that keeps two measurements from sharing the staged sources: {source}",
        path.display()
    )]
    Lock {
        /// The lock file.
        path: PathBuf,
        /// Why.
        #[source]
        source: io::Error,
    },
    /// A measurement failed: a firmware build or QEMU run, a plugin
    /// warning, firmware output that does not parse, a chip CRC that
    /// differs from the host's.
    #[error("{0}")]
    Measurement(String),
}

impl Error {
    /// A bad-input error with `message`.
    pub fn input(message: impl Into<String>) -> Self {
        Self::Input(message.into())
    }

    /// Writing `path` failed with `source`.
    pub fn write(path: &Path, source: io::Error) -> Self {
        Self::Write {
            path: path.to_path_buf(),
            source,
        }
    }

    /// Whether it is bad input (rather than a failure while writing or
    /// measuring).
    pub fn is_input(&self) -> bool {
        matches!(self, Self::Input(_) | Self::Scene(_) | Self::Lock { .. })
    }
}
