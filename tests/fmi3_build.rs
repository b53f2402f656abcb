//! `triad build --fmi 3` and `triad describe --fmi 3` (interface.md §1 "--fmi", §3 "FMI 3
//! names", §4 "FMI 3.0"): every shipped model gives an FMI 3.0 archive whose
//! `modelDescription.xml` says `fmiVersion="3.0"`, carries the FMI 2 GUID as its
//! `instantiationToken`, names vectors and matrices as arrays with their `<Dimension>`s, lists
//! `time` first and every output by value reference; the host's binary sits under its FMI 3
//! platform tuple; the same model built twice gives the same bytes. Bad `--fmi` values are
//! refused by the argument parser.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use triad::package::{fmu_bytes_fmi, Fmi};
use triad::platforms::{Binary, Platform};
use triad::variables::fmi3::Table3;
use triad::variables::{Causality, VariableTable};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The shipped models: (folder name, spec path).
fn shipped() -> Vec<(String, PathBuf)> {
    let mut v: Vec<(String, PathBuf)> = std::fs::read_dir(root().join("modelDescription"))
        .unwrap()
        .filter_map(|e| {
            let p = e.ok()?.path();
            let spec = p.join("spec.toml");
            let name = p.file_name()?.to_string_lossy().into_owned();
            spec.is_file().then_some((name, spec))
        })
        .collect();
    v.sort();
    assert!(v.len() >= 8, "{v:?}");
    v
}

/// This build's library (the newest beside the test executable or one level up).
fn cdylib() -> PathBuf {
    if let Some(p) = std::env::var_os("TRIAD_CDYLIB") {
        return PathBuf::from(p);
    }
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    let (file, _) = triad::package::cdylib_names();
    [deps.parent().unwrap(), deps]
        .into_iter()
        .map(|d| d.join(file))
        .filter_map(|p| Some((p.metadata().ok()?.modified().ok()?, p)))
        .max()
        .map(|(_, p)| p)
        .expect("the cdylib: run cargo build --lib first")
}

fn triad(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_triad"))
        .args(args)
        .current_dir(dir)
        .env("TRIAD_CDYLIB", cdylib())
        .env("TRIAD_RUNTIME_DIR", dir.join("no-runtime"))
        .output()
        .unwrap()
}

fn unzip(bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    let mut z = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    (0..z.len())
        .map(|i| {
            let mut f = z.by_index(i).unwrap();
            let mut data = Vec::new();
            f.read_to_end(&mut data).unwrap();
            (f.name().to_string(), data)
        })
        .collect()
}

/// The value of attribute `name` in the first element that has it.
fn attr<'a>(xml: &'a str, name: &str) -> &'a str {
    let key = format!(" {name}=\"");
    let at = xml.find(&key).unwrap_or_else(|| panic!("no {name}")) + key.len();
    &xml[at..at + xml[at..].find('"').unwrap()]
}

/// The text of the variable element called `name` (to its end tag, or its `/>`).
fn element<'a>(xml: &'a str, name: &str) -> &'a str {
    let key = format!(" name=\"{name}\" ");
    let at = xml
        .find(&key)
        .unwrap_or_else(|| panic!("no variable {name}"));
    let start = xml[..at].rfind('<').unwrap();
    let rest = &xml[start..];
    let line_end = rest.find('\n').unwrap();
    if rest[..line_end].ends_with("/>") {
        &rest[..line_end]
    } else {
        let close = rest.find("</").unwrap();
        &rest[..close + rest[close..].find('>').unwrap() + 1]
    }
}

fn table(spec: &Path) -> VariableTable {
    let spec = triad::spec::Spec::from_path(spec).unwrap();
    let (def, settings) = spec.lower().unwrap();
    triad::fmu::contract::table(&spec, &def, &settings)
}

fn host_tuple() -> String {
    triad::platforms::fmi3_folders(Platform::host()).remove(0)
}

