//! Model set-up ([`Model::new`]): joint rows and coordinate handles (from `joint::JointGeom`), tree order,
//! redundant-row detection and the initial state (from `kinematics` and `loops`).
//!
//! Redundant rows: with loop-closing joints, the reduced constraint Jacobian `G(q₀) P(q₀)` is
//! tested row by row (tree joints first) by Gram–Schmidt with relative tolerance 1e-9; a row
//! that depends on the kept ones is dropped from the Newton solve (it still counts in the
//! constraint residual) and a note names the joint.
// index loops over coupled fixed-size arrays read closer to the formulas than iterator chains
#![allow(clippy::needless_range_loop)]

use super::constraint::write3;
use super::def::{JointType, ModelDef, SolverSettings};
use super::error::ModelError;
use super::joint::{Dof, JointGeom};
use super::joint_actuator::{JointActuator, JointActuators};
use super::runtime::{
    covers, euler_tensor, exact_jacobian, BodyRt, DofRt, InputSlot, JointRt, Model, TurnRt,
    ZERO_MOMENT,
};
use super::sparse_row::SparseRow;
use crate::math::{matrix_to_quat, quat_to_matrix, Vec3};

impl Model {
    /// Builds the model: validates, orders the spanning tree, assembles constraint rows, drops
    /// redundant loop rows (reported in [`Model::notes`]) and computes the initial state.
    ///
    /// # Errors
    /// [`ModelError`] for an inconsistent definition or a loop not closed at the start.
    pub fn new(def: &ModelDef, settings: SolverSettings) -> Result<Self, ModelError> {
        let mut inputs = Vec::new();
        let mut joint_input = vec![None; def.joints.len()];
        for (j, joint) in def.joints.iter().enumerate() {
            if !joint.actuated {
                continue;
            }
            use super::def::JointType as T;
            let first = inputs.len();
            match joint.kind {
                T::Revolute => inputs.push(InputSlot::JointTorque { joint: j, k: 0 }),
                T::Prismatic => inputs.push(InputSlot::JointForce { joint: j }),
                T::Cylindrical => {
                    inputs.push(InputSlot::JointForce { joint: j });
                    inputs.push(InputSlot::JointTorque { joint: j, k: 0 });
                }
                T::Universal => {
                    (0..2).for_each(|k| inputs.push(InputSlot::JointTorque { joint: j, k }))
                }
                T::Spherical => {
                    (0..3).for_each(|k| inputs.push(InputSlot::JointTorque { joint: j, k }))
                }
                T::Planar | T::Fixed => {}
            }
            if inputs.len() > first {
                joint_input[j] = Some(first);
            }
        }
        for jd in &def.joints {
            let spherical = jd.kind == JointType::Spherical;
            let fixed = jd.kind == JointType::Fixed;
            for (what, a, bad_kind, kinds) in [
                (
                    "armature",
                    jd.armature,
                    spherical || fixed,
                    "not spherical or fixed",
                ),
                ("friction", jd.friction, fixed, "not fixed"),
            ] {
                if !(a.is_finite() && a >= 0.0) || (a > 0.0 && (bad_kind || jd.loop_closing)) {
                    return Err(ModelError::Invalid(format!(
                        "joint '{}': {what} must be finite and >= 0, and only on a tree joint that is {kinds} (got {a})",
                        jd.name
                    )));
                }
            }
        }
        let mut body_torques = Vec::new();
        let mut body_forces = Vec::new();
        for load in &def.loads {
            if load.body >= def.bodies.len() {
                return Err(ModelError::Invalid(format!(
                    "body load on unknown body {}",
                    load.body
                )));
            }
            if load.torque {
                body_torques.push((load.body, inputs.len()));
                (0..3).for_each(|i| inputs.push(InputSlot::BodyTorque { body: load.body, i }));
            }
            if load.force {
                body_forces.push((load.body, inputs.len()));
                (0..3).for_each(|i| inputs.push(InputSlot::BodyForce { body: load.body, i }));
            }
        }
        let mut joint_acts = vec![JointActuators::default(); def.joints.len()];
        for (acts, jd) in joint_acts.iter_mut().zip(&def.joints) {
            if let Some(range) = jd.limits.actuator_force {
                if let Some(why) = super::joint_actuator::invalid_range(jd, range) {
                    return Err(ModelError::Invalid(why));
                }
                acts.range = range;
            }
        }
        for (k, a) in def.actuators.iter().enumerate() {
            if let Some(why) = super::joint_actuator::invalid(def, a) {
                return Err(ModelError::Invalid(why));
            }
            joint_acts[a.joint]
                .list
                .push(JointActuator::new(a, k, inputs.len()));
            inputs.push(InputSlot::ActuatorCtrl { actuator: k });
        }
        if !(settings.max_step.is_finite() && settings.max_step > 0.0) {
            return Err(ModelError::Invalid(format!(
                "max_step must be positive, got {}",
                settings.max_step
            )));
        }
        if settings.order != 2 && settings.order != 4 {
            return Err(ModelError::Invalid(format!(
                "order must be 2 or 4, got {}",
                settings.order
            )));
        }
        if settings.stages != 3 && settings.stages != 5 {
            return Err(ModelError::Invalid(format!(
                "stages must be 3 or 5, got {}",
                settings.stages
            )));
        }
        if !(settings.tolerance.is_finite() && settings.tolerance > 0.0)
            || settings.max_iterations == 0
        {
            return Err(ModelError::Invalid(
                "tolerance must be positive and max_iterations ≥ 1".into(),
            ));
        }
        let (bodies, lc) = mass_data(def)?;
        let mut model = Self {
            def: def.clone(),
            settings,
            inputs,
            notes: Vec::new(),
            bodies,
            joints: Vec::new(),
            order: Vec::new(),
            parent: vec![None; def.bodies.len()],
            tree_joint: vec![None; def.bodies.len()],
            nrows: 0,
            couplings: Vec::new(),
            nturn: 0,
            narm: 0,
            nfric: 0,
            dense: false,
            reduced: false,
            exact_reduced: false,
            lc,
            q0: vec![0.0; 12 * def.bodies.len()],
            v0: vec![0.0; 12 * def.bodies.len()],
            angles0: Vec::new(),
            body_torques,
            body_forces,
            naive_torque: false,
            contact: super::contact::build(def),
        };
        build(&mut model, &joint_input, joint_acts)?;
        super::determinacy::check(&model)?;
        if let Some(note) = super::contact::period_note(def, &settings) {
            model.notes.push(note);
        }
        model.reduced = covers(&model);
        // contact's Jacobian leaves out the coupling of two bodies through a feature
        model.exact_reduced = exact_jacobian(&model) && model.contact.features.is_empty();
        Ok(model)
    }
}

