//! Lowering a spec to the mechanics' [`ModelDef`] and [`SolverSettings`].

use crate::math::{matrix_to_quat, quat_to_matrix, rpy_to_matrix, Mat3, Vec3};
use crate::mechanics::{
    ActuatorDef, ActuatorLaw, BodyDef, BodyLoadDef, ContactDef, ContactLaw, CouplingDef, Frame,
    FreeBodyInitial, GroundDef, JointDef, JointInitial, JointLimits, JointType, ModelDef, ShapeDef,
    ShapeKind, SiteDef, SolverSettings,
};

use super::schema::{ActuatorKind, JointKind, JointSpec, OriginSpec, Spec};
use super::values::{rows_to_matrix, OrientationSpec};

/// The spec's contact: the ground, the shapes (those on known bodies, with a geometry) and
/// the pairs (listed ones, and with `self_collision` every pair of shapes on different bodies
/// not joined by a joint; cylinders touch the ground only).
fn contact(spec: &Spec, index: &dyn Fn(&str) -> Option<usize>) -> ContactDef {
    let ground = spec.ground.map(|g| GroundDef {
        height: g.height,
        law: ContactLaw {
            friction: g.friction,
            stiffness: g.stiffness,
            damping: g.damping,
        },
    });
    let base = ground.map(|g| g.law).unwrap_or_default();
    let names = spec.collision_names();
    let mut shapes = Vec::new();
    let mut at: Vec<Option<usize>> = Vec::new();
    for (c, name) in spec.collision.iter().zip(&names) {
        let kind = match (c.sphere, c.capsule, c.cuboid, c.cylinder) {
            (Some(s), None, None, None) => ShapeKind::Sphere { radius: s.radius },
            (None, Some(s), None, None) => ShapeKind::Capsule {
                radius: s.radius,
                length: s.length,
            },
            (None, None, Some(b), None) => ShapeKind::Cuboid {
                size: Vec3::from(b.size),
            },
            (None, None, None, Some(s)) => ShapeKind::Cylinder {
                radius: s.radius,
                length: s.length,
            },
            _ => {
                at.push(None);
                continue;
            }
        };
        let Some(body) = index(&c.body) else {
            at.push(None);
            continue;
        };
        let own = c.friction.is_some() || c.stiffness.is_some() || c.damping.is_some();
        at.push(Some(shapes.len()));
        shapes.push(ShapeDef {
            name: name.clone(),
            body,
            kind,
            frame: frame(&c.origin),
            law: own.then(|| ContactLaw {
                friction: c.friction.unwrap_or(base.friction),
                stiffness: c.stiffness.unwrap_or(base.stiffness),
                damping: c.damping.unwrap_or(base.damping),
            }),
        });
    }
    let by_name = |n: &str| names.iter().position(|m| m == n).and_then(|i| at[i]);
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    let add = |a: usize, b: usize, pairs: &mut Vec<(usize, usize)>| {
        let touchable = shapes[a].body != shapes[b].body
            && crate::mechanics::contact::pair_supported(&shapes[a].kind, &shapes[b].kind);
        if touchable && !pairs.contains(&(a, b)) && !pairs.contains(&(b, a)) {
            pairs.push((a, b));
        }
    };
    for p in &spec.contact_pair {
        if let (Some(a), Some(b)) = (by_name(&p.a), by_name(&p.b)) {
            add(a, b, &mut pairs);
        }
    }
    if spec.self_collision {
        let joined = |x: usize, y: usize| {
            spec.joint.iter().any(|j| {
                let (p, c) = (index(&j.parent), index(&j.child));
                (p == Some(x) && c == Some(y)) || (p == Some(y) && c == Some(x))
            })
        };
        for a in 0..shapes.len() {
            for b in a + 1..shapes.len() {
                if !joined(shapes[a].body, shapes[b].body) {
                    add(a, b, &mut pairs);
                }
            }
        }
    }
    ContactDef {
        ground,
        shapes,
        pairs,
    }
}

