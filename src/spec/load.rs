//! Reading spec text: syntax (with line and column), then a field-by-field structural pass so
//! that every unknown field, missing field and badly shaped value is reported at once, then
//! serde deserialisation of the whole spec.

use serde::de::DeserializeOwned;

use super::error::{did_you_mean, Problem, Report, SpecErrors};
use super::prune;
use super::schema::{ActuatorKind, Format, JointKind, Spec, ACTUATOR_KINDS, JOINT_TYPES};
use super::values::{Coords, InertiaSpec, OrientationSpec};

/// A parsed document node, TOML or JSON (kept apart: TOML can hold `nan`, JSON values cannot).
#[derive(Clone, Copy)]
enum Node<'a> {
    Toml(&'a toml::Value),
    Json(&'a serde_json::Value),
}

impl<'a> Node<'a> {
    /// Keys and values of a table/object.
    fn entries(self) -> Option<Vec<(&'a str, Node<'a>)>> {
        match self {
            Node::Toml(toml::Value::Table(t)) => {
                Some(t.iter().map(|(k, v)| (k.as_str(), Node::Toml(v))).collect())
            }
            Node::Json(serde_json::Value::Object(o)) => {
                Some(o.iter().map(|(k, v)| (k.as_str(), Node::Json(v))).collect())
            }
            _ => None,
        }
    }

    /// Elements of an array.
    fn elements(self) -> Option<Vec<Node<'a>>> {
        match self {
            Node::Toml(toml::Value::Array(a)) => Some(a.iter().map(Node::Toml).collect()),
            Node::Json(serde_json::Value::Array(a)) => Some(a.iter().map(Node::Json).collect()),
            _ => None,
        }
    }

    /// Deserialises this node; the error message is rewritten for people.
    fn parse<T: DeserializeOwned>(self) -> Result<T, String> {
        match self {
            Node::Toml(v) => v.clone().try_into::<T>().map_err(|e| humanize(e.message())),
            Node::Json(v) => {
                serde_json::from_value::<T>(v.clone()).map_err(|e| humanize(&e.to_string()))
            }
        }
    }
}

/// Rewrites serde's type vocabulary into the spec's.
fn humanize(msg: &str) -> String {
    let msg = msg.trim().trim_end_matches('\n');
    if let Some(rest) = msg.strip_prefix("invalid length ") {
        // "invalid length 2, expected an array of length 3"
        if let Some((found, expected)) = rest.split_once(", expected an array of length ") {
            return format!("expected {expected} numbers, found {found}");
        }
    }
    msg.replace(
        "expected an array of length 3",
        "expected 3 numbers [x, y, z]",
    )
    .replace(
        "expected an array of length 4",
        "expected 4 numbers [w, x, y, z]",
    )
    .replace("expected f64", "expected a number")
    .replace("expected u8", "expected 2 or 4")
    .replace("expected a boolean", "expected true or false")
    .replace("a sequence", "an array")
    .replace("invalid type: ", "")
}

