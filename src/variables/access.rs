//! Reading and writing variable values through their [`Accessor`]: inputs, outputs and tunable
//! parameters live in the [`State`]; fixed parameters in the [`ModelDef`] and [`SolverSettings`].

use super::types::Accessor;
use crate::mechanics::{ranges, JointInitial, JointLimits, ModelDef, SolverSettings, State};

/// Value of an input, an output or a tunable parameter (damping, stiffness, actuator gains) in
/// `state`; `None` for fixed parameters (see [`read_param`]) and for outputs the state does not
/// hold.
#[must_use]
pub fn read_state(acc: Accessor, state: &State) -> Option<f64> {
    let out = state.outputs();
    match acc {
        Accessor::Input(i) => state.inputs().get(i).copied(),
        Accessor::BodyR { body, i } => out.bodies.get(body).and_then(|b| b.r.get(i).copied()),
        Accessor::BodyRot { body, i, j } => out
            .bodies
            .get(body)
            .and_then(|b| b.rot.get((i, j)).copied()),
        Accessor::BodyV { body, i } => out.bodies.get(body).and_then(|b| b.v.get(i).copied()),
        Accessor::BodyW { body, i } => out.bodies.get(body).and_then(|b| b.w.get(i).copied()),
        Accessor::SiteR { site, i } => out.sites.get(site).and_then(|b| b.r.get(i).copied()),
        Accessor::SiteRot { site, i, j } => {
            out.sites.get(site).and_then(|b| b.rot.get((i, j)).copied())
        }
        Accessor::SiteV { site, i } => out.sites.get(site).and_then(|b| b.v.get(i).copied()),
        Accessor::SiteW { site, i } => out.sites.get(site).and_then(|b| b.w.get(i).copied()),
        Accessor::JointQ { joint, k } => out.joints.get(joint).and_then(|j| j.q.get(k).copied()),
        Accessor::JointQd { joint, k } => out.joints.get(joint).and_then(|j| j.qd.get(k).copied()),
        Accessor::Energy => Some(out.energy),
        Accessor::Work => Some(out.work),
        Accessor::P(i) => out.p.get(i).copied(),
        Accessor::L(i) => out.l.get(i).copied(),
        Accessor::ConstraintResidual => Some(out.constraint_residual),
        Accessor::ContactForce { shape, i } => out
            .contacts
            .get(shape)
            .and_then(|c| c.force.get(i).copied()),
        Accessor::ContactGap(shape) => out.contacts.get(shape).map(|c| c.gap),
        // the table only makes these for joints of the same definition as the state
        Accessor::Damping(j) => Some(state.damping(j)),
        Accessor::Stiffness(j) => Some(state.stiffness(j)),
        Accessor::ActuatorKp(a) => Some(state.gains(a)[0]),
        Accessor::ActuatorKv(a) => Some(state.gains(a)[1]),
        _ => None,
    }
}

fn initial(def: &ModelDef, joint: usize, k: usize, rate: bool) -> Option<f64> {
    match (&def.joints.get(joint)?.initial, rate) {
        (JointInitial::Coords { q, .. }, false) => Some(q.get(k).copied().unwrap_or(0.0)),
        (JointInitial::Coords { qd, .. }, true) => Some(qd.get(k).copied().unwrap_or(0.0)),
        (JointInitial::Spherical { quat, .. }, false) => quat.get(k).copied(),
        (JointInitial::Spherical { w, .. }, true) => w.get(k).copied(),
    }
}

