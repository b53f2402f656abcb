//! The platforms an FMU can carry, and where `triad build` finds their runtime binaries.
//!
//! The FMU's binary does not depend on the model, so one runtime per platform, built once
//! (`scripts/platforms.sh`), serves every model. The runtime directory holds
//! `<platform>/<file>`:
//!
//! | platform | file | FMU folder |
//! |---|---|---|
//! | `linux64` | `linux64/libtriad.so` (x86_64; glibc ≥ 2.17 from `scripts/platforms.sh`) | `binaries/linux64` |
//! | `win64` | `win64/triad.dll` | `binaries/win64` |
//! | `darwin64` | `darwin64/libtriad.dylib` (x86_64 + arm64) | `binaries/darwin64` |
//! | `aarch64-linux` | `aarch64-linux/libtriad.so` (glibc ≥ 2.17 from `scripts/platforms.sh`) | `binaries/aarch64-linux` (the FMI 3 name) |
//! | `linux64-aarch64` | the same aarch64 file | `binaries/linux64`, for FMI 2 importers on ARM boards |
//!
//! Each binary is labelled by what it needs, read from the binary itself (`needs`: the highest
//! glibc version an ELF file's symbols need, a Mach-O slice's minimum macOS, a PE file's
//! Windows version): a host build needs the host's glibc, not 2.17.
//!
//! The directory is `$TRIAD_RUNTIME_DIR`, else `runtime/` beside the `triad` executable, else
//! `../runtime/` (so `target/release/triad` finds `target/runtime/`). The host's binary is
//! always packed: `$TRIAD_CDYLIB` if set, else the runtime directory's, else the library of
//! this build ([`find_cdylib`]).
//!
//! Every runtime binary carries the runtime id of the sources it was built from
//! ([`crate::fmu::runtime_id::RUNTIME_TAG`]). A binary of the runtime directory with another id (built
//! before the sources changed) is not packed: the host's is replaced by this build's library
//! when that one matches; another platform is left out with a warning, or, asked for by name
//! or `all`, is an error naming the command that rebuilds it.

use std::path::{Path, PathBuf};

mod needs;

pub use needs::needs;

/// FMI platform folder of this build (`linux64`, `win64`, `darwin64`, …).
pub const PLATFORM: &str = env!("TRIAD_FMI_PLATFORM");

/// File name of the crate's cdylib and the shared-library extension of this platform.
#[must_use]
pub fn cdylib_names() -> (&'static str, &'static str) {
    if cfg!(windows) {
        ("triad.dll", "dll")
    } else if cfg!(target_os = "macos") {
        ("libtriad.dylib", "dylib")
    } else {
        ("libtriad.so", "so")
    }
}

/// Finds the compiled cdylib: `$TRIAD_CDYLIB`, else the newest of those next to the running
/// executable, in its parent directory and in their `deps/` directories (covers `target/<profile>/triad`, test binaries
/// in `target/<profile>/deps/` and examples).
///
/// # Errors
/// A message listing the places searched.
pub fn find_cdylib() -> Result<PathBuf, String> {
    if let Some(p) = std::env::var_os("TRIAD_CDYLIB") {
        let p = PathBuf::from(p);
        return if p.is_file() {
            Ok(p)
        } else {
            Err(format!("TRIAD_CDYLIB={} is not a file", p.display()))
        };
    }
    let exe = std::env::current_exe()
        .map_err(|e| format!("cannot locate the running executable: {e}"))?;
    let dir = exe.parent().ok_or("executable has no directory")?;
    let (file, _) = cdylib_names();
    let mut tried = Vec::new();
    let mut found: Option<(std::time::SystemTime, PathBuf)> = None;
    let up = dir.parent().map(Path::to_path_buf);
    let candidates = [
        Some(dir.to_path_buf()),
        Some(dir.join("deps")),
        up.clone(),
        up.map(|u| u.join("deps")),
    ];
    for d in candidates.into_iter().flatten() {
        let p = d.join(file);
        // the newest candidate wins: cargo only copies the library up on `cargo build --lib`
        if let Ok(modified) = p.metadata().and_then(|m| m.modified()) {
            if found.as_ref().is_none_or(|(t, _)| modified > *t) {
                found = Some((modified, p.clone()));
            }
        }
        tried.push(p.display().to_string());
    }
    if let Some((_, p)) = found {
        return Ok(p);
    }
    Err(format!(
        "{file} not found (looked at {}); build it with `cargo build --lib` or set TRIAD_CDYLIB",
        tried.join(", ")
    ))
}

