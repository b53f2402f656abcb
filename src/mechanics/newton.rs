//! Residual and analytic Jacobian of one energy–momentum step, and the Newton iteration.
//!
//! Unknowns per iteration: per body `x_b = (δφ, δθ)` with `φ ← φ + δφ`, `dᵢ ← exp(δθ̂) dᵢ`
//! (orthonormality holds identically), per active joint row the scaled multiplier
//! `μ = h² λ / 2`. Residuals (theory.md §4.4–4.5, scaled by `h²/2`):
//!
//! ```text
//! R̃ = M (q − qₙ − h vₙ) − (h²/2) F(q̄) + Σ_k μ_k ∇g_k(q̄)      (12 per body, node form)
//! r_b = [R̃_φ ; Σᵢ d̄ᵢ × R̃_{dᵢ}] − (h²/2) [0 ; m_b]            (6 per body, P_int(q̄)ᵀ R̃)
//! g_k(q) = 0                                                   (per active row)
//! ```
//!
//! with consistent torques `m_b` entering the projected moment row directly (for any basis
//! `Σᵢ d̄ᵢ × ½ m × d̄ⁱ = m`). Jacobian: `P(q̄)ᵀ K̃ Q + ½ Σᵢ hat(R̃_{dᵢ}) hat(dᵢ)` with
//! `K̃ = M + ½ Σ μ_k H_k − (h²/2) ∂F/∂q`, multiplier columns `P(q̄)ᵀ ∇g(q̄)`, joint rows
//! `∇g(q) Q`, `Q = [I 0; 0 −d̂₁; 0 −d̂₂; 0 −d̂₃]`.

use super::assemble::{read3, write3};
use super::constraint::{nodes, DotRow, Nodes};
use super::model::{DofRt, Model};
use super::solver::{lu_factor, lu_solve, solve_tree, Block, NMAX};
use crate::math::{skew, Mat3, Vec3};

/// Preallocated Newton workspace (all sized at `State::new`).
#[derive(Clone, Debug)]
pub(crate) struct Work {
    /// Stage start: coordinates, velocities (12 per body).
    pub qn: Vec<f64>,
    /// Stage start velocities (high part).
    pub vn: Vec<f64>,
    /// Stage start velocities, low part: `vn + vlo` carries the velocity in double-double so
    /// that the recursion `v_{n+1} = v_n + 2a/h` accumulates no rounding (energy drift).
    pub vlo: Vec<f64>,
    /// `a = (q − qₙ) − h vₙ` of the last evaluation (12 per body).
    pub acc: Vec<f64>,
    /// Multiplier memory `λ/2` per active row (warm start `μ = h² λ/2`).
    pub lam: Vec<f64>,
    /// Unwrapped turn angles at the stage start, rad.
    pub ang: Vec<f64>,
    /// Accumulated work at the stage start, J.
    pub work: f64,
    /// Newton iterate.
    pub q: Vec<f64>,
    /// Increment `q − qₙ`, kept separately so that velocities do not suffer the cancellation
    /// of large positions.
    pub dq: Vec<f64>,
    /// Midpoint `½(qₙ + q)`.
    pub qbar: Vec<f64>,
    /// Node residual `R̃` (12 per body).
    pub rn: Vec<f64>,
    /// Scaled multipliers.
    pub mu: Vec<f64>,
    /// Unwrapped turn angles at the iterate.
    pub ang1: Vec<f64>,
    /// Discrete rotation increments `θ_b = ½ Σ d̄ⁱ × (dᵢ − dᵢₙ)` (3 per body).
    pub theta: Vec<f64>,
    /// Scaled joint torques on the projected moment rows (3 per body).
    pub mom: Vec<f64>,
    /// Per-body 4 × 4 node coupling `C` (mass + ½ Σ μ S on the diagonal).
    pub cbody: Vec<[f64; 16]>,
    /// Per-body extra 6 × 6 diagonal Jacobian terms.
    pub xbody: Vec<[f64; 36]>,
    /// Tree blocks (one per body).
    pub blocks: Vec<Block>,
    /// Dense matrix (loop systems), row-major `n × n`.
    pub dense: Vec<f64>,
    /// Dense pivots.
    pub dpiv: Vec<usize>,
    /// Dense right-hand side / solution.
    pub drhs: Vec<f64>,
}

impl Work {
    /// Workspace for `model`.
    pub fn new(model: &Model) -> Self {
        let nb = model.bodies.len();
        let nr = model.nrows;
        let blocks = (0..nb)
            .map(|b| Block::new(6 + model.tree_joint[b].map_or(0, |j| model.joints[j].rows.len())))
            .collect();
        let nd = if model.dense { 6 * nb + nr } else { 0 };
        Self {
            qn: model.q0.clone(),
            vn: model.v0.clone(),
            vlo: vec![0.0; 12 * nb],
            acc: vec![0.0; 12 * nb],
            lam: vec![0.0; nr],
            ang: model.angles0.clone(),
            work: 0.0,
            q: model.q0.clone(),
            dq: vec![0.0; 12 * nb],
            qbar: model.q0.clone(),
            rn: vec![0.0; 12 * nb],
            mu: vec![0.0; nr],
            ang1: model.angles0.clone(),
            theta: vec![0.0; 3 * nb],
            mom: vec![0.0; 3 * nb],
            cbody: vec![[0.0; 16]; nb],
            xbody: vec![[0.0; 36]; nb],
            blocks,
            dense: vec![0.0; nd * nd],
            dpiv: vec![0; nd],
            drhs: vec![0.0; nd],
        }
    }
}

