//! From the URDF's links and joints to a model spec: the tree, the base, merged fixed links,
//! inertials in the link frames (`mass`), identifiers.
//!
//! ```text
//! T_host←C  = T_host←P ∘ origin_j                 (a fixed joint j merges child C into P's host)
//! ```
//!
//! A body that takes a single inertial keeps it as written (no parallel-axis round trip).

use std::collections::HashMap;

use super::mass::{distribute, Iso, Parts, Placement};
use super::options::{Base, ImportOptions};
use super::robot::{at, Geometry, JointType, Robot, Shape};
use crate::import::entries::{empty_spec, massless_body};
use crate::import::inertia::set_inertial;
use crate::import::names::Namer;
use crate::math::{rpy_to_matrix, Vec3};
use crate::spec::{
    did_you_mean, CouplingSpec, JointKind, JointSpec, OrientationSpec, OriginSpec, Problem,
    SiteSpec, Spec, VisualSpec,
};

/// What the import produced besides the spec.
#[derive(Debug, Default)]
pub struct Outcome {
    /// Notes for `check` and `import` (what was merged, ignored or chosen).
    pub notes: Vec<String>,
    /// `(kind, identifier, URDF name)` for every body and joint whose name changed.
    pub renamed: Vec<(&'static str, String, String)>,
    /// `(identifier, URDF link names merged into it)` per body, in the spec's body order.
    pub merged: Vec<(String, Vec<String>)>,
    /// The URDF line of each body's (first) link, in the spec's body order.
    pub body_lines: Vec<usize>,
    /// The URDF line of each joint, in the spec's joint order.
    pub joint_lines: Vec<usize>,
    /// What was dropped from the robot because it could not be read (geometry only: a
    /// `<visual>` or `<collision>`), each with its line.
    pub warnings: Vec<String>,
    /// Where each `[[collision]]` came from (`--contacts`), in the spec's order: the URDF
    /// element, its line and the body it was merged into.
    pub collisions: Vec<String>,
    /// Every free body (floating base) and how the import would weld it to the world
    /// (`drop --floating-base`, `import with --fixed-base`): for messages about it.
    pub free_bases: Vec<(String, String)>,
    /// Why the import stopped before the robot's tree was known (the checks after it, on the
    /// spec, could not run): set with the problems that stopped it.
    pub skipped: Option<String>,
    /// `--on-ground`: the floating base whose initial `position` was moved, and why.
    pub placed: Option<(String, String)>,
}

/// Lowers `robot` to a spec; `problems` collects what makes that impossible.
#[allow(clippy::too_many_lines)]
pub(crate) fn spec(
    robot: &Robot,
    opts: &ImportOptions,
    origin: &str,
    problems: &mut Vec<Problem>,
) -> (Spec, Outcome) {
    let mut out = Outcome::default();
    // the problems of the robot's values (with placeholders) do not stop the lowering; those
    // of its tree do
    let before = problems.len();
    let mut link_at: HashMap<&str, usize> = HashMap::new();
    for (i, l) in robot.links.iter().enumerate() {
        if let Some(&first) = link_at.get(l.name.as_str()) {
            problems.push(Problem::new(
                at(l.line, &format!("link \"{}\"", l.name)),
                format!(
                    "duplicate link name (also line {})",
                    robot.links[first].line
                ),
            ));
        } else {
            link_at.insert(&l.name, i);
        }
    }
    let mut parent_joint: Vec<Option<usize>> = vec![None; robot.links.len()];
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); robot.links.len()];
    let mut joint_names: HashMap<&str, usize> = HashMap::new();
    for (k, j) in robot.joints.iter().enumerate() {
        let whose = format!("joint \"{}\"", j.name);
        if let Some(&first) = joint_names.get(j.name.as_str()) {
            problems.push(Problem::new(
                at(j.line, &whose),
                format!(
                    "duplicate joint name (also line {})",
                    robot.joints[first].line
                ),
            ));
        } else {
            joint_names.insert(&j.name, k);
        }
        let find = |role: &str, name: &str, problems: &mut Vec<Problem>| {
            let found = link_at.get(name).copied();
            if found.is_none() && !name.is_empty() {
                problems.push(Problem::new(
                    at(j.line, &whose),
                    format!("{role} link \"{name}\" does not exist"),
                ));
            }
            found
        };
        let (p, c) = (
            find("parent", &j.parent, problems),
            find("child", &j.child, problems),
        );
        let (Some(p), Some(c)) = (p, c) else { continue };
        if let Some(other) = parent_joint[c] {
            problems.push(Problem::new(
                at(j.line, &whose),
                format!(
                    "link \"{}\" already has a parent joint (\"{}\", line {}): a URDF is a tree",
                    j.child, robot.joints[other].name, robot.joints[other].line
                ),
            ));
            continue;
        }
        if p == c {
            problems.push(Problem::new(
                at(j.line, &whose),
                "parent and child are the same link",
            ));
            continue;
        }
        parent_joint[c] = Some(k);
        children[p].push(k);
    }
    for j in &robot.joints {
        let Some((other, line, ..)) = &j.mimic else {
            continue;
        };
        if !joint_names.contains_key(other.as_str()) {
            // a joint named like it with the mimicking joint's prefix (`Left_` + `index_q1`)
            let prefixed = robot.joints.iter().find(|c| {
                c.name
                    .strip_suffix(other.as_str())
                    .is_some_and(|pre| !pre.is_empty() && j.name.starts_with(pre))
            });
            let hint = prefixed.map_or_else(
                || did_you_mean(other, robot.joints.iter().map(|c| c.name.as_str())),
                |c| format!("; did you mean \"{}\"?", c.name),
            );
            problems.push(Problem::new(
                at(*line, &format!("joint \"{}\"", j.name)),
                format!("<mimic joint=\"{other}\">: there is no joint \"{other}\"{hint}"),
            ));
        }
    }
    cycles(robot, &link_at, &parent_joint, problems);
    let roots: Vec<usize> = (0..robot.links.len())
        .filter(|&i| {
            parent_joint[i].is_none() && link_at.get(robot.links[i].name.as_str()) == Some(&i)
        })
        .collect();
    let empty = empty_spec("robot".into(), String::new());
    match roots.as_slice() {
        [_] => {}
        [] if robot.links.is_empty() => {
            problems.push(Problem::new("", "the robot has no <link>"));
            out.skipped = Some("the robot has no link".into());
            return (empty, out);
        }
        [] => {
            // every link has a parent joint: `cycles` has named the cycles
            if problems.len() == before {
                problems.push(Problem::new(
                    "",
                    "every link has a parent joint: the joints form a cycle",
                ));
            }
            out.skipped = Some("the links and joints do not form one tree".into());
            return (empty, out);
        }
        many => {
            let names: Vec<String> = many
                .iter()
                .map(|&i| format!("\"{}\" (line {})", robot.links[i].name, robot.links[i].line))
                .collect();
            problems.push(Problem::new(
                "",
                format!(
                    "the robot has {} root links ({}): a URDF has exactly one link without a parent joint",
                    many.len(),
                    names.join(", ")
                ),
            ));
            out.skipped = Some("the links and joints do not form one tree".into());
            return (empty, out);
        }
    }
    if problems.len() > before {
        out.skipped = Some("the links and joints do not form one tree".into());
        return (empty, out);
    }
    let root = roots[0];
    // the world: a root link named "world" (it carries nothing); otherwise the root is the base
    let world_root = robot.links[root].name == "world";
    let mut bodies = Namer::new(&["world"]);
    let mut joints = Namer::default();
    let mut joint_ids: HashMap<&str, (String, JointKind)> = HashMap::new();
    let mut sites = Namer::default();
    let mut spec = empty;
    spec.name = Namer::default().name(&robot.name);
    spec.description = format!("imported from {origin} (URDF robot \"{}\")", robot.name);
    let mut parts: Vec<Parts> = Vec::new();
    // where each link ends up: its body (None: the world), its frame there, its rigid cluster
    let mut host: Vec<Option<Placement>> = vec![None; robot.links.len()];
    let mut new_body = |spec: &mut Spec, parts: &mut Vec<Parts>, link: usize, out: &mut Outcome| {
        let original = &robot.links[link].name;
        let id = bodies.name(original);
        if id != *original {
            out.renamed.push(("body", id.clone(), original.clone()));
        }
        let description = if id == *original {
            String::new()
        } else {
            format!("URDF link \"{original}\"")
        };
        spec.body.push(massless_body(id.clone(), description));
        parts.push(Vec::new());
        out.merged.push((id, vec![original.clone()]));
        out.body_lines.push(robot.links[link].line);
        spec.body.len() - 1
    };
    let free_root = !world_root && opts.base == Base::Floating;
    if world_root || !free_root {
        host[root] = Some(Placement {
            body: None,
            frame: Iso::IDENTITY,
            cluster: None,
            in_cluster: Iso::IDENTITY,
        });
        if !world_root {
            out.notes.push(format!(
                "root link '{}' is welded to the world (use --floating-base to free it)",
                robot.links[root].name
            ));
        }
    } else {
        let b = new_body(&mut spec, &mut parts, root, &mut out);
        spec.body[b].position = Some([0.0; 3]);
        out.free_bases
            .push((spec.body[b].name.clone(), "drop --floating-base".into()));
        host[root] = Some(Placement {
            body: Some(b),
            frame: Iso::IDENTITY,
            cluster: Some(root),
            in_cluster: Iso::IDENTITY,
        });
    }
    // breadth-first from the root: parents are placed before their children
    let mut queue = vec![root];
    let mut next = 0;
    while next < queue.len() {
        let pl = queue[next];
        next += 1;
        let Some(ph) = host[pl] else { continue };
        for &k in &children[pl] {
            let j = &robot.joints[k];
            let cl = link_at[j.child.as_str()];
            queue.push(cl);
            let frame = ph.frame.then(&Iso::of(&j.origin));
            let written = ph.frame.is_identity().then_some(&j.origin);
            let is_base_joint = world_root && pl == root;
            let kind = match j.kind {
                JointType::Floating if is_base_joint && opts.base != Base::Fixed => None,
                JointType::Floating if is_base_joint => Some(JointKind::Fixed),
                JointType::Fixed if is_base_joint && opts.base == Base::Floating => None,
                JointType::Floating => {
                    problems.push(Problem::new(
                        at(j.line, &format!("joint \"{}\"", j.name)),
                        "a floating joint is supported only between the world link and the base",
                    ));
                    continue;
                }
                JointType::Fixed => Some(JointKind::Fixed),
                JointType::Revolute | JointType::Continuous => Some(JointKind::Revolute),
                JointType::Prismatic => Some(JointKind::Prismatic),
                JointType::Planar => Some(JointKind::Planar),
            };
            if kind != Some(JointKind::Revolute)
                && kind != Some(JointKind::Prismatic)
                && kind != Some(JointKind::Planar)
                && (j.damping > 0.0 || j.friction > 0.0)
            {
                let what = if kind.is_some() {
                    "the joint is fixed"
                } else {
                    "the joint frees the base"
                };
                out.notes.push(format!(
                    "joint '{}': <dynamics damping=\"{}\" friction=\"{}\"> is ignored ({what}: no joint motion to damp)",
                    j.name, j.damping, j.friction
                ));
            }
            let Some(kind) = kind else {
                // the base is free: a floating body placed at the joint's origin
                let b = new_body(&mut spec, &mut parts, cl, &mut out);
                let how = if j.kind == JointType::Floating {
                    "import with --fixed-base"
                } else {
                    "drop --floating-base"
                };
                out.free_bases.push((spec.body[b].name.clone(), how.into()));
                let o = frame.origin(written);
                spec.body[b].position = Some(o.xyz);
                let r = rpy_to_matrix(&Vec3::from(o.rpy));
                spec.body[b].orientation =
                    Some(OrientationSpec::Matrix(std::array::from_fn(|i| {
                        std::array::from_fn(|c| r[(i, c)])
                    })));
                host[cl] = Some(Placement {
                    body: Some(b),
                    frame: Iso::IDENTITY,
                    cluster: Some(cl),
                    in_cluster: Iso::IDENTITY,
                });
                continue;
            };
            // a fixed joint welds the child into its parent's rigid cluster
            let (cluster, in_cluster) = if kind == JointKind::Fixed {
                (ph.cluster, ph.in_cluster.then(&Iso::of(&j.origin)))
            } else {
                (Some(cl), Iso::IDENTITY)
            };
            if kind == JointKind::Fixed && !opts.keep_fixed {
                // merged into the parent's host
                host[cl] = Some(Placement {
                    body: ph.body,
                    frame,
                    cluster,
                    in_cluster,
                });
                match ph.body {
                    Some(b) => {
                        out.merged[b].1.push(j.child.clone());
                        let id = sites.name(&j.child);
                        spec.site.push(SiteSpec {
                            description: if id == j.child {
                                String::new()
                            } else {
                                format!("URDF link \"{}\"", j.child)
                            },
                            name: id,
                            body: spec.body[b].name.clone(),
                            origin: frame.origin(written),
                        });
                    }
                    None if robot.links[cl].inertial.is_some_and(|i| i.mass > 0.0) => {
                        out.notes.push(format!(
                            "link '{}' is welded to the world: its mass does not move",
                            j.child
                        ));
                    }
                    None => {}
                }
                continue;
            }
            let b = new_body(&mut spec, &mut parts, cl, &mut out);
            host[cl] = Some(Placement {
                body: Some(b),
                frame: Iso::IDENTITY,
                cluster,
                in_cluster,
            });
            let id = joints.name(&j.name);
            if id != j.name {
                out.renamed.push(("joint", id.clone(), j.name.clone()));
            }
            let movable = matches!(kind, JointKind::Revolute | JointKind::Prismatic);
            let (lower, upper, effort) = if movable && !opts.no_limits {
                limits(j, &mut out.notes)
            } else {
                (None, None, None)
            };
            let description = if id == j.name {
                String::new()
            } else {
                format!("URDF joint \"{}\"", j.name)
            };
            out.joint_lines.push(j.line);
            joint_ids.insert(j.name.as_str(), (id.clone(), kind));
            spec.joint.push(JointSpec {
                name: id,
                kind,
                parent: ph
                    .body
                    .map_or_else(|| "world".to_string(), |p| spec.body[p].name.clone()),
                child: spec.body[b].name.clone(),
                origin: frame.origin(written),
                child_origin: None,
                axis: (kind != JointKind::Fixed).then_some(j.axis),
                axis2: None,
                actuated: movable,
                // a fixed joint's <dynamics> is ignored (noted above)
                damping: if kind == JointKind::Fixed {
                    0.0
                } else {
                    j.damping
                },
                stiffness: 0.0,
                armature: 0.0,
                // <dynamics friction> as the joint's Coulomb friction (none on a fixed joint,
                // noted above; left out with --no-friction)
                friction: if kind == JointKind::Fixed || opts.no_friction {
                    0.0
                } else {
                    j.friction
                },
                lower,
                upper,
                effort,
                actuatorfrcrange: None,
                stop_stiffness: None,
                stop_damping: None,
                initial: None,
                description,
            });
        }
    }
    if opts.no_mimic {
        for j in robot.joints.iter().filter(|j| j.mimic.is_some()) {
            out.notes.push(format!(
                "joint '{}' mimics another: imported as an independent joint (--no-mimic)",
                j.name
            ));
        }
    } else {
        mimics(robot, &joint_ids, &mut spec, &mut out.notes);
    }
    // (kept links welded to the world are bodies, but they do not move either)
    let moving = host.iter().flatten().any(|p| p.cluster.is_some());
    if !moving && problems.len() == before {
        out.skipped = Some("every link is welded to the world".into());
        let r = &robot.links[root];
        problems.push(Problem::new(
            at(r.line, &format!("link \"{}\"", r.name)),
            format!(
                "nothing moves: every link is welded to the world through root link '{}'; run the command again with --floating-base to free it",
                r.name
            ),
        ));
    }
    // the inertials, each in the frame of the body that carries it
    if problems.len() == before {
        distribute(
            robot,
            &host,
            opts.keep_fixed,
            &mut parts,
            &mut out.notes,
            problems,
        );
    }
    // the shapes, each in its host body's frame (or the world's)
    for (l, link) in robot.links.iter().enumerate() {
        let Some(h) = host[l] else { continue };
        let shapes = if link.visuals.is_empty() {
            &link.collisions
        } else {
            &link.visuals
        };
        for shape in shapes {
            let written = h.frame.is_identity().then_some(&shape.origin);
            spec.visual.push(visual(
                shape,
                h.body
                    .map_or_else(|| "world".to_string(), |b| spec.body[b].name.clone()),
                h.frame.then(&Iso::of(&shape.origin)).origin(written),
            ));
        }
    }
    if opts.contacts && problems.len() == before {
        let added = super::contacts::add(robot, &host, &out.merged, &mut spec);
        out.notes.extend(added.notes);
        out.collisions = added.sources;
    }
    for (b, p) in parts.iter().enumerate() {
        set_inertial(&mut spec.body[b], p);
    }
    (spec, out)
}

