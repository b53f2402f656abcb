//! MJCF actuators: MuJoCo's shortcuts and `<general>` become `[[actuator]]` with the law, gear
//! and clamps MuJoCo compiles (the class's actuator defaults, of any actuator element, applied
//! first; `ctrllimited`/`forcelimited` and autolimits), and what triad cannot reproduce is
//! refused with file, line and element.

use std::path::Path;

use super::{import, ImportOptions};
use crate::spec::{ActuatorKind, ActuatorSpec, Spec, SpecErrors};

/// A hinge `h`, a slide `s` and a ball `b`, with `defaults` and the `<actuator>` section `acts`
/// (its first element on line 5).
fn with(defaults: &str, acts: &str) -> Result<Spec, SpecErrors> {
    let text = format!(
        "<mujoco><default>{defaults}</default><worldbody><body><joint name=\"h\"/><geom size=\"0.1\"/>\
         <body><joint name=\"s\" type=\"slide\"/><geom size=\"0.1\"/><body><joint name=\"b\" type=\"ball\"/>\
         <geom size=\"0.1\"/></body></body></body></worldbody>\n\n\n<actuator>\n{acts}</actuator></mujoco>"
    );
    import(&text, Path::new("model.xml"), &ImportOptions::default()).map(|(s, _)| s)
}

fn one(defaults: &str, act: &str) -> ActuatorSpec {
    let spec = with(defaults, act).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(spec.actuator.len(), 1);
    spec.actuator[0].clone()
}

#[test]
fn laws_gears_ranges_and_classes() {
    let a = one(
        "",
        "<motor name=\"m\" joint=\"h\" gear=\"2.5 0 0 0 0 0\" ctrlrange=\"-1 1\"/>",
    );
    assert_eq!(
        (a.kind, a.gear, a.ctrlrange, a.forcerange, a.joint.as_str()),
        (ActuatorKind::Motor, 2.5, Some([-1.0, 1.0]), None, "h")
    );
    // kp from the class's <position>, gear and ctrlrange from main's <motor>; kv given
    let d =
        "<motor gear=\"3\" ctrlrange=\"-1 1\"/><default class=\"c\"><position kp=\"7\"/></default>";
    let a = one(
        d,
        "<position class=\"c\" joint=\"s\" kv=\"0.5\" forcerange=\"-4 4\"/>",
    );
    assert_eq!(
        (a.kind, a.kp, a.kv, a.gear, a.ctrlrange, a.forcerange),
        (
            ActuatorKind::Position,
            Some(7.0),
            Some(0.5),
            3.0,
            Some([-1.0, 1.0]),
            Some([-4.0, 4.0])
        )
    );
    assert_eq!(a.name, "s", "an unnamed actuator takes its joint's name");
    // a velocity servo does not take a position default's gain (kv 1, as MuJoCo compiles it);
    // ctrllimited="false" drops the range
    let a = one(
        d,
        "<velocity class=\"c\" joint=\"h\" ctrllimited=\"false\"/>",
    );
    assert_eq!(
        (a.kind, a.kv, a.ctrlrange),
        (ActuatorKind::Velocity, Some(1.0), None)
    );
    // a <general> default's gains reach every servo, a servo default's a <general>
    let a = one("<general gainprm=\"4\"/>", "<velocity joint=\"h\"/>");
    assert_eq!((a.kind, a.kv), (ActuatorKind::Velocity, Some(4.0)));
    let a = one("<position kp=\"7\" kv=\"2\"/>", "<general joint=\"h\"/>");
    assert_eq!(
        (a.kind, a.kp, a.kv),
        (ActuatorKind::Position, Some(7.0), Some(2.0))
    );
    let a = one("<velocity kv=\"5\"/>", "<position joint=\"h\"/>");
    assert_eq!(
        (a.kind, a.kp, a.kv),
        (ActuatorKind::Position, Some(1.0), None)
    );
    // <general> written as each law
    let g = |attrs: &str| one("", &format!("<general joint=\"h\" {attrs}/>"));
    assert_eq!(g("").kind, ActuatorKind::Motor);
    let a = g("gainprm=\"5\" biastype=\"affine\" biasprm=\"0 -5 -1\"");
    assert_eq!(
        (a.kind, a.kp, a.kv),
        (ActuatorKind::Position, Some(5.0), Some(1.0))
    );
    let a = g("gainprm=\"5\" biastype=\"affine\" biasprm=\"0 0 -5\"");
    assert_eq!((a.kind, a.kv), (ActuatorKind::Velocity, Some(5.0)));
}

#[test]
fn what_triad_cannot_reproduce_is_refused_by_line_and_element() {
    let cases = [
        (
            "<general joint=\"h\" dyntype=\"filter\"/>",
            "<general>",
            "actuator dynamics",
        ),
        (
            "<position joint=\"h\" kp=\"3\" timeconst=\"0.1\"/>",
            "<position>",
            "actuator dynamics",
        ),
        (
            "<position joint=\"h\" kp=\"3\" dampratio=\"1\"/>",
            "<position>",
            "dampratio",
        ),
        (
            "<general joint=\"h\" gainprm=\"2\"/>",
            "<general>",
            "none of the laws",
        ),
        (
            "<general joint=\"h\" gaintype=\"affine\"/>",
            "<general>",
            "gaintype",
        ),
        (
            "<general joint=\"h\" biastype=\"affine\" biasprm=\"1 -1 0\"/>",
            "<general>",
            "none of the laws",
        ),
        (
            "<damper joint=\"h\" kv=\"1\"/>",
            "<damper>",
            "not supported",
        ),
        (
            "<motor site=\"x\"/>",
            "<motor>",
            "only actuators on a joint",
        ),
        ("<motor joint=\"b\"/>", "<motor>", "hinge and slide"),
        ("<motor joint=\"nope\"/>", "<motor>", "does not exist"),
    ];
    for (act, element, why) in cases {
        let e = with("", act).unwrap_err();
        let m = e.to_string();
        assert_eq!(e.problems.len(), 1, "{m}");
        assert!(
            m.starts_with(&format!("model.xml: line 5: {element}")) && m.contains(why),
            "{act}: {m}"
        );
    }
}