/// Loads and parameters held over a step.
pub(crate) struct Held<'a> {
    /// Input values in `Model::inputs` order.
    pub inputs: &'a [f64],
    /// Per-joint damping.
    pub damping: &'a [f64],
    /// Per-joint stiffness.
    pub stiffness: &'a [f64],
}

/// Nodes of body `b` of the flat vector `x`.
#[inline]
pub(crate) fn body_nodes(x: &[f64], b: usize) -> Nodes {
    nodes(&x[12 * b..12 * b + 12])
}

/// Reciprocal basis `dⁱ` of `d₁, d₂, d₃`.
#[inline]
pub(crate) fn reciprocal(d: &[Vec3; 3]) -> [Vec3; 3] {
    let det = d[0].dot(&d[1].cross(&d[2]));
    let s = 1.0 / det;
    [
        d[1].cross(&d[2]) * s,
        d[2].cross(&d[0]) * s,
        d[0].cross(&d[1]) * s,
    ]
}

/// `θ = ½ Σᵢ d̄ⁱ × (dᵢ − dᵢₙ)` for body nodes at the start `n` and the iterate `q`.
#[inline]
pub(crate) fn rotation_increment(n: &Nodes, q: &Nodes) -> Vec3 {
    let dbar = [
        (n[1] + q[1]) * 0.5,
        (n[2] + q[2]) * 0.5,
        (n[3] + q[3]) * 0.5,
    ];
    let rec = reciprocal(&dbar);
    let mut t = Vec3::zeros();
    for i in 0..3 {
        t += rec[i].cross(&(q[i + 1] - n[i + 1]));
    }
    t * 0.5
}

/// The 6 × 6 block `P̄_aᵀ (C ⊗ I) Q_b` (row body `a` with midpoint directors `dbar`, column
/// body `b` with iterate directors `d`), added to `out` (row-major).
fn node_block(c: &[f64; 16], dbar: &[Vec3; 3], d: &[Vec3; 3], out: &mut [f64; 36]) {
    let hd: [Mat3; 3] = std::array::from_fn(|j| skew(&d[j]));
    let hb: [Mat3; 3] = std::array::from_fn(|i| skew(&dbar[i]));
    let mut pt = Mat3::zeros();
    let mut mp = Mat3::zeros();
    let mut mt = Mat3::zeros();
    for j in 0..3 {
        pt -= hd[j] * c[j + 1];
    }
    for i in 0..3 {
        mp += hb[i] * c[4 * (i + 1)];
        let mut row = Mat3::zeros();
        for j in 0..3 {
            row += hd[j] * c[4 * (i + 1) + j + 1];
        }
        mt -= hb[i] * row;
    }
    for r in 0..3 {
        out[r * 6 + r] += c[0];
        for s in 0..3 {
            out[r * 6 + 3 + s] += pt[(r, s)];
            out[(r + 3) * 6 + s] += mp[(r, s)];
            out[(r + 3) * 6 + 3 + s] += mt[(r, s)];
        }
    }
}

/// `P̄ᵀ` applied to one body's node vectors: `[f_φ ; Σ d̄ᵢ × f_{dᵢ}]`.
#[inline]
fn project(f: &[Vec3], dbar: &[Vec3; 3]) -> [f64; 6] {
    let m = dbar[0].cross(&f[1]) + dbar[1].cross(&f[2]) + dbar[2].cross(&f[3]);
    [f[0].x, f[0].y, f[0].z, m.x, m.y, m.z]
}

/// Row vector `∇g · Q` of one body: `[∇_φ ; Σ dᵢ × ∇_{dᵢ}]`.
#[inline]
fn row_q(f: &[Vec3], d: &[Vec3; 3]) -> [f64; 6] {
    project(f, d)
}

/// `∂(LinVec at q̄)/∂x` for the A or B coefficients `k`: 3 × 6 (row-major) `½[k₀ I, −Σ kᵢ hat(dᵢ)]`.
fn linvec_jac(k: &[f64; 4], d: &[Vec3; 3]) -> [f64; 18] {
    let mut out = [0.0; 18];
    let mut m = Mat3::zeros();
    for i in 0..3 {
        m -= skew(&d[i]) * k[i + 1];
    }
    for r in 0..3 {
        out[r * 6 + r] = 0.5 * k[0];
        for s in 0..3 {
            out[r * 6 + 3 + s] = 0.5 * m[(r, s)];
        }
    }
    out
}

/// Where the Jacobian goes: the tree blocks or the dense matrix.
struct Sink<'a> {
    model: &'a Model,
    blocks: &'a mut [Block],
    dense: &'a mut [f64],
    nd: usize,
}

