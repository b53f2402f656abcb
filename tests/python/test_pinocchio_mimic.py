"""URDF `<mimic>` against Pinocchio's mimic joints.

triad imports `<mimic joint multiplier offset>` as a coupling `q_b = ratio q_a + offset`, an
exact constraint between joint coordinates; `triad linearize` writes the dynamics of the
independent coordinates (the leaders and the free joints) at an operating point, `xdot0 =
(q̇_I, q̈_I)`. Pinocchio 4.1 builds the same URDF with `mimic=True`: its nq, nv leave the mimic
joints out, and `crba`/`nle` give the mass matrix and the bias forces in those reduced
coordinates (`aba` refuses mimic joints), so `q̈ = M⁻¹ (τ − nle)`. The two agree to 1e-9
(relative to the largest acceleration) at seeded random states and torques, for a gripper
written here (a prismatic finger on an unaligned axis mimicking another with multiplier −1.5
and an offset, and a revolute tip mimicking the wrist, on a tilted wrist with products of
inertia) and for example-robot-data's Panda (finger_joint2 mimics finger_joint1).

As a check of the reference itself, the same accelerations come from Pinocchio's model without
mimic through the mimic Jacobian `G` (`q_full = G q + o`): `q̈ = (Gᵀ M G)⁻¹ Gᵀ (τ − nle)` (the
coupling is linear: no `Ġ` term); that independent derivation agrees with the mimic model to
1e-12.

Joint damping (Panda's `<dynamics damping>`) is set to zero on triad's side (Pinocchio's nle
knows none), limits and friction are left out at import, and the states lie inside the limits.
"""
import json
import subprocess
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest

import pinocchio_ref as ref

SEEDS = (1, 2, 3)
TOL = 1e-9  # relative to the largest |q̈|
REFERENCE_TOL = 1e-12  # the mimic model against the mimic Jacobian of the full model

GRIPPER = """<?xml version="1.0"?>
<robot name="gripper">
  <link name="base">
    <inertial><origin xyz="0 0 0.05"/><mass value="1.0"/>
      <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>
  </link>
  <link name="palm">
    <inertial><origin xyz="0.02 0.01 0.03" rpy="0.1 0.2 0.3"/><mass value="0.8"/>
      <inertia ixx="0.004" ixy="0.0003" ixz="-0.0002" iyy="0.005" iyz="0.0001" izz="0.003"/></inertial>
  </link>
  <link name="left">
    <inertial><origin xyz="0.01 0.0 0.04" rpy="0.3 0 0.1"/><mass value="0.12"/>
      <inertia ixx="2e-4" ixy="1e-5" ixz="0" iyy="2.5e-4" iyz="-2e-5" izz="1e-4"/></inertial>
  </link>
  <link name="right">
    <inertial><origin xyz="-0.01 0.005 0.04"/><mass value="0.15"/>
      <inertia ixx="2.5e-4" ixy="0" ixz="1e-5" iyy="2e-4" iyz="0" izz="1.2e-4"/></inertial>
  </link>
  <link name="tip">
    <inertial><origin xyz="0 0 0.02"/><mass value="0.05"/>
      <inertia ixx="2e-5" ixy="0" ixz="0" iyy="2e-5" iyz="0" izz="1e-5"/></inertial>
  </link>
  <joint name="wrist" type="revolute">
    <parent link="base"/><child link="palm"/>
    <origin xyz="0 0 0.1" rpy="0 0.4 0"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="10" velocity="5"/>
  </joint>
  <joint name="left_finger" type="prismatic">
    <parent link="palm"/><child link="left"/>
    <origin xyz="0.03 0 0.08"/><axis xyz="1 0 0"/>
    <limit lower="-0.05" upper="0.05" effort="10" velocity="1"/>
  </joint>
  <joint name="right_finger" type="prismatic">
    <parent link="palm"/><child link="right"/>
    <origin xyz="-0.03 0 0.08" rpy="0 0 0.2"/><axis xyz="0.6 0.8 0"/>
    <limit lower="-0.1" upper="0.1" effort="10" velocity="1"/>
    <mimic joint="left_finger" multiplier="-1.5" offset="0.01"/>
  </joint>
  <joint name="tip_joint" type="revolute">
    <parent link="left"/><child link="tip"/>
    <origin xyz="0 0 0.08"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="10" velocity="5"/>
    <mimic joint="wrist" multiplier="0.7" offset="-0.2"/>
  </joint>
</robot>
"""

CASES = {"gripper": None, "panda": "panda_description/urdf/panda.urdf"}


