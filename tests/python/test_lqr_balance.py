"""examples/lqr_balance.py: an LQR designed on `triad linearize`'s A, B of the cart-pole
(examples/specs/cart_pole.toml) balances the cart-pole FMU under fmpy from 0.15 rad off upright
within 5 s; without the controller the pole falls."""
import subprocess
import sys

import numpy as np

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