impl Sink<'_> {
    /// Adds the 6 × 6 block (rows of body `a`, columns `x_b`).
    fn body_body(&mut self, a: usize, b: usize, blk: &[f64; 36]) {
        if self.model.dense {
            let nd = self.nd;
            for r in 0..6 {
                for s in 0..6 {
                    self.dense[(6 * a + r) * nd + 6 * b + s] += blk[r * 6 + s];
                }
            }
        } else if a == b {
            let d = &mut self.blocks[a].d;
            for r in 0..6 {
                for s in 0..6 {
                    d[r * NMAX + s] += blk[r * 6 + s];
                }
            }
        } else if self.model.parent[b] == Some(a) {
            let l = &mut self.blocks[b].l;
            for r in 0..6 {
                for s in 0..6 {
                    l[r * NMAX + s] += blk[r * 6 + s];
                }
            }
        } else if self.model.parent[a] == Some(b) {
            let u = &mut self.blocks[a].u;
            for r in 0..6 {
                for s in 0..6 {
                    u[r * 6 + s] += blk[r * 6 + s];
                }
            }
        }
    }

    /// Adds column `col` (6 body rows of `a`) for multiplier `k` of joint `j`.
    fn body_mu(&mut self, a: usize, j: usize, k: usize, col: &[f64; 6]) {
        let jt = &self.model.joints[j];
        if self.model.dense {
            let nd = self.nd;
            let c = 6 * self.model.bodies.len() + jt.row0 + k;
            for r in 0..6 {
                self.dense[(6 * a + r) * nd + c] += col[r];
            }
        } else if a == jt.child {
            let d = &mut self.blocks[a].d;
            for r in 0..6 {
                d[r * NMAX + 6 + k] += col[r];
            }
        } else {
            let l = &mut self.blocks[jt.child].l;
            for r in 0..6 {
                l[r * NMAX + 6 + k] += col[r];
            }
        }
    }

    /// Adds row `k` of joint `j` against `x_b`.
    fn mu_body(&mut self, j: usize, k: usize, b: usize, row: &[f64; 6]) {
        let jt = &self.model.joints[j];
        if self.model.dense {
            let nd = self.nd;
            let r = 6 * self.model.bodies.len() + jt.row0 + k;
            for s in 0..6 {
                self.dense[r * nd + 6 * b + s] += row[s];
            }
        } else if b == jt.child {
            let d = &mut self.blocks[b].d;
            for s in 0..6 {
                d[(6 + k) * NMAX + s] += row[s];
            }
        } else {
            let u = &mut self.blocks[jt.child].u;
            for s in 0..6 {
                u[(6 + k) * 6 + s] += row[s];
            }
        }
    }
}

/// Residual norms of an evaluation.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Norms {
    /// Scaled residual (max norm).
    pub res: f64,
}

