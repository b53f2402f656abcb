//! `triad simulate`: runs the model through `sim::Simulation` (the FMU's stepping path) and
//! writes one CSV row per communication step: `time`, then every output variable (or those
//! chosen by `--outputs`). Parameters can be changed with `--set`; the rows of `--input` take
//! effect at their own times (the internal steps end there).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use triad::sim::Simulation;
use triad::variables::{read_state, Accessor, Causality, VariableTable};

use super::error::CliError;
use super::import_args::ImportArgs;
use super::input::InputTable;
use super::load::load;
use super::output::{finish, AtomicFile};
use super::plot::{self, Series};
use super::{overrides, select};

/// Options of `triad simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Model spec (.toml or .json), robot description (.urdf or MJCF .xml), or the name of a shipped model.
    pub model: String,
    /// Stop time, s (default: experiment.stop).
    #[arg(long, value_name = "T")]
    pub stop: Option<f64>,
    /// Communication step: one output row every H seconds (default: experiment.step).
    #[arg(long, value_name = "H")]
    pub step: Option<f64>,
    /// Largest internal step, s (overrides solver.max_step).
    #[arg(long, value_name = "S")]
    pub max_step: Option<f64>,
    /// Error-controlled internal steps with this relative tolerance (overrides solver.rtol;
    /// 0: fixed steps). --max-step is then the ceiling of the step.
    #[arg(long, value_name = "RTOL")]
    pub rtol: Option<f64>,
    /// Absolute tolerance of error-controlled steps (overrides solver.atol).
    #[arg(long, value_name = "ATOL")]
    pub atol: Option<f64>,
    /// Integrator order (overrides solver.order).
    #[arg(long, value_parser = ["2", "4"])]
    pub order: Option<String>,
    /// Input CSV: a `time` column and columns named like input variables, each row held from
    /// its own time until the next (zero-order hold; the internal steps end at every row's
    /// time, also between communication points).
    #[arg(long, value_name = "IN.csv")]
    pub input: Option<PathBuf>,
    /// Set a parameter before the run (repeatable), e.g. `joint.elbow.q0=0.3` or
    /// `actuator.A.kp=50` (an actuator's gear, kp, kv): any parameter of `triad describe`,
    /// checked as fmi2SetReal checks it.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Write only the output columns whose names match (repeatable; comma-separated globs with
    /// `*` and `?`, e.g. `joint.*.q,system.energy`); `time` is always written.
    #[arg(long, value_name = "PATTERN[,PATTERN]")]
    pub outputs: Vec<String>,
    /// Output CSV (default: standard output).
    #[arg(short, long, value_name = "OUT.csv")]
    pub output: Option<PathBuf>,
    /// Also plot joint coordinates, energy and work to this PNG.
    #[arg(long, value_name = "OUT.png")]
    pub plot: Option<PathBuf>,
    /// Also write a 3-D replay of the run to this HTML file (as `triad animate`).
    #[arg(long, value_name = "OUT.html")]
    pub animate: Option<PathBuf>,
    /// How a .urdf or MJCF .xml MODEL is imported.
    #[command(flatten)]
    pub urdf: ImportArgs,
}

/// Where the CSV goes: a temporary file renamed on success, or memory printed on success.
enum Sink {
    File(std::io::BufWriter<std::fs::File>),
    Memory(Vec<u8>),
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Sink::File(w) => w.write(buf),
            Sink::Memory(v) => v.write(buf),
        }
    }

    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Sink::File(w) => w.flush(),
            Sink::Memory(v) => v.flush(),
        }
    }
}

/// Shortest text that reads back as the same `f64`.
pub fn number(x: f64) -> String {
    let a = x.abs();
    if x == 0.0 || (1e-5..1e16).contains(&a) {
        format!("{x}")
    } else if x.is_finite() {
        format!("{x:e}")
    } else {
        "NaN".into()
    }
}

fn positive(name: &str, v: Option<f64>) -> Result<(), String> {
    match v {
        Some(x) if !(x > 0.0 && x.is_finite()) => {
            Err(format!("--{name} must be a positive number (got {x})"))
        }
        _ => Ok(()),
    }
}

