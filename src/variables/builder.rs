//! The pieces the table is made of: the builder that numbers variables as they are added,
//! and the words and indices of joint coordinates in names (interface.md §3).

use super::types::{Accessor, Causality, Initial, VarType, Variability, Variable};
use crate::mechanics::JointType;

/// What a joint coordinate measures.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Coord {
    Angle,
    Slide,
}

/// Coordinate kinds of a joint type in `q` order (spherical: none, it has a quaternion).
pub(super) fn coords(kind: JointType) -> &'static [Coord] {
    use Coord::{Angle, Slide};
    match kind {
        JointType::Revolute => &[Angle],
        JointType::Prismatic => &[Slide],
        JointType::Cylindrical => &[Slide, Angle],
        JointType::Universal => &[Angle, Angle],
        JointType::Planar => &[Slide, Slide, Angle],
        JointType::Spherical | JointType::Fixed => &[],
    }
}

/// `[k]` (1-based) when there are several, else nothing.
pub(super) fn index(k: usize, n: usize) -> String {
    if n == 1 {
        String::new()
    } else {
        format!("[{}]", k + 1)
    }
}

pub(super) const XYZ: [&str; 3] = ["x", "y", "z"];

pub(super) fn coord_words(kind: JointType, k: usize) -> &'static str {
    match (kind, k) {
        (JointType::Revolute, _) => "angle about the axis",
        (JointType::Prismatic, _) => "slide along the axis",
        (JointType::Cylindrical, 0) => "slide along the axis",
        (JointType::Cylindrical, _) => "angle about the axis",
        (JointType::Universal, 0) => "angle about axis",
        (JointType::Universal, _) => "angle about axis2",
        (JointType::Planar, 0) => "x offset in the joint plane",
        (JointType::Planar, 1) => "y offset in the joint plane",
        _ => "angle about the plane normal",
    }
}

/// Accumulates variables; the value reference is the position.
pub(super) struct Builder {
    pub(super) vars: Vec<Variable>,
}

impl Builder {
    #[allow(clippy::too_many_arguments)]
    pub(super) fn push(
        &mut self,
        name: String,
        causality: Causality,
        variability: Variability,
        start: Option<f64>,
        unit: Option<&'static str>,
        description: String,
        accessor: Accessor,
    ) {
        let initial = match causality {
            Causality::Input => Initial::None,
            Causality::Output => Initial::Calculated,
            Causality::Parameter => Initial::Exact,
        };
        let ty = if matches!(
            accessor,
            Accessor::Order | Accessor::MaxSubsteps | Accessor::Stages
        ) {
            VarType::Integer
        } else {
            VarType::Real
        };
        let display_unit = if unit == Some("rad") {
            Some("deg")
        } else {
            None
        };
        let vr = u32::try_from(self.vars.len()).unwrap_or(u32::MAX);
        self.vars.push(Variable {
            vr,
            name,
            ty,
            causality,
            variability,
            initial,
            start,
            unit,
            display_unit,
            description,
            accessor,
        });
    }

    pub(super) fn input(
        &mut self,
        name: String,
        unit: &'static str,
        description: String,
        slot: usize,
    ) {
        self.push(
            name,
            Causality::Input,
            Variability::Continuous,
            Some(0.0),
            Some(unit),
            description,
            Accessor::Input(slot),
        );
    }

    pub(super) fn output(
        &mut self,
        name: String,
        unit: &'static str,
        description: String,
        accessor: Accessor,
    ) {
        self.push(
            name,
            Causality::Output,
            Variability::Continuous,
            None,
            Some(unit),
            description,
            accessor,
        );
    }

    pub(super) fn fixed(
        &mut self,
        name: String,
        value: f64,
        unit: Option<&'static str>,
        description: String,
        accessor: Accessor,
    ) {
        self.push(
            name,
            Causality::Parameter,
            Variability::Fixed,
            Some(value),
            unit,
            description,
            accessor,
        );
    }
}
