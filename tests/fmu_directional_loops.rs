//! Directional derivatives of FMUs of models with closed loops and couplings (the four-bar,
//! the slider-crank, the example gripper without its finger's Coulomb friction): the states
//! are the independent coordinates `triad linearize` picks at the initial state; the values
//! are its `A, B, C, D` at the same state (in process) to round-off, and central differences
//! through the FMU (inputs at a communication point; the state through the initial
//! coordinates and rates `joint.J.q0`, `qd0` of every tree joint, closed around the loops);
//! dependent joints are refused as knowns, loop-closing joints as unknowns, and a point where
//! triad's pick is not the declared one is refused.

// index loops over a Jacobian's rows and columns read closer to the formulas
#![allow(clippy::needless_range_loop)]

mod fmu_support;

use fmu_support::api3::fmi3GetDirectionalDerivative;
use fmu_support::fmi3::{assert_adjoint_is_transpose, directional3, shipped, Fmu3};
use fmu_support::*;
use triad::ffi::fmi3::types::{fmi3Error, fmi3OK};
use triad::ffi::types::*;
use triad::mechanics::{JointInitial, Operating, Quantity};
use triad::sim::Simulation;
use triad::variables::linear::{differentiable, quantity, states};
use triad::variables::{Accessor, Causality};

/// The example gripper without its finger's Coulomb friction (no derivative where it
/// sticks), the fingers half closed (off their stops).
fn gripper() -> TestModel {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/specs/gripper.toml"),
    )
    .unwrap();
    let text = text
        .replace(
            "friction = 0.2                      # N\n",
            "initial = { q = 0.02 }\n",
        )
        .replace(
            "axis = [0.0, 1.0, 0.0]              # mirrored\n",
            "axis = [0.0, 1.0, 0.0]\ninitial = { q = 0.02 }\n",
        );
    assert!(!text.contains("friction ="));
    TestModel::new(&text)
}

fn models() -> Vec<(&'static str, TestModel)> {
    vec![
        ("four_bar", shipped("four_bar")),
        ("slider_crank", shipped("slider_crank")),
        ("gripper", gripper()),
    ]
}

/// Input values for a model's inputs (small, so that the run stays in range).
fn inputs(n: usize) -> Vec<f64> {
    (0..n).map(|i| 0.3 - 0.2 * i as f64).collect()
}

/// The declared states' and derivatives' value references (`(q…, qd…)`, `(qd…, qdd…)`).
fn declared(m: &TestModel) -> (Vec<u32>, Vec<u32>) {
    let st = states(&m.table).expect("the model declares states");
    let vr = |i: &usize| m.table.vars[*i].vr;
    (
        st.q.iter().chain(&st.qd).map(vr).collect(),
        st.qd.iter().chain(&st.qdd).map(vr).collect(),
    )
}

/// Every output with derivatives: value references and quantities.
fn outputs(m: &TestModel) -> (Vec<u32>, Vec<Quantity>) {
    m.table
        .vars
        .iter()
        .filter(|v| v.causality == Causality::Output && differentiable(&m.table, v.accessor))
        .map(|v| (v.vr, quantity(v.accessor).unwrap()))
        .unzip()
}

/// The in-process simulation the FMU runs, after `steps` steps of 0.01 s with inputs `u`.
fn sim_at(m: &TestModel, u: &[f64], steps: usize) -> Simulation {
    let (def, settings) = m.spec.lower().unwrap();
    let mut sim = Simulation::new(&def, settings, 0.0).unwrap();
    sim.state_mut().inputs_mut().copy_from_slice(u);
    for _ in 0..steps {
        sim.advance(0.01).unwrap();
    }
    sim
}

/// The states are `triad linearize`'s independent coordinates, named as its `x`; the
/// dependent joints' coordinates, rates and accelerations are outputs, the loop-closing
/// joints' have no accelerations.
#[test]
fn loop_models_declare_the_independent_coordinates() {
    for (name, m) in models() {
        let (states, _) = declared(&m);
        let names: Vec<&str> = states
            .iter()
            .map(|&vr| m.table.by_vr(vr).unwrap().name.as_str())
            .collect();
        let sim = sim_at(&m, &inputs(m.vrs(Causality::Input).len()), 0);
        let op = sim.operating().unwrap();
        assert_eq!(names, op.state_names(sim.model()), "{name}");
        assert!(
            states.len() < 2 * op.q.len(),
            "{name}: dependent joints are no states"
        );
        let def = sim.model().def();
        for (j, jd) in def.joints.iter().enumerate() {
            let has_qdd = m
                .table
                .vars
                .iter()
                .any(|v| v.accessor == Accessor::JointQdd { joint: j, k: 0 });
            assert_eq!(has_qdd, !jd.loop_closing, "{name}: joint {}", jd.name);
        }
    }
}

