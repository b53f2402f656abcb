"""The drop-and-stand of examples/quadruped_stand.py in triad (its FMU under fmpy) and in MuJoCo
(PyPI), in the same run: cost per simulated second against the error of the base-height
trajectory, both measured against one high-accuracy triad run (order 4, max_step 1e-4), and
the ratio of their costs at matched accuracy.

The model: Go1 from the venv's example-robot-data, imported with `--floating-base --contacts`,
with its four foot spheres only (MuJoCo gets the same four; the other shapes never touch in this
run), in the stand pose 0.1 m above the ground; the PD loop of the example at 1 kHz on both
(the controller and the Python loop are not timed: only `fmi2DoStep` and `mj_step`). MuJoCo's
model and contact law: tests/python/quadruped_mujoco.py (the static law matched exactly, the
Hunt-Crossley damping matched at the standing load; elliptic cone, nearly hard friction).

Error: max over the 5 s of |z(t) - z_ref(t)| at the 1 kHz control instants (m). MuJoCo's error
has a floor, the difference of the two contact models at impact: "matched accuracy" is the
larger of the two engines' best errors (times 1.2); each engine's cost there is its cheapest run
within it, and the ratio is triad's over MuJoCo's. Steps: triad order 2 at max_step 1e-3 ...
1.25e-4 and order 4 at 1e-3, 5e-4; MuJoCo (implicitfast) 1e-3 ... 1.25e-4. Each run is timed
`--repeat` times (the minimum is kept).

    .venv/bin/python bench/contact_mujoco.py [--repeat 3] [--out target/contact_mujoco.json]
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "examples"))
sys.path.insert(0, str(ROOT / "tests" / "python"))
import quadruped_mujoco as mj  # noqa: E402
import quadruped_stand as qs  # noqa: E402


def feet_only(spec):
    spec = json.loads(json.dumps(spec))
    spec["collision"] = [c for c in spec["collision"] if c["name"] in qs.FEET]
    return spec


def triad_run(triad, spec, tmp, max_step, order, repeat):
    path = pathlib.Path(tmp) / f"go1_{order}_{max_step:g}.json"
    s = json.loads(json.dumps(spec))
    s["solver"].update(max_step=max_step, order=order)
    path.write_text(json.dumps(s))
    fmu = path.with_suffix(".fmu")
    subprocess.run([triad, "build", str(path), "-o", str(fmu), "--platforms", "host"], check=True,
                   capture_output=True)
    best = None
    for _ in range(repeat):
        r = qs.run_fmu(fmu, s, every=10**9)
        best = r if best is None or r["wall"] < best["wall"] else best
    return best


def mujoco_run(spec, h, repeat):
    sub = int(round(qs.H / h))
    best = None
    for _ in range(repeat):
        r = mj.run(spec, qs.FEET, qs.Stand(spec), qs.STOP, qs.H, substeps=sub)
        best = r if best is None or r["wall"] < best["wall"] else best
    return best


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--triad", default=str(ROOT / "target" / "release" / "triad"))
    p.add_argument("--repeat", type=int, default=3)
    p.add_argument("--out", default=str(ROOT / "target" / "contact_mujoco.json"))
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        spec, _ = qs.make_spec(a.triad, tmp)
        spec = feet_only(spec)
        ref = triad_run(a.triad, spec, tmp, 1e-4, 4, 1)
        runs = []
        for order, steps in ((2, (1e-3, 5e-4, 2.5e-4, 1.25e-4)), (4, (1e-3, 5e-4))):
            for h in steps:
                r = triad_run(a.triad, spec, tmp, h, order, a.repeat)
                runs.append(("triad", f"order {order}", h, r))
        for h in (1e-3, 5e-4, 2.5e-4, 1.25e-4):
            runs.append(("mujoco", "implicitfast", h, mujoco_run(spec, h, a.repeat)))
    rows = []
    print(f"{'engine':7s} {'method':13s} {'step (s)':>9s} {'error (m)':>10s} {'cost (s/s)':>11s} "
          f"{'peak foot (N)':>14s} {'settled z (m)':>14s}")
    for engine, method, h, r in runs:
        err = float(np.abs(r["z"] - ref["z"]).max())
        cost = r["wall"] / qs.STOP
        rows.append({"engine": engine, "method": method, "step": h, "error_m": err, "cost_s_per_s": cost,
                     "peak_foot_N": float(r["feet"].max()), "settled_z_m": float(r["z"][-1])})
        print(f"{engine:7s} {method:13s} {h:9.3g} {err:10.2e} {cost:11.4f} {r['feet'].max():14.1f} "
              f"{r['z'][-1]:14.6f}")
    best = {e: min(x["error_m"] for x in rows if x["engine"] == e) for e in ("triad", "mujoco")}
    matched = 1.2 * max(best.values())
    cost = {e: min(x["cost_s_per_s"] for x in rows if x["engine"] == e and x["error_m"] <= matched)
            for e in best}
    ratio = cost["triad"] / cost["mujoco"]
    print(f"best errors: triad {best['triad']:.2e} m, MuJoCo {best['mujoco']:.2e} m; matched accuracy "
          f"{matched:.2e} m: cost per simulated second triad {cost['triad']:.4f} s, MuJoCo "
          f"{cost['mujoco']:.4f} s, ratio triad/MuJoCo {ratio:.2f}")
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out, "w") as f:
        json.dump({"runs": rows, "matched_error_m": matched, "cost": cost, "ratio": ratio,
                   "reference": {"order": 4, "max_step": 1e-4, "wall_s": ref["wall"]}}, f, indent=1)


if __name__ == "__main__":
    main()
