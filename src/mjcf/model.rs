//! The MJCF document as typed data, `<default>` classes applied: compiler and option settings,
//! the bodies in MuJoCo's order (depth first, the world first) with their joints, geoms, sites
//! and inertials, keyframes, actuators, equalities and contact exclusions. Every problem is
//! collected with its file, line and element; none stops the reading of the others.

use super::defaults::{Attrs, Classes};
use super::frames::{self, frame, unit, Angles};
use super::inertia::Solid;
use super::xml::Node;
use crate::import::frame::Iso;
use crate::math::{quat_to_matrix, Mat3, Vec3};
use crate::spec::Problem;

/// `<compiler inertiafromgeom>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum FromGeom {
    /// Never: a body without `<inertial>` is massless.
    Never,
    /// Always, even over an `<inertial>`.
    Always,
    /// For bodies without `<inertial>` (MuJoCo's default).
    Auto,
}

/// The `<compiler>` settings that change the model.
#[derive(Clone, Copy, Debug)]
pub(super) struct Compiler {
    pub angles: Angles,
    pub autolimits: bool,
    pub from_geom: FromGeom,
    pub boundmass: f64,
    pub boundinertia: f64,
    pub settotalmass: Option<f64>,
}

/// MuJoCo joint types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum JointType {
    Hinge,
    Slide,
    Ball,
    Free,
}

/// `<joint>` (or `<freejoint>`), in the body frame; angles in radians.
#[derive(Clone, Debug)]
pub(super) struct Joint {
    pub name: Option<String>,
    pub at: String,
    pub kind: JointType,
    pub pos: Vec3,
    /// Unit axis.
    pub axis: Vec3,
    /// The stops, when limited.
    pub range: Option<[f64; 2]>,
    pub damping: f64,
    pub stiffness: f64,
    pub springref: f64,
    pub reference: f64,
    pub armature: f64,
    pub frictionloss: f64,
}

/// What a geom is.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Shape {
    Solid(Solid),
    Plane,
    /// Mesh, height field, signed distance field: the type's name.
    Other(String),
}

/// `<geom>`, in the body frame.
#[derive(Clone, Debug)]
pub(super) struct Geom {
    pub name: Option<String>,
    pub at: String,
    pub shape: Shape,
    pub frame: Iso,
    pub mass: Option<f64>,
    pub density: f64,
    pub contype: u32,
    pub conaffinity: u32,
    /// The sliding friction (the first of `friction`).
    pub friction: f64,
    pub solref: [f64; 2],
    /// `solimp`'s dmax (the impedance at depth).
    pub dmax: f64,
}

/// `<site>`, in the body frame.
#[derive(Clone, Debug)]
pub(super) struct Site {
    pub name: Option<String>,
    pub frame: Iso,
}

/// `<inertial>`: mass, centre of mass and inertia about it in the body frame.
#[derive(Clone, Copy, Debug)]
pub(super) struct Inertial {
    pub mass: f64,
    pub com: Vec3,
    pub inertia: Mat3,
}

/// `<body>` (index 0: `<worldbody>`).
#[derive(Clone, Debug)]
pub(super) struct Body {
    pub name: Option<String>,
    pub at: String,
    pub parent: usize,
    /// The body frame in the parent's frame at `qpos0` (`<frame>`s composed).
    pub frame: Iso,
    pub joints: Vec<Joint>,
    pub geoms: Vec<Geom>,
    pub sites: Vec<Site>,
    pub inertial: Option<Inertial>,
}

/// `<key>`.
#[derive(Clone, Debug)]
pub(super) struct Key {
    pub name: String,
    pub at: String,
    pub qpos: Option<Vec<f64>>,
    pub qvel: Option<Vec<f64>>,
}

/// Actuator kinds read (the rest are refused).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum ActuatorKind {
    Motor,
    Position,
    Velocity,
    General,
}