/// Reports every cycle of parent joints (links joined in a ring, attached to the root or not),
/// each once: its joints with their lines, in document order, and its links.
/// Every `<mimic>` between two revolute or two prismatic joints becomes a `[[coupling]]`
/// (`q = multiplier · q_other + offset`), the follower without an input of its own; any other
/// (a joint merged away, kinds that differ) is noted and the joint left independent.
fn mimics(
    robot: &Robot,
    joint_ids: &HashMap<&str, (String, JointKind)>,
    spec: &mut Spec,
    notes: &mut Vec<String>,
) {
    for j in &robot.joints {
        let Some((other, _, ratio, offset)) = &j.mimic else {
            continue;
        };
        let (Some((b, kb)), Some((a, ka))) = (
            joint_ids.get(j.name.as_str()),
            joint_ids.get(other.as_str()),
        ) else {
            if joint_ids.contains_key(j.name.as_str()) {
                notes.push(format!(
                    "joint '{}' mimics '{other}', which is fixed or merged: imported as an independent joint",
                    j.name
                ));
            }
            continue;
        };
        let one = matches!(ka, JointKind::Revolute | JointKind::Prismatic);
        if ka != kb || !one {
            notes.push(format!(
                "joint '{}' mimics '{other}' of another kind: imported as an independent joint (a coupling joins two revolute or two prismatic joints)",
                j.name
            ));
            continue;
        }
        if let Some(js) = spec.joint.iter_mut().find(|s| s.name == *b) {
            js.actuated = false;
        }
        spec.coupling.push(CouplingSpec {
            a: a.clone(),
            b: b.clone(),
            ratio: *ratio,
            offset: *offset,
        });
    }
}

