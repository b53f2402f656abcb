#!/usr/bin/env python3
"""Balance the cart-pole (examples/specs/cart_pole.toml) with a discrete LQR designed on triad's
exact discrete-time linear model of the FMU's own communication step, and run it in closed loop
on the cart-pole FMU under fmpy.

    python examples/lqr_balance.py [--triad target/release/triad] [--angle 0.15] [--stop 5] [--step 0.01]

1. `triad linearize examples/specs/cart_pole.toml --step 0.01 -o -` gives Ad, Bd (JSON on
   standard output): the exact derivatives of one communication step of 0.01 s from the spec's
   initial state, the upright equilibrium, with the inputs held over the step as the FMU holds
   them; x = (cart q, pole q, cart qd, pole qd), u = joint.cart.f;
2. the discrete LQR gain K = (R + Bd^T P Bd)^-1 Bd^T P Ad, P from
   scipy.linalg.solve_discrete_are: the gain of exactly the sampled loop that runs;
3. `triad build` makes the FMU; fmpy's FMU2Slave runs it from the pole `--angle` rad off upright
   (the start value joint.pole.q0), the force u = u0 - K (x - x0) computed from the FMU's outputs
   once per communication step and held over the step.

Prints the closed-loop eigenvalues (of Ad - Bd K: inside the unit circle), the gain, the final pole angle and cart position; exits non-zero if
the pole is not back upright (|angle| >= 0.01 rad) at the end.
"""
import argparse
import json
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import scipy.linalg
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

ROOT = Path(__file__).resolve().parent.parent
SPEC = ROOT / "examples" / "specs" / "cart_pole.toml"
Q = np.diag([10.0, 10.0, 1.0, 1.0])  # state weights: cart q (m), pole q (rad), their rates
R = np.array([[0.1]])  # input weight, 1/N^2
UPRIGHT = 0.01  # rad: |pole angle| at the end below this counts as balanced


def linear_model(triad, spec=SPEC, step=0.01):
    """triad's linear model of `spec` at its initial state (continuous A, B, C, D and the
    discrete Ad, Bd of one communication `step`), as a dict of numpy arrays and names."""
    cmd = [triad, "linearize", str(spec), "--step", str(step), "-o", "-"]
    out = subprocess.run(cmd, check=True, capture_output=True, text=True)
    d = json.loads(out.stdout)
    return {k: (np.array(v, dtype=float) if k not in ("x_names", "u_names", "y_names") else v) for k, v in d.items()}


def lqr(ad, bd, q=Q, r=R):
    """The discrete-time LQR gain K (u = -K x, held over each step) and the closed-loop
    eigenvalues of Ad - Bd K."""
    p = scipy.linalg.solve_discrete_are(ad, bd, q, r)
    k = np.linalg.solve(r + bd.T @ p @ bd, bd.T @ p @ ad)
    return k, np.linalg.eigvals(ad - bd @ k)


def balance(fmu_path, lin, k, angle=0.15, stop=5.0, step=0.01):
    """Runs the loop from the pole `angle` rad off upright; returns (time, x rows, u rows) with x
    in the order of lin["x_names"]."""
    md = read_model_description(str(fmu_path))
    vr = {v.name: v.valueReference for v in md.modelVariables}
    x_vr = [vr[name] for name in lin["x_names"]]
    u_vr = [vr[name] for name in lin["u_names"]]
    x0, u0 = lin["x0"], lin["u0"]
    unzip = extract(str(fmu_path))
    fmu = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier, instanceName="cart_pole")
    times, xs, us = [], [], []
    try:
        fmu.instantiate()
        fmu.setupExperiment(startTime=0.0)
        fmu.setReal([vr["joint.pole.q0"]], [angle])
        fmu.enterInitializationMode()
        fmu.exitInitializationMode()
        n = int(round(stop / step))
        for i in range(n + 1):
            t = i * step
            x = np.array(fmu.getReal(x_vr))
            u = u0 - k @ (x - x0)
            times.append(t)
            xs.append(x)
            us.append(u)
            if i == n:
                break
            fmu.setReal(u_vr, list(u))
            fmu.doStep(currentCommunicationPoint=t, communicationStepSize=step)
        fmu.terminate()
    finally:
        fmu.freeInstance()
        shutil.rmtree(unzip, ignore_errors=True)
    return np.array(times), np.array(xs), np.array(us)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--triad", default=str(ROOT / "target" / "release" / "triad"))
    p.add_argument("--angle", type=float, default=0.15, help="initial pole angle off upright, rad")
    p.add_argument("--stop", type=float, default=5.0)
    p.add_argument("--step", type=float, default=0.01, help="communication step, s")
    a = p.parse_args()

    lin = linear_model(a.triad, step=a.step)
    assert lin["x_names"] == ["joint.cart.q", "joint.pole.q", "joint.cart.qd", "joint.pole.qd"], lin["x_names"]
    assert lin["u_names"] == ["joint.cart.f"], lin["u_names"]
    k, poles = lqr(lin["Ad"], lin["Bd"])
    print("open-loop eigenvalues of Ad:  " + ", ".join(f"{e:.4g}" for e in np.linalg.eigvals(lin["Ad"])))
    print("closed-loop eigenvalues:      " + ", ".join(f"{e:.4g}" for e in poles))
    print("K = " + np.array2string(k.ravel(), precision=4))
    with tempfile.TemporaryDirectory() as tmp:
        fmu = Path(tmp) / "cart_pole.fmu"
        subprocess.run([a.triad, "build", str(SPEC), "--platforms", "host", "-o", str(fmu)], check=True, capture_output=True)
        t, x, u = balance(fmu, lin, k, a.angle, a.stop, a.step)
    i_pole, i_cart = lin["x_names"].index("joint.pole.q"), lin["x_names"].index("joint.cart.q")
    print(f"start: pole {x[0, i_pole]:+.4f} rad; peak force {np.abs(u).max():.3f} N")
    print(f"t = {t[-1]:.2f} s: pole angle {x[-1, i_pole]:+.3e} rad, cart position {x[-1, i_cart]:+.3e} m")
    if not abs(x[-1, i_pole]) < UPRIGHT:
        print(f"the pole is not upright: |angle| = {abs(x[-1, i_pole]):.3e} >= {UPRIGHT} rad", file=sys.stderr)
        sys.exit(1)
    print("balanced")


if __name__ == "__main__":
    main()
