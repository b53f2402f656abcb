#!/usr/bin/env python3
"""Changing parameters without rebuilding the FMU: fmpy passes them as start values, set in
Instantiated mode before initialisation (fixed parameters such as `gravity[3]`,
`joint.<j>.q0`, `solver.max_step`) — the simulation is built from them at
fmi2EnterInitializationMode. Tunable ones (`joint.<j>.damping`, `joint.<j>.stiffness`) could also
be changed between steps.

    python examples/parameters.py path/to/model.fmu [--stop T]

Runs the FMU twice, with the spec's values and with changed ones, and prints the difference.
"""
import argparse

from fmpy import read_model_description, simulate_fmu


def changed_parameters(md):
    """A few parameters of this model with new values: weaker gravity, damping on the first
    joint, a smaller internal step, a different initial angle."""
    start = {v.name: float(v.start) for v in md.modelVariables if v.causality == "parameter" and v.start is not None}
    new = {}
    if "gravity[3]" in start:
        new["gravity[3]"] = 0.5 * start["gravity[3]"]
    for name, value in start.items():
        if name.endswith(".damping"):
            new[name] = value + 0.5
            break
    for name, value in start.items():
        if name.startswith("joint.") and (name.endswith(".q0") or name.endswith(".q0[1]")):
            new[name] = value + 0.2
            break
    if "solver.max_step" in start:
        new["solver.max_step"] = 0.5 * start["solver.max_step"]
    return start, new


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu")
    p.add_argument("--stop", type=float)
    a = p.parse_args()
    md = read_model_description(a.fmu)
    stop = a.stop if a.stop is not None else float(md.defaultExperiment.stopTime)
    start, new = changed_parameters(md)
    base = simulate_fmu(a.fmu, stop_time=stop)
    changed = simulate_fmu(a.fmu, stop_time=stop, start_values=new)
    for name, value in new.items():
        print(f"{name:>28}: {start[name]:g} -> {value:g}")
    for name in ("system.energy", "system.work"):
        print(f"{name:>28} at t = {stop:g}: {base[name][-1]:.9g} (spec values) vs {changed[name][-1]:.9g} (changed)")


if __name__ == "__main__":
    main()
