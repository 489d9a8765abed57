//! `fixshade scenes`: lists the built-in scenes.

use clap::Args;

use crate::builtin::builtin_scenes;

use super::common::print_stdout;
use super::error::CliError;

/// Arguments of `fixshade scenes` (none).
#[derive(Clone, Debug, Args)]
pub struct ScenesArgs {}

/// Prints one line per built-in scene: its name, then its description.
pub fn run(_args: &ScenesArgs) -> Result<(), CliError> {
    let width = builtin_scenes()
        .iter()
        .map(|(name, _, _)| name.len())
        .max()
        .unwrap_or(0);
    let text: String = builtin_scenes()
        .iter()
        .map(|(name, description, _)| format!("{name:width$}  {description}\n"))
        .collect();
    print_stdout(&text)
}
