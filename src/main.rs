//! The `triad` command line (interface.md §1): `check`, `describe`, `simulate`, `build`,
//! `import` and `animate`.
//!
//! Every error prints a message naming the file and place, and exits non-zero; nothing is
//! written on error.
mod cli;

use clap::Parser;

fn main() -> std::process::ExitCode {
    cli::run(cli::Cli::parse())
}