/// An actuator on a joint.
#[derive(Clone, Debug)]
pub(super) struct Actuator {
    pub name: Option<String>,
    pub at: String,
    pub kind: ActuatorKind,
    pub joint: String,
    pub gear: f64,
    pub ctrlrange: Option<[f64; 2]>,
    pub forcerange: Option<[f64; 2]>,
}

/// `<equality>` elements.
#[derive(Clone, Debug)]
pub(super) enum Equality {
    /// `connect body1 body2 anchor` (anchor in body1's frame).
    Connect {
        at: String,
        body1: String,
        body2: Option<String>,
        anchor: Vec3,
    },
    /// `weld body1 body2`.
    Weld {
        at: String,
        body1: String,
        body2: Option<String>,
    },
    /// `joint joint1 joint2 polycoef`.
    Joint {
        at: String,
        joint1: String,
        joint2: Option<String>,
    },
}

/// The document.
#[derive(Clone, Debug)]
pub(super) struct Model {
    pub name: String,
    pub compiler: Compiler,
    pub gravity: Option<[f64; 3]>,
    pub timestep: Option<f64>,
    pub bodies: Vec<Body>,
    pub keys: Vec<Key>,
    pub actuators: Vec<Actuator>,
    pub equalities: Vec<Equality>,
    /// `<contact><exclude body1 body2>`.
    pub excludes: Vec<(String, String)>,
    /// What was ignored or is not modelled, for the notes.
    pub notes: Vec<String>,
}

/// Elements refused wherever they appear: what triad cannot represent.
const REFUSED: [(&str, &str); 8] = [
    ("tendon", "tendons"),
    ("muscle", "muscles"),
    ("flexcomp", "flexible bodies"),
    ("flex", "flexible bodies"),
    ("deformable", "flexible bodies"),
    ("composite", "composite objects"),
    ("plugin", "plugins"),
    ("extension", "plugins"),
];

/// A problem for a refused element, if `node` is one.
fn refused(node: &Node) -> Option<Problem> {
    REFUSED
        .iter()
        .find(|(n, _)| *n == node.name)
        .map(|(_, what)| {
            node.problem(format!(
                "triad cannot represent {what}: remove <{}> (and what uses it) to import the model",
                node.name
            ))
        })
}

/// A boolean keyword (`true`/`false`) of `a`.
fn flag(a: &Attrs, key: &str, default: bool) -> Result<bool, Problem> {
    Ok(a.keyword(
        key,
        &["true", "false"],
        if default { "true" } else { "false" },
    )? == "true")
}

/// Whether `a` (a joint, or an actuator for `what` = ctrl/force) is limited: `limited`
/// true/false, or auto: limited when a range is given and `autolimits` is on.
fn limited(a: &Attrs, key: &str, has_range: bool, autolimits: bool) -> Result<bool, Problem> {
    Ok(match a.keyword(key, &["true", "false", "auto"], "auto")? {
        "true" => true,
        "false" => false,
        _ => has_range && autolimits,
    })
}

