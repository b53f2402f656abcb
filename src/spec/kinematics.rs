//! Forward kinematics of a lowered model at its initial values, used to check that every
//! loop-closing joint is satisfied by the initial pose before the mechanics is asked to build
//! the model. The residuals are those of the joint rows and do not depend on how the mechanics
//! completes the joint axis to a frame.

use crate::math::{exp_so3, quat_to_matrix, Mat3, Vec3};
use crate::mechanics::{Frame, JointDef, JointInitial, JointType, ModelDef};

/// A rigid placement in the world: rotation world ← local and origin.
#[derive(Clone, Copy, Debug)]
struct Pose {
    rot: Mat3,
    pos: Vec3,
}

impl Pose {
    fn then(&self, f: &Frame) -> Pose {
        Pose {
            rot: self.rot * f.rotation,
            pos: self.pos + self.rot * f.translation,
        }
    }

    fn then_inverse(&self, f: &Frame) -> Pose {
        let rot_t = f.rotation.transpose();
        Pose {
            rot: self.rot * rot_t,
            pos: self.pos - self.rot * rot_t * f.translation,
        }
    }
}

/// Two unit vectors completing `u` to a right-handed orthonormal frame; `(x, y)` of the joint
/// frame when `u` is its z axis.
pub(crate) fn plane_basis(u: &Vec3) -> (Vec3, Vec3) {
    let seed = if u.z.abs() > 0.9 {
        Vec3::x()
    } else {
        Vec3::z()
    };
    let e1 = if u.z.abs() > 0.9 {
        (seed - u * u.dot(&seed)).normalize()
    } else {
        u.cross(&seed).normalize()
    };
    let e2 = u.cross(&e1);
    (e1, e2)
}

/// Placement of the child joint frame relative to the parent joint frame at the initial values.
fn joint_motion(j: &JointDef) -> Frame {
    let q = |k: usize| match &j.initial {
        JointInitial::Coords { q, .. } => q.get(k).copied().unwrap_or(0.0),
        JointInitial::Spherical { .. } => 0.0,
    };
    let u = j.axis;
    let rot_about = |v: &Vec3, a: f64| exp_so3(&(v * a));
    let (rotation, translation) = match j.kind {
        JointType::Revolute => (rot_about(&u, q(0)), Vec3::zeros()),
        JointType::Prismatic => (Mat3::identity(), u * q(0)),
        JointType::Cylindrical => (rot_about(&u, q(1)), u * q(0)),
        JointType::Universal => (
            rot_about(&u, q(0)) * rot_about(&j.axis2, q(1)),
            Vec3::zeros(),
        ),
        JointType::Spherical => match &j.initial {
            JointInitial::Spherical { quat, .. } => (quat_to_matrix(quat), Vec3::zeros()),
            JointInitial::Coords { .. } => (Mat3::identity(), Vec3::zeros()),
        },
        JointType::Planar => {
            let (e1, e2) = plane_basis(&u);
            (rot_about(&u, q(2)), e1 * q(0) + e2 * q(1))
        }
        JointType::Fixed => (Mat3::identity(), Vec3::zeros()),
    };
    Frame {
        translation,
        rotation,
    }
}

/// Initial world poses of every body (`None` for a body no tree path reaches).
fn body_poses(def: &ModelDef) -> Vec<Option<Pose>> {
    let mut poses: Vec<Option<Pose>> = vec![None; def.bodies.len()];
    for f in &def.free_bodies {
        if let Some(p) = poses.get_mut(f.body) {
            *p = Some(Pose {
                rot: f.orientation,
                pos: f.position,
            });
        }
    }
    let world = Pose {
        rot: Mat3::identity(),
        pos: Vec3::zeros(),
    };
    // sweep until no tree joint can be placed (at most one sweep per tree level)
    loop {
        let mut progress = false;
        for j in def.joints.iter().filter(|j| !j.loop_closing) {
            if poses.get(j.child).is_some_and(Option::is_some) {
                continue;
            }
            let parent = match j.parent {
                None => Some(world),
                Some(b) => poses.get(b).copied().flatten(),
            };
            if let Some(parent) = parent {
                let child = parent
                    .then(&j.parent_frame)
                    .then(&joint_motion(j))
                    .then_inverse(&j.child_frame);
                if let Some(slot) = poses.get_mut(j.child) {
                    *slot = Some(child);
                    progress = true;
                }
            }
        }
        if !progress {
            return poses;
        }
    }
}

fn max_abs(m: &Mat3) -> f64 {
    m.iter().fold(0.0_f64, |a, x| a.max(x.abs()))
}

/// Largest violation of each loop-closing joint's rows at the initial pose: `(joint index in
/// def, residual)` (m for positions, 1 for directions).
pub(crate) fn loop_residuals(def: &ModelDef) -> Vec<(usize, f64)> {
    let poses = body_poses(def);
    let world = Pose {
        rot: Mat3::identity(),
        pos: Vec3::zeros(),
    };
    let mut out = Vec::new();
    for (k, j) in def
        .joints
        .iter()
        .enumerate()
        .filter(|(_, j)| j.loop_closing)
    {
        let parent = match j.parent {
            None => Some(world),
            Some(b) => poses.get(b).copied().flatten(),
        };
        let (Some(parent), Some(Some(child))) = (parent, poses.get(j.child).copied()) else {
            continue;
        };
        let a = parent.then(&j.parent_frame);
        let b = child.then(&j.child_frame);
        let r = b.pos - a.pos;
        let (ua, ub) = (a.rot * j.axis, b.rot * j.axis);
        let off_axis = (r - ua * r.dot(&ua)).norm();
        let parallel = ua.cross(&ub).norm();
        let residual = match j.kind {
            JointType::Spherical => r.norm(),
            JointType::Revolute => r.norm().max(parallel),
            JointType::Prismatic => off_axis.max(max_abs(&(a.rot - b.rot))),
            JointType::Cylindrical => off_axis.max(parallel),
            JointType::Universal => r.norm().max(ua.dot(&(b.rot * j.axis2)).abs()),
            JointType::Planar => r.dot(&ua).abs().max(parallel),
            JointType::Fixed => r.norm().max(max_abs(&(a.rot - b.rot))),
        };
        out.push((k, residual));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_basis_is_right_handed() {
        for u in [Vec3::z(), Vec3::x(), Vec3::new(0.3, -0.5, 0.8).normalize()] {
            let (e1, e2) = plane_basis(&u);
            assert!((e1.cross(&e2) - u).norm() < 1e-14);
        }
        let (e1, e2) = plane_basis(&Vec3::z());
        assert!((e1 - Vec3::x()).norm() < 1e-15 && (e2 - Vec3::y()).norm() < 1e-15);
    }
}

#[cfg(test)]
mod shipped {
    use super::loop_residuals;
    use crate::spec::schema::{Format, Spec};
    use crate::spec::shipped::bundled;

    #[test]
    fn shipped_loops_close_to_round_off() {
        for name in ["four_bar", "slider_crank"] {
            let (_, text) = bundled().iter().find(|(n, _)| *n == name).unwrap();
            let (def, _) = Spec::from_str(text, Format::Toml, name)
                .unwrap()
                .lower()
                .unwrap();
            let res = loop_residuals(&def);
            assert_eq!(res.len(), 1, "{name}");
            assert!(res[0].1 < 1e-14, "{name}: loop residual {:e}", res[0].1);
        }
    }
}