/// `[A B; C D]` through the FMU (every state and input a known, the derivatives and every
/// differentiable output unknowns) equals `Operating::linearize` at the same state, after a
/// run under inputs, to round-off.
#[test]
fn loop_fmu_jacobian_is_the_linear_model() {
    for (name, m) in models() {
        let ins = m.vrs(Causality::Input);
        let u = inputs(ins.len());
        let f = Fmu::initialised(&m);
        assert_eq!(f.set_real(&ins, &u), fmi2OK);
        for k in 0..20 {
            assert_eq!(f.step(0.01 * f64::from(k), 0.01), fmi2OK);
        }
        let (states, derivs) = declared(&m);
        let (out_vrs, ys) = outputs(&m);
        let op = sim_at(&m, &u, 20).operating().unwrap();
        let lin = op.linearize(&ys).unwrap();
        let nx = states.len();
        assert_eq!(lin.a.nrows(), nx, "{name}");
        let knowns: Vec<u32> = states.iter().chain(&ins).copied().collect();
        let unknowns: Vec<u32> = derivs.iter().chain(&out_vrs).copied().collect();
        let mut worst = 0.0_f64;
        for c in 0..knowns.len() {
            let mut seed = vec![0.0; knowns.len()];
            seed[c] = 1.0;
            let (s, col) = dd(&f, &unknowns, &knowns, &seed);
            assert_eq!(s, fmi2OK, "{name}: {}", f.last_message());
            for r in 0..unknowns.len() {
                let want = match (r < nx, c < nx) {
                    (true, true) => lin.a[(r, c)],
                    (true, false) => lin.b[(r, c - nx)],
                    (false, true) => lin.c[(r - nx, c)],
                    (false, false) => lin.d[(r - nx, c - nx)],
                };
                worst = worst.max((col[r] - want).abs() / (1.0 + want.abs()));
            }
        }
        eprintln!("{name}: FMU vs linearize, worst {worst:.1e}");
        assert!(worst <= 1e-13, "{name}: worst {worst:e}");
    }
}

/// Against central differences through the FMU: over the inputs at a communication point
/// (every joint's acceleration), and over the state at the start through the initial
/// coordinates and rates of every tree joint (`Operating::initial_def`: the dependent ones
/// closed around the loops), every differentiable output.
#[test]
fn loop_fmu_derivatives_match_differences_through_the_fmu() {
    let eps = 1e-6;
    for (name, m) in models() {
        let ins = m.vrs(Causality::Input);
        let u = inputs(ins.len());
        let qdd: Vec<u32> = m
            .table
            .vars
            .iter()
            .filter(|v| matches!(v.accessor, Accessor::JointQdd { .. }))
            .map(|v| v.vr)
            .collect();
        let f = Fmu::initialised(&m);
        assert_eq!(f.set_real(&ins, &u), fmi2OK);
        for k in 0..20 {
            assert_eq!(f.step(0.01 * f64::from(k), 0.01), fmi2OK);
        }
        let mut worst = 0.0_f64;
        for (k, &vr) in ins.iter().enumerate() {
            let (s, ex) = dd(&f, &qdd, &[vr], &[1.0]);
            assert_eq!(s, fmi2OK, "{name}: {}", f.last_message());
            let mut up = u.clone();
            up[k] += eps;
            assert_eq!(f.set_real(&ins, &up), fmi2OK);
            let (_, p) = f.get_real(&qdd);
            up[k] -= 2.0 * eps;
            assert_eq!(f.set_real(&ins, &up), fmi2OK);
            let (_, mm) = f.get_real(&qdd);
            assert_eq!(f.set_real(&ins, &u), fmi2OK);
            for r in 0..qdd.len() {
                let fd = (p[r] - mm[r]) / (2.0 * eps);
                worst = worst.max((fd - ex[r]).abs() / (1.0 + fd.abs()));
            }
        }
        eprintln!("{name}: inputs vs differences, worst {worst:.1e}");
        assert!(worst <= 1e-6, "{name}: inputs: worst {worst:e}");
        // the state, at the start
        let (states, _) = declared(&m);
        let (out_vrs, _) = outputs(&m);
        let sim = sim_at(&m, &vec![0.0; ins.len()], 0);
        let op = sim.operating().unwrap();
        let def = sim.model().def().clone();
        let x0 = op.x();
        let base = Fmu::initialised(&m);
        let mut worst = 0.0_f64;
        for c in 0..x0.len() {
            let mut seed = vec![0.0; states.len()];
            seed[c] = 1.0;
            let (s, ex) = dd(&base, &out_vrs, &states, &seed);
            assert_eq!(s, fmi2OK, "{name}: {}", base.last_message());
            let at = |d: f64| {
                let mut x = x0.clone();
                x[c] += d;
                let moved = op.initial_def(&def, &x);
                let (mut vrs, mut vals) = (Vec::new(), Vec::new());
                for jd in moved.joints.iter().filter(|j| !j.loop_closing) {
                    if let JointInitial::Coords { q, qd } = &jd.initial {
                        vrs.extend([
                            m.vr(&format!("joint.{}.q0", jd.name)),
                            m.vr(&format!("joint.{}.qd0", jd.name)),
                        ]);
                        vals.extend([q[0], qd[0]]);
                    }
                }
                Fmu::initialised_with(&m, &vrs, &vals).get_real(&out_vrs).1
            };
            let (p, mm) = (at(eps), at(-eps));
            for r in 0..out_vrs.len() {
                let fd = (p[r] - mm[r]) / (2.0 * eps);
                worst = worst.max((fd - ex[r]).abs() / (1.0 + fd.abs()));
            }
        }
        eprintln!("{name}: states vs differences, worst {worst:.1e}");
        assert!(worst <= 1e-6, "{name}: states: worst {worst:e}");
    }
}

