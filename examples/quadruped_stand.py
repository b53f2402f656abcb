#!/usr/bin/env python3
"""A quadruped drops onto the ground and stands, under a joint PD loop in fmpy.

Unitree's Go1 from example-robot-data (found in the venv at run time, nothing copied) is imported
with `triad import --floating-base --contacts`: its <collision> elements become collision
shapes (the feet are spheres of 2 cm; the trunk, thighs and calves boxes; the hips and rotors
cylinders) and a ground plane is added at height 0. The legs start in the stand pose, the base
0.1 m higher than where the feet would touch. It is built into an FMU and run in fmpy for 5 s
while a PD loop in Python reads `joint.*.q`, `joint.*.qd` and writes `joint.*.tau` every
communication step (1 kHz), clamped to the URDF's effort limits. Plotted: base height, the
vertical foot forces `contact.<foot>.f[3]` (their sum against the weight) and
`system.energy - system.work`, which stays constant to round-off through the impact; the 3-D
replay is written by `triad animate`.

    .venv/bin/python examples/quadruped_stand.py [--out out/quadruped] [--plot docs/quadruped_stand.png]
    .venv/bin/python examples/quadruped_stand.py --fmu-only target/fmus/quadruped_stand.fmu

Solo-12 is not used: its <collision> elements are all meshes, which `--contacts` leaves out.
"""
import argparse
import json
import pathlib
import subprocess
import sysconfig
import tempfile
import time
import zipfile

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARE = pathlib.Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share"
URDF = SHARE / "example-robot-data" / "robots" / "go1_description" / "urdf" / "go1.urdf"
# the URDF's <dynamics friction> is left out: the comparison with MuJoCo (tests/python/
# test_quadruped.py) gives MuJoCo no joint friction either
IMPORT = ["--floating-base", "--contacts", "--no-friction"]

STAND = {"hip": 0.0, "thigh": 0.8, "calf": -1.5}  # rad, each leg (joint names LEG_PART_joint)
FEET = ("FR_foot", "FL_foot", "RR_foot", "RL_foot")
DROP = 0.1  # m: the lowest foot's clearance at the start
KP, KD = 60.0, 3.0  # N.m/rad, N.m.s/rad
H = 1e-3  # communication step = control period, s
MAX_STEP = 1e-3  # internal step: ≤ √(m/k) = 1.4 ms of the lightest body with a shape (a calf; `triad check`)
STOP = 5.0  # s


def robot_urdf():
    """Go1's URDF in the venv's example-robot-data."""
    if not URDF.is_file():
        raise FileNotFoundError(f"{URDF} (is example-robot-data installed in this venv? bash scripts/setup.sh)")
    return URDF


def spec_of(triad, model, options, tmp):
    """The spec triad makes of MODEL with import OPTIONS, as a dict (the canonical JSON an FMU
    carries in resources/model.json)."""
    fmu = pathlib.Path(tmp) / "spec.fmu"
    subprocess.run([triad, "build", str(model), *options, "-o", str(fmu)], check=True, capture_output=True)
    with zipfile.ZipFile(fmu) as z:
        return json.loads(z.read("resources/model.json"))


def first_row(triad, spec_path, patterns):
    """The outputs matching PATTERNS at the start time (the first row of `triad simulate`)."""
    with tempfile.TemporaryDirectory() as tmp:
        csv = pathlib.Path(tmp) / "t0.csv"
        subprocess.run([triad, "simulate", str(spec_path), "--stop", "1e-3", "--step", "1e-3",
                        "--outputs", patterns, "-o", str(csv)], check=True, capture_output=True)
        names, first = csv.read_text().splitlines()[:2]
    return dict(zip(names.split(","), map(float, first.split(","))))


