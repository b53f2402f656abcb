//! Construction of the variable table from a model definition (interface.md §3 names).

use super::builder::{coord_words, coords, index, Builder, Coord, XYZ};
use super::params::parameters;
use super::types::{Accessor, LoopStates, VariableTable};
use crate::mechanics::{ActuatorLaw, Coord as MechCoord, JointType, ModelDef, SolverSettings};

impl VariableTable {
    /// Builds the table of a model definition (names from `def`), parameters starting at the
    /// values of `def` and `settings`. Order: inputs (in `Model::inputs` order), outputs (per
    /// body, per joint, then `system.*`), parameters (gravity, bodies, joints, solver); the value
    /// reference is the position in `vars`, the ModelVariables index is `vr + 1`.
    #[must_use]
    pub fn new(def: &ModelDef, settings: &SolverSettings) -> Self {
        build(def, settings)
    }
}

impl VariableTable {
    /// Appends ` (text)` to the description of every variable whose name starts with one of
    /// the `(prefix, text)` pairs' prefix followed by `.` (e.g. `body.link_1` → the link's
    /// original URDF name).
    #[must_use]
    pub fn with_labels(mut self, labels: &[(String, String)]) -> Self {
        if labels.is_empty() {
            return self;
        }
        let by_prefix: std::collections::HashMap<&str, &str> = labels
            .iter()
            .map(|(p, t)| (p.as_str(), t.as_str()))
            .collect();
        for v in &mut self.vars {
            // element names are identifiers: the prefix is the text before the second dot
            let mut dots = v.name.match_indices('.').map(|(i, _)| i);
            let (Some(_), Some(end)) = (dots.next(), dots.next()) else {
                continue;
            };
            if let Some(text) = by_prefix.get(&v.name[..end]) {
                v.description = format!("{} ({text})", v.description);
            }
        }
        self
    }
}

fn inputs(b: &mut Builder, def: &ModelDef) {
    // order of `Model::inputs`: joint inputs in joint order, body loads, joint actuators
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
    for a in &def.actuators {
        let Some(jd) = def.joints.get(a.joint) else {
            continue;
        };
        let angle = jd.kind == JointType::Revolute;
        let (unit, law) = match a.law {
            ActuatorLaw::Motor => (if angle { "N.m" } else { "N" }, "motor: force = ctrl"),
            ActuatorLaw::Position { .. } => (
                if angle { "rad" } else { "m" },
                "position servo: force = kp·(ctrl − gear·q) − kv·gear·qd",
            ),
            ActuatorLaw::Velocity { .. } => (
                if angle { "rad/s" } else { "m/s" },
                "velocity servo: force = kv·(ctrl − gear·qd)",
            ),
        };
        let clamp = |what: &str, r: Option<[f64; 2]>| {
            r.map_or(String::new(), |[lo, hi]| {
                format!(", {what} clamped to [{lo}, {hi}]")
            })
        };
        b.input(
            format!("actuator.{}.ctrl", a.name),
            unit,
            format!(
                "control of actuator {} on joint {} ({law}, parameters actuator.{}.*; joint load gear·force){}{}",
                a.name,
                jd.name,
                a.name,
                clamp("ctrl", a.ctrlrange),
                clamp("force", a.forcerange)
            ),
            slot,
        );
        slot += 1;
    }
}

/// The parts of a frame's outputs.
#[derive(Clone, Copy)]
enum Part {
    R,
    Rot,
    V,
    W,
}

/// `{kind}.{n}.r[i]`, `R[i,j]`, `v[i]`, `w[i]` of a body or site frame (world frame), their
/// accessors made by `acc(part, i, j)`.
fn frame_outputs(
    b: &mut Builder,
    kind: &str,
    n: &str,
    acc: impl Fn(Part, usize, usize) -> Accessor,
) {
    for (i, c) in XYZ.iter().enumerate() {
        b.output(
            format!("{kind}.{n}.r[{}]", i + 1),
            "m",
            format!("origin of {kind} {n}'s frame, {c} component, world frame"),
            acc(Part::R, i, 0),
        );
    }
    for i in 0..3 {
        for j in 0..3 {
            b.output(format!("{kind}.{n}.R[{},{}]", i + 1, j + 1), "1", format!("rotation world <- {kind} {n}, row {} column {} (column j is {kind} axis j in world coordinates)", i + 1, j + 1), acc(Part::Rot, i, j));
        }
    }
    for (i, c) in XYZ.iter().enumerate() {
        b.output(
            format!("{kind}.{n}.v[{}]", i + 1),
            "m/s",
            format!("velocity of {kind} {n}'s frame origin, {c} component, world frame"),
            acc(Part::V, i, 0),
        );
    }
    for (i, c) in XYZ.iter().enumerate() {
        b.output(
            format!("{kind}.{n}.w[{}]", i + 1),
            "rad/s",
            format!("angular velocity of {kind} {n}, {c} component, world frame"),
            acc(Part::W, i, 0),
        );
    }
}

