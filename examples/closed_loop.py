#!/usr/bin/env python3
"""Closed loop on the robot_arm FMU under fmpy: a PD controller in Python sets every
`joint.<j>.tau` from `joint.<j>.q` and `joint.<j>.qd` once per communication step.

    python examples/closed_loop.py path/to/robot_arm.fmu [--stop 3] [--step 0.01]

Prints the final tracking error and the drift of `system.energy - system.work` (constant up to the
Newton tolerance: the integrator is energy consistent, and the inputs are held over each step).
"""
import argparse
import shutil

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

# set point (rad) and PD gains per joint, in the order of the spec's joints
SET_POINT = {"shoulder_pan": 0.5, "shoulder_lift": 1.55, "elbow": 0.1, "wrist_1": -0.1, "wrist_2": 0.4, "wrist_3": 0.3}
KP = {"shoulder_pan": 120.0, "shoulder_lift": 600.0, "elbow": 240.0, "wrist_1": 40.0, "wrist_2": 12.0, "wrist_3": 1.2}
KD = {"shoulder_pan": 20.0, "shoulder_lift": 45.0, "elbow": 15.0, "wrist_1": 5.0, "wrist_2": 2.5, "wrist_3": 0.3}


def closed_loop(fmu_path, stop=None, step=None, set_point=SET_POINT, kp=KP, kd=KD, record=()):
    """Runs the loop; returns a dict of numpy arrays: time, q (n x joints), qd, tau, energy, work,
    the joint names, and under "extra" the recorded values of the output variables named in
    `record` (e.g. the body poses body.B.r[i], body.B.R[i,j] for `triad animate`)."""
    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    joints = [j for j in set_point if f"joint.{j}.tau" in vr]
    if not joints:
        raise SystemExit(f"{fmu_path}: no joint.<j>.tau inputs matching {list(set_point)}")
    ex = md.defaultExperiment
    t0 = float(ex.startTime or 0.0) if ex else 0.0
    stop = stop if stop is not None else float(ex.stopTime)
    h = step if step is not None else float(ex.stepSize)
    unzip = extract(fmu_path)
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="arm")
    try:
        fmu.instantiate()
        fmu.setupExperiment(startTime=t0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        q_vr = [vr[f"joint.{j}.q"] for j in joints]
        qd_vr = [vr[f"joint.{j}.qd"] for j in joints]
        tau_vr = [vr[f"joint.{j}.tau"] for j in joints]
        ew_vr = [vr["system.energy"], vr["system.work"]]
        record = list(record)
        extra_vr = [vr[name] for name in record]
        extra = []
        ref = np.array([set_point[j] for j in joints])
        gp = np.array([kp[j] for j in joints])
        gd = np.array([kd[j] for j in joints])
        n = int(round((stop - t0) / h))
        rec = {k: [] for k in ("time", "q", "qd", "tau", "energy", "work")}
        t = t0
        for i in range(n + 1):
            q = np.array(fmu.getReal(q_vr))
            qd = np.array(fmu.getReal(qd_vr))
            energy, work = fmu.getReal(ew_vr)
            tau = gp * (ref - q) - gd * qd
            for k, v in zip(("time", "q", "qd", "tau", "energy", "work"), (t, q, qd, tau, energy, work)):
                rec[k].append(v)
            if extra_vr:
                extra.append(fmu.getReal(extra_vr))
            if i == n:
                break
            fmu.setReal(tau_vr, list(tau))
            fmu.doStep(currentCommunicationPoint=t, communicationStepSize=h)
            t = t0 + (i + 1) * h
        fmu.terminate()
    finally:
        fmu.freeInstance()
        shutil.rmtree(unzip, ignore_errors=True)
    out = {k: np.array(v) for k, v in rec.items()}
    out["joints"] = joints
    out["set_point"] = ref
    values = np.array(extra).reshape(len(out["time"]), len(record))
    out["extra"] = {name: values[:, i] for i, name in enumerate(record)}
    return out


def summary(r):
    """(final tracking error in rad, relative drift of energy - work)."""
    err = float(np.max(np.abs(r["q"][-1] - r["set_point"])))
    ew = r["energy"] - r["work"]
    scale = max(1.0, float(np.max(np.abs(r["energy"]))))
    drift = float(np.max(np.abs(ew - ew[0]))) / scale
    return err, drift


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu")
    p.add_argument("--stop", type=float)
    p.add_argument("--step", type=float)
    a = p.parse_args()
    r = closed_loop(a.fmu, a.stop, a.step)
    err, drift = summary(r)
    for j, q in zip(r["joints"], r["q"][-1]):
        print(f"{j:>14}: q = {q:+.6f} rad (set point {SET_POINT[j]:+.3f})")
    print(f"final tracking error: {err:.3e} rad")
    print(f"energy - work drift:  {drift:.3e} (relative)")


if __name__ == "__main__":
    main()