/// How one field is checked.
#[derive(Clone, Copy)]
enum Check {
    /// A value deserialised on its own.
    Value(for<'a> fn(Node<'a>) -> Result<(), String>),
    /// A table with these fields.
    Table(&'static [Field]),
    /// An array of tables with these fields.
    Tables(&'static [Field]),
}

/// One field of a table: name, required, check.
#[derive(Clone, Copy)]
struct Field {
    name: &'static str,
    required: bool,
    check: Check,
}

fn is<T: DeserializeOwned>(n: Node<'_>) -> Result<(), String> {
    n.parse::<T>().map(|_| ())
}

fn joint_type(n: Node<'_>) -> Result<(), String> {
    let word: String = n.parse()?;
    if n.parse::<JointKind>().is_ok() {
        return Ok(());
    }
    Err(format!(
        "unknown joint type \"{word}\"; valid types are {}{}",
        JOINT_TYPES.join(", "),
        did_you_mean(&word, JOINT_TYPES)
    ))
}

fn actuator_kind(n: Node<'_>) -> Result<(), String> {
    let word: String = n.parse()?;
    if n.parse::<ActuatorKind>().is_ok() {
        return Ok(());
    }
    Err(format!(
        "unknown actuator kind \"{word}\"; valid kinds are {}{}",
        ACTUATOR_KINDS.join(", "),
        did_you_mean(&word, ACTUATOR_KINDS.iter().copied())
    ))
}

const fn req(name: &'static str, check: Check) -> Field {
    Field {
        name,
        required: true,
        check,
    }
}

const fn opt(name: &'static str, check: Check) -> Field {
    Field {
        name,
        required: false,
        check,
    }
}

const VEC3: Check = Check::Value(is::<[f64; 3]>);
const NUM: Check = Check::Value(is::<f64>);
const BOOL: Check = Check::Value(is::<bool>);
const TEXT: Check = Check::Value(is::<String>);

const EXPERIMENT: &[Field] = &[opt("start", NUM), opt("stop", NUM), opt("step", NUM)];
const SOLVER: &[Field] = &[
    opt("max_step", NUM),
    opt("order", Check::Value(is::<super::values::Order>)),
    opt("tolerance", NUM),
    opt("max_substeps", Check::Value(is::<u32>)),
    opt("stages", Check::Value(is::<u8>)),
    opt("rtol", NUM),
    opt("atol", NUM),
    opt("min_step", NUM),
];
const ORIGIN: &[Field] = &[opt("xyz", VEC3), opt("rpy", VEC3)];
const INITIAL: &[Field] = &[
    opt("q", Check::Value(is::<Coords>)),
    opt("qd", Check::Value(is::<Coords>)),
    opt("rpy", VEC3),
    opt("quat", Check::Value(is::<[f64; 4]>)),
    opt("w", VEC3),
];
const BODY: &[Field] = &[
    req("name", TEXT),
    req("mass", NUM),
    opt("com", VEC3),
    req("inertia", Check::Value(is::<InertiaSpec>)),
    opt("position", VEC3),
    opt("orientation", Check::Value(is::<OrientationSpec>)),
    opt("velocity", VEC3),
    opt("angular_velocity", VEC3),
    opt("description", TEXT),
];
const JOINT: &[Field] = &[
    req("name", TEXT),
    req("type", Check::Value(joint_type)),
    req("parent", TEXT),
    req("child", TEXT),
    opt("origin", Check::Table(ORIGIN)),
    opt("child_origin", Check::Table(ORIGIN)),
    opt("axis", VEC3),
    opt("axis2", VEC3),
    opt("actuated", BOOL),
    opt("damping", NUM),
    opt("stiffness", NUM),
    opt("armature", NUM),
    opt("friction", NUM),
    opt("lower", NUM),
    opt("upper", NUM),
    opt("effort", NUM),
    opt("actuatorfrcrange", RANGE),
    opt("stop_stiffness", NUM),
    opt("stop_damping", NUM),
    opt("initial", Check::Table(INITIAL)),
    opt("description", TEXT),
];
const LOAD: &[Field] = &[req("body", TEXT), opt("torque", BOOL), opt("force", BOOL)];
const SITE: &[Field] = &[
    req("name", TEXT),
    req("body", TEXT),
    opt("origin", Check::Table(ORIGIN)),
    opt("description", TEXT),
];
const VISUAL: &[Field] = &[
    req("body", TEXT),
    opt("origin", Check::Table(ORIGIN)),
    opt("box", VEC3),
    opt("cylinder", Check::Value(is::<[f64; 2]>)),
    opt("sphere", NUM),
    opt("mesh", TEXT),
    opt("scale", VEC3),
    opt("rgba", Check::Value(is::<[f64; 4]>)),
];
const GROUND: &[Field] = &[
    opt("height", NUM),
    opt("friction", NUM),
    opt("stiffness", NUM),
    opt("damping", NUM),
];
const SPHERE: &[Field] = &[req("radius", NUM)];
const ROUND: &[Field] = &[req("radius", NUM), req("length", NUM)];
const BOX: &[Field] = &[req("size", VEC3)];
const COLLISION: &[Field] = &[
    opt("name", TEXT),
    req("body", TEXT),
    opt("origin", Check::Table(ORIGIN)),
    opt("sphere", Check::Table(SPHERE)),
    opt("capsule", Check::Table(ROUND)),
    opt("box", Check::Table(BOX)),
    opt("cylinder", Check::Table(ROUND)),
    opt("friction", NUM),
    opt("stiffness", NUM),
    opt("damping", NUM),
];
const PAIR: &[Field] = &[req("a", TEXT), req("b", TEXT)];
const COUPLING: &[Field] = &[
    req("a", TEXT),
    req("b", TEXT),
    opt("ratio", NUM),
    opt("offset", NUM),
];
const RANGE: Check = Check::Value(is::<[f64; 2]>);
const ACTUATOR: &[Field] = &[
    req("name", TEXT),
    req("joint", TEXT),
    req("kind", Check::Value(actuator_kind)),
    opt("gear", NUM),
    opt("kp", NUM),
    opt("kv", NUM),
    opt("ctrlrange", RANGE),
    opt("forcerange", RANGE),
    opt("description", TEXT),
];
const TOP: &[Field] = &[
    req("name", TEXT),
    opt("description", TEXT),
    opt("gravity", VEC3),
    opt("experiment", Check::Table(EXPERIMENT)),
    opt("solver", Check::Table(SOLVER)),
    opt("body", Check::Tables(BODY)),
    opt("joint", Check::Tables(JOINT)),
    opt("load", Check::Tables(LOAD)),
    opt("site", Check::Tables(SITE)),
    opt("visual", Check::Tables(VISUAL)),
    opt("ground", Check::Table(GROUND)),
    opt("collision", Check::Tables(COLLISION)),
    opt("contact_pair", Check::Tables(PAIR)),
    opt("self_collision", BOOL),
    opt("coupling", Check::Tables(COUPLING)),
    opt("actuator", Check::Tables(ACTUATOR)),
];

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

/// Outcome of the structural pass: the problems, the optional fields to prune before
/// deserialising, and whether something that cannot be pruned is wrong.
#[derive(Default)]
struct Structure {
    report: Report,
    prune: Vec<String>,
    fatal: bool,
}

impl Structure {
    /// A problem at `path`; prunable when the field is optional.
    fn problem(&mut self, path: &str, message: String, optional: bool) {
        self.report.push(path, message);
        if optional && !path.is_empty() {
            self.prune.push(path.to_string());
        } else {
            self.fatal = true;
        }
    }
}

/// Checks a table against its fields, reporting every problem.
fn check_table(node: Node<'_>, path: &str, fields: &[Field], optional: bool, s: &mut Structure) {
    let Some(entries) = node.entries() else {
        s.problem(path, "expected a table { ... }".into(), optional);
        return;
    };
    for (key, value) in &entries {
        let here = join(path, key);
        match fields.iter().find(|f| f.name == *key) {
            None => {
                let names: Vec<&str> = fields.iter().map(|f| f.name).collect();
                let hint = did_you_mean(key, names.iter().copied());
                let hint = if hint.is_empty() {
                    format!("; expected one of: {}", names.join(", "))
                } else {
                    hint
                };
                s.problem(&here, format!("unknown field \"{key}\"{hint}"), true);
            }
            Some(field) => check_value(*value, &here, field.check, !field.required, s),
        }
    }
    for field in fields.iter().filter(|f| f.required) {
        if !entries.iter().any(|(k, _)| *k == field.name) {
            s.problem(path, format!("missing field \"{}\"", field.name), false);
        }
    }
}

fn check_value(node: Node<'_>, path: &str, check: Check, optional: bool, s: &mut Structure) {
    match check {
        Check::Value(f) => {
            if let Err(m) = f(node) {
                s.problem(path, m, optional);
            }
        }
        Check::Table(fields) => check_table(node, path, fields, optional, s),
        Check::Tables(fields) => match node.elements() {
            // array elements are never pruned (that would shift the indices of later problems)
            Some(items) => {
                for (i, item) in items.into_iter().enumerate() {
                    check_table(item, &format!("{path}[{i}]"), fields, false, s);
                }
            }
            None => {
                let key = path.rsplit('.').next().unwrap_or(path);
                s.problem(path, format!("expected an array of tables (write [[{key}]] in TOML, \"{key}\": [ {{...}} ] in JSON)"), optional);
            }
        },
    }
}

/// Line and column (1-based) of a byte offset.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// A parsed spec: the shape problems, the spec itself when it could be read (after pruning
/// badly shaped optional fields), and the pruned paths.
#[derive(Debug)]
pub(super) struct Parsed {
    /// Shape problems, in document order.
    pub(super) problems: Vec<Problem>,
    /// The spec, when it could be deserialised.
    pub(super) spec: Option<Spec>,
    /// Fields removed before deserialising.
    pub(super) pruned: Vec<String>,
}

fn finish(s: Structure, spec: Result<Spec, String>) -> Parsed {
    let mut problems = s.report.problems;
    let spec = match spec {
        Ok(spec) => Some(spec),
        Err(m) => {
            if problems.is_empty() {
                problems.push(Problem::new("", m));
            }
            None
        }
    };
    Parsed {
        problems,
        spec,
        pruned: s.prune,
    }
}

/// Parses spec text, reporting syntax problems as errors and shape problems in [`Parsed`]
/// (consistency is `validate`'s job).
pub(super) fn parse(text: &str, format: Format, origin: &str) -> Result<Parsed, SpecErrors> {
    let mut s = Structure::default();
    match format {
        Format::Toml => {
            let mut value: toml::Value = toml::from_str(text).map_err(|e| {
                let at = e.span().map(|s| line_col(text, s.start));
                let path = at.map_or(String::new(), |(l, c)| format!("line {l}, column {c}"));
                SpecErrors::single(
                    origin,
                    path,
                    format!(
                        "TOML syntax error: {}",
                        e.message().trim().replace('\n', "; ")
                    ),
                )
            })?;
            check_table(Node::Toml(&value), "", TOP, false, &mut s);
            if s.fatal {
                return Ok(finish(s, Err(String::new())));
            }
            for path in &s.prune {
                prune::toml_field(&mut value, path);
            }
            let spec = Node::Toml(&value).parse::<Spec>();
            Ok(finish(s, spec))
        }
        Format::Json => {
            let mut value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
                let msg = e.to_string();
                let msg = msg.split(" at line ").next().unwrap_or(&msg).to_string();
                SpecErrors::single(
                    origin,
                    format!("line {}, column {}", e.line(), e.column()),
                    format!("JSON syntax error: {msg}"),
                )
            })?;
            check_table(Node::Json(&value), "", TOP, false, &mut s);
            if s.fatal {
                return Ok(finish(s, Err(String::new())));
            }
            for path in &s.prune {
                prune::json_field(&mut value, path);
            }
            let spec = Node::Json(&value).parse::<Spec>();
            Ok(finish(s, spec))
        }
    }
}

#[cfg(test)]
#[path = "load_tests.rs"]
mod tests;
