//! `fmi2GetDirectionalDerivative` and `fmi3GetDirectionalDerivative`/`AdjointDerivative`:
//! against `triad linearize`'s model at the same state, against finite differences through
//! the FMU (inputs, and the initial coordinates as parameters), and bad calls refused (closed
//! loops and couplings: `fmu_directional_loops.rs`).

// index loops over a Jacobian's rows and columns read closer to the formulas
#![allow(clippy::needless_range_loop)]

mod common;
mod fmu_support;

use fmu_support::api3::fmi3GetDirectionalDerivative;
use fmu_support::fmi3::{assert_adjoint_is_transpose, directional3, shipped, Fmu3};
use fmu_support::*;
use triad::ffi::fmi3::types::{fmi3Error, fmi3OK};
use triad::ffi::getset::fmi2GetDirectionalDerivative;
use triad::ffi::types::*;
use triad::variables::linear::{quantity, states};
use triad::variables::Causality;

/// The robot arm after 0.2 s under torques: its states, derivatives and inputs.
fn arm() -> (TestModel, Fmu, Vec<u32>, Vec<u32>, Vec<u32>) {
    let m = shipped("robot_arm");
    let f = Fmu::initialised(&m);
    let ins = m.vrs(Causality::Input);
    let u: Vec<f64> = (0..ins.len()).map(|i| 3.0 - i as f64).collect();
    assert_eq!(f.set_real(&ins, &u), fmi2OK);
    for k in 0..20 {
        assert_eq!(f.step(0.01 * f64::from(k), 0.01), fmi2OK);
    }
    let st = states(&m.table).expect("the arm declares states");
    let vr = |i: &usize| m.table.vars[*i].vr;
    let states: Vec<u32> = st.q.iter().chain(&st.qd).map(vr).collect();
    let derivs: Vec<u32> = st.qd.iter().chain(&st.qdd).map(vr).collect();
    (m, f, states, derivs, ins)
}

/// The Jacobian of the derivatives over the states and inputs is `[A B]` of `linearize` at the
/// same state (the same simulation in process), to round-off.
#[test]
fn the_fmu_jacobian_is_the_linear_model() {
    let (m, f, states, derivs, ins) = arm();
    let knowns: Vec<u32> = states.iter().chain(&ins).copied().collect();
    let (def, settings) = m.spec.lower().unwrap();
    let mut sim = triad::sim::Simulation::new(&def, settings, 0.0).unwrap();
    let u: Vec<f64> = (0..ins.len()).map(|i| 3.0 - i as f64).collect();
    sim.state_mut().inputs_mut().copy_from_slice(&u);
    for _ in 0..20 {
        sim.advance(0.01).unwrap();
    }
    let op = sim.operating().unwrap();
    let lin = op.linearize(&[]).unwrap();
    let n = op.q.len();
    let mut worst = 0.0_f64;
    for (c, _) in knowns.iter().enumerate() {
        let mut seed = vec![0.0; knowns.len()];
        seed[c] = 1.0;
        let (s, col) = dd(&f, &derivs, &knowns, &seed);
        assert_eq!(s, fmi2OK, "{}", f.last_message());
        for r in 0..2 * n {
            let want = if c < 2 * n {
                lin.a[(r, c)]
            } else {
                lin.b[(r, c - 2 * n)]
            };
            worst = worst.max((col[r] - want).abs() / (1.0 + want.abs()));
        }
    }
    assert!(worst <= 1e-13, "worst {worst:e}");
}

/// Against central differences through the FMU: over the inputs at a communication point, and
/// over the initial coordinates (parameters `joint.J.q0`) at the start.
#[test]
fn the_fmu_derivatives_match_differences_through_the_fmu() {
    let (m, f, _states, derivs, ins) = arm();
    let qdd: Vec<u32> = derivs[derivs.len() / 2..].to_vec();
    let u: Vec<f64> = (0..ins.len()).map(|i| 3.0 - i as f64).collect();
    let eps = 1e-6;
    for (k, &vr) in ins.iter().enumerate() {
        let (_, ex) = dd(&f, &qdd, &[vr], &[1.0]);
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
            assert!(
                (fd - ex[r]).abs() <= 1e-6 * (1.0 + fd.abs()),
                "input {k}: {fd} {}",
                ex[r]
            );
        }
    }
    // states: the initial coordinates as parameters, at t = 0
    let st = states(&m.table).unwrap();
    let names: Vec<String> = st.q.iter().map(|&i| m.table.vars[i].name.clone()).collect();
    let q0 = |name: &str| m.vr(&name.replace(".q", ".q0"));
    let base = Fmu::initialised(&m);
    let qvr: Vec<u32> = st.q.iter().map(|&i| m.table.vars[i].vr).collect();
    let qddvr: Vec<u32> = st.qdd.iter().map(|&i| m.table.vars[i].vr).collect();
    let (_, q_start) = base.get_real(&qvr);
    for (k, name) in names.iter().enumerate() {
        let (_, ex) = dd(&base, &qddvr, &[qvr[k]], &[1.0]);
        let at = |d: f64| {
            let g = Fmu::initialised_with(&m, &[q0(name)], &[q_start[k] + d]);
            g.get_real(&qddvr).1
        };
        let (p, mm) = (at(eps), at(-eps));
        for r in 0..qddvr.len() {
            let fd = (p[r] - mm[r]) / (2.0 * eps);
            assert!(
                (fd - ex[r]).abs() <= 1e-6 * (1.0 + fd.abs()),
                "{name}: {fd} {}",
                ex[r]
            );
        }
    }
}

