//! Conservation (theory.md §4.3): without inputs and damping the EM step keeps
//! `E = ½ vᵀ M v + V` exactly, and every momentum component that is a first integral of the model
//! (all of `p` and `L` for a free body; the vertical `L` of a heavy top about its fixed tip; none
//! for chains hinged about horizontal axes): `|E_n − E_0| ≤ 1e-12 |E_0|`, `|L_n − L_0| ≤ 1e-12 |L_0|`
//! over 10 000 steps, for order 2 and order 4, at large steps (h = 0.05 free body, 0.01 jointed).

mod common;
use common::*;
use triad::math::{Mat3, Vec3};
use triad::mechanics::{step, ModelDef, SolverSettings};

/// Runs `n` steps; returns the largest relative drift of E and of the chosen L components.
fn drift(def: &ModelDef, h: f64, order: u8, n: usize, l_mask: Vec3) -> (f64, f64, f64, usize) {
    drift_with(def, settings(h, order), n, l_mask)
}

/// [`drift`] with explicit solver settings.
fn drift_with(
    def: &ModelDef,
    settings: SolverSettings,
    n: usize,
    l_mask: Vec3,
) -> (f64, f64, f64, usize) {
    let h = settings.max_step;
    let (m, mut s) = build(def, settings);
    let e0 = s.outputs().energy;
    let l0 = s.outputs().l.component_mul(&l_mask);
    let escale = e0.abs().max(kinetic_scale(&s));
    let (mut de, mut dl, mut res) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut iters = 0;
    for _ in 0..n {
        iters += step(&m, &mut s, h).expect("step converges").iterations;
        de = de.max((s.outputs().energy - e0).abs() / escale);
        dl = dl.max((s.outputs().l.component_mul(&l_mask) - l0).norm() / l0.norm().max(1e-300));
        res = res.max(s.outputs().constraint_residual);
    }
    (de, dl, res, iters)
}

/// A scale for E when E₀ ≈ 0: the kinetic energy plus |gravity potential| magnitude.
fn kinetic_scale(s: &triad::mechanics::State) -> f64 {
    s.outputs().energy.abs().max(1e-3)
}

fn free_body_def() -> ModelDef {
    let j = box_inertia(10.0, 1.0, 0.6, 0.3);
    free_body(
        10.0,
        j,
        rot([0.3, -0.5, 0.2]),
        rot([0.3, -0.5, 0.2]) * Vec3::new(0.2, 3.0, 0.3),
        Vec3::new(0.1, 0.0, -0.2),
        false,
        false,
    )
}

/// The peers' Dzhanibekov body (inertia diag(1, 2, 3), ω = (0.05, 2, 0.05) rad/s: it flips
/// about its intermediate axis) at h = 0.02 and 0.01, where Newton takes chord iterations
/// (reused factors): their acceptance must leave no more than round-off (an acceptance 100×
/// looser drifted by 2.6e-12 through the flip at h = 0.02).
#[test]
fn flipping_body_with_chord_iterations() {
    let def = free_body(
        1.0,
        Mat3::from_diagonal(&Vec3::new(1.0, 2.0, 3.0)),
        Mat3::identity(),
        Vec3::new(0.05, 2.0, 0.05),
        Vec3::zeros(),
        false,
        false,
    );
    for h in [0.02, 0.01] {
        // the default Newton tolerance (1e-10), which the acceptance bound scales with
        let s = SolverSettings {
            max_step: h,
            ..SolverSettings::default()
        };
        let (de, dl, _, _) = drift_with(&def, s, (10.0 / h) as usize, Vec3::new(1.0, 1.0, 1.0));
        eprintln!("flipping body h = {h}: dE {de:e} dL {dl:e}");
        assert!(de < tol(2e-13) && dl < tol(2e-13), "h = {h}: {de:e} {dl:e}");
    }
}

#[test]
fn free_body_order2_and_order4() {
    for order in [2, 4] {
        let (de, dl, res, it) = drift(
            &free_body_def(),
            0.05,
            order,
            10_000,
            Vec3::new(1.0, 1.0, 1.0),
        );
        eprintln!(
            "free body order {order}: dE {de:e} dL {dl:e} res {res:e} it/step {}",
            it as f64 / 1e4
        );
        assert!(
            de < tol(1e-12) && dl < tol(1e-12),
            "order {order}: {de:e} {dl:e}"
        );
    }
}

#[test]
fn double_pendulum_order2_and_order4() {
    for order in [2, 4] {
        let (de, _, res, it) = drift(&double_pendulum(), 0.01, order, 10_000, Vec3::zeros());
        eprintln!(
            "double pendulum order {order}: dE {de:e} res {res:e} it/step {}",
            it as f64 / 1e4
        );
        assert!(de < tol(1e-12), "order {order}: {de:e}");
        assert!(res < tol(1e-10), "constraint residual {res:e}");
    }
}

#[test]
fn heavy_top_order2_and_order4() {
    for order in [2, 4] {
        let (de, dl, res, it) = drift(&heavy_top(), 0.01, order, 10_000, Vec3::z());
        eprintln!(
            "heavy top order {order}: dE {de:e} dLz {dl:e} res {res:e} it/step {}",
            it as f64 / 1e4
        );
        assert!(
            de < tol(1e-12) && dl < tol(1e-12),
            "order {order}: {de:e} {dl:e}"
        );
        assert!(res < tol(1e-10), "constraint residual {res:e}");
    }
}

#[test]
fn chain10_order2_and_order4() {
    for order in [2, 4] {
        let (de, _, res, it) = drift(&chain(10), 0.01, order, 10_000, Vec3::zeros());
        eprintln!(
            "chain10 order {order}: dE {de:e} res {res:e} it/step {}",
            it as f64 / 1e4
        );
        assert!(de < tol(1e-12), "order {order}: {de:e}");
        assert!(res < tol(1e-10), "constraint residual {res:e}");
    }
}

/// chain100 (the peers' 2 s run at h = 1e-3, and h = 0.01), where chord iterates are accepted
/// against the round-off floor of 100 bodies (`step.rs`, `FLOOR_SHARE`) rather than 1e-18:
/// the energy still holds to 1e-12 (order 2; order 4 only adds stages of the same kind).
#[test]
fn chain100_at_its_round_off_floor() {
    for (h, n) in [(1e-3, 2000), (0.01, 2000)] {
        let (de, _, res, it) = drift(&chain(100), h, 2, n, Vec3::zeros());
        eprintln!(
            "chain100 h {h}: dE {de:e} res {res:e} it/step {}",
            it as f64 / n as f64
        );
        assert!(de < tol(1e-12), "h {h}: {de:e}");
        assert!(res < tol(1e-10), "constraint residual {res:e}");
    }
}
