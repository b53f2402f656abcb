"""MJCF import against MuJoCo itself: for contact-free MJCF models written here, the joint
trajectories of `triad simulate MODEL.xml --no-contacts` (order 4, max_step 1e-4) equal
MuJoCo's (RK4, timestep 1e-4) over 1 s to 1e-6 rad or m.

Both integrate the same equations of motion to ~1e-12 at these steps, so any difference above
round-off is a modelling difference: a frame, an axis, a sign of `ref`, the unit of an angle
(MuJoCo's default `<compiler angle="degree">`), an inertia computed from the geoms, a keyframe
read in the wrong order. `joint.J.q` is compared with MuJoCo's `qpos` directly (the contract: the
same number), ball joints by their quaternion (up to sign), a free body by its frame's position
and rotation matrix (`body.B.r`, `body.B.R` against `xpos`, `xmat`). The masses and inertias
MuJoCo computes from the geoms are checked as well, through `triad import`'s TOML.
"""
import csv
import os
import subprocess
import tomllib

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

STOP = 1.0
H = 1e-4
TOL = 1e-6

NO_CONTACT = '<option timestep="1e-4" integrator="RK4"><flag contact="disable"/></option>'

DOUBLE_PENDULUM = f"""
<mujoco model="double_pendulum">
  {NO_CONTACT}
  <worldbody>
    <body name="upper" pos="0 0 1" euler="0 0 30">
      <joint name="shoulder" type="hinge" axis="0 1 0" damping="0.05"/>
      <geom type="capsule" fromto="0 0 0 0.1 0 -0.5" size="0.04"/>
      <body name="lower" pos="0.1 0 -0.5" quat="0.9659258 0 0.2588190 0">
        <joint name="elbow" type="hinge" axis="1 1 0" pos="0 0 0.05" ref="20"/>
        <geom type="box" size="0.03 0.04 0.2" pos="0 0 -0.2" euler="10 0 0"/>
        <geom type="sphere" size="0.06" pos="0.02 0 -0.4"/>
      </body>
    </body>
  </worldbody>
  <keyframe><key name="swing" qpos="0.7 -0.4" qvel="1.5 -2"/></keyframe>
</mujoco>
"""

CART_POLE = f"""
<mujoco model="cart_pole">
  <compiler angle="radian"/>
  {NO_CONTACT}
  <default>
    <joint damping="0.2"/>
    <default class="pole"><geom type="cylinder" density="500"/></default>
  </default>
  <worldbody>
    <body name="cart" pos="0 0 0.2">
      <joint name="slider" type="slide" axis="1 0 0" ref="0.1" stiffness="5"/>
      <geom type="box" size="0.2 0.1 0.05"/>
      <body name="pole" childclass="pole" axisangle="0 1 0 0.2">
        <joint name="hinge" type="hinge" axis="0 1 0" damping="0.01"/>
        <geom fromto="0 0 0 0 0 0.6" size="0.02"/>
      </body>
    </body>
  </worldbody>
  <keyframe><key name="tilted" qpos="0.3 0.4" qvel="-0.5 0.2"/></keyframe>
</mujoco>
"""

BALL_CHAIN = f"""
<mujoco model="ball_chain">
  {NO_CONTACT}
  <worldbody>
    <body name="a" pos="0 0 2">
      <joint name="b1" type="ball" damping="0.02"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 -0.3" size="0.03"/>
      <body name="b" pos="0.3 0 -0.3" xyaxes="0 1 0 -1 0 0">
        <joint name="b2" type="ball" pos="0 0 0"/>
        <geom type="ellipsoid" size="0.05 0.08 0.2" pos="0 0 -0.2"/>
        <body name="c" pos="0 0 -0.4" zaxis="1 0 1">
          <joint name="b3" type="ball"/>
          <inertial pos="0.01 0 -0.15" quat="0.9 0.1 0.2 0.3" mass="0.7" diaginertia="0.004 0.005 0.002"/>
        </body>
      </body>
    </body>
  </worldbody>
  <keyframe>
    <key name="spin" qpos="0.9 0.1 0.3 0.2  0.8 -0.2 0.1 0.5  1 0 0 0" qvel="1 -2 0.5  0 3 1  -1 0 2"/>
  </keyframe>
</mujoco>
"""

