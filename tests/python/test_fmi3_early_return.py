"""FMI 3 early return under fmpy: the bouncing ball's FMI 3 FMU, simulated with
`early_return_allowed=True`, adds a row at every touch and lift-off (the gap 0 there, the first
at the free-fall touchdown time) and ends at the stop time; without it the rows are the FMI 2
FMU's, bit for bit."""
import subprocess
from pathlib import Path

import numpy as np
from fmpy import simulate_fmu
from fmpy.validation import validate_fmu

ROOT = Path(__file__).resolve().parent.parent.parent
SPEC = ROOT / "examples" / "specs" / "bouncing_ball.toml"


def _build(triad, out, version):
    subprocess.run([triad, "build", str(SPEC), "--fmi", version, "--platforms", "host", "-o", str(out)],
                   check=True, capture_output=True, text=True)
    return str(out)


def test_early_return_at_touch_and_lift_off(triad_bin, tmp_path):
    fmu3 = _build(triad_bin, tmp_path / "ball3.fmu", "3")
    fmu2 = _build(triad_bin, tmp_path / "ball2.fmu", "2")
    assert validate_fmu(fmu3) == []
    early = simulate_fmu(fmu3, stop_time=1.5, output_interval=0.01, early_return_allowed=True)
    t = early["time"]
    off_grid = [k for k, x in enumerate(t) if abs(x * 100 - round(x * 100)) > 1e-9]
    assert len(off_grid) >= 6, t[off_grid]
    assert abs(t[off_grid[0]] - np.sqrt(2 * 0.9 / 9.81)) < 1e-5
    assert np.abs(early["contact.shell.gap"][off_grid]).max() < 1e-6
    assert t[-1] == 1.5
    plain = simulate_fmu(fmu3, stop_time=1.5, output_interval=0.01)
    fmi2 = simulate_fmu(fmu2, stop_time=1.5, output_interval=0.01)
    assert np.array_equal(plain["body.ball.r"][:, 2], fmi2["body.ball.r[3]"])