/// Runs the command.
pub fn run(args: &SimulateArgs) -> Result<(), CliError> {
    let spec = load(&args.model, &args.urdf)?;
    let (mut def, mut settings) = spec.lower()?;
    let table = VariableTable::new(&def, &settings).with_labels(&spec.labels());
    overrides::apply(&args.set, &table, &mut def, &mut settings)?;
    positive("step", args.step)?;
    positive("max-step", args.max_step)?;
    if let Some(s) = args.max_step {
        triad::mechanics::ranges::max_step(s).map_err(|e| format!("--max-step {e}"))?;
        settings.max_step = s;
    }
    if let Some(r) = args.rtol {
        triad::mechanics::ranges::rtol(r).map_err(|e| format!("--rtol {e}"))?;
        settings.rtol = r;
    }
    if let Some(a) = args.atol {
        triad::mechanics::ranges::atol(a).map_err(|e| format!("--atol {e}"))?;
        settings.atol = a;
    }
    if let Some(o) = &args.order {
        settings.order = if o == "4" { 4 } else { 2 };
    }
    let start = spec.experiment.start;
    let stop = args.stop.unwrap_or(spec.experiment.stop);
    let h = args.step.unwrap_or(spec.experiment.step);
    if !(stop.is_finite() && stop > start) {
        return Err(format!("--stop must be after the start time {start} (got {stop})").into());
    }
    let inputs = args
        .input
        .as_deref()
        .map(|p| InputTable::read(p, &table))
        .transpose()?;
    let mut sim =
        Simulation::new(&def, settings, start).map_err(|e| format!("{}: {e}", args.model))?;
    if let Some(warning) = super::start_gap::for_model(&sim, &args.model, &args.urdf) {
        eprintln!("{warning}");
    }
    let outputs: Vec<_> = table.with_causality(Causality::Output).collect();
    let columns = select::select(&outputs, &select::patterns(&args.outputs))?;
    // joint accelerations are computed once per row, and only when a column wants them
    let is_qdd = |k: &usize| matches!(outputs[*k].accessor, Accessor::JointQdd { .. });
    let has_qdd = columns.iter().any(is_qdd)
        || (args.animate.is_some() && (0..outputs.len()).any(|k| is_qdd(&k)));
    let plotted: Vec<usize> = outputs
        .iter()
        .enumerate()
        .filter(|(_, v)| {
            args.plot.is_some()
                && matches!(
                    v.accessor,
                    Accessor::JointQ { .. } | Accessor::Energy | Accessor::Work
                )
        })
        .map(|(k, _)| k)
        .collect();
    let mut series: Vec<Series> = plotted
        .iter()
        .map(|&k| Series {
            name: outputs[k].name.clone(),
            energy: !matches!(outputs[k].accessor, Accessor::JointQ { .. }),
            points: Vec::new(),
        })
        .collect();

    let file = args.output.as_deref().map(AtomicFile::new);
    let mut sink = match &file {
        Some(f) => Sink::File(f.create()?),
        None => Sink::Memory(Vec::new()),
    };
    let mut pngs = Vec::new();
    let write_err = |e: std::io::Error| CliError::Other(format!("cannot write the output: {e}"));
    // the replay reads every pose, whichever columns --outputs writes: with --animate the
    // whole result is also kept in memory
    let all: Vec<usize> = (0..outputs.len()).collect();
    let mut full: Option<Vec<u8>> = args.animate.as_ref().map(|_| Vec::new());
    let line = |t: f64, values: &[f64], cols: &[usize]| -> String {
        let mut line = number(t);
        for &k in cols {
            line.push(',');
            line.push_str(&number(values[k]));
        }
        line.push('\n');
        line
    };
    let row = |sim: &Simulation,
               sink: &mut Sink,
               series: &mut Vec<Series>,
               full: &mut Option<Vec<u8>>|
     -> Result<(), CliError> {
        let t = sim.time();
        let acc = has_qdd.then(|| sim.accelerations().ok()).flatten();
        let values: Vec<f64> = outputs
            .iter()
            .map(|v| match v.accessor {
                Accessor::JointQdd { joint, k } => acc.as_ref().and_then(|a| a.get(joint, k)),
                a => read_state(a, sim.state()),
            })
            .map(|x| x.unwrap_or(f64::NAN))
            .collect();
        for (s, &k) in series.iter_mut().zip(&plotted) {
            s.points.push((t, values[k]));
        }
        if let Some(full) = full {
            full.extend_from_slice(line(t, &values, &all).as_bytes());
        }
        sink.write_all(line(t, &values, &columns).as_bytes())
            .map_err(write_err)
    };
    // names with commas (`R[1,2]`) are quoted, as CSV requires
    let header = |cols: &[usize]| -> String {
        let names: Vec<String> = std::iter::once("time")
            .chain(cols.iter().map(|&k| outputs[k].name.as_str()))
            .map(|n| {
                if n.contains(',') || n.contains('"') {
                    format!("\"{}\"", n.replace('"', "\"\""))
                } else {
                    n.to_string()
                }
            })
            .collect();
        names.join(",") + "\n"
    };
    if let Some(full) = &mut full {
        full.extend_from_slice(header(&all).as_bytes());
    }
    sink.write_all(header(&columns).as_bytes())
        .map_err(write_err)?;

    // communication points start + k·h, the last one clipped to stop
    let n = ((stop - start) / h * (1.0 - 1e-12)).ceil().max(1.0) as u64;
    let bar = if std::io::stderr().is_terminal() {
        ProgressBar::new(n)
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} steps, eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    // the inputs of the start time are held before the first row, as an FMU host sets them
    // before reading its first outputs (the accelerations follow the inputs held)
    if let Some(table) = &inputs {
        table.apply(sim.time(), sim.state_mut().inputs_mut());
    }
    row(&sim, &mut sink, &mut series, &mut full)?;
    for k in 1..=n {
        let target = if k == n { stop } else { start + k as f64 * h };
        // internal steps end at the input rows' own times, so no row is skipped
        loop {
            if let Some(table) = &inputs {
                table.apply(sim.time(), sim.state_mut().inputs_mut());
            }
            if let Some(msg) = sim.clamp_notice() {
                bar.suspend(|| eprintln!("note: {msg}"));
            }
            let end = inputs
                .as_ref()
                .and_then(|t| t.next_row_time(sim.time(), target))
                .unwrap_or(target);
            let dt = end - sim.time();
            sim.advance(dt).map_err(|e| {
                format!(
                    "{}: step from t = {} failed: {} (no output written)",
                    args.model, e.last_good_time, e.error
                )
            })?;
            if let Some(msg) = sim.order2_notice() {
                bar.suspend(|| eprintln!("note: {msg}"));
            }
            if end == target {
                break;
            }
        }
        row(&sim, &mut sink, &mut series, &mut full)?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    if let (n @ 2.., _) = sim.state().order2_steps() {
        eprintln!("note: order 4: {n} steps in all were taken as order-2 stages (stiff damping)");
    }
    if let Some(path) = &args.plot {
        let png = AtomicFile::new(path);
        plot::draw(png.path(), &spec.name, &series)
            .map_err(|e| format!("cannot plot to {}: {e}", path.display()))?;
        pngs.push(png);
    }
    match (sink, file, args.output.as_deref()) {
        (Sink::File(w), Some(f), Some(path)) => {
            finish(w, path)?;
            f.commit()?;
        }
        (Sink::Memory(bytes), _, _) => {
            let mut stdout = std::io::stdout().lock();
            stdout
                .write_all(&bytes)
                .and_then(|()| stdout.flush())
                .map_err(write_err)?;
        }
        _ => {}
    }
    for png in pngs {
        png.commit()?;
    }
    if let (Some(html), Some(full)) = (&args.animate, &full) {
        super::animate::after_simulate(&args.model, &spec, full, html)?;
    }
    Ok(())
}
