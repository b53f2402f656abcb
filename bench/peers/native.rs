//! The peers-harness runner for triad's in-process path (the same `Simulation` that
//! `triad simulate` and the FMU use). It reads a triad spec made by `to_spec.py` and the neutral
//! model (for the input schedule, the PD controller and the column names), steps with fixed h,
//! times only the stepping loop (controller and output reads included, start-up and I/O
//! excluded) and writes the harness CSV contract (`../shared/peers/README.md`).
//!
//! `cargo run --release --example peers_native -- --spec S.json --model M.json --h H
//!  --t-end T --dt-out D --out OUT.csv`
use std::{error::Error, fs, path::PathBuf, time::Instant};

use serde_json::Value;
use triad::{
    math::matrix_to_quat,
    mechanics::{InputSlot, JointType},
    sim::Simulation,
    spec::Spec,
};

struct Args {
    spec: PathBuf,
    model: PathBuf,
    h: f64,
    t_end: f64,
    dt_out: f64,
    out: PathBuf,
    /// `internal`: the PD law is in the model (stiffness kp, damping kd from the spec) and the
    /// input is the constant kp q_set + tau_ff; `zoh`: tau from the outputs once per step.
    pd_internal: bool,
}

fn parse_args() -> Result<Args, Box<dyn Error>> {
    let mut it = std::env::args().skip(1);
    let (mut spec, mut model, mut out) = (None, None, None);
    let (mut h, mut t_end, mut dt_out) = (None, None, None);
    let mut pd_internal = false;
    while let Some(k) = it.next() {
        let v = it.next().ok_or(format!("{k} needs a value"))?;
        match k.as_str() {
            "--spec" => spec = Some(PathBuf::from(v)),
            "--model" => model = Some(PathBuf::from(v)),
            "--out" => out = Some(PathBuf::from(v)),
            "--h" => h = Some(v.parse()?),
            "--t-end" => t_end = Some(v.parse()?),
            "--dt-out" => dt_out = Some(v.parse()?),
            "--pd" => pd_internal = v == "internal",
            _ => return Err(format!("unknown argument {k}").into()),
        }
    }
    Ok(Args {
        spec: spec.ok_or("--spec missing")?,
        model: model.ok_or("--model missing")?,
        h: h.ok_or("--h missing")?,
        t_end: t_end.ok_or("--t-end missing")?,
        dt_out: dt_out.ok_or("--dt-out missing")?,
        out: out.ok_or("--out missing")?,
        pd_internal,
    })
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap_or(0.0)
}

/// A neutral joint mapped to what triad reports for it.
enum Column {
    Joint { index: usize, kind: JointType },
    Free { body: usize },
}

