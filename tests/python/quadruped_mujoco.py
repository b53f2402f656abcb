"""MuJoCo's side of test_quadruped.py: the MJCF of a triad spec (a floating base with a tree of
revolute joints: the same bodies, masses, centres of mass, inertias, joint frames, axes and
damping, the same foot spheres and ground, the same friction coefficient), run under the same PD
loop (examples/quadruped_stand.py `Stand`) at the same control rate.

Contact law mapping. triad's normal force is Hunt-Crossley's `f = k x (1 + d x')` (penetration
x, stiffness k in N/m, damping d in s/m; `src/mechanics/model/contact_law.rs`). MuJoCo's contact
is a soft constraint: with `solref = (-S, -B)` (the direct form) and a constant impedance
`solimp = (i, i, ...)`, it sets the reference acceleration `a_ref = (S/i) x + (B/i) x'` (MuJoCo
scales k by 1/dmax² and b by 1/dmax, then k by the impedance) and the regulariser
`R = w (1 - i)/i`, where `w` is the contact's "inverse weight": its constraint-space scaling,
the translational `body_invweight0` of the foot's body (MuJoCo's diagonal approximation of
J M⁻¹ Jᵀ, fixed at the model's reference pose). The normal force `f = (a_ref - a0)/(A + R)`
then has, at rest (`a0 + A f = 0`), `a_ref = R f`, that is

    f = S x / (w (1 - i))           exactly, whatever A is,

so `S = k w (1 - i)` gives triad's static law `f = k x`. Moving, with `R >> A` (small i),
`f ≈ (S x + B x' - i a0) / (w (1 - i))`: a linear spring-damper whose damping
`B / (w (1 - i))` is set to Hunt-Crossley's at the standing load, `k d x_s = d W / 4` (x_s the
standing penetration of one foot), since MuJoCo's damper cannot grow with the penetration as
triad's does; `-i a0` is a bias of i / (1 - i) of the force (1 % at i = 0.01). So the settled
height agrees (the same statics) and the impact differs (triad's damper starts at zero at
first touch, MuJoCo's does not): the test asserts the first and reports the second.

Friction: the same μ on an elliptic cone. MuJoCo's friction has no spring (triad's bristle
sticks elastically), only a reference damping, so a foot under a sideways load creeps: with the
friction rows as soft as the normal one (impratio 1) the feet of the standing Go1 splay by 1 cm
and the base sinks 3 mm. Here they get `impratio = 1000/i` (their regulariser R/impratio ≈
w/1000: nearly hard) and `solreffriction = (-1, -B_t)` with the rate `B_t/i = 200 1/s` at which
MuJoCo removes a slip velocity (stable at the step); the creep left moves the base by 0.1 mm.
"""
import numpy as np

IMPEDANCE = 0.01  # MuJoCo's constant impedance i (solimp dmin = dmax)
SLIP_RATE = 200.0  # 1/s: MuJoCo's reference damping of the friction rows (B_t / i)
IMPRATIO = 1000.0  # friction rows regularised by R / (IMPRATIO / i) ≈ w / 100: nearly hard


def _f(v):
    return " ".join(f"{float(x):.17g}" for x in v)


def _rpy_quat(rpy):
    """[w, x, y, z] of R = Rz(yaw) Ry(pitch) Rx(roll) (URDF fixed-axis roll, pitch, yaw)."""
    r, p, y = (0.5 * a for a in rpy)
    cr, sr, cp, sp, cy, sy = np.cos(r), np.sin(r), np.cos(p), np.sin(p), np.cos(y), np.sin(y)
    return [cr * cp * cy + sr * sp * sy, sr * cp * cy - cr * sp * sy,
            cr * sp * cy + sr * cp * sy, cr * cp * sy - sr * sp * cy]


def _matrix_quat(m):
    m = np.asarray(m, dtype=float)
    w = np.sqrt(max(0.0, 1.0 + np.trace(m))) / 2.0
    if w > 1e-6:
        return [w, (m[2, 1] - m[1, 2]) / (4 * w), (m[0, 2] - m[2, 0]) / (4 * w), (m[1, 0] - m[0, 1]) / (4 * w)]
    raise ValueError("base orientation too far from identity for this helper")


