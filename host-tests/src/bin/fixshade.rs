//! The `fixshade` command: see `fixshade --help` and
//! `fixshade_host::cli`.
#![forbid(unsafe_code)]

fn main() -> std::process::ExitCode {
    fixshade_host::cli::main()
}
