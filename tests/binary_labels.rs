//! Each runtime binary is labelled by what it needs, read from the binary (issue 35 item 5):
//! `triad build` prints `linux64 (x86_64 Linux, glibc >= X)` with X the highest `GLIBC_x.y`
//! version the library's symbols need (here computed independently: `objdump -T`, or the
//! `GLIBC_` strings of the file), and `documentation/index.html` lists the same label. A host
//! build needs the host's glibc (2.35 on Ubuntu 22.04), not the 2.17 of the runtime that
//! `scripts/platforms.sh` builds (whose symbols need at most GLIBC_2.14: so it is labelled). Mach-O and PE runtimes under `target/runtime/` are read
//! when they exist (their parsers are unit-tested on synthetic headers in
//! `src/platforms/needs.rs`).

mod common;
use common::triad;
use std::path::{Path, PathBuf};

/// `(2, 35)` of `2.35`.
fn version(v: &str) -> Option<Vec<u32>> {
    let digits: String = v
        .chars()
        .take_while(|c| c.is_ascii_digit() || *c == '.')
        .collect();
    let parts: Option<Vec<u32>> = digits
        .trim_end_matches('.')
        .split('.')
        .map(|x| x.parse().ok())
        .collect();
    parts.filter(|p| !p.is_empty())
}

/// The highest `GLIBC_x.y` that `path` needs: from `objdump -T` where it runs, else from the
/// `GLIBC_` strings in the file's bytes (its version needs are among them).
fn highest_glibc(path: &Path) -> Vec<u32> {
    let text = match std::process::Command::new("objdump")
        .arg("-T")
        .arg(path)
        .output()
    {
        Ok(out) if out.status.success() => String::from_utf8_lossy(&out.stdout).into_owned(),
        _ => String::from_utf8_lossy(&std::fs::read(path).unwrap()).into_owned(),
    };
    text.split("GLIBC_")
        .skip(1)
        .filter_map(version)
        .max()
        .expect("the library needs versioned glibc symbols")
}

fn dotted(v: &[u32]) -> String {
    v.iter().map(u32::to_string).collect::<Vec<_>>().join(".")
}

#[cfg(all(target_os = "linux", target_arch = "x86_64"))]
#[test]
fn the_host_build_is_labelled_with_the_glibc_it_needs() {
    let lib = triad::platforms::find_cdylib().expect("the host library");
    // the host build (glibc 2.35 here) or, in CI, the 2.17 runtime (`TRIAD_CDYLIB`), whose
    // symbols need at most GLIBC_2.14: the label says what the file needs, whichever it is
    let want = highest_glibc(&lib);
    let bytes = std::fs::read(&lib).unwrap();
    assert_eq!(
        triad::platforms::needs(&bytes).unwrap(),
        format!("x86_64 Linux, glibc >= {}", dotted(&want))
    );
    // triad build prints it and the FMU's documentation lists it, for the file it packed
    let tmp = tempfile::tempdir().unwrap();
    let spec = Path::new(env!("CARGO_MANIFEST_DIR")).join("modelDescription/pendulum/spec.toml");
    let out = triad(
        &[
            "build",
            spec.to_str().unwrap(),
            "-o",
            "p.fmu",
            "--platforms",
            "host",
        ],
        tmp.path(),
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let line = text
        .lines()
        .find(|l| l.starts_with("packed binaries/linux64: "))
        .expect("the packed line");
    let source = PathBuf::from(line.rsplit_once(", from ").unwrap().1);
    let label = format!(
        "linux64 (x86_64 Linux, glibc >= {})",
        dotted(&highest_glibc(&source))
    );
    assert!(line.contains(&label), "{line}\nwanted {label}");
    let fmu = std::fs::File::open(tmp.path().join("p.fmu")).unwrap();
    let mut zip = zip::ZipArchive::new(fmu).unwrap();
    let mut html = String::new();
    std::io::Read::read_to_string(
        &mut zip.by_name("documentation/index.html").unwrap(),
        &mut html,
    )
    .unwrap();
    assert!(
        html.contains(&label.replace(">=", "&gt;=")),
        "index.html lists {label}"
    );
}

#[test]
fn runtimes_of_other_platforms_are_read_where_they_exist() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("target/runtime");
    let cases = [
        ("linux64/libtriad.so", "x86_64 Linux, glibc >= "),
        ("aarch64-linux/libtriad.so", "aarch64 Linux, glibc >= "),
        ("win64/triad.dll", "x86_64 Windows >= "),
        ("darwin64/libtriad.dylib", "macOS "),
    ];
    for (file, start) in cases {
        let path = dir.join(file);
        let Ok(bytes) = std::fs::read(&path) else {
            eprintln!("{}: not built here (scripts/platforms.sh)", path.display());
            continue;
        };
        let what = triad::platforms::needs(&bytes).unwrap();
        assert!(what.starts_with(start), "{file}: {what}");
        if file.ends_with(".so") {
            assert_eq!(
                what,
                format!("{start}{}", dotted(&highest_glibc(&path))),
                "{file}"
            );
        }
        if file.ends_with(".dylib") {
            // the universal binary: both slices, each with its minimum
            assert!(
                what.contains("x86_64 >= ") && what.contains("arm64 >= "),
                "{what}"
            );
        }
    }
}

#[test]
fn a_binary_that_cannot_be_read_is_labelled_unknown() {
    let (label, warning) = triad::platforms::label(
        Some(triad::platforms::Platform::Win64),
        "win64",
        b"MZ, but nothing more",
    );
    assert_eq!(label, "win64 (unknown)");
    assert!(warning.is_some());
}
