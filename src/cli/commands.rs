//! `triad check`, `triad describe` and `triad build`.

use std::path::{Path, PathBuf};

use triad::package::Fmi;
use triad::sim::Simulation;
use triad::variables::fmi3::{Table3, TIME_VR};
use triad::variables::{Causality, VarType, VariableTable};

use super::error::CliError;
use super::import_args::ImportArgs;
use super::load::{is_mjcf, is_urdf, load, load_mjcf, load_noted, load_urdf, no_import_options};
use super::start_gap;

/// Prints a note on standard output: `note: …`, or as it is when it is a warning (`warning: …`).
fn print_note(note: &str) {
    if note.starts_with("warning:") {
        println!("{note}");
    } else {
        println!("note: {note}");
    }
}

/// Validates MODEL (a URDF imported as `urdf` asks); prints `ok`, a summary and the notes of
/// the import and of the mechanics. Writes nothing.
pub fn check(model: &str, urdf: &ImportArgs) -> Result<(), CliError> {
    let (spec, import_notes) = load_noted(model, urdf)?;
    let (def, settings) = spec.lower()?;
    let sim = Simulation::new(&def, settings, spec.experiment.start)
        .map_err(|e| format!("{model}: {e}"))?;
    let built = sim.model();
    let table = VariableTable::new(&def, &settings).with_labels(&spec.labels());
    let count = |c: Causality| table.with_causality(c).count();
    let origin = if std::path::Path::new(model).exists() {
        model.to_string()
    } else {
        format!("shipped model {model}")
    };
    println!("{origin}: ok");
    println!(
        "model {}: {}, {} ({} loop-closing), {}, {}, {}",
        spec.name,
        plural(def.bodies.len(), "body", "bodies"),
        plural(def.joints.len(), "joint", "joints"),
        def.joints.iter().filter(|j| j.loop_closing).count(),
        plural(count(Causality::Input), "input", "inputs"),
        plural(count(Causality::Output), "output", "outputs"),
        plural(count(Causality::Parameter), "parameter", "parameters")
    );
    for note in import_notes.iter().chain(built.notes()) {
        print_note(note);
    }
    if let Some(warning) = start_gap::for_model(&sim, model, urdf) {
        print_note(&warning);
    }
    Ok(())
}

