"""MJCF `<equality joint>` against MuJoCo: a linear `polycoef` between two hinges (with `ref`s,
so the offset is taken relative to `qpos0` as MuJoCo does) and between two slides becomes a
`[[coupling]]`, which triad holds exactly. MuJoCo's equality is soft; made stiff (`solref`
direct stiffness 1e8, impedance 0.9999) it holds the coupling to ~1e-12 at its RK4 step of
1e-4, so both integrate the same constrained motion and the joint trajectories agree to 1e-6
over 1 s (measured: ~2e-12)."""
import subprocess

import pytest

from test_mjcf_mujoco import NO_CONTACT, _check_hinges

pytest.importorskip("mujoco")

STIFF = 'solref="-1e8 -2e4" solimp="0.9999 0.9999 0.001"'

COUPLED = f"""
<mujoco model="coupled">
  <compiler angle="radian"/>
  {NO_CONTACT}
  <worldbody>
    <body name="p1" pos="0 0 1">
      <joint name="a" type="hinge" axis="0 1 0" damping="0.05" ref="0.2"/>
      <geom type="capsule" fromto="0 0 0 0.3 0 -0.4" size="0.03"/>
    </body>
    <body name="p2" pos="0.5 0 1">
      <joint name="b" type="hinge" axis="1 0 0" ref="-0.1"/>
      <geom type="box" size="0.03 0.1 0.2" pos="0 0.05 -0.2"/>
    </body>
    <body name="s1" pos="0 1 1">
      <joint name="c" type="slide" axis="1 0 1" stiffness="20"/>
      <geom type="sphere" size="0.1"/>
    </body>
    <body name="s2" pos="0 2 1">
      <joint name="d" type="slide" axis="0 0 1"/>
      <geom type="sphere" size="0.05"/>
    </body>
  </worldbody>
  <equality>
    <joint joint1="b" joint2="a" polycoef="0.1 -0.5 0 0 0" {STIFF}/>
    <joint joint1="d" joint2="c" polycoef="0 2" {STIFF}/>
  </equality>
  <keyframe><key name="k" qpos="0.6 -0.2 0.05 0.1" qvel="1.0 -0.5 0.3 0.6"/></keyframe>
</mujoco>
"""


def test_equality_joint_is_a_coupling_as_mujoco_holds_it(triad_bin, tmp_path):
    _check_hinges(triad_bin, tmp_path, COUPLED, "k", ["a", "b", "c", "d"])


@pytest.mark.parametrize("equality, message", [
    ('<joint joint1="b" polycoef="0.1"/>', "without joint2 locks the joint"),
    ('<joint joint1="b" joint2="a" polycoef="0 1 0.5"/>', "only a linear coupling"),
    ('<joint joint1="b" joint2="c"/>', "both be hinges or both slides"),
    ('<joint joint1="b" joint2="nope"/>', 'joint "nope" does not exist'),
])
def test_unsupported_equality_joints_are_refused_on_their_line(triad_bin, tmp_path, equality, message):
    text = COUPLED.split("<equality>")[0] + f"<equality>\n    {equality}\n  </equality>\n</mujoco>\n"
    xml = tmp_path / "bad.xml"
    xml.write_text(text)
    r = subprocess.run([triad_bin, "check", str(xml), "--no-contacts"], capture_output=True, text=True, timeout=60)
    assert r.returncode != 0
    assert message in r.stderr and "bad.xml" in r.stderr and "line" in r.stderr, r.stderr