/// Value of a parameter as defined in `def` and `settings` (including the start values of the
/// tunable damping and stiffness); `None` for inputs and outputs.
#[must_use]
pub fn read_param(acc: Accessor, def: &ModelDef, settings: &SolverSettings) -> Option<f64> {
    match acc {
        Accessor::Gravity(i) => def.gravity.get(i).copied(),
        Accessor::Mass(b) => def.bodies.get(b).map(|b| b.mass),
        Accessor::Inertia { body, i, j } => def
            .bodies
            .get(body)
            .and_then(|b| b.inertia.get((i, j)).copied()),
        Accessor::Q0 { joint, k } => initial(def, joint, k, false),
        Accessor::Qd0 { joint, k } => initial(def, joint, k, true),
        Accessor::Damping(j) => def.joints.get(j).map(|j| j.damping),
        Accessor::Stiffness(j) => def.joints.get(j).map(|j| j.stiffness),
        Accessor::Lower(j) => def.joints.get(j).map(|j| j.limits.lower),
        Accessor::Upper(j) => def.joints.get(j).map(|j| j.limits.upper),
        Accessor::Effort(j) => def.joints.get(j).map(|j| j.limits.effort),
        Accessor::StopStiffness(j) => def.joints.get(j).map(|j| j.limits.stop_stiffness),
        Accessor::StopDamping(j) => def.joints.get(j).map(|j| j.limits.stop_damping),
        Accessor::Armature(j) => def.joints.get(j).map(|j| j.armature),
        Accessor::Friction(j) => def.joints.get(j).map(|j| j.friction),
        Accessor::ActuatorForce(j, k) => def
            .joints
            .get(j)
            .and_then(|j| j.limits.actuator_force)
            .map(|r| r[k]),
        Accessor::ActuatorGear(a) => def.actuators.get(a).map(|a| a.gear),
        Accessor::ActuatorKp(a) => def.actuators.get(a).map(|a| a.law.gains()[0]),
        Accessor::ActuatorKv(a) => def.actuators.get(a).map(|a| a.law.gains()[1]),
        Accessor::MaxStep => Some(settings.max_step),
        Accessor::Tolerance => Some(settings.tolerance),
        Accessor::Order => Some(f64::from(settings.order)),
        Accessor::MaxSubsteps => Some(f64::from(settings.max_substeps)),
        Accessor::Stages => Some(f64::from(settings.stages)),
        Accessor::Rtol => Some(settings.rtol),
        Accessor::Atol => Some(settings.atol),
        Accessor::MinStep => Some(settings.min_step),
        Accessor::GroundHeight => def.contact.ground.map(|g| g.height),
        Accessor::GroundFriction => def.contact.ground.map(|g| g.law.friction),
        Accessor::GroundStiffness => def.contact.ground.map(|g| g.law.stiffness),
        Accessor::GroundDamping => def.contact.ground.map(|g| g.law.damping),
        _ => None,
    }
}

fn set_initial(
    def: &mut ModelDef,
    joint: usize,
    k: usize,
    rate: bool,
    value: f64,
) -> Result<(), String> {
    let j = def
        .joints
        .get_mut(joint)
        .ok_or_else(|| format!("no joint {joint}"))?;
    let (nq, dof) = (j.kind.nq(), j.kind.dof());
    let slot = match (&mut j.initial, rate) {
        (JointInitial::Coords { q, .. }, false) => {
            q.resize(nq.max(q.len()), 0.0);
            q.get_mut(k)
        }
        (JointInitial::Coords { qd, .. }, true) => {
            qd.resize(dof.max(qd.len()), 0.0);
            qd.get_mut(k)
        }
        (JointInitial::Spherical { quat, .. }, false) => quat.get_mut(k),
        (JointInitial::Spherical { w, .. }, true) => w.get_mut(k),
    };
    *slot.ok_or_else(|| format!("joint '{}' has no coordinate {}", j.name, k + 1))? = value;
    Ok(())
}

fn ground(def: &mut ModelDef) -> Result<&mut crate::mechanics::GroundDef, String> {
    def.contact
        .ground
        .as_mut()
        .ok_or_else(|| "the model has no ground".to_string())
}

fn limits(def: &mut ModelDef, j: usize) -> Result<&mut JointLimits, String> {
    Ok(&mut def.joints.get_mut(j).ok_or("no such joint")?.limits)
}

