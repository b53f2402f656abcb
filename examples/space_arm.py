#!/usr/bin/env python3
"""Closed loop on the space_arm FMU (a free-floating satellite bus with a seven-joint arm, no
gravity) under fmpy: a joint PD controller in Python drives the arm from its initial pose to a
target pose, setting every `joint.<j>.tau` once per communication step.

    python examples/space_arm.py path/to/space_arm.fmu [--stop 30] [--step 0.01] [--plot space_arm.png]

The joint torques are internal forces: the bus turns in reaction while the arm moves, and the
total angular momentum `system.L` (about the world origin) stays at its initial value to
round-off. Prints the final tracking error, the bus's rotation, the largest |system.L| and,
for scale, the largest angular momentum of a single body during the run.
"""
import argparse
import json
import os
import shutil

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

JOINTS = ["shoulder_roll", "shoulder_yaw", "shoulder_pitch", "elbow", "wrist_pitch", "wrist_yaw", "wrist_roll"]
TARGET = {"shoulder_roll": 0.4, "shoulder_yaw": -0.6, "shoulder_pitch": 0.5, "elbow": 0.9,
          "wrist_pitch": 0.3, "wrist_yaw": 0.5, "wrist_roll": -0.8}
# gains by the joint's reflected inertia (N.m/rad, N.m.s/rad): about 0.5 rad/s, well damped
KP = {"shoulder_roll": 60.0, "shoulder_yaw": 120.0, "shoulder_pitch": 120.0, "elbow": 40.0,
      "wrist_pitch": 4.0, "wrist_yaw": 4.0, "wrist_roll": 1.0}
KD = {"shoulder_roll": 180.0, "shoulder_yaw": 360.0, "shoulder_pitch": 360.0, "elbow": 120.0,
      "wrist_pitch": 10.0, "wrist_yaw": 10.0, "wrist_roll": 2.5}


def mass_properties(unzip_dir):
    """{body: (mass, com, inertia 3x3)} from the model the FMU carries (resources/model.json,
    the spec as built; inertia given as [Ixx, Iyy, Izz], [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] or 3x3
    rows)."""
    with open(os.path.join(unzip_dir, "resources", "model.json")) as f:
        spec = json.load(f)
    out = {}
    for b in spec["body"]:
        i = b["inertia"]
        if isinstance(i[0], list):
            inertia = np.array(i)
        elif len(i) == 3:
            inertia = np.diag(i)
        else:
            xx, yy, zz, xy, xz, yz = i
            inertia = np.array([[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]])
        out[b["name"]] = (b["mass"], np.array(b.get("com", [0.0, 0.0, 0.0])), inertia)
    return out


def body_momentum(r, R, v, w, mass, com, inertia):
    """Angular momentum of one body about the world origin from its frame origin r, rotation R,
    origin velocity v and angular velocity w (world frame)."""
    arm = R @ np.asarray(com)
    c = r + arm
    vc = v + np.cross(w, arm)
    return mass * np.cross(c, vc) + R @ np.asarray(inertia) @ R.T @ w


def rotation_angle(R):
    """Angle of a rotation matrix (rad)."""
    return float(np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0)))