fn main() -> Result<(), Box<dyn Error>> {
    let a = parse_args()?;
    let model: Value = serde_json::from_str(&fs::read_to_string(&a.model)?)?;
    let spec = Spec::from_path(&a.spec)?;
    let (def, settings) = spec.lower()?;
    let mut sim = Simulation::new(&def, settings, 0.0)?;

    // columns in neutral joint order
    let body_index = |name: &str| def.bodies.iter().position(|b| b.name == name);
    let joint_index = |name: &str| def.joints.iter().position(|j| j.name == name);
    let mut columns = Vec::new();
    let mut header = vec!["t".to_string()];
    let mut vheader = Vec::new();
    for j in model["joints"].as_array().ok_or("joints")? {
        let name = j["name"].as_str().ok_or("joint name")?;
        match j["type"].as_str() {
            Some("revolute") => {
                let index = joint_index(name).ok_or("joint missing")?;
                columns.push(Column::Joint {
                    index,
                    kind: JointType::Revolute,
                });
                header.push(format!("q.{name}"));
                vheader.push(format!("v.{name}"));
            }
            Some("spherical") => {
                let index = joint_index(name).ok_or("joint missing")?;
                columns.push(Column::Joint {
                    index,
                    kind: JointType::Spherical,
                });
                header.extend(["qw", "qx", "qy", "qz"].map(|c| format!("q.{name}.{c}")));
                vheader.extend(["wx", "wy", "wz"].map(|c| format!("v.{name}.{c}")));
            }
            _ => {
                let body = body_index(j["child"].as_str().ok_or("child")?).ok_or("body missing")?;
                columns.push(Column::Free { body });
                header.extend(
                    ["x", "y", "z", "qw", "qx", "qy", "qz"].map(|c| format!("q.{name}.{c}")),
                );
                vheader
                    .extend(["vx", "vy", "vz", "wx", "wy", "wz"].map(|c| format!("v.{name}.{c}")));
            }
        }
    }
    header.extend(vheader);
    // the engine's own invariants (extra columns, ignored by the harness's metrics)
    header.extend(["energy", "work", "Lx", "Ly", "Lz"].map(String::from));

    // controller: tau = kp (q_set - q) - kd v + tau_ff, once per step (zero-order hold)
    let ctrl = &model["controller"];
    let mut pd = Vec::new();
    if let Some(joints) = ctrl["joints"].as_array() {
        for (k, jn) in joints.iter().enumerate() {
            let j = joint_index(jn.as_str().unwrap_or("")).ok_or("controlled joint missing")?;
            let slot = sim
                .model()
                .inputs()
                .iter()
                .position(|s| *s == InputSlot::JointTorque { joint: j, k: 0 })
                .ok_or("controlled joint not actuated")?;
            pd.push((
                j,
                slot,
                f(&ctrl["kp"][k]),
                f(&ctrl["kd"][k]),
                f(&ctrl["q_set"][k]),
                f(&ctrl["tau_ff"][k]),
            ));
        }
    }
    // body torque schedule
    let mut torques = Vec::new();
    for inp in model["inputs"].as_array().into_iter().flatten() {
        if inp["type"] != "body_torque_world" {
            continue;
        }
        let b = body_index(inp["body"].as_str().unwrap_or("")).ok_or("loaded body missing")?;
        let slots: Vec<usize> = (0..3)
            .map(|i| {
                sim.model()
                    .inputs()
                    .iter()
                    .position(|s| *s == InputSlot::BodyTorque { body: b, i })
            })
            .collect::<Option<_>>()
            .ok_or("body torque not declared")?;
        let tau: Vec<f64> = (0..3).map(|i| f(&inp["torque"][i])).collect();
        torques.push((slots, tau, f(&inp["t_start"]), f(&inp["t_end"])));
    }

    let nsub = (a.dt_out / a.h).round() as usize;
    let nout = (a.t_end / a.dt_out).round() as usize;
    let mut rows = vec![row(&sim, &columns, 0.0)];
    let start = Instant::now();
    let mut t = 0.0;
    for k in 0..nout {
        for i in 0..nsub {
            let state = sim.state_mut();
            for &(j, slot, kp, kd, qs, ff) in &pd {
                let tau = if a.pd_internal {
                    kp * qs + ff
                } else {
                    let out = &state.outputs().joints[j];
                    kp * (qs - out.q[0]) - kd * out.qd[0] + ff
                };
                state.inputs_mut()[slot] = tau;
            }
            for (slots, tau, t0, t1) in &torques {
                let on = *t0 - 1e-9 <= t && t < *t1 - 1e-9;
                for (s, v) in slots.iter().zip(tau) {
                    state.inputs_mut()[*s] = if on { *v } else { 0.0 };
                }
            }
            // outputs are refreshed when they are read: by the once-per-step PD law, and at
            // the output samples
            let read = (!pd.is_empty() && !a.pd_internal) || i + 1 == nsub;
            if read {
                sim.advance(a.h)
            } else {
                sim.advance_state(a.h).map(drop)
            }
            .map_err(|e| format!("step failed at t = {}: {}", e.last_good_time, e.error))?;
            t = (k * nsub + i + 1) as f64 * a.h;
        }
        rows.push(row(&sim, &columns, (k + 1) as f64 * a.dt_out));
    }
    let wall = start.elapsed().as_secs_f64();

    let mut text = format!(
        "# engine=triad\n# version={}\n# method=em-order{}\n# h={}\n# n_steps={}\n# wall_time_s={wall}\n# controller={}\n",
        env!("CARGO_PKG_VERSION"),
        settings.order,
        a.h,
        nout * nsub,
        match (pd.is_empty(), a.pd_internal) {
            (true, _) => "none",
            (false, true) => "internal-continuous",
            (false, false) => "zoh-per-step",
        }
    );
    text.push_str(&header.join(","));
    text.push('\n');
    for r in rows {
        let cells: Vec<String> = r.iter().map(|x| format!("{x:e}")).collect();
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    fs::write(&a.out, text)?;
    Ok(())
}

fn row(sim: &Simulation, columns: &[Column], t: f64) -> Vec<f64> {
    let out = sim.state().outputs();
    let (mut q, mut v) = (vec![t], Vec::new());
    for c in columns {
        match c {
            Column::Joint { index, kind } => {
                let j = &out.joints[*index];
                q.extend_from_slice(&j.q);
                v.extend_from_slice(&j.qd);
                debug_assert_eq!(j.q.len(), kind.nq());
            }
            Column::Free { body } => {
                let b = &out.bodies[*body];
                q.extend(b.r.iter());
                q.extend(matrix_to_quat(&b.rot));
                v.extend(b.v.iter());
                v.extend((b.rot.transpose() * b.w).iter());
            }
        }
    }
    q.extend(v);
    q.extend([out.energy, out.work, out.l.x, out.l.y, out.l.z]);
    q
}
