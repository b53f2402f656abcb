//! From the typed MJCF to a model spec: bodies, joint frames, inertials, sites, the initial
//! state (`qpos0`, or a keyframe), actuated joints, loop-closing equalities.
//!
//! Frames. MuJoCo places a body at `F` (its `pos` and orientation in the parent) and moves it
//! by its joints, each about its anchor `a` (`pos`, body frame): for a hinge
//! `J(q) = T(a) R(n, q − ref) T(−a)`, for a slide `J(q) = T(n (q − ref))`; the joints of one
//! body compose in document order. triad's joint frame is its child's frame at q = 0, so each
//! triad body is its MuJoCo body's frame shifted to the anchor of the body's last joint,
//! `C = T(a)`, and joint k's origin in the previous triad frame is
//!
//! ```text
//! O_k = M_{k−1} ∘ T(a_k) ∘ R(n_k, −ref_k)      hinge       (axis n_k in that frame)
//! O_k = M_{k−1} ∘ T(a_k − n_k ref_k)           slide
//! O_k = M_{k−1} ∘ T(a_k)                        ball
//! ```
//!
//! with `M_0` the MuJoCo body frame in its parent's triad frame and `M_k = T(−a_k)`. Then
//! triad's `q` equals MuJoCo's `qpos` exactly, `ref` included. The bodies between a body's
//! joints are massless triad bodies (`body_joint`). A body without joints is merged into its
//! parent's triad body (its inertial added, its frame a site), or welded to the world.
//!
//! One joint's spec is `joint_spec`'s, the inertials `body_inertials`'.

use std::collections::HashMap;

use super::model::{JointType, Model};
use super::{body_inertials, joint_spec};
use crate::import::entries::{empty_spec, massless_body};
use crate::import::frame::Iso;
use crate::import::inertia::{set_inertial, Part};
use crate::import::names::Namer;
use crate::math::matrix_to_quat;
use crate::spec::{OrientationSpec, Problem, SiteSpec, Spec};

/// What the import produced besides the spec.
#[derive(Debug, Default)]
pub struct Outcome {
    /// What was ignored, approximated or chosen.
    pub notes: Vec<String>,
    /// The MJCF element of each spec body, in the spec's order.
    pub bodies: Vec<String>,
    /// The MJCF element of each spec joint, in the spec's order.
    pub joints: Vec<String>,
    /// Where each `[[collision]]` came from, in the spec's order.
    pub collisions: Vec<String>,
    /// The MJCF element of each `[[actuator]]`, in the spec's order.
    pub actuators: Vec<String>,
}

/// The spec and what the later stages (actuators, keyframe, equalities, contacts) need.
pub(super) struct Lowered {
    pub spec: Spec,
    pub outcome: Outcome,
    /// Where each MuJoCo body ended up.
    pub host: Vec<Host>,
    /// The coordinates of `qpos`, in MuJoCo's order.
    pub slots: Vec<Slot>,
    /// The spec joint of each named MuJoCo joint.
    pub joint_of: HashMap<String, usize>,
}

/// Where a MuJoCo body ended up.
#[derive(Clone, Copy, Debug)]
pub(super) struct Host {
    /// The spec body carrying it (None: the world).
    pub body: Option<usize>,
    /// Its MuJoCo frame in that body's frame.
    pub place: Iso,
}

/// A joint's coordinates in MuJoCo's `qpos`/`qvel`.
#[derive(Clone, Copy, Debug)]
pub(super) enum Slot {
    /// A spec joint (hinge, slide, ball).
    Joint(usize, JointType),
    /// A free body.
    Free(usize),
}

/// The name of MuJoCo body `i` (its `name`, else `body{i}`).
pub(super) fn body_name(m: &Model, i: usize) -> String {
    m.bodies[i]
        .name
        .clone()
        .unwrap_or_else(|| format!("body{i}"))
}

