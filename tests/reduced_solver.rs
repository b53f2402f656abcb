//! The reduced iteration (Newton on the joint increments, discrete null-space method with
//! nodal reparametrization, theory.md §4.5) solves the same equations as the multiplier form:
//! `P̄ᵀ r(Φ(u)) = 0` with `g(Φ(u)) = g(qₙ)` ⟺ `r = −G(q̄)ᵀλ`, `g(q) = 0`. For every lower pair,
//! on a free body and on the world, with gravity, actuators, springs and dampers, the two
//! trajectories agree to the Newton tolerance, the reduced one converges without handing a
//! stage to the multiplier form, and the energy balance `E − E₀ = work` holds to 1e-10. Every
//! eighth stage starts from `qₙ` settled onto the rows (`g(qₙ) = 0` to round-off), so over a
//! long run the rows stay at round-off as in the multiplier form. The updates go to the
//! bodies, so a deep chain balances energy to round-off as well.
mod common;
use common::*;
use triad::math::{exp_so3, Vec3};
use triad::mechanics::{
    step, step_state, Frame, FreeBodyInitial, JointDef, JointInitial, JointType, Model, ModelDef,
    SolverSettings, State,
};

/// Body 0 free; body 1 on body 0 and body 2 on the world, both by `kind`, with offset frames,
/// a skew axis, moving initial states, actuators, springs (not on spherical joints) and
/// dampers.
fn model(kind: JointType) -> ModelDef {
    let b = |name: &str, m: f64, c: Vec3| {
        body(name, m, c, inertia6([0.3, 0.2, 0.25, 0.02, -0.01, 0.03]))
    };
    let initial = |s: f64| match kind {
        JointType::Spherical => JointInitial::Spherical {
            quat: [0.9, 0.1 * s, -0.2, 0.3],
            w: Vec3::new(0.5, -s, 2.0),
        },
        _ => JointInitial::Coords {
            q: (0..kind.nq()).map(|k| 0.3 * s + 0.2 * k as f64).collect(),
            qd: (0..kind.dof()).map(|k| 1.5 * s - 0.7 * k as f64).collect(),
        },
    };
    let jd = |name: &str, parent: Option<usize>, child: usize, s: f64| JointDef {
        name: name.into(),
        kind,
        parent,
        child,
        parent_frame: Frame {
            translation: Vec3::new(0.2, -0.1, 0.3) * s,
            rotation: exp_so3(&Vec3::new(0.1, 0.2, -0.1)),
        },
        child_frame: Frame {
            translation: Vec3::new(-0.1, 0.05, 0.2),
            rotation: exp_so3(&Vec3::new(-0.2, 0.1, 0.3)),
        },
        axis: Vec3::new(0.0, 0.6, 0.8),
        axis2: Vec3::x(),
        actuated: true,
        damping: 0.3,
        stiffness: if kind == JointType::Spherical {
            0.0
        } else {
            4.0
        },
        limits: Default::default(),
        armature: 0.0,
        friction: 0.0,

        loop_closing: false,
        initial: initial(s),
    };
    ModelDef {
        couplings: Vec::new(),
        actuators: Vec::new(),
        contact: Default::default(),
        gravity: Vec3::new(0.0, 0.0, -9.81),
        bodies: vec![
            b("a", 2.0, Vec3::zeros()),
            b("b", 1.5, Vec3::new(0.2, 0.0, 0.1)),
            b("c", 1.0, Vec3::new(0.0, 0.1, -0.1)),
        ],
        joints: vec![jd("j1", Some(0), 1, 1.0), jd("j2", None, 2, -1.0)],
        loads: vec![],
        free_bodies: vec![FreeBodyInitial {
            body: 0,
            position: Vec3::new(0.1, 0.2, 0.3),
            orientation: exp_so3(&Vec3::new(0.3, -0.5, 0.2)),
            velocity: Vec3::new(0.3, -0.1, 0.2),
            angular_velocity: Vec3::new(1.0, -2.0, 0.5),
        }],
        sites: vec![],
    }
}

