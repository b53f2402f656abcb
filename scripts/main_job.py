#!/usr/bin/env python3
"""The README's main job: the robot_arm FMU in closed loop under fmpy (PD controller in Python,
examples/closed_loop.py), results written to CSV (with the bodies' poses, which
`triad animate` replays: scripts/main_job.sh writes results.html) and plotted.

    python scripts/main_job.py path/to/robot_arm.fmu [--csv results.csv] [--plot results.png]

Prints the final tracking error and the drift of system.energy - system.work.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples"))

import closed_loop  # noqa: E402


def poses(fmu):
    """Names of the pose outputs (body.B.r[i], body.B.R[i,j], and the sites') of an FMU."""
    from fmpy import read_model_description

    return [v.name for v in read_model_description(fmu).modelVariables
            if v.causality == "output" and v.name.split(".")[0] in ("body", "site")
            and v.name.split(".")[-1][:2] in ("r[", "R[")]


def write_csv(path, r):
    joints = r["joints"]
    extra = list(r.get("extra", {}))
    header = ["time"] + [f"joint.{j}.q" for j in joints] + [f"joint.{j}.qd" for j in joints] \
        + [f"joint.{j}.tau" for j in joints] + ["system.energy", "system.work", "energy_minus_work"] + extra
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for i, t in enumerate(r["time"]):
            e, wk = r["energy"][i], r["work"][i]
            more = [r["extra"][name][i] for name in extra]
            w.writerow([repr(float(x)) for x in [t, *r["q"][i], *r["qd"][i], *r["tau"][i], e, wk, e - wk, *more]])


def plot(path, r):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    for k, j in enumerate(r["joints"]):
        line, = ax[0].plot(r["time"], r["q"][:, k], label=j)
        ax[0].axhline(r["set_point"][k], color=line.get_color(), ls="--", lw=0.8)
    ax[0].set_ylabel("joint angle q [rad]")
    ax[0].legend(ncol=3, fontsize=8)
    ax[0].set_title("robot_arm under a PD controller (fmpy co-simulation); dashed: set points")
    ax[1].plot(r["time"], r["energy"], label="system.energy")
    ax[1].plot(r["time"], r["work"], label="system.work")
    ax[1].set_ylabel("J")
    ax[1].legend()
    ew = r["energy"] - r["work"]
    ax[2].plot(r["time"], ew - ew[0])
    ax[2].set_ylabel("(energy - work) - initial [J]")
    ax[2].set_xlabel("time [s]")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu")
    p.add_argument("--csv", default="results.csv")
    p.add_argument("--plot", default="results.png")
    p.add_argument("--stop", type=float)
    a = p.parse_args()
    r = closed_loop.closed_loop(a.fmu, a.stop, record=poses(a.fmu))
    write_csv(a.csv, r)
    plot(a.plot, r)
    err, drift = closed_loop.summary(r)
    print(f"wrote {a.csv} ({len(r['time'])} rows) and {a.plot}")
    print(f"final tracking error: {err:.3e} rad")
    print(f"energy - work drift: {drift:.3e} (relative to the largest |energy|)")


if __name__ == "__main__":
    main()
