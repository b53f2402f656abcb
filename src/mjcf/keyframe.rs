//! The initial state: `qpos0` (each hinge and slide at its `ref`, each free body where the
//! model puts it), or a `<key>`'s `qpos` and `qvel` read in MuJoCo's order (a free joint: 3
//! positions, a quaternion, 3 velocities in the world frame and 3 angular velocities in the
//! body frame; a ball: a quaternion and the angular velocity in the child frame; hinges and
//! slides: one each).

use super::lower::Slot;
use super::model::{JointType, Model};
use super::options::ImportOptions;
use crate::math::{Mat3, Vec3};
use crate::spec::{Coords, InitialSpec, OrientationSpec, Problem, Spec};

/// The numbers a joint takes in `qpos` and in `qvel`.
fn sizes(s: &Slot) -> (usize, usize) {
    match s {
        Slot::Free(_) => (7, 6),
        Slot::Joint(_, JointType::Ball) => (4, 3),
        Slot::Joint(..) => (1, 1),
    }
}

/// Sets the initial state: `qpos0` (each hinge and slide at its `ref`, each free body where the
/// model puts it), or the keyframe `opts.keyframe`.
pub(super) fn initial_state(
    m: &Model,
    opts: &ImportOptions,
    slots: &[Slot],
    spec: &mut Spec,
    problems: &mut Vec<Problem>,
) {
    let Some(name) = &opts.keyframe else { return };
    let Some(key) = m.keys.iter().find(|k| k.name == *name) else {
        let names: Vec<&str> = m.keys.iter().map(|k| k.name.as_str()).collect();
        problems.push(Problem::new(
            "",
            format!(
                "--keyframe {name}: the model has no <key name=\"{name}\"> (keys: {}){}",
                if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(", ")
                },
                crate::spec::did_you_mean(name, names.iter().copied())
            ),
        ));
        return;
    };
    let nq: usize = slots.iter().map(|s| sizes(s).0).sum();
    let nv: usize = slots.iter().map(|s| sizes(s).1).sum();
    let check = |v: &Option<Vec<f64>>, n: usize, what: &str, problems: &mut Vec<Problem>| match v {
        Some(v) if v.len() != n => {
            problems.push(Problem::new(
                key.at.clone(),
                format!("{what} has {} numbers; the model has {n}", v.len()),
            ));
            false
        }
        _ => true,
    };
    if !check(&key.qpos, nq, "qpos", problems) || !check(&key.qvel, nv, "qvel", problems) {
        return;
    }
    let (mut iq, mut iv) = (0, 0);
    for s in slots {
        let q = |k: usize| key.qpos.as_ref().map(|v| v[iq + k]);
        let v = |k: usize| key.qvel.as_ref().map_or(0.0, |v| v[iv + k]);
        match *s {
            Slot::Free(b) => {
                let body = &mut spec.body[b];
                let r = match key.qpos.as_ref() {
                    Some(p) => {
                        body.position = Some([p[iq], p[iq + 1], p[iq + 2]]);
                        let quat = [p[iq + 3], p[iq + 4], p[iq + 5], p[iq + 6]];
                        body.orientation = Some(OrientationSpec::Quat(quat));
                        crate::math::quat_to_matrix(&quat)
                    }
                    None => match &body.orientation {
                        Some(OrientationSpec::Quat(q)) => crate::math::quat_to_matrix(q),
                        _ => Mat3::identity(),
                    },
                };
                let w_local = Vec3::new(v(3), v(4), v(5));
                let w = r * w_local;
                body.velocity = Some([v(0), v(1), v(2)]);
                body.angular_velocity = Some([w.x, w.y, w.z]);
            }
            Slot::Joint(j, JointType::Ball) => {
                let quat = q(0).map(|_| {
                    [
                        q(0).unwrap_or(1.0),
                        q(1).unwrap_or(0.0),
                        q(2).unwrap_or(0.0),
                        q(3).unwrap_or(0.0),
                    ]
                });
                spec.joint[j].initial = Some(InitialSpec {
                    quat: Some(quat.unwrap_or([1.0, 0.0, 0.0, 0.0])),
                    w: Some([v(0), v(1), v(2)]),
                    ..InitialSpec::default()
                });
            }
            Slot::Joint(j, _) => {
                let q0 = q(0).or_else(|| {
                    spec.joint[j].initial.as_ref().and_then(|i| match i.q {
                        Some(Coords::Scalar(x)) => Some(x),
                        _ => None,
                    })
                });
                spec.joint[j].initial = Some(InitialSpec {
                    q: Some(Coords::Scalar(q0.unwrap_or(0.0))),
                    qd: Some(Coords::Scalar(v(0))),
                    ..InitialSpec::default()
                });
            }
        }
        let (dq, dv) = sizes(s);
        iq += dq;
        iv += dv;
    }
}
