//! The spanning tree and the initial state: forward kinematics of positions and velocities from
//! the tree joints' initial coordinates and rates (interface.md §2, theory.md pitfall 6).
//!
//! Pose composition (URDF): child joint frame = parent body frame · `parent_frame` · `M(q)`,
//! child body frame = child joint frame · `child_frame⁻¹`, with the joint motion `M(q)` in the
//! user's joint frame (`n = S e₃` the unit axis, `S` = [`joint_frame`]):
//! revolute `Rot(n, θ)`; prismatic `Trans(s n)`; cylindrical `Trans(s n)·Rot(n, θ)`; universal
//! `Rot(axis, α)·Rot(axis2, β)`; planar `Trans(x S e₁ + y S e₂)·Rot(n, θ)` (x, y measured along
//! S's first two columns — the joint frame's x and y when the normal is z, see
//! [`super::joint::axis_frame`]); spherical `Rot(quat)`; fixed identity.

use super::body::BodyInertia;
use super::def::{JointDef, JointInitial, JointType, ModelDef};
use super::error::ModelError;
use super::joint::{check_rotation, joint_frame};
use crate::math::{exp_so3, quat_to_matrix, Mat3, Vec3};

/// The spanning tree of a model.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TreeOrder {
    /// Body indices, every parent before its children.
    pub order: Vec<usize>,
    /// Per body: the tree joint whose child it is (`None` for free bodies).
    pub tree_joint: Vec<Option<usize>>,
    /// Per body: its entry in `ModelDef::free_bodies` (free bodies only).
    pub free: Vec<Option<usize>>,
    /// Loop-closing joints, in model order.
    pub loop_joints: Vec<usize>,
}

/// Orders the bodies along the tree joints (non-loop-closing joints).
///
/// # Errors
/// [`ModelError::Invalid`] for indices out of range, a body that is the child of two tree
/// joints, a cycle of tree joints, a body with neither tree joint nor free-body pose, or a
/// free-body pose given for a body that has a tree joint (or twice).
pub fn tree_order(def: &ModelDef) -> Result<TreeOrder, ModelError> {
    let n = def.bodies.len();
    let name = |b: usize| def.bodies[b].name.as_str();
    let mut tree_joint = vec![None; n];
    let mut loop_joints = Vec::new();
    for (j, joint) in def.joints.iter().enumerate() {
        let bad = |what: &str| ModelError::Invalid(format!("joint '{}': {what}", joint.name));
        if joint.child >= n || joint.parent.is_some_and(|p| p >= n) {
            return Err(bad("body index out of range"));
        }
        if joint.parent == Some(joint.child) {
            return Err(bad("parent and child are the same body"));
        }
        if joint.loop_closing {
            loop_joints.push(j);
        } else if let Some(other) = tree_joint[joint.child].replace(j) {
            let msg = format!(
                "is the child of two tree joints ('{}', '{}'); mark one loop_closing",
                def.joints[other].name, joint.name
            );
            return Err(ModelError::Invalid(format!(
                "body '{}' {msg}",
                name(joint.child)
            )));
        }
    }
    let mut free = vec![None; n];
    for (k, f) in def.free_bodies.iter().enumerate() {
        if f.body >= n {
            return Err(ModelError::Invalid("free body index out of range".into()));
        }
        if tree_joint[f.body].is_some() || free[f.body].replace(k).is_some() {
            return Err(ModelError::Invalid(format!(
                "body '{}' has both a joint and a free-body pose, or two poses",
                name(f.body)
            )));
        }
    }
    if let Some(b) = (0..n).find(|&b| tree_joint[b].is_none() && free[b].is_none()) {
        return Err(ModelError::Invalid(format!(
            "body '{}' has no pose: no tree joint and no free-body initial state",
            name(b)
        )));
    }
    // walk up each chain until a placed body or a root; a body met twice on one walk is a cycle
    let mut placed = vec![false; n];
    let mut order = Vec::with_capacity(n);
    for start in 0..n {
        let mut chain = Vec::new();
        let mut b = Some(start);
        while let Some(k) = b.filter(|&k| !placed[k]) {
            if chain.contains(&k) {
                return Err(ModelError::Invalid(format!(
                    "tree joints form a cycle through body '{}'",
                    name(k)
                )));
            }
            chain.push(k);
            b = tree_joint[k].and_then(|j| def.joints[j].parent);
        }
        for &k in chain.iter().rev() {
            placed[k] = true;
            order.push(k);
        }
    }
    Ok(TreeOrder {
        order,
        tree_joint,
        free,
        loop_joints,
    })
}