#[test]
fn bad_calls_are_refused_and_change_nothing() {
    let (m, f, states, derivs, ins) = arm();
    let body_r = m.vr("body.shoulder_pan_link.r[1]");
    let work = m.vr("system.work");
    let cases: [(&[u32], &[u32], &str); 5] = [
        (&derivs[..1], &[999_999], "unknown value reference"),
        (&derivs[..1], &[body_r], "neither a state nor an input"),
        (&[ins[0]], &states[..1], "not an output"),
        (&[work], &states[..1], "not an output"),
        (
            &derivs[..1],
            &[m.vr("joint.elbow.damping")],
            "neither a state nor an input",
        ),
    ];
    for (u, k, msg) in cases {
        let (s, out) = dd(&f, u, k, &vec![1.0; k.len()]);
        assert_eq!(s, fmi2Error, "{msg}");
        assert!(out.iter().all(|x| x.is_nan()), "output written");
        assert!(f.last_message().contains(msg), "{}", f.last_message());
    }
    let (s, _) = dd(&f, &derivs[..1], &states[..1], &[f64::NAN]);
    assert_eq!(s, fmi2Error);
    let null = unsafe {
        fmi2GetDirectionalDerivative(
            f.c,
            derivs.as_ptr(),
            1,
            std::ptr::null(),
            1,
            [1.0].as_ptr(),
            [0.0].as_mut_ptr(),
        )
    };
    assert_eq!(null, fmi2Error);
    // before initialisation
    let g = Fmu::new(&m);
    assert_eq!(dd(&g, &derivs[..1], &states[..1], &[1.0]).0, fmi2Error);
    // the instance goes on
    assert_eq!(f.step(0.2, 0.01), fmi2OK);
    assert_eq!(dd(&f, &derivs, &states[..1], &[1.0]).0, fmi2OK);
    // models with closed loops and couplings: tests/fmu_directional_loops.rs
    // every output the table maps to a quantity can be asked for
    assert!(quantity(m.table.by_name("system.energy").unwrap().accessor).is_some());
}

/// FMI 3: the directional derivative over arrays equals FMI 2's, and the adjoint is its
/// transpose: `wᵀ (J v) = (Jᵀ w)ᵀ v`.
#[test]
fn fmi3_directional_and_adjoint_agree() {
    let m = shipped("robot_arm");
    let f = Fmu3::initialised(&m);
    let names = [
        "joint.elbow.q",
        "joint.elbow.qd",
        "joint.wrist_1.q",
        "joint.shoulder_lift.tau",
    ];
    let knowns: Vec<u32> = names.iter().map(|n| f.var(n).vr).collect();
    let unknowns: Vec<u32> = [
        "joint.elbow.qdd",
        "joint.wrist_2.qdd",
        "body.wrist_3_link.r",
        "system.L",
    ]
    .iter()
    .map(|n| f.var(n).vr)
    .collect();
    let nu = 1 + 1 + 3 + 3;
    let v = [0.3, -0.2, 0.7, 1.1];
    let (s, mut jv) = directional3(&f, &unknowns, &knowns, &v, nu);
    assert_eq!(s, fmi3OK, "{}", f.last_message());
    assert_adjoint_is_transpose(&f, &unknowns, &knowns, &v, &jv);
    // a wrong nSensitivity is refused
    let s = unsafe {
        fmi3GetDirectionalDerivative(
            f.c,
            unknowns.as_ptr(),
            4,
            knowns.as_ptr(),
            4,
            v.as_ptr(),
            4,
            jv.as_mut_ptr(),
            nu - 1,
        )
    };
    assert_eq!(s, fmi3Error);
}

/// A chain of 300 links carries no accelerations (their read would factor a 300 × 300 mass
/// matrix) and so declares no states; one of 150 does.
#[test]
fn large_trees_carry_no_accelerations() {
    for (n, want) in [(150, true), (300, false)] {
        let def = common::chain(n);
        let table = triad::variables::VariableTable::new(
            &def,
            &triad::mechanics::SolverSettings::default(),
        );
        let qdd = table
            .vars
            .iter()
            .any(|v| matches!(v.accessor, triad::variables::Accessor::JointQdd { .. }));
        assert_eq!(qdd, want, "chain{n}");
    }
}
