//! Contact forces in a stage: the laws of `model::contact_law` at the ground points and the
//! body–body features of `model::contact`, into the node residual, the bodies' diagonal
//! Jacobian blocks, and (at the converged iterate) the work account and the bristles.
//!
//! ```text
//! ground point:  x = φ + Σ Xᵢ dᵢ,  g = n·x − h₀ − r,  Δg = n·Δx
//!                R̃_φ −= (h²/2)(f n + F),   R̃_dᵢ −= (h²/2)(Xᵢ f n + X_cᵢ F)
//!                u = P_t Δx_c,  X_c = X − r D̄ᵀ n      (the contact point, fixed in the body)
//! feature:       π_k(q),  Δπ_k = ∇π_k(q̄)·Δq,  g = G(π) − r_a − r_b,  Δg = Σ Q_k Δπ_k
//!                R̃ −= (h²/2) f Σ_k Q_k ∇π_k(q̄)       (both bodies' nodes)
//!                friction at p̄ (the middle of the nearest points at q̄): F on B, −F on A
//! work:          W_contact = −Σ (D_n + D_t)            (exactly −(ΔV + ΔV_bristle) − the loads' work)
//! ```
//!
//! The Jacobian keeps each body's own terms (normal stiffness `f'` along the gap's gradient,
//! the bristle's tangential stiffness, the cone's dependence on the normal force); the coupling
//! of two bodies through a feature is left out of the matrix, which only slows Newton's
//! convergence where bodies press on each other.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::contact_tangent::exact_blocks;
use super::ground_law::{ground_law, world, GroundStep};
use super::work::ContactJacobian;
use super::work::Work;
use crate::math::{skew, Mat3, Vec3};
use crate::mechanics::model::constraint::{body_nodes, read3, write3};
use crate::mechanics::model::contact::{material_point, pair_nodes, Feature, GroundPoint};
use crate::mechanics::model::contact_law::{friction, normal, Friction, Normal};
use crate::mechanics::model::kernels::project;
use crate::mechanics::model::runtime::Model;

/// The laws of ground point `p` (bristle `s0`) over the stage `ws.qn → ws.q` of size `h`.
fn ground_step(
    p: &GroundPoint,
    normal_dir: &Vec3,
    height: f64,
    ws: &Work,
    s0: Vec3,
    h: f64,
) -> GroundStep {
    let b = p.body;
    let (q0, dq, qbar) = (
        body_nodes(&ws.qn, b),
        body_nodes(&ws.dq, b),
        body_nodes(&ws.qbar, b),
    );
    ground_law(p, normal_dir, height, [&q0, &dq, &qbar], s0, h)
}

/// Adds `−hh·(F at X)` to body `b`'s node residual.
fn push_force(rn: &mut [f64], b: usize, x: &Vec3, f: &Vec3, hh: f64) {
    let at = 12 * b;
    let v = read3(rn, at) - f * hh;
    write3(rn, at, &v);
    for i in 0..3 {
        let v = read3(rn, at + 3 * (i + 1)) - f * (hh * x[i]);
        write3(rn, at + 3 * (i + 1), &v);
    }
}

/// `blk += s·a bᵀ` (6 × 6, row-major).
fn outer(blk: &mut [f64; 36], s: f64, a: &[f64; 6], b: &[f64; 6]) {
    for r in 0..6 {
        for c in 0..6 {
            blk[6 * r + c] += s * a[r] * b[c];
        }
    }
}

/// `blk += s [I; hat(rbar)] T [I, −hat(r)]` for a 3 × 3 tangential stiffness `T`.
fn tangential(blk: &mut [f64; 36], s: f64, rbar: &Vec3, r: &Vec3, t: &Mat3) {
    let left = skew(rbar);
    let right = -skew(r);
    let m = [[*t, t * right], [left * t, left * t * right]];
    for (bi, row) in m.iter().enumerate() {
        for (bj, blkm) in row.iter().enumerate() {
            for i in 0..3 {
                for j in 0..3 {
                    blk[6 * (3 * bi + i) + 3 * bj + j] += s * blkm[(i, j)];
                }
            }
        }
    }
}

/// `[n; r × n]`.
fn wrench(n: &Vec3, r: &Vec3) -> [f64; 6] {
    let m = r.cross(n);
    [n.x, n.y, n.z, m.x, m.y, m.z]
}

/// The tangential stiffness matrix `−∂F/∂u·P_t = (stiff P_t + radial t̂t̂ᵀ) P_t` of a friction
/// force.
fn tangent_matrix(n: &Vec3, fr: &Friction) -> Mat3 {
    let p = Mat3::identity() - n * n.transpose();
    (p * fr.stiff + fr.dir * fr.dir.transpose() * fr.radial) * p
}

