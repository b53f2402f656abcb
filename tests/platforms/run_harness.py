"""Runs tests/harness/fmi_harness.c on every FMU of a folder, on every platform this machine can
run: linux64 natively, win64 under wine64, aarch64 Linux under qemu-aarch64, and (with
--host-lib) the host build of the library, then compares the results with linux64's.

    python run_harness.py FMU_DIR HARNESS_DIR [--host-lib target/release/libtriad.so] [--fmi3-dir DIR]

HARNESS_DIR holds fmi_harness (native), fmi_harness.exe with the test-only
bcryptprimitives.dll beside it, and fmi_harness.aarch64. Every FMU must carry
binaries/linux64, win64 and aarch64-linux (`triad build --platforms all`).

Passes when every harness run passed all its checks, and for every model:
- the host build gives the same outputs as linux64 (the glibc 2.17 build), bit for bit;
- win64 and aarch64 agree with linux64 after 1 s to 1e-12 (|a - b| / max(|a|, |b|, 1), the
  relative difference, absolute below 1), except models listed in CHAOTIC (reported only);
- on every platform `energy - work` changed over the run by at most 1e-12 of the largest
  |energy| or |work| (round-off).
With --fmi3-dir, every FMI 3 FMU there whose name matches an FMI 2 FMU is driven by
tests/harness/fmi3_harness.c (fmi3_harness, .exe, .aarch64 in HARNESS_DIR) on the same
platforms, from binaries/x86_64-linux, x86_64-windows and aarch64-linux; it must pass all its
checks and give the FMI 2 run's outputs bit for bit (the same runtime, the same inputs; array
elements row-major).
Prints a table and a closing `N passed, M failed` line.
"""

import argparse
import os
import re
import pathlib
import subprocess
import sys
import time
import zipfile

# models whose motion after 1 s amplifies a last-place difference beyond 1e-12, reported only:
# quadruped_stand (examples/quadruped_stand.py), the unactuated Go1 folding onto the ground under
# the harness's small inputs (legs into their stops, feet and trunk sliding): a change of gravity
# by one ulp moves joint.FR_thigh_joint.qd by 1.1e-6 after 1 s on one machine (triad simulate),
# and aarch64 differs from linux64 by 6.5e-7 on the same output (qemu, measured)
CHAOTIC = {"quadruped_stand"}
REL_TOL = 1e-12
# slider_crank (a closed loop): its coordinates and rates agree to 1e-14 between libms, but
# system.p and system.L, read from the integrator's nodal velocities, differ by up to 9e-12
# relative after 1 s (measured: win64 4.9e-12 on p[3] = 0.554); held to 1e-10
# gripper (examples/specs/gripper.toml: a turning wrist, coupled fingers, a friction bristle):
# its coordinates agree to round-off, but system.p[3] differs by 2.2e-12 (win64 against linux64,
# measured), the libms' last places amplified by the stiff bristle; held to 1e-10 as well
LOOSE = {"slider_crank": 1e-10, "gripper": 1e-10}
EW_TOL = 1e-12


def run(cmd, env=None, timeout=600):
    t = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)
    return p, time.time() - t


def parse(stdout):
    outs, ew, checks, fails = {}, None, None, []
    for line in stdout.splitlines():
        parts = line.split()
        if parts[:1] == ["out"]:
            outs[parts[1]] = float(parts[2])
        elif parts[:1] == ["ew"]:
            ew = (float(parts[1]), float(parts[2]))
        elif parts[:1] == ["checks"]:
            checks = line
        elif parts[:1] == ["FAIL"]:
            fails.append(line)
    return outs, ew, checks, fails


def flat_fmi2(outs):
    """FMI 2 outputs keyed as the FMI 3 harness prints them: (name, row-major element)."""
    cols = {}
    for n in outs:
        m = re.match(r"(.*)\[(\d+),(\d+)\]$", n)
        if m:
            cols[m.group(1)] = max(cols.get(m.group(1), 0), int(m.group(3)))
    flat = {}
    for n, v in outs.items():
        m = re.match(r"(.*)\[(\d+)(?:,(\d+))?\]$", n)
        if not m:
            flat[f"{n}#0"] = v
        elif m.group(3) is None:
            flat[f"{m.group(1)}#{int(m.group(2)) - 1}"] = v
        else:
            flat[f"{m.group(1)}#{(int(m.group(2)) - 1) * cols[m.group(1)] + int(m.group(3)) - 1}"] = v
    return flat


