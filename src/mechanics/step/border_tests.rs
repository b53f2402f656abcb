//! The bordered tree solve against the dense LU oracle on the same assembled systems: Newton
//! update (fresh factorisation and chord re-solve with a new right-hand side) and velocity
//! projection, on the four-bar and on 30-link chains closed to the world or to an earlier body.

use crate::mechanics::model::def::{ModelDef, SolverSettings};
use crate::mechanics::model::fixtures::{chain_loop, four_bar, AX};
use crate::mechanics::model::projection::{project_velocities, ProjWork};
use crate::mechanics::model::runtime::Model;
use crate::mechanics::step::newton::{
    evaluate, resolve, solve, stage_rates, update, Held, Mode, Work,
};

/// The joints' damping and stiffness as defined (the `Held` parameters of a step).
fn joint_parameters(def: &ModelDef) -> (Vec<f64>, Vec<f64>) {
    (
        def.joints.iter().map(|j| j.damping).collect(),
        def.joints.iter().map(|j| j.stiffness).collect(),
    )
}

/// The Newton unknowns in the dense order (bodies, then multipliers by `row0`).
fn gather(model: &Model, ws: &Work) -> Vec<f64> {
    if model.dense {
        return ws.drhs.clone();
    }
    let nb = model.bodies.len();
    let mut x = vec![0.0; 6 * nb + model.nrows];
    for b in 0..nb {
        x[6 * b..6 * b + 6].copy_from_slice(&ws.blocks[b].r[..6]);
    }
    for (j, jt) in model.joints.iter().enumerate() {
        for k in 0..jt.rows.len() {
            x[6 * nb + jt.row0 + k] =
                ws.border.lrow[j].map_or(ws.blocks[jt.child].r[6 + k], |l| ws.border.rc[l + k]);
        }
    }
    x
}

/// Largest difference relative to the largest entry, bodies and multipliers apart.
fn mismatch(nb: usize, a: &[f64], b: &[f64]) -> f64 {
    let part = |r: std::ops::Range<usize>| {
        let big = b[r.clone()].iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let d = r.fold(0.0_f64, |m, i| m.max((a[i] - b[i]).abs()));
        d / big.max(f64::MIN_POSITIVE)
    };
    part(0..6 * nb).max(part(6 * nb..a.len()))
}

/// Fresh solve and chord re-solve of both solvers at the same iterates agree to `tol` (and the
/// velocity projections, if `tol` is given); returns the larger mismatch. Without loops (a tree)
/// the tree solve is compared.
fn assert_newton_agrees(def: &ModelDef, tol: f64, coupled: bool) -> f64 {
    let mut md = Model::new(def, SolverSettings::default()).expect("model");
    md.dense = true;
    let mb = Model::new(def, SolverSettings::default()).expect("model");
    assert!(!mb.dense && !mb.uses_dense_solver());
    let (mut wd, mut wb) = (Work::new(&md), Work::new(&mb));
    let loops = def.joints.iter().any(|j| j.loop_closing);
    assert_eq!(wb.border.is_active(), loops);
    assert!(wb.dense.is_empty());
    let (damping, stiffness) = joint_parameters(def);
    let held = Held {
        inputs: &[],
        damping: &damping,
        stiffness: &stiffness,
        gains: &[],
    };
    let h = 0.01;
    stage_rates(&mut wd, h);
    stage_rates(&mut wb, h);
    let nb = md.bodies.len();
    // a nontrivial iterate: increments and multipliers
    wd.drhs.fill(0.0);
    for i in 0..6 * nb {
        wd.drhs[i] = 2e-3 * (0.37 * i as f64).cos();
    }
    update(&md, &mut wd);
    for (k, m) in wd.mu.iter_mut().enumerate() {
        *m = 2e-3 * (k as f64 + 1.0).sin();
    }
    let copy = |wd: &Work, wb: &mut Work| {
        wb.q.copy_from_slice(&wd.q);
        wb.dq.copy_from_slice(&wd.dq);
        wb.mu.copy_from_slice(&wd.mu);
    };
    copy(&wd, &mut wb);
    evaluate(&md, &mut wd, &held, h, Mode::Full);
    evaluate(&mb, &mut wb, &held, h, Mode::Full);
    if coupled {
        assert!(
            wb.border.x.iter().any(|v| v.abs() > 1e-9),
            "no off-tree coupling"
        );
    }
    let (a, r) = (wd.dense.clone(), wd.drhs.clone());
    assert!(solve(&md, &mut wd) && solve(&mb, &mut wb));
    let (xd, xb) = (gather(&md, &wd), gather(&mb, &wb));
    let n = r.len();
    let resid = |x: &[f64]| -> Vec<f64> {
        (0..n)
            .map(|i| r[i] - (0..n).map(|j| a[i * n + j] * x[j]).sum::<f64>())
            .collect()
    };
    let mut corr = resid(&xd);
    crate::mechanics::linalg::dense::lu_solve(&wd.dense, n, n, &wd.dpiv, &mut corr);
    let xr: Vec<f64> = xd.iter().zip(&corr).map(|(x, c)| x + c).collect();
    let e = mismatch(nb, &xb, &xd);
    // against the dense solution improved by one refinement step: the error is the tree's
    eprintln!(
        "fresh: mismatch {e:.1e} (to the refined solution: dense {:.1e}, tree/bordered {:.1e})",
        mismatch(nb, &xd, &xr),
        mismatch(nb, &xb, &xr)
    );
    assert!(e < tol, "fresh solve: mismatch {e:e}");
    // chord: a new iterate, right-hand side only, the old factors
    update(&md, &mut wd);
    copy(&wd, &mut wb);
    evaluate(&md, &mut wd, &held, h, Mode::Residual);
    evaluate(&mb, &mut wb, &held, h, Mode::Residual);
    let (rd, rb) = (gather(&md, &wd), gather(&mb, &wb));
    assert!(mismatch(nb, &rb, &rd) < 1e-14, "right-hand sides differ");
    assert!(resolve(&md, &mut wd) && resolve(&mb, &mut wb));
    let (yd, yb) = (gather(&md, &wd), gather(&mb, &wb));
    let e2 = mismatch(nb, &yb, &yd);
    eprintln!("chord: mismatch {e2:.1e}");
    assert!(e2 < tol, "chord re-solve: mismatch {e2:e}");
    assert!(
        mismatch(nb, &yd, &xd) > 1e-3,
        "the chord right-hand side did not change"
    );
    // the velocity projection
    let (mut pd, mut pb) = (ProjWork::new(&md), ProjWork::new(&mb));
    let v: Vec<f64> = (0..12 * nb).map(|i| (0.11 * i as f64).sin()).collect();
    assert!(project_velocities(&md, &wd.q, &v, &mut pd));
    assert!(project_velocities(&mb, &wd.q, &v, &mut pb));
    let e = mismatch(0, &pb.vp, &pd.vp);
    eprintln!("projection: mismatch {e:.1e}");
    assert!(e < tol, "projection: mismatch {e:e}");
    e.max(e2).max(mismatch(nb, &xb, &xd))
}

