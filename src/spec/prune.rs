//! Pruning badly shaped optional fields out of a parsed document, so that the consistency checks
//! can still run and report their problems in the same pass as the shape problems.

/// One step of a problem path: a table key or an array index.
enum Seg<'a> {
    Key(&'a str),
    Index(usize),
}

/// `joint[0].origin.xy` → `joint`, `0`, `origin`, `xy`.
fn segments(path: &str) -> Option<Vec<Seg<'_>>> {
    let mut out = Vec::new();
    for part in path.split('.') {
        let (key, rest) = part.split_once('[').map_or((part, ""), |(k, r)| (k, r));
        out.push(Seg::Key(key));
        for index in rest.split('[').filter(|s| !s.is_empty()) {
            out.push(Seg::Index(index.trim_end_matches(']').parse().ok()?));
        }
    }
    Some(out)
}

fn prune_toml(v: &mut toml::Value, segs: &[Seg<'_>]) {
    match (segs, v) {
        ([Seg::Key(k)], toml::Value::Table(t)) => {
            t.remove(*k);
        }
        ([Seg::Key(k), rest @ ..], toml::Value::Table(t)) => {
            if let Some(child) = t.get_mut(*k) {
                prune_toml(child, rest);
            }
        }
        ([Seg::Index(i), rest @ ..], toml::Value::Array(a)) => {
            if let Some(child) = a.get_mut(*i) {
                prune_toml(child, rest);
            }
        }
        _ => {}
    }
}

fn prune_json(v: &mut serde_json::Value, segs: &[Seg<'_>]) {
    match (segs, v) {
        ([Seg::Key(k)], serde_json::Value::Object(o)) => {
            o.remove(*k);
        }
        ([Seg::Key(k), rest @ ..], serde_json::Value::Object(o)) => {
            if let Some(child) = o.get_mut(*k) {
                prune_json(child, rest);
            }
        }
        ([Seg::Index(i), rest @ ..], serde_json::Value::Array(a)) => {
            if let Some(child) = a.get_mut(*i) {
                prune_json(child, rest);
            }
        }
        _ => {}
    }
}

/// Removes the field at `path` from a TOML document.
pub(super) fn toml_field(v: &mut toml::Value, path: &str) {
    if let Some(segs) = segments(path) {
        prune_toml(v, &segs);
    }
}

/// Removes the field at `path` from a JSON document.
pub(super) fn json_field(v: &mut serde_json::Value, path: &str) {
    if let Some(segs) = segments(path) {
        prune_json(v, &segs);
    }
}

/// True when one path lies inside the other (`joint[0]` and `joint[0].axis`, not `joint[10]`).
pub(super) fn related(a: &str, b: &str) -> bool {
    let inside = |x: &str, y: &str| {
        x == y || (x.starts_with(y) && matches!(x.as_bytes().get(y.len()), Some(b'.' | b'[')))
    };
    inside(a, b) || inside(b, a)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prunes_nested_fields() {
        let mut v: toml::Value =
            toml::from_str("[[joint]]\nname = \"j\"\norigin = { xy = 1, xyz = [0, 0, 0] }\n")
                .unwrap();
        toml_field(&mut v, "joint[0].origin.xy");
        assert!(
            v["joint"][0]["origin"].get("xy").is_none()
                && v["joint"][0]["origin"].get("xyz").is_some()
        );
        let mut j: serde_json::Value = serde_json::from_str(r#"{"body": [{"mas": 1}]}"#).unwrap();
        json_field(&mut j, "body[0].mas");
        assert_eq!(j, serde_json::json!({"body": [{}]}));
    }

    #[test]
    fn relation_respects_segments() {
        assert!(related("joint[0]", "joint[0].axis"));
        assert!(related("joint[0].axis", "joint[0].axis"));
        assert!(!related("joint[1]", "joint[10].axis"));
        assert!(!related("body", "bodyx"));
    }
}