/// Reads the compiler settings of every `<compiler>`.
fn compiler(root: &Node, problems: &mut Vec<Problem>, notes: &mut Vec<String>) -> Compiler {
    let mut c = Compiler {
        angles: Angles::default(),
        autolimits: true,
        from_geom: FromGeom::Auto,
        boundmass: 0.0,
        boundinertia: 0.0,
        settotalmass: None,
    };
    for node in root.all("compiler") {
        let a = Attrs::own(node);
        let mut read = || -> Result<(), Problem> {
            c.angles.radian = a.keyword(
                "angle",
                &["degree", "radian"],
                if c.angles.radian { "radian" } else { "degree" },
            )? == "radian";
            if let Some(seq) = a.text("eulerseq") {
                let b = seq.as_bytes();
                if b.len() != 3 || !b.iter().all(|x| b"xyzXYZ".contains(x)) {
                    return Err(node.problem(format!(
                        "eulerseq=\"{seq}\": expected three of x, y, z, X, Y, Z"
                    )));
                }
                c.angles.seq = [b[0], b[1], b[2]];
            }
            c.autolimits = flag(&a, "autolimits", c.autolimits)?;
            c.from_geom = match a.keyword("inertiafromgeom", &["false", "true", "auto"], "")? {
                "false" => FromGeom::Never,
                "true" => FromGeom::Always,
                "auto" => FromGeom::Auto,
                _ => c.from_geom,
            };
            c.boundmass = a.number("boundmass", c.boundmass)?;
            c.boundinertia = a.number("boundinertia", c.boundinertia)?;
            if let Some(m) = a.numbers("settotalmass", 1, 1)? {
                c.settotalmass = (m[0] > 0.0).then_some(m[0]);
            }
            if a.keyword("coordinate", &["local", "global"], "local")? == "global" {
                return Err(node.problem("coordinate=\"global\" is not supported (MuJoCo removed it): use local coordinates"));
            }
            if a.text("balanceinertia") == Some("true") {
                notes.push("<compiler balanceinertia=\"true\"> is not applied: inertias are used as written".into());
            }
            Ok(())
        };
        if let Err(p) = read() {
            problems.push(p);
        }
    }
    c
}

/// The reader's state while walking the tree.
struct Reader<'a> {
    classes: Classes<'a>,
    compiler: Compiler,
    bodies: Vec<Body>,
    problems: Vec<Problem>,
    notes: Vec<String>,
}

impl<'a> Reader<'a> {
    /// Records `r`'s problem, if any; its value otherwise.
    fn ok<T>(&mut self, r: Result<T, Problem>) -> Option<T> {
        r.map_err(|p| self.problems.push(p)).ok()
    }

    /// Reads the children of `node` (a `<worldbody>`, `<body>` or `<frame>`) into body `b`;
    /// `offset` places `node`'s frame in `b`'s frame, `class` is the class passed down.
    fn children(&mut self, node: &'a Node, b: usize, offset: Iso, class: usize) {
        for child in &node.children {
            if let Some(p) = refused(child) {
                self.problems.push(p);
                continue;
            }
            let own = match child.name.as_str() {
                "body" | "frame" => child.attr("childclass"),
                _ => None,
            };
            let class_here = match own {
                Some(c) => match self.classes.find(c, child) {
                    Ok(k) => k,
                    Err(p) => {
                        self.problems.push(p);
                        continue;
                    }
                },
                None => class,
            };
            let Some(elem_class) = self.ok(self.classes.of(child, class_here)) else {
                continue;
            };
            let a = self.classes.attrs(child, elem_class);
            let angles = self.compiler.angles;
            match child.name.as_str() {
                "body" => {
                    let Some(f) = self.ok(frame(&a, &angles)) else {
                        continue;
                    };
                    self.bodies.push(Body {
                        name: child.attr("name").map(str::to_string),
                        at: child.at(),
                        parent: b,
                        frame: offset.then(&f),
                        joints: Vec::new(),
                        geoms: Vec::new(),
                        sites: Vec::new(),
                        inertial: None,
                    });
                    let id = self.bodies.len() - 1;
                    self.children(child, id, Iso::IDENTITY, class_here);
                }
                "frame" => {
                    let Some(f) = self.ok(frame(&a, &angles)) else {
                        continue;
                    };
                    self.children(child, b, offset.then(&f), class_here);
                }
                "joint" | "freejoint" => {
                    if b == 0 {
                        self.problems.push(child.problem(
                            "a joint in <worldbody> has no body to move: put it in a <body>",
                        ));
                        continue;
                    }
                    if !offset.is_identity() {
                        self.problems.push(child.problem("a joint inside a <frame> is not supported: put it directly in the <body>"));
                        continue;
                    }
                    if let Some(j) = self.ok(joint(&a, &self.compiler)) {
                        self.bodies[b].joints.push(j);
                    }
                }
                "geom" => {
                    if let Some(mut g) = self.ok(geom(&a, &angles)) {
                        g.frame = offset.then(&g.frame);
                        self.bodies[b].geoms.push(g);
                    }
                }
                "site" => {
                    if let Some(f) = self.ok(frame(&a, &angles)) {
                        self.bodies[b].sites.push(Site {
                            name: child.attr("name").map(str::to_string),
                            frame: offset.then(&f),
                        });
                    }
                }
                "inertial" => {
                    if b == 0 {
                        continue;
                    }
                    if let Some(i) = self.ok(inertial(&a, &angles)) {
                        let f = offset;
                        self.bodies[b].inertial = Some(Inertial {
                            mass: i.mass,
                            com: f.p + f.r * i.com,
                            inertia: f.r * i.inertia * f.r.transpose(),
                        });
                    }
                }
                "camera" | "light" => {}
                "attach" | "replicate" => self.problems.push(child.problem(format!(
                    "<{}> is not supported: expand it into bodies first (MuJoCo's model editing)",
                    child.name
                ))),
                other => self
                    .problems
                    .push(child.problem(format!("unknown element <{other}> in a body"))),
            }
        }
    }
}

