"""The Pinocchio side of test_pinocchio.py: where example-robot-data's URDFs are, which URDF name
each triad body, site and joint carries, random states in triad's and Pinocchio's coordinates,
and the reference motion (`pin.aba` integrated by DOP853 under a zero-order-hold torque).

Conventions bridged here (Pinocchio 4 -> triad):
- a continuous joint has nq = 2 (cos, sin) in Pinocchio, one continuous angle in triad;
- a free-flyer has q = [position, quaternion (x, y, z, w)] and v = [linear, angular] velocity of
  the base frame in the BASE frame; triad's free body takes position, orientation [w, x, y, z],
  and the velocity of the body-frame origin and the angular velocity in the WORLD frame;
- `<dynamics damping>` is a viscous joint torque -d * qd in triad; `pin.aba` knows no damping,
  so the reference subtracts it from the applied torque (friction is modelled by neither).
"""
import re
import sysconfig
from pathlib import Path

import numpy as np
import pinocchio as pin
from scipy.integrate import solve_ivp

ROBOTS = Path(sysconfig.get_paths()["purelib"]) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"


def robot_urdf(relative):
    """A URDF of the installed example-robot-data, e.g. `ur_description/urdf/ur5_robot.urdf`."""
    path = ROBOTS / relative
    if not path.is_file():
        raise FileNotFoundError(f"{path} (is example-robot-data installed in this venv?)")
    return path


def load_model(urdf, floating):
    """Pinocchio's model of a URDF: the root link welded to the universe, or on a free-flyer."""
    model = pin.buildModelFromUrdf(str(urdf), pin.JointModelFreeFlyer()) if floating else pin.buildModelFromUrdf(str(urdf))
    assert not np.any(model.armature), "armature is not in URDF and not in triad"
    return model


_URDF_NAME = re.compile(r'URDF (?:link|joint) "(.*?)"')
_TABLE = re.compile(r"\[\[(body|joint|site)\]\]")
_KEY = re.compile(r"(\w+) = (.*)")


def _spec_tables(toml_text):
    """The [[body]], [[joint]] and [[site]] tables of an imported spec, in order, as dicts of
    kind, their top-level keys (raw TOML values) and `urdf`, the name in the comment above them.
    (A line scan of what `triad import` writes: Python 3.10 has no TOML reader.)"""
    tables, current, above = [], None, None
    for line in toml_text.splitlines():
        stripped = line.strip()
        if stripped.startswith("#"):
            found = _URDF_NAME.search(stripped)
            above = found.group(1) if found else above
            continue
        if stripped.startswith("["):
            header = _TABLE.fullmatch(stripped)
            current = {"kind": header.group(1), "urdf": above} if header else None  # None: a sub-table
            if current is not None:
                tables.append(current)
        elif current is not None and (key := _KEY.fullmatch(stripped)):
            current.setdefault(*key.groups())
        above = None if stripped else above
    return tables


def urdf_names(toml_text):
    """{"body"|"joint"|"site": {triad name: URDF name}} of an imported spec. The URDF name is
    read from the table's `description` when it has one, else from the `# URDF link "..."` /
    `# URDF joint "..."` comment right above the table, else it is the triad name itself."""
    names = {"body": {}, "joint": {}, "site": {}}
    for table in _spec_tables(toml_text):
        name = table["name"].strip('"')
        found = _URDF_NAME.search(table.get("description", ""))
        names[table["kind"]][name] = found.group(1) if found else (table["urdf"] or name)
    return names


def total_mass(toml_text):
    """The sum of the `mass` of every [[body]] of an imported spec, kg."""
    return sum(float(t["mass"]) for t in _spec_tables(toml_text) if t["kind"] == "body")


def free_bodies(toml_text):
    """triad names of the bodies that take a `position` (free bodies and floating bases)."""
    return [t["name"].strip('"') for t in _spec_tables(toml_text) if t["kind"] == "body" and "position" in t]


def _kind(joint):
    name = joint.shortname()
    if name == "JointModelFreeFlyer":
        return "free"
    if joint.nq == 2 and joint.nv == 1:
        return "continuous"
    assert joint.nq == 1 and joint.nv == 1, name
    return "scalar"


def moving_joints(model):
    """[(URDF joint name, joint model)] of every joint below the universe except the free-flyer."""
    return [(model.names[i], j) for i, j in enumerate(model.joints) if i > 0 and _kind(j) != "free"]


def free_joint(model):
    """The free-flyer's joint model, or None for a fixed base."""
    free = [j for i, j in enumerate(model.joints) if i > 0 and _kind(j) == "free"]
    return free[0] if free else None


def joint_ranges(model):
    """{URDF joint name: (lower, upper)}: the URDF limits where given, else +-1 rad (or m)."""
    ranges = {}
    for name, joint in moving_joints(model):
        lo, hi = model.lowerPositionLimit[joint.idx_q], model.upperPositionLimit[joint.idx_q]
        limited = _kind(joint) == "scalar" and np.isfinite(lo) and np.isfinite(hi) and lo < hi
        ranges[name] = (lo, hi) if limited else (-1.0, 1.0)
    return ranges


def random_joint_state(model, rng):
    """{URDF joint name: (q, qd)}: q uniform in the joint's range, qd uniform in +-1."""
    return {name: (rng.uniform(lo, hi), rng.uniform(-1.0, 1.0)) for name, (lo, hi) in joint_ranges(model).items()}


def random_base_state(rng):
    """A free base's initial state in triad's terms: position, orientation [w, x, y, z],
    velocity of the body-frame origin and angular velocity, both world frame."""
    quat = rng.normal(size=4)
    return {
        "position": rng.uniform(-0.5, 0.5, 3) + [0.0, 0.0, 1.0],
        "orientation": quat / np.linalg.norm(quat),
        "velocity": rng.uniform(-0.5, 0.5, 3),
        "angular_velocity": rng.uniform(-1.0, 1.0, 3),
    }


