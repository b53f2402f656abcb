"""MJCF actuators against MuJoCo itself: `<motor>` (gear != 1), `<position>` and `<velocity>`
servos (with gear, ctrlrange, forcerange, `<default>` classes, a `<general>` written as a servo)
become triad's `actuator.A.ctrl` inputs with MuJoCo's laws. For contact-free models, the joint
trajectories of `triad simulate MODEL.xml --input ctrl.csv` (order 4, max_step 1e-4) equal
MuJoCo's (RK4, timestep 1e-4, the same controls held over the same intervals) over 1 s to
1e-6 rad or m, for a constant control and for a time-varying one (a new value every 0.01 s).

The dm_control suite's cart-pole, acrobot and pendulum (their motors, gear 10, 2 and 1) are
read from the installed `dm_control` package (its XML files only; the package is not imported).
"""
import csv
import importlib.util
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

from test_mjcf_mujoco import H, STOP, TOL, mujoco

DT = 0.01  # the interval over which each control value is held

SERVOS = """
<mujoco model="servos">
  <compiler angle="radian"/>
  <option timestep="1e-4" integrator="RK4"><flag contact="disable"/></option>
  <default>
    <default class="stiff"><position kp="40" kv="2" ctrlrange="-1 1"/></default>
  </default>
  <worldbody>
    <body name="cart" pos="0 0 0.5">
      <joint name="rail" type="slide" axis="1 0 0" damping="0.1"/>
      <geom type="box" size="0.2 0.1 0.05" mass="2"/>
      <body name="upper" pos="0 0 0">
        <joint name="shoulder" type="hinge" axis="0 1 0"/>
        <geom type="capsule" fromto="0 0 0 0.1 0 -0.5" size="0.04"/>
        <body name="lower" pos="0.1 0 -0.5">
          <joint name="elbow" type="hinge" axis="1 1 0" ref="0.2"/>
          <geom type="box" size="0.03 0.04 0.2" pos="0 0 -0.2"/>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <position name="rail_servo" joint="rail" kp="30" kv="8" gear="0.5" forcerange="-6 6"/>
    <position name="shoulder_servo" class="stiff" joint="shoulder" gear="2" forcerange="-15 15"/>
    <velocity name="elbow_velocity" joint="elbow" kv="0.8" gear="-1.5" ctrlrange="-2 3"/>
    <general name="elbow_position" joint="elbow" gainprm="3" biastype="affine" biasprm="0 -3 -0.1"/>
    <motor name="elbow_motor" joint="elbow" gear="0.7" ctrlrange="-0.5 0.5" forcerange="-0.2 0.3"/>
  </actuator>
  <keyframe><key name="k" qpos="0.1 0.4 -0.3" qvel="0.2 -1 0.5"/></keyframe>
</mujoco>
"""


def _suite(name):
    spec = importlib.util.find_spec("dm_control")
    if spec is None:
        pytest.skip("dm_control is not installed (pip install --no-deps dm-control)")
    return pathlib.Path(spec.submodule_search_locations[0]) / "suite" / f"{name}.xml"


def _with_key(text, qpos, qvel):
    """The model at timestep H, RK4, no contact, with the keyframe `k`."""
    key = f'<keyframe><key name="k" qpos="{qpos}" qvel="{qvel}"/></keyframe>'
    text = text.replace('timestep="0.01"', f'timestep="{H}"').replace('timestep="0.02"', f'timestep="{H}"')
    text = text.replace('<option ', '<option integrator="RK4" ') if 'integrator=' not in text else text
    return text.replace("</mujoco>", key + "\n</mujoco>")


def _controls(names, law):
    """Rows (time, ctrl per actuator) at every DT up to STOP."""
    times = np.arange(0.0, STOP + DT / 2, DT)
    return times, np.array([[law(t, k) for k in range(len(names))] for t in times])