/// Reads a `<joint>` or `<freejoint>`.
fn joint(a: &Attrs, c: &Compiler) -> Result<Joint, Problem> {
    let kind = if a.node.name == "freejoint" {
        JointType::Free
    } else {
        match a.keyword("type", &["hinge", "slide", "ball", "free"], "hinge")? {
            "slide" => JointType::Slide,
            "ball" => JointType::Ball,
            "free" => JointType::Free,
            _ => JointType::Hinge,
        }
    };
    let angular = kind == JointType::Hinge;
    let conv = |x: f64| if angular { c.angles.rad(x) } else { x };
    let range = a.numbers("range", 2, 2)?;
    let is_limited = limited(a, "limited", range.is_some(), c.autolimits)?;
    let range = match (is_limited, range) {
        (true, Some(r)) => {
            // a ball joint's range is its cone angle
            let k = |x: f64| {
                if kind == JointType::Ball {
                    c.angles.rad(x)
                } else {
                    conv(x)
                }
            };
            Some([k(r[0]), k(r[1])])
        }
        (true, None) => return Err(a.node.problem("limited=\"true\" needs a range")),
        _ => None,
    };
    Ok(Joint {
        name: a.node.attr("name").map(str::to_string),
        at: a.node.at(),
        kind,
        pos: Vec3::from(a.array("pos", [0.0; 3])?),
        axis: unit(a.array("axis", [0.0, 0.0, 1.0])?, "axis", a)?,
        range,
        damping: a.number("damping", 0.0)?,
        stiffness: a.number("stiffness", 0.0)?,
        springref: conv(a.number("springref", 0.0)?),
        reference: conv(a.number("ref", 0.0)?),
        armature: a.number("armature", 0.0)?,
        frictionloss: a.number("frictionloss", 0.0)?,
    })
}