/// Every body's runtime mass data and the characteristic length `lc` (m) of the model.
///
/// Residual scales: `fs = 1/(m lc)` for the force rows, `ms = 1/(|tr E| + ½|E|)` for the
/// moment rows; a body without mass (or without inertia) takes those of the model's largest
/// mass (largest Euler tensor) instead, so that its rows weigh like the loads it transmits.
/// `lc = max_b (√(|tr E_b|/m_b) + |c_b|)` over the bodies with mass (at least 1e-6 m).
fn mass_data(def: &ModelDef) -> Result<(Vec<BodyRt>, f64), ModelError> {
    let mut bodies = Vec::with_capacity(def.bodies.len());
    for b in &def.bodies {
        // only J > 0 is needed of a body with inertia: the projected iteration matrix carries
        // P̄ᵀ M Q ≈ R J Rᵀ, so an indefinite Euler tensor (a body violating the triangle
        // inequality, e.g. theory B1's J = (1, 1, 2.5)) still integrates
        let e = euler_tensor(&b.inertia);
        let scale = b.inertia.abs().max();
        let sym = (b.inertia - b.inertia.transpose()).abs().max() <= 1e-12 * scale;
        let eig = b.inertia.symmetric_eigenvalues();
        let ok = b.mass >= 0.0
            && b.mass.is_finite()
            && sym
            && eig.iter().all(|&x| x >= -1e-12 * scale && x.is_finite());
        if !ok {
            return Err(ModelError::Invalid(format!(
                "body '{}': mass must be zero or positive and the inertia symmetric positive \
                 semi-definite",
                b.name
            )));
        }
        bodies.push(BodyRt {
            mass: b.mass,
            e,
            com: b.com,
            fs: 0.0,
            ms: 1.0 / (e.trace().abs() + 0.5 * e.norm()),
            singular: b.mass == 0.0 || eig.min() <= ZERO_MOMENT * eig.amax(),
        });
    }
    let lc = bodies
        .iter()
        .filter(|b| b.mass > 0.0)
        .map(|b| (b.e.trace().abs() / b.mass).sqrt() + b.com.norm())
        .fold(0.0_f64, f64::max)
        .max(bodies.iter().map(|b| b.com.norm()).fold(0.0, f64::max))
        .max(1e-6);
    let m_ref = bodies.iter().map(|b| b.mass).fold(0.0_f64, f64::max);
    let ms_ref = bodies
        .iter()
        .map(|b| b.ms)
        .filter(|x| x.is_finite())
        .fold(f64::INFINITY, f64::min);
    for b in &mut bodies {
        let m = if b.mass > 0.0 { b.mass } else { m_ref };
        b.fs = if m > 0.0 { 1.0 / (m * lc) } else { 1.0 / lc };
        if !b.ms.is_finite() {
            b.ms = if ms_ref.is_finite() {
                ms_ref
            } else {
                1.0 / (lc * lc)
            };
        }
    }
    Ok((bodies, lc))
}

