"""examples/lqr_balance.py: a discrete LQR designed on `triad linearize`'s Ad, Bd of the
cart-pole (examples/specs/cart_pole.toml) balances the cart-pole FMU under fmpy from 0.15 rad off
upright within 5 s; without the controller the pole falls. Ad, Bd are the sampled flow of the
exact A, B to the step's own accuracy."""
import subprocess
import sys

import numpy as np
import scipy.linalg

import lqr_balance


def test_lqr_balances_the_cart_pole(triad_bin):
    proc = subprocess.run([sys.executable, str(lqr_balance.ROOT / "examples" / "lqr_balance.py"), "--triad", triad_bin],
                          capture_output=True, text=True, timeout=120)
    print(proc.stdout)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert "balanced" in proc.stdout


def test_linear_model_of_the_upright_cart_pole(triad_bin):
    lin = lqr_balance.linear_model(triad_bin)
    assert lin["x_names"] == ["joint.cart.q", "joint.pole.q", "joint.cart.qd", "joint.pole.qd"]
    assert lin["u_names"] == ["joint.cart.f"]
    assert not np.any(lin["x0"]) and not np.any(lin["xdot0"]), "the spec starts at the upright equilibrium"
    # the textbook cart-pole (cart M, pole m, COM at l above the pin, inertia I about the COM):
    # with D = (M + m)(I + m l^2) - (m l)^2, pole-angle row g m l (M + m)/D, input rows
    # (I + m l^2)/D and -m l/D (the force along +x tips the pole towards -x: negative about +y)
    big_m, m, l, inertia, g = 1.0, 0.3, 0.5, 0.025, 9.81
    d = (big_m + m) * (inertia + m * l * l) - (m * l) ** 2
    a = np.zeros((4, 4))
    a[0, 2] = a[1, 3] = 1.0
    a[2, 1] = -(m * l) ** 2 * g / d
    a[3, 1] = m * g * l * (big_m + m) / d
    b = np.array([[0.0], [0.0], [(inertia + m * l * l) / d], [-m * l / d]])
    assert np.allclose(lin["A"], a, rtol=1e-13, atol=1e-13), lin["A"]
    assert np.allclose(lin["B"], b, rtol=1e-13, atol=1e-13), lin["B"]


def test_without_control_the_pole_falls(triad_bin, tmp_path):
    lin = lqr_balance.linear_model(triad_bin)
    fmu = tmp_path / "cart_pole.fmu"
    subprocess.run([triad_bin, "build", str(lqr_balance.SPEC), "--platforms", "host", "-o", str(fmu)], check=True, capture_output=True)
    _, x, _ = lqr_balance.balance(fmu, lin, np.zeros((1, 4)), angle=0.15, stop=1.0)
    assert abs(x[-1, 1]) > 1.0, x[-1]


def test_discrete_model_is_the_sampled_flow(triad_bin):
    """At the equilibrium the flow's map over h is expm(A h), and the held input's is
    int_0^h expm(A s) ds B; the step reproduces both to its own error (midpoint: O(h max_step^2),
    measured 2.6e-7 for Ad at h = 0.01, max_step = 1e-3), and the discrete LQR on Ad, Bd puts
    every closed-loop eigenvalue inside the unit circle."""
    lin = lqr_balance.linear_model(triad_bin, step=0.01)
    h = float(lin["h"])
    assert h == 0.01
    a, b = lin["A"], lin["B"]
    n, m = b.shape
    blk = np.zeros((n + m, n + m))
    blk[:n, :n], blk[:n, n:] = a * h, b * h
    e = scipy.linalg.expm(blk)
    ad, bd = e[:n, :n], e[:n, n:]
    assert np.abs(lin["Ad"] - ad).max() < 1e-6, lin["Ad"] - ad
    assert np.abs(lin["Bd"] - bd).max() < 1e-5 * np.abs(bd).max(), lin["Bd"] - bd
    # and not trivially: the same comparison at a step 100 times longer is off by far more
    coarse = lqr_balance.linear_model(triad_bin, step=1.0)
    assert np.abs(coarse["Ad"] - scipy.linalg.expm(a)).max() > 1e-4
    _, poles = lqr_balance.lqr(lin["Ad"], lin["Bd"])
    assert np.all(np.abs(poles) < 1.0), poles
    assert np.any(np.abs(np.linalg.eigvals(lin["Ad"])) > 1.0), "the upright pole is unstable"
