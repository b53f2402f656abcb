#!/usr/bin/env python3
"""Neutral peers model (schema peers-nmodel/1) -> triad model spec (JSON, interface.md §2).

Conventions match: a neutral joint's `anchor`/`rotation` place the joint frame in the parent frame
(triad `origin = {xyz, rpy}`), the child frame is the joint frame at q = 0, revolute axes are given
in the joint frame, spherical initial states are (quaternion w-first, angular velocity in child
axes). Neutral `free` joints become triad free bodies with an explicit initial pose and twist
(neutral: origin velocity in world axes, angular velocity in body axes; triad: both world).

Usage: to_spec.py MODEL.json OUT.json --h H [--order 2|4] [--t-end T] [--dt-out D]
"""
import argparse
import json
import math


def rpy_from_matrix(r):
    """URDF fixed-axis roll, pitch, yaw with R = Rz(yaw) Ry(pitch) Rx(roll)."""
    pitch = -math.asin(max(-1.0, min(1.0, r[2][0])))
    roll = math.atan2(r[2][1], r[2][2])
    yaw = math.atan2(r[1][0], r[0][0])
    return [roll, pitch, yaw]


def quat_rotate(q, v):
    w, x, y, z = q
    n = math.sqrt(w * w + x * x + y * y + z * z)
    w, x, y, z = w / n, x / n, y / n, z / n
    r = [
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ]
    return [sum(r[i][k] * v[k] for k in range(3)) for i in range(3)]


def convert(model, h, order=2, t_end=None, dt_out=None, tolerance=1e-10, pd_internal=False):
    """The triad spec of a neutral model. With `pd_internal`, a `joint_pd` controller
    tau = kp (q_set - q) - kd qd + tau_ff becomes part of the model: joint stiffness kp (about 0)
    and damping kd, integrated implicitly with the scheme's discrete gradients; the remaining
    constant torque kp q_set + tau_ff is the joint input (set by the runner)."""
    sim = model.get("sim", {})
    t_end = t_end if t_end is not None else sim.get("t_end", 1.0)
    dt_out = dt_out if dt_out is not None else sim.get("dt_out", 0.1)
    init_q = model.get("initial", {}).get("q", {})
    init_v = model.get("initial", {}).get("v", {})
    ctrl = model.get("controller") or {}
    actuated = set(ctrl.get("joints", []))
    bodies = []
    for b in model["bodies"]:
        body = {"name": b["name"], "mass": b["mass"], "com": b.get("com", [0, 0, 0]),
                "inertia": b["inertia"]}
        bodies.append(body)
    by_name = {b["name"]: b for b in bodies}
    joints = []
    for j in model["joints"]:
        name = j["name"]
        if j["type"] == "free":
            q = init_q.get(name, [0, 0, 0, 1, 0, 0, 0])
            v = init_v.get(name, [0, 0, 0, 0, 0, 0])
            b = by_name[j["child"]]
            b["position"] = list(q[:3])
            b["orientation"] = list(q[3:7])
            b["velocity"] = list(v[:3])
            b["angular_velocity"] = quat_rotate(q[3:7], v[3:6])
            continue
        rot = j.get("rotation", [[1, 0, 0], [0, 1, 0], [0, 0, 1]])
        joint = {"name": name, "type": j["type"], "parent": j["parent"], "child": j["child"],
                 "origin": {"xyz": j.get("anchor", [0, 0, 0]), "rpy": rpy_from_matrix(rot)}}
        if j["type"] == "revolute":
            joint["axis"] = j["axis"]
            joint["initial"] = {"q": float(init_q.get(name, 0.0)), "qd": float(init_v.get(name, 0.0))}
        elif j["type"] == "spherical":
            joint["initial"] = {"quat": list(init_q.get(name, [1, 0, 0, 0])),
                                "w": list(init_v.get(name, [0, 0, 0]))}
        else:
            raise SystemExit(f"joint type {j['type']} not supported by the adapter")
        if name in actuated:
            joint["actuated"] = True
            if pd_internal:
                k = ctrl["joints"].index(name)
                joint["stiffness"] = float(ctrl["kp"][k])
                joint["damping"] = float(ctrl["kd"][k])
        joints.append(joint)
    loads = []
    torque_bodies = sorted({i["body"] for i in model.get("inputs", []) if i["type"] == "body_torque_world"})
    for b in torque_bodies:
        loads.append({"body": b, "torque": True})
    spec = {
        "name": "peers_" + "".join(c if c.isalnum() else "_" for c in model["name"]),
        "description": model.get("description", model["name"]),
        "gravity": model.get("gravity", [0, 0, -9.81]),
        "experiment": {"start": 0.0, "stop": t_end, "step": dt_out},
        "solver": {"max_step": h, "order": order, "tolerance": tolerance},
        "body": bodies,
        "joint": joints,
    }
    if loads:
        spec["load"] = loads
    return spec


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("model")
    ap.add_argument("out")
    ap.add_argument("--h", type=float, required=True)
    ap.add_argument("--order", type=int, default=2)
    ap.add_argument("--t-end", type=float)
    ap.add_argument("--dt-out", type=float)
    a = ap.parse_args()
    with open(a.model) as f:
        model = json.load(f)
    spec = convert(model, a.h, a.order, a.t_end, a.dt_out)
    with open(a.out, "w") as f:
        json.dump(spec, f, indent=1)


if __name__ == "__main__":
    main()