/// Evaluates the residual at the iterate `ws.q` (and, if `jac`, the Jacobian) into the sink;
/// the right-hand side stored is `−r`. Also returns the step's discrete work in `work_out`.
#[allow(clippy::too_many_lines)]
pub(crate) fn evaluate(
    model: &Model,
    ws: &mut Work,
    held: &Held,
    h: f64,
    jac: bool,
    work_out: &mut f64,
) -> Norms {
    let nb = model.bodies.len();
    let hh = 0.5 * h * h;
    let g = model.def().gravity;
    let mut work = 0.0;
    for k in 0..ws.q.len() {
        ws.qbar[k] = ws.qn[k] + 0.5 * ws.dq[k];
    }
    if jac {
        if model.dense {
            ws.dense.fill(0.0);
            ws.drhs.fill(0.0);
        } else {
            for b in &mut ws.blocks {
                b.clear();
            }
        }
    }
    // body inertia and applied forces, node form
    for b in 0..nb {
        let br = &model.bodies[b];
        let qn = body_nodes(&ws.qn, b);
        let q = body_nodes(&ws.q, b);
        // a = Δq − h vₙ with one rounding (fused multiply-add) plus the low part of vₙ
        for k in 12 * b..12 * b + 12 {
            ws.acc[k] = (-h).mul_add(ws.vn[k], ws.dq[k]) - h * ws.vlo[k];
        }
        let dq = body_nodes(&ws.acc, b);
        let mut r = [Vec3::zeros(); 4];
        r[0] = dq[0] * br.mass - g * (hh * br.mass);
        for i in 0..3 {
            r[i + 1] = dq[1] * br.e[(i, 0)] + dq[2] * br.e[(i, 1)] + dq[3] * br.e[(i, 2)];
        }
        for k in 0..4 {
            write3(&mut ws.rn, 12 * b + 3 * k, &r[k]);
        }
        let th = rotation_increment(&qn, &q);
        write3(&mut ws.theta, 3 * b, &th);
        let c = &mut ws.cbody[b];
        c.fill(0.0);
        c[0] = br.mass;
        for i in 0..3 {
            for j in 0..3 {
                c[4 * (i + 1) + j + 1] = br.e[(i, j)];
            }
        }
        ws.xbody[b].fill(0.0);
        write3(&mut ws.mom, 3 * b, &Vec3::zeros());
    }
    for &(b, at) in &model.body_forces {
        let f = Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]);
        let r = read3(&ws.rn, 12 * b) - f * hh;
        write3(&mut ws.rn, 12 * b, &r);
        work += f.dot(&read3(&ws.dq, 12 * b));
    }
    // joint rows: μ ∇g(q̄) into R̃, g(q) residual, Jacobian columns/rows and node couplings
    let mut res = 0.0_f64;
    let gscale = 1.0 / model.lc.min(1.0);
    let zero: Nodes = [Vec3::zeros(); 4];
    let mut sink_dense = std::mem::take(&mut ws.dense);
    let mut sink_blocks = std::mem::take(&mut ws.blocks);
    let nd = ws.drhs.len();
    {
        let mut sink = Sink {
            model,
            blocks: &mut sink_blocks,
            dense: &mut sink_dense,
            nd,
        };
        for (j, jt) in model.joints.iter().enumerate() {
            let a = jt.parent;
            let bb = jt.child;
            let qa_bar = a.map_or(zero, |a| body_nodes(&ws.qbar, a));
            let qb_bar = body_nodes(&ws.qbar, bb);
            let qa = a.map_or(zero, |a| body_nodes(&ws.q, a));
            let qb = body_nodes(&ws.q, bb);
            let qa_n = a.map_or(zero, |a| body_nodes(&ws.qn, a));
            let qb_n = body_nodes(&ws.qn, bb);
            let dbar_a = [qa_bar[1], qa_bar[2], qa_bar[3]];
            let dbar_b = [qb_bar[1], qb_bar[2], qb_bar[3]];
            let d_a = [qa[1], qa[2], qa[3]];
            let d_b = [qb[1], qb[2], qb[3]];
            // off-diagonal node coupling C_AB and extra blocks for this joint
            let mut cab = [0.0; 16];
            let mut x_ab = [0.0; 36];
            let mut x_ba = [0.0; 36];
            let mut x_aa = [0.0; 36];
            let mut x_bb = [0.0; 36];
            let mut grad = [Vec3::zeros(); 8];
            let mut add_row = |row: &DotRow,
                               coef: f64,
                               rn: &mut [f64],
                               cb: &mut [[f64; 16]],
                               cab: &mut [f64; 16]| {
                row.gradient(&qa_bar, &qb_bar, &mut grad);
                if let Some(a) = a {
                    for k in 0..4 {
                        let v = read3(rn, 12 * a + 3 * k) + grad[k] * coef;
                        write3(rn, 12 * a + 3 * k, &v);
                    }
                }
                for k in 0..4 {
                    let v = read3(rn, 12 * bb + 3 * k) + grad[4 + k] * coef;
                    write3(rn, 12 * bb + 3 * k, &v);
                }
                if jac {
                    let s = row.hessian();
                    let hc = 0.5 * coef;
                    for n in 0..4 {
                        for m in 0..4 {
                            cb[bb][4 * n + m] += hc * s[4 + n][4 + m];
                            if let Some(a) = a {
                                cb[a][4 * n + m] += hc * s[n][m];
                                cab[4 * n + m] += hc * s[n][4 + m];
                            }
                        }
                    }
                }
                grad
            };
            for (k, row) in jt.rows.iter().enumerate() {
                let mu = ws.mu[jt.row0 + k];
                let grad = add_row(row, mu, &mut ws.rn, &mut ws.cbody, &mut cab);
                let gv = row.eval(&qa, &qb);
                res = res.max(gv.abs() * gscale);
                if model.dense {
                    ws.drhs[6 * nb + jt.row0 + k] = -gv;
                } else {
                    sink.blocks[bb].r[6 + k] = -gv;
                }
                if jac {
                    // multiplier columns P̄ᵀ∇g(q̄)
                    sink.body_mu(bb, j, k, &project(&grad[4..], &dbar_b));
                    if let Some(a) = a {
                        sink.body_mu(a, j, k, &project(&grad[..4], &dbar_a));
                    }
                    // joint rows ∇g(q) Q
                    let mut g1 = [Vec3::zeros(); 8];
                    row.gradient(&qa, &qb, &mut g1);
                    sink.mu_body(j, k, bb, &row_q(&g1[4..], &d_b));
                    if let Some(a) = a {
                        sink.mu_body(j, k, a, &row_q(&g1[..4], &d_a));
                    }
                }
            }
            // joint loads on the coordinates
            let c_d = held.damping[j];
            let k_s = held.stiffness[j];
            let mut turn = jt.turn0;
            let mut sph_t = Vec3::zeros();
            for (dk, dof) in jt.dofs.iter().enumerate() {
                let act = jt
                    .input
                    .map_or(0.0, |i| actuator_input(model, j, dk, held.inputs, i));
                match dof {
                    DofRt::Slide(row) => {
                        let s0 = row.eval(&qa_n, &qb_n);
                        let s1 = row.eval(&qa, &qb);
                        let ds = s1 - s0;
                        let coef = act - 0.5 * k_s * (s0 + s1) - c_d * ds / h;
                        work += act * ds - c_d * ds * ds / h;
                        let grad = add_row(row, -hh * coef, &mut ws.rn, &mut ws.cbody, &mut cab);
                        if jac && (k_s != 0.0 || c_d != 0.0) {
                            // rank-one term d(−hh·coef)/dx = hh (k/2 + c/h) ∇s(q) Q
                            let kap = hh * (0.5 * k_s + c_d / h);
                            let mut g1 = [Vec3::zeros(); 8];
                            row.gradient(&qa, &qb, &mut g1);
                            let cb_ = project(&grad[4..], &dbar_b);
                            let rb_ = row_q(&g1[4..], &d_b);
                            outer(&mut x_bb, kap, &cb_, &rb_);
                            if a.is_some() {
                                let ca_ = project(&grad[..4], &dbar_a);
                                let ra_ = row_q(&g1[..4], &d_a);
                                outer(&mut x_aa, kap, &ca_, &ra_);
                                outer(&mut x_ab, kap, &ca_, &rb_);
                                outer(&mut x_ba, kap, &cb_, &ra_);
                            }
                        }
                    }
                    DofRt::Turn(n) => {
                        let nbar = n.eval(&qa_bar, &qb_bar);
                        let th_b = read3(&ws.theta, 3 * bb);
                        let th_a = a.map_or(Vec3::zeros(), |a| read3(&ws.theta, 3 * a));
                        let delta = nbar.dot(&(th_b - th_a));
                        let raw = super::assemble::turn_angle(model, j, dk, &qa, &qb);
                        let t0 = ws.ang[turn];
                        let t1 = super::assemble::unwrap(t0, raw);
                        ws.ang1[turn] = t1;
                        let spring = if delta.abs() > 1e-13 * (1.0 + t0.abs() + t1.abs()) {
                            -0.5 * k_s * (t1 * t1 - t0 * t0) / delta
                        } else {
                            -0.5 * k_s * (t0 + t1)
                        };
                        let tau = act + spring - c_d * delta / h;
                        work += act * delta - c_d * delta * delta / h;
                        turn += 1;
                        push_torque(&mut ws.mom, bb, a, &(nbar * (hh * tau)));
                        if jac {
                            let ka = n.a;
                            let kb = n.b;
                            let jb = linvec_jac(&kb, &d_b);
                            let ja = linvec_jac(&ka, &d_a);
                            let kap = hh * (0.5 * k_s + c_d / h);
                            torque_jac(
                                &mut x_bb,
                                &mut x_ba,
                                &mut x_ab,
                                &mut x_aa,
                                hh * tau,
                                &jb,
                                &ja,
                                a.is_some(),
                            );
                            nn_terms(
                                &mut x_bb,
                                &mut x_ba,
                                &mut x_ab,
                                &mut x_aa,
                                kap,
                                &nbar,
                                a.is_some(),
                            );
                        }
                    }
                }
            }
            if let Some(axes) = &jt.sph_axes {
                let th_b = read3(&ws.theta, 3 * bb);
                let th_a = a.map_or(Vec3::zeros(), |a| read3(&ws.theta, 3 * a));
                let rel = th_b - th_a;
                let mut tv = -rel * (c_d / h);
                work -= c_d * rel.norm_squared() / h;
                for (k, ax) in axes.iter().enumerate() {
                    let act = jt.input.map_or(0.0, |i| held.inputs[i + k]);
                    if act != 0.0 {
                        let abar = ax.eval(&qa_bar, &qb_bar);
                        tv += abar * act;
                        work += act * abar.dot(&rel);
                        if jac {
                            let jb = linvec_jac(&ax.b, &d_b);
                            let ja = linvec_jac(&ax.a, &d_a);
                            torque_jac(
                                &mut x_bb,
                                &mut x_ba,
                                &mut x_ab,
                                &mut x_aa,
                                hh * act,
                                &jb,
                                &ja,
                                a.is_some(),
                            );
                        }
                    }
                }
                sph_t += tv;
                push_torque(&mut ws.mom, bb, a, &(sph_t * hh));
                if jac && c_d != 0.0 {
                    let kap = hh * c_d / h;
                    for r in 0..3 {
                        x_bb[(r + 3) * 6 + 3 + r] += kap;
                        if a.is_some() {
                            x_aa[(r + 3) * 6 + 3 + r] += kap;
                            x_ab[(r + 3) * 6 + 3 + r] -= kap;
                            x_ba[(r + 3) * 6 + 3 + r] -= kap;
                        }
                    }
                }
            }
            if jac {
                for r in 0..36 {
                    ws.xbody[bb][r] += x_bb[r];
                }
                if let Some(a) = a {
                    for r in 0..36 {
                        ws.xbody[a][r] += x_aa[r];
                    }
                    let mut blk = x_ab;
                    node_block(&cab, &dbar_a, &d_b, &mut blk);
                    sink.body_body(a, bb, &blk);
                    let mut cba = [0.0; 16];
                    for n in 0..4 {
                        for m in 0..4 {
                            cba[4 * n + m] = cab[4 * m + n];
                        }
                    }
                    let mut blk = x_ba;
                    node_block(&cba, &dbar_b, &d_a, &mut blk);
                    sink.body_body(bb, a, &blk);
                }
            }
        }
    }
    ws.dense = sink_dense;
    ws.blocks = sink_blocks;
    // projection, body torques, diagonal blocks
    for b in 0..nb {
        let br = &model.bodies[b];
        let qbar = body_nodes(&ws.qbar, b);
        let dbar = [qbar[1], qbar[2], qbar[3]];
        let rnode: [Vec3; 4] = std::array::from_fn(|k| read3(&ws.rn, 12 * b + 3 * k));
        let mut r = project(&rnode, &dbar);
        for k in 0..3 {
            r[3 + k] += ws.mom[3 * b + k];
        }
        for &(tb, at) in &model.body_torques {
            if tb != b {
                continue;
            }
            let m = Vec3::new(held.inputs[at], held.inputs[at + 1], held.inputs[at + 2]);
            let applied = if model.naive_torque {
                let mut c = Mat3::zeros();
                for d in &dbar {
                    c += d * d.transpose();
                }
                (Mat3::identity() * c.trace() - c) * m * 0.5
            } else {
                m
            };
            for k in 0..3 {
                r[3 + k] -= hh * applied[k];
            }
            work += m.dot(&read3(&ws.theta, 3 * b));
        }
        let fs = 1.0 / (br.mass * model.lc);
        let ms = 1.0 / (br.e.trace().abs() + 0.5 * br.e.norm());
        for k in 0..3 {
            res = res.max((r[k] * fs).abs()).max((r[3 + k] * ms).abs());
        }
        if model.dense {
            for k in 0..6 {
                ws.drhs[6 * b + k] = -r[k];
            }
        } else {
            for k in 0..6 {
                ws.blocks[b].r[k] = -r[k];
            }
        }
        if jac {
            let q = body_nodes(&ws.q, b);
            let d = [q[1], q[2], q[3]];
            let mut blk = ws.xbody[b];
            node_block(&ws.cbody[b], &dbar, &d, &mut blk);
            // derivative of the projection: ½ Σ hat(R̃_{dᵢ}) hat(dᵢ)
            let mut pm = Mat3::zeros();
            for i in 0..3 {
                pm += skew(&rnode[i + 1]) * skew(&d[i]);
            }
            for rr in 0..3 {
                for s in 0..3 {
                    blk[(rr + 3) * 6 + 3 + s] += 0.5 * pm[(rr, s)];
                }
            }
            let mut sink = Sink {
                model,
                blocks: &mut ws.blocks,
                dense: &mut ws.dense,
                nd,
            };
            sink.body_body(b, b, &blk);
        }
    }
    *work_out = work;
    Norms { res }
}

