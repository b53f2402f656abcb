//! Construction of the variable table from a model definition (interface.md §3 names).

use super::{Accessor, Causality, Initial, VarType, Variability, Variable, VariableTable};
use crate::mechanics::{JointType, ModelDef, SolverSettings};

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
        let ty = if accessor == Accessor::Order {
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

    fn input(&mut self, name: String, unit: &'static str, description: String, slot: usize) {
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

    fn output(
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

fn inputs(b: &mut Builder, def: &ModelDef) {
    // order of `Model::inputs`: joint actuators in joint order, then body loads
    let mut slot = 0;
    for j in def.joints.iter().filter(|j| j.actuated) {
        let n = &j.name;
        let frame = "applied to the child and, reversed, to the parent";
        match j.kind {
            JointType::Revolute => {
                b.input(
                    format!("joint.{n}.tau"),
                    "N.m",
                    format!("actuator torque of revolute joint {n} about its axis, {frame}"),
                    slot,
                );
                slot += 1;
            }
            JointType::Prismatic => {
                b.input(
                    format!("joint.{n}.f"),
                    "N",
                    format!("actuator force of prismatic joint {n} along its axis, {frame}"),
                    slot,
                );
                slot += 1;
            }
            JointType::Cylindrical => {
                b.input(
                    format!("joint.{n}.f"),
                    "N",
                    format!("actuator force of cylindrical joint {n} along its axis, {frame}"),
                    slot,
                );
                b.input(
                    format!("joint.{n}.tau"),
                    "N.m",
                    format!("actuator torque of cylindrical joint {n} about its axis, {frame}"),
                    slot + 1,
                );
                slot += 2;
            }
            JointType::Universal => {
                for (k, ax) in ["axis", "axis2"].iter().enumerate() {
                    b.input(
                        format!("joint.{n}.tau[{}]", k + 1),
                        "N.m",
                        format!("actuator torque of universal joint {n} about {ax}, {frame}"),
                        slot + k,
                    );
                }
                slot += 2;
            }
            JointType::Spherical => {
                for (k, c) in XYZ.iter().enumerate() {
                    b.input(format!("joint.{n}.tau[{}]", k + 1), "N.m", format!("actuator torque of spherical joint {n}, {c} component in the parent joint frame, {frame}"), slot + k);
                }
                slot += 3;
            }
            JointType::Planar | JointType::Fixed => {}
        }
    }
    for l in &def.loads {
        let name = def.bodies.get(l.body).map_or("?", |bd| bd.name.as_str());
        if l.torque {
            for (i, c) in XYZ.iter().enumerate() {
                b.input(
                    format!("body.{name}.torque[{}]", i + 1),
                    "N.m",
                    format!("external torque on body {name}, {c} component, world frame"),
                    slot + i,
                );
            }
            slot += 3;
        }
        if l.force {
            for (i, c) in XYZ.iter().enumerate() {
                b.input(format!("body.{name}.force[{}]", i + 1), "N", format!("external force on body {name} at its centre of mass, {c} component, world frame"), slot + i);
            }
            slot += 3;
        }
    }
}

fn outputs(b: &mut Builder, def: &ModelDef) {
    for (body, bd) in def.bodies.iter().enumerate() {
        let n = &bd.name;
        for (i, c) in XYZ.iter().enumerate() {
            b.output(
                format!("body.{n}.r[{}]", i + 1),
                "m",
                format!("origin of body {n}'s frame, {c} component, world frame"),
                Accessor::BodyR { body, i },
            );
        }
        for i in 0..3 {
            for j in 0..3 {
                b.output(format!("body.{n}.R[{},{}]", i + 1, j + 1), "1", format!("rotation world <- body {n}, row {} column {} (column j is body axis j in world coordinates)", i + 1, j + 1), Accessor::BodyRot { body, i, j });
            }
        }
        for (i, c) in XYZ.iter().enumerate() {
            b.output(
                format!("body.{n}.v[{}]", i + 1),
                "m/s",
                format!("velocity of body {n}'s frame origin, {c} component, world frame"),
                Accessor::BodyV { body, i },
            );
        }
        for (i, c) in XYZ.iter().enumerate() {
            b.output(
                format!("body.{n}.w[{}]", i + 1),
                "rad/s",
                format!("angular velocity of body {n}, {c} component, world frame"),
                Accessor::BodyW { body, i },
            );
        }
    }
    for (joint, j) in def.joints.iter().enumerate() {
        let n = &j.name;
        if j.kind == JointType::Spherical {
            for (k, c) in ["w", "x", "y", "z"].iter().enumerate() {
                b.output(format!("joint.{n}.quat[{}]", k + 1), "1", format!("orientation of joint {n}'s child frame relative to its joint frame, quaternion component {c}"), Accessor::JointQ { joint, k });
            }
            for (k, c) in XYZ.iter().enumerate() {
                b.output(format!("joint.{n}.w[{}]", k + 1), "rad/s", format!("angular velocity of joint {n}'s child relative to its parent, {c} component, child frame"), Accessor::JointQd { joint, k });
            }
            continue;
        }
        let cs = coords(j.kind);
        for (k, c) in cs.iter().enumerate() {
            let (unit, what) = if *c == Coord::Angle {
                ("rad", " (continuous, not wrapped)")
            } else {
                ("m", "")
            };
            b.output(
                format!("joint.{n}.q{}", index(k, cs.len())),
                unit,
                format!("joint {n} coordinate: {}{what}", coord_words(j.kind, k)),
                Accessor::JointQ { joint, k },
            );
        }
        for (k, c) in cs.iter().enumerate() {
            let unit = if *c == Coord::Angle { "rad/s" } else { "m/s" };
            b.output(
                format!("joint.{n}.qd{}", index(k, cs.len())),
                unit,
                format!("joint {n} rate: d/dt of the {}", coord_words(j.kind, k)),
                Accessor::JointQd { joint, k },
            );
        }
    }
    b.output(
        "system.energy".into(),
        "J",
        "kinetic + potential energy (gravity and joint springs)".into(),
        Accessor::Energy,
    );
    b.output("system.work".into(), "J", "work of the inputs minus energy dissipated by damping since the start; energy - work stays constant".into(), Accessor::Work);
    for (i, c) in XYZ.iter().enumerate() {
        b.output(
            format!("system.p[{}]", i + 1),
            "N.s",
            format!("total linear momentum, {c} component, world frame"),
            Accessor::P(i),
        );
    }
    for (i, c) in XYZ.iter().enumerate() {
        b.output(
            format!("system.L[{}]", i + 1),
            "N.m.s",
            format!("total angular momentum about the world origin, {c} component, world frame"),
            Accessor::L(i),
        );
    }
    b.output(
        "system.constraint_residual".into(),
        "1",
        "largest constraint violation after the last step".into(),
        Accessor::ConstraintResidual,
    );
}

/// Builds the table: inputs, outputs, parameters (see [`VariableTable::new`]).
pub(super) fn build(def: &ModelDef, settings: &SolverSettings) -> VariableTable {
    let mut b = Builder { vars: Vec::new() };
    inputs(&mut b, def);
    outputs(&mut b, def);
    super::params::parameters(&mut b, def, settings);
    VariableTable { vars: b.vars }
}