#[test]
fn every_shipped_model_builds_an_fmi3_fmu() {
    let tmp = tempfile::tempdir().unwrap();
    for (name, spec) in shipped() {
        let out = format!("{name}.fmu");
        let run = triad(
            &[
                "build",
                spec.to_str().unwrap(),
                "--fmi",
                "3",
                "-o",
                &out,
                "--platforms",
                "host",
            ],
            tmp.path(),
        );
        let stdout = String::from_utf8_lossy(&run.stdout);
        assert!(
            run.status.success(),
            "{name}: {stdout}{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let bytes = std::fs::read(tmp.path().join(&out)).unwrap();
        let entries = unzip(&bytes);
        let golden = std::fs::read_to_string(spec.with_file_name("modelDescription.xml")).unwrap();
        let id = attr(&golden, "modelIdentifier");
        let guid = attr(&golden, "guid");
        let so = format!(
            "binaries/{}/{id}.{}",
            host_tuple(),
            triad::package::cdylib_names().1
        );
        let names: Vec<&str> = entries.iter().map(|e| e.0.as_str()).collect();
        assert_eq!(
            names,
            vec![
                so.as_str(),
                "documentation/index.html",
                "documentation/scene.html",
                "modelDescription.xml",
                "resources/model.json"
            ],
            "{name}"
        );
        assert!(
            stdout.contains(&format!("packed binaries/{}: ", host_tuple())),
            "{stdout}"
        );
        let xml = std::str::from_utf8(&entries[3].1).unwrap();
        assert_eq!(attr(xml, "fmiVersion"), "3.0", "{name}");
        assert_eq!(attr(xml, "instantiationToken"), guid, "{name}");
        assert_eq!(attr(xml, "modelIdentifier"), id, "{name}");
        assert!(!xml.contains(" guid=\""), "{name}");
        for flag in [
            "canHandleVariableCommunicationStepSize=\"true\"",
            "canGetAndSetFMUState=\"true\"",
            "canSerializeFMUState=\"true\"",
            "mightReturnEarlyFromDoStep=\"true\"",
            "hasEventMode=\"false\"",
        ] {
            assert!(xml.contains(flag), "{name}: {flag}");
        }
        // derivatives where the model declares states: trees with joint coordinates, no contact
        // (as the FMI 2 file says)
        let provides = attr(&golden, "providesDirectionalDerivative");
        for flag in [
            "providesDirectionalDerivatives",
            "providesAdjointDerivatives",
        ] {
            assert_eq!(attr(xml, flag), provides, "{name}: {flag}");
        }
        // time first, at value reference 0
        let vars = &xml[xml.find("<ModelVariables>").unwrap()..];
        let first = vars.lines().nth(1).unwrap();
        assert!(
            first.contains("<Float64 name=\"time\" valueReference=\"0\"")
                && first.contains("causality=\"independent\""),
            "{name}: {first}"
        );
        // every FMI 3 variable, arrays with their dimensions; outputs by value reference
        let t = table(&spec);
        let t3 = Table3::new(&t);
        let mut outputs = 0;
        for v in &t3.vars {
            let e = element(xml, &v.name);
            assert!(e.contains(&format!(" valueReference=\"{}\"", v.vr)), "{e}");
            let dims: Vec<String> = v
                .dims
                .iter()
                .map(|d| format!("<Dimension start=\"{d}\"/>"))
                .collect();
            assert_eq!(e.matches("<Dimension ").count(), v.dims.len(), "{e}");
            for d in &dims {
                assert!(e.contains(d.as_str()), "{e}");
            }
            let causality = t.by_vr(v.members[0]).unwrap().causality;
            if causality == Causality::Output {
                outputs += 1;
                assert!(
                    xml.contains(&format!("<Output valueReference=\"{}\" ", v.vr)),
                    "{name}: {} not an Output",
                    v.name
                );
            }
        }
        assert_eq!(xml.matches("<Output ").count(), outputs, "{name}");
        assert_eq!(
            xml.matches("<Float64 ").count() + xml.matches("<Int32 ").count(),
            t3.vars.len() + 1,
            "{name}"
        );
        // the quantities that are arrays
        for b in t.vars.iter().filter_map(|v| v.name.strip_suffix(".R[1,1]")) {
            let r = element(xml, &format!("{b}.R"));
            assert_eq!(r.matches("<Dimension start=\"3\"/>").count(), 2, "{r}");
            let p = element(xml, &format!("{b}.r"));
            assert_eq!(p.matches("<Dimension start=\"3\"/>").count(), 1, "{p}");
        }
        let g = element(xml, "gravity");
        assert!(
            g.contains("<Dimension start=\"3\"/>") && g.contains(" start=\""),
            "{g}"
        );
        // documentation: the FMI 3 names
        let html = std::str::from_utf8(&entries[1].1).unwrap();
        assert!(html.contains("FMI 3.0 Co-Simulation FMU"), "{name}");
        for v in &t3.vars {
            assert!(
                html.contains(&format!("<code>{}</code>", v.name)),
                "{name}: {}",
                v.name
            );
        }
        // deterministic: the same model built again gives the same bytes
        let again = triad(
            &[
                "build",
                spec.to_str().unwrap(),
                "--fmi",
                "3",
                "-o",
                "again.fmu",
                "--platforms",
                "host",
            ],
            tmp.path(),
        );
        assert!(again.status.success());
        assert_eq!(
            std::fs::read(tmp.path().join("again.fmu")).unwrap(),
            bytes,
            "{name}: not deterministic"
        );
    }
}

#[test]
fn fmi2_stays_the_default() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = root().join("modelDescription/pendulum/spec.toml");
    let s = spec.to_str().unwrap();
    for (args, version) in [
        (
            vec!["build", s, "-o", "a.fmu", "--platforms", "host"],
            "2.0",
        ),
        (
            vec![
                "build",
                s,
                "-o",
                "b.fmu",
                "--platforms",
                "host",
                "--fmi",
                "2",
            ],
            "2.0",
        ),
    ] {
        let out = triad(&args, tmp.path());
        assert!(out.status.success());
        let fmu = args[3];
        let entries = unzip(&std::fs::read(tmp.path().join(fmu)).unwrap());
        let xml = entries
            .iter()
            .find(|e| e.0 == "modelDescription.xml")
            .unwrap();
        let xml = std::str::from_utf8(&xml.1).unwrap();
        assert_eq!(attr(xml, "fmiVersion"), version);
        assert_eq!(
            xml,
            std::fs::read_to_string(spec.with_file_name("modelDescription.xml")).unwrap()
        );
    }
}

