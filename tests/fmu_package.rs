//! The .fmu archive (FMI 2.0.4 §2.3): the five expected entries in sorted order with forward
//! slashes, `modelIdentifier` = the .so name, deterministic bytes (same input → same archive),
//! and a `modelDescription.xml` whose GUID is the one `fmi2Instantiate` recomputes from
//! `resources/model.json` — so the packaged FMU instantiates from its own unzipped resources.

mod fmu_support;

use fmu_support::*;
use std::io::Read;
use triad::ffi::types::*;

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

#[test]
fn archive_layout_determinism_and_guid() {
    let m = TestModel::pendulum();
    let so = std::fs::read(cdylib()).unwrap();
    let a = triad::package::fmu_bytes(&m.spec, &so).unwrap();
    let b = triad::package::fmu_bytes(&m.spec, &so).unwrap();
    assert_eq!(a, b, "same input, same bytes");
    let entries = unzip(&a);
    let names: Vec<&str> = entries.iter().map(|e| e.0.as_str()).collect();
    let so_name = format!("binaries/{}/{}.so", triad::package::PLATFORM, m.spec.name);
    assert_eq!(
        names,
        vec![
            so_name.as_str(),
            "documentation/index.html",
            "documentation/scene.html",
            "modelDescription.xml",
            "resources/model.json"
        ]
    );
    assert_eq!(entries[0].1, so);
    let xml = String::from_utf8(entries[3].1.clone()).unwrap();
    assert!(xml.contains(&format!("guid=\"{}\"", m.guid)));
    assert!(xml.contains(&format!("modelIdentifier=\"{}\"", m.spec.name)));
    assert!(!xml.contains("generationDateAndTime"));
    let html = String::from_utf8(entries[1].1.clone()).unwrap();
    for v in &m.table.vars {
        assert!(html.contains(&v.name), "{} missing from index.html", v.name);
    }
    // the scene: the initial pose, one frame, every body
    let scene = String::from_utf8(entries[2].1.clone()).unwrap();
    let poses = triad::viewer::decode(triad::viewer::payload_of(&scene).unwrap()).unwrap();
    assert_eq!(poses.time.len(), 1);
    assert_eq!(poses.bodies.len(), m.spec.body.len());

    // unpack and instantiate from the archive's own resources
    let dir = tempfile::tempdir().unwrap();
    for (name, data) in &entries {
        let p = dir.path().join(name);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, data).unwrap();
    }
    let uri = triad::fmu::resource::path_to_uri(&dir.path().join("resources"));
    let (c, log, _cb) = instantiate_with("pkg", fmi2CoSimulation, &m.guid, Some(&uri), false);
    assert!(!c.is_null(), "{:?}", log.lock().unwrap());
    unsafe { triad::ffi::common::fmi2FreeInstance(c) };
}

#[test]
fn build_fmu_writes_the_file() {
    let m = TestModel::pendulum();
    let spec_path = m.dir.path().join("pendulum.toml");
    std::fs::write(&spec_path, PENDULUM).unwrap();
    let out = m.dir.path().join("out/Pendulum.fmu");
    std::env::set_var("TRIAD_CDYLIB", cdylib());
    let written = triad::package::build_fmu(&spec_path, &out).unwrap();
    assert_eq!(written, out);
    let bytes = std::fs::read(&out).unwrap();
    assert_eq!(
        bytes,
        triad::package::fmu_bytes(&m.spec, &std::fs::read(cdylib()).unwrap()).unwrap()
    );
}
