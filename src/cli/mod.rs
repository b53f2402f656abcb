//! Argument parsing and dispatch of the `triad` command line.

mod animate;
mod commands;
mod error;
mod import_args;
mod input;
mod load;
mod output;
mod overrides;
mod plot;
mod select;
mod simulate;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use error::CliError;
use import_args::ImportArgs;

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
        /// Model spec (.toml or .json), a robot description (.urdf), or the name of a shipped
        /// model (e.g. double_pendulum).
        model: String,
        /// How a .urdf MODEL is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
    /// Print the variable table (name, valueReference, causality, variability, unit).
    Describe {
        /// Model spec (.toml or .json), a robot description (.urdf), or the name of a shipped
        /// model.
        model: String,
        /// How a .urdf MODEL is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
    /// Run MODEL natively and write every output variable every --step seconds as CSV.
    #[command(allow_negative_numbers = true)]
    Simulate(simulate::SimulateArgs),
    /// Write a 3-D replay of a result CSV: one self-contained HTML file (works offline) that
    /// places the bodies from their recorded poses, with play/pause, time slider, speed, loop,
    /// orbit/pan/zoom, frames, sites, a trace and a panel of joint angles and energy - work.
    Animate(animate::AnimateArgs),
    /// Package an FMI 2.0 Co-Simulation FMU for MODEL.
    Build {
        /// Model spec (.toml or .json) or robot description (.urdf).
        model: PathBuf,
        /// Output file (default: <name>.fmu in the current directory).
        #[arg(short, long, value_name = "OUT.fmu")]
        output: Option<PathBuf>,
        /// How a .urdf MODEL is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
    /// Write the model spec equivalent to a URDF (editable TOML; building from either gives
    /// the same FMU). The root link is as the URDF says (a `world` link with a fixed joint:
    /// welded; a floating joint: free); a bare root is welded to the world (as Pinocchio and
    /// MuJoCo do). Links on fixed joints are merged into their parents and become sites.
    /// Revolute and prismatic `<limit lower upper>` become joint stops and `effort` clamps the
    /// actuator input (placeholders lower = upper or effort = 0 are ignored). A `<visual>` or
    /// `<collision>` that cannot be read is dropped with a warning naming its line.
    Import {
        /// Robot description (.urdf).
        robot: PathBuf,
        /// Output file (default: standard output).
        #[arg(short, long, value_name = "OUT.toml")]
        output: Option<PathBuf>,
        /// How the URDF is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
}

/// Runs one command; prints errors to stderr.
pub fn run(cli: Cli) -> ExitCode {
    let result = match cli.command {
        Command::Check { model, urdf } => commands::check(&model, &urdf),
        Command::Describe { model, urdf } => commands::describe(&model, &urdf),
        Command::Simulate(args) => simulate::run(&args),
        Command::Animate(args) => animate::run(&args),
        Command::Build {
            model,
            output,
            urdf,
        } => commands::build(&model, output.as_deref(), &urdf),
        Command::Import {
            robot,
            output,
            urdf,
        } => commands::import(&robot, output.as_deref(), &urdf),
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
