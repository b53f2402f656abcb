//! Construction of the variable table from a model definition (interface.md §3 names).

use super::{Accessor, Causality, Initial, VarType, Variability, Variable, VariableTable};
use crate::mechanics::{JointDef, JointInitial, JointType, ModelDef, SolverSettings};

/// What a joint coordinate measures.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Coord {
    Angle,
    Slide,
}

/// Coordinate kinds of a joint type in `q` order (spherical: none, it has a quaternion).
fn coords(kind: JointType) -> &'static [Coord] {
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
fn index(k: usize, n: usize) -> String {
    if n == 1 {
        String::new()
    } else {
        format!("[{}]", k + 1)
    }
}

const XYZ: [&str; 3] = ["x", "y", "z"];

fn coord_words(kind: JointType, k: usize) -> &'static str {
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
struct Builder {
    vars: Vec<Variable>,
}

impl Builder {
    #[allow(clippy::too_many_arguments)]
    fn push(
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

    fn fixed(
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

fn initial_value(j: &JointDef, k: usize, rate: bool) -> f64 {
    match (&j.initial, rate) {
        (JointInitial::Coords { q, .. }, false) => q.get(k).copied().unwrap_or(0.0),
        (JointInitial::Coords { qd, .. }, true) => qd.get(k).copied().unwrap_or(0.0),
        (JointInitial::Spherical { quat, .. }, false) => quat.get(k).copied().unwrap_or(0.0),
        (JointInitial::Spherical { w, .. }, true) => w.get(k).copied().unwrap_or(0.0),
    }
}

fn joint_parameters(b: &mut Builder, joint: usize, j: &JointDef) {
    let n = &j.name;
    if j.kind == JointType::Fixed {
        return;
    }
    // initial values: tree joints only (a loop-closing joint's state follows from the tree)
    if !j.loop_closing {
        if j.kind == JointType::Spherical {
            for (k, c) in ["w", "x", "y", "z"].iter().enumerate() {
                let v = initial_value(j, k, false);
                b.fixed(format!("joint.{n}.q0[{}]", k + 1), v, Some("1"), format!("initial orientation of joint {n}'s child frame relative to its joint frame, quaternion component {c}"), Accessor::Q0 { joint, k });
            }
            for (k, c) in XYZ.iter().enumerate() {
                let v = initial_value(j, k, true);
                b.fixed(format!("joint.{n}.qd0[{}]", k + 1), v, Some("rad/s"), format!("initial relative angular velocity of joint {n}, {c} component, child frame"), Accessor::Qd0 { joint, k });
            }
        } else {
            let cs = coords(j.kind);
            for (k, c) in cs.iter().enumerate() {
                let unit = if *c == Coord::Angle { "rad" } else { "m" };
                b.fixed(
                    format!("joint.{n}.q0{}", index(k, cs.len())),
                    initial_value(j, k, false),
                    Some(unit),
                    format!("initial value of joint {n}'s {}", coord_words(j.kind, k)),
                    Accessor::Q0 { joint, k },
                );
            }
            for (k, c) in cs.iter().enumerate() {
                let unit = if *c == Coord::Angle { "rad/s" } else { "m/s" };
                b.fixed(
                    format!("joint.{n}.qd0{}", index(k, cs.len())),
                    initial_value(j, k, true),
                    Some(unit),
                    format!("initial rate of joint {n}'s {}", coord_words(j.kind, k)),
                    Accessor::Qd0 { joint, k },
                );
            }
        }
    }
    let (damping_unit, stiffness_unit, per) = match j.kind {
        JointType::Prismatic => (Some("N.s/m"), Some("N/m"), "N.s/m"),
        JointType::Cylindrical | JointType::Planar => {
            (None, None, "N.m.s/rad on angles, N.s/m on slides")
        }
        _ => (Some("N.m.s"), Some("N.m"), "N.m.s/rad"),
    };
    let tunable = |b: &mut Builder, name: String, v: f64, unit, d: String, acc| {
        b.push(
            name,
            Causality::Parameter,
            Variability::Tunable,
            Some(v),
            unit,
            d,
            acc,
        )
    };
    tunable(
        b,
        format!("joint.{n}.damping"),
        j.damping,
        damping_unit,
        format!("viscous damping of joint {n} on each coordinate ({per})"),
        Accessor::Damping(joint),
    );
    if j.kind != JointType::Spherical {
        let per = per.replace(".s", "");
        tunable(
            b,
            format!("joint.{n}.stiffness"),
            j.stiffness,
            stiffness_unit,
            format!("linear stiffness of joint {n} about q = 0 on each coordinate ({per})"),
            Accessor::Stiffness(joint),
        );
    }
}

fn parameters(b: &mut Builder, def: &ModelDef, settings: &SolverSettings) {
    for (i, c) in XYZ.iter().enumerate() {
        b.fixed(
            format!("gravity[{}]", i + 1),
            def.gravity[i],
            Some("m/s2"),
            format!("gravitational acceleration, {c} component, world frame"),
            Accessor::Gravity(i),
        );
    }
    for (body, bd) in def.bodies.iter().enumerate() {
        let n = &bd.name;
        b.fixed(
            format!("body.{n}.mass"),
            bd.mass,
            Some("kg"),
            format!("mass of body {n}"),
            Accessor::Mass(body),
        );
        for i in 0..3 {
            for j in 0..3 {
                b.fixed(format!("body.{n}.inertia[{},{}]", i + 1, j + 1), bd.inertia[(i, j)], Some("kg.m2"), format!("inertia tensor of body {n} about its centre of mass, body axes, row {} column {} (setting it sets its transpose too)", i + 1, j + 1), Accessor::Inertia { body, i, j });
            }
        }
    }
    for (joint, j) in def.joints.iter().enumerate() {
        joint_parameters(b, joint, j);
    }
    b.fixed(
        "solver.max_step".into(),
        settings.max_step,
        Some("s"),
        "largest internal time step; a communication step takes ceil(H / max_step) equal sub-steps"
            .into(),
        Accessor::MaxStep,
    );
    b.fixed(
        "solver.tolerance".into(),
        settings.tolerance,
        Some("1"),
        "Newton tolerance on the scaled residual".into(),
        Accessor::Tolerance,
    );
    b.fixed(
        "solver.order".into(),
        f64::from(settings.order),
        None,
        "order of the time integrator: 2 (energy-momentum midpoint) or 4 (triple jump)".into(),
        Accessor::Order,
    );
}

/// Builds the table: inputs, outputs, parameters (see [`VariableTable::new`]).
pub(super) fn build(def: &ModelDef, settings: &SolverSettings) -> VariableTable {
    let mut b = Builder { vars: Vec::new() };
    inputs(&mut b, def);
    outputs(&mut b, def);
    parameters(&mut b, def, settings);
    VariableTable { vars: b.vars }
}