/// Reads a `<geom>`.
fn geom(a: &Attrs, angles: &Angles) -> Result<Geom, Problem> {
    let kind = a.keyword(
        "type",
        &[
            "sphere",
            "capsule",
            "cylinder",
            "box",
            "ellipsoid",
            "plane",
            "mesh",
            "hfield",
            "sdf",
        ],
        "sphere",
    )?;
    let mut f = frame(a, angles)?;
    let size = a.numbers("size", 0, 3)?.unwrap_or_default();
    let fromto = a.numbers("fromto", 6, 6)?;
    let need = |n: usize| -> Result<Vec<f64>, Problem> {
        if size.len() < n {
            return Err(a.node.problem(format!(
                "a {kind} geom needs {n} size number{}, found {}",
                if n == 1 { "" } else { "s" },
                size.len()
            )));
        }
        if size[..n].iter().any(|&x| x <= 0.0) {
            return Err(a
                .node
                .problem(format!("size of a {kind} geom must be positive")));
        }
        Ok(size[..n].to_vec())
    };
    let mut half_from_to = None;
    if let Some(ft) = &fromto {
        if !matches!(kind, "capsule" | "cylinder") {
            return Err(a.node.problem(format!(
                "fromto on a {kind} geom is not supported (capsules and cylinders only)"
            )));
        }
        let (p, q) = (
            Vec3::new(ft[0], ft[1], ft[2]),
            Vec3::new(ft[3], ft[4], ft[5]),
        );
        let d = q - p;
        if d.norm() < 1e-12 {
            return Err(a.node.problem("fromto: the two points coincide"));
        }
        f = Iso {
            r: frames::z_to(d.normalize()),
            p: (p + q) * 0.5,
        };
        half_from_to = Some(d.norm() / 2.0);
    }
    let round = |s: Vec<f64>| {
        (
            s[0],
            half_from_to.unwrap_or_else(|| s.get(1).copied().unwrap_or(0.0)),
        )
    };
    let shape = match kind {
        "sphere" => Shape::Solid(Solid::Sphere(need(1)?[0])),
        "capsule" => {
            let (r, h) = round(need(if half_from_to.is_some() { 1 } else { 2 })?);
            Shape::Solid(Solid::Capsule(r, h))
        }
        "cylinder" => {
            let (r, h) = round(need(if half_from_to.is_some() { 1 } else { 2 })?);
            Shape::Solid(Solid::Cylinder(r, h))
        }
        "box" => {
            let s = need(3)?;
            Shape::Solid(Solid::Box([s[0], s[1], s[2]]))
        }
        "ellipsoid" => {
            let s = need(3)?;
            Shape::Solid(Solid::Ellipsoid([s[0], s[1], s[2]]))
        }
        "plane" => Shape::Plane,
        other => Shape::Other(other.to_string()),
    };
    let bits = |key: &str| -> Result<u32, Problem> {
        let x = a.number(key, 1.0)?;
        if x < 0.0 || x.fract() != 0.0 || x > f64::from(u32::MAX) {
            return Err(a
                .node
                .problem(format!("{key} must be a non-negative integer")));
        }
        Ok(x as u32)
    };
    let solimp = a
        .numbers("solimp", 1, 5)?
        .unwrap_or_else(|| vec![0.9, 0.95]);
    Ok(Geom {
        name: a.node.attr("name").map(str::to_string),
        at: a.node.at(),
        shape,
        frame: f,
        mass: a.numbers("mass", 1, 1)?.map(|m| m[0]),
        density: a.number("density", 1000.0)?,
        contype: bits("contype")?,
        conaffinity: bits("conaffinity")?,
        friction: a.numbers("friction", 1, 3)?.map_or(1.0, |f| f[0]),
        solref: a.array("solref", [0.02, 1.0])?,
        dmax: solimp.get(1).copied().unwrap_or(solimp[0]),
    })
}

/// Reads an `<inertial>`: mass, centre of mass and inertia about it in its parent's frame.
fn inertial(a: &Attrs, angles: &Angles) -> Result<Inertial, Problem> {
    let f = frame(a, angles)?;
    let Some(mass) = a.numbers("mass", 1, 1)?.map(|m| m[0]) else {
        return Err(a.node.problem("<inertial> needs a mass"));
    };
    let j = match (
        a.numbers("diaginertia", 3, 3)?,
        a.numbers("fullinertia", 6, 6)?,
    ) {
        (Some(d), None) => Mat3::from_diagonal(&Vec3::new(d[0], d[1], d[2])),
        (None, Some(v)) => Mat3::new(v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2]),
        (Some(_), Some(_)) => {
            return Err(a
                .node
                .problem("give one of diaginertia and fullinertia, not both"))
        }
        (None, None) => {
            return Err(a
                .node
                .problem("<inertial> needs diaginertia or fullinertia"))
        }
    };
    Ok(Inertial {
        mass,
        com: f.p,
        inertia: f.r * j * f.r.transpose(),
    })
}

