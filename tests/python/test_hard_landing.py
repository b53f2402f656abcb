"""A hard landing at the default step: the MJCF quadruped of `test_mjcf_stand.py` thrown forward
at 1.5 m/s (a keyframe) lands at 0.07 s on feet that skid. At its max_step of 1 ms one sub-step
of that landing is too hard for Newton; it is retaken as two halves (down to 1/16, `SPLITS` in
`src/sim.rs`), so the run goes on (it failed before). Every step taken is still an
energy-momentum step: `energy - work` holds to round-off, and the end pose agrees with a run at
a tenth of the step (measured: 2.7 mm forward, 1.8 mm in height after 0.5 s)."""
import csv
import subprocess

import numpy as np

from test_mjcf_stand import quadruped


def _run(triad_bin, xml, out, *extra):
    subprocess.run([triad_bin, "simulate", str(xml), "--keyframe", "throw", "--stop", "0.5", "--step", "0.01",
                    *extra, "-o", str(out)], check=True, capture_output=True)
    rows = list(csv.reader(out.open()))
    return rows[0], np.array(rows[1:], float)


def test_a_hard_landing_is_taken_in_halves(triad_bin, tmp_path):
    qpos = "0 0 0.35 1 0 0 0" + " 0" * 8
    qvel = "1.5" + " 0" * 13
    xml = tmp_path / "throw.xml"
    xml.write_text(quadruped().replace("</mujoco>", f'  <keyframe><key name="throw" qpos="{qpos}" qvel="{qvel}"/></keyframe>\n</mujoco>'))
    h, d = _run(triad_bin, xml, tmp_path / "coarse.csv")
    assert d[-1, h.index("time")] == 0.5
    e = d[:, h.index("system.energy")] - d[:, h.index("system.work")]
    drift = np.abs(e - e[0]).max()
    hf, f = _run(triad_bin, xml, tmp_path / "fine.csv", "--set", "solver.max_step=1e-4")
    dx = abs(d[-1, h.index("body.torso.r[1]")] - f[-1, hf.index("body.torso.r[1]")])
    dz = abs(d[-1, h.index("body.torso.r[3]")] - f[-1, hf.index("body.torso.r[3]")])
    print(f"hard landing: energy - work drift {drift:.2e} J of {abs(e[0]):.1f}; "
          f"against max_step 1e-4: {dx * 1e3:.2f} mm forward, {dz * 1e3:.2f} mm height")
    assert drift < 1e-11 * abs(e[0])
    assert dx < 0.01 and dz < 0.01
