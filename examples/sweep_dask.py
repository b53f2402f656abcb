#!/usr/bin/env python3
"""Parameter sweep in parallel processes with Dask: one fmpy simulation per damping value of the
first joint (a tunable parameter passed as a start value — no rebuild), each in its own worker
process (triad instances share nothing, so this is also safe with threads).

    python examples/sweep_dask.py path/to/model.fmu [--values 0 0.1 0.5 1 2] [--workers 4]

Prints the dissipated energy -work(T) for each damping value.
"""
import argparse

import dask
from fmpy import read_model_description, simulate_fmu


def run(fmu, name, value, stop):
    res = simulate_fmu(fmu, stop_time=stop, start_values={name: value})
    return value, float(res["system.energy"][-1]), float(res["system.work"][-1])


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu")
    p.add_argument("--values", type=float, nargs="+", default=[0.0, 0.1, 0.5, 1.0, 2.0])
    p.add_argument("--stop", type=float)
    p.add_argument("--workers", type=int, default=4)
    a = p.parse_args()
    md = read_model_description(a.fmu)
    names = [v.name for v in md.modelVariables if v.causality == "parameter" and v.name.endswith(".damping")]
    if not names:
        raise SystemExit(f"{a.fmu}: the model has no joint damping parameter to sweep")
    stop = a.stop if a.stop is not None else float(md.defaultExperiment.stopTime)
    tasks = [dask.delayed(run)(a.fmu, names[0], v, stop) for v in a.values]
    results = dask.compute(*tasks, scheduler="processes", num_workers=a.workers)
    print(f"sweep of {names[0]} over {len(results)} values, t = {stop:g} s")
    print(f"{'damping':>10} {'energy':>16} {'dissipated':>16}")
    for value, energy, work in results:
        print(f"{value:>10g} {energy:>16.9g} {-work:>16.9g}")


if __name__ == "__main__":
    main()
