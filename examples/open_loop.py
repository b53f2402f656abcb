#!/usr/bin/env python3
"""Open loop under fmpy: drive every input of a triad FMU from a table (piecewise constant:
+A for the first half of the run, -A for the second) and write the outputs to CSV.

    python examples/open_loop.py path/to/model.fmu [--amplitude 0.5] [--stop T] [-o out.csv]

Inputs of a triad FMU are held constant over each communication step, so a table that changes
only at communication points is reproduced exactly.
"""
import argparse

import numpy as np
from fmpy import read_model_description, simulate_fmu
from fmpy.util import write_csv


def input_table(md, amplitude, start, stop, step):
    names = [v.name for v in md.modelVariables if v.causality == "input"]
    if not names:
        return names, None
    # switch at a communication point; fmpy applies the value at the step's start time
    half = start + step * round((stop - start) / (2 * step))
    rows = [(start, amplitude), (half - 1e-12, amplitude), (half, -amplitude), (stop, -amplitude)]
    table = np.array([(t, *([a] * len(names))) for t, a in rows], dtype=[("time", float)] + [(n, float) for n in names])
    return names, table


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("fmu")
    p.add_argument("--amplitude", type=float, default=0.5, help="input magnitude (N.m or N)")
    p.add_argument("--stop", type=float)
    p.add_argument("-o", "--output", default="open_loop.csv")
    a = p.parse_args()
    md = read_model_description(a.fmu)
    ex = md.defaultExperiment
    start, step = float(ex.startTime or 0.0), float(ex.stepSize)
    stop = a.stop if a.stop is not None else float(ex.stopTime)
    names, table = input_table(md, a.amplitude, start, stop, step)
    res = simulate_fmu(a.fmu, start_time=start, stop_time=stop, output_interval=step, input=table)
    write_csv(a.output, res)
    print(f"inputs: {', '.join(names) or '(none)'}; {len(res)} rows written to {a.output}")
    for name in ("system.energy", "system.work"):
        if name in res.dtype.names:
            print(f"{name} at t = {res['time'][-1]:g}: {res[name][-1]:.9g}")


if __name__ == "__main__":
    main()
