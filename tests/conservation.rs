//! Conservation (theory.md §4.3): without inputs and damping the EM step keeps
//! `E = ½ vᵀ M v + V` exactly, and every momentum component that is a first integral of the model
//! (all of `p` and `L` for a free body; the vertical `L` of a heavy top about its fixed tip; none
//! for chains hinged about horizontal axes): `|E_n − E_0| ≤ 1e-12 |E_0|`, `|L_n − L_0| ≤ 1e-12 |L_0|`
//! over 10 000 steps, for order 2 and order 4, at large steps (h = 0.05 free body, 0.01 jointed).

mod common;
use common::*;
use triad::math::Vec3;
use triad::mechanics::{step, ModelDef};

/// Runs `n` steps; returns the largest relative drift of E and of the chosen L components.
fn drift(def: &ModelDef, h: f64, order: u8, n: usize, l_mask: Vec3) -> (f64, f64, f64, usize) {
    let (m, mut s) = build(def, settings(h, order));
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