/// Fills the joint, tree and initial-state parts of `model`.
pub(crate) fn build(
    model: &mut Model,
    joint_input: &[Option<usize>],
    mut joint_acts: Vec<JointActuators>,
) -> Result<(), ModelError> {
    let def = model.def().clone();
    let nb = def.bodies.len();
    let tree = super::kinematics::tree_order(&def)?;
    model.order.clone_from(&tree.order);
    model.tree_joint.clone_from(&tree.tree_joint);
    for b in 0..nb {
        model.parent[b] = tree.tree_joint[b].and_then(|j| def.joints[j].parent);
    }
    // initial rates that violate the loop velocity constraints are projected onto them once
    // the joints are assembled (below)
    let mut project_rates = false;
    // initial state: free-body-only models are placed here (this also admits bodies whose
    // principal moments violate the triangle inequality, theory B1); jointed ones by kinematics
    if def.joints.is_empty() {
        free_initial(model)?;
    } else {
        let (q0, v0) = super::kinematics::initial_configuration(&def)?;
        super::loops::check_loops(&def, &q0)?;
        project_rates = super::loops::loop_velocities_violated(&def, &q0, &v0)?;
        model.q0 = q0;
        model.v0 = v0;
    }
    // joints
    let mut geoms = Vec::with_capacity(def.joints.len());
    for jd in &def.joints {
        geoms.push(JointGeom::new(jd, &def.bodies)?);
    }
    let keep = super::redundancy::redundant_rows(model, &geoms);
    let mut row0 = 0;
    let mut turn0 = 0;
    let mut angles0 = Vec::new();
    let mut arm0 = 0;
    let mut fric0 = 0;
    for (j, (jd, g)) in def.joints.iter().zip(geoms).enumerate() {
        let mut rows = Vec::new();
        let mut dropped = Vec::new();
        for (k, row) in g.rows.iter().enumerate() {
            if keep[j][k] {
                rows.push(*row);
            } else {
                dropped.push(*row);
            }
        }
        if !dropped.is_empty() {
            model.push_note(format!(
                "joint '{}': {} of {} constraint rows are redundant and were dropped",
                jd.name,
                dropped.len(),
                g.rows.len()
            ));
        }
        let spherical = jd.kind == JointType::Spherical;
        let dofs: Vec<DofRt> = if spherical {
            Vec::new()
        } else {
            g.dofs
                .iter()
                .enumerate()
                .map(|(k, d)| match d {
                    Dof::Slide(r) => Ok(DofRt::Slide(*r)),
                    Dof::Turn(n) => {
                        let (sin, cos) = g.angle_rows(k).ok_or_else(|| {
                            ModelError::Invalid(format!(
                                "joint '{}': coordinate {k} has no angle invariants",
                                jd.name
                            ))
                        })?;
                        let has_a = g.parent.is_some();
                        let sparse = [SparseRow::new(&sin, has_a), SparseRow::new(&cos, has_a)];
                        Ok(DofRt::Turn(TurnRt {
                            axis: *n,
                            sin,
                            cos,
                            sparse,
                        }))
                    }
                })
                .collect::<Result<_, ModelError>>()?
        };
        // unwrapping memory starts from the given initial angle (q = 4.0 stays 4.0)
        let qa = super::joint::body_nodes(&model.q0, g.parent);
        let qb = super::joint::body_nodes(&model.q0, Some(g.child));
        let mut raw = [0.0; 4];
        g.coords(&qa, &qb, &mut raw[..jd.kind.nq()]);
        let given = if jd.loop_closing {
            None
        } else {
            super::kinematics::joint_initial(jd).ok().map(|x| x.0)
        };
        for (k, d) in dofs.iter().enumerate() {
            if let DofRt::Turn(_) = d {
                let a = given.as_ref().map_or(raw[k], |q| unwrap(q[k], raw[k]));
                angles0.push(a);
            }
        }
        let nturn = dofs.iter().filter(|d| matches!(d, DofRt::Turn(_))).count();
        let dofs_len = dofs.len();
        let nrow = rows.len();
        let sparse = rows
            .iter()
            .map(|r| SparseRow::new(r, g.parent.is_some()))
            .collect();
        model.joints.push(JointRt {
            parent: g.parent,
            child: g.child,
            rows,
            sparse,
            dropped,
            row0,
            dofs,
            sph_axes: if spherical { Some(g.a) } else { None },
            input: joint_input[j],
            turn0,
            geom: g,
            stops: stops_of(jd)?,
            effort: if matches!(jd.kind, JointType::Revolute | JointType::Prismatic) {
                jd.limits.effort
            } else {
                f64::INFINITY
            },
            armature: if spherical { 0.0 } else { jd.armature },
            arm0,
            friction: (jd.friction > 0.0).then_some(super::joint_friction::JointFriction {
                limit: jd.friction,
                mirrored: false,
            }),
            fric0,
            acts: std::mem::take(&mut joint_acts[j]),
        });
        if !spherical && jd.armature > 0.0 {
            arm0 += dofs_len;
        }
        if jd.friction > 0.0 {
            // a spherical joint's bristle is a vector (`joint_friction`)
            fric0 += if spherical { 3 } else { dofs_len };
        }
        row0 += nrow;
        turn0 += nturn;
    }
    model.nturn = turn0;
    model.angles0 = angles0.clone();
    model.couplings = super::coupling::build(model, &def, row0)?;
    model.nrows = row0 + model.couplings.len();
    project_rates |= super::coupling::rates_violated(model);
    model.narm = arm0;
    model.nfric = fric0;
    model.angles0 = angles0;
    // loop-closing joints (`tree.loop_joints`) form the border of the tree solve (`border`);
    // the dense LU is only the test oracle (`Model::set_dense_solver`)
    for (b, tj) in model.tree_joint.iter().enumerate() {
        if let Some(j) = tj {
            if model.joints[*j].rows.len() > 6 {
                return Err(ModelError::Invalid(format!(
                    "body {b}: tree joint with more than 6 rows"
                )));
            }
        }
    }
    if project_rates {
        // the M-orthogonal projection onto the admissible velocities (least change in kinetic
        // energy), by the same O(N) bordered tree solve as the outputs' projection
        let mut pw = super::projection::ProjWork::new(model);
        if !super::projection::project_velocities(model, &model.q0, &model.v0, &mut pw) {
            return Err(ModelError::Invalid(
                "projection of the initial rates onto the loop constraints failed".into(),
            ));
        }
        model.v0.copy_from_slice(&pw.vp);
        model.push_note(
            "initial rates violated the loop velocity constraints and were projected onto them (least change in kinetic energy)"
                .into(),
        );
    }
    Ok(())
}

