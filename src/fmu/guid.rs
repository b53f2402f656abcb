//! The GUID: a hash of what the importer sees (style.md §3 rule 3). SHA-256 over the canonical
//! spec JSON and every variable-table row, the first 16 bytes formatted like a UUID (version
//! nibble 5, RFC 4122 variant), in braces as FMI tools usually write it. Changing any variable,
//! start value, unit or the model changes the GUID, so a stale modelDescription.xml is refused
//! by `fmi2Instantiate`.

use crate::variables::{Variable, VariableTable};
use sha2::{Digest, Sha256};
use std::fmt::Write as _;

/// Bumped when the hashed content or its encoding changes meaning.
const DOMAIN: &[u8] = b"triad-guid-v1\0";

/// One table row as hashed: every field that reaches modelDescription.xml, floats as bit
/// patterns (no formatting ambiguity).
fn row(v: &Variable) -> String {
    let start = v
        .start
        .map_or_else(|| "-".to_string(), |s| format!("{:016x}", s.to_bits()));
    format!(
        "{}\t{}\t{:?}\t{:?}\t{:?}\t{:?}\t{}\t{}\t{}\t{}\n",
        v.vr,
        v.name,
        v.ty,
        v.causality,
        v.variability,
        v.initial,
        start,
        v.unit.unwrap_or("-"),
        v.display_unit.unwrap_or("-"),
        v.description,
    )
}

/// The GUID of a model: `{xxxxxxxx-xxxx-5xxx-yxxx-xxxxxxxxxxxx}`.
#[must_use]
pub fn guid(canonical_json: &str, table: &VariableTable) -> String {
    let mut h = Sha256::new();
    h.update(DOMAIN);
    h.update((canonical_json.len() as u64).to_le_bytes());
    h.update(canonical_json.as_bytes());
    for v in &table.vars {
        h.update(row(v).as_bytes());
    }
    let d = h.finalize();
    let mut b = [0u8; 16];
    b.copy_from_slice(&d[..16]);
    b[6] = (b[6] & 0x0f) | 0x50;
    b[8] = (b[8] & 0x3f) | 0x80;
    let mut s = String::with_capacity(38);
    s.push('{');
    for (i, byte) in b.iter().enumerate() {
        if matches!(i, 4 | 6 | 8 | 10) {
            s.push('-');
        }
        let _ = write!(s, "{byte:02x}");
    }
    s.push('}');
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_and_sensitivity() {
        let t = VariableTable::default();
        let g = guid("{}", &t);
        assert_eq!(g.len(), 38);
        assert_eq!(&g[15..16], "5");
        assert_eq!(g, guid("{}", &t));
        assert_ne!(g, guid("{ }", &t));
    }
}