#[test]
fn describe_fmi3_lists_arrays_with_their_dimensions() {
    let tmp = tempfile::tempdir().unwrap();
    let out = triad(&["describe", "double_pendulum", "--fmi", "3"], tmp.path());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line = |name: &str| {
        text.lines()
            .find(|l| l.split_whitespace().next() == Some(name))
            .unwrap_or_else(|| panic!("no {name} in\n{text}"))
            .split_whitespace()
            .map(str::to_string)
            .collect::<Vec<_>>()
    };
    let rot = line("body.link1.R");
    assert_eq!(rot[1], "[3,3]", "{rot:?}");
    assert_eq!(rot[3], "output");
    assert_eq!(rot[5], "Float64");
    assert_eq!(line("body.link1.r")[1], "[3]");
    assert_eq!(line("gravity")[1], "[3]");
    let time = line("time");
    assert_eq!(time[1], "0");
    assert_eq!(time[2], "independent");
    let tau = line("joint.shoulder.tau");
    assert_eq!(tau[1], "1", "a scalar has no dims and vr 1: {tau:?}");
    // no scalar element names of arrays
    assert!(!text.contains("body.link1.R[1,1]"), "{text}");
    // the FMI 2 view stays the default
    let two = triad(&["describe", "double_pendulum"], tmp.path());
    assert!(String::from_utf8_lossy(&two.stdout).contains("body.link1.R[1,1]"));
}

