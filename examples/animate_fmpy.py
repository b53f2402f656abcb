#!/usr/bin/env python3
"""See an fmpy run in 3-D: simulate a triad FMU under fmpy, record the bodies' poses (and the joint
angles, energy and work for the page's plot), write them with fmpy's own write_csv, and replay
them with `triad animate` as one self-contained HTML page.

    triad build tests/data/urdf/mesh_arm/mesh_arm.urdf -o mesh_arm.fmu
    python examples/animate_fmpy.py mesh_arm.fmu tests/data/urdf/mesh_arm/mesh_arm.urdf \
        [--stop 3] [--csv run.csv] [--html run.html] [--triad target/release/triad]

MODEL is the spec or URDF the FMU was built from: the page draws its shapes (URDF meshes are
found relative to it, through package:// and --package-path); the poses come from the CSV only.
"""
import argparse
import pathlib
import subprocess

from fmpy import read_model_description, simulate_fmu
from fmpy.util import write_csv


def replayed(name):
    """True for the outputs `triad animate` reads: poses, joint coordinates, energy and work."""
    kind, _, rest = name.partition(".")
    last = rest.rsplit(".", 1)[-1]
    if kind in ("body", "site"):
        return last.startswith(("r[", "R["))
    if kind == "joint":
        return last == "q" or last.startswith("q[")
    return name in ("system.energy", "system.work")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu")
    p.add_argument("model", help="the spec or URDF the FMU was built from")
    p.add_argument("--stop", type=float, default=3.0)
    p.add_argument("--step", type=float, default=0.01, help="output interval, s")
    p.add_argument("--csv", default="run.csv")
    p.add_argument("--html", default="run.html")
    root = pathlib.Path(__file__).resolve().parent.parent
    p.add_argument("--triad", default=str(root / "target" / "release" / "triad"))
    a = p.parse_args()

    md = read_model_description(a.fmu)
    outputs = [v.name for v in md.modelVariables if v.causality == "output" and replayed(v.name)]
    result = simulate_fmu(a.fmu, stop_time=a.stop, output_interval=a.step, output=outputs)
    write_csv(a.csv, result)
    print(f"wrote {a.csv} ({len(result)} rows, {len(outputs)} outputs)")
    subprocess.run([a.triad, "animate", a.model, a.csv, "-o", a.html], check=True)


if __name__ == "__main__":
    main()
