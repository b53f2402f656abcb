#!/usr/bin/env python3
"""Pinocchio's exact derivatives of the forward dynamics (`computeABADerivatives`: dq̈/dq,
dq̈/dv and M⁻¹) on the shipped robot arm's URDF at rest in its zero pose, the reference of
BENCHMARKS.md "Linearisation" beside `cargo bench --bench linearize -- linearize/robot_arm`.

    .venv/bin/python bench/aba_pinocchio.py
"""
import pathlib
import time

import numpy as np
import pinocchio as pin

URDF = pathlib.Path(__file__).resolve().parent.parent / "modelDescription" / "robot_arm" / "robot_arm.urdf"


def main():
    model = pin.buildModelFromUrdf(str(URDF))
    data = model.createData()
    q, v, tau = pin.neutral(model), np.zeros(model.nv), np.zeros(model.nv)
    for _ in range(2000):
        pin.computeABADerivatives(model, data, q, v, tau)
    best = float("inf")
    for _ in range(20):
        n = 5000
        t0 = time.perf_counter()
        for _ in range(n):
            pin.computeABADerivatives(model, data, q, v, tau)
        best = min(best, (time.perf_counter() - t0) / n)
    print(f"pinocchio {pin.__version__} computeABADerivatives robot_arm (nv = {model.nv}): {best * 1e6:.2f} µs "
          "(best of 20 × 5000, Python call included)")


if __name__ == "__main__":
    main()