/// A platform of the runtime directory (and of `triad build --platforms`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Platform {
    /// x86_64 Linux (glibc ≥ 2.17 when built by `scripts/platforms.sh`).
    Linux64,
    /// x86_64 Windows.
    Win64,
    /// macOS, one universal x86_64 + arm64 file.
    Darwin64,
    /// aarch64 Linux (glibc ≥ 2.17 when built by `scripts/platforms.sh`), in the FMI 3 folder
    /// `aarch64-linux`.
    Aarch64Linux,
    /// The aarch64 Linux binary in `linux64`: what FMI 2 importers on ARM boards load.
    Linux64Aarch64,
}

impl Platform {
    /// What `--platforms all` packs.
    pub const ALL: [Self; 4] = [
        Self::Linux64,
        Self::Win64,
        Self::Darwin64,
        Self::Aarch64Linux,
    ];
    /// Every name `--platforms` accepts.
    pub const NAMES: [Self; 5] = [
        Self::Linux64,
        Self::Win64,
        Self::Darwin64,
        Self::Aarch64Linux,
        Self::Linux64Aarch64,
    ];

    /// The name on the command line.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Linux64 => "linux64",
            Self::Win64 => "win64",
            Self::Darwin64 => "darwin64",
            Self::Aarch64Linux => "aarch64-linux",
            Self::Linux64Aarch64 => "linux64-aarch64",
        }
    }

    /// The folder under `binaries/` in the FMU.
    #[must_use]
    pub fn folder(self) -> &'static str {
        match self {
            Self::Linux64 | Self::Linux64Aarch64 => "linux64",
            Self::Aarch64Linux => "aarch64-linux",
            other => other.name(),
        }
    }

    /// The folder in the runtime directory (and the `--only` name of `scripts/platforms.sh`).
    #[must_use]
    pub fn runtime(self) -> &'static str {
        match self {
            Self::Linux64Aarch64 => "aarch64-linux",
            other => other.name(),
        }
    }

    /// File name in the runtime directory and the extension of the FMU's library.
    #[must_use]
    pub fn file(self) -> (&'static str, &'static str) {
        match self {
            Self::Win64 => ("triad.dll", "dll"),
            Self::Darwin64 => ("libtriad.dylib", "dylib"),
            _ => ("libtriad.so", "so"),
        }
    }

    /// The FMI 3 platform tuples (`binaries/<tuple>/`) its binary goes into: the universal
    /// macOS file serves both `x86_64-darwin` and `aarch64-darwin` (the loader picks its slice);
    /// `linux64-aarch64` is `aarch64-linux` in FMI 3 (no FMI 2 folder to stand in for).
    #[must_use]
    pub fn fmi3_folders(self) -> &'static [&'static str] {
        match self {
            Self::Linux64 => &["x86_64-linux"],
            Self::Win64 => &["x86_64-windows"],
            Self::Darwin64 => &["aarch64-darwin", "x86_64-darwin"],
            Self::Aarch64Linux | Self::Linux64Aarch64 => &["aarch64-linux"],
        }
    }

    /// The system the platform's binary is built for (what it needs beyond that is read from
    /// the binary: [`needs`]).
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Self::Linux64 => "x86_64 Linux",
            Self::Win64 => "x86_64 Windows",
            Self::Darwin64 => "macOS x86_64 + arm64",
            Self::Aarch64Linux | Self::Linux64Aarch64 => "aarch64 Linux",
        }
    }

    /// What the label adds about the folder: `""`, or why this folder.
    #[must_use]
    pub fn note(self) -> &'static str {
        match self {
            Self::Aarch64Linux => " (FMI 3 folder name)",
            Self::Linux64Aarch64 => ", for FMI 2 importers on ARM",
            _ => "",
        }
    }

    /// The platform named `name`.
    #[must_use]
    pub fn parse(name: &str) -> Option<Self> {
        Self::NAMES.into_iter().find(|p| p.name() == name)
    }

    /// The platform of this build's own library (`None` on a system without runtimes).
    #[must_use]
    pub fn host() -> Option<Self> {
        match (std::env::consts::OS, std::env::consts::ARCH) {
            ("linux", "x86_64") => Some(Self::Linux64),
            ("linux", "aarch64") => Some(Self::Linux64Aarch64),
            ("windows", "x86_64") => Some(Self::Win64),
            ("macos", _) => Some(Self::Darwin64),
            _ => None,
        }
    }
}

