"""A legged MJCF model with contact stands as MuJoCo's does: a quadruped written here (a box
torso on a free joint, hinged thighs and shins of capsules, sphere feet, a world plane, position
servos holding the legs straight, MuJoCo's default solref/solimp), dropped 2.5 cm. After 3 s
both stand on their four feet; the torso heights differ by less than the feet's penetration in
MuJoCo (the scale of its soft contact; `triad import` maps solref/solimp to a stiffness and a
damper as Bring your robot explains, an approximation). Measured: MuJoCo 0.32448 m
(penetration 0.52 mm), triad 0.32495 m: 0.47 mm apart."""
import csv
import subprocess

import numpy as np
import pytest

mujoco = pytest.importorskip("mujoco")

LEGS = {"fl": (0.15, 0.1), "fr": (0.15, -0.1), "hl": (-0.15, 0.1), "hr": (-0.15, -0.1)}
STOP = 3.0


def quadruped():
    legs, servos = "", ""
    for n, (x, y) in LEGS.items():
        legs += f"""
      <body name="{n}_thigh" pos="{x} {y} 0">
        <joint name="{n}_hip" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0 0 -0.15" size="0.02" mass="0.3"/>
        <body name="{n}_shin" pos="0 0 -0.15">
          <joint name="{n}_knee" axis="0 1 0"/>
          <geom type="capsule" fromto="0 0 0 0 0 -0.13" size="0.015" mass="0.2"/>
          <geom name="{n}_foot" type="sphere" pos="0 0 -0.15" size="0.025" mass="0.05"/>
        </body>
      </body>"""
        servos += (f'    <position name="{n}_hip_servo" joint="{n}_hip" kp="60" kv="3"/>\n'
                   f'    <position name="{n}_knee_servo" joint="{n}_knee" kp="60" kv="3"/>\n')
    return f"""<mujoco model="quadruped">
  <compiler angle="radian"/>
  <option timestep="0.001"/>
  <default>
    <joint damping="0.5" armature="0.01"/>
    <geom friction="1 0.005 0.0001"/>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="5 5 0.1"/>
    <body name="torso" pos="0 0 0.35">
      <freejoint name="root"/>
      <geom type="box" size="0.2 0.1 0.04" mass="4"/>{legs}
    </body>
  </worldbody>
  <actuator>
{servos}  </actuator>
</mujoco>
"""


def test_a_legged_mjcf_model_stands_as_in_mujoco(triad_bin, tmp_path):
    text = quadruped()
    m = mujoco.MjModel.from_xml_string(text)
    d = mujoco.MjData(m)
    while d.time < STOP - 1e-9:
        mujoco.mj_step(m, d)
    z_mj = d.xpos[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, "torso")][2]
    feet = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, f"{n}_foot") for n in LEGS]
    pen_mj = max(0.025 - d.geom_xpos[f][2] for f in feet)

    xml = tmp_path / "quadruped.xml"
    xml.write_text(text)
    out = tmp_path / "out.csv"
    subprocess.run([triad_bin, "simulate", str(xml), "--stop", repr(STOP), "--step", "0.01", "-o", str(out)],
                   check=True, capture_output=True, timeout=600)
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    z = data[:, header.index("body.torso.r[3]")]
    energy, work = data[:, header.index("system.energy")], data[:, header.index("system.work")]
    print(f"torso height after {STOP} s: MuJoCo {z_mj:.5f} m (feet {pen_mj * 1e3:.2f} mm deep), "
          f"triad {z[-1]:.5f} m, difference {abs(z[-1] - z_mj) * 1e3:.2f} mm")
    # both stand on straight legs (0.15 + 0.15 + the foot's radius below the torso)
    assert abs(z_mj - 0.325) < 2e-3 and abs(z[-1] - 0.325) < 2e-3
    # at rest, and as high as MuJoCo within its contact's penetration
    assert np.ptp(z[data[:, 0] >= STOP - 0.5]) < 1e-5
    assert abs(z[-1] - z_mj) <= max(pen_mj, 1e-4), (z[-1], z_mj, pen_mj)
    # the drop, the impact and the stand keep energy − work
    ew = energy - work
    assert np.abs(ew - ew[0]).max() <= 1e-12 * np.abs(energy).max()
