//! Checks shared by the spec-wide and the joint checks.

use crate::math::Vec3;
use crate::spec::error::Report;

/// `[A-Za-z_][A-Za-z0-9_]*`.
pub(crate) fn is_identifier(s: &str) -> bool {
    let mut chars = s.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// Reports `path` unless every value is finite.
pub(super) fn check_finite(report: &mut Report, path: &str, values: &[f64]) {
    if values.iter().any(|x| !x.is_finite()) {
        report.push(path, "must be finite (nan and inf are not allowed)");
    }
}

/// Axis helper shared with the joint checks: the unit vector or `None` for a zero vector.
pub(super) fn normalized(v: [f64; 3]) -> Option<Vec3> {
    Vec3::from(v).try_normalize(1e-300)
}
