//! Argument parsing and dispatch of the `triad` command line.

mod commands;
mod error;
mod input;
mod load;
mod output;
mod plot;
mod simulate;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use error::CliError;

/// triad: rigid multibody models to FMI 2.0 Co-Simulation FMUs.
#[derive(Debug, Parser)]
#[command(name = "triad", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The sub-commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Validate MODEL and report every problem, with its location.
    Check {
        /// Model spec (.toml or .json), or the name of a shipped model (e.g. double_pendulum).
        model: String,
    },
    /// Print the variable table (name, valueReference, causality, variability, unit).
    Describe {
        /// Model spec (.toml or .json), or the name of a shipped model.
        model: String,
    },
    /// Run MODEL natively and write every output variable every --step seconds as CSV.
    #[command(allow_negative_numbers = true)]
    Simulate(simulate::SimulateArgs),
    /// Package an FMI 2.0 Co-Simulation FMU for MODEL.
    Build {
        /// Model spec (.toml or .json).
        model: PathBuf,
        /// Output file (default: <name>.fmu in the current directory).
        #[arg(short, long, value_name = "OUT.fmu")]
        output: Option<PathBuf>,
    },
}

/// Runs one command; prints errors to stderr.
pub fn run(cli: Cli) -> ExitCode {
    let result = match cli.command {
        Command::Check { model } => commands::check(&model),
        Command::Describe { model } => commands::describe(&model),
        Command::Simulate(args) => simulate::run(&args),
        Command::Build { model, output } => commands::build(&model, output.as_deref()),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(CliError::Spec(e)) => {
            let n = e.problems.len();
            eprintln!("{e}");
            eprintln!(
                "error: {} has {n} problem{}",
                e.origin,
                if n == 1 { "" } else { "s" }
            );
            ExitCode::FAILURE
        }
        Err(CliError::Other(m)) => {
            eprintln!("error: {m}");
            ExitCode::FAILURE
        }
    }
}