#[test]
fn four_bar_matches_dense() {
    _ = assert_newton_agrees(&four_bar(), 1e-12, false);
}

#[test]
fn chain_closed_to_world_matches_dense() {
    _ = assert_newton_agrees(&chain_loop(30, None, AX), 1e-12, false);
}

#[test]
fn chain_closed_to_an_earlier_body_matches_dense() {
    _ = assert_newton_agrees(&chain_loop(30, Some(3), AX), 1e-12, true);
}

/// A tree has an empty border.
#[test]
fn tree_has_no_border() {
    let mut def = chain_loop(4, None, 3.1e-6);
    def.joints.pop();
    let m = Model::new(&def, SolverSettings::default()).expect("model");
    let b = m.border();
    assert!(!b.is_active() && b.rc.is_empty() && b.w.is_empty());
}

/// With the peers' thin rods (axial inertia 3.1e-6 kg·m²) neither the tree solve of the open
/// chain nor the bordered solve of the closed one reaches 1e-12 against the dense LU; the
/// bordered solve is as accurate as the tree solve (within a factor 2) and below 1e-10.
#[test]
fn thin_rods_as_accurate_as_the_tree_solve() {
    let mut open = chain_loop(30, None, 3.1e-6);
    open.joints.pop();
    let tree = assert_newton_agrees(&open, 1e-9, false);
    for to in [None, Some(3)] {
        let e = assert_newton_agrees(&chain_loop(30, to, 3.1e-6), 1e-10, to.is_some());
        eprintln!("thin rods, loop to {to:?}: {e:.1e}, tree solve of the open chain {tree:.1e}");
        assert!(
            e <= 2.0 * tree.max(1e-12),
            "bordered {e:e} against tree {tree:e}"
        );
    }
}

/// `Mode::Residual` rebuilds the loop rows' right-hand side bit for bit and leaves the border
/// matrices (part of the factors for chord iterations) untouched.
#[test]
fn residual_mode_keeps_the_border() {
    const SENTINEL: f64 = 1234.5;
    let def = chain_loop(8, Some(2), AX);
    let m = Model::new(&def, SolverSettings::default()).expect("model");
    let mut ws = Work::new(&m);
    stage_rates(&mut ws, 0.01);
    let (damping, stiffness) = joint_parameters(&def);
    let held = Held {
        inputs: &[],
        damping: &damping,
        stiffness: &stiffness,
        gains: &[],
    };
    evaluate(&m, &mut ws, &held, 0.01, Mode::Full);
    assert!(solve(&m, &mut ws));
    update(&m, &mut ws);
    evaluate(&m, &mut ws, &held, 0.01, Mode::Full);
    let rc = ws.border.rc.clone();
    assert!(rc.iter().any(|x| *x != 0.0));
    for v in [&mut ws.border.bt, &mut ws.border.ct, &mut ws.border.x] {
        v.fill(SENTINEL);
    }
    ws.border.rc.fill(-SENTINEL);
    evaluate(&m, &mut ws, &held, 0.01, Mode::Residual);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&ws.border.rc), bits(&rc));
    let b = &ws.border;
    assert!(b.bt.iter().chain(&b.ct).chain(&b.x).all(|x| *x == SENTINEL));
}
