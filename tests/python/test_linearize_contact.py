"""Linear models with contact: the MJCF quadruped of `test_mjcf_stand.py` (position servos,
sphere feet, MuJoCo's default contact) stands after a 2.5 cm drop; `triad linearize` at its row
of the result at 3 s gives x = (q, ν, σ) with the feet's sticking bristles `contact.F.s[i]`
(fitted to the point: the result does not record them).

What the model must show (`docs/guide/linear_models.md`, "Contact and joint friction"):
- rank A = 2n: the stance holds every coordinate (springs of the feet, servos);
- exactly one zero eigenvalue per bristle state: every placement of the feet's anchors is an
  equilibrium, a family of dimension 8;
- every other mode decays: the stance is stable;
- the step's map `Ad` of one communication step keeps one eigenvalue 1 per bristle state and
  contracts every other mode.
"""
import json
import subprocess

import numpy as np
import pytest

from test_mjcf_stand import quadruped


def test_a_standing_quadruped_has_the_right_rank_and_stable_modes(triad_bin, tmp_path):
    xml = tmp_path / "quadruped.xml"
    xml.write_text(quadruped())
    out = tmp_path / "stand.csv"
    subprocess.run([triad_bin, "simulate", str(xml), "--stop", "3", "--step", "0.01", "-o", str(out)],
                   check=True, capture_output=True)
    lin = tmp_path / "stand.json"
    run = subprocess.run([triad_bin, "linearize", str(xml), "--at", str(out), "--time", "3", "-o", str(lin)],
                         check=True, capture_output=True, text=True)
    assert "fitted" in run.stderr, run.stderr
    d = json.loads(lin.read_text())
    names = d["x_names"]
    bristles = [n for n in names if n.startswith("contact.")]
    assert bristles == [f"contact.{leg}_foot.s[{i}]" for leg in ("fl", "fr", "hl", "hr") for i in (1, 2)]
    nx, ns = len(names), len(bristles)
    n = (nx - ns) // 2
    assert n == 6 + 8
    A = np.array(d["A"])
    assert np.abs(d["xdot0"]).max() < 1e-6, "the stance is an equilibrium"
    ev = np.linalg.eigvals(A)
    scale = np.abs(ev).max()
    zero = np.abs(ev) < 1e-8 * scale
    print(f"quadruped: {nx} states, rank {np.linalg.matrix_rank(A)}, {zero.sum()} zero eigenvalues, "
          f"slowest decaying mode Re = {ev.real[~zero].max():.3f} 1/s, fastest |λ| = {scale:.3e}")
    assert np.linalg.matrix_rank(A, tol=1e-10 * np.abs(A).max()) == 2 * n
    assert zero.sum() == ns
    assert (ev.real[~zero] < -1e-3).all()
    # the step's map of one communication step h (the bristles states too): the anchors'
    # family stays (one eigenvalue 1 per bristle state), every other mode contracts
    Ad, h = np.array(d["Ad"]), d["h"]
    assert Ad.shape == (nx, nx) and np.array(d["Bd"]).shape[0] == nx
    mu = np.linalg.eigvals(Ad)
    one = np.abs(mu - 1) < 1e-6
    print(f"quadruped: Ad of h = {h} s: {one.sum()} eigenvalues 1, the largest other |μ| = "
          f"{np.abs(mu[~one]).max():.6f} (exp(h·slowest Re λ) = {np.exp(h * ev.real[~zero].max()):.6f})")
    assert one.sum() == ns
    assert np.abs(mu[~one]).max() < 1


def test_a_sliding_quadruped_is_named(triad_bin, tmp_path):
    """Thrown forward at 1.5 m/s (a keyframe) on slippery ground (μ = 0.1), it lands and its
    feet slide. A result does not record the bristles, so they are fitted to the row: at 0.1 s
    no fit holds the feet inside the cone, refused with the foot named; at 0.15 s a fit does
    (as if the feet stuck), and the note says how fast the feet move (over a metre per
    second), so the user sees that they slide."""
    xml = tmp_path / "quadruped.xml"
    qpos = "0 0 0.35 1 0 0 0" + " 0" * 8
    qvel = "1.5" + " 0" * 13
    text = quadruped().replace('friction="1 0.005 0.0001"', 'friction="0.1 0.005 0.0001"')
    assert "0.1 0.005" in text
    xml.write_text(text.replace("</mujoco>", f'  <keyframe><key name="throw" qpos="{qpos}" qvel="{qvel}"/></keyframe>\n</mujoco>'))
    out = tmp_path / "slide.csv"
    subprocess.run([triad_bin, "simulate", str(xml), "--keyframe", "throw", "--stop", "0.2", "--step", "0.01",
                    "--set", "solver.max_step=2e-4", "-o", str(out)], check=True, capture_output=True)

    def linearize(t):
        return subprocess.run([triad_bin, "linearize", str(xml), "--keyframe", "throw", "--at", str(out),
                               "--time", str(t), "-o", "-"], capture_output=True, text=True)

    run = linearize(0.1)
    assert run.returncode != 0
    assert "_foot (point 1) slides at the operating point" in run.stderr, run.stderr
    run = linearize(0.15)
    assert run.returncode == 0, run.stderr
    note = next(line for line in run.stderr.splitlines() if "fitted" in line)
    speed = float(note.split("move at up to ")[1].split()[0])
    assert speed > 1.0, note
