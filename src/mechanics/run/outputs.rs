//! Output values at the current node time: per body, per joint, per site and for the system.
//!
//! ```text
//! body:  r = φ − R c,  R = [d₁ d₂ d₃],  v = v̂_φ − Σᵢ cᵢ v̂_dᵢ,  w = ½ Σᵢ dᵢ × v̂_dᵢ   (v̂: projected)
//! site:  r_s = r + R p,  R_s = R R_p,  v_s = v + w × R p,  w_s = w   (p, R_p: site in body)
//! E = Σ ½ vₙᵀ M vₙ − m g·φ + springs + stops + contact springs and bristles,
//! p = Σ m v_φ,   L = Σ (φ × m v_φ + Σᵢ dᵢ × pᵢ)
//! contact: per shape, its force and ground gap at the state (`model::contact::state_outputs`)
//! ```
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use crate::math::{Mat3, Vec3};

/// Kinematic outputs of one body (interface.md §3).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BodyOutput {
    /// Origin of the body frame, world frame, m.
    pub r: Vec3,
    /// Rotation world ← body (columns are the directors), 1.
    pub rot: Mat3,
    /// Velocity of the body frame origin, world frame, m/s.
    pub v: Vec3,
    /// Angular velocity, world frame, rad/s.
    pub w: Vec3,
}

/// Joint coordinates and rates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct JointOutput {
    /// Coordinates (len `JointType::nq`): angles unwrapped (continuous), slides in m; spherical:
    /// the quaternion `[w, x, y, z]` of the child joint frame relative to the parent joint frame.
    pub q: Vec<f64>,
    /// Rates (len `JointType::dof`); spherical: relative angular velocity in the child frame.
    pub qd: Vec<f64>,
}

/// Every output of the system at the current time.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Outputs {
    /// Per body, in model order.
    pub bodies: Vec<BodyOutput>,
    /// Per joint, in model order.
    pub joints: Vec<JointOutput>,
    /// Per site, in model order (pose and twist of the site frame, as for bodies).
    pub sites: Vec<BodyOutput>,
    /// Kinetic + potential (gravity and joint springs) energy, J.
    pub energy: f64,
    /// Work of the inputs minus energy dissipated by damping since the start, J.
    pub work: f64,
    /// Total linear momentum, world frame, N·s.
    pub p: Vec3,
    /// Total angular momentum about the world origin, world frame, N·m·s.
    pub l: Vec3,
    /// Largest constraint violation after the last step (internal and joint rows), 1 or m.
    pub constraint_residual: f64,
    /// Per collision shape, in model order: its contact force and its gap to the ground.
    pub contacts: Vec<ShapeContact>,
}

use crate::mechanics::model::constraint::{body_nodes, Nodes};
use crate::mechanics::model::contact::state_outputs;
pub use crate::mechanics::model::contact::ShapeContact;
use crate::mechanics::model::joint::world_nodes;
use crate::mechanics::model::runtime::{DofRt, Model};

impl Outputs {
    /// The name of the first non-finite output (`body 2 r`, `system.energy`, ...), if any.
    #[must_use]
    pub fn first_non_finite(&self) -> Option<String> {
        let bad = |xs: &[f64]| xs.iter().any(|x| !x.is_finite());
        let frames = [("body", &self.bodies), ("site", &self.sites)];
        for (what, list) in frames {
            for (i, b) in list.iter().enumerate() {
                for (name, xs) in [
                    ("r", b.r.as_slice()),
                    ("R", b.rot.as_slice()),
                    ("v", b.v.as_slice()),
                    ("w", b.w.as_slice()),
                ] {
                    if bad(xs) {
                        return Some(format!("{what} {} {name}", i + 1));
                    }
                }
            }
        }
        for (i, j) in self.joints.iter().enumerate() {
            if bad(&j.q) || bad(&j.qd) {
                return Some(format!("joint {} coordinates", i + 1));
            }
        }
        let system = [
            ("system.energy", self.energy),
            ("system.work", self.work),
            ("system.constraint_residual", self.constraint_residual),
        ];
        for (name, x) in system {
            if !x.is_finite() {
                return Some(name.into());
            }
        }
        if bad(self.p.as_slice()) || bad(self.l.as_slice()) {
            return Some("system momentum".into());
        }
        None
    }

    /// Outputs sized for `model` (values zero until [`update`] runs).
    #[must_use]
    pub(crate) fn for_model(model: &Model) -> Self {
        Self {
            bodies: vec![BodyOutput::default(); model.bodies.len()],
            joints: model
                .def()
                .joints
                .iter()
                .map(|j| JointOutput {
                    q: vec![0.0; j.kind.nq()],
                    qd: vec![0.0; j.kind.dof()],
                })
                .collect(),
            sites: vec![BodyOutput::default(); model.def().sites.len()],
            contacts: vec![ShapeContact::default(); model.def().contact.shapes.len()],
            ..Self::default()
        }
    }
}