def closed_loop(fmu_path, stop=None, step=None):
    """Runs the loop; returns a dict of numpy arrays: time, q (n x 7), L (n x 3), bus_R (n x 3 x 3),
    bus_r (n x 3), largest single-body |L_b|, and the joint names and target."""
    md = read_model_description(fmu_path)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    ex = md.defaultExperiment
    stop = stop if stop is not None else float(ex.stopTime)
    h = step if step is not None else float(ex.stepSize)
    unzip = extract(fmu_path)
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier,
                    instanceName="space_arm")
    bodies = mass_properties(unzip)
    # per body: r (3), R (9, row-major), v (3), w (3) in one getReal call
    body_vr = [vr[f"body.{b}.{x}"] for b in bodies
               for x in ["r[1]", "r[2]", "r[3]"] + [f"R[{i},{j}]" for i in range(1, 4) for j in range(1, 4)]
               + ["v[1]", "v[2]", "v[3]", "w[1]", "w[2]", "w[3]"]]
    try:
        fmu.instantiate()
        fmu.setupExperiment(startTime=0.0)
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        q_vr = [vr[f"joint.{j}.q"] for j in JOINTS]
        qd_vr = [vr[f"joint.{j}.qd"] for j in JOINTS]
        tau_vr = [vr[f"joint.{j}.tau"] for j in JOINTS]
        l_vr = [vr[f"system.L[{i}]"] for i in range(1, 4)]
        ref = np.array([TARGET[j] for j in JOINTS])
        kp = np.array([KP[j] for j in JOINTS])
        kd = np.array([KD[j] for j in JOINTS])
        n = int(round(stop / h))
        rec = {k: [] for k in ("time", "q", "L", "bus_R", "bus_r")}
        lb_max = 0.0
        for i in range(n + 1):
            q = np.array(fmu.getReal(q_vr))
            qd = np.array(fmu.getReal(qd_vr))
            state = np.array(fmu.getReal(body_vr)).reshape(len(bodies), 18)
            for (b, (m, com, inertia)), x in zip(bodies.items(), state):
                R = x[3:12].reshape(3, 3)
                lb = body_momentum(x[0:3], R, x[12:15], x[15:18], m, com, inertia)
                lb_max = max(lb_max, float(np.linalg.norm(lb)))
                if b == "bus":
                    rec["bus_R"].append(R)
                    rec["bus_r"].append(x[0:3])
            rec["time"].append(i * h)
            rec["q"].append(q)
            rec["L"].append(np.array(fmu.getReal(l_vr)))
            if i == n:
                break
            fmu.setReal(tau_vr, list(kp * (ref - q) - kd * qd))
            fmu.doStep(currentCommunicationPoint=i * h, communicationStepSize=h)
        fmu.terminate()
    finally:
        fmu.freeInstance()
        shutil.rmtree(unzip, ignore_errors=True)
    out = {k: np.array(v) for k, v in rec.items()}
    out["single_body_L_max"] = lb_max
    out["joints"] = JOINTS
    out["target"] = ref
    return out


def summary(r):
    """(final tracking error in rad, bus rotation at the end in rad, largest |L| relative to the
    largest single-body angular momentum)."""
    err = float(np.max(np.abs(r["q"][-1] - r["target"])))
    turn = rotation_angle(r["bus_R"][-1])
    drift = float(np.max(np.linalg.norm(r["L"] - r["L"][0], axis=1))) / r["single_body_L_max"]
    return err, turn, drift


def plot(r, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = r["time"]
    fig, ax = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    for k, j in enumerate(r["joints"]):
        ax[0].plot(t, r["q"][:, k], label=j)
    ax[0].set_ylabel("joint angle (rad)")
    ax[0].legend(ncol=4, fontsize=7)
    ax[0].set_title("space_arm: joint PD to a target pose, bus floating free")
    ang = [np.degrees(rotation_angle(R)) for R in r["bus_R"]]
    ax[1].plot(t, ang, color="k", label="bus rotation angle")
    ax[1].set_ylabel("bus attitude change (deg)")
    ax[1].legend(fontsize=8)
    for k, c in enumerate("xyz"):
        ax[2].plot(t, r["L"][:, k] - r["L"][0, k],
                   label=f"system.L[{k + 1}] ({c}), L(0) = {r['L'][0, k]:.4g}")
    ax[2].set_ylabel("system.L - L(0) (N.m.s)")
    ax[2].set_xlabel("time (s)")
    ax[2].legend(fontsize=8)
    ax[2].ticklabel_format(axis="y", style="sci", scilimits=(0, 0))
    fig.tight_layout()
    fig.savefig(path, dpi=90)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu")
    p.add_argument("--stop", type=float)
    p.add_argument("--step", type=float)
    p.add_argument("--plot", help="write the joint angles, bus attitude and system.L to this PNG")
    a = p.parse_args()
    r = closed_loop(a.fmu, a.stop, a.step)
    err, turn, drift = summary(r)
    for j, q, ref in zip(r["joints"], r["q"][-1], r["target"]):
        print(f"{j:>15}: q = {q:+.6f} rad (target {ref:+.3f})")
    print(f"final tracking error:          {err:.3e} rad")
    print(f"bus rotation at the end:       {np.degrees(turn):.3f} deg")
    print(f"largest single-body |L_b|:     {r['single_body_L_max']:.3e} N.m.s")
    print(f"largest |system.L - L(0)|:     {drift * r['single_body_L_max']:.3e} N.m.s "
          f"({drift:.1e} of the largest single-body momentum)")
    if a.plot:
        plot(r, a.plot)
        print(f"wrote {a.plot}")


if __name__ == "__main__":
    main()
