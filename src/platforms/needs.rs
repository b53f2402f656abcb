//! What a runtime binary needs of the system it runs on, read from the binary itself (the
//! `object` crate), for its label in `triad build`'s output and the FMU's
//! `documentation/index.html`:
//!
//! | format | read | label |
//! |---|---|---|
//! | ELF | the highest `GLIBC_x.y` among the version needs (`.gnu.version_r`) | `x86_64 Linux, glibc >= 2.35` |
//! | Mach-O (one slice or universal) | each slice's minimum OS (`LC_BUILD_VERSION` `minos`, else `LC_VERSION_MIN_MACOSX`) | `macOS x86_64 >= 10.12, arm64 >= 11.0` |
//! | PE | the optional header's OS and subsystem versions (the higher; the loader refuses a subsystem version above the system's) | `x86_64 Windows >= 6.0 (Vista)` |
//!
//! A file that is none of these, or whose headers cannot be read, is an `Err` with the reason:
//! the caller labels it `unknown` with a warning.

use object::macho;
use object::read::elf::{ElfFile32, ElfFile64, FileHeader};
use object::read::macho::{
    FatArch as _, LoadCommandVariant, MachOFatFile32, MachOFatFile64, MachOFile32, MachOFile64,
};
use object::read::pe::{ImageNtHeaders, ImageOptionalHeader, PeFile32, PeFile64};
use object::{Architecture, Endianness, FileKind, Object, ReadRef};

/// What the shared library `bytes` needs to run (module docs), or why that cannot be read.
///
/// # Errors
/// Not an ELF, Mach-O or PE file, or headers that do not parse.
pub fn needs(bytes: &[u8]) -> Result<String, String> {
    let kind = FileKind::parse(bytes).map_err(|e| format!("not an object file ({e})"))?;
    match kind {
        FileKind::Elf64 => elf(&ElfFile64::<Endianness>::parse(bytes).map_err(bad)?, bytes),
        FileKind::Elf32 => elf(&ElfFile32::<Endianness>::parse(bytes).map_err(bad)?, bytes),
        FileKind::MachO64 => macos(&[slice(bytes)?]),
        FileKind::MachO32 => macos(&[slice(bytes)?]),
        FileKind::MachOFat32 => {
            let fat = MachOFatFile32::parse(bytes).map_err(bad)?;
            let slices = fat
                .arches()
                .iter()
                .map(|a| a.data(bytes).map_err(bad).and_then(slice))
                .collect::<Result<Vec<_>, _>>()?;
            macos(&slices)
        }
        FileKind::MachOFat64 => {
            let fat = MachOFatFile64::parse(bytes).map_err(bad)?;
            let slices = fat
                .arches()
                .iter()
                .map(|a| a.data(bytes).map_err(bad).and_then(slice))
                .collect::<Result<Vec<_>, _>>()?;
            macos(&slices)
        }
        FileKind::Pe64 => windows(&PeFile64::parse(bytes).map_err(bad)?),
        FileKind::Pe32 => windows(&PeFile32::parse(bytes).map_err(bad)?),
        other => Err(format!(
            "a {other:?} file, not an ELF, Mach-O or PE shared library"
        )),
    }
}

fn bad(e: object::Error) -> String {
    format!("its headers cannot be read ({e})")
}

/// The architecture's usual name.
fn arch(a: Architecture) -> String {
    match a {
        Architecture::X86_64 => "x86_64".into(),
        Architecture::Aarch64 => "aarch64".into(),
        Architecture::I386 => "i386".into(),
        Architecture::Arm => "arm".into(),
        other => format!("{other:?}").to_lowercase(),
    }
}

