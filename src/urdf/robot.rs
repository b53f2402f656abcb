//! The URDF document as typed data: links with their inertials, joints with their frames, axes
//! and dynamics. Every problem is collected (with the element's line), none stops the reading.
//! Geometry is not needed by the dynamics: a `<visual>` or `<collision>` that cannot be read is
//! dropped with a warning (its line and what is wrong), never a problem.

use crate::import::xml::Element;
use crate::spec::Problem;

/// A placement `origin xyz rpy` (m; rad, fixed-axis roll, pitch, yaw).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Pose {
    pub xyz: [f64; 3],
    pub rpy: [f64; 3],
}

/// `<inertial>`: the centre-of-mass frame in the link frame, the mass (kg) and the inertia
/// about the centre of mass in that frame (kg·m²).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Inertial {
    pub origin: Pose,
    pub mass: f64,
    /// `[ixx, iyy, izz, ixy, ixz, iyz]`.
    pub inertia: [f64; 6],
    /// The line of `<inertia>` (of `<inertial>` when it has none).
    pub line: usize,
}

/// The geometry of a `<visual>` or `<collision>` (m).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Geometry {
    Box([f64; 3]),
    /// Radius, length (along z).
    Cylinder([f64; 2]),
    Sphere(f64),
    /// The URI as written (`package://`, relative or absolute) and its scale.
    Mesh(String, [f64; 3]),
}

/// A `<visual>` (or, for a link without any, a `<collision>`): its frame in the link frame, its
/// geometry and the colour of its `<material>` when given inline.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Shape {
    /// The line of the `<visual>` or `<collision>` element.
    pub line: usize,
    pub origin: Pose,
    pub geometry: Geometry,
    pub rgba: Option<[f64; 4]>,
}

/// `<link>`.
#[derive(Clone, Debug)]
pub(crate) struct Link {
    pub name: String,
    pub line: usize,
    /// None: a link without `<inertial>` (massless).
    pub inertial: Option<Inertial>,
    /// Its readable `<visual>` elements, for the viewer.
    pub visuals: Vec<Shape>,
    /// Its readable `<collision>` elements (drawn when the link has no visual).
    pub collisions: Vec<Shape>,
}

/// URDF joint types.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum JointType {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
}

/// `<limit>` (absent attributes as None).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Limit {
    pub lower: Option<f64>,
    pub upper: Option<f64>,
    pub effort: Option<f64>,
}

/// `<joint>`.
#[derive(Clone, Debug)]
pub(crate) struct Joint {
    pub name: String,
    pub line: usize,
    pub kind: JointType,
    pub parent: String,
    pub child: String,
    pub origin: Pose,
    /// In the joint frame (default `1 0 0`), as written (not normalised).
    pub axis: [f64; 3],
    pub damping: f64,
    pub friction: f64,
    pub limit: Option<Limit>,
    /// The `<mimic>`: the joint this one follows, the line, `multiplier` (default 1) and
    /// `offset` (default 0): `q = multiplier · q_other + offset`.
    pub mimic: Option<(String, usize, f64, f64)>,
}

/// The robot: its name, links and joints in document order.
#[derive(Clone, Debug, Default)]
pub(crate) struct Robot {
    pub name: String,
    pub links: Vec<Link>,
    pub joints: Vec<Joint>,
    /// The elements left out because they could not be read (`line 12: <joint>`): with any,
    /// the tree the links and joints form is not known.
    pub dropped: Vec<String>,
}

/// Where a problem is: `line L: <what>`.
pub(crate) fn at(line: usize, what: &str) -> String {
    format!("line {line}: {what}")
}