fn cycles(
    robot: &Robot,
    link_at: &HashMap<&str, usize>,
    parent_joint: &[Option<usize>],
    problems: &mut Vec<Problem>,
) {
    // 0: not visited, 1: on the current walk up, 2: done
    let mut state = vec![0u8; parent_joint.len()];
    for start in 0..parent_joint.len() {
        let mut walk = Vec::new();
        let mut at_link = start;
        let mut closed = false;
        while state[at_link] == 0 {
            state[at_link] = 1;
            walk.push(at_link);
            let Some(k) = parent_joint[at_link] else {
                break;
            };
            at_link = link_at[robot.joints[k].parent.as_str()];
            closed = state[at_link] == 1;
        }
        if closed {
            let from = walk.iter().position(|&l| l == at_link).unwrap_or(0);
            let mut ring: Vec<usize> = walk[from..]
                .iter()
                .filter_map(|&l| parent_joint[l])
                .collect();
            ring.sort_unstable();
            let joints: Vec<String> = ring
                .iter()
                .map(|&k| {
                    format!(
                        "\"{}\" (line {})",
                        robot.joints[k].name, robot.joints[k].line
                    )
                })
                .collect();
            let links: Vec<String> = walk[from..]
                .iter()
                .rev()
                .map(|&l| format!("\"{}\"", robot.links[l].name))
                .collect();
            let first = &robot.joints[ring[0]];
            problems.push(Problem::new(
                at(first.line, &format!("joint \"{}\"", first.name)),
                format!(
                    "the joints form a cycle: joints {} join links {} in a ring; a URDF is a tree",
                    joints.join(", "),
                    links.join(", ")
                ),
            ));
        }
        for l in walk {
            state[l] = 2;
        }
    }
}