def _run(triad_bin, tmp_path, xml, names, law, joints):
    times, ctrl = _controls(names, law)
    inp = tmp_path / "ctrl.csv"
    with open(inp, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["time"] + [f"actuator.{n}.ctrl" for n in names])
        for t, row in zip(times, ctrl):
            w.writerow([repr(float(t))] + [repr(float(x)) for x in row])
    out = tmp_path / "out.csv"
    cmd = [triad_bin, "simulate", str(xml), "--no-contacts", "--keyframe", "k", "--stop", repr(STOP),
           "--step", repr(DT), "--max-step", repr(H), "--order", "4", "--input", str(inp), "-o", str(out)]
    subprocess.run(cmd, check=True, capture_output=True, timeout=600)
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], dtype=float)

    m = mujoco.MjModel.from_xml_path(str(xml))
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    ids = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_ACTUATOR, n) for n in names]
    assert min(ids) >= 0 and m.nu == len(names)
    adr = [m.jnt_qposadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, j)] for j in joints]
    steps = int(round(DT / m.opt.timestep))
    ref = [d.qpos[adr].copy()]
    for row in ctrl[:-1]:
        d.ctrl[ids] = row
        for _ in range(steps):
            mujoco.mj_step(m, d)
        ref.append(d.qpos[adr].copy())
    ref = np.array(ref)
    ours = data[:, [header.index(f"joint.{j}.q") for j in joints]]
    assert len(ours) == len(ref) and np.allclose(data[:, 0], times)
    worst = float(np.max(np.abs(ours - ref)))
    print(f"{xml.stem}: largest |q_triad - qpos_mujoco| over {STOP} s = {worst:.2e}")
    assert np.ptp(ref, axis=0).max() > 0.1  # the motion is not trivial
    return worst


def _constant(values):
    return lambda t, k: values[k]


def _varying(amplitudes):
    return lambda t, k: amplitudes[k] * np.sin(2 * np.pi * (1 + 0.5 * k) * t + k)


def _check(triad_bin, tmp_path, xml, names, joints, constant, amplitudes):
    worst = max(_run(triad_bin, tmp_path, xml, names, _constant(constant), joints),
                _run(triad_bin, tmp_path, xml, names, _varying(amplitudes), joints))
    assert worst < TOL, worst


def _suite_copy(tmp_path, name, qpos, qvel):
    src = _suite(name)
    shutil.copytree(src.parent / "common", tmp_path / "common")
    xml = tmp_path / f"{name}.xml"
    xml.write_text(_with_key(src.read_text(), qpos, qvel))
    return xml


def test_cartpole_motor_gear_10(triad_bin, tmp_path):
    xml = _suite_copy(tmp_path, "cartpole", "0 0.3", "0.1 -0.5")
    _check(triad_bin, tmp_path, xml, ["slide"], ["slider", "hinge_1"], [0.15], [0.6])


def test_acrobot_motor_gear_2(triad_bin, tmp_path):
    xml = _suite_copy(tmp_path, "acrobot", "2.8 -0.4", "0.5 1")
    # ctrl beyond ctrlrange [-1, 1]: MuJoCo's ctrllimited clamp
    _check(triad_bin, tmp_path, xml, ["elbow"], ["shoulder", "elbow"], [1.7], [1.5])


def test_pendulum_motor(triad_bin, tmp_path):
    xml = _suite_copy(tmp_path, "pendulum", "0.5", "0")
    _check(triad_bin, tmp_path, xml, ["torque"], ["hinge"], [-0.8], [1.2])


def test_position_velocity_general_servos_with_ranges_and_classes(triad_bin, tmp_path):
    xml = tmp_path / "servos.xml"
    xml.write_text(SERVOS)
    names = ["rail_servo", "shoulder_servo", "elbow_velocity", "elbow_position", "elbow_motor"]
    _check(triad_bin, tmp_path, xml, names, ["rail", "shoulder", "elbow"],
           [0.3, 0.6, 2.5, -0.2, 0.4], [0.4, 1.4, 3.0, 0.5, 0.8])


