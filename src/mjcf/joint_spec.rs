//! One MuJoCo joint (hinge, slide, ball) as a spec `[[joint]]`: its frame (the module formulas
//! of `lower`: `O_k = M_{k−1} ∘ T(a_k) ∘ R(n_k, −ref_k)` for a hinge, `M_{k−1} ∘ T(a_k − n_k
//! ref_k)` for a slide, `M_{k−1} ∘ T(a_k)` for a ball), its stops, spring, damper, armature,
//! friction and actuator force range, its initial `q = ref`, and notes on what a spherical joint
//! cannot take or takes differently.

use super::model::{Joint, JointType};
use crate::import::frame::Iso;
use crate::math::{exp_so3, Vec3};
use crate::spec::{Coords, InitialSpec, JointKind, JointSpec};

/// Where a joint sits: its parent's and child's spec names, and `M_{k−1}`, the frame it starts
/// from (the MuJoCo body frame in the parent's triad frame for the body's first joint, else
/// `T(−a_{k−1})`).
pub(super) struct Ends {
    pub parent: String,
    pub child: String,
    pub frame: Iso,
}

/// The spec joint `id` of MuJoCo joint `j` at `ends`, and `M_k = T(−a_k)`, the frame the body's
/// next joint starts from; what is not reproduced goes to `notes`.
pub(super) fn joint(
    j: &Joint,
    id: String,
    ends: Ends,
    notes: &mut Vec<String>,
) -> (JointSpec, Iso) {
    let anchor = Iso::shift(j.pos);
    let (kind, joint_frame) = match j.kind {
        JointType::Hinge => (
            JointKind::Revolute,
            ends.frame.then(&anchor).then(&Iso {
                r: exp_so3(&(j.axis * -j.reference)),
                p: Vec3::zeros(),
            }),
        ),
        JointType::Slide => (
            JointKind::Prismatic,
            ends.frame.then(&Iso::shift(j.pos - j.axis * j.reference)),
        ),
        _ => (JointKind::Spherical, ends.frame.then(&anchor)),
    };
    let movable = kind != JointKind::Spherical;
    let what = format!("joint '{}'", j.name.as_deref().unwrap_or(&id));
    // armature and frictionloss are triad's armature and Coulomb friction; a ball joint's
    // armature is noted (triad's spherical joints take none), its frictionloss is a cone
    if !movable && j.armature > 0.0 {
        notes.push(format!("{what}: armature=\"{}\" of a ball joint is not modelled: the joint is lighter than in MuJoCo", j.armature));
    }
    if !movable && j.frictionloss > 0.0 {
        notes.push(format!(
            "{what}: frictionloss=\"{}\" of a ball joint limits the friction torque's magnitude (a cone |τ| ≤ {0}); MuJoCo limits each of its three axes",
            j.frictionloss
        ));
    }
    if j.springref != 0.0 && j.stiffness > 0.0 && movable {
        notes.push(format!(
            "{what}: the spring acts about q = 0, not about springref = {} (triad's joint spring has no rest position yet)",
            j.springref
        ));
    }
    if !movable && j.stiffness > 0.0 {
        notes.push(format!("{what}: stiffness of a ball joint is not modelled (triad's spherical joints take no spring)"));
    }
    if !movable && j.range.is_some() {
        notes.push(format!(
            "{what}: the cone limit (range) of a ball joint is not modelled"
        ));
    }
    let initial = (j.kind == JointType::Hinge || j.kind == JointType::Slide)
        .then_some(j.reference)
        .filter(|r| *r != 0.0)
        .map(|r| InitialSpec {
            q: Some(Coords::Scalar(r)),
            ..InitialSpec::default()
        });
    let (lower, upper) = match j.range {
        Some([lo, hi]) if movable && lo < hi => (Some(lo), Some(hi)),
        Some([lo, hi]) if movable => {
            notes.push(format!("{what}: range {lo} {hi} is empty: no stops"));
            (None, None)
        }
        _ => (None, None),
    };
    let joint = JointSpec {
        name: id.clone(),
        kind,
        parent: ends.parent,
        child: ends.child,
        origin: joint_frame.origin_spec(),
        child_origin: None,
        axis: movable.then_some([j.axis.x, j.axis.y, j.axis.z]),
        axis2: None,
        actuated: false,
        damping: j.damping,
        stiffness: if movable { j.stiffness } else { 0.0 },
        armature: if movable { j.armature } else { 0.0 },
        friction: j.frictionloss,
        lower,
        upper,
        effort: None,
        actuatorfrcrange: j.actuatorfrcrange.filter(|_| movable),
        stop_stiffness: None,
        stop_damping: None,
        initial,
        description: if j.name.as_deref() == Some(id.as_str()) {
            String::new()
        } else {
            format!("MJCF joint \"{}\"", j.name.as_deref().unwrap_or(""))
        },
    };
    (joint, Iso::shift(-j.pos))
}
