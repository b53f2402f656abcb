"""Closed loop on robot_arm (examples/closed_loop.py): a PD controller in Python sets every
`joint.<j>.tau` from `joint.<j>.q`, `joint.<j>.qd` once per communication step. The arm reaches
its set point (max error < 0.01 rad after the default 3 s), and `system.energy - system.work`
stays constant to 1e-9 relative: the integrator's discrete energy balance is exact up to the
Newton tolerance, also with inputs that change at every communication point."""
import closed_loop


def test_pd_loop_reaches_set_point_and_balances_energy(robot_arm):
    r = closed_loop.closed_loop(robot_arm)
    err, drift = closed_loop.summary(r)
    assert err < 1e-2, err
    assert drift < 1e-9, drift
