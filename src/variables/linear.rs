//! Which output variables a linear model can differentiate: the variable table's accessors
//! mapped to `mechanics::Quantity`.

use super::types::Accessor;
use crate::mechanics::Quantity;

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
        Accessor::Energy => Quantity::Energy,
        Accessor::P(i) => Quantity::P(i),
        Accessor::L(i) => Quantity::L(i),
        _ => return None,
    })
}
