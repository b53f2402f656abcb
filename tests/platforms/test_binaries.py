"""Structure of every runtime binary in the runtime directory (TRIAD_RUNTIME_DIR, default
target/runtime), checked without running it:

- linux64 and aarch64-linux: exactly the 34 fmi2* and the 75 fmi3* functions exported, NEEDED only libc, libm,
  libpthread, libdl and the loader, no GLIBC symbol version above 2.17, the right machine;
- win64: a PE32+ x86-64 DLL exporting exactly those 109 functions, importing only Windows system
  DLLs (no libgcc_s, libwinpthread or libstdc++);
- darwin64: one universal file with an x86_64 and an arm64 slice, each exporting exactly the 109
  functions (the C names with Mach-O's leading underscore), loading only libSystem, minimum
  macOS 10.12 (x86_64) and 11.0 (arm64), install name @rpath/libtriad.dylib, and on arm64 (which
  refuses unsigned code; zig's linker signs it) an ad-hoc signature whose every page hash is
  recomputed here (macho.py). Besides the FMI functions zig's linker exports four symbols it
  cannot be told to hide (DARWIN_EXTRA).

Run by .ci/run with the platform tools' python: `python -m pytest tests/platforms`.
"""

import os
import pathlib
import re
import subprocess
import sys

import pytest

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import macho  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
RUNTIME = pathlib.Path(os.environ.get("TRIAD_RUNTIME_DIR", ROOT / "target" / "runtime"))
FMI2_LIST = sorted(
    re.findall(r'"(fmi2\w+)"', (ROOT / "src" / "ffi" / "types.rs").read_text())
)
FMI3_LIST = sorted(
    re.findall(r'"(fmi3\w+)"', (ROOT / "src" / "ffi" / "fmi3" / "types.rs").read_text())
)
# every exported function: FMI 2's and FMI 3's, from one binary
FMI2 = sorted(FMI2_LIST + FMI3_LIST)
SYSTEM_DLLS = {
    "kernel32.dll", "ntdll.dll", "msvcrt.dll", "bcryptprimitives.dll", "advapi32.dll",
    "ws2_32.dll", "userenv.dll", "bcrypt.dll", "api-ms-win-core-synch-l1-2-0.dll",
}


# What zig's Mach-O linker exports besides the fmi2* functions (it ignores export lists; fat LTO
# hides every other Rust symbol): the image header and DSO handle every dylib has, and one
# constant of Rust's standard library.
DARWIN_EXTRA = re.compile(
    r"^(__mh_dylib_header|___dso_handle|_rust_eh_personality"
    r"|__RNvNtCs\w+_3std9panicking11EMPTY_PANIC)$"
)


def test_the_lists_are_the_34_and_75_functions():
    assert len(FMI2_LIST) == 34 and len(set(FMI2_LIST)) == 34, FMI2_LIST
    assert len(FMI3_LIST) == 75 and len(set(FMI3_LIST)) == 75, FMI3_LIST


def required(platform, file):
    path = RUNTIME / platform / file
    if not path.is_file():
        pytest.fail(f"{path} missing: bash scripts/platforms.sh --only {platform}")
    return path


def tool(name):
    return subprocess.run(name, capture_output=True, text=True, check=True).stdout


@pytest.mark.parametrize(
    "platform,objdump,machine",
    [("linux64", "objdump", "x86-64"), ("aarch64-linux", "aarch64-linux-gnu-objdump", "aarch64")],
)
def test_elf(platform, objdump, machine):
    so = required(platform, "libtriad.so")
    head = tool([objdump, "-f", str(so)])
    assert f"architecture: {machine}" in head.replace("i386:x86-64", "x86-64"), head
    dyn = tool([objdump, "-T", str(so)])
    exported = sorted(
        l.split()[-1] for l in dyn.splitlines()
        if " g " in l and ".text" in l
    )
    assert exported == FMI2, exported
    versions = {tuple(int(x) for x in v.split(".")) for v in re.findall(r"GLIBC_([0-9.]+)", dyn)}
    assert versions and max(versions) <= (2, 17), f"GLIBC versions above 2.17: {sorted(versions)}"
    needed = re.findall(r"NEEDED\s+(\S+)", tool([objdump, "-p", str(so)]))
    allowed = ("libc.so", "libm.so", "libpthread.so", "libdl.so", "ld-linux")
    bad = [n for n in needed if not n.startswith(allowed)]
    assert not bad, f"unexpected NEEDED: {bad}"


