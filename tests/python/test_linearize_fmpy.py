"""examples/linearize_fmpy.py: A, B of an FMU through fmpy's getDirectionalDerivative equal
`triad linearize`'s, at the start and at a later communication point; fmpy validate stays
clean with the states declared."""
import json
import subprocess

import numpy as np
from fmpy import read_model_description
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