/// Sets a parameter in `def`/`settings` (before the model is built), after checking it against
/// its range ([`crate::mechanics::ranges`], the rules `triad check` applies to a spec).
/// `inertia[i,j]` sets `[i,j]` and `[j,i]`; the rules that involve several parameters (the
/// inertia tensor as a whole, `lower < upper`) are checked when the model is built
/// ([`crate::mechanics::ranges::cross_checks`]).
///
/// # Errors
/// A message for a value outside its range and for accessors that are not parameters.
pub fn write_param(
    acc: Accessor,
    def: &mut ModelDef,
    settings: &mut SolverSettings,
    value: f64,
) -> Result<(), String> {
    fn named<T>(what: &str, r: Result<T, String>) -> Result<T, String> {
        r.map_err(|e| format!("{what} {e}"))
    }
    match acc {
        Accessor::Gravity(i) => {
            named("gravity", ranges::any_finite(value))?;
            *def.gravity.get_mut(i).ok_or("no such gravity component")? = value;
        }
        Accessor::Mass(b) => {
            // zero is a mass like any other; whether the motion stays determined is decided
            // when the model is built
            named("mass", ranges::non_negative(value))?;
            def.bodies.get_mut(b).ok_or("no such body")?.mass = value;
        }
        Accessor::Inertia { body, i, j } => {
            named("inertia", ranges::any_finite(value))?;
            let b = def.bodies.get_mut(body).ok_or("no such body")?;
            if i > 2 || j > 2 {
                return Err("inertia index out of range".into());
            }
            b.inertia[(i, j)] = value;
            b.inertia[(j, i)] = value;
        }
        Accessor::Q0 { joint, k } => {
            named("initial value", ranges::any_finite(value))?;
            set_initial(def, joint, k, false, value)?;
        }
        Accessor::Qd0 { joint, k } => {
            named("initial rate", ranges::any_finite(value))?;
            set_initial(def, joint, k, true, value)?;
        }
        Accessor::Damping(j) => {
            named("damping", ranges::non_negative(value))?;
            def.joints.get_mut(j).ok_or("no such joint")?.damping = value;
        }
        Accessor::Stiffness(j) => {
            named("stiffness", ranges::non_negative(value))?;
            def.joints.get_mut(j).ok_or("no such joint")?.stiffness = value;
        }
        Accessor::Lower(j) => {
            named("lower", ranges::any_finite(value))?;
            limits(def, j)?.lower = value;
        }
        Accessor::Upper(j) => {
            named("upper", ranges::any_finite(value))?;
            limits(def, j)?.upper = value;
        }
        Accessor::Effort(j) => {
            named("effort", ranges::positive(value))?;
            limits(def, j)?.effort = value;
        }
        Accessor::StopStiffness(j) => {
            named("stop_stiffness", ranges::positive(value))?;
            limits(def, j)?.stop_stiffness = value;
        }
        Accessor::StopDamping(j) => {
            named("stop_damping", ranges::non_negative(value))?;
            limits(def, j)?.stop_damping = value;
        }
        Accessor::Armature(j) => {
            named("armature", ranges::non_negative(value))?;
            def.joints.get_mut(j).ok_or("no such joint")?.armature = value;
        }
        Accessor::Friction(j) => {
            named("friction", ranges::non_negative(value))?;
            def.joints.get_mut(j).ok_or("no such joint")?.friction = value;
        }
        Accessor::ActuatorForce(j, k) => {
            // lo < hi is checked when the model is built (`joint_actuator::invalid_range`), so
            // that either end can be set first
            named("actuatorfrcrange", ranges::any_finite(value))?;
            let range = limits(def, j)?.actuator_force.as_mut();
            range.ok_or("no actuator force range")?[k] = value;
        }
        Accessor::ActuatorGear(a) => {
            named("gear", ranges::non_zero(value))?;
            def.actuators.get_mut(a).ok_or("no such actuator")?.gear = value;
        }
        Accessor::ActuatorKp(a) | Accessor::ActuatorKv(a) => {
            let kv = matches!(acc, Accessor::ActuatorKv(_));
            named(if kv { "kv" } else { "kp" }, ranges::non_negative(value))?;
            let act = def.actuators.get_mut(a).ok_or("no such actuator")?;
            let mut gains = act.law.gains();
            gains[usize::from(kv)] = value;
            act.law = act.law.with_gains(gains);
        }
        Accessor::MaxStep => {
            named("solver.max_step", ranges::max_step(value))?;
            settings.max_step = value;
        }
        Accessor::Tolerance => {
            named("solver.tolerance", ranges::tolerance(value))?;
            settings.tolerance = value;
        }
        Accessor::Order => {
            settings.order = named("solver.order", ranges::order(value))?;
        }
        Accessor::MaxSubsteps => {
            settings.max_substeps = named("solver.max_substeps", ranges::max_substeps(value))?;
        }
        Accessor::Stages => {
            settings.stages = named("solver.stages", ranges::stages(value))?;
        }
        Accessor::Rtol => {
            named("solver.rtol", ranges::rtol(value))?;
            settings.rtol = value;
        }
        Accessor::Atol => {
            named("solver.atol", ranges::atol(value))?;
            settings.atol = value;
        }
        Accessor::GroundHeight => {
            named("ground.height", ranges::any_finite(value))?;
            ground(def)?.height = value;
        }
        Accessor::GroundFriction => {
            named("ground.friction", ranges::non_negative(value))?;
            ground(def)?.law.friction = value;
        }
        Accessor::GroundStiffness => {
            named("ground.stiffness", ranges::positive(value))?;
            ground(def)?.law.stiffness = value;
        }
        Accessor::GroundDamping => {
            named("ground.damping", ranges::non_negative(value))?;
            ground(def)?.law.damping = value;
        }
        Accessor::MinStep => {
            named("solver.min_step", ranges::min_step(value))?;
            settings.min_step = value;
        }
        _ => return Err("not a parameter".into()),
    }
    Ok(())
}