def make_spec(triad, out_dir, max_step=MAX_STEP, stop=STOP, drop=DROP):
    """Imports Go1 (`--floating-base --contacts`; the commented TOML is written beside, for
    reading), sets the stand pose as the joints' initial values and lifts the base so the
    lowest foot is `drop` above the ground; writes and returns `quadruped_stand.json`."""
    out_dir = pathlib.Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    urdf = robot_urdf()
    subprocess.run([triad, "import", str(urdf), *IMPORT, "-o", str(out_dir / "go1.toml")], check=True,
                   capture_output=True)
    with tempfile.TemporaryDirectory() as tmp:
        spec = spec_of(triad, urdf, IMPORT, tmp)
    spec["name"] = "quadruped_stand"
    spec["description"] = "Go1 (example-robot-data) dropped from 0.1 m onto the ground in its stand pose"
    for j in spec["joint"]:
        if j["type"] == "revolute":
            j["initial"] = {"q": STAND[j["name"].split("_")[1]], "qd": 0.0}
    spec["solver"]["max_step"] = max_step
    spec["experiment"].update(start=0.0, stop=stop, step=H)
    path = out_dir / "quadruped_stand.json"
    path.write_text(json.dumps(spec, indent=1))
    # a translation of the free base moves every shape by as much: one look at the gaps
    gaps = first_row(triad, path, "contact.*.gap")
    lowest = min(gaps[f"contact.{f}.gap"] for f in FEET)
    base = next(b for b in spec["body"] if "position" in b)
    base["position"][2] += drop - lowest
    path.write_text(json.dumps(spec, indent=1))
    return spec, path


class Stand:
    """The joint PD loop: tau = KP (q* - q) - KD qd on every actuated joint, clamped to its
    effort limit; q* is the stand pose."""

    def __init__(self, spec, kp=KP, kd=KD):
        joints = [j for j in spec["joint"] if j.get("actuated")]
        self.names = [j["name"] for j in joints]
        self.target = np.array([STAND[n.split("_")[1]] for n in self.names])
        self.limit = np.array([j.get("effort") or np.inf for j in joints])
        self.kp, self.kd = kp, kd

    def torque(self, q, qd):
        return np.clip(self.kp * (self.target - q) - self.kd * qd, -self.limit, self.limit)


def weight(spec):
    """The robot's weight, N."""
    return sum(b["mass"] for b in spec["body"]) * float(np.linalg.norm(spec["gravity"]))