/// The mechanics' joint type of a spec joint type.
pub(crate) fn joint_type(kind: JointKind) -> JointType {
    match kind {
        JointKind::Revolute => JointType::Revolute,
        JointKind::Prismatic => JointType::Prismatic,
        JointKind::Cylindrical => JointType::Cylindrical,
        JointKind::Universal => JointType::Universal,
        JointKind::Spherical => JointType::Spherical,
        JointKind::Planar => JointType::Planar,
        JointKind::Fixed => JointType::Fixed,
    }
}

fn frame(o: &OriginSpec) -> Frame {
    Frame {
        translation: Vec3::from(o.xyz),
        rotation: rpy_to_matrix(&Vec3::from(o.rpy)),
    }
}

fn unit(v: Option<[f64; 3]>) -> Vec3 {
    let v = Vec3::from(v.unwrap_or([0.0, 0.0, 1.0]));
    v.try_normalize(0.0).unwrap_or_else(Vec3::z)
}

fn initial(j: &JointSpec) -> JointInitial {
    let Some(init) = &j.initial else {
        return if j.kind == JointKind::Spherical {
            JointInitial::Spherical {
                quat: [1.0, 0.0, 0.0, 0.0],
                w: Vec3::zeros(),
            }
        } else {
            JointInitial::default()
        };
    };
    if j.kind == JointKind::Spherical {
        let quat = match (init.quat, init.rpy) {
            (Some(q), _) => {
                let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
                if n > 0.0 {
                    q.map(|x| x / n)
                } else {
                    [1.0, 0.0, 0.0, 0.0]
                }
            }
            (None, Some(rpy)) => matrix_to_quat(&rpy_to_matrix(&Vec3::from(rpy))),
            (None, None) => [1.0, 0.0, 0.0, 0.0],
        };
        JointInitial::Spherical {
            quat,
            w: Vec3::from(init.w.unwrap_or_default()),
        }
    } else {
        let q = init
            .q
            .as_ref()
            .map(super::values::Coords::values)
            .unwrap_or_default();
        let qd = init
            .qd
            .as_ref()
            .map(super::values::Coords::values)
            .unwrap_or_default();
        JointInitial::Coords { q, qd }
    }
}

/// The couplings of `spec` as joint indices of the lowered `joints`; each follower's initial
/// `q`, `qd` set from its leader's (`q_b = r q_a + o`, `q̇_b = r q̇_a`), leaders first along a
/// chain of couplings. Unknown names (reported by validation) are left out.
fn couplings(spec: &Spec, joints: &mut [JointDef]) -> Vec<CouplingDef> {
    let at = |name: &str| joints.iter().position(|j| j.name == name);
    let out: Vec<CouplingDef> = spec
        .coupling
        .iter()
        .filter_map(|c| {
            Some(CouplingDef {
                a: at(&c.a)?,
                b: at(&c.b)?,
                ratio: c.ratio,
                offset: c.offset,
            })
        })
        .collect();
    // a follower's state from its leader's, repeated so that a chain settles in any order
    for _ in 0..out.len() {
        for c in &out {
            let JointInitial::Coords { q, qd } = &joints[c.a].initial else {
                continue;
            };
            let (qa, qda) = (
                q.first().copied().unwrap_or(0.0),
                qd.first().copied().unwrap_or(0.0),
            );
            joints[c.b].initial = JointInitial::Coords {
                q: vec![c.ratio * qa + c.offset],
                qd: vec![c.ratio * qda],
            };
        }
    }
    out
}

fn limits(j: &JointSpec) -> JointLimits {
    let d = JointLimits::default();
    JointLimits {
        lower: j.lower.unwrap_or(d.lower),
        upper: j.upper.unwrap_or(d.upper),
        effort: j.effort.unwrap_or(d.effort),
        stop_stiffness: j.stop_stiffness.unwrap_or(d.stop_stiffness),
        stop_damping: j.stop_damping.unwrap_or(d.stop_damping),
        actuator_force: j.actuatorfrcrange,
    }
}

fn orientation(o: Option<&OrientationSpec>) -> Mat3 {
    match o {
        None => Mat3::identity(),
        Some(OrientationSpec::Quat(q)) => quat_to_matrix(q),
        Some(OrientationSpec::Matrix(m)) => rows_to_matrix(m),
    }
}

