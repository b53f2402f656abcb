//! `triad linearize`: the exact continuous-time linear model `A, B, C, D` of MODEL at an
//! operating point (its initial state with `--set`, or a result's row at `--time`), inputs held
//! at `--u` values, and the exact discrete-time `Ad, Bd` of one communication step `--step H`
//! from it (`Simulation::step_map`), written as `.json`, `.npz` or `.mat` (`matrix_file`).

use std::path::PathBuf;

use clap::Args;
use triad::mechanics::{Independent, Operating, Quantity};
use triad::sim::Simulation;
use triad::variables::linear::quantity;
use triad::variables::{Accessor, Causality, VariableTable};
use triad::viewer::ResultTable;

use super::error::CliError;
use super::import_args::ImportArgs;
use super::load::load;
use super::matrix_file::{self, Entries, Value};
use super::output::AtomicFile;
use super::{overrides, select};

/// Options of `triad linearize`.
#[derive(Debug, Args)]
pub struct LinearizeArgs {
    /// Model spec (.toml or .json), robot description (.urdf or MJCF .xml), or the name of a shipped model.
    pub model: String,
    /// Output file: .json, .npz (numpy) or .mat (MATLAB level 5), the same names in each;
    /// `-` (the default) prints JSON.
    #[arg(short, long, value_name = "OUT.npz|OUT.mat|OUT.json|-")]
    pub output: Option<PathBuf>,
    /// The communication step H of the discrete-time Ad, Bd (default: the spec's experiment
    /// step), taken with the model's own solver settings (max_step, order, error control).
    #[arg(long, value_name = "H")]
    pub step: Option<f64>,
    /// Take the operating point from this result CSV (as `simulate` or fmpy write it: the
    /// joint coordinates and rates, spherical joints' quat and w, free bodies' r, R, v, w) at
    /// --time. A result does not record friction bristles: they are fitted to the row.
    #[arg(long, value_name = "RESULT.csv", requires = "time")]
    pub at: Option<PathBuf>,
    /// The time of the row of --at to linearise at, s.
    #[arg(long, value_name = "T", requires = "at")]
    pub time: Option<f64>,
    /// Set a parameter first (repeatable), e.g. `joint.elbow.q0=0.3`, as `simulate --set`.
    #[arg(long = "set", value_name = "NAME=VALUE")]
    pub set: Vec<String>,
    /// Hold an input at a value (repeatable), e.g. `joint.elbow.tau=2.5`; others are 0.
    #[arg(long = "u", value_name = "NAME=VALUE")]
    pub u: Vec<String>,
    /// The inputs u, in table order (comma-separated globs; default: every input).
    #[arg(long, value_name = "PATTERN[,PATTERN]")]
    pub inputs: Vec<String>,
    /// The outputs y, in table order (comma-separated globs; default: the joint coordinates
    /// and rates, and a floating base's r, v, w). Poses, twists, joint values, system.energy,
    /// system.p, system.L and the contact forces contact.C.f can be differentiated.
    #[arg(long, value_name = "PATTERN[,PATTERN]")]
    pub outputs: Vec<String>,
    /// Closed loops: the joints whose coordinates are the independent coordinates of x
    /// (comma-separated tree joints, as many coordinates as the loops leave free, e.g.
    /// `crank_pivot`); the other tree joints follow them around the loops. Default: triad picks
    /// the actuated joints first, then the others in model order, each when the rest can still
    /// close the loops there (well-conditioned), and prints its choice.
    #[arg(long, value_name = "J1,J2,...")]
    pub coordinates: Option<String>,
    /// How a .urdf or MJCF .xml MODEL is imported.
    #[command(flatten)]
    pub urdf: ImportArgs,
}

/// Reads `NAME=VALUE` input holds into `u`.
fn hold_inputs(holds: &[String], table: &VariableTable, u: &mut [f64]) -> Result<(), String> {
    let mut problems = Vec::new();
    for h in holds {
        let Some((name, text)) = h.split_once('=') else {
            problems.push(format!("--u {h}: expected NAME=VALUE"));
            continue;
        };
        let (name, text) = (name.trim(), text.trim());
        let acc = table.by_name(name).map(|v| v.accessor);
        let Some(Accessor::Input(i)) = acc else {
            let hint = triad::spec::did_you_mean(
                name,
                table
                    .with_causality(Causality::Input)
                    .map(|v| v.name.as_str()),
            );
            problems.push(format!("--u {name}: no such input{hint}"));
            continue;
        };
        match text.parse::<f64>() {
            Ok(x) if x.is_finite() => u[i] = x,
            _ => problems.push(format!("--u {name}: \"{text}\" is not a finite number")),
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems.join("\n"))
    }
}

