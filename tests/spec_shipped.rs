//! Every shipped spec reads the same from TOML and from its JSON translation (the TOML value
//! serialised by serde_json): the same `Spec` and the same lowered `ModelDef`. The canonical
//! JSON of each spec reads back to an equal spec, and the spec example of interface.md §2 parses.
//! Together these make TOML and JSON one schema and `resources/model.json` a faithful copy.

use triad::mechanics::JointInitial;
use triad::spec::{bundled, Format, Spec};

fn toml_and_json(name: &str, text: &str) -> (Spec, Spec) {
    let from_toml = Spec::from_str(text, Format::Toml, name).unwrap_or_else(|e| panic!("{e}"));
    let value: toml::Value = toml::from_str(text).unwrap();
    let json = serde_json::to_string_pretty(&value).unwrap();
    let from_json = Spec::from_str(&json, Format::Json, name).unwrap_or_else(|e| panic!("{e}"));
    (from_toml, from_json)
}

#[test]
fn seven_models_are_shipped() {
    let names: Vec<&str> = bundled().iter().map(|(n, _)| *n).collect();
    for want in [
        "pendulum",
        "double_pendulum",
        "heavy_top",
        "free_body",
        "four_bar",
        "slider_crank",
        "robot_arm",
    ] {
        assert!(names.contains(&want), "{want} missing from {names:?}");
    }
}

#[test]
fn toml_and_json_give_the_same_spec_and_model() {
    for (name, text) in bundled() {
        let (a, b) = toml_and_json(name, text);
        assert_eq!(a, b, "{name}: TOML and JSON specs differ");
        assert_eq!(
            a.lower().unwrap(),
            b.lower().unwrap(),
            "{name}: lowered models differ"
        );
    }
}

#[test]
fn canonical_json_round_trips() {
    for (name, text) in bundled() {
        let spec = Spec::from_str(text, Format::Toml, name).unwrap();
        let json = spec.canonical_json();
        let back =
            Spec::from_str(&json, Format::Json, name).unwrap_or_else(|e| panic!("{e}\n{json}"));
        assert_eq!(spec, back, "{name}");
        assert_eq!(
            json,
            back.canonical_json(),
            "{name}: canonical JSON is not a fixed point"
        );
    }
}

#[test]
fn lowering_normalises_axes_and_orders_tree_joints_first() {
    let (_, text) = bundled().iter().find(|(n, _)| *n == "four_bar").unwrap();
    let (def, settings) = Spec::from_str(text, Format::Toml, "four_bar")
        .unwrap()
        .lower()
        .unwrap();
    assert_eq!(settings.order, 2);
    let loops: Vec<bool> = def.joints.iter().map(|j| j.loop_closing).collect();
    assert_eq!(loops, [false, false, false, true]);
    for j in &def.joints {
        assert!((j.axis.norm() - 1.0).abs() < 1e-15);
        assert_eq!(j.parent.is_none(), j.name.ends_with("_pivot"));
    }
    assert_eq!(def.joints[3].child_frame.translation.x, 0.8);
}

#[test]
fn spherical_rpy_and_quat_lower_alike() {
    let base = |init: &str| {
        format!(
            "name = \"T\"\n[[body]]\nname = \"top\"\nmass = 1.0\ninertia = [0.1, 0.1, 0.05]\n\
             [[joint]]\nname = \"tip\"\ntype = \"spherical\"\nparent = \"world\"\nchild = \"top\"\ninitial = {init}\n"
        )
    };
    let a = Spec::from_str(
        &base("{ rpy = [0.5235987755982988, 0.0, 0.0], w = [0.0, 0.0, 30.0] }"),
        Format::Toml,
        "a",
    )
    .unwrap();
    let b = Spec::from_str(
        &base(
            "{ quat = [0.9659258262890683, 0.25881904510252074, 0.0, 0.0], w = [0.0, 0.0, 30.0] }",
        ),
        Format::Toml,
        "b",
    )
    .unwrap();
    let (da, _) = a.lower().unwrap();
    let (db, _) = b.lower().unwrap();
    let (JointInitial::Spherical { quat: qa, w: wa }, JointInitial::Spherical { quat: qb, w: wb }) =
        (&da.joints[0].initial, &db.joints[0].initial)
    else {
        panic!("spherical initial expected");
    };
    assert!(
        qa.iter().zip(qb).all(|(x, y)| (x - y).abs() < 1e-15),
        "{qa:?} vs {qb:?}"
    );
    assert_eq!(wa, wb);
}