#[test]
fn loop_bad_calls_are_refused_and_change_nothing() {
    let m = shipped("four_bar");
    let f = Fmu::initialised(&m);
    let (states, derivs) = declared(&m);
    let cases: [(&[u32], &[u32], &str); 4] = [
        (
            &derivs[..1],
            &[m.vr("joint.rocker_pivot.q")],
            "is a dependent joint's",
        ),
        (
            &derivs[..1],
            &[m.vr("joint.crank_coupler.qd")],
            "is a dependent joint's",
        ),
        (
            &[m.vr("joint.coupler_rocker.q")],
            &states[..1],
            "loop-closing joint's",
        ),
        (
            &derivs[..1],
            &[m.vr("joint.coupler_rocker.q")],
            "neither a state nor an input",
        ),
    ];
    for (u, k, msg) in cases {
        let (s, out) = dd(&f, u, k, &vec![1.0; k.len()]);
        assert_eq!(s, fmi2Error, "{msg}");
        assert!(out.iter().all(|x| x.is_nan()), "output written");
        assert!(f.last_message().contains(msg), "{}", f.last_message());
    }
    // the instance goes on
    assert_eq!(f.step(0.0, 0.01), fmi2OK);
    assert_eq!(dd(&f, &derivs, &states[..1], &[1.0]).0, fmi2OK);
    // the shipped gripper's finger has Coulomb friction: no derivatives, and it says why
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/specs/gripper.toml"),
    )
    .unwrap();
    let g = TestModel::new(&text);
    assert!(triad::variables::linear::states(&g.table).is_none());
    let h = Fmu::initialised(&g);
    let o = g.vrs(Causality::Output);
    assert_eq!(dd(&h, &o[..1], &[], &[]).0, fmi2Error);
    assert!(
        h.last_message().contains("Coulomb friction"),
        "{}",
        h.last_message()
    );
}