#[test]
fn every_pair_agrees_with_the_multiplier_form() {
    let h = 0.01;
    for kind in KINDS {
        let def = model(kind);
        let s = SolverSettings {
            max_step: h,
            order: 2,
            tolerance: 1e-10,
            max_iterations: 20,
            ..SolverSettings::default()
        };
        let reduced = Model::new(&def, s).expect("model");
        let mut multiplier = reduced.clone();
        multiplier.set_reduced_solver(false);
        assert!(reduced.uses_reduced_solver() && !multiplier.uses_reduced_solver());
        let (mut a, mut b) = (State::new(&reduced), State::new(&multiplier));
        let inputs: Vec<f64> = (0..a.inputs().len())
            .map(|k| 0.4 * (k as f64 + 1.0).sin())
            .collect();
        a.inputs_mut().copy_from_slice(&inputs);
        b.inputs_mut().copy_from_slice(&inputs);
        let e0 = a.outputs().energy;
        let (mut dq, mut bal, mut fallbacks, mut its) = (0.0_f64, 0.0_f64, 0, 0);
        for _ in 0..300 {
            let sa = step(&reduced, &mut a, h).expect("reduced step");
            step(&multiplier, &mut b, h).expect("multiplier step");
            fallbacks += sa.fallbacks;
            its += sa.iterations;
            let d = a.coordinates().iter().zip(b.coordinates());
            dq = dq.max(d.map(|(x, y)| (x - y).abs()).fold(0.0, f64::max));
            let o = a.outputs();
            bal = bal.max((o.energy - e0 - o.work).abs() / e0.abs().max(1.0));
        }
        eprintln!(
            "{kind:?}: |Δq| {dq:e}, energy balance {bal:e}, {} iterations/step",
            its as f64 / 300.0
        );
        assert_eq!(
            fallbacks, 0,
            "{kind:?}: stages handed to the multiplier form"
        );
        assert!(dq < tol(1e-9), "{kind:?}: trajectories differ by {dq:e}");
        assert!(bal < tol(1e-10), "{kind:?}: energy balance {bal:e}");
        assert!(
            a.outputs().constraint_residual < 1e-12,
            "{kind:?}: constraints"
        );
    }
}

/// The joint rows stay at round-off over a long run: every eighth reduced stage starts from
/// the settled configuration (without it the largest row of chain30 grew to 5.9e-14 over
/// these 8000 steps; with it 2.4e-15).
#[test]
fn rows_stay_at_round_off_over_a_long_run() {
    let h = 1e-3;
    let (m, mut s) = build(&chain(30), settings(h, 2));
    assert!(m.uses_reduced_solver());
    for _ in 0..8000 {
        step_state(&m, &mut s, h).expect("step");
    }
    s.refresh_outputs(&m);
    let rows = s.outputs().constraint_residual;
    assert!(rows < 1e-14, "largest row {rows:e}");
}

/// The energy balance of a deep chain stays at round-off in the reduced form: the updates go
/// to each body's own increments, not through the joint increments, whose last place near the
/// root turns the whole subtree (chain300, default settings, 1000 steps at h = 1e-3: 6e-16
/// relative; placed through the joints 2.1e-14).
#[test]
fn a_deep_chain_balances_energy_to_round_off_in_the_reduced_form() {
    let h = 1e-3;
    let s = SolverSettings {
        max_step: h,
        ..SolverSettings::default()
    };
    let (m, mut st) = build(&chain(300), s);
    assert!(m.uses_reduced_solver());
    let e0 = st.outputs().energy;
    let mut fallbacks = 0;
    for _ in 0..1000 {
        fallbacks += step_state(&m, &mut st, h).expect("step").fallbacks;
    }
    st.refresh_outputs(&m);
    let o = st.outputs();
    let bal = (o.energy - e0 - o.work).abs() / e0.abs();
    eprintln!("chain300: energy balance {bal:e}, {fallbacks} stages handed back");
    assert_eq!(fallbacks, 0, "stages handed to the multiplier form");
    assert!(bal < 5e-15, "energy balance {bal:e}");
}

/// Large steps of fast motion start a stage from a poor predictor (first updates ≈ 1e-2): the
/// matrix is refreshed at the second iteration, whose chords then contract at about the square
/// of the first matrix's rate. Heavy top, order 4 with five stages, h = 0.05: about 20
/// iterations and 8 factorisations per step (on chords from the first matrix alone: 28.4
/// iterations and 5 factorisations), no stage handed back, energy balanced.
#[test]
fn large_steps_refresh_the_matrix_after_a_poor_first_update() {
    let h = 0.05;
    let s = SolverSettings {
        max_step: h,
        order: 4,
        stages: 5,
        tolerance: 1e-10,
        max_iterations: 20,
        ..SolverSettings::default()
    };
    let (m, mut st) = build(&heavy_top(), s);
    assert!(m.uses_reduced_solver());
    let e0 = st.outputs().energy;
    let steps = 400;
    let (mut it, mut fac, mut fallbacks) = (0, 0, 0);
    for _ in 0..steps {
        let stats = step_state(&m, &mut st, h).expect("step");
        it += stats.iterations;
        fac += stats.factorizations;
        fallbacks += stats.fallbacks;
    }
    st.refresh_outputs(&m);
    let o = st.outputs();
    let bal = (o.energy - e0 - o.work).abs() / e0.abs();
    let (it, fac) = (it as f64 / steps as f64, fac as f64 / steps as f64);
    eprintln!("heavy top h = {h}: {it} iterations, {fac} factorisations per step, balance {bal:e}");
    assert_eq!(fallbacks, 0, "stages handed to the multiplier form");
    assert!(it < 23.0, "{it} iterations per step");
    assert!(fac > 7.0, "{fac} factorisations per step");
    assert!(bal < 1e-13, "energy balance {bal:e}");
}
