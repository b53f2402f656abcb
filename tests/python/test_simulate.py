"""fmpy simulates every shipped FMU, and its results equal `triad simulate`'s for the same model
and inputs: both run the same `Simulation` (communication step = ceil(H/max_step) equal
sub-steps), so with constant inputs every output agrees to 1e-12 (relative, floor 1)."""
import csv
import os
import subprocess
import tempfile
import zipfile

import numpy as np
from fmpy import read_model_description, simulate_fmu


def _inputs(md):
    return [v.name for v in md.modelVariables if v.causality == "input"]


def test_fmpy_equals_triad_simulate(fmu, triad_bin):
    md = read_model_description(fmu)
    ex = md.defaultExperiment
    h = float(ex.stepSize)
    stop = float(ex.startTime or 0.0) + min(float(ex.stopTime) - float(ex.startTime or 0.0), 50 * h)
    names = _inputs(md)
    values = [0.05 * (i + 1) * (-1) ** i for i in range(len(names))]
    with tempfile.TemporaryDirectory() as d:
        spec = os.path.join(d, "model.json")
        with zipfile.ZipFile(fmu) as z, open(spec, "wb") as f:
            f.write(z.read("resources/model.json"))
        cmd = [triad_bin, "simulate", spec, "--stop", repr(stop), "--step", repr(h), "-o", os.path.join(d, "out.csv")]
        sig = None
        if names:
            with open(os.path.join(d, "in.csv"), "w", newline="") as f:
                w = csv.writer(f)
                w.writerow(["time"] + names)
                w.writerow([0.0] + values)
            cmd += ["--input", os.path.join(d, "in.csv")]
            sig = np.array([(0.0, *values), (stop, *values)], dtype=[("time", float)] + [(n, float) for n in names])
        subprocess.run(cmd, check=True, capture_output=True, timeout=600)
        with open(os.path.join(d, "out.csv"), newline="") as f:
            rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    res = simulate_fmu(fmu, stop_time=stop, output_interval=h, input=sig)
    assert len(res) == len(data), (len(res), len(data))
    assert np.allclose(res["time"], data[:, 0], rtol=0, atol=1e-9 * max(1.0, stop))
    outputs = [v.name for v in md.modelVariables if v.causality == "output"]
    assert outputs and set(outputs) <= set(header)
    worst = 0.0
    for name in outputs:
        a = np.asarray(res[name], dtype=float)
        b = data[:, header.index(name)]
        worst = max(worst, float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b)))))
    assert worst <= 1e-12, worst
