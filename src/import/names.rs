//! Deterministic identifiers from URDF and MJCF names (interface.md §3): every character outside
//! `[A-Za-z0-9_]` becomes `_`, a leading digit (or an empty name) is prefixed with `_`, and a
//! name already taken (or reserved: `world` for bodies) gets the smallest suffix `_2`, `_3`, …
//! that is free. Names are given out in document order, so the same file always gives the
//! same identifiers.

use std::collections::HashSet;

/// Hands out unique identifiers for one namespace (bodies, or joints).
#[derive(Debug, Default)]
pub(crate) struct Namer {
    taken: HashSet<String>,
}

impl Namer {
    /// A namer with `reserved` names already taken.
    pub fn new(reserved: &[&str]) -> Self {
        Self {
            taken: reserved.iter().map(|s| (*s).to_string()).collect(),
        }
    }

    /// The identifier for `original`.
    pub fn name(&mut self, original: &str) -> String {
        let mut base: String = original
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '_' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        if base.is_empty() || base.starts_with(|c: char| c.is_ascii_digit()) {
            base.insert(0, '_');
        }
        let mut name = base.clone();
        let mut k = 2;
        while self.taken.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        self.taken.insert(name.clone());
        name
    }
}

#[cfg(test)]
mod tests {
    use super::Namer;

    #[test]
    fn names_are_identifiers_and_unique() {
        let mut n = Namer::new(&["world"]);
        assert_eq!(n.name("base_link"), "base_link");
        assert_eq!(n.name("arm-1/link.2"), "arm_1_link_2");
        assert_eq!(n.name("3rd"), "_3rd");
        assert_eq!(n.name("world"), "world_2");
        assert_eq!(n.name("arm_1_link_2"), "arm_1_link_2_2");
        assert_eq!(n.name("arm:1_link_2"), "arm_1_link_2_3");
        assert_eq!(n.name(""), "_");
    }
}