def test_imported_actuators(triad_bin, tmp_path):
    """The written [[actuator]] tables: kinds, gains, gears, clamps as MuJoCo compiles them."""
    import tomllib
    xml = tmp_path / "servos.xml"
    xml.write_text(SERVOS)
    spec = tomllib.loads(subprocess.run([triad_bin, "import", str(xml)], check=True, capture_output=True,
                                        text=True, timeout=60).stdout)
    m = mujoco.MjModel.from_xml_string(SERVOS)
    acts = {a["name"]: a for a in spec["actuator"]}
    assert [a["kind"] for a in spec["actuator"]] == ["position", "position", "velocity", "position", "motor"]
    for i in range(m.nu):
        a = acts[mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_ACTUATOR, i)]
        assert a.get("gear", 1.0) == m.actuator_gear[i, 0]
        gain = 1.0 if a["kind"] == "motor" else a.get("kp", a.get("kv"))
        assert gain == m.actuator_gainprm[i, 0]
        assert ("ctrlrange" in a) == bool(m.actuator_ctrllimited[i])
        assert ("forcerange" in a) == bool(m.actuator_forcelimited[i])
        if "ctrlrange" in a:
            assert a["ctrlrange"] == list(m.actuator_ctrlrange[i])


DEFAULTS = ['', '<position kp="7"/>', '<velocity kv="5"/>', '<general gainprm="4"/>', '<position kp="7" kv="2"/>',
            '<general biastype="affine" biasprm="0 -3 -1" gainprm="3"/>', '<motor gear="2" ctrlrange="-1 2"/>',
            '<position kp="7"/><default class="c"><velocity kv="3" forcerange="-1 1"/></default>']
ELEMENTS = ['<position joint="h"/>', '<velocity joint="h"/>', '<motor joint="h"/>', '<general joint="h"/>',
            '<position joint="h" kp="9"/>', '<velocity joint="h" class="c"/>', '<position joint="h" class="c"/>']


@pytest.mark.parametrize("default", DEFAULTS)
def test_actuator_defaults_as_mujoco_compiles_them(triad_bin, tmp_path, default):
    """Every actuator element under every kind of actuator default: the imported law, gain,
    bias, gear and clamps are MuJoCo's compiled `actuator_gainprm`, `biasprm`, `gear`, ranges."""
    import tomllib
    for element in ELEMENTS:
        if 'class="c"' in element and 'class="c"' not in default:
            continue
        text = (f'<mujoco><default>{default}</default><worldbody><body><joint name="h"/><geom size="0.1"/>'
                f'</body></worldbody><actuator>{element}</actuator></mujoco>')
        xml = tmp_path / "d.xml"
        xml.write_text(text)
        run = subprocess.run([triad_bin, "import", str(xml)], capture_output=True, text=True, timeout=60)
        m = mujoco.MjModel.from_xml_string(text)
        gain, bias = m.actuator_gainprm[0, :3], m.actuator_biasprm[0, :3]
        if run.returncode != 0:
            # refused: then MuJoCo's law is none of the three either (here: gain 4, no bias)
            assert "none of the laws" in run.stderr, run.stderr
            assert m.actuator_biastype[0] == 0 and gain[0] != 1, (default, element)
            continue
        a = tomllib.loads(run.stdout)["actuator"][0]
        ours = {"motor": ([1, 0, 0], [0, 0, 0]),
                "position": ([a.get("kp"), 0, 0], [0, -a.get("kp", 0), -a.get("kv", 0)]),
                "velocity": ([a.get("kv"), 0, 0], [0, 0, -a.get("kv", 0)])}[a["kind"]]
        if a["kind"] == "motor":
            assert m.actuator_biastype[0] == 0, (default, element)
        else:
            assert list(bias) == ours[1], (default, element, a)
        assert list(gain) == ours[0], (default, element, a)
        assert a.get("gear", 1.0) == m.actuator_gear[0, 0], (default, element)
        assert ("ctrlrange" in a) == bool(m.actuator_ctrllimited[0]), (default, element)
        assert ("forcerange" in a) == bool(m.actuator_forcelimited[0]), (default, element)