/// The four-bar driven at the rocker: the rocker's coordinate is the state (picked at the
/// start), but where the rocker turns back (its rate 0 while the crank moves) it cannot be
/// independent and triad picks another: there the call is refused (nothing written), and
/// after it the rocker is the state again.
#[test]
fn a_point_where_the_pick_differs_is_refused() {
    let text = triad::spec::bundled()
        .iter()
        .find(|(n, _)| *n == "four_bar")
        .unwrap()
        .1
        .replacen("actuated = true\n", "", 1)
        .replace(
            "name = \"rocker_pivot\"\n",
            "name = \"rocker_pivot\"\nactuated = true\n",
        );
    let m = TestModel::new(&text);
    let (states, derivs) = declared(&m);
    assert_eq!(
        m.table.by_vr(states[0]).unwrap().name,
        "joint.rocker_pivot.q"
    );
    let f = Fmu::initialised(&m);
    let (mut refused, mut ok_after) = (0, 0);
    for k in 0..400 {
        let (s, out) = dd(&f, &derivs, &states[..1], &[1.0]);
        if s == fmi2Error {
            refused += 1;
            assert!(out.iter().all(|x| x.is_nan()), "output written");
            let msg = f.last_message();
            assert!(
                msg.contains("are not the declared states (joint.rocker_pivot.q)"),
                "{msg}"
            );
        } else {
            assert_eq!(s, fmi2OK, "{}", f.last_message());
            if refused > 0 {
                ok_after += 1;
            }
        }
        assert_eq!(f.step(0.01 * f64::from(k), 0.01), fmi2OK);
    }
    eprintln!("{refused} of 400 points refused, {ok_after} accepted after the first refusal");
    assert!(
        refused > 0 && ok_after > 0,
        "{refused} refused, {ok_after} after"
    );
}

/// FMI 3: the four-bar's directional derivative equals FMI 2's, the adjoint is its transpose,
/// and a dependent joint is refused as a known.
#[test]
fn loop_fmi3_directional_and_adjoint() {
    let m = shipped("four_bar");
    let f2 = Fmu::initialised(&m);
    let f = Fmu3::initialised(&m);
    let names = [
        "joint.crank_pivot.q",
        "joint.crank_pivot.qd",
        "joint.crank_pivot.tau",
    ];
    let outs = [
        "joint.crank_pivot.qdd",
        "joint.rocker_pivot.qdd",
        "joint.crank_coupler.q",
        "body.coupler.r",
    ];
    let knowns: Vec<u32> = names.iter().map(|n| f.var(n).vr).collect();
    let unknowns: Vec<u32> = outs.iter().map(|n| f.var(n).vr).collect();
    let nu = 1 + 1 + 1 + 3;
    let v = [0.3, -0.2, 0.7];
    let (s, jv) = directional3(&f, &unknowns, &knowns, &v, nu);
    assert_eq!(s, fmi3OK, "{}", f.last_message());
    // FMI 2, element by element
    let k2: Vec<u32> = names.iter().map(|n| m.vr(n)).collect();
    let u2: Vec<u32> = [
        "joint.crank_pivot.qdd",
        "joint.rocker_pivot.qdd",
        "joint.crank_coupler.q",
        "body.coupler.r[1]",
        "body.coupler.r[2]",
        "body.coupler.r[3]",
    ]
    .iter()
    .map(|n| m.vr(n))
    .collect();
    let (s, j2) = dd(&f2, &u2, &k2, &v);
    assert_eq!(s, fmi2OK);
    assert_eq!(jv, j2);
    assert_adjoint_is_transpose(&f, &unknowns, &knowns, &v, &jv);
    // a dependent joint as a known
    let dep = [f.var("joint.rocker_pivot.q").vr];
    let mut out = [f64::NAN];
    let s = unsafe {
        fmi3GetDirectionalDerivative(
            f.c,
            unknowns.as_ptr(),
            1,
            dep.as_ptr(),
            1,
            [1.0].as_ptr(),
            1,
            out.as_mut_ptr(),
            1,
        )
    };
    assert_eq!(s, fmi3Error);
    assert!(out[0].is_nan());
    assert!(
        f.last_message().contains("dependent joint"),
        "{}",
        f.last_message()
    );
}

/// `Operating::directional` along a unit direction is `linearize`'s column, bit for bit.
#[test]
fn operating_directional_is_the_linear_models_column() {
    let m = shipped("slider_crank");
    let sim = sim_at(&m, &inputs(m.vrs(Causality::Input).len()), 5);
    let op: Operating = sim.operating().unwrap();
    let (_, ys) = outputs(&m);
    let lin = op.linearize(&ys).unwrap();
    let nx = op.x().len();
    for c in 0..nx {
        let mut dx = vec![0.0; nx];
        dx[c] = 1.0;
        let col = op.directional(&dx, &vec![0.0; op.u.len()], &ys).unwrap();
        for r in 0..ys.len() {
            assert_eq!(col[r], lin.c[(r, c)]);
        }
    }
}