/// Free bodies of a joint-free model: COM and directors from the given pose and twist.
fn free_initial(model: &mut Model) -> Result<(), ModelError> {
    let def = model.def().clone();
    for fb in &def.free_bodies {
        let ok = [fb.position, fb.velocity, fb.angular_velocity]
            .iter()
            .all(|v| v.iter().all(|x| x.is_finite()))
            && fb.orientation.iter().all(|x| x.is_finite())
            && (fb.orientation.transpose() * fb.orientation - crate::math::Mat3::identity()).amax()
                < 1e-9
            && fb.orientation.determinant() > 0.0;
        if !ok {
            return Err(ModelError::Invalid(format!(
                "body '{}': initial state must be finite with an orthonormal right-handed orientation",
                def.bodies[fb.body].name
            )));
        }
        let com = model.bodies[fb.body].com;
        let r = quat_to_matrix(&matrix_to_quat(&fb.orientation));
        let rc = r * com;
        let phi = fb.position + rc;
        let phid = fb.velocity + fb.angular_velocity.cross(&rc);
        let q = &mut model.q0[12 * fb.body..12 * fb.body + 12];
        let v = &mut model.v0[12 * fb.body..12 * fb.body + 12];
        write3(q, 0, &phi);
        write3(v, 0, &phid);
        for i in 0..3 {
            let d: Vec3 = r.column(i).into();
            write3(q, 3 + 3 * i, &d);
            write3(v, 3 + 3 * i, &fb.angular_velocity.cross(&d));
        }
    }
    Ok(())
}

