"""MuJoCo's `mjd_transitionFD` (the step's A, B by finite differences) on the peers' chainN with
a motor on every joint (2N states, N inputs), timed beside triad's exact Ad, Bd of the same
chain (`cargo bench --bench linearize -- step_map`, run it in the same session).

    python bench/transition_mujoco.py [N ...]     (default: 10 100)

Prints, per chain and MuJoCo integrator (Euler, implicitfast; MuJoCo refuses RK4 here), the
best of 5 timings of one `mjd_transitionFD`
(forward differences, eps 1e-6, and centred) at the chain's initial state with a 1 ms step."""
import os
import sys
import time

import mujoco
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "shared", "peers"))
import nmodel as nm  # noqa: E402
from engines.mujoco_engine import to_mjcf  # noqa: E402


def model_xml(n, integrator):
    model = nm.load(f"chain{n}")
    xml = to_mjcf(model, integrator, 1e-3)
    motors = "".join(f'    <motor joint="{j["name"]}"/>\n' for j in model["joints"])
    xml = xml.replace("</mujoco>", f"  <actuator>\n{motors}  </actuator>\n</mujoco>")
    return model, xml


def time_transition(n, integrator, centred):
    model, xml = model_xml(n, integrator)
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    q0, v0 = nm.initial_qv(model)
    d.qpos[:] = q0
    d.qvel[:] = v0
    mujoco.mj_forward(m, d)
    nx, nu = 2 * m.nv + m.na, m.nu
    a, b = np.zeros((nx, nx)), np.zeros((nx, nu))
    best = np.inf
    for _ in range(5):
        t = time.perf_counter()
        mujoco.mjd_transitionFD(m, d, 1e-6, centred, a, b, None, None)
        best = min(best, time.perf_counter() - t)
    return best, nx, nu


def main():
    ns = [int(x) for x in sys.argv[1:]] or [10, 100]
    print(f"mujoco {mujoco.__version__}")
    for n in ns:
        for integrator in ["Euler", "implicitfast"]:  # RK4: "not supported" by mjd_transitionFD
            for centred in [False, True]:
                t, nx, nu = time_transition(n, integrator, centred)
                kind = "centred" if centred else "forward"
                print(f"chain{n} ({nx} states, {nu} inputs) {integrator:12s} {kind:8s} {t * 1e3:9.3f} ms")


if __name__ == "__main__":
    main()