/// Reads the document under `root` (includes expanded).
pub(super) fn model(root: &Node) -> Result<Model, Vec<Problem>> {
    let mut problems = Vec::new();
    let mut notes = Vec::new();
    let compiler = compiler(root, &mut problems, &mut notes);
    let classes = Classes::read(root, &mut problems);
    let mut r = Reader {
        classes,
        compiler,
        bodies: vec![Body {
            name: Some("world".into()),
            at: String::new(),
            parent: 0,
            frame: Iso::IDENTITY,
            joints: Vec::new(),
            geoms: Vec::new(),
            sites: Vec::new(),
            inertial: None,
        }],
        problems,
        notes,
    };
    let mut m = Model {
        name: root.attr("model").unwrap_or("mujoco").to_string(),
        compiler,
        gravity: None,
        timestep: None,
        bodies: Vec::new(),
        keys: Vec::new(),
        actuators: Vec::new(),
        equalities: Vec::new(),
        excludes: Vec::new(),
        notes: Vec::new(),
    };
    for node in &root.children {
        if let Some(p) = refused(node) {
            r.problems.push(p);
            continue;
        }
        let a = Attrs::own(node);
        match node.name.as_str() {
            "worldbody" => r.children(node, 0, Iso::IDENTITY, 0),
            "option" => {
                if let Some(g) = r.ok(a.numbers("gravity", 3, 3)) {
                    m.gravity = g.map(|g| [g[0], g[1], g[2]]);
                }
                if let Some(t) = r.ok(a.numbers("timestep", 1, 1)) {
                    m.timestep = t.map(|t| t[0]);
                }
            }
            "keyframe" => {
                for (k, key) in node.all("key").enumerate() {
                    let a = Attrs::own(key);
                    let qpos = r.ok(a.numbers("qpos", 0, usize::MAX)).flatten();
                    let qvel = r.ok(a.numbers("qvel", 0, usize::MAX)).flatten();
                    m.keys.push(Key {
                        name: key
                            .attr("name")
                            .map_or_else(|| k.to_string(), str::to_string),
                        at: key.at(),
                        qpos,
                        qvel,
                    });
                }
            }
            "actuator" => actuators(&mut r, node, &mut m.actuators),
            "equality" => equalities(&mut r, node, &mut m.equalities),
            "contact" => {
                for c in &node.children {
                    match (c.name.as_str(), c.attr("body1"), c.attr("body2")) {
                        ("exclude", Some(b1), Some(b2)) => {
                            m.excludes.push((b1.to_string(), b2.to_string()));
                        }
                        ("exclude", ..) => r.problems.push(c.problem("<exclude> needs body1 and body2")),
                        _ => r.notes.push(format!(
                            "{}: explicit contact pairs are not imported (contacts follow contype/conaffinity)",
                            c.at()
                        )),
                    }
                }
            }
            "sensor" => r.notes.push(
                "<sensor> elements are ignored (triad's outputs cover body, joint and site states)"
                    .into(),
            ),
            "compiler" | "size" | "visual" | "statistic" | "asset" | "default" | "custom" => {}
            other => r
                .problems
                .push(node.problem(format!("unknown element <{other}> in <mujoco>"))),
        }
    }
    if !r.problems.is_empty() {
        return Err(r.problems);
    }
    m.bodies = r.bodies;
    m.notes = r.notes;
    Ok(m)
}