def mjcf(spec, feet, timestep, solref_normal=None, solref_friction=None, impedance=IMPEDANCE):
    """The MJCF of SPEC (a free base with revolute joints): the spheres named in FEET on their
    bodies, the ground as a plane, contacts only between the ground and the feet (explicit
    pairs with `solref_normal[foot]`, `solref_friction[foot]`; MuJoCo's defaults when None)."""
    bodies = {b["name"]: b for b in spec["body"]}
    children = {}
    for j in spec["joint"]:
        if j["type"] != "revolute":
            raise ValueError(f"joint {j['name']}: this helper builds revolute joints only")
        children.setdefault(j["parent"], []).append(j)
    shapes = {c["name"]: c for c in spec.get("collision", [])}
    on = {}
    for f in feet:
        on.setdefault(shapes[f]["body"], []).append(shapes[f])

    def inertial(b):
        return (f'<inertial pos="{_f(b["com"])}" mass="{b["mass"]:.17g}" '
                f'fullinertia="{_f(b["inertia"])}"/>')

    def geoms(name, ind):
        return "".join(f'{ind}<geom name="{c["name"]}" type="sphere" size="{c["sphere"]["radius"]:.17g}" '
                       f'pos="{_f(c["origin"]["xyz"])}" contype="0" conaffinity="0"/>\n'
                       for c in on.get(name, []))

    def subtree(j, ind):
        b = bodies[j["child"]]
        s = (f'{ind}<body name="{b["name"]}" pos="{_f(j["origin"]["xyz"])}" '
             f'quat="{_f(_rpy_quat(j["origin"]["rpy"]))}">\n')
        s += (f'{ind}  <joint name="{j["name"]}" type="hinge" axis="{_f(j["axis"])}" '
              f'damping="{j.get("damping", 0.0):.17g}" armature="0"/>\n')
        s += f"{ind}  {inertial(b)}\n" + geoms(b["name"], ind + "  ")
        for c in children.get(b["name"], []):
            s += subtree(c, ind + "  ")
        return s + f"{ind}</body>\n"

    root = next(b for b in spec["body"] if "position" in b)
    o = root.get("orientation")
    quat = [1.0, 0.0, 0.0, 0.0] if o is None else (o if len(o) == 4 else _matrix_quat(o))
    base = (f'    <body name="{root["name"]}" pos="{_f(root["position"])}" quat="{_f(quat)}">\n'
            f'      <freejoint name="root"/>\n      {inertial(root)}\n' + geoms(root["name"], "      "))
    for c in children.get(root["name"], []):
        base += subtree(c, "      ")
    base += "    </body>\n"
    g = spec["ground"]
    mu = g["friction"]
    pairs = ""
    for f in feet:
        attrs = f'geom1="ground" geom2="{f}" condim="3" friction="{_f([mu, mu, 0.005, 1e-4, 1e-4])}"'
        if solref_normal is not None:
            i = impedance
            attrs += (f' solref="{_f(solref_normal[f])}" solreffriction="{_f(solref_friction[f])}"'
                      f' solimp="{_f([i, i, 0.001, 0.5, 2])}"')
        pairs += f"    <pair {attrs}/>\n"
    impratio = IMPRATIO / impedance if solref_normal is not None else 1.0
    return f"""<mujoco model="{spec['name']}">
  <compiler angle="radian" inertiafromgeom="false" autolimits="true"/>
  <option timestep="{timestep:.17g}" integrator="implicitfast" gravity="{_f(spec['gravity'])}"
          cone="elliptic" impratio="{impratio:.17g}"/>
  <worldbody>
    <geom name="ground" type="plane" size="0 0 1" pos="0 0 {g['height']:.17g}" contype="0" conaffinity="0"/>
{base}  </worldbody>
  <contact>
{pairs}  </contact>
</mujoco>
"""


def model(spec, feet, timestep, impedance=IMPEDANCE):
    """The MuJoCo model of SPEC with triad's contact law mapped (module doc), and the mapping:
    {foot: (w, S, B)}."""
    import mujoco

    plain = mujoco.MjModel.from_xml_string(mjcf(spec, feet, timestep))
    g = spec["ground"]
    k, d = g["stiffness"], g["damping"]
    weight = sum(b["mass"] for b in spec["body"]) * float(np.linalg.norm(spec["gravity"]))
    normal, friction, mapping = {}, {}, {}
    i = impedance
    for f in feet:
        gid = mujoco.mj_name2id(plain, mujoco.mjtObj.mjOBJ_GEOM, f)
        w = float(plain.body_invweight0[plain.geom_bodyid[gid], 0])
        stiff = k * w * (1.0 - i)
        damp = d * weight / len(feet) * w * (1.0 - i)
        normal[f] = [-stiff, -damp]
        friction[f] = [-1.0, -SLIP_RATE * i]
        mapping[f] = (w, stiff, damp)
    xml = mjcf(spec, feet, timestep, normal, friction, impedance)
    return mujoco.MjModel.from_xml_string(xml), mapping, xml


def run(spec, feet, controller, stop, h, substeps=1, impedance=IMPEDANCE):
    """Runs MuJoCo under CONTROLLER (`torque(q, qd)` of the actuated joints, in spec order) every
    H seconds with `substeps` MuJoCo steps per control step, from the spec's initial state.
    Returns a dict: `t`, `z` (base frame height), `feet` (normal force per foot), `wall` (s),
    `mapping` ({foot: (w, S, B)})."""
    import time

    import mujoco

    m, mapping, _ = model(spec, feet, h / substeps, impedance)
    d = mujoco.MjData(m)
    names = controller.names
    jid = [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, n) for n in names]
    qa = np.array([m.jnt_qposadr[j] for j in jid])
    va = np.array([m.jnt_dofadr[j] for j in jid])
    initial = {j["name"]: j.get("initial", {}).get("q", 0.0) for j in spec["joint"]}
    d.qpos[qa] = [initial[n] for n in names]
    mujoco.mj_forward(m, d)
    base = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_BODY, next(b["name"] for b in spec["body"] if "position" in b))
    foot_geom = {mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_GEOM, f): k for k, f in enumerate(feet)}
    n = int(round(stop / h))
    t = np.arange(n + 1) * h
    z = np.empty(n + 1)
    forces = np.zeros((n + 1, len(feet)))
    out = np.zeros(6)

    def sample(k):
        z[k] = d.xpos[base, 2]
        for c in range(d.ncon):
            foot = foot_geom.get(d.contact[c].geom2, foot_geom.get(d.contact[c].geom1))
            if foot is not None:
                mujoco.mj_contactForce(m, d, c, out)
                forces[k, foot] += out[0]

    sample(0)
    wall = 0.0
    for k in range(n):
        d.qfrc_applied[:] = 0.0
        d.qfrc_applied[va] = controller.torque(d.qpos[qa], d.qvel[va])
        w0 = time.perf_counter()
        mujoco.mj_step(m, d, substeps)
        wall += time.perf_counter() - w0
        sample(k + 1)
    return {"t": t, "z": z, "feet": forces, "wall": wall, "mapping": mapping}