/// The unwrapped angle nearest to `prev` with the same value as `raw` modulo 2π.
#[must_use]
pub(crate) fn unwrap(prev: f64, raw: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let d = raw - prev;
    prev + d - tau * (d / tau).round()
}

#[cfg(test)]
#[path = "assemble_tests.rs"]
mod tests;

/// The stops of a revolute or prismatic joint with a position limit.
fn stops_of(jd: &super::def::JointDef) -> Result<Option<super::stops::Stops>, ModelError> {
    let l = &jd.limits;
    let ok = !(l.lower >= l.upper || l.lower.is_nan() || l.upper.is_nan())
        && l.effort > 0.0
        && l.stop_stiffness > 0.0
        && l.stop_stiffness.is_finite()
        && l.stop_damping >= 0.0
        && l.stop_damping.is_finite();
    if !ok {
        return Err(ModelError::Invalid(format!(
            "joint '{}': limits need lower < upper, effort > 0, stop_stiffness > 0 and finite, stop_damping >= 0 and finite (got {:?})",
            jd.name, l
        )));
    }
    Ok(
        (matches!(jd.kind, JointType::Revolute | JointType::Prismatic) && l.has_stops()).then_some(
            super::stops::Stops {
                lower: l.lower,
                upper: l.upper,
                stiffness: l.stop_stiffness,
                damping: l.stop_damping,
            },
        ),
    )
}
