//! `triad animate MODEL RESULT.csv [-o OUT.html]` and `simulate --animate OUT.html`: the 3-D
//! replay of a result CSV as one self-contained HTML file (see `triad::viewer`).

use std::path::{Path, PathBuf};

use clap::Args;
use triad::spec::Spec;
use triad::viewer::{self, Options, Page, Recording, ResultTable, ViewerError};

use super::error::CliError;
use super::import_args::ImportArgs;
use super::load::{is_urdf, load};
use super::output::AtomicFile;

/// Options of `triad animate`.
#[derive(Debug, Args)]
pub struct AnimateArgs {
    /// Model spec (.toml or .json), robot description (.urdf or MJCF .xml), or the name of a shipped model:
    /// the model the result comes from (its shapes, or defaults drawn from its joints and
    /// inertia).
    pub model: String,
    /// Result CSV with the FMU's variable names: `time`, `body.B.r[i]`, `body.B.R[i,j]` for every
    /// body (`triad simulate` writes them; so does fmpy's write_csv when they are recorded), and
    /// `contact.C.f[i]` for the contact-force arrows.
    #[arg(value_name = "RESULT.csv")]
    pub result: PathBuf,
    /// Output file (default: RESULT with the extension .html).
    #[arg(short, long, value_name = "OUT.html")]
    pub output: Option<PathBuf>,
    /// A folder holding ROS packages, or a package folder, where `package://` meshes are looked
    /// for (repeatable); searched before ROS_PACKAGE_PATH, GAZEBO_MODEL_PATH,
    /// GZ_SIM_RESOURCE_PATH, AMENT_PREFIX_PATH (PREFIX/share/PKG) and the folders above the model.
    #[arg(long = "package-path", value_name = "DIR")]
    pub package_path: Vec<PathBuf>,
    /// Most frames kept per second of recorded time; denser results are decimated (the first and
    /// last rows are always kept).
    #[arg(long, value_name = "N", default_value_t = 100.0)]
    pub fps: f64,
    /// How a .urdf or MJCF .xml MODEL is imported. as for the run the result comes from (a result of a run
    /// with --floating-base is replayed with --floating-base).
    #[command(flatten)]
    pub urdf: ImportArgs,
}

/// The folder a model's relative mesh paths start from: the model file's folder, a model
/// folder itself, none for a shipped model.
fn model_dir(model: &str) -> Option<PathBuf> {
    let path = Path::new(model);
    if path.is_dir() {
        return Some(path.to_path_buf());
    }
    path.is_file()
        .then(|| path.parent().map(Path::to_path_buf).unwrap_or_default())
}

/// Prints the page's warnings and writes it to `out` (nothing is left behind on error).
fn write(page: &Page, out: &Path) -> Result<(), CliError> {
    for w in &page.warnings {
        eprintln!("warning: {w}");
    }
    let file = AtomicFile::new(out);
    std::fs::write(file.path(), &page.html)
        .map_err(|e| format!("cannot write {}: {e}", out.display()))?;
    file.commit()?;
    eprintln!(
        "wrote {} ({} frames, {:.1} MB)",
        out.display(),
        page.frames,
        page.html.len() as f64 / 1e6
    );
    Ok(())
}

/// Runs `triad animate`.
pub fn run(args: &AnimateArgs) -> Result<(), CliError> {
    if !(args.fps > 0.0 && args.fps.is_finite()) {
        return Err(format!("--fps must be a positive number (got {})", args.fps).into());
    }
    let spec = load(&args.model, &args.urdf)?;
    let opts = Options {
        max_rate: args.fps,
        package_dirs: args.package_path.clone(),
    };
    let page = viewer::replay_csv(
        &spec,
        model_dir(&args.model).as_deref(),
        &args.result,
        &opts,
    )
    .map_err(|e| match e {
        // a URDF imported otherwise than for the run gives other bodies: say how to match it
        ViewerError::OtherModel { .. } if is_urdf(Path::new(&args.model)) => format!(
            "{e}; a .urdf is replayed as imported with the options of the run \
             (--floating-base, --fixed-base, --keep-fixed)"
        ),
        e => e.to_string(),
    })?;
    let out = args
        .output
        .clone()
        .unwrap_or_else(|| args.result.with_extension("html"));
    write(&page, &out)
}

/// `simulate --animate OUT`: the replay of the run just simulated (`result`: its CSV with every
/// output column, whichever columns `--outputs` wrote).
pub fn after_simulate(model: &str, spec: &Spec, result: &[u8], out: &Path) -> Result<(), CliError> {
    let table = ResultTable::parse(result, "the simulated result", &Recording::reads)
        .map_err(|e| e.to_string())?;
    let recording = Recording::from_table(&table, spec).map_err(|e| format!("--animate: {e}"))?;
    let page = viewer::replay(
        spec,
        model_dir(model).as_deref(),
        &recording,
        &Options::default(),
    );
    write(&page, out)
}
