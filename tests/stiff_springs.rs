//! Stiff joint springs and dampers (theory.md §4.2): a UR5 arm whose joint PD law
//! `τ = kp (q_set − q) − kd q̇ + g(q_set)` is built into the model as joint stiffness `kp`
//! (up to 270 N·m/rad), damping `kd` (up to 38 N·m·s/rad) and the constant input
//! `kp q_set + g(q_set)`. The angle spring and damper act through the `atan2` discrete gradient
//! `F = f β (c̄ ∇s(q̄) − s̄ ∇c(q̄))`, so for every step size and both orders:
//! - every step converges (no `StepError`), also once the joints come to rest under the springs
//!   (the case that broke a spring written as `ΔV/δ` with a small relative rotation δ);
//! - `E_n − E_0 = W_n` (input work minus damper dissipation) to ≤ 1e-10 relative;
//! - the arm settles at `q_set` (the PD with exact gravity compensation has that equilibrium).

use std::path::Path;
use triad::mechanics::InputSlot;
use triad::sim::Simulation;
use triad::spec::Spec;

const Q_SET: [f64; 6] = [0.8, -1.2, 1.5, -0.8, 1.2, 0.5];
/// `kp q_set + g(q_set)` per joint (the peers' ur5_pd model), N·m.
const TAU: [f64; 6] = [
    149.35737695932642,
    -355.62567031112076,
    112.45664451143534,
    -19.643395843397094,
    29.928822106773907,
    0.85682365727,
];

fn run(h: f64, order: u8) -> (Vec<f64>, f64, f64, f64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/ur5_pd_internal.json");
    let spec = Spec::from_path(&path).expect("spec");
    let (def, mut settings) = spec.lower().expect("lower");
    settings.max_step = h;
    settings.order = order;
    let mut sim = Simulation::new(&def, settings, 0.0).expect("model");
    for (i, slot) in sim.model().inputs().to_vec().iter().enumerate() {
        let InputSlot::JointTorque { joint, .. } = slot else {
            panic!("unexpected input {slot:?}");
        };
        sim.state_mut().inputs_mut()[i] = TAU[*joint];
    }
    let e0 = sim.state().outputs().energy;
    let n = (3.0 / h).round() as usize;
    for k in 0..n {
        if let Err(e) = sim.advance(h) {
            panic!("h = {h}, order {order}: step {k} failed: {e:?}");
        }
    }
    let out = sim.state().outputs();
    let q = out.joints.iter().map(|j| j.q[0]).collect();
    (q, e0, out.energy, out.work)
}

#[test]
fn stiff_joint_springs_converge_balance_energy_and_settle() {
    for order in [2, 4] {
        for h in [1e-3, 1e-2, 2e-2, 5e-2] {
            let (q, e0, e, w) = run(h, order);
            let scale = e0.abs().max(e.abs()).max(w.abs());
            let bal = (e - e0 - w).abs() / scale;
            assert!(
                bal <= 1e-10,
                "h = {h}, order {order}: |E − E0 − W| = {bal:e}"
            );
            for (k, (qk, qs)) in q.iter().zip(Q_SET).enumerate() {
                assert!(
                    (qk - qs).abs() <= 1e-3,
                    "h = {h}, order {order}: joint {k} at {qk}, set point {qs}"
                );
            }
        }
    }
}
