//! The built cdylib exports every one of the 34 FMI 2.0 Co-Simulation functions under its exact
//! name (fmi.md pitfall 1), checked by loading `target/<profile>/libtriad.so` (or
//! `$TRIAD_CDYLIB`, the glibc 2.17 runtime in CI) with the system loader exactly as an importer
//! would; and it depends on nothing beyond the C runtime (pitfall 10): libc, libm, libgcc_s,
//! the loader, and libpthread and libdl, which a library linked for glibc < 2.34 names. With
//! `TRIAD_GLIBC_FLOOR=2.17` no symbol it imports may need a later glibc.

mod fmu_support;

use triad::ffi::types::FMI2_CS_FUNCTIONS;

#[test]
fn all_34_symbols_resolve() {
    let path = fmu_support::cdylib();
    // SAFETY (test): loading our own library runs no foreign initialisers.
    let lib = unsafe { libloading::Library::new(&path) }
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut missing = Vec::new();
    for name in FMI2_CS_FUNCTIONS {
        // SAFETY (test): only the address is looked up, the function is not called.
        if unsafe { lib.get::<*const ()>(name.as_bytes()) }.is_err() {
            missing.push(name);
        }
    }
    assert!(missing.is_empty(), "missing exports: {missing:?}");
    assert_eq!(FMI2_CS_FUNCTIONS.len(), 34);
    let mut sorted = FMI2_CS_FUNCTIONS.to_vec();
    sorted.sort_unstable();
    sorted.dedup();
    assert_eq!(sorted.len(), 34);
}

#[cfg(target_os = "linux")]
#[test]
fn the_shared_object_needs_only_the_c_runtime() {
    let path = fmu_support::cdylib();
    let out = std::process::Command::new("ldd")
        .arg(&path)
        .output()
        .expect("ldd runs");
    let text = String::from_utf8_lossy(&out.stdout);
    let allowed = [
        "linux-vdso",
        "libc.so",
        "libm.so",
        "libgcc_s.so",
        "libpthread.so",
        "libdl.so",
        "ld-linux",
    ];
    let bad: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !allowed.iter().any(|a| l.contains(a)))
        .collect();
    assert!(
        bad.is_empty(),
        "unexpected dependencies of {}:\n{}",
        path.display(),
        bad.join("\n")
    );
}

#[cfg(target_os = "linux")]
#[test]
fn exactly_the_fmi2_and_fmi3_functions_are_exported() {
    // nothing else is visible, so two FMUs in one process cannot clash on symbols: the 34
    // fmi2* functions and the 75 fmi3* ones
    let path = fmu_support::cdylib();
    let out = std::process::Command::new("nm")
        .args(["-D", "--defined-only"])
        .arg(&path)
        .output()
        .expect("nm runs");
    let text = String::from_utf8_lossy(&out.stdout);
    let mut names: Vec<&str> = text
        .lines()
        .filter_map(|l| l.split_whitespace().nth(2))
        .collect();
    names.sort_unstable();
    let mut want = FMI2_CS_FUNCTIONS.to_vec();
    want.extend(triad::ffi::fmi3::types::FMI3_FUNCTIONS);
    want.sort_unstable();
    assert_eq!(names, want);
}

/// The highest `GLIBC_x.y` version among the symbols `objdump -T` lists for `path`.
#[cfg(target_os = "linux")]
fn highest_glibc(path: &std::path::Path) -> (u32, u32) {
    let out = std::process::Command::new("objdump")
        .arg("-T")
        .arg(path)
        .output()
        .expect("objdump runs");
    let text = String::from_utf8_lossy(&out.stdout);
    text.split("GLIBC_")
        .skip(1)
        .filter_map(|rest| {
            let v: String = rest
                .chars()
                .take_while(|c| c.is_ascii_digit() || *c == '.')
                .collect();
            let mut it = v.split('.').map(|x| x.parse::<u32>().ok());
            Some((it.next()??, it.next().flatten().unwrap_or(0)))
        })
        .max()
        .expect("the library imports versioned glibc symbols")
}

#[cfg(target_os = "linux")]
#[test]
fn no_glibc_symbol_above_the_floor() {
    // `TRIAD_GLIBC_FLOOR=2.17` (CI, with TRIAD_CDYLIB the runtime of scripts/platforms.sh)
    let path = fmu_support::cdylib();
    let highest = highest_glibc(&path);
    match std::env::var("TRIAD_GLIBC_FLOOR") {
        Ok(floor) => {
            let mut it = floor
                .split('.')
                .map(|x| x.parse::<u32>().expect("TRIAD_GLIBC_FLOOR"));
            let floor = (it.next().unwrap(), it.next().unwrap_or(0));
            assert!(
                highest <= floor,
                "{} needs GLIBC_{}.{}: above the floor {}.{}",
                path.display(),
                highest.0,
                highest.1,
                floor.0,
                floor.1
            );
        }
        Err(_) => eprintln!(
            "{}: highest GLIBC_{}.{} (set TRIAD_GLIBC_FLOOR to check a floor)",
            path.display(),
            highest.0,
            highest.1
        ),
    }
}
