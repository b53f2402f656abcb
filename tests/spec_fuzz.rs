//! Validation never panics: shipped specs mutated at random (a line dropped or duplicated, a
//! number replaced by nan, inf, a negative, zero, a huge value, a string or an array) are
//! either accepted or rejected with at least one `origin: ...` problem line, in TOML and JSON.

use proptest::prelude::*;
use triad::spec::{bundled, Format, Spec};

const REPLACEMENTS: [&str; 9] = [
    "nan",
    "inf",
    "-1.0",
    "0.0",
    "1e308",
    "\"x\"",
    "[1.0, 2.0]",
    "[]",
    "true",
];

fn mutate(text: &str, line: usize, kind: usize, pick: usize) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let i = line % lines.len();
    match kind % 3 {
        0 => {
            lines.remove(i);
        }
        1 => {
            let l = lines[i].clone();
            lines.insert(i, l);
        }
        _ => {
            if let Some((key, _)) = lines[i].split_once(" = ") {
                lines[i] = format!("{key} = {}", REPLACEMENTS[pick % REPLACEMENTS.len()]);
            }
        }
    }
    lines.join("\n")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]
    #[test]
    fn mutated_specs_never_panic(model in 0usize..7, line in 0usize..200, kind in 0usize..3, pick in 0usize..9) {
        let (name, text) = bundled()[model % bundled().len()];
        let text = mutate(text, line, kind, pick);
        match Spec::from_str(&text, Format::Toml, name) {
            Ok(spec) => {
                let json = spec.canonical_json();
                prop_assert_eq!(Spec::from_str(&json, Format::Json, name).ok(), Some(spec.clone()));
                prop_assert!(spec.lower().is_ok());
            }
            Err(e) => {
                prop_assert!(!e.problems.is_empty());
                prop_assert!(e.to_string().lines().all(|l| l.starts_with(name)));
            }
        }
        if let Ok(value) = toml::from_str::<toml::Value>(&text) {
            if let Ok(json) = serde_json::to_string(&value) {
                let _ = Spec::from_str(&json, Format::Json, name);
            }
        }
    }
}
