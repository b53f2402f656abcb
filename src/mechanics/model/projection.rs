//! Constraint-consistent output velocities: the M-orthogonal projection of the nodal velocities
//! `vₙ` (which satisfy the hidden constraints only to O(h²), theory.md §4.3) onto the admissible
//! velocities at `qₙ`.
//!
//! ```text
//! v' = argmin ½ (v' − v)ᵀ M (v' − v)   subject to   G(qₙ) v' = 0   (internal + active joint rows)
//! ```
//!
//! In twist coordinates (6 per body, `t = (φ̇, ω)`, world frame, m/s and rad/s) the admissible
//! velocities are `v' = P t` with `P = [I; −d̂₁; −d̂₂; −d̂₃]` (12 × 6 per body), which satisfies the
//! internal constraints identically; the joint rows remain. The KKT system
//!
//! ```text
//! [ PᵀMP      (G P)ᵀ ] [ t ]   [ PᵀM v ]
//! [ G P        0     ] [ λ ] = [   0   ]
//! ```
//!
//! has per body `PᵀMP = diag(m I, J_s)` (`J_s = −Σᵢⱼ Eᵢⱼ d̂ᵢ d̂ⱼ = R J Rᵀ` for orthonormal
//! directors, kg·m²) and `PᵀM v = (m φ̇, Σᵢ dᵢ × pᵢ)`, `pᵢ = Σⱼ Eᵢⱼ ḋⱼ` (N·s, N·m·s). It has the
//! block structure of the Newton matrix (a 6 × 6 block per body, the rows of each tree joint
//! with its child, couplings along tree edges), so it is solved by the same O(N) tree
//! elimination; the rows of loop-closing joints form the border of that solve (`border`, the same
//! bordered solve as the Newton step; the dense LU only as the test oracle). Redundant (dropped)
//! loop rows stay dropped. A joint coupling `q_b = r q_a + o` adds the row `q̇_b − r q̇_a = 0`
//! (`coupling`), in the border like a loop row.
//!
//! Properties: the residual `v − v'` is M-orthogonal to every admissible velocity, in
//! particular to superposed rigid motions whenever these are admissible, so every momentum that
//! is a first integral is the same computed from `v'` or `v`; `½ v'ᵀMv' = ½ vᵀMv − ½ |v − v'|²_M`
//! differs by O(h⁴).
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use crate::mechanics::linalg::border::Border;
use crate::mechanics::linalg::dense::{lu_factor, lu_solve};
use crate::mechanics::linalg::tree::{solve_tree, Block};

use super::constraint::{body_nodes, Nodes};
use super::kernels::{node_block, row_q};
use super::runtime::Model;
use super::sink::Sink;
use crate::math::Vec3;

/// Preallocated workspace of the projection (sized once for the model; not part of a snapshot).
#[derive(Clone, Debug)]
pub(crate) struct ProjWork {
    /// Tree blocks (one per body; `6 +` rows of its tree joint).
    blocks: Vec<Block>,
    /// Border of the loop-closing joints (empty for a tree).
    border: Border,
    /// Dense KKT matrix (test oracle `Model::dense` only), row-major `nd × nd`,
    /// `nd = 6 N + active rows`.
    dense: Vec<f64>,
    /// Dense pivots.
    dpiv: Vec<usize>,
    /// Dense right-hand side / solution.
    drhs: Vec<f64>,
    /// Projected velocities `v'` (12 per body, layout of `v`), world frame, m/s and 1/s.
    pub vp: Vec<f64>,
}

impl ProjWork {
    /// Workspace for `model`.
    pub fn new(model: &Model) -> Self {
        let nb = model.bodies.len();
        // every block factored whole: the body block `diag(m I, J_s)` plus the children's
        // updates is ill-conditioned below a light body (singular for a massless one) while
        // the supernode is not, and eliminating through it would cost accuracy ∝ 1/mass
        let blocks = model.tree_blocks(|_| true);
        let nd = if model.dense { 6 * nb + model.nrows } else { 0 };
        Self {
            blocks,
            border: model.border(),
            dense: vec![0.0; nd * nd],
            dpiv: vec![0; nd],
            drhs: vec![0.0; nd],
            vp: model.v0.clone(),
        }
    }
}

