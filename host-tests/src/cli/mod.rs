//! The `fixshade` command line (`src/bin/fixshade.rs` only calls
//! [`main`]).
//!
//! # Structure
//!
//! * [`Cli`] is the clap parser; [`Command`] has one variant per
//!   subcommand, holding that subcommand's argument struct;
//!   [`Command::run`] dispatches to the subcommand's `run` function.
//! * One module per subcommand: [`scenes`], [`bake`], [`ideal`],
//!   [`render`], [`compare`], [`report`], [`animate`], each with
//!   its `...Args` struct and `pub fn run(&Args) -> Result<(), CliError>`.
//! * Shared helpers in [`common`]: [`SceneArgs`] (a scene file or
//!   `--scene NAME`, flattened into a subcommand's arguments, with
//!   [`SceneArgs::load`]), [`write_output`] (temporary file then
//!   rename) and [`print_stdout`].
//! * [`CliError`] carries the exit status: 2 for bad input ([`ErrorKind::Input`],
//!   as clap's usage errors), 1 for I/O failures while writing
//!   ([`ErrorKind::Io`]). Errors print as one line `error: MESSAGE` on
//!   stderr; for scenes `MESSAGE` is `FILE: FIELD: problem`. A failing
//!   subcommand writes no output file and leaves an existing one
//!   untouched.
//!
//! * Only this module knows messages' exit statuses: the library modules
//!   return their own errors ([`crate::report::Error`],
//!   [`crate::scene_file::SceneError`], `std::io::Error`, ...), which
//!   [`CliError`] maps (its `From` impls; bad input 2, failures 1). No
//!   module outside `cli` and `bin` imports from `cli`.
//!
//! Adding a subcommand: a module with its `Args` struct and `run`, one
//! [`Command`] variant and its arm in [`Command::run`].

pub mod animate;
pub mod bake;
pub mod common;
pub mod compare;
mod error;
pub mod ideal;
pub mod measure;
pub mod pick;
pub mod render;
pub mod report;
pub mod scenes;

use std::ffi::OsString;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub use common::{print_stdout, write_output, SceneArgs};
pub use error::{CliError, ErrorKind};

/// `fixshade`: scenes, baking and reference rendering for the fixshade
/// fixed-point shading crate.
#[derive(Clone, Debug, Parser)]
#[command(name = "fixshade", version, about, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Clone, Debug, Subcommand)]
pub enum Command {
    /// List the built-in scenes (name and description).
    Scenes(scenes::ScenesArgs),
    /// Bake an OBJ file into Rust constant mesh data (Q1.14).
    Bake(bake::BakeArgs),
    /// Render a scene with the ideal f64 reference renderer to PNG.
    Ideal(ideal::IdealArgs),
    /// Render a scene with the fixed-point core to PNG (`--crc` prints the
    /// frame's CRC-32).
    Render(render::RenderArgs),
    /// Compare a profile with its f64 twin and the ideal reference.
    Compare(compare::CompareArgs),
    /// Sweep scenes × shading modes × profiles and write the
    /// accuracy-versus-speed report (HTML, Markdown, JSON).
    Report(report::ReportArgs),
    /// Render one turn of a scene with the core to an animated GIF.
    Animate(animate::AnimateArgs),
    /// Measure every profile's chip costs under QEMU; write or check
    /// docs/measurements/firmware.json.
    MeasureFirmware(measure::MeasureArgs),
    /// The most accurate configuration that fits a chip's clock, frame
    /// rate and RAM.
    Pick(pick::PickArgs),
}

impl Command {
    /// Runs the subcommand.
    pub fn run(&self) -> Result<(), CliError> {
        match self {
            Self::Scenes(args) => scenes::run(args),
            Self::Bake(args) => bake::run(args),
            Self::Ideal(args) => ideal::run(args),
            Self::Render(args) => render::run(args),
            Self::Compare(args) => compare::run(args),
            Self::Report(args) => report::run(args),
            Self::Animate(args) => animate::run(args),
            Self::MeasureFirmware(args) => measure::run(args),
            Self::Pick(args) => pick::run(args),
        }
    }
}

/// Parses the process arguments and runs; see [`run_from`].
pub fn main() -> ExitCode {
    run_from(std::env::args_os())
}

/// Parses `args` (the first is the program name) and runs the command.
/// Usage errors print clap's message and give status 2 (`--help` and
/// `--version` give 0); command errors print `error: MESSAGE` and give
/// [`CliError::exit_status`].
pub fn run_from<I, T>(args: I) -> ExitCode
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            // Printing fails only if stdout/stderr are closed: nothing to do.
            let _ = e.print();
            return ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2));
        }
    };
    match cli.command.run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(e.exit_status())
        }
    }
}
