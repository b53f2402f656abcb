//! Unit tests of `load`.
use super::*;

#[test]
fn every_structural_problem_reported() {
    let text = r#"
name = "M"
bogus = 1
[[body]]
name = "a"
mas = 1.0
inertia = [1, 1]
[[joint]]
name = "j"
type = "hinge"
parent = "world"
child = "a"
axis = [0, 1]
"#;
    let p = parse(text, Format::Toml, "m.toml").unwrap();
    let e = SpecErrors {
        origin: "m.toml".into(),
        problems: p.problems,
        notes: Vec::new(),
    }
    .to_string();
    for want in [
        "m.toml: bogus: unknown field",
        "body[0].mas: unknown field \"mas\"; did you mean \"mass\"?",
        "body[0]: missing field \"mass\"",
        "body[0].inertia: expected [Ixx, Iyy, Izz]",
        "joint[0].type: unknown joint type \"hinge\"; valid types are revolute",
        "joint[0].axis: expected 3 numbers, found 2",
    ] {
        assert!(e.contains(want), "missing {want:?} in\n{e}");
    }
}

#[test]
fn syntax_error_has_line_and_column() {
    let e = parse("name = \"M\"\nmass = = 1\n", Format::Toml, "m.toml")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("m.toml: line 2, column"), "{e}");
    let e = parse("{\"name\": \"M\",\n }", Format::Json, "m.json")
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("m.json: line 2, column"), "{e}");
}
