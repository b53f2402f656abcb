"""examples/linearize_fmpy.py: A, B of an FMU through fmpy's getDirectionalDerivative equal
`triad linearize`'s, at the start and at a later communication point; fmpy validate stays
clean with the states declared; closed loops and couplings (the four-bar, the slider-crank,
the example gripper without friction) in the independent coordinates the command picks."""
import json
import pathlib
import shutil
import subprocess

import numpy as np
import pytest
from fmpy import extract, read_model_description
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

import linearize_fmpy


def _triad_linear(triad, spec, *extra):
    out = subprocess.run([triad, "linearize", str(spec), "-o", "-", *extra], check=True, capture_output=True, text=True)
    return json.loads(out.stdout)


def test_fmu_jacobian_equals_linearize(built, triad_bin, tmp_path):
    fmu2, fmu3 = built("robot_arm")
    assert validate_fmu(fmu2) == [] and validate_fmu(fmu3) == []
    md = read_model_description(fmu2)
    assert md.coSimulation.providesDirectionalDerivative
    assert len(md.derivatives) == 12
    spec = linearize_fmpy.__file__.replace("examples/linearize_fmpy.py", "modelDescription/robot_arm/spec.toml")
    a, b, xs, us = linearize_fmpy.linear_model(fmu2)
    lin = _triad_linear(triad_bin, spec)
    assert xs == lin["x_names"] and us == lin["u_names"]
    assert np.allclose(a, lin["A"], rtol=1e-12, atol=1e-12)
    assert np.allclose(b, lin["B"], rtol=1e-12, atol=1e-12)
    # at t = 0.5 s of the free swing: the FMU's state and simulate's row are the same state
    a5, b5, _, _ = linearize_fmpy.linear_model(fmu2, time=0.5, step=0.01)
    csv = tmp_path / "r.csv"
    subprocess.run([triad_bin, "simulate", spec, "--stop", "0.5", "--step", "0.01", "-o", str(csv)], check=True, capture_output=True)
    lin5 = _triad_linear(triad_bin, spec, "--at", str(csv), "--time", "0.5")
    assert np.allclose(a5, lin5["A"], rtol=1e-10, atol=1e-10), np.abs(a5 - np.array(lin5["A"])).max()
    assert np.allclose(b5, lin5["B"], rtol=1e-10, atol=1e-10)
    assert np.abs(a5 - a).max() > 1e-3, "the operating point moved"


def _gripper_without_friction(tmp_path):
    """The example gripper without its finger's Coulomb friction, the fingers half closed."""
    root = pathlib.Path(linearize_fmpy.__file__).resolve().parent.parent
    text = (root / "examples/specs/gripper.toml").read_text()
    text = text.replace("friction = 0.2                      # N\n", "initial = { q = 0.02 }\n")
    text = text.replace("axis = [0.0, 1.0, 0.0]              # mirrored\n", "axis = [0.0, 1.0, 0.0]\ninitial = { q = 0.02 }\n")
    assert "friction =" not in text
    spec = tmp_path / "gripper0.toml"
    spec.write_text(text)
    return spec


def _build(triad, spec, out):
    pair = []
    for version in ("2", "3"):
        fmu = out / f"{spec.stem}.fmi{version}.fmu"
        subprocess.run([triad, "build", str(spec), "--fmi", version, "--platforms", "host", "-o", str(fmu)], check=True, capture_output=True)
        pair.append(str(fmu))
    return pair


def _c_d(fmu, y_names, x_names, u_names, time=0.0, step=0.01):
    """C, D of the outputs y_names through fmpy's FMI 2 getDirectionalDerivative, and the
    refusal of a dependent joint's coordinate as a known."""
    md = read_model_description(fmu)
    vr = {v.name: v.valueReference for v in md.modelVariables}
    unzip = extract(fmu)
    slave = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="cd")
    try:
        slave.instantiate()
        slave.setupExperiment(startTime=0.0)
        slave.enterInitializationMode()
        slave.exitInitializationMode()
        t = 0.0
        while t < time - 1e-12:
            slave.doStep(t, step)
            t += step
        ys = [vr[n] for n in y_names]
        cols = [slave.getDirectionalDerivative(ys, [vr[n]], [1.0]) for n in x_names + u_names]
        dependent = [n for n in y_names if n.endswith(".q") and n not in x_names]
        refused = None
        if dependent:
            try:
                slave.getDirectionalDerivative(ys[:1], [vr[dependent[0]]], [1.0])
            except FMICallException as e:
                refused = e
        slave.terminate()
    finally:
        slave.freeInstance()
        shutil.rmtree(unzip, ignore_errors=True)
    j = np.array(cols).T.reshape(len(ys), len(x_names) + len(u_names))
    return j[:, : len(x_names)], j[:, len(x_names) :], refused


