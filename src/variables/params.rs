//! Parameters of the variable table: gravity, bodies, joint initial values, damping and
//! stiffness, actuator gears and gains, solver settings.

use super::builder::{coord_words, coords, index, Builder, Coord, XYZ};
use super::types::{Accessor, Causality, Variability};
use crate::mechanics::{ActuatorLaw, JointDef, JointInitial, JointType, ModelDef, SolverSettings};

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
    limit_parameters(b, joint, j);
    // joint-space terms, declared where set: (name, value, units on slides / angles, what)
    let slide = j.kind == JointType::Prismatic;
    let terms = [
        ("armature", j.armature, ["kg", "kg.m2"], Accessor::Armature(joint),
         "rotor inertia of joint {n} in joint space on each coordinate (kg.m2 on angles, kg on slides): adds armature q'^2/2 of kinetic energy"),
        ("friction", j.friction, ["N", "N.m"], Accessor::Friction(joint),
         "Coulomb friction of joint {n} on each coordinate (N.m on angles, N on slides): sticks below it, slides at it; its loss is counted in system.work"),
    ];
    for (name, value, units, acc, what) in terms {
        if value > 0.0 {
            let unit = units[usize::from(!slide)];
            b.fixed(
                format!("joint.{n}.{name}"),
                value,
                Some(unit),
                what.replace("{n}", n),
                acc,
            );
        }
    }
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

/// `lower`, `upper`, `stop_stiffness`, `stop_damping` (joints with stops) and `effort` (with an
/// effort limit) of a revolute or prismatic joint.
fn limit_parameters(b: &mut Builder, joint: usize, j: &JointDef) {
    let (q, force, k, c) = match j.kind {
        JointType::Revolute => ("rad", "N.m", "N.m", "N.m.s"),
        JointType::Prismatic => ("m", "N", "N/m", "N.s/m2"),
        _ => return,
    };
    let n = &j.name;
    let l = &j.limits;
    for (word, v, acc) in [
        ("lower", l.lower, Accessor::Lower(joint)),
        ("upper", l.upper, Accessor::Upper(joint)),
    ] {
        if v.is_finite() {
            b.fixed(
                format!("joint.{n}.{word}"),
                v,
                Some(q),
                format!("{word} position limit of joint {n} (a one-sided stop)"),
                acc,
            );
        }
    }
    if l.has_stops() {
        b.fixed(
            format!("joint.{n}.stop_stiffness"),
            l.stop_stiffness,
            Some(k),
            format!("stiffness of joint {n}'s stops per unit of penetration"),
            Accessor::StopStiffness(joint),
        );
        b.fixed(
            format!("joint.{n}.stop_damping"),
            l.stop_damping,
            Some(c),
            format!("Hunt-Crossley damping of joint {n}'s stops: force = stop_damping x penetration x rate (dissipation counted in system.work)"),
            Accessor::StopDamping(joint),
        );
    }
    if let Some(range) = l.actuator_force {
        for (k, (end, v)) in ["lower", "upper"].iter().zip(range).enumerate() {
            b.fixed(
                format!("joint.{n}.actuatorfrcrange[{}]", k + 1),
                v,
                Some(force),
                format!("{end} end of the range that clamps the sum of the [[actuator]]s' forces on joint {n} (MuJoCo's actuatorfrcrange; checked lo < hi when the model is built)"),
                Accessor::ActuatorForce(joint, k),
            );
        }
    }
    if l.effort.is_finite() {
        b.fixed(
            format!("joint.{n}.effort"),
            l.effort,
            Some(force),
            format!(
                "largest actuator input of joint {n}: inputs beyond +-effort are applied clamped"
            ),
            Accessor::Effort(joint),
        );
    }
}