/// Computes `pw.vp`, the M-orthogonal projection of `v` onto the admissible velocities at `q`
/// (both 12 per body, world frame). One linear solve, no allocation. Returns false (and leaves
/// `pw.vp = v`) if the KKT matrix is singular, which cannot happen for a regular model.
pub(crate) fn project_velocities(model: &Model, q: &[f64], v: &[f64], pw: &mut ProjWork) -> bool {
    let nb = model.bodies.len();
    let dense = model.dense;
    let nd = pw.drhs.len();
    if dense {
        pw.dense.fill(0.0);
    } else {
        for b in &mut pw.blocks {
            b.clear();
        }
        pw.border.clear();
    }
    let mut sink = Sink {
        model,
        blocks: &mut pw.blocks,
        border: &mut pw.border,
        dense: &mut pw.dense,
        drhs: &mut pw.drhs,
        nd,
    };
    // body blocks PᵀMP and right-hand sides PᵀMv
    for (b, br) in model.bodies.iter().enumerate() {
        let qb = body_nodes(q, b);
        let vb = body_nodes(v, b);
        let d = [qb[1], qb[2], qb[3]];
        let mut c = [0.0; 16];
        c[0] = br.mass;
        for i in 0..3 {
            for j in 0..3 {
                c[4 * (i + 1) + j + 1] = br.e[(i, j)];
            }
        }
        let mut blk = [0.0; 36];
        node_block(&c, &d, &d, &mut blk);
        sink.body_body(b, b, &blk);
        let mut l = Vec3::zeros();
        for i in 0..3 {
            let pi = vb[1] * br.e[(i, 0)] + vb[2] * br.e[(i, 1)] + vb[3] * br.e[(i, 2)];
            l += d[i].cross(&pi);
        }
        let rhs = [
            br.mass * vb[0].x,
            br.mass * vb[0].y,
            br.mass * vb[0].z,
            l.x,
            l.y,
            l.z,
        ];
        if dense {
            sink.drhs[6 * b..6 * b + 6].copy_from_slice(&rhs);
        } else {
            sink.blocks[b].r[..6].copy_from_slice(&rhs);
        }
    }
    if dense {
        sink.drhs[6 * nb..].fill(0.0);
    }
    // joint rows G P (active rows only) and their transposes
    let zero: Nodes = [Vec3::zeros(); 4];
    let mut grad = [Vec3::zeros(); 8];
    for (j, jt) in model.joints.iter().enumerate() {
        let qa = jt.parent.map_or(zero, |a| body_nodes(q, a));
        let qb = body_nodes(q, jt.child);
        let da = [qa[1], qa[2], qa[3]];
        let db = [qb[1], qb[2], qb[3]];
        for (k, row) in jt.rows.iter().enumerate() {
            row.gradient(&qa, &qb, &mut grad);
            let gb = row_q(&grad[4..], &db);
            sink.mu_body(j, k, jt.child, &gb);
            sink.body_mu(jt.child, j, k, &gb);
            if let Some(a) = jt.parent {
                let ga = row_q(&grad[..4], &da);
                sink.mu_body(j, k, a, &ga);
                sink.body_mu(a, j, k, &ga);
            }
        }
    }
    // coupling rows q̇_b − r q̇_a: ṫ = (c ∇s − s ∇c)·v/(s² + c²) of a turn, ∇s·v of a slide
    let nj = model.joints.len();
    for (c, cp) in model.couplings.iter().enumerate() {
        for (j, w) in [(cp.b, 1.0), (cp.a, -cp.ratio)] {
            let jt = &model.joints[j];
            let qa = jt.parent.map_or(zero, |a| body_nodes(q, a));
            let qb = body_nodes(q, jt.child);
            let da = [qa[1], qa[2], qa[3]];
            let db = [qb[1], qb[2], qb[3]];
            let rate = jt.dofs[0].rate_gradient(&qa, &qb).map(|g| g * w);
            let gb = row_q(&rate[4..], &db);
            sink.mu_body(nj + c, 0, jt.child, &gb);
            sink.body_mu(jt.child, nj + c, 0, &gb);
            if let Some(a) = jt.parent {
                let ga = row_q(&rate[..4], &da);
                sink.mu_body(nj + c, 0, a, &ga);
                sink.body_mu(a, nj + c, 0, &ga);
            }
        }
    }
    let ok = if dense {
        lu_factor(&mut pw.dense, nd, nd, &mut pw.dpiv, 1e-14) && {
            lu_solve(&pw.dense, nd, nd, &pw.dpiv, &mut pw.drhs);
            true
        }
    } else if pw.border.is_active() {
        pw.border
            .factor_solve(&mut pw.blocks, &model.order, &model.parent)
    } else {
        solve_tree(&mut pw.blocks, &model.order, &model.parent)
    };
    let ok = ok && {
        // v' = P t: φ̇' = t_φ, ḋᵢ' = ω × dᵢ
        for b in 0..nb {
            let t: [f64; 6] = if dense {
                std::array::from_fn(|k| pw.drhs[6 * b + k])
            } else {
                std::array::from_fn(|k| pw.blocks[b].r[k])
            };
            let w = Vec3::new(t[3], t[4], t[5]);
            let o = 12 * b;
            pw.vp[o..o + 3].copy_from_slice(&t[..3]);
            for i in 0..3 {
                let di = Vec3::new(q[o + 3 + 3 * i], q[o + 4 + 3 * i], q[o + 5 + 3 * i]);
                pw.vp[o + 3 + 3 * i..o + 6 + 3 * i].copy_from_slice(w.cross(&di).as_slice());
            }
        }
        pw.vp.iter().all(|x| x.is_finite())
    };
    if !ok {
        pw.vp.copy_from_slice(v);
    }
    ok
}
