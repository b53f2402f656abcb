//! Residual of the reduced equations and the body blocks of their Newton matrix:
//!
//! ```text
//! r_b = P̄_int,bᵀ R̃_b                      (6 per body: inertia, gravity, loads; newton.rs)
//! W_b = r_b + Σ_{children c} Ā_cᵀ W_c      (wrench of the subtree about b's centre of mass)
//! R_b = S̄_bᵀ W_b                          (= (P̄ᵀ r) for the rates of b's joint)
//! ```
//!
//! No joint row and no multiplier enters: the constraint forces lie in the range of
//! `G(q̄)ᵀ` and `P̄ᵀ` annihilates it. In a Jacobian pass the body diagonal blocks `K_bb`, the
//! joint loads' couplings `K_cp`, `K_pc` and the maps `Q` at the iterate are kept for `tree`.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::super::body_terms::body_rows;
use super::super::contact::contact_forces;
use super::super::coupling::reaction;
use super::super::joint_loads::{joint_loads, loaded, Acc, Pair};
use super::super::newton::{apply_joint, inertia_and_forces};
use super::super::work::{Held, Work};
use super::bordered::Couplings;
use super::joint_space::joint_row;
use super::maps::{joint_map, Map};
use super::work::RedWork;
use crate::math::Vec3;
use crate::mechanics::model::constraint::body_nodes;
use crate::mechanics::model::def::JointType;
use crate::mechanics::model::runtime::Model;

fn to66(x: &[f64; 36]) -> [[f64; 6]; 6] {
    std::array::from_fn(|i| std::array::from_fn(|j| x[6 * i + j]))
}

/// The maps of body `b`'s joint at the midpoint (`P̄`) and at the iterate (`Q`).
fn maps(model: &Model, ws: &Work, b: usize, jac: bool) -> (Map, Option<Map>) {
    let Some(j) = model.tree_joint[b] else {
        return (Map::free(), Some(Map::free()));
    };
    let g = &model.joints[j].geom;
    let zero = [Vec3::zeros(); 4];
    let p = model.parent[b];
    let at = |x: &[f64]| (p.map_or(zero, |p| body_nodes(x, p)), body_nodes(x, b));
    let (qa, qb) = at(&ws.qbar);
    let pm = joint_map(g, &qa, &qb, true);
    let qm = jac.then(|| {
        let (qa, qb) = at(&ws.q);
        joint_map(g, &qa, &qb, false)
    });
    (pm, qm)
}

/// Evaluates the reduced residual at the placed iterate (`ws.q`, `ws.dq`) into `rw.res`
/// (and, if `jac`, the blocks and maps of the Newton matrix); returns the largest scaled
/// residual (moments about the joint axes times the child's moment scale, slide forces times
/// its force scale).
pub(crate) fn evaluate(
    model: &Model,
    ws: &mut Work,
    rw: &mut RedWork,
    held: &Held,
    h: f64,
    jac: bool,
) -> f64 {
    let hh = 0.5 * h * h;
    ws.set_midpoint();
    inertia_and_forces(model, ws, held, h, jac);
    if !model.contact.is_empty() {
        contact_forces(model, ws, h, jac);
    }
    let mut acc = Acc::new();
    for (slot, cp) in rw.cpl.slots.iter_mut().zip(&model.couplings) {
        slot.g = -cp.offset;
    }
    for (j, jt) in model.joints.iter().enumerate() {
        let c = jt.child;
        if jac {
            // `kcp`, `kpc` are read only where `coupled`
            rw.coupled[c] = false;
        }
        let load = loaded(model, held, j);
        let coupled = rw.cpl.on_joint.get(j).is_some_and(|v| !v.is_empty());
        rw.jon[c] = false;
        if !load && !coupled {
            continue;
        }
        if let Some(sp) = rw.split[j] {
            let Couplings {
                on_joint, slots, ..
            } = &mut rw.cpl;
            let cps = on_joint.get(j).map_or(&[][..], |v| &v[..]);
            rw.jrow[c] = joint_row(model, ws, held, (j, &sp), h, jac, load, cps, slots);
            rw.jon[c] = true;
            continue;
        }
        let p = Pair::new(ws, jt.parent, c);
        acc.clear(jac);
        if load {
            joint_loads(model, ws, held, j, h, jac, &p, &mut acc);
        }
        if coupled {
            reactions(model, ws, rw, j, jac, &p, &mut acc);
        }
        if apply_joint(ws, &p, &mut acc, jac) {
            rw.kpc[c] = to66(&acc.x_ab);
            rw.kcp[c] = to66(&acc.x_ba);
            rw.coupled[c] = true;
        }
    }
    for b in 0..model.bodies.len() {
        rw.w[b] = body_rows(model, ws, held, hh, b, jac);
        if jac {
            rw.kd[b] = to66(&ws.xbody[b]);
        }
    }
    let mut res = 0.0_f64;
    for &b in model.order.iter().rev() {
        let (pm, qm) = maps(model, ws, b, jac);
        let mut r = [0.0; 6];
        pm.st_mul(&rw.w[b], &mut r);
        if rw.jon[b] {
            r[0] += rw.jrow[b].r;
        }
        if let Some(qm) = qm {
            rw.q[b] = qm;
            geometric_stiffness(model, rw, b, &pm, &qm);
            if rw.jon[b] {
                let jr = &rw.jrow[b];
                for i in 0..3 {
                    rw.xc[b][0][3 + i] += jr.xc[i];
                    rw.xp[b][0][3 + i] += jr.xp[i];
                }
            }
        }
        let br = &model.bodies[b];
        // a coupled joint's residual is judged after its multipliers' update (`couple`)
        if !rw.cpl.coupled.get(b).copied().unwrap_or(false) {
            for k in 0..pm.f() {
                let s = if k < pm.fr { br.ms } else { br.fs };
                res = res.max((r[k] * s).abs());
            }
        }
        rw.res[b] = r;
        rw.p[b] = pm;
        if let Some(p) = model.parent[b] {
            let t = pm.at_mul(&rw.w[b]);
            for k in 0..6 {
                rw.w[p][k] += t[k];
            }
        }
    }
    // the couplings' values are corrected within the solve, as the joints' defects are
    res
}