/// Reads the numbers of attribute `key` of `e` (`n` of them); the default when absent.
fn numbers<const N: usize>(
    e: &Element,
    key: &str,
    default: [f64; N],
    whose: &str,
    problems: &mut Vec<Problem>,
) -> [f64; N] {
    let Some(text) = e.attr(key) else {
        return default;
    };
    let parsed: Result<Vec<f64>, _> = text.split_whitespace().map(str::parse::<f64>).collect();
    let here = at(e.line, whose);
    match parsed {
        Ok(v) if v.len() == N && v.iter().all(|x| x.is_finite()) => std::array::from_fn(|i| v[i]),
        Ok(v) if v.len() == N => {
            problems.push(Problem::new(
                here,
                format!("<{}> {key}=\"{text}\": numbers must be finite", e.name),
            ));
            default
        }
        Ok(v) => {
            problems.push(Problem::new(
                here,
                format!(
                    "<{}> {key}=\"{text}\": expected {N} numbers, found {}",
                    e.name,
                    v.len()
                ),
            ));
            default
        }
        Err(_) => {
            problems.push(Problem::new(
                here,
                format!("<{}> {key}=\"{text}\": not a list of numbers", e.name),
            ));
            default
        }
    }
}

/// One number attribute (`None` when absent).
fn number(e: &Element, key: &str, whose: &str, problems: &mut Vec<Problem>) -> Option<f64> {
    e.attr(key)?;
    Some(numbers::<1>(e, key, [0.0], whose, problems)[0])
}

/// `<origin>` child of `e` (identity when absent).
fn origin(e: &Element, whose: &str, problems: &mut Vec<Problem>) -> Pose {
    e.first("origin").map_or_else(Pose::default, |o| Pose {
        xyz: numbers(o, "xyz", [0.0; 3], whose, problems),
        rpy: numbers(o, "rpy", [0.0; 3], whose, problems),
    })
}

/// A `<visual>` or `<collision>` element `e` of `whose`: its shape, or `Err(what is wrong)`
/// (with the line of the offending element) when it cannot be read. A missing mesh file is not
/// looked for (the URI is kept as written). A colour that cannot be read only loses the colour:
/// `colour` says why.
fn shape(e: &Element, whose: &str, colour: &mut Vec<Problem>) -> Result<Shape, Vec<Problem>> {
    let mut problems = Vec::new();
    let tag = &e.name;
    let Some(g) = e.first("geometry") else {
        return Err(vec![Problem::new(
            at(e.line, whose),
            format!("<{tag}> has no <geometry>"),
        )]);
    };
    let size = |el: &Element, key: &str, problems: &mut Vec<Problem>| {
        let v = number(el, key, whose, problems);
        if v.is_none() {
            problems.push(Problem::new(
                at(el.line, whose),
                format!("<{}> needs {key}=\"…\"", el.name),
            ));
        }
        v.unwrap_or(0.0)
    };
    let geometry = if let Some(b) = g.first("box") {
        if b.attr("size").is_none() {
            problems.push(Problem::new(
                at(b.line, whose),
                "<box> needs size=\"x y z\"",
            ));
        }
        Geometry::Box(numbers(b, "size", [0.0; 3], whose, &mut problems))
    } else if let Some(c) = g.first("cylinder") {
        Geometry::Cylinder([
            size(c, "radius", &mut problems),
            size(c, "length", &mut problems),
        ])
    } else if let Some(s) = g.first("sphere") {
        Geometry::Sphere(size(s, "radius", &mut problems))
    } else if let Some(m) = g.first("mesh") {
        let file = m.attr("filename").unwrap_or_default().trim();
        if file.is_empty() {
            problems.push(Problem::new(at(m.line, whose), "<mesh> has no filename"));
        }
        Geometry::Mesh(
            file.to_string(),
            numbers(m, "scale", [1.0; 3], whose, &mut problems),
        )
    } else {
        let found = g
            .children
            .first()
            .map_or_else(|| "nothing".to_string(), |c| format!("<{}>", c.name));
        problems.push(Problem::new(
            at(g.line, whose),
            format!("<geometry> holds {found}, not a box, cylinder, sphere or mesh"),
        ));
        Geometry::Sphere(0.0)
    };
    let negative = match &geometry {
        Geometry::Box(s) => s.iter().any(|&x| x < 0.0),
        Geometry::Cylinder(c) => c.iter().any(|&x| x < 0.0),
        Geometry::Sphere(r) => *r < 0.0,
        Geometry::Mesh(..) => false,
    };
    if negative {
        problems.push(Problem::new(
            at(g.line, whose),
            "<geometry> sizes must be >= 0",
        ));
    }
    let origin = origin(e, whose, &mut problems);
    if !problems.is_empty() {
        return Err(problems);
    }
    let rgba = e
        .first("material")
        .and_then(|m| m.first("color"))
        .and_then(|c| {
            let before = colour.len();
            let rgba = numbers(c, "rgba", [0.7, 0.7, 0.7, 1.0], whose, colour);
            (colour.len() == before).then_some(rgba)
        });
    Ok(Shape {
        line: e.line,
        origin,
        geometry,
        rgba,
    })
}

