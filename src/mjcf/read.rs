//! Reads the document under `<mujoco>` (includes expanded) into a [`Model`]: `<compiler>`,
//! `<option>`, `<default>`, `<worldbody>`, `<keyframe>`, `<actuator>`, `<equality>`,
//! `<contact>`. Every problem is collected with its file, line and element; none stops the
//! reading of the others.

use super::defaults::{Attrs, Classes};
use super::frames::Angles;
use super::model::{Body, Compiler, FromGeom, Key, Model};
use super::reader::{flag, refused, Reader};
use super::sections::{actuators, equalities};
use super::xml::Node;
use crate::import::frame::Iso;
use crate::spec::Problem;

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
