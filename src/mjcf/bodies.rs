//! The body tree: `<body>`, `<frame>` (composed into its children's frames), `<joint>`,
//! `<freejoint>`, `<geom>`, `<site>`, `<inertial>`, each element with its class.

use super::defaults::Attrs;
use super::frames::{self, frame, unit, Angles};
use super::inertia::Solid;
use super::model::{Body, Compiler, Geom, Inertial, Joint, JointType, Shape, Site};
use super::reader::{limited, refused, Reader};
use super::xml::Node;
use crate::import::frame::Iso;
use crate::math::{Mat3, Vec3};
use crate::spec::Problem;

impl<'a> Reader<'a> {
    /// Reads the children of `node` (a `<worldbody>`, `<body>` or `<frame>`) into body `b`;
    /// `offset` places `node`'s frame in `b`'s frame, `class` is the class passed down.
    pub(super) fn children(&mut self, node: &'a Node, b: usize, offset: Iso, class: usize) {
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
    // the clamp of the summed actuator force, as MuJoCo compiles it (in force units: no
    // angle conversion)
    let frc = a.numbers("actuatorfrcrange", 2, 2)?;
    let frc_on = limited(a, "actuatorfrclimited", frc.is_some(), c.autolimits)?;
    let actuatorfrcrange = match (frc_on, frc) {
        (true, Some(r)) => Some([r[0], r[1]]),
        (true, None) => {
            return Err(a
                .node
                .problem("actuatorfrclimited=\"true\" needs an actuatorfrcrange"))
        }
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
        actuatorfrcrange,
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