/// The spec's actuators on the lowered `joints` (those on known joints).
fn actuators(spec: &Spec, joints: &[JointDef]) -> Vec<ActuatorDef> {
    spec.actuator
        .iter()
        .filter_map(|a| {
            let joint = joints.iter().position(|j| j.name == a.joint)?;
            let law = match a.kind {
                ActuatorKind::Motor => ActuatorLaw::Motor,
                ActuatorKind::Position => ActuatorLaw::Position {
                    kp: a.kp.unwrap_or(0.0),
                    kv: a.kv.unwrap_or(0.0),
                },
                ActuatorKind::Velocity => ActuatorLaw::Velocity {
                    kv: a.kv.unwrap_or(0.0),
                },
            };
            Some(ActuatorDef {
                name: a.name.clone(),
                joint,
                law,
                gear: a.gear,
                ctrlrange: a.ctrlrange,
                forcerange: a.forcerange,
            })
        })
        .collect()
}

/// Builds the definition of a structurally valid spec (see `validate::structure`); lookups that
/// cannot fail on such a spec fall back to harmless values instead of panicking.
pub(crate) fn build(spec: &Spec) -> (ModelDef, SolverSettings) {
    let index = |name: &str| spec.body.iter().position(|b| b.name == name);
    let bodies = spec
        .body
        .iter()
        .map(|b| BodyDef {
            name: b.name.clone(),
            mass: b.mass,
            com: Vec3::from(b.com),
            inertia: b.inertia.matrix(),
        })
        .collect();
    // tree joints first, then loop-closing ones, each in spec order
    let ordered = spec
        .joint
        .iter()
        .filter(|j| !j.is_loop_closing())
        .chain(spec.joint.iter().filter(|j| j.is_loop_closing()));
    let mut joints: Vec<JointDef> = ordered
        .map(|j| JointDef {
            name: j.name.clone(),
            kind: joint_type(j.kind),
            parent: if j.parent == "world" {
                None
            } else {
                index(&j.parent)
            },
            child: index(&j.child).unwrap_or(0),
            parent_frame: frame(&j.origin),
            child_frame: j.child_origin.as_ref().map_or_else(Frame::identity, frame),
            axis: unit(j.axis),
            axis2: if j.kind == JointKind::Universal {
                unit(j.axis2)
            } else {
                Vec3::zeros()
            },
            actuated: j.actuated,
            damping: j.damping,
            stiffness: j.stiffness,
            limits: limits(j),
            armature: j.armature,
            friction: j.friction,

            loop_closing: j.is_loop_closing(),
            initial: initial(j),
        })
        .collect();
    let loads = spec
        .load
        .iter()
        .filter_map(|l| {
            index(&l.body).map(|body| BodyLoadDef {
                body,
                torque: l.torque,
                force: l.force,
            })
        })
        .collect();
    let free_bodies = spec
        .body
        .iter()
        .enumerate()
        .filter(|(_, b)| b.position.is_some())
        .map(|(body, b)| FreeBodyInitial {
            body,
            position: Vec3::from(b.position.unwrap_or_default()),
            orientation: orientation(b.orientation.as_ref()),
            velocity: Vec3::from(b.velocity.unwrap_or_default()),
            angular_velocity: Vec3::from(b.angular_velocity.unwrap_or_default()),
        })
        .collect();
    let sites = spec
        .site
        .iter()
        .filter_map(|s| {
            index(&s.body).map(|body| SiteDef {
                name: s.name.clone(),
                body,
                frame: frame(&s.origin),
            })
        })
        .collect();
    let contact = contact(spec, &index);
    let actuators = actuators(spec, &joints);
    let couplings = couplings(spec, &mut joints);
    let def = ModelDef {
        actuators,
        couplings,
        contact,
        gravity: Vec3::from(spec.gravity),
        bodies,
        joints,
        loads,
        free_bodies,
        sites,
    };
    let settings = SolverSettings {
        max_step: spec.solver.max_step,
        order: spec.solver.order,
        tolerance: spec.solver.tolerance,
        max_substeps: spec.solver.max_substeps,
        stages: spec.solver.stages,
        rtol: spec.solver.rtol,
        atol: spec.solver.atol,
        min_step: spec.solver.min_step,
        ..SolverSettings::default()
    };
    (def, settings)
}