def test_win64_pe():
    dll = required("win64", "triad.dll")
    p = tool(["x86_64-w64-mingw32-objdump", "-p", str(dll)])
    assert "pei-x86-64" in tool(["x86_64-w64-mingw32-objdump", "-f", str(dll)])
    table = p.split("[Ordinal/Name Pointer] Table", 1)[1].split("\n\n", 1)[0]
    exported = sorted(re.findall(r"\]\s+(\S+)", table))
    assert exported == FMI2, exported
    imports = {n.lower() for n in re.findall(r"DLL Name: (\S+)", p)}
    assert imports, "no imports read"
    bad = imports - SYSTEM_DLLS
    assert not bad, f"imports beyond the Windows system DLLs: {sorted(bad)}"


def test_darwin64_universal():
    info = macho.read(required("darwin64", "libtriad.dylib"))
    assert info["fat"], "not a universal file"
    cpus = sorted(s["cpu"] for s in info["slices"])
    assert cpus == ["arm64", "x86_64"], cpus
    for s in info["slices"]:
        fmi = [e for e in s["exports"] if not DARWIN_EXTRA.match(e)]
        assert fmi == ["_" + f for f in FMI2], (s["cpu"], s["exports"][:40])
        assert len(s["exports"]) - len(fmi) <= 4, s["exports"]
        assert s["dylibs"] == ["/usr/lib/libSystem.B.dylib"], s["dylibs"]
        assert s["install_name"] == "@rpath/libtriad.dylib", s["install_name"]
        want = "11.0" if s["cpu"] == "arm64" else "10.12"
        assert s["minos"] == want, (s["cpu"], s["minos"])
        sig = s["signature"]
        if s["cpu"] == "x86_64" and sig is None:
            continue  # Intel macOS loads unsigned code; zig's linker signs arm64 only
        assert sig is not None, f"{s['cpu']}: no code signature (arm64 macOS refuses unsigned code)"
        assert sig["ok"], (s["cpu"], sig)
        assert sig["adhoc"], (s["cpu"], sig)


def test_the_signature_check_can_fail(tmp_path):
    """A byte changed in the code of the arm64 slice breaks its page hash."""
    src = required("darwin64", "libtriad.dylib").read_bytes()
    thin = [b for cpu, _sub, b in macho.slices(src) if cpu == 0x0100000C][0]
    bad = bytearray(thin)
    bad[0x4000 + 17] ^= 0xFF
    p = tmp_path / "bad.dylib"
    p.write_bytes(bytes(bad))
    sig = macho.read(p)["slices"][0]["signature"]
    assert not sig["ok"] and "page hashes differ" in sig["why"], sig


RUNTIME_ID = re.compile(rb"triad-runtime-id:([0-9a-f]{16})")


def test_every_runtime_carries_the_runtime_id_of_these_sources():
    """`triad build` packs only runtimes built from its own sources (src/platforms.rs): each
    binary carries `triad-runtime-id:` and 16 hex digits, the same in all of them and in the host
    build of the same tree (darwin64: in both slices)."""
    ids = {}
    for platform, file in [("linux64", "libtriad.so"), ("win64", "triad.dll"),
                           ("darwin64", "libtriad.dylib"), ("aarch64-linux", "libtriad.so")]:
        found = RUNTIME_ID.findall(required(platform, file).read_bytes())
        assert len(set(found)) == 1, f"{platform}: runtime ids {found}"
        assert platform != "darwin64" or len(found) >= 2, f"darwin64: {len(found)} slice(s) with an id"
        ids[platform] = found[0]
    host = ROOT / "target" / "release" / "libtriad.so"
    if host.is_file():
        ids["host build"] = RUNTIME_ID.findall(host.read_bytes())[0]
    assert len(set(ids.values())) == 1, ids
