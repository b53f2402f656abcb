"""MuJoCo's `mjd_transitionFD` on a box resting on the ground (the box of
`tests/common/contact_models.rs`: 0.4 × 0.3 × 0.1 m, 2 kg, on four corners; six inputs, a force
and a torque on its free joint), timed beside triad's exact Ad, Bd of its 1 ms step
(`cargo bench --bench linearize -- step_map/box`, run it in the same session).

    python bench/transition_box_mujoco.py

Settles the box for 2 s, loads it (the inputs of `tests/step_map_contact.rs`), and prints per
integrator the best of 20 timings of one `mjd_transitionFD` (forward and centred, eps 1e-6),
the number of contacts and MuJoCo's state size (12: it has no friction bristle states)."""
import time

import mujoco
import numpy as np

XML = """<mujoco><option timestep="0.001" integrator="{integrator}"/>
<worldbody><geom type="plane" size="5 5 0.1"/>
<body name="box" pos="0 0 0.06"><freejoint name="f"/>
<geom type="box" size="0.2 0.15 0.05" mass="2"/></body></worldbody>
<actuator>{actuators}</actuator></mujoco>"""


def main():
    print(f"mujoco {mujoco.__version__}")
    gears = [" ".join("1" if i == k else "0" for i in range(6)) for k in range(6)]
    actuators = "".join(f'<general joint="f" gear="{g}"/>' for g in gears)
    for integrator in ["Euler", "implicitfast"]:
        m = mujoco.MjModel.from_xml_string(XML.format(integrator=integrator, actuators=actuators))
        d = mujoco.MjData(m)
        for _ in range(2000):
            mujoco.mj_step(m, d)
        d.ctrl[:] = [0.6, -0.4, 1.0, 0.01, -0.01, 0.02]
        mujoco.mj_forward(m, d)
        nx = 2 * m.nv + m.na
        a, b = np.zeros((nx, nx)), np.zeros((nx, m.nu))
        for centred in [False, True]:
            best = np.inf
            for _ in range(20):
                t = time.perf_counter()
                mujoco.mjd_transitionFD(m, d, 1e-6, centred, a, b, None, None)
                best = min(best, time.perf_counter() - t)
            kind = "centred" if centred else "forward"
            print(f"box ({nx} states, {m.nu} inputs, {d.ncon} contacts) {integrator:12s} {kind:8s} "
                  f"{best * 1e6:8.1f} µs")


if __name__ == "__main__":
    main()
