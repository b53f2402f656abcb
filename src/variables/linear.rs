//! Which output variables a linear model can differentiate: the variable table's accessors
//! mapped to `mechanics::Quantity`.

use super::types::{Accessor, Causality, VariableTable};
use crate::mechanics::Quantity;

/// The largest `outputs × states` for which the states are declared (each output's
/// `dependencies` lists every state: beyond this the description would grow past a few MB).
pub const MAX_DEPENDENCY_ENTRIES: usize = 250_000;

/// The FMI states of a model: table indices (0-based) of each joint coordinate `joint.J.q`,
/// its rate `joint.J.qd` (the derivative of the coordinate) and its acceleration
/// `joint.J.qdd` (the derivative of the rate), aligned; the state vector is `(q…, qd…)`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct States {
    /// Coordinates.
    pub q: Vec<usize>,
    /// Rates.
    pub qd: Vec<usize>,
    /// Accelerations.
    pub qdd: Vec<usize>,
}

/// The states a model declares: the joints with accelerations `joint.J.qdd` (in the table of
/// models without contact or joint friction: every joint but spherical, fixed and
/// loop-closing ones), with closed loops or couplings only the independent coordinates of
/// `VariableTable::loops`, within [`MAX_DEPENDENCY_ENTRIES`]; `None` otherwise (then no
/// directional derivatives either).
#[must_use]
pub fn states(table: &VariableTable) -> Option<States> {
    let find = |want: Accessor| table.vars.iter().position(|v| v.accessor == want);
    let mut st = States {
        q: Vec::new(),
        qd: Vec::new(),
        qdd: Vec::new(),
    };
    let is_state = |joint: usize, k: usize| {
        table
            .loops
            .as_ref()
            .is_none_or(|l| l.independent.contains(&(joint, k)))
    };
    for (i, v) in table.vars.iter().enumerate() {
        if let Accessor::JointQdd { joint, k } = v.accessor {
            if !is_state(joint, k) {
                continue;
            }
            st.q.push(find(Accessor::JointQ { joint, k })?);
            st.qd.push(find(Accessor::JointQd { joint, k })?);
            st.qdd.push(i);
        }
    }
    let outputs = table.with_causality(Causality::Output).count();
    (!st.q.is_empty() && outputs * 2 * st.q.len() <= MAX_DEPENDENCY_ENTRIES).then_some(st)
}

/// Whether output `acc` of `table`'s model has directional derivatives when the model declares
/// states: a [`quantity`], but not the coordinate or rate of a loop-closing joint (no
/// coordinate of the tree: `LoopStates::closing`).
#[must_use]
pub fn differentiable(table: &VariableTable, acc: Accessor) -> bool {
    let closing = |j: usize| table.loops.as_ref().is_some_and(|l| l.closing.contains(&j));
    match acc {
        Accessor::JointQ { joint, .. } | Accessor::JointQd { joint, .. } if closing(joint) => false,
        _ => quantity(acc).is_some(),
    }
}

/// The differentiable quantity behind an output accessor, if it is one (pose, twist, joint
/// coordinates and rates, energy, momenta; not `system.work`, the constraint residual or
/// contact outputs).
#[must_use]
pub fn quantity(acc: Accessor) -> Option<Quantity> {
    Some(match acc {
        Accessor::BodyR { body, i } => Quantity::BodyR(body, i),
        Accessor::BodyRot { body, i, j } => Quantity::BodyRot(body, i, j),
        Accessor::BodyV { body, i } => Quantity::BodyV(body, i),
        Accessor::BodyW { body, i } => Quantity::BodyW(body, i),
        Accessor::SiteR { site, i } => Quantity::SiteR(site, i),
        Accessor::SiteRot { site, i, j } => Quantity::SiteRot(site, i, j),
        Accessor::SiteV { site, i } => Quantity::SiteV(site, i),
        Accessor::SiteW { site, i } => Quantity::SiteW(site, i),
        Accessor::JointQ { joint, k } => Quantity::JointQ(joint, k),
        Accessor::JointQd { joint, k } => Quantity::JointQd(joint, k),
        Accessor::JointQdd { joint, k } => Quantity::JointQdd(joint, k),
        Accessor::Energy => Quantity::Energy,
        Accessor::P(i) => Quantity::P(i),
        Accessor::L(i) => Quantity::L(i),
        Accessor::ContactForce { shape, i } => Quantity::ContactForce(shape, i),
        _ => return None,
    })
}