/// The readable `<visual>` (`tag`) or `<collision>` elements of link element `e`; each one that
/// cannot be read becomes a warning.
fn shapes(e: &Element, tag: &str, whose: &str, warnings: &mut Vec<String>) -> Vec<Shape> {
    let mut out = Vec::new();
    for v in e.all(tag) {
        let mut colour = Vec::new();
        match shape(v, whose, &mut colour) {
            Ok(s) => {
                for p in colour {
                    warnings.push(format!(
                        "{}: {} (the <{tag}> of line {} is drawn in the default colour)",
                        p.path, p.message, v.line
                    ));
                }
                out.push(s);
            }
            Err(problems) => {
                for p in problems {
                    warnings.push(format!(
                        "{}: {} (the <{tag}> of line {} is dropped)",
                        p.path, p.message, v.line
                    ));
                }
            }
        }
    }
    out
}

fn inertial(e: &Element, whose: &str, problems: &mut Vec<Problem>) -> Inertial {
    let mass = match e.first("mass") {
        Some(m) => match number(m, "value", whose, problems) {
            Some(v) => v,
            None => {
                problems.push(Problem::new(at(m.line, whose), "<mass> needs value=\"…\""));
                0.0
            }
        },
        None => {
            problems.push(Problem::new(at(e.line, whose), "<inertial> has no <mass>"));
            0.0
        }
    };
    if mass < 0.0 {
        problems.push(Problem::new(
            at(e.line, whose),
            format!("mass {mass} is negative"),
        ));
    }
    let mut inertia = [0.0; 6];
    let mut line = e.line;
    match e.first("inertia") {
        Some(i) => {
            line = i.line;
            for (k, key) in ["ixx", "iyy", "izz", "ixy", "ixz", "iyz"]
                .iter()
                .enumerate()
            {
                inertia[k] = number(i, key, whose, problems).unwrap_or(0.0);
            }
        }
        None if mass > 0.0 => {
            problems.push(Problem::new(
                at(e.line, whose),
                "<inertial> has a mass but no <inertia>",
            ));
            // a placeholder for the later checks (a uniform sphere of 0.1 m radius), so that
            // they report the robot's other problems in the same run
            let j = 0.4 * mass * 0.01;
            inertia = [j, j, j, 0.0, 0.0, 0.0];
        }
        None => {}
    }
    Inertial {
        origin: origin(e, whose, problems),
        mass,
        inertia,
        line,
    }
}

fn joint_type(s: &str) -> Option<JointType> {
    Some(match s {
        "revolute" => JointType::Revolute,
        "continuous" => JointType::Continuous,
        "prismatic" => JointType::Prismatic,
        "fixed" => JointType::Fixed,
        "floating" => JointType::Floating,
        "planar" => JointType::Planar,
        _ => return None,
    })
}