/// The row of `csv` at time `t` (within 1e-9 relative), or a message naming the nearest.
fn row_at(csv: &ResultTable, t: f64) -> Result<usize, String> {
    let times = csv.column("time").unwrap_or(&[]);
    let tol = 1e-9 * t.abs().max(1.0);
    if let Some(k) = times.iter().position(|&x| (x - t).abs() <= tol) {
        return Ok(k);
    }
    let near = times
        .iter()
        .min_by(|a, b| (*a - t).abs().total_cmp(&(*b - t).abs()))
        .map_or("none".to_string(), |x| x.to_string());
    Err(format!(
        "{}: no row at time {t} (the nearest is {near}); pick a time the result has",
        csv.origin
    ))
}

/// Moves the operating point to the state recorded in `path` at `t`.
fn from_result(
    op: &mut Operating,
    names: &[String],
    path: &std::path::Path,
    t: f64,
    def: &triad::mechanics::ModelDef,
) -> Result<(), String> {
    let csv = ResultTable::read(path, &|_| true).map_err(|e| e.to_string())?;
    let k = row_at(&csv, t)?;
    let get = |name: &str| -> Result<f64, String> {
        csv.column(name).map(|c| c[k]).ok_or_else(|| {
            format!(
                "{}: no column {name} (the operating point needs every joint coordinate and rate, spherical joints' quat and w, free bodies' r, R, v and w)",
                path.display()
            )
        })
    };
    let n = op.q.len();
    for (i, name) in names.iter().enumerate() {
        if name.contains(".theta[") {
            continue;
        }
        let v = get(name)?;
        if i < n {
            op.q[i] = v;
        } else {
            op.nu[i - n] = v;
        }
    }
    for (j, jd) in def.joints.iter().enumerate() {
        if op.dynamics.is_spherical(j) {
            let mut q = [0.0; 4];
            for (c, x) in q.iter_mut().enumerate() {
                *x = get(&format!("joint.{}.quat[{}]", jd.name, c + 1))?;
            }
            op.dynamics
                .set_joint_rot0(j, triad::math::quat_to_matrix(&q));
        }
    }
    for f in &def.free_bodies {
        let b = &def.bodies[f.body].name;
        let mut r = triad::math::Mat3::zeros();
        for i in 0..3 {
            for j in 0..3 {
                r[(i, j)] = get(&format!("body.{b}.R[{},{}]", i + 1, j + 1))?;
            }
        }
        // re-orthonormalised through the quaternion: a CSV's digits need not be exact
        let r = triad::math::quat_to_matrix(&triad::math::matrix_to_quat(&r));
        op.dynamics.set_body_rot0(f.body, r);
    }
    Ok(())
}

/// The default outputs: joint coordinates and rates (spherical: quat and w), free bodies' r, v, w.
fn default_output(name: &str, acc: Accessor, free: &[String]) -> bool {
    match acc {
        Accessor::JointQ { .. } | Accessor::JointQd { .. } => true,
        Accessor::BodyR { .. } | Accessor::BodyV { .. } | Accessor::BodyW { .. } => {
            free.iter().any(|b| name.starts_with(&format!("body.{b}.")))
        }
        _ => false,
    }
}

