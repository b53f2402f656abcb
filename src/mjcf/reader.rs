//! The reader's state while the document is read (classes, compiler settings, bodies so far,
//! problems, notes) and the checks every section shares: refused elements, flags, limits.

use super::defaults::{Attrs, Classes};
use super::model::{Body, Compiler};
use super::xml::Node;
use crate::spec::Problem;

/// Elements refused wherever they appear: what triad cannot represent.
pub(super) const REFUSED: [(&str, &str); 8] = [
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
pub(super) fn refused(node: &Node) -> Option<Problem> {
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
pub(super) fn flag(a: &Attrs, key: &str, default: bool) -> Result<bool, Problem> {
    Ok(a.keyword(
        key,
        &["true", "false"],
        if default { "true" } else { "false" },
    )? == "true")
}

/// Whether `a` (a joint, or an actuator for `what` = ctrl/force) is limited: `limited`
/// true/false, or auto: limited when a range is given and `autolimits` is on.
pub(super) fn limited(
    a: &Attrs,
    key: &str,
    has_range: bool,
    autolimits: bool,
) -> Result<bool, Problem> {
    Ok(match a.keyword(key, &["true", "false", "auto"], "auto")? {
        "true" => true,
        "false" => false,
        _ => has_range && autolimits,
    })
}

/// The reader's state while walking the tree.
pub(super) struct Reader<'a> {
    pub classes: Classes<'a>,
    pub compiler: Compiler,
    pub bodies: Vec<Body>,
    pub problems: Vec<Problem>,
    pub notes: Vec<String>,
}
impl Reader<'_> {
    /// Records `r`'s problem, if any; its value otherwise.
    pub fn ok<T>(&mut self, r: Result<T, Problem>) -> Option<T> {
        r.map_err(|p| self.problems.push(p)).ok()
    }
}