def pinocchio_state(model, joints, base=None):
    """(q, v) in Pinocchio's coordinates from triad's joint states and base state."""
    q, v = np.zeros(model.nq), np.zeros(model.nv)
    for name, joint in moving_joints(model):
        angle, rate = joints[name]
        q[joint.idx_q:joint.idx_q + joint.nq] = [np.cos(angle), np.sin(angle)] if _kind(joint) == "continuous" else [angle]
        v[joint.idx_v] = rate
    free = free_joint(model)
    if free is not None:
        w, x, y, z = base["orientation"]
        rot = pin.Quaternion(w, x, y, z).toRotationMatrix()
        q[free.idx_q:free.idx_q + 7] = [*base["position"], x, y, z, w]
        v[free.idx_v:free.idx_v + 6] = [*(rot.T @ base["velocity"]), *(rot.T @ base["angular_velocity"])]
    return q, v


class _ConfigurationRate:
    """dq/dt for the velocity v, q on Pinocchio's configuration manifold (index arrays built once:
    the stiff robots' reference takes hundreds of thousands of right-hand sides)."""

    def __init__(self, model):
        joints = [j for i, j in enumerate(model.joints) if i > 0]
        self.nq = model.nq
        self.scalar_q = np.array([j.idx_q for j in joints if _kind(j) == "scalar"], dtype=int)
        self.scalar_v = np.array([j.idx_v for j in joints if _kind(j) == "scalar"], dtype=int)
        self.circle_q = np.array([j.idx_q for j in joints if _kind(j) == "continuous"], dtype=int)
        self.circle_v = np.array([j.idx_v for j in joints if _kind(j) == "continuous"], dtype=int)
        free = free_joint(model)
        self.free = None if free is None else (free.idx_q, free.idx_v)

    def __call__(self, q, v):
        rate = np.empty(self.nq)
        rate[self.scalar_q] = v[self.scalar_v]
        cos, sin, omega = q[self.circle_q], q[self.circle_q + 1], v[self.circle_v]
        rate[self.circle_q], rate[self.circle_q + 1] = -sin * omega, cos * omega
        if self.free is not None:
            iq, iv = self.free
            vec, w = q[iq + 3:iq + 6], q[iq + 6]
            omega = v[iv + 3:iv + 6]
            rate[iq:iq + 3] = pin.Quaternion(w, *vec).toRotationMatrix() @ v[iv:iv + 3]
            rate[iq + 3:iq + 6] = 0.5 * (w * omega + np.cross(vec, omega))
            rate[iq + 6] = -0.5 * vec @ omega
        return rate


def simulate(model, q0, v0, torques, h):
    """The reference motion under the torques `torques[k]` (one row of nv generalised forces per
    communication step, held over [k h, (k + 1) h)). Returns (q, s) at the len(torques) + 1
    communication points: the configurations and the integrals of v since t = 0, so that a
    1-dof joint's continuous coordinate is its initial value plus s[:, idx_v]."""
    data = model.createData()
    nq, nv = model.nq, model.nv
    rate = _ConfigurationRate(model)
    on_manifold = (lambda q: pin.normalize(model, q)) if nq != nv else (lambda q: q)

    def rhs(_t, y, tau):
        q, v = on_manifold(y[:nq]), y[nq:nq + nv]
        a = pin.aba(model, data, q, v, tau - model.damping * v)
        return np.concatenate([rate(q, v), a, v])

    y = np.concatenate([q0, v0, np.zeros(nv)])
    states = [y]
    for k, tau in enumerate(torques):
        sol = solve_ivp(rhs, (k * h, (k + 1) * h), y, method="DOP853", rtol=1e-12, atol=1e-12, args=(tau,))
        assert sol.success, sol.message
        y = sol.y[:, -1]
        states.append(y)
    states = np.array(states)
    return np.array([on_manifold(q) for q in states[:, :nq]]), states[:, nq + nv:]


def energies(model, q, v):
    """(kinetic, potential) energy; the potential is -sum m g.c, zero at the world origin."""
    data = model.createData()
    return pin.computeKineticEnergy(model, data, q, v), pin.computePotentialEnergy(model, data, q)


def frame_states(model, q, v, links):
    """{URDF link name: (r, R, v, w)} of the links' frames, all in the world frame."""
    data = model.createData()
    pin.forwardKinematics(model, data, q, v)
    pin.updateFramePlacements(model, data)
    out = {}
    for link in links:
        assert model.existFrame(link, pin.BODY), f"Pinocchio has no frame for link {link!r}"
        fid = model.getFrameId(link, pin.BODY)
        twist = pin.getFrameVelocity(model, data, fid, pin.LOCAL_WORLD_ALIGNED)
        placement = data.oMf[fid]
        out[link] = (placement.translation.copy(), placement.rotation.copy(), twist.linear.copy(), twist.angular.copy())
    return out


def mass_matrix_diagonal(model, q):
    """The diagonal of the joint-space mass matrix at q (to size test torques to each joint)."""
    return np.diag(pin.crba(model, model.createData(), q)).copy()


def _toml_array(values):
    return "[" + ", ".join(repr(float(x)) for x in values) + "]"


def with_base(spec, base):
    """The spec with the free base's `position = [...]` line replaced by its initial state
    (`base`: position, orientation, velocity, angular_velocity)."""
    lines = spec.splitlines()
    (at,) = [i for i, line in enumerate(lines) if line.startswith("position = ")]
    lines[at:at + 1] = [f"{key} = {_toml_array(base[key])}" for key in ("position", "orientation", "velocity", "angular_velocity")]
    return "\n".join(lines) + "\n"