/// `x86_64 Linux, glibc >= 2.35` from the version needs of an ELF file.
fn elf<'data, Elf: FileHeader<Endian = Endianness>, R: ReadRef<'data>>(
    file: &object::read::elf::ElfFile<'data, Elf, R>,
    data: R,
) -> Result<String, String> {
    let endian = file.endian();
    let sections = file.elf_section_table();
    let mut highest: Option<Vec<u32>> = None;
    if let Some((mut needs, link)) = sections.gnu_verneed(endian, data).map_err(bad)? {
        let strings = sections.strings(endian, data, link).map_err(bad)?;
        while let Some((_, mut aux)) = needs.next().map_err(bad)? {
            while let Some(a) = aux.next().map_err(bad)? {
                let name = a.name(endian, strings).map_err(bad)?;
                if let Some(v) = glibc_version(name) {
                    if highest.as_ref().is_none_or(|h| v > *h) {
                        highest = Some(v);
                    }
                }
            }
        }
    }
    let glibc = highest.map_or_else(
        || "no versioned glibc symbol".to_string(),
        |v| format!("glibc >= {}", dotted(&v)),
    );
    Ok(format!("{} Linux, {glibc}", arch(file.architecture())))
}

/// `[2, 35]` of `GLIBC_2.35`; `None` for other names (`GLIBC_PRIVATE`, `GCC_3.0`).
fn glibc_version(name: &[u8]) -> Option<Vec<u32>> {
    let v = std::str::from_utf8(name.strip_prefix(b"GLIBC_")?).ok()?;
    v.split('.').map(|x| x.parse().ok()).collect()
}

fn dotted(v: &[u32]) -> String {
    v.iter().map(u32::to_string).collect::<Vec<_>>().join(".")
}

/// One Mach-O slice: its architecture and minimum macOS (`None`: it states none).
struct Slice {
    arch: String,
    min: Option<String>,
}

/// The architecture and minimum OS of a thin Mach-O file.
fn slice(bytes: &[u8]) -> Result<Slice, String> {
    match FileKind::parse(bytes).map_err(bad)? {
        FileKind::MachO64 => {
            let f = MachOFile64::<Endianness>::parse(bytes).map_err(bad)?;
            let min = min_os(f.macho_load_commands().map_err(bad)?, f.endian())?;
            Ok(Slice {
                arch: arch(f.architecture()),
                min,
            })
        }
        FileKind::MachO32 => {
            let f = MachOFile32::<Endianness>::parse(bytes).map_err(bad)?;
            let min = min_os(f.macho_load_commands().map_err(bad)?, f.endian())?;
            Ok(Slice {
                arch: arch(f.architecture()),
                min,
            })
        }
        other => Err(format!("a universal binary's slice is a {other:?} file")),
    }
}

/// `LC_BUILD_VERSION`'s `minos` (macOS), else `LC_VERSION_MIN_MACOSX`'s version.
fn min_os(
    mut commands: object::read::macho::LoadCommandIterator<'_, Endianness>,
    endian: Endianness,
) -> Result<Option<String>, String> {
    let version = |v: macho::Version| {
        if v.update() == 0 {
            format!("{}.{}", v.major(), v.minor())
        } else {
            format!("{}.{}.{}", v.major(), v.minor(), v.update())
        }
    };
    let mut min = None;
    while let Some(c) = commands.next().map_err(bad)? {
        match c.variant().map_err(bad)? {
            LoadCommandVariant::BuildVersion(b, _) => {
                let platform = b.platform.get(endian);
                let v = version(b.minos.get(endian));
                return Ok(Some(if platform == macho::PLATFORM_MACOS {
                    v
                } else {
                    format!("{v} (platform {})", platform.0)
                }));
            }
            LoadCommandVariant::VersionMin(m) if c.cmd() == macho::LC_VERSION_MIN_MACOSX => {
                min = Some(version(m.version.get(endian)));
            }
            _ => {}
        }
    }
    Ok(min)
}