/// Value of the actuator input driving dof `dk` of joint `j` (inputs start at `first`).
fn actuator_input(model: &Model, j: usize, dk: usize, inputs: &[f64], first: usize) -> f64 {
    let _ = (model, j);
    inputs.get(first + dk).copied().unwrap_or(0.0)
}

/// Adds the scaled joint torque `t` (already times `h²/2`) to the projected moment rows:
/// `−t` on the child, `+t` on the parent. Consistent director forces `½ t × d̄ⁱ` project to
/// exactly `t` for any basis, so the pair enters the moment rows directly.
fn push_torque(mom: &mut [f64], child: usize, parent: Option<usize>, t: &Vec3) {
    let v = read3(mom, 3 * child) - t;
    write3(mom, 3 * child, &v);
    if let Some(a) = parent {
        let v = read3(mom, 3 * a) + t;
        write3(mom, 3 * a, &v);
    }
}

/// `out += s · col ⊗ row` (6 × 6).
fn outer(out: &mut [f64; 36], s: f64, col: &[f64; 6], row: &[f64; 6]) {
    for r in 0..6 {
        for c in 0..6 {
            out[r * 6 + c] += s * col[r] * row[c];
        }
    }
}

/// Jacobian of the moments `−t n̄` (child) and `+t n̄` (parent) through `n̄(q̄)`, `t = hh·τ`.
#[allow(clippy::too_many_arguments)]
fn torque_jac(
    x_bb: &mut [f64; 36],
    x_ba: &mut [f64; 36],
    x_ab: &mut [f64; 36],
    x_aa: &mut [f64; 36],
    t: f64,
    jb: &[f64; 18],
    ja: &[f64; 18],
    has_a: bool,
) {
    for r in 0..3 {
        for c in 0..6 {
            x_bb[(r + 3) * 6 + c] -= t * jb[r * 6 + c];
            if has_a {
                x_ba[(r + 3) * 6 + c] -= t * ja[r * 6 + c];
                x_ab[(r + 3) * 6 + c] += t * jb[r * 6 + c];
                x_aa[(r + 3) * 6 + c] += t * ja[r * 6 + c];
            }
        }
    }
}