SPRINGS = f"""
<mujoco model="springs">
  <compiler eulerseq="ZYX"/>
  {NO_CONTACT}
  <default>
    <default class="soft"><joint stiffness="20" damping="0.3"/></default>
  </default>
  <worldbody>
    <body name="arm" pos="0 0 0.5" euler="20 -10 45">
      <joint name="yaw" class="soft" axis="0 0 1"/>
      <joint name="pitch" class="soft" axis="1 0 0" pos="0 0 0.1" ref="-15"/>
      <geom type="cylinder" size="0.05 0.2" pos="0 0 0.3"/>
      <body name="hand" pos="0 0 0.5">
        <geom type="box" size="0.1 0.05 0.02" mass="0.5"/>
        <site name="tip" pos="0.1 0 0"/>
      </body>
      <body name="finger" pos="0.05 0 0.55">
        <joint name="slide" type="slide" axis="0 0.6 0.8" stiffness="50" damping="1"/>
        <geom type="sphere" size="0.03"/>
      </body>
    </body>
  </worldbody>
  <keyframe><key name="bent" qpos="0.5 0.3 0.02" qvel="0 1 0"/></keyframe>
</mujoco>
"""

FREE = f"""
<mujoco model="tumbler">
  {NO_CONTACT}
  <worldbody>
    <body name="box" pos="0.1 0.2 1.5" euler="10 20 30">
      <freejoint name="float"/>
      <geom type="box" size="0.3 0.1 0.05"/>
      <geom type="sphere" size="0.05" pos="0.3 0 0"/>
      <body name="flap" pos="-0.3 0 0">
        <joint name="flap" axis="0 1 0" damping="0.01"/>
        <geom type="box" size="0.1 0.08 0.01" pos="-0.1 0 0"/>
      </body>
    </body>
  </worldbody>
  <keyframe><key name="toss" qpos="0 0 2 1 0 0 0 0.3" qvel="0.5 0 3 1 7 0.5 -2"/></keyframe>
</mujoco>
"""


def _triad(triad_bin, tmp_path, text, key):
    xml = tmp_path / "model.xml"
    xml.write_text(text)
    out = tmp_path / "out.csv"
    cmd = [triad_bin, "simulate", str(xml), "--no-contacts", "--keyframe", key, "--stop", repr(STOP),
           "--step", "0.01", "--max-step", repr(H), "--order", "4", "-o", str(out)]
    subprocess.run(cmd, check=True, capture_output=True, timeout=600)
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    spec = subprocess.run([triad_bin, "import", str(xml), "--no-contacts"], check=True, capture_output=True,
                          text=True, timeout=60).stdout
    return rows[0], np.array(rows[1:], dtype=float), tomllib.loads(spec)


def _mujoco(text, key, times, record):
    m = mujoco.MjModel.from_xml_string(text)
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_KEY, key))
    mujoco.mj_forward(m, d)
    out = [record(m, d)]
    steps = int(round(times[1] / m.opt.timestep))
    for _ in times[1:]:
        for _ in range(steps):
            mujoco.mj_step(m, d)
        out.append(record(m, d))
    return m, np.array(out)


def _quat_gap(a, b):
    """Largest entry of |a - b| for unit quaternions, up to their sign."""
    return min(np.max(np.abs(a - b)), np.max(np.abs(a + b)))


def _check_hinges(triad_bin, tmp_path, text, key, names):
    header, data, _ = _triad(triad_bin, tmp_path, text, key)
    m, ref = _mujoco(text, key, data[:, 0], lambda m, d: d.qpos.copy())
    worst = 0.0
    for name in names:
        adr = m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, name)]
        col = data[:, header.index(f"joint.{name}.q")]
        worst = max(worst, float(np.max(np.abs(col - ref[:, adr]))))
    print(f"{m.nq} coordinates: largest |q_triad - qpos_mujoco| over {STOP} s = {worst:.2e}")
    # the motion is not trivial: the coordinates move by more than the tolerance many times over
    assert np.ptp(ref, axis=0).max() > 0.1
    assert worst < TOL, worst


