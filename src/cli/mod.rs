//! Argument parsing and dispatch of the `triad` command line.

mod commands;
mod input;
mod output;
mod plot;
mod simulate;

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use triad::spec::{bundled, Format, Spec, SpecErrors};

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

/// A failed command: the message to print.
#[derive(Debug)]
pub enum CliError {
    /// Problems in the spec (one line each).
    Spec(SpecErrors),
    /// Anything else.
    Other(String),
}

impl From<SpecErrors> for CliError {
    fn from(e: SpecErrors) -> Self {
        Self::Spec(e)
    }
}

impl From<String> for CliError {
    fn from(e: String) -> Self {
        Self::Other(e)
    }
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

/// Loads MODEL: a spec file, a folder holding `spec.toml`, or, when no such file exists and
/// MODEL has no extension, the shipped model of that name.
pub fn load(model: &str) -> Result<Spec, SpecErrors> {
    let path = Path::new(model);
    // a model folder stands for its spec.toml (or spec.json)
    if path.is_dir() {
        for file in ["spec.toml", "spec.json"] {
            if path.join(file).is_file() {
                return Spec::from_path(&path.join(file));
            }
        }
        return Err(SpecErrors::single(
            model,
            "",
            "is a folder without spec.toml or spec.json",
        ));
    }
    if !path.exists() && path.extension().is_none() {
        if let Some((name, text)) = bundled().iter().find(|(n, _)| *n == model) {
            return Spec::from_str(
                text,
                Format::Toml,
                &format!("modelDescription/{name}/spec.toml"),
            );
        }
        let names: Vec<&str> = bundled().iter().map(|(n, _)| *n).collect();
        return Err(SpecErrors::single(
            model,
            "",
            format!(
                "no such file, and no shipped model of that name (shipped: {})",
                names.join(", ")
            ),
        ));
    }
    Spec::from_path(path)
}
