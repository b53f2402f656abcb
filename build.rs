//! Embeds the shipped example specs (`modelDescription/*/spec.toml`) so the CLI and the tests
//! iterate over exactly the shipped set, and records the FMI platform name.
use std::{env, fs, path::Path};

fn main() {
    println!("cargo:rerun-if-changed=modelDescription");
    println!("cargo:rerun-if-changed=build.rs");
    let root = env::var("CARGO_MANIFEST_DIR").expect("manifest dir");
    let dir = Path::new(&root).join("modelDescription");
    let mut entries: Vec<(String, String)> = Vec::new();
    if let Ok(read) = fs::read_dir(&dir) {
        for e in read.flatten() {
            let spec = e.path().join("spec.toml");
            if spec.is_file() {
                println!("cargo:rerun-if-changed={}", spec.display());
                let name = e.file_name().to_string_lossy().into_owned();
                entries.push((name, spec.display().to_string()));
            }
        }
    }
    entries.sort();
    let mut out = String::from("/// Shipped example specs: (folder name, spec.toml text).\npub static BUNDLED: &[(&str, &str)] = &[\n");
    for (name, path) in &entries {
        out.push_str(&format!("    ({name:?}, include_str!({path:?})),\n"));
    }
    out.push_str("];\n");
    let out_dir = env::var("OUT_DIR").expect("out dir");
    fs::write(Path::new(&out_dir).join("bundled.rs"), out).expect("write bundled.rs");
    let os = env::var("CARGO_CFG_TARGET_OS").unwrap_or_default();
    let width = env::var("CARGO_CFG_TARGET_POINTER_WIDTH").unwrap_or_default();
    let platform = match (os.as_str(), width.as_str()) {
        ("windows", "64") => "win64",
        ("windows", _) => "win32",
        ("macos", _) => "darwin64",
        (_, "32") => "linux32",
        _ => "linux64",
    };
    println!("cargo:rustc-env=TRIAD_FMI_PLATFORM={platform}");
}