/// Jacobian of `∓hh τ n̄` through `dτ ≈ −κ n̄·(δθᴮ − δθᴬ)`, `kap = hh κ`.
fn nn_terms(
    x_bb: &mut [f64; 36],
    x_ba: &mut [f64; 36],
    x_ab: &mut [f64; 36],
    x_aa: &mut [f64; 36],
    kap: f64,
    n: &Vec3,
    has_a: bool,
) {
    if kap == 0.0 {
        return;
    }
    for r in 0..3 {
        for c in 0..3 {
            let v = kap * n[r] * n[c];
            x_bb[(r + 3) * 6 + 3 + c] += v;
            if has_a {
                x_ba[(r + 3) * 6 + 3 + c] -= v;
                x_ab[(r + 3) * 6 + 3 + c] -= v;
                x_aa[(r + 3) * 6 + 3 + c] += v;
            }
        }
    }
}

/// `exp(θ̂) − I = s θ̂ + c θ̂²` without the cancellation of subtracting `I`
/// (`c = 2 sin²(|θ|/2)/|θ|²`), so that director increments stay accurate to round-off.
#[must_use]
pub(crate) fn expm1_so3(theta: &Vec3) -> Mat3 {
    let a2 = theta.norm_squared();
    let k = skew(theta);
    let (s, c) = if a2 < 1e-8 {
        (
            1.0 - a2 / 6.0 * (1.0 - a2 / 20.0),
            0.5 - a2 / 24.0 * (1.0 - a2 / 30.0),
        )
    } else {
        let a = a2.sqrt();
        let sh = (0.5 * a).sin();
        (a.sin() / a, 2.0 * sh * sh / a2)
    };
    k * s + k * k * c
}