/// Recomputes every output from the nodal state (theory.md §4.7). Allocates nothing.
///
/// `v` are the nodal velocities `vₙ` of the scheme (12 per body, world frame): the energy
/// `½ vₙᵀ M vₙ + Σ ½ a ω² + V` (the conserved discrete energy; `arm` the rotor rates `ω` of the
/// coordinates with an armature `a`; `V` includes the joint friction bristles' `½ k s²`, `fric`), `p` and `L` come from them. `vp` are their
/// M-orthogonal projection onto the admissible velocities at `q` (`projection.rs`, same layout):
/// the body velocities `v`, `w` and the joint rates come from `vp`, so that they satisfy the
/// velocity constraints to round-off.
#[allow(clippy::too_many_arguments)]
pub(crate) fn update(
    model: &Model,
    q: &[f64],
    v: &[f64],
    vp: &[f64],
    angles: &[f64],
    stiffness: &[f64],
    bristle: &[f64],
    arm: &[f64],
    fric: &[f64],
    work: f64,
    out: &mut Outputs,
) {
    let g = model.def().gravity;
    let mut energy = 0.0;
    let mut p = Vec3::zeros();
    let mut l = Vec3::zeros();
    let mut resid = 0.0_f64;
    for (b, br) in model.bodies.iter().enumerate() {
        let qb = body_nodes(q, b);
        let vb = body_nodes(v, b);
        let wb = body_nodes(vp, b);
        let rot = Mat3::from_columns(&[qb[1], qb[2], qb[3]]);
        let o = &mut out.bodies[b];
        o.rot = rot;
        o.r = qb[0] - rot * br.com;
        o.v = wb[0] - (wb[1] * br.com.x + wb[2] * br.com.y + wb[3] * br.com.z);
        o.w = (qb[1].cross(&wb[1]) + qb[2].cross(&wb[2]) + qb[3].cross(&wb[3])) * 0.5;
        // kinetic + gravity energy, momenta (director momenta pᵢ = Σⱼ Eᵢⱼ ḋⱼ)
        let pphi = vb[0] * br.mass;
        energy += 0.5 * pphi.dot(&vb[0]) - br.mass * g.dot(&qb[0]);
        p += pphi;
        l += qb[0].cross(&pphi);
        for i in 0..3 {
            let pi = vb[1] * br.e[(i, 0)] + vb[2] * br.e[(i, 1)] + vb[3] * br.e[(i, 2)];
            energy += 0.5 * pi.dot(&vb[i + 1]);
            l += qb[i + 1].cross(&pi);
        }
        // internal constraints ½(dᵢ·dᵢ − 1), dᵢ·dⱼ
        for i in 0..3 {
            resid = resid.max((0.5 * (qb[i + 1].norm_squared() - 1.0)).abs());
            for j in i + 1..3 {
                resid = resid.max(qb[i + 1].dot(&qb[j + 1]).abs());
            }
        }
    }
    let zero: Nodes = [Vec3::zeros(); 4];
    for (j, jt) in model.joints.iter().enumerate() {
        let qa = jt.parent.map_or(zero, |a| body_nodes(q, a));
        let qb = body_nodes(q, jt.child);
        for row in jt.rows.iter().chain(jt.dropped.iter()) {
            resid = resid.max(row.eval(&qa, &qb).abs());
        }
        // a spherical joint's friction bristle, ½ k |s|²
        if let (Some(fr), Some(_)) = (&jt.friction, &jt.sph_axes) {
            let s = &fric[jt.fric0..jt.fric0 + 3];
            energy += 0.5 * fr.stiffness() * s.iter().map(|x| x * x).sum::<f64>();
        }
        // joint springs
        let k = stiffness[j];
        let mut turn = jt.turn0;
        for (dk, dof) in jt.dofs.iter().enumerate() {
            // the rotor's kinetic energy ½ a ω² (its own rate, as the step carries it)
            if jt.armature > 0.0 {
                let w = arm[jt.arm0 + dk];
                energy += 0.5 * jt.armature * w * w;
            }
            // the friction bristle's ½ k s²
            if let Some(fr) = &jt.friction {
                energy += fr.energy(fric[jt.fric0 + dk]);
            }
            match dof {
                DofRt::Slide(row) => {
                    let s = row.eval(&qa, &qb);
                    energy += 0.5 * k * s * s + jt.stops.map_or(0.0, |st| st.energy(s));
                }
                DofRt::Turn(_) => {
                    let t = angles[turn];
                    energy += 0.5 * k * t * t + jt.stops.map_or(0.0, |st| st.energy(t));
                    turn += 1;
                }
            }
        }
        let va = jt.parent.map_or(zero, |a| body_nodes(vp, a));
        let vb = body_nodes(vp, jt.child);
        let jo = &mut out.joints[j];
        joint_outputs(
            model,
            j,
            &qa,
            &qb,
            &va,
            &vb,
            &angles[jt.turn0..],
            &mut jo.q,
            &mut jo.qd,
        );
    }
    for (site, o) in model.def().sites.iter().zip(out.sites.iter_mut()) {
        // rigidly attached: r_s = r + R p, R_s = R R_p, v_s = v + w × R p, w_s = w
        let b = &out.bodies[site.body];
        let arm = b.rot * site.frame.translation;
        o.r = b.r + arm;
        o.rot = b.rot * site.frame.rotation;
        o.v = b.v + b.w.cross(&arm);
        o.w = b.w;
    }
    if !model.contact.is_empty() {
        energy += state_outputs(&model.contact, q, vp, bristle, &mut out.contacts);
    }
    out.energy = energy;
    out.work = work;
    out.p = p;
    out.l = l;
    out.constraint_residual = resid;
}
/// Joint coordinates and rates at the nodes; turn coordinates take the unwrapped `angles`
/// (this joint's turn dofs first).
#[allow(clippy::too_many_arguments)]
pub(crate) fn joint_outputs(
    model: &Model,
    j: usize,
    qa: &Nodes,
    qb: &Nodes,
    va: &Nodes,
    vb: &Nodes,
    angles: &[f64],
    q: &mut [f64],
    qd: &mut [f64],
) {
    let jt = &model.joints[j];
    let world = world_nodes();
    let qa = if jt.parent.is_some() { qa } else { &world };
    jt.geom.coords(qa, qb, q);
    jt.geom.rates(qa, qb, va, vb, qd);
    let mut t = 0;
    for (k, d) in jt.dofs.iter().enumerate() {
        if let DofRt::Turn(_) = d {
            q[k] = angles[t];
            t += 1;
        }
    }
}