fn joint(e: &Element, problems: &mut Vec<Problem>) -> Option<Joint> {
    let name = e.attr("name").unwrap_or_default().to_string();
    let whose = format!("joint \"{name}\"");
    if name.is_empty() {
        problems.push(Problem::new(at(e.line, "<joint>"), "has no name"));
    }
    let kind = match e.attr("type") {
        Some(t) => joint_type(t).or_else(|| {
            problems.push(Problem::new(at(e.line, &whose), format!("unknown joint type \"{t}\"; URDF types are revolute, continuous, prismatic, fixed, floating, planar")));
            None
        }),
        None => {
            problems.push(Problem::new(at(e.line, &whose), "has no type"));
            None
        }
    };
    let link_of = |tag: &str, problems: &mut Vec<Problem>| match e.first(tag) {
        Some(p) => match p.attr("link") {
            Some(l) => l.to_string(),
            None => {
                problems.push(Problem::new(
                    at(p.line, &whose),
                    format!("<{tag}> has no link"),
                ));
                String::new()
            }
        },
        None => {
            problems.push(Problem::new(at(e.line, &whose), format!("has no <{tag}>")));
            String::new()
        }
    };
    let parent = link_of("parent", problems);
    let child = link_of("child", problems);
    let mut axis = e.first("axis").map_or([1.0, 0.0, 0.0], |a| {
        numbers(a, "xyz", [1.0, 0.0, 0.0], &whose, problems)
    });
    let moving = matches!(
        kind,
        Some(
            JointType::Revolute | JointType::Continuous | JointType::Prismatic | JointType::Planar
        )
    );
    if moving && axis.iter().all(|&x| x == 0.0) {
        problems.push(Problem::new(at(e.line, &whose), "<axis> has zero length"));
        // the default axis as a placeholder, so that the later checks still run
        axis = [1.0, 0.0, 0.0];
    }
    let (damping, friction) = e.first("dynamics").map_or((0.0, 0.0), |d| {
        (
            number(d, "damping", &whose, problems).unwrap_or(0.0),
            number(d, "friction", &whose, problems).unwrap_or(0.0),
        )
    });
    if damping < 0.0 || friction < 0.0 {
        problems.push(Problem::new(
            at(e.line, &whose),
            "<dynamics> damping and friction must be ≥ 0",
        ));
    }
    let limit = e.first("limit").map(|l| Limit {
        lower: number(l, "lower", &whose, problems),
        upper: number(l, "upper", &whose, problems),
        effort: number(l, "effort", &whose, problems),
    });
    let mimic = e.first("mimic").and_then(|m| match m.attr("joint") {
        Some(other) => Some((
            other.to_string(),
            m.line,
            number(m, "multiplier", &whose, problems).unwrap_or(1.0),
            number(m, "offset", &whose, problems).unwrap_or(0.0),
        )),
        None => {
            problems.push(Problem::new(
                at(m.line, &whose),
                "<mimic> has no joint=\"…\"",
            ));
            None
        }
    });
    let origin = origin(e, &whose, problems);
    Some(Joint {
        name,
        line: e.line,
        kind: kind?,
        parent,
        child,
        origin,
        axis,
        damping,
        friction,
        limit,
        mimic,
    })
}

/// Reads the robot from the root element; `warnings` receives the geometry that was dropped.
pub(crate) fn robot(
    root: &Element,
    problems: &mut Vec<Problem>,
    warnings: &mut Vec<String>,
) -> Robot {
    if root.name != "robot" {
        problems.push(Problem::new(
            at(root.line, &format!("<{}>", root.name)),
            "the root element of a URDF is <robot>",
        ));
    }
    let mut robot = Robot {
        name: root.attr("name").unwrap_or("robot").to_string(),
        ..Robot::default()
    };
    for e in root.all("link") {
        let name = e.attr("name").unwrap_or_default().to_string();
        if name.is_empty() {
            problems.push(Problem::new(at(e.line, "<link>"), "has no name"));
            robot.dropped.push(at(e.line, "<link>"));
            continue;
        }
        let whose = format!("link \"{name}\"");
        let inertial = e.first("inertial").map(|i| inertial(i, &whose, problems));
        let visuals = shapes(e, "visual", &whose, warnings);
        let collisions = shapes(e, "collision", &whose, warnings);
        robot.links.push(Link {
            name,
            line: e.line,
            inertial,
            visuals,
            collisions,
        });
    }
    for e in root.all("joint") {
        match joint(e, problems) {
            // a joint without its links cannot join the tree
            Some(j) if !(j.parent.is_empty() || j.child.is_empty()) => robot.joints.push(j),
            _ => robot.dropped.push(at(e.line, "<joint>")),
        }
    }
    if root.name != "robot" {
        robot
            .dropped
            .push(at(root.line, &format!("<{}>", root.name)));
    }
    robot
}