fn plural(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// Prints `rows` under `header` with aligned columns (`right`: the right-aligned column; the
/// last column unpadded).
fn print_table<const N: usize>(header: [&str; N], rows: &[[String; N]], right: usize) {
    let header = header.map(String::from);
    let mut widths = [0usize; N];
    for row in std::iter::once(&header).chain(rows) {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let mut out = String::new();
    for row in std::iter::once(&header).chain(rows) {
        let mut line = String::new();
        for (k, (cell, w)) in row.iter().zip(widths).enumerate() {
            if k == N - 1 {
                line.push_str(cell);
            } else if k == right {
                line.push_str(&format!("{cell:>w$}  "));
            } else {
                line.push_str(&format!("{cell:<w$}  "));
            }
        }
        out.push_str(line.trim_end());
        out.push('\n');
    }
    print!("{out}");
}

fn type_name(ty: VarType, fmi: Fmi) -> &'static str {
    match (ty, fmi) {
        (VarType::Integer, Fmi::V2) => "Integer",
        (VarType::Real, Fmi::V2) => "Real",
        (VarType::Integer, Fmi::V3) => "Int32",
        (VarType::Real, Fmi::V3) => "Float64",
    }
}

/// Prints the FMI 3 variables: `time`, then each variable with its dimensions (`[3,3]`).
fn describe3(table: &VariableTable) {
    let t3 = Table3::new(table);
    let mut rows: Vec<[String; 8]> = vec![[
        "time".into(),
        "".into(),
        TIME_VR.to_string(),
        "independent".into(),
        "continuous".into(),
        "Float64".into(),
        "s".into(),
        "simulation time".into(),
    ]];
    for v in &t3.vars {
        let Some(f) = v.members.first().and_then(|&vr| table.by_vr(vr)) else {
            continue;
        };
        rows.push([
            v.name.clone(),
            triad::package::dims_text(&v.dims),
            v.vr.to_string(),
            f.causality.fmi_name().into(),
            f.variability.fmi_name().into(),
            type_name(f.ty, Fmi::V3).into(),
            f.unit.unwrap_or("-").into(),
            v.description.clone(),
        ]);
    }
    print_table(
        [
            "name",
            "dims",
            "vr",
            "causality",
            "variability",
            "type",
            "unit",
            "description",
        ],
        &rows,
        2,
    );
}

/// Prints the variable table with aligned columns (`fmi`: `2`, or `3` for the FMI 3 view).
pub fn describe(model: &str, fmi: &str, urdf: &ImportArgs) -> Result<(), CliError> {
    let fmi = Fmi::parse(fmi)?;
    let spec = load(model, urdf)?;
    let (def, settings) = spec.lower()?;
    let table = VariableTable::new(&def, &settings).with_labels(&spec.labels());
    if fmi == Fmi::V3 {
        describe3(&table);
        return Ok(());
    }
    let rows: Vec<[String; 7]> = table
        .vars
        .iter()
        .map(|v| {
            [
                v.name.clone(),
                v.vr.to_string(),
                v.causality.fmi_name().into(),
                v.variability.fmi_name().into(),
                type_name(v.ty, Fmi::V2).into(),
                v.unit.unwrap_or("-").into(),
                v.description.clone(),
            ]
        })
        .collect();
    print_table(
        [
            "name",
            "vr",
            "causality",
            "variability",
            "type",
            "unit",
            "description",
        ],
        &rows,
        1,
    );
    Ok(())
}

/// Validates MODEL, then packages its FMU.
pub fn build(
    model: &Path,
    output: Option<&Path>,
    platforms: Option<&str>,
    fmi: &str,
    urdf: &ImportArgs,
) -> Result<(), CliError> {
    let fmi = Fmi::parse(fmi)?;
    let selection = match platforms {
        Some(text) => triad::platforms::Selection::parse(text)?,
        None => triad::platforms::Selection::Found,
    };
    if !model.exists() && model.extension().is_none() {
        let name = model.display();
        if triad::spec::bundled()
            .iter()
            .any(|(n, _)| model.as_os_str() == *n)
        {
            return Err(format!(
                "{name}: build needs the spec file: triad build modelDescription/{name}/spec.toml"
            )
            .into());
        }
    }
    let folder_spec = model.join("spec.toml");
    let model = if model.is_dir() && folder_spec.is_file() {
        folder_spec.as_path()
    } else {
        model
    };
    let spec = if is_urdf(model) || is_mjcf(model) {
        load(&model.to_string_lossy(), urdf)?
    } else {
        no_import_options(&model.to_string_lossy(), urdf)?;
        triad::spec::Spec::from_path(model)?
    };
    let out = output.map_or_else(
        || PathBuf::from(format!("{}.fmu", spec.name)),
        Path::to_path_buf,
    );
    let built = triad::package::build_fmu_fmi(&spec, model.parent(), &out, &selection, fmi)
        .map_err(|e| format!("{}: {e}", model.display()))?;
    for (folder, label, source) in &built.packed {
        println!(
            "packed binaries/{folder}: {label}, from {}",
            source.display()
        );
    }
    for note in &built.notes {
        print_note(note);
    }
    let start = spec
        .lower()
        .ok()
        .and_then(|(def, settings)| Simulation::new(&def, settings, spec.experiment.start).ok());
    if let Some(warning) = start
        .as_ref()
        .and_then(|sim| start_gap::for_model(sim, &model.to_string_lossy(), urdf))
    {
        print_note(&warning);
    }
    println!("wrote {}", built.path.display());
    Ok(())
}

/// `triad import ROBOT.urdf|MODEL.xml`: writes the equivalent spec (TOML) to `output`, or to
/// standard output; nothing is written when the robot description has a problem.
pub fn import(robot: &Path, output: Option<&Path>, urdf: &ImportArgs) -> Result<(), CliError> {
    let name = robot.to_string_lossy();
    no_import_options(&name, urdf)?;
    let toml = if is_urdf(robot) {
        let (spec, outcome) = load_urdf(&name, &urdf.options())?;
        triad::urdf::to_toml(&spec, &outcome)
    } else if is_mjcf(robot) {
        let (spec, outcome) = load_mjcf(&name, &urdf.mjcf_options())?;
        triad::mjcf::to_toml(&spec, &outcome)
    } else {
        return Err(format!("{name}: import reads a .urdf or an MJCF .xml file").into());
    }
    .map_err(|e| format!("{name}: {e}"))?;
    match output {
        Some(out) => {
            std::fs::write(out, toml).map_err(|e| format!("{}: {e}", out.display()))?;
            eprintln!("wrote {}", out.display());
        }
        None => print!("{toml}"),
    }
    Ok(())
}
