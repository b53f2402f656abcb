"""Closed loop on space_arm (examples/space_arm.py), a free-floating satellite bus with a
seven-joint arm and no gravity: a joint PD loop in Python drives the arm to its target pose
(max error < 1e-2 rad after the default 30 s), the bus turns in reaction (by more than 10 deg),
and the total angular momentum system.L stays at its initial value to <= 1e-12 of the largest
angular momentum of any single body during the run (the joint torques are internal forces and
the integrator's discrete momentum balance is exact)."""
import math

import space_arm


def test_pd_loop_turns_the_bus_and_keeps_angular_momentum(space_arm_fmu):
    r = space_arm.closed_loop(space_arm_fmu)
    err, turn, drift = space_arm.summary(r)
    assert err < 1e-2, err
    assert math.degrees(turn) > 10.0, turn
    assert r["single_body_L_max"] > 1.0, r["single_body_L_max"]
    assert drift <= 1e-12, drift