/// `macOS x86_64 >= 10.12, arm64 >= 11.0` of the slices.
fn macos(slices: &[Slice]) -> Result<String, String> {
    if slices.is_empty() {
        return Err("a universal binary without slices".into());
    }
    let each: Vec<String> = slices
        .iter()
        .map(|s| {
            let arch = if s.arch == "aarch64" {
                "arm64"
            } else {
                &s.arch
            };
            match &s.min {
                Some(v) => format!("{arch} >= {v}"),
                None => format!("{arch} (no minimum stated)"),
            }
        })
        .collect();
    Ok(format!("macOS {}", each.join(", ")))
}

/// `x86_64 Windows >= 6.0 (Vista)` from a PE file's optional header.
fn windows<'data, Pe: ImageNtHeaders, R: ReadRef<'data>>(
    file: &object::read::pe::PeFile<'data, Pe, R>,
) -> Result<String, String> {
    let h = file.nt_headers().optional_header();
    let os = (
        h.major_operating_system_version(),
        h.minor_operating_system_version(),
    );
    let subsystem = (h.major_subsystem_version(), h.minor_subsystem_version());
    let (major, minor) = os.max(subsystem);
    let name = match (major, minor) {
        (5, 1) => " (XP)",
        (5, 2) => " (XP x64, Server 2003)",
        (6, 0) => " (Vista)",
        (6, 1) => " (7)",
        (6, 2) => " (8)",
        (6, 3) => " (8.1)",
        (10, 0) => " (10)",
        _ => "",
    };
    Ok(format!(
        "{} Windows >= {major}.{minor}{name}",
        arch(file.architecture())
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glibc_names() {
        assert_eq!(glibc_version(b"GLIBC_2.35"), Some(vec![2, 35]));
        assert_eq!(glibc_version(b"GLIBC_2.2.5"), Some(vec![2, 2, 5]));
        assert_eq!(glibc_version(b"GLIBC_PRIVATE"), None);
        assert_eq!(glibc_version(b"GCC_3.0"), None);
        assert!(vec![2, 35] > vec![2, 2, 5] && vec![2, 17] > vec![2, 3, 4]);
    }

    /// A thin 64-bit Mach-O dylib header of CPU `cpu` with one load command `command`.
    fn macho(cpu: u32, command: &[u32]) -> Vec<u8> {
        let words = [
            0xfeed_facf,
            cpu,
            0,
            6, // MH_DYLIB
            1,
            4 * command.len() as u32,
            0,
            0,
        ];
        words
            .iter()
            .chain(command)
            .flat_map(|w| w.to_le_bytes())
            .collect()
    }

    /// A universal binary of `slices` (each at a 4096-aligned offset).
    fn fat(slices: &[(u32, Vec<u8>)]) -> Vec<u8> {
        let mut out: Vec<u8> = [0xcafe_babe_u32, slices.len() as u32]
            .iter()
            .flat_map(|w| w.to_be_bytes())
            .collect();
        let mut offset = 4096;
        let mut body = Vec::new();
        for (cpu, bytes) in slices {
            for w in [*cpu, 0, offset, bytes.len() as u32, 12] {
                out.extend(w.to_be_bytes());
            }
            body.resize(offset as usize - 4096, 0);
            body.extend(bytes);
            offset += 4096 * (1 + bytes.len() as u32 / 4096);
        }
        out.resize(4096, 0);
        out.extend(body);
        out
    }

    /// A PE32+ DLL header (no sections) with OS version `os` and subsystem version `sub`.
    fn pe(os: (u16, u16), sub: (u16, u16)) -> Vec<u8> {
        let mut b = vec![0u8; 0x40 + 4 + 20 + 240];
        b[0..2].copy_from_slice(b"MZ");
        b[0x3c..0x40].copy_from_slice(&0x40u32.to_le_bytes());
        b[0x40..0x44].copy_from_slice(b"PE\0\0");
        let coff = 0x44;
        b[coff..coff + 2].copy_from_slice(&0x8664u16.to_le_bytes());
        b[coff + 16..coff + 18].copy_from_slice(&240u16.to_le_bytes());
        b[coff + 18..coff + 20].copy_from_slice(&0x2022u16.to_le_bytes());
        let opt = coff + 20;
        let put16 = |b: &mut Vec<u8>, at: usize, v: u16| {
            b[opt + at..opt + at + 2].copy_from_slice(&v.to_le_bytes());
        };
        put16(&mut b, 0, 0x20b);
        put16(&mut b, 40, os.0);
        put16(&mut b, 42, os.1);
        put16(&mut b, 48, sub.0);
        put16(&mut b, 50, sub.1);
        b[opt + 32..opt + 36].copy_from_slice(&0x1000u32.to_le_bytes());
        b[opt + 36..opt + 40].copy_from_slice(&0x200u32.to_le_bytes());
        b[opt + 60..opt + 64].copy_from_slice(&0x200u32.to_le_bytes());
        b[opt + 108..opt + 112].copy_from_slice(&16u32.to_le_bytes());
        b
    }

    const X86_64: u32 = 0x0100_0007;
    const ARM64: u32 = 0x0100_000c;

    #[test]
    fn macho_minimum_os_of_each_slice() {
        // LC_BUILD_VERSION (macOS 11.0), LC_VERSION_MIN_MACOSX (10.12)
        let arm = macho(ARM64, &[0x32, 24, 1, 0x000b_0000, 0, 0]);
        let intel = macho(X86_64, &[0x24, 16, 0x000a_0c00, 0]);
        assert_eq!(needs(&arm).unwrap(), "macOS arm64 >= 11.0");
        assert_eq!(needs(&intel).unwrap(), "macOS x86_64 >= 10.12");
        assert_eq!(
            needs(&fat(&[(X86_64, intel), (ARM64, arm)])).unwrap(),
            "macOS x86_64 >= 10.12, arm64 >= 11.0"
        );
        // another platform's build version says so; none at all says so
        let ios = macho(ARM64, &[0x32, 24, 2, 0x000e_0100, 0, 0]);
        assert_eq!(needs(&ios).unwrap(), "macOS arm64 >= 14.1 (platform 2)");
        let bare = macho(X86_64, &[0x2a, 16, 0, 0]);
        assert_eq!(needs(&bare).unwrap(), "macOS x86_64 (no minimum stated)");
    }

    #[test]
    fn pe_windows_version() {
        assert_eq!(
            needs(&pe((6, 0), (6, 0))).unwrap(),
            "x86_64 Windows >= 6.0 (Vista)"
        );
        assert_eq!(
            needs(&pe((4, 0), (10, 0))).unwrap(),
            "x86_64 Windows >= 10.0 (10)"
        );
        assert_eq!(
            needs(&pe((6, 1), (5, 2))).unwrap(),
            "x86_64 Windows >= 6.1 (7)"
        );
    }

    #[test]
    fn unreadable_files_are_errors_not_panics() {
        assert!(needs(b"").is_err());
        assert!(needs(b"not a binary at all").is_err());
        // an ELF header cut short, a Mach-O magic with nothing after it
        assert!(needs(b"\x7fELF\x02\x01\x01\0\0\0\0\0\0\0\0\0\x03\0").is_err());
        assert!(needs(&[0xcf, 0xfa, 0xed, 0xfe, 7, 0, 0, 1]).is_err());
        assert!(needs(b"MZ\x90\0").is_err());
        // every prefix of valid headers, and flipped bytes: a result or an error, never a panic
        let arm = macho(ARM64, &[0x32, 24, 1, 0x000b_0000, 0, 0]);
        for whole in [fat(&[(ARM64, arm.clone())]), arm, pe((6, 0), (6, 0))] {
            for n in 0..whole.len() {
                let _ = needs(&whole[..n]);
                let mut flipped = whole.clone();
                flipped[n] ^= 0xff;
                let _ = needs(&flipped);
            }
        }
    }
}
