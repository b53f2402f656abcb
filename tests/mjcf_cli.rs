//! The command line with MJCF models: `triad import model.xml` writes a spec that reads back
//! as the same spec, every command takes the `.xml` with `--no-contacts` and `--keyframe`, the
//! MJCF options are refused for other models, and a bad model exits non-zero naming the file,
//! line and element, writing nothing.

use std::process::Command;

const MODEL: &str = r#"<mujoco model="arm">
  <worldbody>
    <geom type="plane" size="5 5 0.1"/>
    <body name="upper" pos="0 0 1">
      <joint name="shoulder" axis="0 1 0" range="-90 90"/>
      <geom type="capsule" fromto="0 0 0 0 0 -0.5" size="0.05"/>
    </body>
  </worldbody>
  <actuator><motor joint="shoulder" ctrlrange="-3 3"/></actuator>
  <keyframe><key name="up" qpos="0.5" qvel="0"/></keyframe>
</mujoco>
"#;

fn triad(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_triad"))
        .args(args)
        .output()
        .expect("triad runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn import_check_describe_and_options() {
    let dir = tempfile::tempdir().unwrap();
    let xml = dir.path().join("arm.xml");
    std::fs::write(&xml, MODEL).unwrap();
    let xml = xml.to_str().unwrap();
    let toml = dir.path().join("arm.toml");
    let (ok, _, err) = triad(&[
        "import",
        xml,
        "--keyframe",
        "up",
        "-o",
        toml.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(&toml).unwrap();
    assert!(
        text.contains("# MJCF line 4: <body name=\"upper\">"),
        "{text}"
    );
    assert!(
        text.contains("q = 0.5")
            && text.contains("[[actuator]]")
            && text.contains("ctrlrange = [-3.0, 3.0]")
            && text.contains("[ground]"),
        "{text}"
    );
    let spec = triad::spec::Spec::from_path(&toml).unwrap();
    assert_eq!(spec.collision.len(), 1);
    let (ok, out, err) = triad(&["check", xml, "--no-contacts"]);
    assert!(ok && out.contains("ok"), "{out}{err}");
    let (ok, out, _) = triad(&["describe", xml]);
    assert!(ok && out.contains("actuator.shoulder.ctrl") && out.contains("contact.upper.gap"));
    // MJCF options for a spec, URDF options for an MJCF file: refused
    let (ok, _, err) = triad(&["check", toml.to_str().unwrap(), "--keyframe", "up"]);
    assert!(
        !ok && err.contains("--keyframe is for an MJCF .xml MODEL only"),
        "{err}"
    );
    let (ok, _, err) = triad(&["check", xml, "--floating-base"]);
    assert!(
        !ok && err.contains("--floating-base is for a .urdf MODEL only"),
        "{err}"
    );
}

#[test]
fn a_bad_model_names_file_line_and_element_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let xml = dir.path().join("bad.xml");
    std::fs::write(&xml, MODEL.replace("<actuator>", "<tendon/><actuator>")).unwrap();
    let out = dir.path().join("bad.toml");
    let (ok, _, err) = triad(&["import", xml.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert!(!ok && err.contains("bad.xml: line 9: <tendon>"), "{err}");
    assert!(!out.exists());
}