#[test]
fn bad_fmi_versions_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let spec = root().join("modelDescription/pendulum/spec.toml");
    for bad in ["4", "1", "3.1", "x"] {
        for cmd in [
            vec!["build", spec.to_str().unwrap(), "--fmi", bad],
            vec!["describe", "pendulum", "--fmi", bad],
        ] {
            let out = triad(&cmd, tmp.path());
            let err = String::from_utf8_lossy(&out.stderr);
            assert!(!out.status.success(), "{cmd:?}");
            assert!(
                err.contains(&format!("invalid value '{bad}' for '--fmi <2|3>'"))
                    && err.contains("[possible values: 2, 3]"),
                "{cmd:?}: {err}"
            );
        }
    }
    assert!(std::fs::read_dir(tmp.path()).unwrap().next().is_none());
    let help = triad(&["build", "--help"], tmp.path());
    let help = String::from_utf8_lossy(&help.stdout);
    for needle in [
        "--fmi <2|3>",
        "arrays",
        "Simulink",
        "x86_64-linux",
        "aarch64-darwin",
    ] {
        assert!(help.contains(needle), "{needle}: {help}");
    }
}

fn fake(platform: Platform, folder: &str, bytes: &[u8]) -> Binary {
    Binary {
        platform: Some(platform),
        folder: folder.to_string(),
        ext: platform.file().1,
        label: platform.name().to_string(),
        unreadable: None,
        source: PathBuf::new(),
        bytes: bytes.to_vec(),
    }
}

#[test]
fn every_platform_goes_under_its_fmi3_tuple() {
    assert_eq!(Platform::Linux64.fmi3_folders(), ["x86_64-linux"]);
    assert_eq!(Platform::Win64.fmi3_folders(), ["x86_64-windows"]);
    assert_eq!(
        Platform::Darwin64.fmi3_folders(),
        ["aarch64-darwin", "x86_64-darwin"]
    );
    assert_eq!(Platform::Aarch64Linux.fmi3_folders(), ["aarch64-linux"]);
    assert_eq!(Platform::Linux64Aarch64.fmi3_folders(), ["aarch64-linux"]);
    let spec =
        triad::spec::Spec::from_path(&root().join("modelDescription/pendulum/spec.toml")).unwrap();
    let binaries = [
        fake(Platform::Aarch64Linux, "aarch64-linux", b"arm"),
        fake(Platform::Darwin64, "darwin64", b"mac"),
        fake(Platform::Linux64, "linux64", b"x86"),
        fake(Platform::Linux64Aarch64, "linux64-aarch64", b"arm"),
        fake(Platform::Win64, "win64", b"win"),
    ];
    let bytes = fmu_bytes_fmi(&spec, None, &binaries, Fmi::V3).unwrap();
    assert_eq!(
        bytes,
        fmu_bytes_fmi(&spec, None, &binaries, Fmi::V3).unwrap()
    );
    let entries = unzip(&bytes);
    let bins: Vec<(&str, &[u8])> = entries
        .iter()
        .filter(|e| e.0.starts_with("binaries/"))
        .map(|e| (e.0.as_str(), e.1.as_slice()))
        .collect();
    let id = &spec.name;
    assert_eq!(
        bins,
        vec![
            (
                format!("binaries/aarch64-darwin/{id}.dylib").as_str(),
                &b"mac"[..]
            ),
            (
                format!("binaries/aarch64-linux/{id}.so").as_str(),
                &b"arm"[..]
            ),
            (
                format!("binaries/x86_64-darwin/{id}.dylib").as_str(),
                &b"mac"[..]
            ),
            (
                format!("binaries/x86_64-linux/{id}.so").as_str(),
                &b"x86"[..]
            ),
            (
                format!("binaries/x86_64-windows/{id}.dll").as_str(),
                &b"win"[..]
            ),
        ]
    );
    // two different files for one tuple are refused
    let clash = [
        fake(Platform::Aarch64Linux, "aarch64-linux", b"arm"),
        fake(Platform::Linux64Aarch64, "linux64", b"other"),
    ];
    let e = fmu_bytes_fmi(&spec, None, &clash, Fmi::V3).unwrap_err();
    assert!(e.to_string().contains("two binaries"), "{e}");
    // FMI 2: the folders as before
    let two = unzip(&fmu_bytes_fmi(&spec, None, &binaries[..3], Fmi::V2).unwrap());
    assert!(two
        .iter()
        .any(|e| e.0 == format!("binaries/darwin64/{id}.dylib")));
}
