#!/usr/bin/env python3
"""The linear model A, B of a triad FMU at a communication point, from the FMU alone, through
fmpy's getDirectionalDerivative (exact: the FMU computes the derivatives analytically).

    python examples/linearize_fmpy.py MODEL.fmu [--time T] [--step H] [-o OUT.npz]

The FMU declares its states in <ModelStructure><Derivatives> (the joint coordinates and rates
of a tree without contact or joint friction; with closed loops or couplings, the independent
coordinates and rates that `triad linearize` picks at the model's initial state, e.g. the
four-bar's crank); A = d(derivatives)/d(states) and B = d(derivatives)/d(inputs), one
directional derivative per column. With --time the FMU first runs to T (inputs 0, steps H).
Prints the state and input names and the eigenvalues of A; writes A, B and the names to OUT.npz.
"""
import argparse
import shutil
import sys

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


def linear_model(fmu_path, time=0.0, step=0.01):
    """(A, B, state names, input names) of the FMU at `time`."""
    md = read_model_description(fmu_path)
    if not md.coSimulation.providesDirectionalDerivative:
        raise SystemExit(f"{fmu_path}: the FMU provides no directional derivatives (a model with contact or joint friction)")
    unzip = extract(fmu_path)
    slave = FMU2Slave(guid=md.guid, unzipDirectory=unzip, modelIdentifier=md.coSimulation.modelIdentifier,
                      instanceName="linearize")
    try:
        slave.instantiate()
        slave.setupExperiment(startTime=0.0)
        slave.enterInitializationMode()
        slave.exitInitializationMode()
        t = 0.0
        while t < time - 1e-12:
            h = min(step, time - t)
            slave.doStep(t, h)
            t += h
        derivatives = [d.variable for d in md.derivatives]
        states = [d.derivative for d in derivatives]
        inputs = [v for v in md.modelVariables if v.causality == "input"]
        ders = [v.valueReference for v in derivatives]

        def column(known):
            return slave.getDirectionalDerivative(ders, [known.valueReference], [1.0])

        a = np.array([column(s) for s in states]).T
        b = np.array([column(u) for u in inputs]).T.reshape(len(ders), len(inputs))
        slave.terminate()
    finally:
        slave.freeInstance()
        shutil.rmtree(unzip, ignore_errors=True)
    return a, b, [s.name for s in states], [u.name for u in inputs]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("fmu")
    p.add_argument("--time", type=float, default=0.0)
    p.add_argument("--step", type=float, default=0.01)
    p.add_argument("-o", "--output")
    args = p.parse_args()
    a, b, xs, us = linear_model(args.fmu, args.time, args.step)
    print("x =", ", ".join(xs))
    print("u =", ", ".join(us))
    print("eigenvalues of A:", np.array2string(np.linalg.eigvals(a), precision=4))
    if args.output:
        np.savez(args.output, A=a, B=b, x_names=np.array(xs), u_names=np.array(us))
        print("wrote", args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
