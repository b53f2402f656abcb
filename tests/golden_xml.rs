//! modelDescription.xml is generated, never edited: for every shipped model
//! (`modelDescription/<model>/spec.toml`) the writer's output must equal the committed
//! `modelDescription/<model>/modelDescription.xml` byte for byte. `UPDATE_GOLDEN=1` rewrites
//! the files instead. Structural rules of FMI 2.0.4 §2.2 are checked on the way: every unit
//! declared with base units, `<Outputs>` = exactly the outputs in index order with
//! `dependencies=""`, `<InitialUnknowns>` = exactly the outputs with `initial="calculated"`,
//! inputs with `start="0"` and no `initial`, unique value references.

mod fmu_support;

use std::path::Path;
use triad::fmu::contract::{self, Format, Spec};
use triad::variables::{Causality, Initial};
use triad::xml::{unknown_units, write_model_description, Meta};

fn generate(spec: &Spec) -> String {
    let (def, settings) = spec.lower().unwrap();
    let table = contract::table(spec, &def, &settings);
    assert!(
        unknown_units(&table).is_empty(),
        "units without base units: {:?}",
        unknown_units(&table)
    );
    let mut vrs: Vec<u32> = table.vars.iter().map(|v| v.vr).collect();
    vrs.sort_unstable();
    vrs.dedup();
    assert_eq!(
        vrs.len(),
        table.vars.len(),
        "value references must be unique"
    );
    let xml = write_model_description(&table, &Meta::new(spec, &settings, &table)).unwrap();
    // structure
    let idx = |pred: &dyn Fn(&triad::variables::Variable) -> bool| -> String {
        table
            .vars
            .iter()
            .enumerate()
            .filter(|(_, v)| pred(v))
            .map(|(i, _)| format!("<Unknown index=\"{}\"", i + 1))
            .collect::<Vec<_>>()
            .join("")
    };
    let section = |tag: &str| -> String {
        let Some(a) = xml.find(&format!("<{tag}>")) else {
            return String::new();
        };
        let b = xml[a..].find(&format!("</{tag}>")).unwrap() + a;
        xml[a..b]
            .lines()
            .map(|l| {
                l.trim()
                    .split(" dependencies")
                    .next()
                    .unwrap()
                    .trim_end_matches("/>")
                    .to_string()
            })
            .filter(|l| l.starts_with("<Unknown"))
            .collect()
    };
    assert_eq!(
        section("Outputs"),
        idx(&|v| v.causality == Causality::Output)
    );
    assert_eq!(
        section("InitialUnknowns"),
        idx(&|v| v.causality == Causality::Output && v.initial == Initial::Calculated)
    );
    for v in table
        .vars
        .iter()
        .filter(|v| v.causality == Causality::Input)
    {
        let line = xml
            .lines()
            .find(|l| l.contains(&format!("name=\"{}\"", v.name)))
            .unwrap();
        assert!(!line.contains("initial="), "{line}");
    }
    assert!(!xml.contains("generationDateAndTime"));
    assert_eq!(
        xml,
        write_model_description(&table, &Meta::new(spec, &settings, &table)).unwrap(),
        "deterministic"
    );
    xml
}

#[test]
fn shipped_models_match_their_golden_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("modelDescription");
    let update = std::env::var_os("UPDATE_GOLDEN").is_some();
    let mut stale = Vec::new();
    for (name, text) in contract::bundled() {
        let spec =
            Spec::from_str(text, Format::Toml, name).unwrap_or_else(|e| panic!("{name}: {e}"));
        let xml = generate(&spec);
        let path = root.join(name).join("modelDescription.xml");
        if update {
            std::fs::write(&path, &xml).unwrap();
        } else if std::fs::read_to_string(&path).ok().as_deref() != Some(xml.as_str()) {
            stale.push(path.display().to_string());
        }
    }
    assert!(
        stale.is_empty(),
        "stale golden files (run UPDATE_GOLDEN=1 cargo test --test golden_xml): {stale:?}"
    );
}

#[test]
fn test_model_description_structure() {
    let spec = Spec::from_str(fmu_support::PENDULUM, Format::Toml, "pendulum").unwrap();
    let xml = generate(&spec);
    for needle in [
        "fmiVersion=\"2.0\"",
        "causality=\"input\" variability=\"continuous\">",
        "<Real unit=\"N.m\" start=\"0\"/>",
        "variableNamingConvention=\"structured\"",
        concat!("generationTool=\"triad ", env!("CARGO_PKG_VERSION"), "\""),
        "canHandleVariableCommunicationStepSize=\"true\"",
        "canGetAndSetFMUstate=\"true\"",
        "canSerializeFMUstate=\"true\"",
        "canNotUseMemoryManagementFunctions=\"true\"",
        "<Category name=\"logStatusDiscard\"",
        "<DisplayUnit name=\"deg\" factor=\"57.29577951308232\"/>",
        "<DefaultExperiment startTime=\"0\" stopTime=\"1\" tolerance=\"1e-10\" stepSize=\"0.01\"/>",
    ] {
        assert!(xml.contains(needle), "{needle} missing in\n{xml}");
    }
}
