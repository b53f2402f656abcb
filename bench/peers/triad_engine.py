#!/usr/bin/env python3
"""External engine for the peers harness (`../shared/peers/README.md`, CSV contract).

  triad_engine.py --variant native|fmu --model M.json --h H --t-end T --dt-out D --out OUT.csv --method M

Methods: EM2, EM4 (triple jump), EM4s5 (Suzuki's five stages) with fixed steps h; EMa2-<rtol>,
EMa4-<rtol> (five stages) with error-controlled steps (solver.rtol), h their ceiling and the
communication step.

Both variants first turn the neutral model into a triad spec (`to_spec.py`).
* native: runs the in-process `Simulation` (`target/release/examples/peers_native`), which times
  only its stepping loop; a `joint_pd` controller runs inside the model, continuously (joint
  stiffness kp, damping kd, constant torque kp q_set + tau_ff), integrated implicitly.
* fmu: builds the FMU with `triad build`, drives it with fmpy at communication step h (one internal
  step per communication step), closes the PD loop in Python once per step and times the loop
  (doStep + the get/set calls), so the cost of the FMI boundary and of fmpy's Python loop shows.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

import to_spec  # noqa: E402

TRIAD = os.environ.get("TRIAD_BIN", os.path.join(ROOT, "target", "release", "triad"))
NATIVE = os.environ.get("TRIAD_PEERS_NATIVE", os.path.join(ROOT, "target", "release", "examples", "peers_native"))


def columns(model):
    q, v = [], []
    for j in model["joints"]:
        n = j["name"]
        if j["type"] == "revolute":
            q.append(f"q.{n}")
            v.append(f"v.{n}")
        elif j["type"] == "spherical":
            q += [f"q.{n}.{c}" for c in ("qw", "qx", "qy", "qz")]
            v += [f"v.{n}.{c}" for c in ("wx", "wy", "wz")]
        else:
            q += [f"q.{n}.{c}" for c in ("x", "y", "z", "qw", "qx", "qy", "qz")]
            v += [f"v.{n}.{c}" for c in ("vx", "vy", "vz", "wx", "wy", "wz")]
    return q, v


def run_fmu(model, spec_path, a, order, workdir):
    import numpy as np
    from fmpy import extract, read_model_description
    from fmpy.fmi2 import FMU2Slave

    fmu_path = os.path.join(workdir, "model.fmu")
    subprocess.run([TRIAD, "build", spec_path, "-o", fmu_path], check=True, capture_output=True)
    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzip = extract(fmu_path)
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier,
                    instanceName="peers")
    fmu.instantiate()
    fmu.setupExperiment(startTime=0.0, stopTime=a.t_end)
    fmu.enterInitializationMode()
    fmu.exitInitializationMode()

    # output value references in CSV column order
    refs = []
    for j in model["joints"]:
        n = j["name"]
        if j["type"] == "revolute":
            refs.append(("q", [vr[f"joint.{n}.q"]]))
        elif j["type"] == "spherical":
            refs.append(("q", [vr[f"joint.{n}.quat[{k}]"] for k in range(1, 5)]))
        else:
            b = j["child"]
            refs.append(("free_q", [vr[f"body.{b}.r[{i}]"] for i in range(1, 4)]
                         + [vr[f"body.{b}.R[{i},{k}]"] for i in range(1, 4) for k in range(1, 4)]))
    vrefs = []
    for j in model["joints"]:
        n = j["name"]
        if j["type"] == "revolute":
            vrefs.append(("v", [vr[f"joint.{n}.qd"]]))
        elif j["type"] == "spherical":
            vrefs.append(("v", [vr[f"joint.{n}.w[{k}]"] for k in range(1, 4)]))
        else:
            b = j["child"]
            vrefs.append(("free_v", [vr[f"body.{b}.v[{i}]"] for i in range(1, 4)]
                          + [vr[f"body.{b}.w[{i}]"] for i in range(1, 4)]
                          + [vr[f"body.{b}.R[{i},{k}]"] for i in range(1, 4) for k in range(1, 4)]))
    all_refs = [r for _, rs in refs + vrefs for r in rs] + [vr["system.energy"]]

    def sample(t):
        y = fmu.getReal(all_refs)
        row, pos = [t], 0
        for kind, rs in refs + vrefs:
            vals = y[pos:pos + len(rs)]
            pos += len(rs)
            if kind in ("q", "v"):
                row += vals
            elif kind == "free_q":
                R = np.array(vals[3:]).reshape(3, 3)
                row += vals[:3] + list(to_spec_quat(R))
            else:
                R = np.array(vals[6:]).reshape(3, 3)
                row += vals[:3] + list(R.T @ np.array(vals[3:6]))
        row.append(y[-1])
        return row

    ctrl = model.get("controller") or {}
    pd = []
    for k, n in enumerate(ctrl.get("joints", [])):
        pd.append((vr[f"joint.{n}.q"], vr[f"joint.{n}.qd"], vr[f"joint.{n}.tau"], ctrl["kp"][k], ctrl["kd"][k],
                   ctrl["q_set"][k], ctrl["tau_ff"][k]))
    pd_meas = [r for p in pd for r in p[:2]]
    pd_tau = [p[2] for p in pd]
    torque = []
    for inp in model.get("inputs", []):
        if inp["type"] == "body_torque_world":
            torque.append(([vr[f"body.{inp['body']}.torque[{i}]"] for i in range(1, 4)], inp))

    nsub = int(round(a.dt_out / a.h))
    nout = int(round(a.t_end / a.dt_out))
    rows = [sample(0.0)]
    wall = 0.0
    t = 0.0
    for k in range(nout):
        t0 = time.perf_counter()
        for i in range(nsub):
            if pd:
                m = fmu.getReal(pd_meas)
                fmu.setReal(pd_tau, [p[3] * (p[5] - m[2 * c]) - p[4] * m[2 * c + 1] + p[6] for c, p in enumerate(pd)])
            for rs, inp in torque:
                on = inp["t_start"] - 1e-9 <= t < inp["t_end"] - 1e-9
                fmu.setReal(rs, [float(x) if on else 0.0 for x in inp["torque"]])
            # fmpy raises on any status other than fmi2OK
            fmu.doStep(currentCommunicationPoint=t, communicationStepSize=a.h)
            t = (k * nsub + i + 1) * a.h
        wall += time.perf_counter() - t0
        rows.append(sample((k + 1) * a.dt_out))
    fmu.terminate()
    fmu.freeInstance()
    shutil.rmtree(unzip, ignore_errors=True)
    meta = {"engine": "triad-fmu", "method": f"em-order{order}-fmi2-fmpy", "h": a.h, "n_steps": nout * nsub,
            "wall_time_s": wall, "controller": "zoh-per-step" if pd else "none"}
    return meta, rows


def to_spec_quat(R):
    """[w, x, y, z] (w >= 0) of a rotation matrix (Shepperd)."""
    import numpy as np
    tr = np.trace(R)
    if tr >= max(R[0, 0], R[1, 1], R[2, 2]):
        w = 0.5 * np.sqrt(1 + tr)
        q = [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)]
    else:
        i = int(np.argmax([R[0, 0], R[1, 1], R[2, 2]]))
        j, k = (i + 1) % 3, (i + 2) % 3
        x = 0.5 * np.sqrt(1 + R[i, i] - R[j, j] - R[k, k])
        v = [0.0, 0.0, 0.0]
        v[i] = x
        v[j] = (R[j, i] + R[i, j]) / (4 * x)
        v[k] = (R[k, i] + R[i, k]) / (4 * x)
        q = [(R[k, j] - R[j, k]) / (4 * x)] + v
    if q[0] < 0:
        q = [-c for c in q]
    return q


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--variant", choices=["native", "fmu"], default="native")
    ap.add_argument("--model", required=True)
    ap.add_argument("--h", type=float, required=True)
    ap.add_argument("--t-end", type=float, required=True)
    ap.add_argument("--dt-out", type=float, required=True)
    ap.add_argument("--out", required=True)
    ap.add_argument("--method", default="EM2")
    a = ap.parse_args()
    # EM2, EM4 (triple jump), EM4s5 (Suzuki's five stages): fixed steps h;
    # EMa2-<rtol>, EMa4-<rtol>: error-controlled steps (order 4 with five stages), h the ceiling
    meth = a.method.upper()
    rtol = float(a.method.split("-", 1)[1]) if meth.startswith("EMA") else 0.0
    order = 4 if meth.startswith(("EM4", "EMA4")) else 2
    stages = 5 if meth == "EM4S5" or (rtol > 0 and order == 4) else 3
    with open(a.model) as f:
        model = json.load(f)
    with tempfile.TemporaryDirectory() as d:
        spec_path = os.path.join(d, "spec.json")
        with open(spec_path, "w") as f:
            spec = to_spec.convert(model, a.h, order, a.t_end, a.dt_out, pd_internal=a.variant == "native")
            spec["solver"].update({"stages": stages, "rtol": rtol})
            json.dump(spec, f)
        if a.variant == "native":
            r = subprocess.run([NATIVE, "--pd", "internal", "--spec", spec_path, "--model", a.model, "--h", repr(a.h),
                                "--t-end", repr(a.t_end), "--dt-out", repr(a.dt_out), "--out", a.out],
                               capture_output=True, text=True)
            if r.returncode != 0:
                sys.stderr.write(r.stderr)
                raise SystemExit(r.returncode)
            return
        meta, rows = run_fmu(model, spec_path, a, order, d)
    q, v = columns(model)
    with open(a.out, "w") as f:
        for k, val in meta.items():
            f.write(f"# {k}={val}\n")
        f.write(",".join(["t"] + q + v + ["energy"]) + "\n")
        for r in rows:
            f.write(",".join(repr(float(x)) for x in r) + "\n")


if __name__ == "__main__":
    main()
