"""`triad linearize`: its three file formats agree, its A and B agree with Pinocchio's analytic
derivatives of the forward dynamics on real robots, and what it refuses it refuses by name.

- Formats: robot_arm written as .json, .npz and .mat gives the same A, B, C, D, operating point
  and name lists, bit for bit, through json, numpy.load and scipy.io.loadmat.
- Pinocchio: example-robot-data's URDFs (found in the venv as test_pinocchio.py finds them; the
  6.0.0 wheel ships the data only, no `example_robot_data` Python module), linearised by triad
  straight from the URDF (`--no-limits`: no stops, no effort clamp; a bare root welded to the
  world, as Pinocchio's buildModelFromUrdf does; gravity -9.81 z in both), at seeded random joint
  states and torques. The lower half of A is compared with `pin.computeABADerivatives`
  (ddq_dq, ddq_dv), the lower half of B with Minv, the lower half of xdot0 with `pin.aba`, to a
  relative Frobenius error of 1e-9. URDF `<dynamics damping>` is a viscous torque -d qd in triad
  and unknown to Pinocchio: the reference takes tau - d v and adds -Minv diag(d) to ddq_dv.
  Joint coordinates are the same in both (triad's q of a revolute joint is Pinocchio's angle; a
  continuous joint's (cos, sin) is its angle, and Pinocchio's tangent is d(angle)): no offset, no
  sign. A floating base (solo12) is compared through the change of coordinates written out in
  `_floating_reference`.
- Armature: the same robots with a rotor inertia on every joint (`armature` written into the
  imported spec) against Pinocchio with `model.armature` set alike (its ABA and CRBA add it to
  the joint-space inertia): A, B and xdot0 to the same 1e-9.
- Errors: an unknown joint in --coordinates, a step of 0 s, an unknown output extension and an unknown input are refused
  with a message naming the problem.
"""
import json
import subprocess
import zlib

import numpy as np
import pinocchio as pin
import pytest
import scipy.io

import pinocchio_ref as ref

TOL = 1e-9  # relative Frobenius error against Pinocchio
SEEDS = (1, 2, 3)
ACCEL = 5.0  # torque amplitude per unit of mass-matrix diagonal, rad/s2

FIXED = {
    "ur5": "ur_description/urdf/ur5_robot.urdf",
    "panda": "panda_description/urdf/panda.urdf",  # prismatic fingers (inputs .f), damping
    "kinova": "kinova_description/robots/kinova.urdf",  # continuous joints (Pinocchio nq = 2)
}
FLOATING = {"solo12": "solo_description/robots/solo12.urdf"}
KEYS = ("A", "B", "C", "D", "Ad", "Bd", "x0", "u0", "y0", "xdot0")
NAMES = ("x_names", "u_names", "y_names")


def _triad(triad_bin, *args, ok=True):
    proc = subprocess.run([triad_bin, *args], capture_output=True, text=True, timeout=300)
    if ok:
        assert proc.returncode == 0, f"triad {' '.join(map(str, args))}:\n{proc.stderr}"
    return proc


def _rel(a, b):
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def _skew(w):
    return np.array([[0.0, -w[2], w[1]], [w[2], 0.0, -w[0]], [-w[1], w[0], 0.0]])


# --- formats -------------------------------------------------------------------------------


def _from_mat(path):
    m = scipy.io.loadmat(str(path))
    out = {k: np.asarray(m[k], dtype=float) for k in KEYS}
    for k in ("x0", "u0", "y0", "xdot0"):
        out[k] = out[k].ravel()
    for k in NAMES:
        cell = m[k]
        assert cell.shape[0] == 1, f"{k}: a 1 x k cell array, got shape {cell.shape}"
        out[k] = [str(np.atleast_1d(c)[0]) for c in cell.ravel()]
    out["t0"] = float(np.asarray(m["t0"]).ravel()[0])
    return out


def _from_npz(path):
    d = np.load(path)
    out = {k: np.asarray(d[k], dtype=float) for k in KEYS}
    out |= {k: [str(s) for s in d[k]] for k in NAMES}
    out["t0"] = float(d["t0"])
    return out


