//! The spec API reports problems as values: `SpecErrors` prints one `origin: path: reason` line
//! per problem, `lower()` refuses a spec built in code that validation would reject, and JSON
//! specs get the same checks as TOML (TOML's `nan` has no JSON spelling; JSON's out-of-range
//! numbers are syntax errors).

use triad::spec::{bundled, Format, Spec};

fn pendulum() -> Spec {
    let (_, text) = bundled().iter().find(|(n, _)| *n == "pendulum").unwrap();
    Spec::from_str(text, Format::Toml, "pendulum.toml").unwrap()
}

#[test]
fn display_is_one_line_per_problem() {
    let mut spec = pendulum();
    spec.joint[0].axis = Some([0.0; 3]);
    spec.body[0].mass = -2.0;
    let json = serde_json::to_string(&spec).unwrap();
    let err = Spec::from_str(&json, Format::Json, "p.json").unwrap_err();
    assert_eq!(err.origin, "p.json");
    assert_eq!(err.problems.len(), 2);
    let text = err.to_string();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines,
        [
            "p.json: body[0].mass: must be >= 0 (got -2)",
            "p.json: joint[0].axis: zero length"
        ]
    );
    let _: &dyn std::error::Error = &err;
}

#[test]
fn lower_refuses_an_invalid_spec_built_in_code() {
    let mut spec = pendulum();
    spec.joint[0].child = "nobody".into();
    let err = spec.lower().unwrap_err();
    assert!(
        err.to_string()
            .contains("joint[0].child: no body named \"nobody\""),
        "{err}"
    );
    assert!(pendulum().lower().is_ok());
}

#[test]
fn json_numbers_out_of_range_are_syntax_errors() {
    let text = r#"{ "name": "P", "gravity": [0, 0, -1e400] }"#;
    let err = Spec::from_str(text, Format::Json, "p.json")
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("p.json: line 1, column"), "{err}");
}

#[test]
fn toml_infinity_is_rejected() {
    let text = "name = \"P\"\ngravity = [0.0, 0.0, -inf]\n[[body]]\nname = \"b\"\nmass = 1.0\ninertia = [1.0, 1.0, 1.0]\nposition = [0.0, 0.0, 0.0]\nvelocity = [nan, 0.0, 0.0]\n";
    let err = Spec::from_str(text, Format::Toml, "p.toml")
        .unwrap_err()
        .to_string();
    assert!(err.contains("p.toml: gravity: must be finite"), "{err}");
    assert!(
        err.contains("p.toml: body[0].velocity: must be finite"),
        "{err}"
    );
}

#[test]
fn free_body_fields_on_a_jointed_body_are_refused() {
    let mut spec = pendulum();
    spec.body[0].position = Some([0.0; 3]);
    let err = Spec::from_str(&spec.canonical_json(), Format::Json, "p.json")
        .unwrap_err()
        .to_string();
    assert!(err.contains("body[0].position: body \"rod\" is placed by joint \"hinge\"; only free bodies and floating bases (bodies that are no tree joint's child) take position"), "{err}");
}

#[test]
fn loop_closing_joint_takes_no_initial() {
    let (_, text) = bundled().iter().find(|(n, _)| *n == "four_bar").unwrap();
    let text = text.replace(
        "child_origin = { xyz = [0.8, 0.0, 0.0] }",
        "child_origin = { xyz = [0.8, 0.0, 0.0] }\ninitial = { q = 0.1 }",
    );
    let err = Spec::from_str(&text, Format::Toml, "fb.toml")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("fb.toml: joint[3].initial: a loop-closing joint takes no initial values"),
        "{err}"
    );
}

#[test]
fn shape_and_consistency_problems_are_reported_together() {
    let text = "name = \"Mix\"\ngravity = [0.0, 0.0]\n[[body]]\nname = \"a\"\nmass = -1.0\ncolour = \"red\"\ninertia = [1.0, 1.0, 5.0]\n\
                [[joint]]\nname = \"j\"\ntype = \"revolute\"\nparent = \"world\"\nchild = \"a\"\naxis = [0.0, 0.0]\n";
    let err = Spec::from_str(text, Format::Toml, "mix.toml")
        .unwrap_err()
        .to_string();
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(
        lines,
        [
            "mix.toml: gravity: expected 3 numbers, found 2",
            "mix.toml: body[0].colour: unknown field \"colour\"; expected one of: name, mass, com, inertia, position, orientation, velocity, angular_velocity, description",
            "mix.toml: joint[0].axis: expected 3 numbers, found 2",
            "mix.toml: body[0].mass: must be >= 0 (got -1)",
            "mix.toml: body[0].inertia: violates the triangle inequality: principal moments 1 + 1 < 5, which no mass distribution has",
        ]
    );
}

#[test]
fn sites_name_a_body_and_are_unique() {
    let (_, text) = bundled().iter().find(|(n, _)| *n == "pendulum").unwrap();
    let body = &pendulum().body[0].name;
    let bad = format!(
        "{text}\n[[site]]\nname = \"tip\"\nbody = \"{body}x\"\n\n[[site]]\nname = \"tip\"\nbody = \"world\"\norigin = {{ xyz = [0.0, nan, 0.0] }}\n\n[[site]]\nname = \"2tip\"\nbody = \"{body}\"\n"
    );
    let err = Spec::from_str(&bad, Format::Toml, "p.toml")
        .unwrap_err()
        .to_string();
    for want in [
        format!("p.toml: site[0].body: no body named \"{body}x\""),
        "p.toml: site[1].name: duplicate site name \"tip\" (also site[0])".into(),
        "p.toml: site[1].body: a site must be fixed on a body".into(),
        "p.toml: site[1].origin".into(),
        "p.toml: site[2].name: \"2tip\" is not an identifier".into(),
    ] {
        assert!(err.contains(&want), "missing {want:?} in\n{err}");
    }
    // a good site adds its outputs
    let good = format!("{text}\n[[site]]\nname = \"tip\"\nbody = \"{body}\"\norigin = {{ xyz = [0.0, 0.0, -1.0] }}\n");
    let spec = Spec::from_str(&good, Format::Toml, "p.toml").unwrap();
    let (def, settings) = spec.lower().unwrap();
    let table = triad::variables::VariableTable::new(&def, &settings);
    for name in [
        "site.tip.r[3]",
        "site.tip.R[2,2]",
        "site.tip.v[1]",
        "site.tip.w[2]",
    ] {
        assert!(table.by_name(name).is_some(), "{name}");
    }
}
