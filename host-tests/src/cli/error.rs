//! Errors of the `fixshade` command and their exit statuses.

use std::fmt;
use std::path::Path;

use crate::scene_file::SceneError;

/// What kind of failure an error is; decides the exit status.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ErrorKind {
    /// Bad input: a bad scene, OBJ or option (exit status 2, like usage
    /// errors). Nothing was written.
    Input,
    /// A failure while writing the output or measuring, or a pick that
    /// finds nothing (exit status 1).
    Io,
}

/// A failure of a subcommand, printed as one line `error: MESSAGE`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct CliError {
    /// What kind of failure.
    pub kind: ErrorKind,
    /// The message, on one line: `FILE: FIELD: problem` for bad input.
    pub message: String,
}

impl CliError {
    /// A bad-input error.
    pub fn input(message: impl Into<String>) -> Self {
        Self {
            kind: ErrorKind::Input,
            message: message.into(),
        }
    }

    /// An I/O error while writing `path`.
    pub fn io(path: &Path, error: &std::io::Error) -> Self {
        Self {
            kind: ErrorKind::Io,
            message: format!("{}: cannot write: {error}", path.display()),
        }
    }

    /// The process exit status: 2 for bad input, 1 for I/O failures.
    pub fn exit_status(&self) -> u8 {
        match self.kind {
            ErrorKind::Input => 2,
            ErrorKind::Io => 1,
        }
    }
}

impl From<crate::report::Error> for CliError {
    /// Bad input (and a measurement lock that cannot be taken) is exit
    /// status 2; a failed write or measurement 1.
    fn from(e: crate::report::Error) -> Self {
        Self {
            kind: if e.is_input() {
                ErrorKind::Input
            } else {
                ErrorKind::Io
            },
            message: e.to_string(),
        }
    }
}

impl From<SceneError> for CliError {
    fn from(e: SceneError) -> Self {
        Self::input(e.to_string())
    }
}

impl fmt::Display for CliError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for CliError {}
