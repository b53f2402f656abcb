//! Finding MODEL: a spec file, a URDF, an MJCF file, a model folder or the name of a shipped
//! model.

use std::path::Path;

use triad::mjcf;
use triad::spec::{bundled, Format, Spec, SpecErrors};
use triad::urdf::{self, ImportOptions};

use super::import_args::ImportArgs;

/// Loads MODEL: a spec file, a `.urdf` or an MJCF `.xml` (imported as `urdf` asks), a folder
/// holding `spec.toml`, or, when no such file exists and MODEL has no extension, the shipped
/// model of that name. Returns the validated spec and the import's notes (none for a spec).
/// Import options given with a MODEL of another kind are an error.
pub fn load_noted(model: &str, urdf: &ImportArgs) -> Result<(Spec, Vec<String>), SpecErrors> {
    let path = Path::new(model);
    no_import_options(model, urdf)?;
    if is_urdf(path) {
        return load_urdf(model, &urdf.options()).map(|(spec, outcome)| (spec, outcome.notes));
    }
    if is_mjcf(path) {
        return load_mjcf(model, &urdf.mjcf_options()).map(|(spec, outcome)| (spec, outcome.notes));
    }
    load_spec(model).map(|s| (s, Vec::new()))
}

/// Refuses the import options MODEL does not take (they would change nothing): URDF options
/// for anything but a `.urdf`, MJCF options for anything but an MJCF `.xml`.
pub fn no_import_options(model: &str, urdf: &ImportArgs) -> Result<(), SpecErrors> {
    let path = Path::new(model);
    if !is_urdf(path) {
        refuse(model, &urdf.given(), "a .urdf", "URDF")?;
    }
    if !is_mjcf(path) {
        refuse(model, &urdf.given_mjcf(), "an MJCF .xml", "MJCF")?;
    }
    Ok(())
}

/// The error for the options `given`, which only `kind` (of `format`) takes.
fn refuse(model: &str, given: &[&str], kind: &str, format: &str) -> Result<(), SpecErrors> {
    if given.is_empty() {
        return Ok(());
    }
    Err(SpecErrors::single(
        model,
        "",
        format!(
            "{} {} for {kind} MODEL only ({format} import); this MODEL is not one",
            given.join(", "),
            if given.len() == 1 { "is" } else { "are" }
        ),
    ))
}

/// Reads, imports and validates the MJCF file `model` (problems of the imported spec in the
/// MJCF's terms); the spec and what the import says of it.
pub fn load_mjcf(
    model: &str,
    opts: &mjcf::ImportOptions,
) -> Result<(Spec, mjcf::Outcome), SpecErrors> {
    let text = std::fs::read_to_string(model)
        .map_err(|e| SpecErrors::single(model, "", format!("cannot read the file: {e}")))?;
    let (spec, outcome) = mjcf::import(&text, Path::new(model), opts)?;
    spec.validate(model)
        .map_err(|e| mjcf::in_mjcf_terms(e, &outcome))?;
    Ok((spec, outcome))
}

/// True for an MJCF path (`.xml`).
pub fn is_mjcf(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("xml"))
}

/// Reads, imports and validates the URDF `model` (problems of the imported spec in the URDF's
/// terms); the spec and what the import says of it. The geometry dropped (`<visual>` or
/// `<collision>` that cannot be read) is printed to standard error as warnings.
pub fn load_urdf(model: &str, opts: &ImportOptions) -> Result<(Spec, urdf::Outcome), SpecErrors> {
    let text = std::fs::read_to_string(model)
        .map_err(|e| SpecErrors::single(model, "", format!("cannot read the file: {e}")))?;
    let (spec, outcome) = urdf::import(&text, model, opts)?;
    spec.validate(model)
        .map_err(|e| urdf::in_urdf_terms(e, &spec, &outcome))?;
    for w in &outcome.warnings {
        eprintln!("warning: {model}: {w}");
    }
    Ok((spec, outcome))
}

/// True for a `.urdf` path.
pub fn is_urdf(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("urdf"))
}

/// Loads MODEL as [`load_noted`], without the notes.
pub fn load(model: &str, urdf: &ImportArgs) -> Result<Spec, SpecErrors> {
    load_noted(model, urdf).map(|(s, _)| s)
}

/// Loads a MODEL that is not a URDF: a spec file, a model folder or a shipped model's name.
fn load_spec(model: &str) -> Result<Spec, SpecErrors> {
    let path = Path::new(model);
    // a model folder stands for its spec.toml (or spec.json)
    if path.is_dir() {
        for file in ["spec.toml", "spec.json"] {
            if path.join(file).is_file() {
                return Spec::from_path(&path.join(file));
            }
        }
        return Err(SpecErrors::single(
            model,
            "",
            "is a folder without spec.toml or spec.json",
        ));
    }
    if !path.exists() && path.extension().is_none() {
        if let Some((name, text)) = bundled().iter().find(|(n, _)| *n == model) {
            return Spec::from_str(
                text,
                Format::Toml,
                &format!("modelDescription/{name}/spec.toml"),
            );
        }
        let names: Vec<&str> = bundled().iter().map(|(n, _)| *n).collect();
        return Err(SpecErrors::single(
            model,
            "",
            format!(
                "no such file, and no shipped model of that name (shipped: {})",
                names.join(", ")
            ),
        ));
    }
    Spec::from_path(path)
}