# A joint's actuatorfrcrange clamps the *sum* of the actuator forces on it (MuJoCo's
# qfrc_actuator clamp): on the hinge a motor and a servo whose sum saturates, on the slide one
# motor beyond it; the elbow's range is switched off by actuatorfrclimited="false", the wrist's
# comes from a <default> class with autolimits.
FRCRANGE = """
<mujoco model="frcrange">
  <compiler angle="radian" autolimits="true"/>
  <option timestep="1e-4" integrator="RK4"><flag contact="disable"/></option>
  <default>
    <default class="limited"><joint actuatorfrcrange="-0.3 0.25"/></default>
  </default>
  <worldbody>
    <body name="cart" pos="0 0 0.5">
      <joint name="rail" type="slide" axis="1 0 0" actuatorfrcrange="-1.5 1"/>
      <geom type="box" size="0.2 0.1 0.05" mass="2"/>
      <body name="upper">
        <joint name="shoulder" type="hinge" axis="0 1 0" actuatorfrcrange="-2 1.2"/>
        <geom type="capsule" fromto="0 0 0 0.1 0 -0.5" size="0.04"/>
        <body name="lower" pos="0.1 0 -0.5">
          <joint name="elbow" type="hinge" axis="1 1 0" actuatorfrcrange="-0.1 0.1" actuatorfrclimited="false"/>
          <geom type="box" size="0.03 0.04 0.2" pos="0 0 -0.2"/>
          <body name="hand" pos="0 0 -0.4">
            <joint name="wrist" class="limited" type="hinge" axis="0 0 1"/>
            <geom type="box" size="0.1 0.02 0.02" mass="0.3"/>
          </body>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor name="rail_motor" joint="rail" gear="2"/>
    <motor name="shoulder_motor" joint="shoulder" gear="1.5"/>
    <position name="shoulder_servo" joint="shoulder" kp="6" kv="0.5" gear="-1"/>
    <motor name="elbow_motor" joint="elbow"/>
    <motor name="wrist_motor" joint="wrist" gear="0.5"/>
    <velocity name="wrist_velocity" joint="wrist" kv="0.4"/>
  </actuator>
  <keyframe><key name="k" qpos="0.1 0.4 -0.3 0.2" qvel="0.2 -1 0.5 1"/></keyframe>
</mujoco>
"""
FRC_NAMES = ["rail_motor", "shoulder_motor", "shoulder_servo", "elbow_motor", "wrist_motor", "wrist_velocity"]


def test_actuatorfrcrange_clamps_the_summed_force(triad_bin, tmp_path):
    """The joints' trajectories against MuJoCo's (RK4) to TOL, with the summed forces clamped
    for part of the run (checked below on MuJoCo's own qfrc_actuator)."""
    xml = tmp_path / "frcrange.xml"
    xml.write_text(FRCRANGE)
    m = mujoco.MjModel.from_xml_string(FRCRANGE)
    assert list(m.jnt_actfrclimited) == [1, 1, 0, 1]
    # the clamp is hit: MuJoCo's unclamped sum exceeds the range at the constant controls
    constant = [0.8, 1.5, -0.6, 0.3, 0.9, -1.0]
    d = mujoco.MjData(m)
    mujoco.mj_resetDataKeyframe(m, d, 0)
    d.ctrl[:] = constant
    mujoco.mj_forward(m, d)
    raw = np.zeros(m.nv)
    for a in range(m.nu):
        raw[m.jnt_dofadr[m.actuator_trnid[a, 0]]] += m.actuator_gear[a, 0] * d.actuator_force[a]
    # the rail's one motor and the shoulder's motor + servo sum beyond their ranges
    assert np.all(np.abs(raw - d.qfrc_actuator)[:2] > 0.1), (raw, d.qfrc_actuator)
    _check(triad_bin, tmp_path, xml, FRC_NAMES, ["rail", "shoulder", "elbow", "wrist"],
           constant, [1.2, 2.0, 1.5, 0.5, 1.0, 2.0])


def test_imported_actuatorfrcrange(triad_bin, tmp_path):
    """The written joints carry actuatorfrcrange exactly where MuJoCo limits them."""
    import tomllib
    xml = tmp_path / "frcrange.xml"
    xml.write_text(FRCRANGE)
    spec = tomllib.loads(subprocess.run([triad_bin, "import", str(xml)], check=True, capture_output=True,
                                        text=True, timeout=60).stdout)
    m = mujoco.MjModel.from_xml_string(FRCRANGE)
    joints = {j["name"]: j for j in spec["joint"]}
    for i in range(m.njnt):
        j = joints[mujoco.mj_id2name(m, mujoco.mjtObj.mjOBJ_JOINT, i)]
        if m.jnt_actfrclimited[i]:
            assert j["actuatorfrcrange"] == list(m.jnt_actfrcrange[i])
        else:
            assert "actuatorfrcrange" not in j
