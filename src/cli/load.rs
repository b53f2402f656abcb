//! Finding MODEL: a spec file, a model folder or the name of a shipped model.

use std::path::Path;

use triad::spec::{bundled, Format, Spec, SpecErrors};

/// Loads MODEL: a spec file, a folder holding `spec.toml`, or, when no such file exists and
/// MODEL has no extension, the shipped model of that name.
pub fn load(model: &str) -> Result<Spec, SpecErrors> {
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