/// The contact forces at the iterate `ws.q` of a stage of size `h` into the node residual
/// `ws.rn` and, if `jac`, the bodies' diagonal blocks `ws.xbody`.
pub(crate) fn contact_forces(model: &Model, ws: &mut Work, h: f64, jac: bool) {
    let hh = 0.5 * h * h;
    let exact = jac && ws.contact_jacobian == ContactJacobian::Exact;
    if let Some(g) = &model.contact.ground {
        if exact {
            exact_blocks(g, ws, h);
        }
        for (k, p) in g.points.iter().enumerate() {
            let s0 = read3(&ws.bristle, 3 * k);
            let st = ground_step(p, &g.normal, g.height, ws, s0, h);
            if st.normal.force == 0.0 && st.friction.force == Vec3::zeros() {
                continue;
            }
            let b = p.body;
            push_force(&mut ws.rn, b, &p.x, &(g.normal * st.normal.force), hh);
            push_force(&mut ws.rn, b, &st.xc, &st.friction.force, hh);
            if jac && !exact {
                let (qbar, q) = (body_nodes(&ws.qbar, b), body_nodes(&ws.q, b));
                let (rbar, r) = (world(&qbar, &p.x), world(&q, &p.x));
                let (rcbar, rc) = (world(&qbar, &st.xc), world(&q, &st.xc));
                let (wbar, w) = (wrench(&g.normal, &rbar), wrench(&g.normal, &r));
                let blk = &mut ws.xbody[b];
                outer(blk, hh * st.normal.dforce, &wbar, &w);
                let t = tangent_matrix(&g.normal, &st.friction);
                tangential(blk, hh, &rcbar, &rc, &t);
                // the cone μ f follows the normal force, the damper k d p̄ the penetration:
                // ∂F/∂x₁ = μ f' ∂F/∂C + k d ∂p̄/∂x₁ ∂F/∂c_t
                let dmean = if st.x1 > 0.0 { 0.5 } else { 0.0 };
                let s = st.friction.dcap * (p.law.friction * st.normal.dforce)
                    + st.friction.dct * (p.law.stiffness * p.law.damping * dmean);
                if s != Vec3::zeros() {
                    let left: [f64; 6] = {
                        let m = rcbar.cross(&s);
                        [s.x, s.y, s.z, m.x, m.y, m.z]
                    };
                    outer(blk, hh, &left, &w);
                }
            }
        }
    }
    let off = model.contact.ground.as_ref().map_or(0, |g| g.points.len());
    for (k, f) in model.contact.features.iter().enumerate() {
        let s0 = read3(&ws.bristle, 3 * (off + k));
        let Some(st) = feature_step(f, ws, s0, h) else {
            continue;
        };
        let (a, b) = f.bodies;
        // normal: −hh f Σ Q_k ∇π_k(q̄) on both bodies' nodes
        let (ga, gb) = (&st.grad_a, &st.grad_b);
        add_nodes(&mut ws.rn, a, ga, -hh * st.normal.force);
        add_nodes(&mut ws.rn, b, gb, -hh * st.normal.force);
        push_force(&mut ws.rn, b, &st.xb, &st.friction.force, hh);
        push_force(&mut ws.rn, a, &st.xa, &(-st.friction.force), hh);
        if jac {
            let law = f.law;
            let dmean = if st.x1 > 0.0 { 0.5 } else { 0.0 };
            let coupling = st.friction.dcap * (law.friction * st.normal.dforce)
                + st.friction.dct * (law.stiffness * law.damping * dmean);
            for (body, grad, x, sign) in [(a, ga, &st.xa, -1.0), (b, gb, &st.xb, 1.0)] {
                let qbar = body_nodes(&ws.qbar, body);
                let dbar = [qbar[1], qbar[2], qbar[3]];
                let w = project(grad, &dbar);
                outer(&mut ws.xbody[body], hh * st.normal.dforce, &w, &w);
                let r = world(&qbar, x);
                let t = tangent_matrix(&st.n, &st.friction);
                tangential(&mut ws.xbody[body], hh, &r, &r, &t);
                // the friction on this body (sign) follows its own share of the penetration
                let s = coupling * sign;
                let left = {
                    let m = r.cross(&s);
                    [s.x, s.y, s.z, m.x, m.y, m.z]
                };
                outer(&mut ws.xbody[body], hh, &left, &w);
            }
        }
    }
}

/// The first body–body feature that touches or holds a loaded bristle over the stage in `ws`,
/// named (`None`: none does).
pub(crate) fn touching_features(model: &Model, ws: &Work, h: f64) -> Option<String> {
    let off = model.contact.ground.as_ref().map_or(0, |g| g.points.len());
    let shapes = &model.def().contact.shapes;
    model
        .contact
        .features
        .iter()
        .enumerate()
        .find_map(|(k, f)| {
            let s0 = read3(&ws.bristle, 3 * (off + k));
            feature_step(f, ws, s0, h).map(|_| {
                format!(
                    "the shapes {} and {} touch each other",
                    shapes[f.shapes.0].name, shapes[f.shapes.1].name
                )
            })
        })
}

/// `rn[body] += s·grad` (4 node vectors).
fn add_nodes(rn: &mut [f64], body: usize, grad: &[Vec3; 4], s: f64) {
    for k in 0..4 {
        let v = read3(rn, 12 * body + 3 * k) + grad[k] * s;
        write3(rn, 12 * body + 3 * k, &v);
    }
}