/// What `--platforms` asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Selection {
    /// No `--platforms`: the host's and every platform found in the runtime directory.
    Found,
    /// `all`: every platform of [`Platform::ALL`]; one missing is an error.
    All,
    /// `host`: the host's binary only.
    Host,
    /// A list: these and the host's; one missing is an error.
    List(Vec<Platform>),
}

impl Selection {
    /// Parses `all`, `host` or a comma-separated list of platform names.
    ///
    /// # Errors
    /// An unknown name (the message lists the known ones), an empty list.
    pub fn parse(text: &str) -> Result<Self, String> {
        match text.trim() {
            "all" => return Ok(Self::All),
            "host" => return Ok(Self::Host),
            _ => {}
        }
        let mut list = Vec::new();
        for name in text.split(',').map(str::trim) {
            let p = Platform::parse(name).ok_or_else(|| {
                let known: Vec<&str> = Platform::NAMES.iter().map(|p| p.name()).collect();
                format!(
                    "unknown platform '{name}' in --platforms (all, host, or a list of: {})",
                    known.join(", ")
                )
            })?;
            if !list.contains(&p) {
                list.push(p);
            }
        }
        Ok(Self::List(list))
    }
}

/// The FMI 3 platform tuple of this build (`<arch>-<os>`, FMI 3.0 §2.5.1.4), for a host of no
/// [`Platform`].
#[must_use]
pub fn host_fmi3_folder() -> String {
    let os = match std::env::consts::OS {
        "macos" => "darwin",
        other => other,
    };
    format!("{}-{os}", std::env::consts::ARCH)
}

/// The FMI 3 folders of a binary of `platform` (the host's when `None`).
#[must_use]
pub fn fmi3_folders(platform: Option<Platform>) -> Vec<String> {
    platform.map_or_else(
        || vec![host_fmi3_folder()],
        |p| p.fmi3_folders().iter().map(|f| (*f).to_string()).collect(),
    )
}

/// One binary to pack.
#[derive(Clone, Debug)]
pub struct Binary {
    /// Its platform (`None`: this build's, on a system of no [`Platform`]).
    pub platform: Option<Platform>,
    /// Folder under `binaries/`.
    pub folder: String,
    /// Library extension (`so`, `dll`, `dylib`).
    pub ext: &'static str,
    /// The `--platforms` name, with what it runs on (read from the binary: [`label`]).
    pub label: String,
    /// Why what the binary needs could not be read (a warning; the label says `unknown`).
    pub unreadable: Option<String>,
    /// Where it was read from.
    pub source: PathBuf,
    /// Its bytes.
    pub bytes: Vec<u8>,
}

/// The runtime directory: `$TRIAD_RUNTIME_DIR`, else `runtime/` beside the running executable,
/// else `../runtime/` from it; `None` when none is a directory.
#[must_use]
pub fn runtime_dir() -> Option<PathBuf> {
    if let Some(d) = std::env::var_os("TRIAD_RUNTIME_DIR") {
        return Some(PathBuf::from(d));
    }
    let exe = std::env::current_exe().ok()?;
    let dir = exe.parent()?;
    [
        Some(dir.join("runtime")),
        dir.parent().map(|p| p.join("runtime")),
    ]
    .into_iter()
    .flatten()
    .find(|d| d.is_dir())
}

