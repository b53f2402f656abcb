//! Argument parsing and dispatch of the `triad` command line.

mod animate;
mod commands;
mod error;
mod import_args;
mod input;
mod linearize;
mod load;
mod matrix_file;
mod output;
mod overrides;
mod plot;
mod select;
mod simulate;
mod start_gap;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use error::CliError;
use import_args::ImportArgs;

/// triad: rigid multibody models to FMI 2.0 and FMI 3.0 Co-Simulation FMUs.
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
        /// Model spec (.toml or .json), a robot description (.urdf, or MuJoCo MJCF .xml), or the name of a shipped
        /// model (e.g. double_pendulum).
        model: String,
        /// How a .urdf or MJCF .xml MODEL is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
    /// Print the variable table (name, valueReference, causality, variability, unit); with
    /// --fmi 3 the FMI 3 names (arrays with their dimensions) and value references.
    Describe {
        /// Model spec (.toml or .json), a robot description (.urdf, or MuJoCo MJCF .xml), or the name of a shipped
        /// model.
        model: String,
        /// Whose names to print: 2 (default: the FMI 2 scalars) or 3 (the FMI 3 variables:
        /// vectors and matrices as arrays, `time` at valueReference 0).
        #[arg(long, value_name = "2|3", default_value = "2", value_parser = ["2", "3"])]
        fmi: String,
        /// How a .urdf or MJCF .xml MODEL is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
    /// Run MODEL natively and write every output variable every --step seconds as CSV.
    #[command(allow_negative_numbers = true)]
    Simulate(simulate::SimulateArgs),
    /// The exact linear model of MODEL at an operating point, for control design: the
    /// continuous-time A, B, C, D (dx/dt = A dx + B du, dy = C dx + D du) in minimal
    /// coordinates x = (joint coordinates and a floating base's r and rotation vector theta,
    /// then their rates), from analytic derivatives (not finite differences), written as
    /// .json, .npz or .mat with the names of x, u, y and the operating point (x0, u0, y0,
    /// xdot0, t0), and the exact discrete-time Ad, Bd of one step (--step). Closed loops: x holds
    /// independent coordinates (--coordinates picks them). Contact and joint friction: the
    /// sticking bristles of the touching ground points and the friction joints are states too
    /// (contact.C.s[i], joint.J.s; sliding is refused by name), in A and in Ad alike.
    #[command(allow_negative_numbers = true)]
    Linearize(linearize::LinearizeArgs),
    /// Write a 3-D replay of a result CSV: one self-contained HTML file (works offline) that
    /// places the bodies from their recorded poses, with play/pause, time slider, speed, loop,
    /// orbit/pan/zoom, frames, sites, a trace and a panel of joint angles and energy - work.
    Animate(animate::AnimateArgs),
    /// Package an FMI 2.0 (or, with --fmi 3, FMI 3.0) Co-Simulation FMU for MODEL, with the
    /// runtime binary of every platform found (one modelDescription.xml and one GUID for all).
    ///
    /// The binaries are read from the runtime directory: $TRIAD_RUNTIME_DIR, else runtime/
    /// beside the triad executable, else ../runtime/ (target/runtime/ for target/release/triad),
    /// as <platform>/<file>: linux64/libtriad.so (x86_64 Linux, glibc >= 2.17), win64/triad.dll,
    /// darwin64/libtriad.dylib (macOS x86_64 >= 10.12 + arm64 >= 11.0) and
    /// aarch64-linux/libtriad.so (glibc >= 2.17). `bash scripts/platforms.sh` builds them. The
    /// host's binary is always packed ($TRIAD_CDYLIB, else the runtime directory's, else the
    /// library of this build). Only binaries built from this triad's sources are packed (each
    /// carries their runtime id): an out-of-date one is left out with a warning, or is an error
    /// when asked for (the host's is replaced by this build's library). The command prints what
    /// it packed, each binary labelled by what it needs, read from the binary (the highest glibc
    /// version its symbols need, each macOS slice's minimum, the Windows version of its header;
    /// a host build needs the host's glibc).
    ///
    /// With --fmi 3 the same platforms go under the FMI 3 platform tuples: linux64 ->
    /// binaries/x86_64-linux, win64 -> x86_64-windows, darwin64 -> x86_64-darwin and
    /// aarch64-darwin (the universal file in both), aarch64-linux and linux64-aarch64 ->
    /// aarch64-linux.
    Build {
        /// Model spec (.toml or .json) or robot description (.urdf, or MuJoCo MJCF .xml).
        model: PathBuf,
        /// Output file (default: <name>.fmu in the current directory).
        #[arg(short, long, value_name = "OUT.fmu")]
        output: Option<PathBuf>,
        /// Which platforms to pack (default: every one found). `all`: linux64, win64, darwin64
        /// and aarch64-linux, each required; `host`: only this machine's; or a comma-separated
        /// list of linux64, win64, darwin64, aarch64-linux (binaries/aarch64-linux, the FMI 3
        /// folder, which FMI 2 importers ignore) and linux64-aarch64 (the aarch64 binary in
        /// binaries/linux64, where FMI 2 importers on ARM Linux look: an FMU for ARM boards,
        /// without the x86_64 Linux binary). A platform asked for but not found is an error
        /// that names the command building it.
        #[arg(long, value_name = "all|host|LIST")]
        platforms: Option<String>,
        /// FMI version of the FMU: 2 (default) or 3. Pick 3 for arrays (body.B.R as one 3x3
        /// variable, body.B.r [3], ...) in a host that imports FMI 3.0 Co-Simulation (fmpy,
        /// Simulink R2023b+, Dymola); pick 2 for every other host (FMI 2.0 is what most tools,
        /// OMSimulator and libcosim among them, import). Both come from the same variable table
        /// and the same runtime binary and give the same results; FMI 3 names vectors and
        /// matrices as arrays and adds `time` (valueReference 0). Directional (and, FMI 3, adjoint)
        /// derivatives for trees without contact; FMI 3 returns early from fmi3DoStep at
        /// contact and joint-stop events when the importer allows it.
        #[arg(long, value_name = "2|3", default_value = "2", value_parser = ["2", "3"])]
        fmi: String,
        /// How a .urdf or MJCF .xml MODEL is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
    /// Write the model spec equivalent to a URDF or an MJCF model (editable TOML; building from
    /// either gives the same FMU).
    ///
    /// URDF: the root link is as the URDF says (a `world` link with a fixed joint: welded; a
    /// floating joint: free); a bare root is welded to the world (as Pinocchio and MuJoCo do).
    /// Links on fixed joints are merged into their parents and become sites. Revolute and
    /// prismatic `<limit lower upper>` become joint stops and `effort` clamps the actuator input
    /// (placeholders lower = upper or effort = 0 are ignored). A `<visual>` or `<collision>` that
    /// cannot be read is dropped with a warning naming its line.
    ///
    /// MJCF (MuJoCo's .xml): hinge, slide, ball and free joints, bodies without joints merged
    /// into their parents, inertials given or computed from the geoms as MuJoCo does, default
    /// classes, includes, keyframes (--keyframe), geoms as collision shapes touching the
    /// world's plane (unless --no-contacts), connect and weld equalities as loop-closing
    /// joints, motor, position and velocity actuators on hinges and slides as [[actuator]]
    /// (the input actuator.A.ctrl, MuJoCo's laws, gear and clamps, a joint's
    /// actuatorfrcrange; the parameters actuator.A.gear, joint.J.actuatorfrcrange[1], [2],
    /// and actuator.A.kp, actuator.A.kv tunable between steps). Joint coordinates are
    /// MuJoCo's qpos (angles in the
    /// file's <compiler angle> unit, degrees by default). What is not reproduced is noted in
    /// the output; tendons, muscles, flex, composites and plugins are refused.
    Import {
        /// Robot description (.urdf, or MuJoCo MJCF .xml).
        robot: PathBuf,
        /// Output file (default: standard output).
        #[arg(short, long, value_name = "OUT.toml")]
        output: Option<PathBuf>,
        /// How the robot description is imported.
        #[command(flatten)]
        urdf: ImportArgs,
    },
}

/// Runs one command; prints errors to stderr.
pub fn run(cli: Cli) -> ExitCode {
    let result = match cli.command {
        Command::Check { model, urdf } => commands::check(&model, &urdf),
        Command::Describe { model, fmi, urdf } => commands::describe(&model, &fmi, &urdf),
        Command::Simulate(args) => simulate::run(&args),
        Command::Linearize(args) => linearize::run(&args),
        Command::Animate(args) => animate::run(&args),
        Command::Build {
            model,
            output,
            platforms,
            fmi,
            urdf,
        } => commands::build(&model, output.as_deref(), platforms.as_deref(), &fmi, &urdf),
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
            for note in &e.notes {
                eprintln!("note: {note}");
            }
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