/// The reactions of the couplings on joint `j` into `acc`, their row values into `rw.cpl.g`
/// and (`jac`) their columns and rows (`couple`).
fn reactions(
    model: &Model,
    ws: &mut Work,
    rw: &mut RedWork,
    j: usize,
    jac: bool,
    p: &Pair,
    acc: &mut Acc,
) {
    let cpl = &mut rw.cpl;
    for &(c, w) in &cpl.on_joint[j] {
        let mu = ws.mu[model.couplings[c].row];
        let r = reaction(model, ws, (j, w, mu), p, jac, acc);
        let slot = &mut cpl.slots[c];
        slot.g += r.g;
        if jac {
            let cp = (&model.couplings[c], j);
            slot.put(cp, (p.b, p.a), (r.col[0], true), r.row);
        }
    }
}

/// `s ((f·v) I − v fᵀ)`: the derivative of `f × (δθ × v)` with respect to `δθ`, times `s`.
fn turn_block(s: f64, f: &Vec3, v: &Vec3) -> [[f64; 3]; 3] {
    let fv = f.dot(v);
    std::array::from_fn(|i| {
        std::array::from_fn(|j| if i == j { s * fv } else { 0.0 } - s * v[i] * f[j])
    })
}

/// Adds [`turn_block`] to the 3 × 3 block at `(r0, c0)` of `k`.
fn add_turn(k: &mut [[f64; 6]; 6], r0: usize, c0: usize, s: f64, f: &Vec3, v: &Vec3) {
    let t = turn_block(s, f, v);
    for i in 0..3 {
        for j in 0..3 {
            k[r0 + i][c0 + j] += t[i][j];
        }
    }
}

/// The geometric stiffness of the constraint forces (the `∂P̄/∂u` term of theory.md §4.5),
/// with the accumulated wrench `W_b` of body `b`'s subtree: midpoint vectors fixed in a body
/// turn by `½ δθ` of that body: `δv̄ = ½ δθ × v` with `v` at the iterate (map `qm`). Exact
/// for every pair but the slides, whose midpoint directions `ā₁ × ā₂` are taken to turn
/// rigidly and whose lever `r̄` to turn with the parent only (an O(h) error in these terms).
/// Into `rw.xc`, `rw.xp` (rows of `b`'s joint rates, columns of the body twists of `b` and its
/// parent) for `S̄ᵀ W`, and into `rw.kd` of the parent and `rw.gpc[b]` for `Āᵀ W`.
fn geometric_stiffness(model: &Model, rw: &mut RedWork, b: usize, pm: &Map, qm: &Map) {
    let w = rw.w[b];
    let f = Vec3::new(w[0], w[1], w[2]);
    let m = Vec3::new(w[3], w[4], w[5]);
    // only the rows of the joint's rates are read
    let rows = pm.f();
    let (xc, xp) = (&mut rw.xc[b], &mut rw.xp[b]);
    for r in 0..rows {
        xc[r] = [0.0; 6];
        xp[r] = [0.0; 6];
    }
    let kind = model.tree_joint[b].map(|j| model.joints[j].geom.kind);
    if let Some(kind) = kind {
        let mj = m + f.cross(&pm.rho);
        for k in 0..pm.fr {
            let n = pm.n[k];
            // δn̄·(m + f × ρ̄): n fixed in the parent (a axes) or the child (b₂)
            let t = qm.n[k].cross(&mj) * 0.5;
            let owner = match (kind, k) {
                (JointType::Spherical, _) => None,
                (JointType::Universal, 1) => Some(&mut *xc),
                _ => Some(&mut *xp),
            };
            if let Some(x) = owner {
                for i in 0..3 {
                    x[k][3 + i] += t[i];
                }
            }
            // n̄·(f × δρ̄), ρ fixed in the child
            let t = (n * f.dot(&qm.rho) - f * n.dot(&qm.rho)) * 0.5;
            for i in 0..3 {
                xc[k][3 + i] += t[i];
            }
        }
        for l in 0..pm.ft {
            // δt̄·f, t fixed in the parent
            let t = qm.t[l].cross(&f) * 0.5;
            for i in 0..3 {
                xp[pm.fr + l][3 + i] += t[i];
            }
        }
    }
    // Āᵀ W: δē × f with ē = Eᴬ − Z ρ̄ (Eᴬ fixed in the parent, ρ̄ in the child)
    if let Some(p) = model.parent[b] {
        let ea = qm.e + if qm.z { qm.rho } else { Vec3::zeros() };
        add_turn(&mut rw.kd[p], 3, 3, -0.5, &f, &ea);
        // the child's turn columns (none for a spherical child)
        rw.gpc[b] = if qm.z {
            turn_block(0.5, &f, &qm.rho)
        } else {
            [[0.0; 3]; 3]
        };
    }
}