/// `actuator.A.gear` (fixed) of every actuator, `actuator.A.kp` (position servos) and
/// `actuator.A.kv` (position and velocity servos), tunable between steps.
fn actuator_parameters(b: &mut Builder, def: &ModelDef) {
    for (k, a) in def.actuators.iter().enumerate() {
        let Some(jd) = def.joints.get(a.joint) else {
            continue;
        };
        let (n, j) = (&a.name, &jd.name);
        let angle = jd.kind == JointType::Revolute;
        b.fixed(
            format!("actuator.{n}.gear"),
            a.gear,
            Some("1"),
            format!("gear of actuator {n}: its length is gear·q of joint {j}, and joint {j} receives gear·force (finite, non-zero)"),
            Accessor::ActuatorGear(k),
        );
        let [kp, kv] = a.law.gains();
        let (kp_unit, kv_unit) = if angle {
            ("N.m/rad", "N.m.s/rad")
        } else {
            ("N/m", "N.s/m")
        };
        let position = matches!(a.law, ActuatorLaw::Position { .. });
        if position {
            b.push(
                format!("actuator.{n}.kp"),
                Causality::Parameter,
                Variability::Tunable,
                Some(kp),
                Some(kp_unit),
                format!("position gain of servo {n}: force = kp·(ctrl − gear·q) − kv·gear·qd (>= 0; tunable between steps, its work counted in system.work)"),
                Accessor::ActuatorKp(k),
            );
        }
        if position || matches!(a.law, ActuatorLaw::Velocity { .. }) {
            let law = if position {
                "damping gain of position servo {n}: force = kp·(ctrl − gear·q) − kv·gear·qd"
            } else {
                "gain of velocity servo {n}: force = kv·(ctrl − gear·qd)"
            };
            b.push(
                format!("actuator.{n}.kv"),
                Causality::Parameter,
                Variability::Tunable,
                Some(kv),
                Some(kv_unit),
                format!(
                    "{} (>= 0; tunable between steps, its work counted in system.work)",
                    law.replace("{n}", n)
                ),
                Accessor::ActuatorKv(k),
            );
        }
    }
}

pub(super) fn parameters(b: &mut Builder, def: &ModelDef, settings: &SolverSettings) {
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
    actuator_parameters(b, def);
    if let Some(g) = &def.contact.ground {
        b.fixed(
            "ground.height".into(),
            g.height,
            Some("m"),
            "height of the ground plane along its normal (the normal points against gravity)"
                .into(),
            Accessor::GroundHeight,
        );
        b.fixed("ground.friction".into(), g.law.friction, Some("1"), "Coulomb friction coefficient of the ground (and of every collision shape that sets none of its own)".into(), Accessor::GroundFriction);
        b.fixed(
            "ground.stiffness".into(),
            g.law.stiffness,
            Some("N/m"),
            "normal contact stiffness of the ground (and of its friction bristles)".into(),
            Accessor::GroundStiffness,
        );
        b.fixed("ground.damping".into(), g.law.damping, Some("s/m"), "Hunt-Crossley damping of the ground contacts: normal force k x (1 + damping x'); its loss is counted in system.work".into(), Accessor::GroundDamping);
    }
    b.fixed(
        "solver.max_step".into(),
        settings.max_step,
        Some("s"),
        "largest internal time step; with solver.rtol = 0 a communication step takes ceil(H / max_step) equal sub-steps, with solver.rtol > 0 it is the ceiling of the error-controlled step"
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
    b.fixed(
        "solver.max_substeps".into(),
        f64::from(settings.max_substeps),
        None,
        "most internal sub-steps in one fmi2DoStep: a step needing more stops there with fmi2Discard (fmi2LastSuccessfulTime says how far it got)".into(),
        Accessor::MaxSubsteps,
    );
    b.fixed(
        "solver.stages".into(),
        f64::from(settings.stages),
        None,
        "stages of the order-4 composition: 3 (triple jump) or 5 (Suzuki: about 1/64 of the error at the same step, 5/3 of the cost)".into(),
        Accessor::Stages,
    );
    b.fixed(
        "solver.rtol".into(),
        settings.rtol,
        Some("1"),
        "relative tolerance of error-controlled internal steps (0: fixed steps of solver.max_step); every step is still an energy-momentum step".into(),
        Accessor::Rtol,
    );
    b.fixed(
        "solver.atol".into(),
        settings.atol,
        Some("1"),
        "absolute tolerance of error-controlled internal steps, added to solver.rtol".into(),
        Accessor::Atol,
    );
    b.fixed(
        "solver.min_step".into(),
        settings.min_step,
        Some("s"),
        "floor of an error-controlled internal step".into(),
        Accessor::MinStep,
    );
}