/// The world frame of every MuJoCo body at `qpos0`.
pub(super) fn world_frames(m: &Model) -> Vec<Iso> {
    let mut w = vec![Iso::IDENTITY; m.bodies.len()];
    for i in 1..m.bodies.len() {
        w[i] = w[m.bodies[i].parent].then(&m.bodies[i].frame);
    }
    w
}

/// Lowers `m` to a spec; `problems` collects what makes that impossible.
#[allow(clippy::too_many_lines)]
pub(super) fn spec(m: &Model, origin: &str, problems: &mut Vec<Problem>) -> Lowered {
    let mut out = Outcome {
        notes: m.notes.clone(),
        ..Outcome::default()
    };
    let mut spec = empty_spec(
        Namer::default().name(&m.name),
        format!("imported from {origin} (MJCF model \"{}\")", m.name),
    );
    if let Some(g) = m.gravity {
        spec.gravity = g;
    }
    if let Some(t) = m.timestep {
        if t > 0.0 && t <= spec.experiment.step {
            spec.solver.max_step = t;
        }
    }
    let mut bodies = Namer::new(&["world"]);
    let mut joints = Namer::default();
    let mut sites = Namer::default();
    let world = world_frames(m);
    let mut host = vec![
        Host {
            body: None,
            place: Iso::IDENTITY,
        };
        m.bodies.len()
    ];
    let mut slots: Vec<Slot> = Vec::new();
    // the spec joint of each named MuJoCo joint, for actuators and equalities
    let mut joint_of: HashMap<&str, usize> = HashMap::new();
    let mut parts: Vec<Vec<Part>> = Vec::new();
    let mut add_body = |spec: &mut Spec,
                        parts: &mut Vec<Vec<Part>>,
                        out: &mut Outcome,
                        original: &str,
                        at: &str| {
        let id = bodies.name(original);
        let description = if id == original {
            String::new()
        } else {
            format!("MJCF body \"{original}\"")
        };
        spec.body.push(massless_body(id, description));
        parts.push(Vec::new());
        out.bodies.push(at.to_string());
        spec.body.len() - 1
    };
    for i in 1..m.bodies.len() {
        let b = &m.bodies[i];
        let name = body_name(m, i);
        let ph = host[b.parent];
        let frame0 = ph.place.then(&b.frame);
        if b.joints.is_empty() {
            host[i] = Host {
                body: ph.body,
                place: frame0,
            };
            if let (Some(hb), Some(n)) = (ph.body, &b.name) {
                let id = sites.name(n);
                spec.site.push(SiteSpec {
                    description: format!(
                        "MJCF body \"{n}\" (no joint: merged into {})",
                        spec.body[hb].name
                    ),
                    name: id,
                    body: spec.body[hb].name.clone(),
                    origin: frame0.origin_spec(),
                });
            }
            continue;
        }
        if let Some(free) = b.joints.iter().find(|j| j.kind == JointType::Free) {
            if b.joints.len() > 1 || b.parent != 0 {
                problems.push(Problem::new(
                    free.at.clone(),
                    "a free joint must be the only joint of a body that is a child of <worldbody>",
                ));
                continue;
            }
            let k = add_body(&mut spec, &mut parts, &mut out, &name, &b.at);
            let w = world[i];
            spec.body[k].position = Some([w.p.x, w.p.y, w.p.z]);
            spec.body[k].orientation = Some(OrientationSpec::Quat(matrix_to_quat(&w.r)));
            host[i] = Host {
                body: Some(k),
                place: Iso::IDENTITY,
            };
            slots.push(Slot::Free(k));
            if let Some(n) = &free.name {
                if free.damping > 0.0 || free.armature > 0.0 || free.frictionloss > 0.0 {
                    out.notes.push(format!(
                        "free joint '{n}': damping, armature and frictionloss of a free joint are not modelled"
                    ));
                }
            }
            continue;
        }
        let mut m_prev = frame0;
        let mut parent = ph.body;
        let last = b.joints.len() - 1;
        for (k, j) in b.joints.iter().enumerate() {
            let jname = j.name.clone().unwrap_or_else(|| format!("{name}_joint"));
            let child = if k == last {
                add_body(&mut spec, &mut parts, &mut out, &name, &b.at)
            } else {
                let id = add_body(
                    &mut spec,
                    &mut parts,
                    &mut out,
                    &format!("{name}_{jname}"),
                    &b.at,
                );
                spec.body[id].description = format!(
                    "massless frame between the joints of MJCF body \"{name}\" (after joint \"{jname}\")"
                );
                id
            };
            let id = joints.name(&jname);
            let original = j.name.as_deref().unwrap_or("");
            if !original.is_empty() {
                joint_of.insert(original, spec.joint.len());
            }
            let ends = joint_spec::Ends {
                parent: parent.map_or_else(|| "world".to_string(), |p| spec.body[p].name.clone()),
                child: spec.body[child].name.clone(),
                frame: m_prev,
            };
            let (joint, next) = joint_spec::joint(j, id, ends, &mut out.notes);
            m_prev = next;
            out.joints.push(j.at.clone());
            spec.joint.push(joint);
            slots.push(Slot::Joint(spec.joint.len() - 1, j.kind));
            parent = Some(child);
        }
        host[i] = Host {
            body: parent,
            place: m_prev,
        };
    }
    if spec.joint.iter().any(|j| j.lower.is_some()) {
        out.notes.push("joint ranges are triad's one-sided elastic stops (stop_stiffness 1e4), not MuJoCo's soft limit constraints (solreflimit)".into());
    }
    // the inertials, each in its host's frame; the compiler's total mass
    let own = body_inertials::own_parts(m, problems);
    for i in 1..m.bodies.len() {
        let h = host[i];
        place_inertial(m, i, own[i], h, &mut parts, &mut out);
        place_sites(m, i, h, &mut spec, &mut sites, &mut out);
    }
    for (b, p) in parts.iter().enumerate() {
        set_inertial(&mut spec.body[b], p);
    }
    if spec.body.is_empty() && problems.is_empty() {
        problems.push(Problem::new(
            "",
            "nothing moves: no body of the model has a joint",
        ));
    }
    Lowered {
        spec,
        outcome: out,
        host,
        slots,
        joint_of: joint_of
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .collect(),
    }
}