def _from_json(path):
    d = json.loads(path.read_text())
    out = {k: np.asarray(d[k], dtype=float) for k in KEYS}
    out |= {k: list(d[k]) for k in NAMES}
    out["t0"] = float(d["t0"])
    return out


def test_json_npz_mat_agree(triad_bin, tmp_path):
    args = ["--set", "joint.elbow.q0=0.7", "--set", "joint.shoulder_lift.qd0=-0.4", "--u", "joint.wrist_1.tau=1.5"]
    read = {".json": _from_json, ".npz": _from_npz, ".mat": _from_mat}
    got = {}
    for ext, reader in read.items():
        out = tmp_path / f"arm{ext}"
        _triad(triad_bin, "linearize", "robot_arm", *args, "-o", str(out))
        got[ext] = reader(out)
    ref_ = got[".json"]
    n, m, p = len(ref_["x_names"]), len(ref_["u_names"]), len(ref_["y_names"])
    assert (n, m) == (12, 6) and p > 0
    assert ref_["A"].shape == (n, n) and ref_["B"].shape == (n, m)
    assert ref_["C"].shape == (p, n) and ref_["D"].shape == (p, m)
    assert np.any(ref_["A"][n // 2:, : n // 2]), "gravity couples the joints: d qdd/dq is not zero"
    for ext, other in got.items():
        for k in KEYS:
            assert other[k].shape == ref_[k].shape, (ext, k)
            assert np.array_equal(other[k], ref_[k]), f"{ext} {k} differs from .json"
        for k in NAMES:
            assert other[k] == ref_[k], f"{ext} {k} differs from .json"
        assert other["t0"] == ref_["t0"] == 0.0
    assert ref_["x0"][ref_["x_names"].index("joint.elbow.q")] == 0.7
    assert ref_["u0"][ref_["u_names"].index("joint.wrist_1.tau")] == 1.5


# --- against Pinocchio ---------------------------------------------------------------------


class Linearized:
    """triad's linear model of one robot at one state, with index maps to Pinocchio's order."""

    def __init__(self, path):
        d = np.load(path)
        self.A, self.B, self.xdot0 = d["A"], d["B"], d["xdot0"]
        self.x = {str(s): i for i, s in enumerate(d["x_names"])}
        self.u = {str(s): i for i, s in enumerate(d["u_names"])}


def _setup(triad_bin, tmp_path, name, relative, floating):
    urdf = ref.robot_urdf(relative)
    model = ref.load_model(urdf, floating)
    spec = tmp_path / f"{name}.toml"
    _triad(triad_bin, "import", str(urdf), "-o", str(spec), "--no-limits", "--no-friction", "--no-mimic",
           *(["--floating-base"] if floating else []))
    text = spec.read_text()
    names = ref.urdf_names(text)["joint"]  # triad joint name -> URDF joint name
    assert set(names.values()) == {n for n, _ in ref.moving_joints(model)}
    return urdf, model, spec, text, names


def _joint_maps(model, names, lin):
    """Per Pinocchio joint velocity index iv: triad's x index of q, of qd, and u index of the
    joint's input."""
    iq, iv, iu = {}, {}, {}
    for triad_name, urdf_name in names.items():
        j = model.joints[model.getJointId(urdf_name)]
        iq[j.idx_v] = lin.x[f"joint.{triad_name}.q"]
        iv[j.idx_v] = lin.x[f"joint.{triad_name}.qd"]
        (inp,) = [lin.u[k] for k in (f"joint.{triad_name}.tau", f"joint.{triad_name}.f") if k in lin.u]
        iu[j.idx_v] = inp
    return iq, iv, iu


def _state_args(model, names, joints, tau):
    args = []
    for triad_name, urdf_name in names.items():
        j = model.joints[model.getJointId(urdf_name)]
        q, qd = joints[urdf_name]
        kind = "f" if j.shortname().startswith("JointModelP") else "tau"
        args += ["--set", f"joint.{triad_name}.q0={q:.17g}", "--set", f"joint.{triad_name}.qd0={qd:.17g}"]
        args += ["--u", f"joint.{triad_name}.{kind}={tau[j.idx_v]:.17g}"]
    return args


def _aba_reference(model, q, v, tau):
    """(a, d a/d q_tangent, d a/d v, Minv) of Pinocchio with triad's viscous joint damping."""
    data = model.createData()
    damping = np.asarray(model.damping)
    tau_eff = tau - damping * v
    pin.computeABADerivatives(model, data, q, v, tau_eff)
    minv = np.triu(data.Minv)
    minv = minv + np.triu(minv, 1).T
    a = pin.aba(model, model.createData(), q, v, tau_eff)
    return a, data.ddq_dq.copy(), data.ddq_dv.copy() - minv @ np.diag(damping), minv


def _random_torque(model, q, rng):
    return rng.uniform(-1.0, 1.0, model.nv) * ACCEL * ref.mass_matrix_diagonal(model, q)


def _seed(name, seed):
    return np.random.default_rng([zlib.crc32(name.encode()), seed])


@pytest.mark.parametrize("name", list(FIXED))
def test_fixed_base_against_pinocchio(triad_bin, tmp_path, name, record_property):
    urdf, model, _, _, names = _setup(triad_bin, tmp_path, name, FIXED[name], False)
    nv = model.nv
    worst = {"A_dq": 0.0, "A_dv": 0.0, "B": 0.0, "xdot": 0.0, "upper": 0.0}
    for seed in SEEDS:
        rng = _seed(name, seed)
        joints = ref.random_joint_state(model, rng)
        q, v = ref.pinocchio_state(model, joints)
        tau = _random_torque(model, q, rng)
        out = tmp_path / f"{name}_{seed}.npz"
        _triad(triad_bin, "linearize", str(urdf), "--no-limits", "--no-friction", "--no-mimic",
               *_state_args(model, names, joints, tau), "-o", str(out))
        lin = Linearized(out)
        iq, iv, iu = _joint_maps(model, names, lin)
        P_q = [iq[k] for k in range(nv)]
        P_v = [iv[k] for k in range(nv)]
        P_u = [iu[k] for k in range(nv)]
        assert len(lin.x) == 2 * nv and len(lin.u) == nv
        a, da_dq, da_dv, minv = _aba_reference(model, q, v, tau)
        errs = {
            "A_dq": _rel(lin.A[np.ix_(P_v, P_q)], da_dq),
            "A_dv": _rel(lin.A[np.ix_(P_v, P_v)], da_dv),
            "B": _rel(lin.B[np.ix_(P_v, P_u)], minv),
            "xdot": _rel(lin.xdot0[P_v], a),
            # the upper half: dq/dt = qd
            "upper": float(np.abs(lin.A[np.ix_(P_q, P_v)] - np.eye(nv)).max() + np.abs(lin.A[np.ix_(P_q, P_q)]).max()
                           + np.abs(lin.B[P_q]).max()),
        }
        print(f"{name} seed {seed}: " + ", ".join(f"{k} {e:.2e}" for k, e in errs.items()))
        worst = {k: max(worst[k], errs[k]) for k in worst}
    for k, e in worst.items():
        record_property(f"linearize_{name}_{k}", f"{e:.3e}")
    assert max(worst.values()) <= TOL, worst


def _with_armature(text, armature):
    """The spec text with `armature = value` in each named joint's table."""
    out = []
    for line in text.splitlines():
        out.append(line)
        if line.startswith("name = ") and line[8:-1] in armature:
            out.append(f"armature = {armature[line[8:-1]]!r}")
    return "\n".join(out) + "\n"


@pytest.mark.parametrize("name", ["ur5", "panda"])
def test_armature_against_pinocchio(triad_bin, tmp_path, name, record_property):
    urdf, model, spec, text, names = _setup(triad_bin, tmp_path, name, FIXED[name], False)
    nv = model.nv
    rng = _seed(name, 7)
    arm = {t: float(rng.uniform(0.05, 0.5)) for t in names}
    model.armature = np.zeros(nv)
    for triad_name, urdf_name in names.items():
        model.armature[model.joints[model.getJointId(urdf_name)].idx_v] = arm[triad_name]
    spec.write_text(_with_armature(text, arm))
    worst = 0.0
    for seed in SEEDS:
        rng = _seed(name, 10 + seed)
        joints = ref.random_joint_state(model, rng)
        q, v = ref.pinocchio_state(model, joints)
        tau = _random_torque(model, q, rng)
        out = tmp_path / f"{name}_arm_{seed}.npz"
        _triad(triad_bin, "linearize", str(spec), *_state_args(model, names, joints, tau), "-o", str(out))
        lin = Linearized(out)
        iq, iv, iu = _joint_maps(model, names, lin)
        P_q, P_v, P_u = ([m[k] for k in range(nv)] for m in (iq, iv, iu))
        a, da_dq, da_dv, minv = _aba_reference(model, q, v, tau)
        errs = [
            _rel(lin.A[np.ix_(P_v, P_q)], da_dq),
            _rel(lin.A[np.ix_(P_v, P_v)], da_dv),
            _rel(lin.B[np.ix_(P_v, P_u)], minv),
            _rel(lin.xdot0[P_v], a),
        ]
        # and the armature matters: without it the accelerations differ by far more
        bare = pin.aba(ref.load_model(urdf, False), pin.Data(ref.load_model(urdf, False)), q, v,
                       tau - np.asarray(model.damping) * v)
        assert _rel(bare, a) > 1e-3
        print(f"{name} seed {seed}: A_dq {errs[0]:.2e}, A_dv {errs[1]:.2e}, B {errs[2]:.2e}, xdot {errs[3]:.2e}")
        worst = max(worst, *errs)
    record_property(f"linearize_{name}_armature", f"{worst:.3e}")
    assert worst <= TOL, worst


# --- a floating base -----------------------------------------------------------------------


def _floating_reference(model, q, v, tau_joints, base):
    """triad's lower half of A and B and its xdot0's lower half from Pinocchio, in the order
    (base r, base theta, joints by Pinocchio's index) for positions and
    (base v, base w, joints) for rates and accelerations; inputs: the joints.

    triad: x = (r, theta, qj, v_w, w_w, qdj) with R = exp(theta^) R0 (a world-frame rotation
    vector, 0 at the operating point), v_w the velocity of the base frame's origin and w_w the
    angular velocity, both world. Pinocchio: q = (p, quat, qj), tangent perturbation
    M0 exp6(delta) (local frame), nu = (R^T v_w, R^T w_w, qdj), nu-dot = aba.
    To first order: delta_lin = R0^T dr, delta_ang = R0^T theta; d(R^T v_w)/d theta = R0^T [v_w]x,
    d(R^T w_w)/d theta = R0^T [w_w]x. The accelerations: d v_w/dt = w_w x v_w + R a_lin,
    d w_w/dt = R a_ang, so with R = exp(theta^) R0 their theta-derivatives gain -[R a_lin]x and
    -[R a_ang]x, and v_w, w_w enter w_w x v_w directly."""
    nv = model.nv
    tau = np.concatenate([np.zeros(6), tau_joints[6:]])
    a, da_dq, da_dv, minv = _aba_reference(model, q, v, tau)
    R0 = pin.Quaternion(base["orientation"][0], *base["orientation"][1:]).toRotationMatrix()
    vw, ww = np.asarray(base["velocity"], float), np.asarray(base["angular_velocity"], float)
    RT = np.eye(nv)
    RT[0:3, 0:3] = R0.T
    RT[3:6, 3:6] = R0.T
    dnu_dpos = np.zeros((nv, nv))
    dnu_dpos[0:3, 3:6] = R0.T @ _skew(vw)
    dnu_dpos[3:6, 3:6] = R0.T @ _skew(ww)
    R = RT.T
    dg_dpos = R @ (da_dq @ RT + da_dv @ dnu_dpos)
    dg_dpos[0:3, 3:6] -= _skew(R0 @ a[0:3])
    dg_dpos[3:6, 3:6] -= _skew(R0 @ a[3:6])
    dg_dvel = R @ da_dv @ RT
    dg_dvel[0:3, 0:3] += _skew(ww)
    dg_dvel[0:3, 3:6] -= _skew(vw)
    g = R @ a
    g[0:3] += np.cross(ww, vw)
    return dg_dpos, dg_dvel, (R @ minv)[:, 6:], g


@pytest.mark.parametrize("name", list(FLOATING))
def test_floating_base_against_pinocchio(triad_bin, tmp_path, name, record_property):
    urdf, model, _, text, names = _setup(triad_bin, tmp_path, name, FLOATING[name], True)
    (body,) = ref.free_bodies(text)
    free = ref.free_joint(model)
    assert (free.idx_q, free.idx_v) == (0, 0), "the free-flyer comes first in Pinocchio's order"
    nv = model.nv
    worst = {"A_dq": 0.0, "A_dv": 0.0, "B": 0.0, "xdot": 0.0}
    for seed in SEEDS:
        rng = _seed(name, seed)
        joints = ref.random_joint_state(model, rng)
        base = ref.random_base_state(rng)
        q, v = ref.pinocchio_state(model, joints, base)
        tau = _random_torque(model, q, rng)
        spec = tmp_path / f"{name}_{seed}.toml"
        spec.write_text(ref.with_base(text, base))
        out = tmp_path / f"{name}_{seed}.npz"
        _triad(triad_bin, "linearize", str(spec), *_state_args(model, names, joints, tau), "-o", str(out))
        lin = Linearized(out)
        iq, iv, iu = _joint_maps(model, names, lin)
        base_q = [lin.x[f"body.{body}.r[{i}]"] for i in (1, 2, 3)] + [lin.x[f"body.{body}.theta[{i}]"] for i in (1, 2, 3)]
        base_v = [lin.x[f"body.{body}.v[{i}]"] for i in (1, 2, 3)] + [lin.x[f"body.{body}.w[{i}]"] for i in (1, 2, 3)]
        P_q = base_q + [iq[k] for k in range(6, nv)]
        P_v = base_v + [iv[k] for k in range(6, nv)]
        P_u = [iu[k] for k in range(6, nv)]
        assert len(lin.x) == 2 * nv and len(lin.u) == nv - 6
        x0 = np.load(out)["x0"]
        assert np.allclose(x0[base_q[:3]], base["position"], rtol=0, atol=0) and not np.any(x0[base_q[3:]])
        dg_dpos, dg_dvel, b, g = _floating_reference(model, q, v, tau, base)
        errs = {
            "A_dq": _rel(lin.A[np.ix_(P_v, P_q)], dg_dpos),
            "A_dv": _rel(lin.A[np.ix_(P_v, P_v)], dg_dvel),
            "B": _rel(lin.B[np.ix_(P_v, P_u)], b),
            "xdot": _rel(lin.xdot0[P_v], g),
        }
        print(f"{name} seed {seed}: " + ", ".join(f"{k} {e:.2e}" for k, e in errs.items()))
        worst = {k: max(worst[k], errs[k]) for k in worst}
    for k, e in worst.items():
        record_property(f"linearize_{name}_{k}", f"{e:.3e}")
    assert max(worst.values()) <= TOL, worst


# --- refusals ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "args, words",
    [
        (["four_bar", "--coordinates", "nosuch"], ["--coordinates", "no joint 'nosuch'"]),
        (["pendulum", "--step", "0", "-o", "{tmp}/x.txt"], ["--step", "positive"]),
        (["pendulum", "-o", "{tmp}/x.txt"], [".json", ".npz", ".mat"]),
        (["pendulum", "--u", "nosuch=1"], ["nosuch", "no such input"]),
    ],
    ids=["coordinates", "step", "extension", "input"],
)
def test_refusals_are_named(triad_bin, tmp_path, args, words):
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    proc = _triad(triad_bin, "linearize", *args, ok=False)
    assert proc.returncode != 0, f"triad linearize {' '.join(args)} succeeded:\n{proc.stdout[:500]}"
    for word in words:
        assert word in proc.stderr, f"{word!r} not in the message: {proc.stderr!r}"
    assert not (tmp_path / "x.txt").exists()
