//! The variable table: value references are positions, names are unique, inputs follow
//! `Model::inputs()` slot by slot, parameters read back what the spec says, and writes keep the
//! definition consistent (`inertia[i,j]` also sets `[j,i]`, out-of-range values are refused).

use triad::mechanics::{InputSlot, Model};
use triad::spec::{bundled, Format, Spec};
use triad::variables::{
    read_param, write_param, Accessor, Causality, Initial, VarType, Variability, VariableTable,
};

fn model(name: &str) -> (triad::mechanics::ModelDef, triad::mechanics::SolverSettings) {
    let (_, text) = bundled().iter().find(|(n, _)| *n == name).unwrap();
    Spec::from_str(text, Format::Toml, name)
        .unwrap()
        .lower()
        .unwrap()
}

#[test]
fn value_references_are_positions_and_names_unique() {
    for (name, _) in bundled() {
        let (def, settings) = model(name);
        let table = VariableTable::new(&def, &settings);
        let mut names = std::collections::HashSet::new();
        for (k, v) in table.vars.iter().enumerate() {
            assert_eq!(v.vr as usize, k);
            assert!(names.insert(v.name.clone()), "{name}: duplicate {}", v.name);
            assert_eq!(table.by_vr(v.vr), Some(v));
            assert_eq!(table.by_name(&v.name), Some(v));
            assert!(!v.description.is_empty());
            match v.causality {
                Causality::Input => assert!(
                    v.initial == Initial::None
                        && v.start == Some(0.0)
                        && v.variability == Variability::Continuous
                ),
                Causality::Output => assert!(
                    v.initial == Initial::Calculated
                        && v.start.is_none()
                        && v.variability == Variability::Continuous
                ),
                Causality::Parameter => {
                    assert_eq!(v.initial, Initial::Exact);
                    assert_eq!(
                        v.start,
                        read_param(v.accessor, &def, &settings),
                        "{}",
                        v.name
                    );
                }
            }
            assert_eq!(
                v.display_unit.is_some(),
                v.unit == Some("rad"),
                "{}",
                v.name
            );
        }
        assert!(table.by_vr(table.vars.len() as u32).is_none());
    }
}

#[test]
fn inputs_follow_the_model_slots() {
    for (name, _) in bundled() {
        let (def, settings) = model(name);
        let table = VariableTable::new(&def, &settings);
        let built = Model::new(&def, settings).unwrap();
        let inputs: Vec<_> = table.with_causality(Causality::Input).collect();
        assert_eq!(inputs.len(), built.inputs().len(), "{name}");
        for (slot, (v, s)) in inputs.iter().zip(built.inputs()).enumerate() {
            assert_eq!(v.accessor, Accessor::Input(slot));
            let ok = match *s {
                InputSlot::JointTorque { joint, .. } => v
                    .name
                    .starts_with(&format!("joint.{}.tau", def.joints[joint].name)),
                InputSlot::JointForce { joint } => {
                    v.name == format!("joint.{}.f", def.joints[joint].name)
                }
                InputSlot::BodyTorque { body, i } => {
                    v.name == format!("body.{}.torque[{}]", def.bodies[body].name, i + 1)
                }
                InputSlot::BodyForce { body, i } => {
                    v.name == format!("body.{}.force[{}]", def.bodies[body].name, i + 1)
                }
                InputSlot::ActuatorCtrl { actuator } => {
                    v.name == format!("actuator.{}.ctrl", def.actuators[actuator].name)
                }
            };
            assert!(
                ok,
                "{name}: slot {slot} is {s:?} but the table says {}",
                v.name
            );
        }
    }
}

#[test]
fn units_and_types() {
    let (def, settings) = model("slider_crank");
    let t = VariableTable::new(&def, &settings);
    let unit = |n: &str| t.by_name(n).unwrap_or_else(|| panic!("{n}")).unit;
    assert_eq!(unit("joint.crank_pivot.q"), Some("rad"));
    assert_eq!(unit("joint.guide.q"), Some("m"));
    assert_eq!(unit("joint.guide.qd"), Some("m/s"));
    assert_eq!(unit("joint.guide.f"), Some("N"));
    assert_eq!(unit("joint.crank_pivot.tau"), Some("N.m"));
    assert_eq!(unit("system.L[3]"), Some("N.m.s"));
    assert_eq!(unit("body.rod.inertia[1,2]"), Some("kg.m2"));
    assert_eq!(
        t.by_name("joint.crank_pivot.q").unwrap().display_unit,
        Some("deg")
    );
    assert_eq!(t.by_name("solver.order").unwrap().ty, VarType::Integer);
    assert_eq!(
        t.by_name("joint.guide.damping").unwrap().variability,
        Variability::Tunable
    );
    // loop-closing joints have outputs but no initial-value parameters
    assert!(t.by_name("joint.rod_slider.q").is_some());
    assert!(t.by_name("joint.rod_slider.q0").is_none());
    let (def, settings) = model("heavy_top");
    let t = VariableTable::new(&def, &settings);
    assert_eq!(
        t.by_name("joint.tip.q0[1]").unwrap().start,
        Some(0.9659258262890683)
    );
    assert_eq!(t.by_name("joint.tip.qd0[3]").unwrap().start, Some(30.0));
    assert!(t.by_name("joint.tip.stiffness").is_none());
}

#[test]
fn writes_keep_the_definition_consistent() {
    let (mut def, mut settings) = model("double_pendulum");
    let t = VariableTable::new(&def, &settings);
    let acc = |n: &str| t.by_name(n).unwrap().accessor;
    write_param(
        acc("body.link1.inertia[1,2]"),
        &mut def,
        &mut settings,
        0.01,
    )
    .unwrap();
    assert_eq!(def.bodies[0].inertia[(1, 0)], 0.01);
    assert_eq!(
        read_param(acc("body.link1.inertia[2,1]"), &def, &settings),
        Some(0.01)
    );
    write_param(acc("joint.elbow.q0"), &mut def, &mut settings, -1.5).unwrap();
    assert_eq!(
        read_param(acc("joint.elbow.q0"), &def, &settings),
        Some(-1.5)
    );
    write_param(acc("solver.order"), &mut def, &mut settings, 4.0).unwrap();
    assert_eq!(settings.order, 4);
    assert!(write_param(acc("solver.order"), &mut def, &mut settings, 3.0).is_err());
    assert!(write_param(acc("body.link1.mass"), &mut def, &mut settings, -1.0).is_err());
    assert!(write_param(
        acc("joint.elbow.damping"),
        &mut def,
        &mut settings,
        f64::NAN
    )
    .is_err());
    assert!(write_param(acc("system.energy"), &mut def, &mut settings, 1.0).is_err());
    assert!(write_param(acc("joint.elbow.tau"), &mut def, &mut settings, 1.0).is_err());
    assert_eq!(settings.order, 4);
}