fn outputs(b: &mut Builder, def: &ModelDef) {
    for (body, bd) in def.bodies.iter().enumerate() {
        frame_outputs(b, "body", &bd.name, |part, i, j| match part {
            Part::R => Accessor::BodyR { body, i },
            Part::Rot => Accessor::BodyRot { body, i, j },
            Part::V => Accessor::BodyV { body, i },
            Part::W => Accessor::BodyW { body, i },
        });
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
    for (site, sd) in def.sites.iter().enumerate() {
        frame_outputs(b, "site", &sd.name, |part, i, j| match part {
            Part::R => Accessor::SiteR { site, i },
            Part::Rot => Accessor::SiteRot { site, i, j },
            Part::V => Accessor::SiteV { site, i },
            Part::W => Accessor::SiteW { site, i },
        });
    }
    b.output(
        "system.energy".into(),
        "J",
        "kinetic + potential energy (gravity, joint springs and stops, contact springs)".into(),
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
    for (shape, sd) in def.contact.shapes.iter().enumerate() {
        let n = &sd.name;
        let body = &def.bodies[sd.body].name;
        for (i, c) in XYZ.iter().enumerate() {
            b.output(
                format!("contact.{n}.f[{}]", i + 1),
                "N",
                format!("contact force on body {body} through collision shape {n} (ground and other shapes), {c} component, world frame"),
                Accessor::ContactForce { shape, i },
            );
        }
        if def.contact.ground.is_some() {
            b.output(
                format!("contact.{n}.gap"),
                "m",
                format!(
                    "signed distance of collision shape {n} to the ground (negative: penetration)"
                ),
                Accessor::ContactGap(shape),
            );
        }
    }
}

/// The most minimal coordinates a model may have for `joint.J.qdd` outputs: reading them
/// factors the `n × n` mass matrix (O(n³): 1 ms at 200).
pub const MAX_ACCELERATION_COORDS: usize = 200;

/// The joint accelerations `joint.J.qdd` of a model without contact or joint friction (not of
/// spherical or loop-closing joints) of at most [`MAX_ACCELERATION_COORDS`] coordinates, last
/// in the table so that every other value reference is as it was without them. With closed
/// loops or couplings, also the states: the independent coordinates `triad linearize` picks at
/// the initial state (`Operating::initial_independent`, [`loop_states`]); without them (the
/// loops cannot be split there, or a spherical joint or free body is independent) neither
/// accelerations nor states.
fn accelerations(b: &mut Builder, def: &ModelDef, settings: &SolverSettings) -> Option<LoopStates> {
    let n_coords = def
        .joints
        .iter()
        .map(|j| j.kind.dof())
        .chain(def.free_bodies.iter().map(|_| 6))
        .sum::<usize>();
    if crate::mechanics::linearizable(def).is_err() || n_coords > MAX_ACCELERATION_COORDS {
        return None;
    }
    let loops = if crate::mechanics::supported(def).is_err() {
        Some(loop_states(def, settings)?)
    } else {
        None
    };
    for (joint, j) in def.joints.iter().enumerate() {
        if j.kind == JointType::Spherical || j.loop_closing {
            continue;
        }
        let n = &j.name;
        let cs = coords(j.kind);
        for (k, c) in cs.iter().enumerate() {
            let unit = if *c == Coord::Angle { "rad/s2" } else { "m/s2" };
            b.output(
                format!("joint.{n}.qdd{}", index(k, cs.len())),
                unit,
                format!(
                    "joint {n} acceleration: second derivative of the {}, at the communication point",
                    coord_words(j.kind, k)
                ),
                Accessor::JointQdd { joint, k },
            );
        }
    }
    loops
}

/// The states of a model with closed loops or couplings (`LoopStates`): the independent
/// coordinates of `Operating::initial_independent` (the choice `triad linearize` makes by
/// default at the initial state), when each is a coordinate of a joint that is not spherical
/// and every coordinate of such a joint is independent (an FMI 3 array is one state).
fn loop_states(def: &ModelDef, settings: &SolverSettings) -> Option<LoopStates> {
    let picked = crate::mechanics::Operating::initial_independent(def, *settings).ok()??;
    let independent = picked
        .iter()
        .map(|c| match *c {
            MechCoord::Joint { joint, k } if def.joints[joint].kind != JointType::Spherical => {
                Some((joint, k))
            }
            _ => None,
        })
        .collect::<Option<Vec<(usize, usize)>>>()?;
    // a joint's coordinates are states together (an FMI 3 array is one variable)
    let whole = independent
        .iter()
        .all(|&(j, _)| (0..def.joints[j].kind.dof()).all(|k| independent.contains(&(j, k))));
    if !whole {
        return None;
    }
    let closing = (0..def.joints.len())
        .filter(|&j| def.joints[j].loop_closing)
        .collect();
    Some(LoopStates {
        independent,
        closing,
    })
}

/// Builds the table: inputs, outputs, parameters, joint accelerations (see
/// [`VariableTable::new`]).
pub(super) fn build(def: &ModelDef, settings: &SolverSettings) -> VariableTable {
    let mut b = Builder { vars: Vec::new() };
    inputs(&mut b, def);
    outputs(&mut b, def);
    parameters(&mut b, def, settings);
    let loops = accelerations(&mut b, def, settings);
    VariableTable {
        vars: b.vars,
        loops,
    }
}