def _fmi3_a(fmu):
    """A through FMI 3 (fmpy's FMU3Slave) at the start."""
    md = read_model_description(fmu)
    unzip = extract(fmu)
    slave = FMU3Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="a3")
    try:
        slave.instantiate()
        slave.enterInitializationMode(startTime=0.0)
        slave.exitInitializationMode()
        ders = [d.variable.valueReference for d in md.derivatives]
        states = [d.variable.derivative.valueReference for d in md.derivatives]
        a = np.array([slave.getDirectionalDerivative(ders, [s], [1.0]) for s in states]).T
        slave.terminate()
    finally:
        slave.freeInstance()
        shutil.rmtree(unzip, ignore_errors=True)
    return a


@pytest.mark.parametrize("name", ["four_bar", "slider_crank", "gripper"])
def test_loop_fmu_jacobian_equals_linearize(name, built, triad_bin, tmp_path):
    """Closed loops and couplings: the FMU declares triad linearize's independent coordinates
    as its states; A, B, C, D through fmpy equal the command's, at the start and later; fmpy
    validate stays clean (FMI 2 and 3); a dependent joint as a known is refused."""
    if name == "gripper":
        spec = _gripper_without_friction(tmp_path)
        fmu2, fmu3 = _build(triad_bin, spec, tmp_path)
    else:
        root = pathlib.Path(linearize_fmpy.__file__).resolve().parent.parent
        spec = root / "modelDescription" / name / "spec.toml"
        fmu2, fmu3 = built(name)
    assert validate_fmu(fmu2) == [] and validate_fmu(fmu3) == []
    md = read_model_description(fmu2)
    assert md.coSimulation.providesDirectionalDerivative
    lin = _triad_linear(triad_bin, spec)
    nx = len(lin["x_names"])
    assert len(md.derivatives) == nx
    a, b, xs, us = linearize_fmpy.linear_model(fmu2)
    assert xs == lin["x_names"] and us == lin["u_names"]
    assert np.allclose(a, lin["A"], rtol=1e-12, atol=1e-12)
    assert np.allclose(b, lin["B"], rtol=1e-12, atol=1e-12)
    c, d, refused = _c_d(fmu2, lin["y_names"], xs, us)
    assert np.allclose(c, lin["C"], rtol=1e-12, atol=1e-12)
    assert np.allclose(d, lin["D"], rtol=1e-12, atol=1e-12)
    if name != "gripper":  # the four-bar's and slider-crank's y hold dependent joints
        assert refused is not None
    assert np.allclose(_fmi3_a(fmu3), a, rtol=1e-12, atol=1e-12)
    # later in the run: the FMU's state and simulate's row are the same state
    a5, b5, _, _ = linearize_fmpy.linear_model(fmu2, time=0.5, step=0.01)
    csv = tmp_path / "r.csv"
    subprocess.run([triad_bin, "simulate", str(spec), "--stop", "0.5", "--step", "0.01", "-o", str(csv)], check=True, capture_output=True)
    lin5 = _triad_linear(triad_bin, spec, "--at", str(csv), "--time", "0.5")
    assert lin5["x_names"] == xs
    assert np.allclose(a5, lin5["A"], rtol=1e-8, atol=1e-8), np.abs(a5 - np.array(lin5["A"])).max()
    assert np.allclose(b5, lin5["B"], rtol=1e-8, atol=1e-8)
    c5, d5, _ = _c_d(fmu2, lin5["y_names"], xs, us, time=0.5)
    assert np.allclose(c5, lin5["C"], rtol=1e-8, atol=1e-8), np.abs(c5 - np.array(lin5["C"])).max()
    assert np.allclose(d5, lin5["D"], rtol=1e-8, atol=1e-8)
