//! Embeds the shipped example specs (`modelDescription/*/spec.toml`) so the CLI and the tests
//! iterate over exactly the shipped set, records the FMI platform name, and the runtime id: a
//! hash of the sources the FMU runtime compiles, so `triad build` can tell a runtime binary
//! built from other sources (`src/platforms.rs`).
use std::{env, fs, path::Path};

/// The sources of the FMU runtime (`--no-default-features`): everything but the tools modules.
const RUNTIME_SOURCES: &[&str] = &[
    "src/lib.rs",
    "src/math.rs",
    "src/sim.rs",
    "src/variables.rs",
    "src/ffi",
    "src/fmu",
    "src/mechanics",
    "src/spec",
    "src/variables",
];

/// The files below `path` (or `path` itself), sorted.
fn files(path: &Path, out: &mut Vec<std::path::PathBuf>) {
    if path.is_dir() {
        let mut entries: Vec<_> = fs::read_dir(path)
            .map(|r| r.flatten().map(|e| e.path()).collect())
            .unwrap_or_default();
        entries.sort();
        for e in entries {
            files(&e, out);
        }
    } else if path.is_file() {
        out.push(path.to_path_buf());
    }
}

/// 64-bit FNV-1a of the runtime's sources (relative paths and contents, `\r` dropped so a
/// Windows checkout hashes alike), as 16 hex digits.
fn runtime_id(root: &Path) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes.iter().filter(|&&b| b != b'\r') {
            h ^= u64::from(b);
            h = h.wrapping_mul(0x0100_0000_01b3);
        }
    };
    for source in RUNTIME_SOURCES {
        println!("cargo:rerun-if-changed={source}");
        let mut list = Vec::new();
        files(&root.join(source), &mut list);
        for f in list {
            let rel = f
                .strip_prefix(root)
                .unwrap_or(&f)
                .to_string_lossy()
                .replace('\\', "/");
            eat(rel.as_bytes());
            eat(&[0]);
            eat(&fs::read(&f).unwrap_or_default());
            eat(&[0]);
        }
    }
    format!("{h:016x}")
}

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
    println!(
        "cargo:rustc-env=TRIAD_RUNTIME_ID={}",
        runtime_id(Path::new(&root))
    );
}
