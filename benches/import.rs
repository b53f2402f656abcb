//! The cost of bringing a robot in: a synthetic 40-joint humanoid URDF (floating pelvis, two
//! 6-joint legs, a 2-joint waist, two 7-joint arms, a 2-joint neck, two 5-joint grippers, rotated
//! inertials, a fixed sensor frame per limb) read into a spec (`urdf::import`), then checked as
//! `triad check` does (`Spec::validate`: every spec check and the model set-up).
//! Run: `cargo bench --bench import -- --warm-up-time 1 --measurement-time 3`.
use criterion::{criterion_group, criterion_main, Criterion};
use std::fmt::Write;
use triad::urdf::{import, Base, ImportOptions};

/// A chain of `n` revolute joints hanging from `parent`, with a fixed frame at its end.
fn limb(out: &mut String, parent: &str, name: &str, n: usize, dir: f64) {
    let mut prev = parent.to_string();
    for k in 0..n {
        let link = format!("{name}_{k}");
        let axis = ["1 0 0", "0 1 0", "0 0 1"][k % 3];
        let _ = write!(
            out,
            r#"<link name="{link}"><inertial><origin xyz="0 0 {z}" rpy="0.1 {r} 0.2"/><mass value="{m}"/><inertia ixx="0.02" iyy="0.018" izz="0.004" ixy="0.001" ixz="0" iyz="0.0005"/></inertial></link>
<joint name="{link}_joint" type="revolute"><parent link="{prev}"/><child link="{link}"/><origin xyz="0 {y} -0.1" rpy="0 0 0.05"/><axis xyz="{axis}"/><limit lower="-2" upper="2" effort="80" velocity="5"/><dynamics damping="0.1"/></joint>
"#,
            z = -0.1,
            r = 0.05 * k as f64,
            m = 2.0 / (k + 1) as f64,
            y = 0.02 * dir,
        );
        prev = link;
    }
    let _ = writeln!(
        out,
        r#"<link name="{name}_sensor"/><joint name="{name}_sensor_joint" type="fixed"><parent link="{prev}"/><child link="{name}_sensor"/><origin xyz="0 0 -0.05"/></joint>"#
    );
}

fn humanoid() -> String {
    let mut s = String::from(
        r#"<?xml version="1.0"?><robot name="humanoid"><link name="pelvis"><inertial><mass value="8"/><inertia ixx="0.1" iyy="0.1" izz="0.08" ixy="0" ixz="0" iyz="0"/></inertial></link>
"#,
    );
    limb(&mut s, "pelvis", "left_leg", 6, 1.0);
    limb(&mut s, "pelvis", "right_leg", 6, -1.0);
    limb(&mut s, "pelvis", "waist", 2, 0.0);
    limb(&mut s, "waist_1", "left_arm", 7, 1.0);
    limb(&mut s, "waist_1", "right_arm", 7, -1.0);
    limb(&mut s, "waist_1", "neck", 2, 0.0);
    limb(&mut s, "left_arm_6", "left_gripper", 5, 1.0);
    limb(&mut s, "right_arm_6", "right_gripper", 5, -1.0);
    s.push_str("</robot>\n");
    s
}

fn bench(c: &mut Criterion) {
    let text = humanoid();
    let opts = ImportOptions {
        base: Base::Floating,
        ..ImportOptions::default()
    };
    let (spec, _) = import(&text, "humanoid.urdf", &opts).expect("import");
    assert_eq!(spec.joint.len(), 40, "40 joints");
    spec.validate("humanoid.urdf").expect("valid");
    let mut g = c.benchmark_group("humanoid40");
    g.bench_function("import", |b| {
        b.iter(|| import(&text, "humanoid.urdf", &opts).expect("import"))
    });
    g.bench_function("import_and_check", |b| {
        b.iter(|| {
            let (spec, _) = import(&text, "humanoid.urdf", &opts).expect("import");
            spec.validate("humanoid.urdf").expect("valid");
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