def rel(a, b):
    worst, where = 0.0, None
    for k in a:
        d = abs(a[k] - b.get(k, float("nan"))) / max(abs(a[k]), abs(b.get(k, 0.0)), 1.0)
        if not d <= worst:
            worst, where = d, k
    return worst, where


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("fmu_dir")
    ap.add_argument("harness_dir")
    ap.add_argument("--host-lib")
    ap.add_argument("--only", help="comma-separated platforms (linux64,win64,aarch64-linux)")
    ap.add_argument("--fmi3-dir", help="FMI 3 FMUs of the same models, run by fmi3_harness")
    a = ap.parse_args()
    harness = pathlib.Path(a.harness_dir).resolve()
    work = harness / "unzipped"
    platforms = (a.only or "linux64,win64,aarch64-linux").split(",")
    env = dict(os.environ, WINEDEBUG="-all", WINEDLLOVERRIDES="mscoree,mshtml=")
    env.setdefault("WINEPREFIX", str(harness.parent / "wine"))
    wine = "/usr/lib/wine/wine64"
    passed = failed = 0
    rows = []
    for fmu in sorted(pathlib.Path(a.fmu_dir).glob("*.fmu")):
        d = work / fmu.stem
        if d.exists():
            subprocess.run(["rm", "-rf", str(d)], check=True)
        with zipfile.ZipFile(fmu) as z:
            z.extractall(d)
        ident = next((d / "binaries" / "linux64").glob("*.so")).stem
        results = {}
        cmds = {
            "linux64": [str(harness / "fmi_harness"), str(d / "binaries/linux64" / f"{ident}.so"), str(d)],
            "win64": [wine, str(harness / "fmi_harness.exe"),
                      "Z:" + str(d / "binaries/win64" / f"{ident}.dll").replace("/", "\\"),
                      "Z:" + str(d).replace("/", "\\")],
            "aarch64-linux": ["qemu-aarch64", "-L", "/usr/aarch64-linux-gnu",
                              str(harness / "fmi_harness.aarch64"),
                              str(d / "binaries/aarch64-linux" / f"{ident}.so"), str(d)],
        }
        if a.host_lib:
            platforms_here = ["host"] + platforms
            cmds["host"] = [str(harness / "fmi_harness"), a.host_lib, str(d)]
        else:
            platforms_here = platforms
        for plat in platforms_here:
            p, secs = run(cmds[plat], env=env)
            outs, ew, checks, fails = parse(p.stdout)
            ok = p.returncode == 0 and checks is not None and outs and ew is not None
            results[plat] = (outs, ew)
            status = "ok" if ok else "FAILED"
            if ok:
                passed += 1
            else:
                failed += 1
                print(f"{fmu.stem} {plat}: harness failed (exit {p.returncode})")
                print("\n".join(fails[:10]) or p.stdout[-2000:])
                print(p.stderr[-2000:])
            drift = ew[0] / max(ew[1], 1e-300) if ew else float("nan")
            if ew is not None:
                if drift <= EW_TOL:
                    passed += 1
                else:
                    failed += 1
                    status += f" energy-work drift {drift:.2e} > {EW_TOL:g}"
            rows.append((fmu.stem, plat, checks or "-", f"{drift:.1e}", f"{secs:.1f}", status))
        base = results.get("linux64", ({}, None))[0]
        for plat in platforms_here:
            if plat == "linux64" or not base or not results[plat][0]:
                continue
            worst, where = rel(base, results[plat][0])
            if plat == "host":
                same = results[plat][0] == base
                passed += same
                failed += not same
                rows.append((fmu.stem, "host = linux64", "bit for bit" if same else "DIFFERENT",
                             f"{worst:.1e}", "", "ok" if same else f"FAILED at {where}"))
                continue
            tol = LOOSE.get(fmu.stem, REL_TOL)
            ok = worst <= tol or fmu.stem in CHAOTIC
            passed += ok
            failed += not ok
            rows.append((fmu.stem, f"{plat} vs linux64", f"max rel diff {worst:.1e}", where or "",
                         "", ("ok" if ok else "FAILED") + f" (tolerance {tol:g})"))
        fmu3 = pathlib.Path(a.fmi3_dir) / fmu.name if a.fmi3_dir else None
        if fmu3 is None or not fmu3.exists():
            continue
        d3 = work / f"{fmu.stem}.fmi3"
        if d3.exists():
            subprocess.run(["rm", "-rf", str(d3)], check=True)
        with zipfile.ZipFile(fmu3) as z:
            z.extractall(d3)
        cmds3 = {
            "linux64": [str(harness / "fmi3_harness"), str(d3 / "binaries/x86_64-linux" / f"{ident}.so"), str(d3)],
            "win64": [wine, str(harness / "fmi3_harness.exe"),
                      "Z:" + str(d3 / "binaries/x86_64-windows" / f"{ident}.dll").replace("/", "\\"),
                      "Z:" + str(d3).replace("/", "\\")],
            "aarch64-linux": ["qemu-aarch64", "-L", "/usr/aarch64-linux-gnu",
                              str(harness / "fmi3_harness.aarch64"),
                              str(d3 / "binaries/aarch64-linux" / f"{ident}.so"), str(d3)],
        }
        if a.host_lib:
            cmds3["host"] = [str(harness / "fmi3_harness"), a.host_lib, str(d3)]
        for plat in platforms_here:
            p, secs = run(cmds3[plat], env=env)
            outs, _, checks, fails = parse(p.stdout)
            ok = p.returncode == 0 and checks is not None and bool(outs)
            same = ok and outs == flat_fmi2(results[plat][0])
            passed += same
            failed += not same
            if not same:
                print(f"{fmu.stem} FMI 3 {plat}: exit {p.returncode}, outputs equal to FMI 2: {ok and outs == flat_fmi2(results[plat][0])}")
                print("\n".join(fails[:10]) or p.stdout[-2000:])
                print(p.stderr[-2000:])
            rows.append((fmu.stem, f"FMI 3 {plat}", checks or "-", "= FMI 2" if same else "DIFFERENT",
                         f"{secs:.1f}", "ok" if same else "FAILED"))
    w = [max(len(str(r[i])) for r in rows) for i in range(6)]
    print("model | platform | harness | energy-work drift / max diff | s | result")
    for r in rows:
        print(" | ".join(str(c).ljust(w[i]) for i, c in enumerate(r)))
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