/// Initial coordinates (len `nq`) and rates (len `dof`) of a joint; spherical coordinates are
/// the quaternion `[w, x, y, z]`, its rates the relative angular velocity in the child frame.
///
/// # Errors
/// [`ModelError::Invalid`] for wrong lengths, non-finite values, a zero quaternion, or a
/// spherical initial state on another joint type.
pub fn joint_initial(def: &JointDef) -> Result<(Vec<f64>, Vec<f64>), ModelError> {
    let bad = |what: String| ModelError::Invalid(format!("joint '{}': {what}", def.name));
    let (nq, nd) = (def.kind.nq(), def.kind.dof());
    let (mut q, qd) = match &def.initial {
        JointInitial::Spherical { quat, w } if def.kind == JointType::Spherical => {
            (quat.to_vec(), w.as_slice().to_vec())
        }
        JointInitial::Spherical { .. } => {
            return Err(bad(
                "a quaternion initial state needs a spherical joint".into()
            ))
        }
        JointInitial::Coords { q, qd } => (
            if q.is_empty() {
                zeros_or_identity(def.kind)
            } else {
                q.clone()
            },
            if qd.is_empty() {
                vec![0.0; nd]
            } else {
                qd.clone()
            },
        ),
    };
    if q.len() != nq || qd.len() != nd {
        return Err(bad(format!(
            "initial q needs {nq} and qd {nd} values, got {} and {}",
            q.len(),
            qd.len()
        )));
    }
    if !q.iter().chain(&qd).all(|x| x.is_finite()) {
        return Err(bad("initial values must be finite".into()));
    }
    if def.kind == JointType::Spherical {
        let norm = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm < 1e-12 {
            return Err(bad("initial quaternion must be non-zero".into()));
        }
        q.iter_mut().for_each(|x| *x /= norm);
    }
    Ok((q, qd))
}

fn zeros_or_identity(kind: JointType) -> Vec<f64> {
    let mut q = vec![0.0; kind.nq()];
    if kind == JointType::Spherical {
        q[0] = 1.0;
    }
    q
}

/// Relative motion of a joint in the user's joint frame: rotation `M(q)`, translation `τ(q)`
/// (m), relative angular velocity `ω_rel` (rad/s) and translation rate `τ̇` (m/s), all in the
/// parent joint frame; `s` is the joint's internal frame `S`.
#[must_use]
pub fn joint_motion(kind: JointType, s: &Mat3, q: &[f64], qd: &[f64]) -> (Mat3, Vec3, Vec3, Vec3) {
    let (e1, e2, n) = (
        s.column(0).into_owned(),
        s.column(1).into_owned(),
        s.column(2).into_owned(),
    );
    let z = Vec3::zeros();
    match kind {
        JointType::Revolute => (exp_so3(&(n * q[0])), z, n * qd[0], z),
        JointType::Prismatic => (Mat3::identity(), n * q[0], z, n * qd[0]),
        JointType::Cylindrical => (exp_so3(&(n * q[1])), n * q[0], n * qd[1], n * qd[0]),
        JointType::Universal => {
            let ra = exp_so3(&(e1 * q[0]));
            (
                ra * exp_so3(&(e2 * q[1])),
                z,
                e1 * qd[0] + ra * e2 * qd[1],
                z,
            )
        }
        JointType::Planar => (
            exp_so3(&(n * q[2])),
            e1 * q[0] + e2 * q[1],
            n * qd[2],
            e1 * qd[0] + e2 * qd[1],
        ),
        JointType::Spherical => {
            let m = quat_to_matrix(&[q[0], q[1], q[2], q[3]]);
            let w = m * Vec3::new(qd[0], qd[1], qd[2]);
            (m, z, w, z)
        }
        JointType::Fixed => (Mat3::identity(), z, z, z),
    }
}

