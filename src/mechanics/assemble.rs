//! Model set-up: joint rows and coordinates, tree order, redundant-row detection and the initial
//! state (free bodies here; jointed bodies from `kinematics`).

use super::constraint::Nodes;
use super::def::JointType;
use super::error::ModelError;
use super::model::Model;
use crate::math::Vec3;

/// Fills the joint, tree and initial-state parts of `model`.
pub(crate) fn build(model: &mut Model, joint_input: &[Option<usize>]) -> Result<(), ModelError> {
    let _ = joint_input;
    let def = model.def().clone();
    let nb = def.bodies.len();
    if !def.joints.is_empty() {
        return Err(ModelError::Invalid("joints are not supported yet".into()));
    }
    let _ = JointType::Fixed;
    model.order = (0..nb).collect();
    let mut given = vec![false; nb];
    for fb in &def.free_bodies {
        if fb.body >= nb {
            return Err(ModelError::Invalid(format!(
                "free-body initial state for unknown body {}",
                fb.body
            )));
        }
        given[fb.body] = true;
        let com = model.bodies[fb.body].com;
        let r = fb.orientation;
        let rc = r * com;
        let phi = fb.position + rc;
        let phid = fb.velocity + fb.angular_velocity.cross(&rc);
        let q = &mut model.q0[12 * fb.body..12 * fb.body + 12];
        let v = &mut model.v0[12 * fb.body..12 * fb.body + 12];
        write3(q, 0, &phi);
        write3(v, 0, &phid);
        for i in 0..3 {
            let d: Vec3 = r.column(i).into();
            write3(q, 3 + 3 * i, &d);
            write3(v, 3 + 3 * i, &fb.angular_velocity.cross(&d));
        }
    }
    for (b, g) in given.iter().enumerate() {
        if !g {
            // a free body without initial data rests at the origin, axes aligned
            let q = &mut model.q0[12 * b..12 * b + 12];
            for i in 0..3 {
                q[3 + 4 * i] = 1.0;
            }
            let com = model.bodies[b].com;
            write3(q, 0, &com);
        }
    }
    Ok(())
}

/// Writes `v` to `x[at..at + 3]`.
pub(crate) fn write3(x: &mut [f64], at: usize, v: &Vec3) {
    x[at] = v.x;
    x[at + 1] = v.y;
    x[at + 2] = v.z;
}

/// Reads `x[at..at + 3]`.
#[must_use]
pub(crate) fn read3(x: &[f64], at: usize) -> Vec3 {
    Vec3::new(x[at], x[at + 1], x[at + 2])
}

/// Raw (wrapped) angle of turn coordinate `dk` of joint `j`, rad.
pub(crate) fn turn_angle(model: &Model, j: usize, dk: usize, qa: &Nodes, qb: &Nodes) -> f64 {
    let _ = (model, j, dk, qa, qb);
    0.0
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
    let _ = (model, j, qa, qb, va, vb, angles, q, qd);
}