/// Runs the command.
#[allow(clippy::too_many_lines)]
pub fn run(args: &LinearizeArgs) -> Result<(), CliError> {
    if let Some(h) = args.step {
        if !(h.is_finite() && h > 0.0) {
            return Err(
                format!("--step {h}: the step must be a positive number of seconds").into(),
            );
        }
    }
    let pick = match &args.coordinates {
        Some(list) => {
            let names: Vec<String> = list
                .split(',')
                .map(|s| s.trim().to_string())
                .filter(|s| !s.is_empty())
                .collect();
            if names.is_empty() {
                return Err("--coordinates: name at least one joint".to_string().into());
            }
            Independent::Joints(names)
        }
        None => Independent::Auto,
    };
    let spec = load(&args.model, &args.urdf)?;
    let (mut def, mut settings) = spec.lower()?;
    let table = VariableTable::new(&def, &settings).with_labels(&spec.labels());
    overrides::apply(&args.set, &table, &mut def, &mut settings)?;
    let start = spec.experiment.start;
    let h = args.step.unwrap_or(spec.experiment.step);
    let mut sim =
        Simulation::new(&def, settings, start).map_err(|e| format!("{}: {e}", args.model))?;
    hold_inputs(&args.u, &table, sim.state_mut().inputs_mut())?;
    let coordinates_error = |e: String| -> CliError {
        if args.coordinates.is_some() {
            format!("{}: --coordinates: {e}", args.model).into()
        } else {
            format!("{}: {e}", args.model).into()
        }
    };
    let mut op = Operating::picked(sim.model(), sim.state(), &pick)
        .map_err(|e| coordinates_error(e.to_string()))?;
    let t0 = match (&args.at, args.time) {
        (Some(path), Some(t)) => {
            let names = op.tree_names(sim.model());
            from_result(&mut op, &names, path, t, &def)?;
            op.forget_bristles();
            op.pick(sim.model(), &pick).map_err(coordinates_error)?;
            if let (Some((before, after)), true) = (op.fitted, op.dynamics.sticking().n() > 0) {
                let speed = op
                    .dynamics
                    .bristle_rates(&op.q, &op.nu)
                    .iter()
                    .fold(0.0_f64, |m, x| m.max(x.abs()));
                eprintln!(
                    "note: {} does not record the friction bristles; they are fitted to the point \
                     (least squares: |accelerations| {before:.3e} with none, {after:.3e} fitted). \
                     The bristles' points move at up to {speed:.3e} m/s (or rad/s): where that is \
                     more than a sticking bristle's small vibration they slide, and this model \
                     describes them sticking",
                    path.display()
                );
            }
            t
        }
        _ => start,
    };
    let x_names = op.state_names(sim.model());
    let loop_pick = match &op.loops {
        Some(cl) => {
            let n = cl.indep.len();
            eprintln!(
                "closed loops or couplings: x holds {n} independent coordinate(s) {} (the other \
                 tree joints follow them around the loops and couplings{})",
                x_names[..n].join(", "),
                if args.coordinates.is_some() {
                    ""
                } else {
                    "; --coordinates picks others"
                }
            );
            Independent::Coords(cl.indep.clone())
        }
        None => Independent::Auto,
    };
    // inputs and outputs, in table order
    let inputs: Vec<_> = table.with_causality(Causality::Input).collect();
    let u_cols = select::select(&inputs, &select::patterns(&args.inputs)).map_err(|e| {
        e.replace("--outputs", "--inputs")
            .replace("output variable", "input variable")
    })?;
    let outputs: Vec<_> = table.with_causality(Causality::Output).collect();
    let free: Vec<String> = def
        .free_bodies
        .iter()
        .map(|f| def.bodies[f.body].name.clone())
        .collect();
    let chosen: Vec<usize> = if args.outputs.is_empty() {
        (0..outputs.len())
            .filter(|&k| default_output(&outputs[k].name, outputs[k].accessor, &free))
            .collect()
    } else {
        select::select(&outputs, &select::patterns(&args.outputs))?
    };
    let mut ys: Vec<Quantity> = Vec::new();
    let mut y_names = Vec::new();
    let mut left_out = Vec::new();
    let mut closing = Vec::new();
    for &k in &chosen {
        match quantity(outputs[k].accessor) {
            Some(q) if op.differentiable(&q) => {
                ys.push(q);
                y_names.push(outputs[k].name.clone());
            }
            Some(_) => closing.push(outputs[k].name.clone()),
            None => left_out.push(outputs[k].name.clone()),
        }
    }
    if !closing.is_empty() {
        eprintln!(
            "note: left out of y (values of loop-closing joints, no coordinates of the tree): {}",
            closing.join(", ")
        );
    }
    if !left_out.is_empty() {
        eprintln!(
            "note: left out of y (not differentiable here): {}",
            left_out.join(", ")
        );
    }
    let lin = op
        .linearize(&ys)
        .map_err(|e| format!("{}: {e}", args.model))?;
    let input_index = |k: usize| match inputs[k].accessor {
        Accessor::Input(i) => i,
        _ => 0,
    };
    let nx = x_names.len();
    let pick = |m: &nalgebra::DMatrix<f64>, rows: usize| -> Vec<f64> {
        (0..rows)
            .flat_map(|r| u_cols.iter().map(move |&k| (r, k)))
            .map(|(r, k)| m[(r, input_index(k))])
            .collect()
    };
    let row_major = |m: &nalgebra::DMatrix<f64>| -> Vec<f64> {
        (0..m.nrows())
            .flat_map(|r| (0..m.ncols()).map(move |c| (r, c)))
            .map(|(r, c)| m[(r, c)])
            .collect()
    };
    // the discrete-time model: one communication step from the operating point, as a run
    // started there takes it
    let x_op = op.x();
    let mut from_op = Simulation::new(&op.initial_def(&def, &x_op), settings, t0)
        .map_err(|e| format!("{}: {e}", args.model))?;
    from_op.state_mut().inputs_mut().copy_from_slice(&op.u);
    // the sticking bristles are part of the point (the state's, or fitted)
    let (contact, joints) = op.bristles(sim.model());
    let st = from_op.state_mut();
    st.contact_bristles_mut().copy_from_slice(&contact);
    st.joint_bristles_mut().copy_from_slice(&joints);
    // without --step a model whose step map is not available still gets A, B, C, D
    let map = match from_op.step_map_in(h, &loop_pick) {
        Ok(map) => Some(map),
        Err(e) if args.step.is_none() => {
            eprintln!("note: no Ad, Bd (the step of {h} s from the operating point: {e})");
            None
        }
        Err(e) => {
            return Err(format!(
                "{}: the step of {h} s from the operating point: {e}",
                args.model
            )
            .into())
        }
    };
    let nu = u_cols.len();
    let ny = ys.len();
    let x0 = op.x();
    let u0: Vec<f64> = u_cols.iter().map(|&k| op.u[input_index(k)]).collect();
    let speed = lin.xdot0.iter().map(|x| x * x).sum::<f64>().sqrt();
    eprintln!(
        "operating point at t = {t0}: |xdot| = {speed:.3e} ({}); {nx} states, {nu} inputs, {ny} outputs",
        if speed == 0.0 { "an equilibrium" } else { "0 at an equilibrium" }
    );
    let entries: Entries = vec![
        ("A", Value::Matrix(nx, nx, row_major(&lin.a))),
        ("B", Value::Matrix(nx, nu, pick(&lin.b, nx))),
        ("C", Value::Matrix(ny, nx, row_major(&lin.c))),
        ("D", Value::Matrix(ny, nu, pick(&lin.d, ny))),
        ("x_names", Value::Names(x_names)),
        (
            "u_names",
            Value::Names(u_cols.iter().map(|&k| inputs[k].name.clone()).collect()),
        ),
        ("y_names", Value::Names(y_names)),
        ("x0", Value::Vector(x0)),
        ("u0", Value::Vector(u0)),
        ("y0", Value::Vector(lin.y0.clone())),
        ("xdot0", Value::Vector(lin.xdot0.clone())),
        ("t0", Value::Scalar(t0)),
    ];
    let mut entries = entries;
    if let Some(map) = &map {
        entries.push(("Ad", Value::Matrix(nx, nx, row_major(&map.ad))));
        entries.push(("Bd", Value::Matrix(nx, nu, pick(&map.bd, nx))));
        entries.push(("h", Value::Scalar(h)));
    }
    let target = args.output.clone().unwrap_or_else(|| PathBuf::from("-"));
    if target.as_os_str() == "-" {
        print!("{}", matrix_file::json(&entries));
        return Ok(());
    }
    let ext = target
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let bytes = match ext.as_str() {
        "json" => matrix_file::json(&entries).into_bytes(),
        "npz" => matrix_file::npz(&entries)?,
        "mat" => matrix_file::mat(&entries),
        _ => {
            return Err(format!(
            "{}: the output must end in .json, .npz or .mat (or be - for JSON on standard output)",
            target.display()
        )
            .into())
        }
    };
    let file = AtomicFile::new(&target);
    let mut w = file.create()?;
    std::io::Write::write_all(&mut w, &bytes)
        .map_err(|e| format!("cannot write {}: {e}", target.display()))?;
    std::io::Write::flush(&mut w).map_err(|e| format!("cannot write {}: {e}", target.display()))?;
    drop(w);
    file.commit()?;
    eprintln!("wrote {}", target.display());
    Ok(())
}