def run_fmu(fmu_path, spec, stop=STOP, h=H, every=10, start_values=None):
    """Runs the FMU under the PD loop. Returns a dict: `t`, `z` (base height), `feet` (vertical
    forces, one column per foot in FEET), `energy`, `work`, `others` (the largest |force| on any
    other shape), `wall` (s) and `replay`: (names, rows) every `every` steps for `triad animate`
    (poses, joint angles, energy, work, and the contact forces and gaps: the page draws the
    ground where the gaps put it and the forces as arrows)."""
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    md = read_model_description(str(fmu_path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    ctl = Stand(spec)
    base = next(b["name"] for b in spec["body"] if "position" in b)
    q = [vr[f"joint.{n}.q"] for n in ctl.names]
    qd = [vr[f"joint.{n}.qd"] for n in ctl.names]
    tau = [vr[f"joint.{n}.tau"] for n in ctl.names]
    feet = [vr[f"contact.{f}.f[3]"] for f in FEET]
    others = [v for n, v in vr.items() if n.startswith("contact.") and ".f[" in n
              and n.split(".")[1] not in FEET]
    record = [vr[f"body.{base}.r[3]"], vr["system.energy"], vr["system.work"]] + feet + others
    replay = [n for n in vr if (n.startswith("body.") and (".r[" in n or ".R[" in n)) or n.startswith("contact.")
              or (n.startswith("joint.") and n.endswith(".q")) or n in ("system.energy", "system.work")]
    replay_vr = [vr[n] for n in replay]
    unzipped = extract(str(fmu_path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzipped, modelIdentifier=md.coSimulation.modelIdentifier,
                    instanceName="quadruped")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0)
    for name, value in (start_values or {}).items():
        fmu.setReal([vr[name]], [value])
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()
    n = int(round(stop / h))
    rows = np.empty((n + 1, 1 + len(record)))
    rows[0] = [0.0, *fmu.getReal(record)]
    frames = [[0.0, *fmu.getReal(replay_vr)]]
    wall = 0.0
    t = 0.0
    for k in range(n):
        y = np.array(fmu.getReal(q + qd))
        fmu.setReal(tau, list(ctl.torque(y[:len(q)], y[len(q):])))
        w0 = time.perf_counter()
        fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
        wall += time.perf_counter() - w0
        t = (k + 1) * h
        rows[k + 1] = [t, *fmu.getReal(record)]
        if (k + 1) % every == 0:
            frames.append([t, *fmu.getReal(replay_vr)])
    fmu.terminate()
    fmu.freeInstance()
    nf = len(feet)
    return {
        "t": rows[:, 0], "z": rows[:, 1], "energy": rows[:, 2], "work": rows[:, 3],
        "feet": rows[:, 4:4 + nf],
        "others": np.abs(rows[:, 4 + nf:]).max(axis=1) if others else np.zeros(n + 1),
        "wall": wall, "replay": (["time"] + replay, frames),
    }


def settled(t, z, tol=1e-3):
    """The first time after which the base height stays within `tol` of its final value."""
    off = np.abs(z - z[-1]) > tol
    return float(t[np.nonzero(off)[0][-1] + 1]) if off.any() else float(t[0])


def write_csv(path, replay):
    names, frames = replay
    with open(path, "w") as f:
        f.write(",".join(f'"{n}"' for n in names) + "\n")  # R[i,j] holds a comma
        for row in frames:
            f.write(",".join(repr(float(x)) for x in row) + "\n")


def plot(res, spec, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = res["t"]
    fig, ax = plt.subplots(3, 1, figsize=(8, 8.5), sharex=True)
    ax[0].plot(t, res["z"], "k")
    ax[0].set_ylabel("base height (m)")
    ax[0].set_title("Go1 (example-robot-data) dropped 0.1 m, standing under a joint PD loop in fmpy")
    for k, f in enumerate(FEET):
        ax[1].plot(t, res["feet"][:, k], lw=1, label=f"contact.{f}.f[3]")
    total = res["feet"][-1].sum()
    ax[1].axhline(weight(spec) / 4, color="k", ls="--", lw=1, label="weight / 4")
    ax[1].set_ylim(0, 1.05 * res["feet"].max())
    ax[1].set_title(f"at {t[-1]:g} s the four sum to {total:.3f} N, the weight {weight(spec):.3f} N", fontsize=9)
    ax[1].set_ylabel("vertical foot force (N)")
    ax[1].legend(ncol=3, fontsize=8, loc="upper right")
    ew = res["energy"] - res["work"]
    ax[2].plot(t, ew - ew[0], "b")
    scale = np.abs(res["energy"]).max()
    ax[2].set_ylabel("(energy − work) − initial (J)")
    ax[2].set_xlabel("time (s)")
    ax[2].set_title(f"max |change| {np.abs(ew - ew[0]).max():.1e} J, {np.abs(ew - ew[0]).max() / scale:.1e} of "
                    f"max |energy| {scale:.1f} J", fontsize=9)
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", default=str(ROOT / "out" / "quadruped"), help="folder for the spec, FMU, CSV and page")
    p.add_argument("--plot", default=None, help="the picture (default OUT/quadruped_stand.png)")
    p.add_argument("--triad", default=str(ROOT / "target" / "release" / "triad"))
    p.add_argument("--fmu-only", metavar="FMU", help="only build the FMU (what .ci/run does)")
    a = p.parse_args()
    out = pathlib.Path(a.out)
    if a.fmu_only:
        with tempfile.TemporaryDirectory() as tmp:
            _, path = make_spec(a.triad, tmp)
            subprocess.run([a.triad, "build", str(path), "-o", a.fmu_only], check=True)
        return
    spec, path = make_spec(a.triad, out)
    fmu = out / "quadruped_stand.fmu"
    subprocess.run([a.triad, "build", str(path), "-o", str(fmu)], check=True, capture_output=True)
    res = run_fmu(fmu, spec)
    feet = res["feet"]
    ew = res["energy"] - res["work"]
    print(f"{STOP:g} s in {res['wall']:.2f} s of fmi2DoStep; base height {res['z'][0]:.4f} -> {res['z'][-1]:.4f} m, "
          f"settled (within 1 mm) at {settled(res['t'], res['z']):.2f} s")
    print(f"vertical foot forces at the end: {feet[-1].round(2)} N, sum {feet[-1].sum():.3f} N, "
          f"weight {weight(spec):.3f} N; peak foot force {feet.max():.1f} N")
    print(f"energy - work: max change {np.abs(ew - ew[0]).max():.2e} J "
          f"({np.abs(ew - ew[0]).max() / np.abs(res['energy']).max():.1e} of max |energy|)")
    png = pathlib.Path(a.plot) if a.plot else out / "quadruped_stand.png"
    plot(res, spec, png)
    csv = out / "quadruped_stand.csv"
    write_csv(csv, res["replay"])
    html = out / "quadruped_stand.html"
    subprocess.run([a.triad, "animate", str(path), str(csv), "-o", str(html), "--package-path", str(SHARE)],
                   check=True)
    print(f"wrote {png}, {csv} and {html} (the 3-D replay)")


if __name__ == "__main__":
    main()