/// One feature's step quantities.
struct FeatureStep {
    normal: Normal,
    friction: Friction,
    /// `Σ_k Q_k ∇π_k(q̄)` on A's and B's nodes.
    grad_a: [Vec3; 4],
    grad_b: [Vec3; 4],
    /// The friction point in A's and B's body axes (relative to the centres of mass).
    xa: Vec3,
    xb: Vec3,
    /// Unit normal from A to B at the midpoint.
    n: Vec3,
    /// Penetrations at the stage's start and end.
    x0: f64,
    x1: f64,
    /// Energy released by turning the bristle into the new tangent plane (≥ 0), J.
    turned: f64,
}

/// The laws of feature `f` (bristle `s0`) over the stage `ws.qn → ws.q` of size `h`; `None`
/// where nothing touches at either end and the bristle is relaxed.
fn feature_step(f: &Feature, ws: &Work, s0: Vec3, h: f64) -> Option<FeatureStep> {
    let (qa0, qb0) = pair_nodes(&ws.qn, f);
    let (qab, qbb) = pair_nodes(&ws.qbar, f);
    let (dqa, dqb) = pair_nodes(&ws.dq, f);
    let p0 = f.invariants(&qa0, &qb0);
    let mut p1 = p0;
    let mut grads = [[Vec3::zeros(); 8]; 4];
    for k in 0..f.nrows {
        f.rows[k].gradient(&qab, &qbb, &mut grads[k]);
        let dp: f64 = (0..4)
            .map(|n| grads[k][n].dot(&dqa[n]) + grads[k][4 + n].dot(&dqb[n]))
            .sum();
        p1[k] = p0[k] + dp;
    }
    let (g0, g1) = (f.gap(&p0), f.gap(&p1));
    if g0 > 0.0 && g1 > 0.0 && s0 == Vec3::zeros() {
        return None;
    }
    let q = f.gap_quotients(&p0, &p1);
    let mut grad_a = [Vec3::zeros(); 4];
    let mut grad_b = [Vec3::zeros(); 4];
    for k in 0..f.nrows {
        for n in 0..4 {
            grad_a[n] += grads[k][n] * q[k];
            grad_b[n] += grads[k][4 + n] * q[k];
        }
    }
    let law = f.law;
    let (x0, x1) = (-g0, -g1);
    let nrm = normal(law.stiffness, law.damping, x0, x1, h);
    // friction at the middle of the nearest points at the midpoint, fixed in both bodies
    let (pa, pb, n) = f.nearest(&qab, &qbb);
    let ra = f.radius_a;
    let rb = f.radii - f.radius_a;
    let pbar = (pa + n * ra + pb - n * rb) * 0.5;
    let (xa, xb) = (material_point(&qab, &pbar), material_point(&qbb, &pbar));
    let rel = (dqb[0] + world(&dqb, &xb)) - (dqa[0] + world(&dqa, &xa));
    let u = rel - n * n.dot(&rel);
    let s0p = s0 - n * n.dot(&s0);
    let turned = 0.5 * law.stiffness * (s0.norm_squared() - s0p.norm_squared());
    let ct = law.stiffness * law.damping * nrm.mean;
    let fr = friction(law.stiffness, ct, law.friction * nrm.force, s0p, u, h);
    Some(FeatureStep {
        normal: nrm,
        friction: fr,
        grad_a,
        grad_b,
        xa,
        xb,
        n,
        x0,
        x1,
        turned: turned.max(0.0),
    })
}

/// At the converged iterate of a stage of size `h`: the contact's work (minus what its dampers
/// and friction dissipated, J), the bristles at the stage's end into `ws.bristle1`, and the
/// dissipation added to `ws.contact_loss`.
pub(crate) fn contact_finish(model: &Model, ws: &mut Work, h: f64) -> f64 {
    let mut lost = 0.0;
    if let Some(g) = &model.contact.ground {
        for (k, p) in g.points.iter().enumerate() {
            let s0 = read3(&ws.bristle, 3 * k);
            let st = ground_step(p, &g.normal, g.height, ws, s0, h);
            lost += (st.normal.force - st.normal.elastic) * (st.x1 - st.x0) + st.friction.loss;
            write3(&mut ws.bristle1, 3 * k, &st.friction.s1);
        }
    }
    let off = model.contact.ground.as_ref().map_or(0, |g| g.points.len());
    for (k, f) in model.contact.features.iter().enumerate() {
        let s0 = read3(&ws.bristle, 3 * (off + k));
        let (s1, l) = match feature_step(f, ws, s0, h) {
            Some(st) => (
                st.friction.s1,
                (st.normal.force - st.normal.elastic) * (st.x1 - st.x0)
                    + st.friction.loss
                    + st.turned,
            ),
            None => (Vec3::zeros(), 0.0),
        };
        lost += l;
        write3(&mut ws.bristle1, 3 * (off + k), &s1);
    }
    ws.contact_loss += lost;
    -lost
}