/// The sites of MuJoCo body `i` as `[[site]]`s on its host `h` (left out, with a note, on a body
/// welded to the world).
fn place_sites(
    m: &Model,
    i: usize,
    h: Host,
    spec: &mut Spec,
    sites: &mut Namer,
    out: &mut Outcome,
) {
    for s in &m.bodies[i].sites {
        let Some(b) = h.body else {
            if let Some(n) = &s.name {
                out.notes.push(format!(
                    "site '{n}' is on a body welded to the world: left out"
                ));
            }
            continue;
        };
        let n = s
            .name
            .clone()
            .unwrap_or_else(|| format!("{}_site", body_name(m, i)));
        let id = sites.name(&n);
        spec.site.push(SiteSpec {
            description: if id == n {
                String::new()
            } else {
                format!("MJCF site \"{n}\"")
            },
            name: id,
            body: spec.body[b].name.clone(),
            origin: h.place.then(&s.frame).origin_spec(),
        });
    }
}

/// Adds MuJoCo body `i`'s inertial `own` to the parts of its host `h`, in the host's frame (a
/// note when the body is welded to the world with a mass).
fn place_inertial(
    m: &Model,
    i: usize,
    (mass, com, j): Part,
    h: Host,
    parts: &mut [Vec<Part>],
    out: &mut Outcome,
) {
    match h.body {
        Some(b) => parts[b].push((
            mass,
            h.place.p + h.place.r * com,
            h.place.r * j * h.place.r.transpose(),
        )),
        None if mass > 0.0 => out.notes.push(format!(
            "body '{}' has no joint: it is welded to the world and its mass does not move",
            body_name(m, i)
        )),
        None => {}
    }
}