/// Reads the `<actuator>` section.
fn actuators(r: &mut Reader, node: &Node, out: &mut Vec<Actuator>) {
    for act in &node.children {
        if let Some(p) = refused(act) {
            r.problems.push(p);
            continue;
        }
        let kind = match act.name.as_str() {
            "motor" => ActuatorKind::Motor,
            "position" => ActuatorKind::Position,
            "velocity" => ActuatorKind::Velocity,
            "general" => ActuatorKind::General,
            other => {
                r.problems.push(act.problem(format!(
                    "actuator <{other}> is not supported (motor, position, velocity, general on a joint are)"
                )));
                continue;
            }
        };
        let Some(class) = r.ok(r.classes.of(act, 0)) else {
            continue;
        };
        let a = r.classes.attrs(act, class);
        let Some(joint) = a.text("joint") else {
            r.problems.push(act.problem(
                "only actuators on a joint (joint=\"...\") are supported: tendon, site and body transmissions are not",
            ));
            continue;
        };
        let autolimits = r.compiler.autolimits;
        let read = || -> Result<Actuator, Problem> {
            let ctrl = a.numbers("ctrlrange", 2, 2)?;
            let force = a.numbers("forcerange", 2, 2)?;
            let ctrl_on = limited(&a, "ctrllimited", ctrl.is_some(), autolimits)?;
            let force_on = limited(&a, "forcelimited", force.is_some(), autolimits)?;
            Ok(Actuator {
                name: act.attr("name").map(str::to_string),
                at: act.at(),
                kind,
                joint: joint.to_string(),
                gear: a.numbers("gear", 1, 6)?.map_or(1.0, |g| g[0]),
                ctrlrange: ctrl.filter(|_| ctrl_on).map(|v| [v[0], v[1]]),
                forcerange: force.filter(|_| force_on).map(|v| [v[0], v[1]]),
            })
        };
        if let Some(x) = r.ok(read()) {
            out.push(x);
        }
    }
}

/// Reads the `<equality>` section.
fn equalities(r: &mut Reader, node: &Node, out: &mut Vec<Equality>) {
    for e in &node.children {
        let Some(class) = r.ok(r.classes.of(e, 0)) else {
            continue;
        };
        let a = r.classes.attrs(e, class);
        let need = |key: &str| {
            a.text(key)
                .map(str::to_string)
                .ok_or_else(|| e.problem(format!("<{}> needs {key}", e.name)))
        };
        let read = || -> Result<Equality, Problem> {
            Ok(match e.name.as_str() {
                "connect" => {
                    if a.text("site1").is_some() {
                        return Err(e.problem(
                            "<connect site1 site2> is not supported: use body1, body2 and anchor",
                        ));
                    }
                    Equality::Connect {
                        at: e.at(),
                        body1: need("body1")?,
                        body2: a.text("body2").map(str::to_string),
                        anchor: Vec3::from(a.array("anchor", [0.0; 3])?),
                    }
                }
                "weld" => {
                    if a.text("site1").is_some() {
                        return Err(
                            e.problem("<weld site1 site2> is not supported: use body1 and body2")
                        );
                    }
                    if a.text("relpose").is_some() {
                        return Err(e.problem("<weld relpose> is not supported: the bodies are welded where they are at the model's pose"));
                    }
                    Equality::Weld {
                        at: e.at(),
                        body1: need("body1")?,
                        body2: a.text("body2").map(str::to_string),
                    }
                }
                "joint" => Equality::Joint {
                    at: e.at(),
                    joint1: need("joint1")?,
                    joint2: a.text("joint2").map(str::to_string),
                },
                other => {
                    return Err(e.problem(format!(
                        "<equality><{other}> is not supported (connect, weld, joint are)"
                    )))
                }
            })
        };
        if let Some(x) = r.ok(read()) {
            out.push(x);
        }
    }
}

/// A quaternion `[w, x, y, z]` as a rotation (for keyframes).
pub(super) fn rotation(q: [f64; 4]) -> Mat3 {
    quat_to_matrix(&q)
}