/// How `triad build` and the documentation name a binary: the platform and what the binary
/// needs, read from `bytes` ([`needs`]: `linux64 (x86_64 Linux, glibc >= 2.35)`); and a
/// warning when that cannot be read (the label then says `unknown`).
#[must_use]
pub fn label(platform: Option<Platform>, folder: &str, bytes: &[u8]) -> (String, Option<String>) {
    let name = platform.map_or_else(|| format!("{folder}, this build"), |p| p.name().to_string());
    let note = platform.map_or("", Platform::note);
    match needs(bytes) {
        Ok(what) => (format!("{name} ({what}{note})"), None),
        Err(why) => (format!("{name} (unknown{note})"), Some(why)),
    }
}

/// The runtime id in a runtime binary's bytes (the 16 hex digits after `triad-runtime-id:`),
/// `None` when it carries none (built before runtime ids, or not a triad runtime).
#[must_use]
pub fn runtime_id(bytes: &[u8]) -> Option<&str> {
    use crate::fmu::runtime_id::{RUNTIME_ID, RUNTIME_TAG};
    // `triad-runtime-id:`, the tag without the id
    let key = &RUNTIME_TAG.as_bytes()[..RUNTIME_TAG.len() - RUNTIME_ID.len()];
    let at = bytes.windows(key.len()).position(|w| w == key)? + key.len();
    let id = bytes.get(at..at + RUNTIME_ID.len())?;
    id.iter()
        .all(u8::is_ascii_hexdigit)
        .then(|| std::str::from_utf8(id).ok())
        .flatten()
}

/// Why `path` (its bytes `bytes`) is not this triad's runtime, or `None` when it is.
fn stale(path: &Path, bytes: &[u8]) -> Option<String> {
    let own = crate::fmu::runtime_id::RUNTIME_ID;
    match runtime_id(bytes) {
        Some(id) if id == own => None,
        Some(id) => Some(format!(
            "{} was built from other sources than this triad (runtime id {id}, this triad's {own})",
            path.display()
        )),
        None => Some(format!(
            "{} carries no runtime id (built by an older triad; this triad's is {own})",
            path.display()
        )),
    }
}

fn read(
    platform: Option<Platform>,
    folder: &str,
    ext: &'static str,
    path: &Path,
) -> Result<Binary, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let (label, unreadable) = label(platform, folder, &bytes);
    Ok(Binary {
        platform,
        folder: folder.to_string(),
        ext,
        label,
        unreadable: unreadable.map(|why| {
            format!(
                "warning: what {} needs to run cannot be read: {why}; labelled unknown",
                path.display()
            )
        }),
        source: path.to_path_buf(),
        bytes,
    })
}

fn missing(p: Platform, dir: Option<&Path>) -> String {
    let (file, _) = p.file();
    let place = dir.map_or_else(
        || "no runtime directory was found ($TRIAD_RUNTIME_DIR, runtime/ or ../runtime/ beside triad)".to_string(),
        |d| format!("{} is missing", d.join(p.runtime()).join(file).display()),
    );
    format!(
        "platform {} asked for but not found: {place}; build it with `bash scripts/platforms.sh --only {}` (or set TRIAD_RUNTIME_DIR)",
        p.name(),
        p.runtime()
    )
}