def _triad(triad_bin, *args):
    proc = subprocess.run([triad_bin, *args], capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, f"triad {' '.join(map(str, args))}:\n{proc.stderr}"
    return proc.stdout


def _mimics(urdf_text):
    """{follower: (leader, multiplier, offset)} of the URDF's movable joints (URDF defaults 1, 0)."""
    out = {}
    for joint in ET.fromstring(urdf_text).iter("joint"):
        mimic = joint.find("mimic")
        if mimic is not None and joint.get("type") not in ("fixed", "floating", "planar"):
            out[joint.get("name")] = (mimic.get("joint"), float(mimic.get("multiplier", "1")),
                                      float(mimic.get("offset", "0")))
    return out


class Case:
    """One URDF seen by triad (imported with its mimics as couplings) and by Pinocchio (with and
    without mimic joints)."""

    def __init__(self, triad_bin, tmp_path, name):
        relative = CASES[name]
        if relative is None:
            self.urdf = tmp_path / "gripper.urdf"
            self.urdf.write_text(GRIPPER)
        else:
            self.urdf = ref.robot_urdf(relative)
        text = self.urdf.read_text()
        self.bin = triad_bin
        self.mimics = _mimics(text)
        assert self.mimics, "no movable mimic joint"
        self.model = pin.buildModelFromXML(text, mimic=True)
        self.full = pin.buildModelFromXML(text)
        assert not np.any(self.full.armature)
        spec = _triad(triad_bin, "import", str(self.urdf), "--no-limits", "--no-friction")
        assert spec.count("[[coupling]]") == len(self.mimics)
        self.names = {urdf: triad for triad, urdf in ref.urdf_names(spec)["joint"].items()}
        # Pinocchio's independent joints, in its velocity order
        self.independent = [(self.model.names[i], j) for i, j in enumerate(self.model.joints)
                            if i > 0 and j.shortname() != "JointModelMimic"]
        for name, j in self.independent:
            assert j.nq == 1 and j.nv == 1, f"{name}: only revolute and prismatic joints here"
        assert self.model.nv == len(self.independent) == self.full.nv - len(self.mimics)

    def random_point(self, rng):
        """(q, v, tau) in Pinocchio's reduced coordinates: q inside the limits (and the
        followers' inside theirs), v in +-1, tau sized by the mass-matrix diagonal."""
        lo, hi = self.model.lowerPositionLimit, self.model.upperPositionLimit
        q = np.array([rng.uniform(lo[j.idx_q], hi[j.idx_q]) for _, j in self.independent])
        v = rng.uniform(-1.0, 1.0, self.model.nv)
        diag = np.diag(self._mass(q))
        tau = rng.uniform(-1.0, 1.0, self.model.nv) * 5.0 * diag
        return q, v, tau

    def _mass(self, q):
        data = self.model.createData()
        m = pin.crba(self.model, data, q)
        return np.triu(m) + np.triu(m, 1).T

    def pinocchio(self, q, v, tau):
        """q̈ of the mimic model: M⁻¹ (τ − nle)."""
        data = self.model.createData()
        return np.linalg.solve(self._mass(q), tau - pin.nle(self.model, data, q, v))

    def _jacobian(self):
        """The mimic Jacobian G and offset o of the full model: q_full = G q + o."""
        g, o = np.zeros((self.full.nv, self.model.nv)), np.zeros(self.full.nq)
        col = {name: k for k, (name, _) in enumerate(self.independent)}
        for i in range(1, self.full.njoints):
            name, j = self.full.names[i], self.full.joints[i]
            leader, ratio, offset = self.mimics.get(name, (name, 1.0, 0.0))
            g[j.idx_v, col[leader]] = ratio
            o[j.idx_q] = offset
        return g, o

    def pinocchio_full(self, q, v, tau):
        """q̈ from the model without mimic through the mimic Jacobian (module docs)."""
        g, o = self._jacobian()
        data = self.full.createData()
        m = pin.crba(self.full, data, g @ q + o)
        m = np.triu(m) + np.triu(m, 1).T
        b = pin.nle(self.full, data, g @ q + o, g @ v)
        return np.linalg.solve(g.T @ m @ g, tau - g.T @ b)

    def full_state(self, q, v):
        """{URDF joint: (q, qd)} of every movable joint, the followers' from their leaders."""
        state = {name: (q[k], v[k]) for k, (name, _) in enumerate(self.independent)}
        for follower, (leader, ratio, offset) in self.mimics.items():
            ql, vl = state[leader]
            state[follower] = (ratio * ql + offset, ratio * vl)
        return state

    def triad(self, q, v, tau):
        """q̈ of the independent joints from `triad linearize`'s xdot0, in Pinocchio's order."""
        args = ["linearize", str(self.urdf), "--no-limits", "--no-friction", "-o", "-"]
        for urdf_name, (qj, vj) in self.full_state(q, v).items():
            n = self.names[urdf_name]
            args += ["--set", f"joint.{n}.q0={float(qj)!r}", "--set", f"joint.{n}.qd0={float(vj)!r}",
                     "--set", f"joint.{n}.damping=0"]
        for k, (name, j) in enumerate(self.independent):
            word = "f" if j.shortname().startswith("JointModelP") else "tau"  # PX..PZ, PrismaticUnaligned
            args += ["--u", f"joint.{self.names[name]}.{word}={float(tau[k])!r}"]
        out = json.loads(_triad(self.bin, *args))
        xdot = dict(zip(out["x_names"], out["xdot0"]))
        return np.array([xdot[f"joint.{self.names[name]}.qd"] for name, _ in self.independent])


@pytest.mark.parametrize("name", list(CASES))
def test_mimic_accelerations_against_pinocchio(triad_bin, tmp_path, name):
    case = Case(triad_bin, tmp_path, name)
    worst = worst_ref = 0.0
    for seed in SEEDS:
        rng = np.random.default_rng([seed, len(name)])
        q, v, tau = case.random_point(rng)
        want = case.pinocchio(q, v, tau)
        scale = max(1.0, np.max(np.abs(want)))
        worst_ref = max(worst_ref, np.max(np.abs(case.pinocchio_full(q, v, tau) - want)) / scale)
        worst = max(worst, np.max(np.abs(case.triad(q, v, tau) - want)) / scale)
    print(f"{name}: |q̈_triad − q̈_pinocchio| ≤ {worst:.1e}, mimic model against the mimic Jacobian "
          f"{worst_ref:.1e} (relative to max |q̈|)")
    assert worst_ref < REFERENCE_TOL, worst_ref
    assert worst < TOL, worst