def test_double_pendulum_hinges_degrees_ref(triad_bin, tmp_path):
    _check_hinges(triad_bin, tmp_path, DOUBLE_PENDULUM, "swing", ["shoulder", "elbow"])


def test_cart_pole_slide_and_hinge_radians_classes(triad_bin, tmp_path):
    _check_hinges(triad_bin, tmp_path, CART_POLE, "tilted", ["slider", "hinge"])


def test_armature_on_hinges_and_slide(triad_bin, tmp_path):
    """MuJoCo's armature (joint-space rotor inertia a q'^2/2) on the cart-pole's slide and hinge
    and the double pendulum's hinges is triad's armature: the same trajectories."""
    cart = CART_POLE.replace('stiffness="5"/>', 'stiffness="5" armature="0.4"/>').replace(
        '<joint name="hinge" type="hinge" axis="0 1 0" damping="0.01"/>',
        '<joint name="hinge" type="hinge" axis="0 1 0" damping="0.01" armature="0.02"/>')
    assert cart.count("armature") == 2
    _check_hinges(triad_bin, tmp_path, cart, "tilted", ["slider", "hinge"])
    pend = DOUBLE_PENDULUM.replace('damping="0.05"/>', 'damping="0.05" armature="0.05"/>').replace(
        'ref="20"/>', 'ref="20" armature="0.01"/>')
    assert pend.count("armature") == 2
    _check_hinges(triad_bin, tmp_path, pend, "swing", ["shoulder", "elbow"])


def test_springs_dampers_several_joints_in_one_body(triad_bin, tmp_path):
    _check_hinges(triad_bin, tmp_path, SPRINGS, "bent", ["yaw", "pitch", "slide"])


def test_ball_chain(triad_bin, tmp_path):
    header, data, _ = _triad(triad_bin, tmp_path, BALL_CHAIN, "spin")
    m, ref = _mujoco(BALL_CHAIN, "spin", data[:, 0], lambda m, d: d.qpos.copy())
    worst = 0.0
    for name in ["b1", "b2", "b3"]:
        adr = m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, name)]
        quat = data[:, [header.index(f"joint.{name}.quat[{k}]") for k in range(1, 5)]]
        for row, mj in zip(quat, ref[:, adr:adr + 4]):
            worst = max(worst, _quat_gap(row, mj / np.linalg.norm(mj)))
    print(f"ball chain: largest quaternion gap over {STOP} s = {worst:.2e}")
    assert worst < TOL, worst


def test_free_body_with_a_hinged_flap(triad_bin, tmp_path):
    header, data, _ = _triad(triad_bin, tmp_path, FREE, "toss")

    def record(m, d):
        b = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "box")
        return np.concatenate([d.xpos[b], d.xmat[b], d.qpos[7:8]])

    m, ref = _mujoco(FREE, "toss", data[:, 0], record)
    r = data[:, [header.index(f"body.box.r[{i}]") for i in range(1, 4)]]
    rot = data[:, [header.index(f"body.box.R[{i},{j}]") for i in range(1, 4) for j in range(1, 4)]]
    flap = data[:, header.index("joint.flap.q")]
    worst = max(np.max(np.abs(r - ref[:, 0:3])), np.max(np.abs(rot - ref[:, 3:12])),
                np.max(np.abs(flap - ref[:, 12])))
    print(f"free body: largest gap in position, rotation matrix, flap angle over {STOP} s = {worst:.2e}")
    assert worst < TOL, worst


@pytest.mark.parametrize("text", [DOUBLE_PENDULUM, CART_POLE, BALL_CHAIN, SPRINGS, FREE],
                         ids=["double_pendulum", "cart_pole", "ball_chain", "springs", "free"])
def test_total_mass_as_mujoco_computes_it(triad_bin, tmp_path, text):
    xml = tmp_path / "m.xml"
    xml.write_text(text)
    spec = tomllib.loads(subprocess.run([triad_bin, "import", str(xml), "--no-contacts"], check=True,
                                        capture_output=True, text=True, timeout=60).stdout)
    m = mujoco.MjModel.from_xml_string(text)
    assert abs(sum(b["mass"] for b in spec["body"]) - float(np.sum(m.body_mass))) < 1e-9 * float(np.sum(m.body_mass))