/// Initial coordinates `q0` and velocities `v0` (12 per body, layout of `body.rs`), from the
/// tree joints' initial values and the free bodies' poses and twists. Directors are products
/// of exact rotations (orthonormal to round-off); `v0 = P(q0) t0` from propagated twists.
///
/// # Errors
/// [`ModelError::Invalid`] from [`tree_order`], [`joint_initial`], [`joint_frame`],
/// `BodyInertia::new`, or non-orthonormal frame rotations.
pub fn initial_configuration(def: &ModelDef) -> Result<(Vec<f64>, Vec<f64>), ModelError> {
    let tree = tree_order(def)?;
    let n = def.bodies.len();
    let inertia = def
        .bodies
        .iter()
        .map(BodyInertia::new)
        .collect::<Result<Vec<_>, _>>()?;
    let mut pose = vec![(Vec3::zeros(), Mat3::identity()); n];
    let mut twist = vec![(Vec3::zeros(), Vec3::zeros()); n];
    for &b in &tree.order {
        if let Some(j) = tree.tree_joint[b] {
            let jd = &def.joints[j];
            check_rotation(
                &jd.parent_frame.rotation,
                &format!("joint '{}' parent frame", jd.name),
            )?;
            check_rotation(
                &jd.child_frame.rotation,
                &format!("joint '{}' child frame", jd.name),
            )?;
            let s = joint_frame(jd)?;
            let (q, qd) = joint_initial(jd)?;
            let ((o_p, r_p), (v_p, w_p)) = match jd.parent {
                Some(p) => (pose[p], twist[p]),
                None => (
                    (Vec3::zeros(), Mat3::identity()),
                    (Vec3::zeros(), Vec3::zeros()),
                ),
            };
            // parent joint frame, then the child joint frame, then the child body frame
            let (r_j, arm) = (
                r_p * jd.parent_frame.rotation,
                r_p * jd.parent_frame.translation,
            );
            let (o_j, v_j) = (o_p + arm, v_p + w_p.cross(&arm));
            let (m, tau, w_rel, tau_d) = joint_motion(jd.kind, &s, &q, &qd);
            let r_c = r_j * m;
            let (o_c, w_c) = (o_j + r_j * tau, w_p + r_j * w_rel);
            let v_c = v_j + w_p.cross(&(r_j * tau)) + r_j * tau_d;
            let r_b = r_c * jd.child_frame.rotation.transpose();
            let o_b = o_c - r_b * jd.child_frame.translation;
            pose[b] = (o_b, r_b);
            twist[b] = (v_c + w_c.cross(&(o_b - o_c)), w_c);
        } else if let Some(k) = tree.free[b] {
            let f = &def.free_bodies[k];
            check_rotation(
                &f.orientation,
                &format!("body '{}' orientation", def.bodies[b].name),
            )?;
            // re-project through the quaternion so that the directors are orthonormal to round-off
            let r = quat_to_matrix(&crate::math::matrix_to_quat(&f.orientation));
            let vals = [f.position, f.velocity, f.angular_velocity];
            if !vals.iter().all(|v| v.iter().all(|x| x.is_finite())) {
                return Err(ModelError::Invalid(format!(
                    "body '{}': initial state must be finite",
                    def.bodies[b].name
                )));
            }
            pose[b] = (f.position, r);
            twist[b] = (f.velocity, f.angular_velocity);
        }
    }
    let (mut q0, mut v0) = (vec![0.0; 12 * n], vec![0.0; 12 * n]);
    for b in 0..n {
        let q = inertia[b].coords_from_frame(&pose[b].0, &pose[b].1);
        let v = inertia[b].velocity_from_twist(&q, &twist[b].0, &twist[b].1);
        q0[12 * b..12 * b + 12].copy_from_slice(&q);
        v0[12 * b..12 * b + 12].copy_from_slice(&v);
    }
    Ok((q0, v0))
}

#[cfg(test)]
#[path = "kinematics_tests.rs"]
mod tests;