/// The example of interface.md §2, verbatim.
const INTERFACE_EXAMPLE: &str = r#"
name = "DoublePendulum"        # modelIdentifier: [A-Za-z_][A-Za-z0-9_]*, also the .so name
description = "Two slender links on parallel revolute joints"
gravity = [0.0, 0.0, -9.81]    # world frame; default [0, 0, -9.81]

[experiment]                   # -> <DefaultExperiment> and the solver defaults
start = 0.0
stop = 10.0
step = 1e-3                    # communication step hint (DefaultExperiment stepSize)

[solver]
max_step = 1e-3                # internal step; fmi2DoStep takes ceil(H / max_step) equal sub-steps
order = 2                      # 2: energy-momentum midpoint scheme; 4: its symmetric triple-jump composition
tolerance = 1e-10              # Newton tolerance (scaled residual)

[[body]]
name = "link1"
mass = 1.0
com = [0.0, 0.0, -0.5]         # centre of mass in the body frame; default origin
inertia = [0.0834, 0.0834, 1e-4]   # about the centre of mass, body axes: [Ixx, Iyy, Izz]
                                   # or [Ixx, Iyy, Izz, Ixy, Ixz, Iyz], or a full 3x3 array

[[joint]]
name = "shoulder"
type = "revolute"              # revolute | prismatic | cylindrical | universal | spherical | planar | fixed
parent = "world"               # a body name or "world"
child = "link1"
origin = { xyz = [0.0, 0.0, 0.0], rpy = [0.0, 0.0, 0.0] }  # joint frame in the parent frame (URDF style)
axis = [0.0, 1.0, 0.0]         # in the joint frame; universal joints take axis2 as well
actuated = true                # adds the input joint.shoulder.tau
damping = 0.0                  # viscous, N·m·s/rad (N·s/m for sliding)
stiffness = 0.0                # N·m/rad (N/m) about rest = 0.0
initial = { q = 2.0, qd = 0.0 }
"#;

#[test]
fn interface_example_parses() {
    let spec = Spec::from_str(INTERFACE_EXAMPLE, Format::Toml, "interface.md")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(spec.name, "DoublePendulum");
    assert_eq!(
        spec.joint[0]
            .initial
            .as_ref()
            .and_then(|i| i.q.clone())
            .map(|q| q.values()),
        Some(vec![2.0])
    );
    let (def, _) = spec.lower().unwrap();
    assert!(def.joints[0].actuated);
}

#[test]
fn inertia_spellings_agree() {
    let with = |inertia: &str| {
        let text = format!("name = \"P\"\n[[body]]\nname = \"b\"\nmass = 1.0\ninertia = {inertia}\nposition = [0.0, 0.0, 0.0]\n");
        Spec::from_str(&text, Format::Toml, "p")
            .unwrap_or_else(|e| panic!("{e}"))
            .lower()
            .unwrap()
            .0
            .bodies[0]
            .inertia
    };
    let a = with("[1.0, 2.0, 2.5, 0.1, 0.0, 0.0]");
    let b = with("[[1.0, 0.1, 0.0], [0.1, 2.0, 0.0], [0.0, 0.0, 2.5]]");
    assert_eq!(a, b);
    assert_eq!(with("[1, 2, 2.5]")[(1, 1)], 2.0);
}