/// The position limits (revolute and prismatic joints; not continuous ones) and the effort
/// limit of a movable joint's `<limit>`; placeholders are left out with a note.
fn limits(
    j: &super::robot::Joint,
    notes: &mut Vec<String>,
) -> (Option<f64>, Option<f64>, Option<f64>) {
    let Some(l) = j.limit else {
        return (None, None, None);
    };
    let effort = match l.effort {
        Some(e) if e > 0.0 => Some(e),
        Some(_) => {
            notes.push(format!(
                "joint '{}': <limit effort=\"0\"> is a placeholder: the actuator is not clamped",
                j.name
            ));
            None
        }
        None => None,
    };
    if j.kind == JointType::Continuous {
        return (None, None, effort);
    }
    match (l.lower, l.upper) {
        (Some(lo), Some(hi)) if lo < hi => (Some(lo), Some(hi), effort),
        (Some(lo), Some(hi)) if lo == hi => {
            notes.push(format!(
                "joint '{}': <limit lower=\"{lo}\" upper=\"{hi}\"> is a placeholder: no joint stops",
                j.name
            ));
            (None, None, effort)
        }
        (Some(lo), Some(hi)) => {
            notes.push(format!(
                "joint '{}': <limit lower=\"{lo}\" upper=\"{hi}\"> has lower > upper: no joint stops",
                j.name
            ));
            (None, None, effort)
        }
        (lo, hi) => (lo, hi, effort),
    }
}

/// The spec's `[[visual]]` of a URDF shape on `body`, placed at `origin`.
fn visual(shape: &Shape, body: String, origin: OriginSpec) -> VisualSpec {
    let mut v = VisualSpec {
        body,
        origin,
        cuboid: None,
        cylinder: None,
        sphere: None,
        mesh: None,
        scale: None,
        rgba: shape.rgba,
    };
    match &shape.geometry {
        Geometry::Box(s) => v.cuboid = Some(*s),
        Geometry::Cylinder(c) => v.cylinder = Some(*c),
        Geometry::Sphere(r) => v.sphere = Some(*r),
        Geometry::Mesh(uri, scale) => {
            v.mesh = Some(uri.clone());
            v.scale = (*scale != [1.0; 3]).then_some(*scale);
        }
    }
    v
}
