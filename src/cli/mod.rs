//! Argument parsing and dispatch of the `triad` command line.

mod animate;
mod commands;
mod error;
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
    },
    /// Print the variable table (name, valueReference, causality, variability, unit).
    Describe {
        /// Model spec (.toml or .json), a robot description (.urdf), or the name of a shipped
        /// model.
        model: String,
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
    },
    /// Write the model spec equivalent to a URDF (editable TOML; building from either gives
    /// the same FMU). The root link is as the URDF says (a `world` link with a fixed joint:
    /// welded; a floating joint: free); a bare root is welded to the world (as Pinocchio and
    /// MuJoCo do). Links on fixed joints are merged into their parents and become sites.
    /// Revolute and prismatic `<limit lower upper>` become joint stops and `effort` clamps the
    /// actuator input (placeholders lower = upper or effort = 0 are ignored).
    Import {
        /// Robot description (.urdf).
        robot: PathBuf,
        /// Output file (default: standard output).
        #[arg(short, long, value_name = "OUT.toml")]
        output: Option<PathBuf>,
        /// Weld the base to the world even if the URDF declares it floating.
        #[arg(long, conflicts_with = "floating_base")]
        fixed_base: bool,
        /// Free the base (a floating base: legged robots, humanoids, free-flying arms).
        #[arg(long)]
        floating_base: bool,
        /// Keep links on fixed joints as bodies on `fixed` joints instead of merging them.
        #[arg(long)]
        keep_fixed: bool,
        /// Leave out the URDF's <limit> (by default `lower`/`upper` become joint stops and
        /// `effort` clamps the actuator input).
        #[arg(long)]
        no_limits: bool,
    },
}

/// Runs one command; prints errors to stderr.
pub fn run(cli: Cli) -> ExitCode {
    let result = match cli.command {
        Command::Check { model } => commands::check(&model),
        Command::Describe { model } => commands::describe(&model),
        Command::Simulate(args) => simulate::run(&args),
        Command::Animate(args) => animate::run(&args),
        Command::Build { model, output } => commands::build(&model, output.as_deref()),
        Command::Import {
            robot,
            output,
            fixed_base,
            floating_base,
            keep_fixed,
            no_limits,
        } => {
            let base = match (fixed_base, floating_base) {
                (true, _) => triad::urdf::Base::Fixed,
                (_, true) => triad::urdf::Base::Floating,
                _ => triad::urdf::Base::Auto,
            };
            let opts = triad::urdf::ImportOptions {
                base,
                keep_fixed,
                no_limits,
            };
            commands::import(&robot, output.as_deref(), &opts)
        }
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