/// The binaries `selection` asks for, read from the runtime directory `dir`, the host's
/// always among them, sorted by folder; and notes (a platform left out because its folder is
/// taken).
///
/// # Errors
/// A platform asked for (`all` or a list) but not found, two platforms asked for that share a
/// folder, a host library that cannot be found or read.
pub fn collect(
    selection: &Selection,
    dir: Option<&Path>,
) -> Result<(Vec<Binary>, Vec<String>), String> {
    let mut notes = Vec::new();
    let asked: Vec<Platform> = match selection {
        Selection::Found => Platform::ALL
            .into_iter()
            .filter(|p| dir.is_some_and(|d| d.join(p.runtime()).join(p.file().0).is_file()))
            .collect(),
        Selection::All => Platform::ALL.to_vec(),
        Selection::Host => Vec::new(),
        Selection::List(list) => list.clone(),
    };
    let explicit = matches!(selection, Selection::List(_));
    for (i, a) in asked.iter().enumerate() {
        if let Some(b) = asked[i + 1..].iter().find(|b| b.folder() == a.folder()) {
            return Err(format!(
                "--platforms: {} and {} both go into binaries/{}; ask for one of them",
                a.name(),
                b.name(),
                a.folder()
            ));
        }
    }
    let host = Platform::host();
    let mut out: Vec<Binary> = Vec::new();
    // the host's binary: explicit TRIAD_CDYLIB, the runtime directory's, this build's
    let host_folder = host.map_or(PLATFORM, Platform::folder);
    let replaced = explicit
        && asked
            .iter()
            .any(|p| p.folder() == host_folder && Some(*p) != host);
    if replaced {
        notes.push(format!(
            "the host's binary is not packed: binaries/{host_folder} holds the platform asked for"
        ));
    } else {
        let in_dir = host
            .zip(dir)
            .map(|(h, d)| d.join(h.runtime()).join(h.file().0))
            .filter(|p| p.is_file());
        let ext = host.map_or(cdylib_names().1, |h| h.file().1);
        let mut binary = match (std::env::var_os("TRIAD_CDYLIB"), in_dir) {
            (None, Some(p)) => read(host, host_folder, ext, &p)?,
            _ => read(host, host_folder, ext, &find_cdylib()?)?,
        };
        if let Some(why) = stale(&binary.source, &binary.bytes) {
            // the runtime directory's is out of date: this build's library, if it is current
            let own = find_cdylib()
                .ok()
                .filter(|p| *p != binary.source)
                .and_then(|p| read(host, host_folder, ext, &p).ok())
                .filter(|b| stale(&b.source, &b.bytes).is_none());
            if let Some(own) = own {
                notes.push(format!(
                    "{why}: packed this build's library {} instead; `bash scripts/platforms.sh` rebuilds the runtimes",
                    own.source.display()
                ));
                binary = own;
            } else {
                notes.push(format!(
                    "warning: {why}; the FMU may not run (`bash scripts/platforms.sh` or `cargo build --release` rebuilds it)"
                ));
            }
        }
        out.push(binary);
    }
    for p in asked {
        if Some(p) == host && !replaced {
            continue;
        }
        if p.folder() == host_folder && !explicit {
            notes.push(format!(
                "{} is not packed: binaries/{} holds the host's binary",
                p.name(),
                p.folder()
            ));
            continue;
        }
        let path = dir
            .map(|d| d.join(p.runtime()).join(p.file().0))
            .filter(|f| f.is_file())
            .ok_or_else(|| missing(p, dir))?;
        let binary = read(Some(p), p.folder(), p.file().1, &path)?;
        if let Some(why) = stale(&binary.source, &binary.bytes) {
            let fix = format!(
                "rebuild it with `bash scripts/platforms.sh --only {}`",
                p.runtime()
            );
            if matches!(selection, Selection::Found) {
                notes.push(format!("warning: {} is not packed: {why}; {fix}", p.name()));
                continue;
            }
            return Err(format!("platform {}: {why}; {fix}", p.name()));
        }
        out.push(binary);
    }
    out.sort_by(|a, b| a.folder.cmp(&b.folder));
    notes.extend(out.iter().filter_map(|b| b.unreadable.clone()));
    Ok((out, notes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_and_lists() {
        for p in Platform::NAMES {
            assert_eq!(Platform::parse(p.name()), Some(p));
        }
        assert_eq!(Selection::parse("all"), Ok(Selection::All));
        assert_eq!(Selection::parse("host"), Ok(Selection::Host));
        assert_eq!(
            Selection::parse("win64, darwin64,win64"),
            Ok(Selection::List(vec![Platform::Win64, Platform::Darwin64]))
        );
        let e = Selection::parse("win64,win32").unwrap_err();
        assert!(
            e.contains("'win32'") && e.contains("linux64-aarch64"),
            "{e}"
        );
        assert!(Selection::parse("").is_err());
        assert_eq!(Platform::Linux64Aarch64.folder(), "linux64");
        assert_eq!(Platform::Linux64Aarch64.runtime(), "aarch64-linux");
    }

    #[test]
    fn found_asked_and_missing() {
        let dir = tempfile_dir();
        let tagged =
            |head: &str| format!("{head}..{}..", crate::fmu::runtime_id::RUNTIME_TAG).into_bytes();
        std::fs::create_dir_all(dir.join("win64")).unwrap();
        std::fs::write(dir.join("win64/triad.dll"), tagged("MZ")).unwrap();
        std::fs::create_dir_all(dir.join("aarch64-linux")).unwrap();
        std::fs::write(dir.join("aarch64-linux/libtriad.so"), tagged("ELF")).unwrap();
        let host = Platform::host().unwrap();
        // found: the host and what the directory holds
        let (found, _) = collect(&Selection::Found, Some(&dir)).unwrap();
        let folders: Vec<&str> = found.iter().map(|b| b.folder.as_str()).collect();
        assert!(folders.contains(&host.folder()), "{folders:?}");
        assert!(folders.contains(&"win64") && folders.contains(&"aarch64-linux"));
        assert!(!folders.contains(&"darwin64") || host == Platform::Darwin64);
        // a platform asked for and missing names the command that builds it
        let e = collect(&Selection::List(vec![Platform::Darwin64]), Some(&dir));
        if host != Platform::Darwin64 {
            let e = e.unwrap_err();
            assert!(
                e.contains("bash scripts/platforms.sh --only darwin64"),
                "{e}"
            );
            let e = collect(&Selection::All, Some(&dir)).unwrap_err();
            assert!(e.contains("--only"), "{e}");
            let e = collect(&Selection::All, None).unwrap_err();
            assert!(e.contains("no runtime directory"), "{e}");
        }
        // two platforms for one folder
        let e = collect(
            &Selection::List(vec![Platform::Linux64, Platform::Linux64Aarch64]),
            Some(&dir),
        )
        .unwrap_err();
        assert!(e.contains("both go into binaries/linux64"), "{e}");
        // the ARM-Linux FMU for FMI 2 importers: the aarch64 file in linux64
        if host == Platform::Linux64 {
            let (arm, notes) =
                collect(&Selection::List(vec![Platform::Linux64Aarch64]), Some(&dir)).unwrap();
            assert_eq!(arm.len(), 1);
            assert_eq!(arm[0].folder, "linux64");
            assert_eq!(arm[0].bytes, tagged("ELF"));
            assert!(notes[0].contains("host's binary is not packed"));
        }
        // host only
        let (h, _) = collect(&Selection::Host, Some(&dir)).unwrap();
        assert_eq!(h.len(), 1);
        assert_eq!(h[0].folder, host.folder());
        // a runtime built from other sources: left out with a warning, or an error when asked for
        if host != Platform::Win64 {
            let other = b"MZ..triad-runtime-id:0123456789abcdef..";
            std::fs::write(dir.join("win64/triad.dll"), other).unwrap();
            let (found, notes) = collect(&Selection::Found, Some(&dir)).unwrap();
            assert!(found.iter().all(|b| b.folder != "win64"));
            let note = notes.iter().find(|n| n.contains("win64")).unwrap();
            assert!(
                note.starts_with("warning: win64 is not packed")
                    && note.contains("runtime id 0123456789abcdef")
                    && note.contains("--only win64"),
                "{note}"
            );
            let e = collect(&Selection::List(vec![Platform::Win64]), Some(&dir)).unwrap_err();
            assert!(
                e.contains("other sources") && e.contains("--only win64"),
                "{e}"
            );
            std::fs::write(dir.join("win64/triad.dll"), b"MZ").unwrap();
            let e = collect(&Selection::All, Some(&dir)).unwrap_err();
            assert!(e.contains("no runtime id") || e.contains("missing"), "{e}");
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn runtime_ids_are_read_from_the_bytes() {
        assert_eq!(
            runtime_id(b"\0\0triad-runtime-id:00ff00ff00ff00ff\0"),
            Some("00ff00ff00ff00ff")
        );
        assert_eq!(runtime_id(b"triad-runtime-id:00ff"), None);
        assert_eq!(runtime_id(b"triad-runtime-id:zzzzzzzzzzzzzzzz"), None);
        assert_eq!(runtime_id(b"no id"), None);
        assert_eq!(
            runtime_id(crate::fmu::runtime_id::RUNTIME_TAG.as_bytes()),
            Some(crate::fmu::runtime_id::RUNTIME_ID)
        );
    }

    fn tempfile_dir() -> PathBuf {
        let d = std::env::temp_dir().join(format!("triad-platforms-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }
}