/// Solves the assembled linear system; the solution replaces the right-hand side.
pub(crate) fn solve(model: &Model, ws: &mut Work) -> bool {
    if model.dense {
        let n = ws.drhs.len();
        if !lu_factor(&mut ws.dense, n, n, &mut ws.dpiv, 1e-14) {
            return false;
        }
        lu_solve(&ws.dense, n, n, &ws.dpiv, &mut ws.drhs);
        true
    } else {
        solve_tree(&mut ws.blocks, &model.order, &model.parent)
    }
}

/// Applies the Newton update; returns the scaled update norm.
pub(crate) fn update(model: &Model, ws: &mut Work) -> f64 {
    let nb = model.bodies.len();
    let mut upd = 0.0_f64;
    for b in 0..nb {
        let x: [f64; 6] = if model.dense {
            std::array::from_fn(|k| ws.drhs[6 * b + k])
        } else {
            std::array::from_fn(|k| ws.blocks[b].r[k])
        };
        let dphi = Vec3::new(x[0], x[1], x[2]);
        let dth = Vec3::new(x[3], x[4], x[5]);
        upd = upd.max(dphi.norm() / model.lc).max(dth.norm());
        let inc = read3(&ws.dq, 12 * b) + dphi;
        write3(&mut ws.dq, 12 * b, &inc);
        write3(&mut ws.q, 12 * b, &(read3(&ws.qn, 12 * b) + inc));
        let em1 = expm1_so3(&dth);
        for i in 0..3 {
            let o = 12 * b + 3 + 3 * i;
            let inc = read3(&ws.dq, o) + em1 * read3(&ws.q, o);
            write3(&mut ws.dq, o, &inc);
            write3(&mut ws.q, o, &(read3(&ws.qn, o) + inc));
        }
    }
    for jt in &model.joints {
        for k in 0..jt.rows.len() {
            let dm = if model.dense {
                ws.drhs[6 * nb + jt.row0 + k]
            } else {
                ws.blocks[jt.child].r[6 + k]
            };
            ws.mu[jt.row0 + k] += dm;
        }
    }
    upd
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::{exp_so3, Mat3};
    use crate::mechanics::def::{
        BodyDef, BodyLoadDef, Frame, FreeBodyInitial, JointDef, JointInitial, JointType, ModelDef,
        SolverSettings,
    };

    fn body(name: &str, m: f64, j: [f64; 3], com: Vec3) -> BodyDef {
        BodyDef {
            name: name.into(),
            mass: m,
            com,
            inertia: Mat3::from_diagonal(&Vec3::new(j[0], j[1], j[2])),
        }
    }

    fn joint(
        kind: JointType,
        parent: Option<usize>,
        child: usize,
        at: Vec3,
        axis: Vec3,
        q: Vec<f64>,
        qd: Vec<f64>,
    ) -> JointDef {
        JointDef {
            name: format!("j{child}"),
            kind,
            parent,
            child,
            parent_frame: Frame {
                translation: at,
                rotation: exp_so3(&Vec3::new(0.1, 0.2, -0.1)),
            },
            child_frame: Frame::identity(),
            axis,
            axis2: Vec3::y(),
            actuated: true,
            damping: 0.0,
            stiffness: 0.0,
            loop_closing: false,
            initial: JointInitial::Coords { q, qd },
        }
    }

    /// A free body carrying a revolute child (motor) and a prismatic grandchild (actuator), with
    /// a spherical-jointed body on the free body, body torque and force loads, gravity.
    fn sample() -> ModelDef {
        ModelDef {
            gravity: Vec3::new(0.0, 0.0, -9.81),
            bodies: vec![
                body("a", 2.0, [0.3, 0.4, 0.5], Vec3::zeros()),
                body("b", 1.5, [0.1, 0.2, 0.25], Vec3::new(0.2, 0.0, 0.1)),
                body("c", 1.0, [0.05, 0.06, 0.07], Vec3::new(0.0, 0.1, 0.0)),
                body("d", 0.7, [0.02, 0.03, 0.04], Vec3::new(0.0, 0.0, 0.2)),
            ],
            joints: vec![
                joint(
                    JointType::Revolute,
                    Some(0),
                    1,
                    Vec3::new(0.3, 0.1, 0.0),
                    Vec3::new(0.0, 0.6, 0.8),
                    vec![0.4],
                    vec![1.5],
                ),
                joint(
                    JointType::Prismatic,
                    Some(1),
                    2,
                    Vec3::new(0.0, 0.2, 0.3),
                    Vec3::x(),
                    vec![0.3],
                    vec![-0.4],
                ),
                JointDef {
                    initial: JointInitial::Spherical {
                        quat: [0.9, 0.1, -0.2, 0.3],
                        w: Vec3::new(0.5, -1.0, 2.0),
                    },
                    ..joint(
                        JointType::Spherical,
                        Some(0),
                        3,
                        Vec3::new(-0.2, 0.0, 0.2),
                        Vec3::z(),
                        vec![],
                        vec![],
                    )
                },
            ],
            loads: vec![BodyLoadDef {
                body: 0,
                torque: true,
                force: true,
            }],
            free_bodies: vec![FreeBodyInitial {
                body: 0,
                position: Vec3::new(0.1, 0.2, 0.3),
                orientation: exp_so3(&Vec3::new(0.3, -0.5, 0.2)),
                velocity: Vec3::new(0.3, -0.1, 0.2),
                angular_velocity: Vec3::new(1.0, -2.0, 0.5),
            }],
        }
    }

    fn residual(model: &Model, ws: &mut Work, held: &Held, h: f64) -> Vec<f64> {
        let mut w = 0.0;
        evaluate(model, ws, held, h, false, &mut w);
        ws.drhs.iter().map(|x| -x).collect()
    }

    /// The analytic Jacobian matches central differences of the residual (loads without
    /// springs/dampers, whose angle terms use a leading-order derivative).
    #[test]
    fn jacobian_matches_finite_differences() {
        let mut model = Model::new(&sample(), SolverSettings::default()).expect("model");
        model.dense = true;
        let mut ws = Work::new(&model);
        let inputs: Vec<f64> = (0..model.inputs().len())
            .map(|k| 0.3 + 0.7 * (k as f64).sin())
            .collect();
        let zeros = vec![0.0; model.def().joints.len()];
        let held = Held {
            inputs: &inputs,
            damping: &zeros,
            stiffness: &zeros,
        };
        let h = 0.05;
        // a nontrivial iterate: predictor-like increments and multipliers
        let nb = model.bodies.len();
        ws.qn.copy_from_slice(&model.q0);
        ws.vn.copy_from_slice(&model.v0);
        ws.q.copy_from_slice(&model.q0);
        ws.dq.fill(0.0);
        ws.drhs.fill(0.0);
        for b in 0..nb {
            for k in 0..6 {
                ws.drhs[6 * b + k] = 0.02 * ((7 * b + k) as f64).cos();
            }
        }
        update(&model, &mut ws);
        for (k, m) in ws.mu.iter_mut().enumerate() {
            *m = 0.01 * (k as f64 + 1.0).sin();
        }
        let base_q = ws.q.clone();
        let base_dq = ws.dq.clone();
        let base_mu = ws.mu.clone();
        let mut w = 0.0;
        evaluate(&model, &mut ws, &held, h, true, &mut w);
        let jac = ws.dense.clone();
        let n = ws.drhs.len();
        let eps = 1e-6;
        let mut worst = 0.0_f64;
        for c in 0..n {
            let mut col = [vec![0.0; n], vec![0.0; n]];
            for (s, sign) in [1.0, -1.0].iter().enumerate() {
                ws.q.copy_from_slice(&base_q);
                ws.dq.copy_from_slice(&base_dq);
                ws.mu.copy_from_slice(&base_mu);
                ws.drhs.fill(0.0);
                ws.drhs[c] = sign * eps;
                update(&model, &mut ws);
                col[s] = residual(&model, &mut ws, &held, h);
            }
            for r in 0..n {
                let fd = (col[0][r] - col[1][r]) / (2.0 * eps);
                let an = jac[r * n + c];
                worst = worst.max((fd - an).abs() / (1.0 + an.abs()));
            }
        }
        assert!(worst < 1e-7, "largest Jacobian mismatch {worst:e}");
    }
}
