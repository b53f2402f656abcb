"""The 3-D replay (`triad animate`, `simulate --animate`) in a real browser.

Headless Chromium (Debian's `chromium`, installed by `scripts/setup.sh --browser`, which `.ci/run`
calls; WebGL on its software rasteriser) opens the page of two models -- the shipped
double_pendulum spec, drawn with its default shapes, and tests/data/urdf/mesh_arm, a URDF drawn
with STL, OBJ and DAE meshes -- and checks that

- the first frame is drawn and is not blank, with no script error and nothing fetched;
- the robot is where its recorded pose projects: the pixels that change when the robot is hidden
  cover the projection (through the page's camera) of every body origin and site read from the
  CSV, not from the page's own payload (the moving ones fall off the robot at another time);
- moving the time slider changes the picture, and the bodies are then where the CSV puts them
  at the new time.

With contact (examples/specs/bouncing_ball.toml), the page draws the spec's ground where it is
(each checker cell's centre, projected from the plane of the spec, shows its cell's tone) and,
with #forces=1, an arrow from the ball's contact point along the CSV's contact.shell.f, |f| /
scale long: its pixels reach from the contact point to the tip and no further, and there is
none while the ball flies. The FMU's documentation/scene.html shows the ground as well.

Screenshots are kept in target/screenshots/. Without Chromium the test skips locally and FAILS
under CI=true (CI installs it).
"""
import csv
import io
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

from browser import Browser, find_chromium

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHOTS = ROOT / "target" / "screenshots"
IN_CI = os.environ.get("CI", "").lower() == "true"
SIZE = (1000, 700)


def _missing(msg):
    if IN_CI:
        pytest.fail(msg + " -- CI=true, so this is a failure, not a skip")
    pytest.skip(msg)


@pytest.fixture(scope="module")
def chromium():
    path = find_chromium()
    if not path:
        _missing("no Chromium found: install Debian's chromium (bash scripts/setup.sh --browser)")
    return path


@pytest.fixture(scope="module")
def triad():
    b = os.environ.get("TRIAD_BIN") or str(ROOT / "target" / "release" / "triad")
    if not os.path.exists(b):
        _missing(f"no triad binary at {b} (set TRIAD_BIN or cargo build --release)")
    return b


def run(*args, cwd):
    r = subprocess.run(args, cwd=cwd, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r.stderr


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header = rows[0]
    return header, np.array([[float(x) for x in r] for r in rows[1:]])


def origins(header, data, t):
    """World positions of every body origin and site at the recorded row of time t."""
    k = int(np.argmin(np.abs(data[:, 0] - t)))
    assert abs(data[k, 0] - t) < 1e-9, f"no row at t = {t}"
    out = {}
    for i, name in enumerate(header):
        kind, _, rest = name.partition(".")
        if kind in ("body", "site") and name.endswith(".r[1]"):
            what = rest[:-len(".r[1]")]
            out[f"{kind} {what}"] = data[k, i:i + 3]
            assert header[i + 2] == f"{kind}.{what}.r[3]"
    return out


def image(png):
    import matplotlib.image

    return matplotlib.image.imread(io.BytesIO(png), format="png")[:, :, :3]


def changed(a, b, tol=0.06):
    return np.max(np.abs(a - b), axis=2) > tol


def covered(mask, x, y, r=3):
    h, w = mask.shape
    xi, yi = int(round(x)), int(round(y))
    assert 0 <= xi < w and 0 <= yi < h, f"({x:.0f}, {y:.0f}) is off the page"
    return bool(mask[max(yi - r, 0):yi + r + 1, max(xi - r, 0):xi + r + 1].any())


def show(b, t):
    """Moves the slider to t as a person would, then waits for the frame."""
    b.evaluate(f"(() => {{ const s = document.getElementById('slider'); s.value = '{t}';"
               " s.dispatchEvent(new Event('input')); return true; })()")
    b.wait_for(f"Math.abs(window.triad.time() - {t}) < 1e-9")
    b.next_frame()


def check_pose(b, name, label, header, data, t):
    """Screenshot at t, then with the robot hidden; the robot's pixels cover its origins."""
    show(b, t)
    with_robot = b.screenshot(str(SHOTS / f"{name}_{label}.png"))
    b.evaluate("window.triad.setRobotVisible(false)")
    b.next_frame()
    without = b.screenshot(str(SHOTS / f"{name}_{label}_empty.png"))
    b.evaluate("window.triad.setRobotVisible(true)")
    b.next_frame()
    a, e = image(with_robot), image(without)
    mask = changed(a, e)
    share = mask.mean()
    assert share > 0.004, f"{name} at t = {t}: the robot covers only {share:.2%} of the page"
    assert a.std() > 0.02, f"{name} at t = {t}: the page is blank"
    for body, p in origins(header, data, t).items():
        x, y, depth = b.evaluate(f"window.triad.project({p[0]}, {p[1]}, {p[2]})")
        assert -1 < depth < 1, f"{body} is outside the camera's depth range"
        assert covered(mask, x, y), f"{name} at t = {t}: no robot pixel at {body}'s origin ({x:.0f}, {y:.0f})"
    return a


MODELS = {
    "double_pendulum": ("modelDescription/double_pendulum/spec.toml", False),
    "mesh_arm": ("tests/data/urdf/mesh_arm/mesh_arm.urdf", True),
}


@pytest.mark.parametrize("name", sorted(MODELS))
def test_replay_in_chromium(name, chromium, triad, tmp_path):
    model, separate = MODELS[name]
    model = str(ROOT / model)
    result = tmp_path / f"{name}.csv"
    page = tmp_path / f"{name}.html"
    if separate:
        # simulate, then animate the CSV
        run(triad, "simulate", model, "--stop", "2", "--step", "0.01", "-o", str(result), cwd=tmp_path)
        err = run(triad, "animate", model, str(result), cwd=tmp_path)
        assert "warning" not in err, err
    else:
        run(triad, "simulate", model, "--stop", "2", "--step", "0.01", "-o", str(result),
            "--animate", str(page), cwd=tmp_path)
    assert page.exists()
    html = page.read_text()
    assert "<script src" not in html and "<link " not in html, "the page must be self-contained"
    header, data = read_csv(result)
    SHOTS.mkdir(parents=True, exist_ok=True)
    with Browser(chromium, *SIZE) as b:
        b.open(page, "play=0&t=0.5&ui=0")
        b.wait_for("window.triad && window.triad.ready", timeout=60)
        assert b.evaluate("window.triad.frames") == len(data)
        assert b.evaluate("performance.getEntriesByType('resource').length") == 0, "nothing is fetched"
        first = check_pose(b, name, "t0.5", header, data, 0.5)
        later = check_pose(b, name, "t1.5", header, data, 1.5)
        moved = changed(first, later).mean()
        assert moved > 0.002, f"{name}: moving the slider changed only {moved:.2%} of the page"
        # the page with its controls, for people
        b.evaluate("window.triad.setUi(true)")
        b.evaluate("window.triad.setTrace(window.triad.bodies.length ? 'body:' + window.triad.bodies[window.triad.bodies.length - 1] : '')")
        b.next_frame()
        b.screenshot(str(SHOTS / f"{name}_ui.png"))
        errors = [e for e in b.events if e.get("method") == "Runtime.exceptionThrown"
                  or (e.get("method") == "Runtime.consoleAPICalled" and e["params"].get("type") == "error")]
        assert not errors, errors


def test_fmu_documentation_scene(chromium, triad, tmp_path):
    """The FMU's documentation/scene.html shows the model in its initial pose."""
    import zipfile

    fmu = tmp_path / "mesh_arm.fmu"
    run(triad, "build", str(ROOT / "tests/data/urdf/mesh_arm/mesh_arm.urdf"), "-o", str(fmu), cwd=tmp_path)
    with zipfile.ZipFile(fmu) as z:
        z.extract("documentation/scene.html", tmp_path)
    scene = tmp_path / "documentation" / "scene.html"
    SHOTS.mkdir(parents=True, exist_ok=True)
    with Browser(chromium, *SIZE) as b:
        b.open(scene, "ui=0")
        b.wait_for("window.triad && window.triad.ready", timeout=60)
        assert b.evaluate("window.triad.frames") == 1
        b.next_frame()
        a = image(b.screenshot(str(SHOTS / "mesh_arm_fmu_scene.png")))
        b.evaluate("window.triad.setRobotVisible(false)")
        b.next_frame()
        e = image(b.screenshot())
        # upright at q = 0: the upper arm's origin (shoulder, z = 0.1) and the forearm's (z = 0.6)
        mask = changed(a, e)
        for p in ([0, 0, 0.1], [0, 0, 0.6]):
            x, y, _ = b.evaluate(f"window.triad.project({p[0]}, {p[1]}, {p[2]})")
            assert covered(mask, x, y), f"no robot pixel at {p}"


def test_main_job_writes_results_html(triad, tmp_path):
    """The README's main job (scripts/main_job.sh): the fmpy closed loop writes results.csv with
    the poses, and `triad animate` makes results.html of it (here over 0.3 s)."""
    import sys

    urdf = str(ROOT / "modelDescription/robot_arm/robot_arm.urdf")
    fmu = tmp_path / "robot_arm.fmu"
    run(triad, "build", urdf, "-o", str(fmu), cwd=tmp_path)
    run(sys.executable, str(ROOT / "scripts/main_job.py"), str(fmu), "--stop", "0.3",
        "--csv", "results.csv", "--plot", "results.png", cwd=tmp_path)
    run(triad, "animate", urdf, "results.csv", "-o", "results.html", cwd=tmp_path)
    header, data = read_csv(tmp_path / "results.csv")
    html = (tmp_path / "results.html").read_text()
    assert f'"frames":{len(data)}' in html
    assert all(f"body.{b}.R[3,3]" in header for b in ("shoulder_pan_link", "wrist_3_link"))


def test_fmpy_example(triad, tmp_path):
    """examples/animate_fmpy.py: an fmpy run written by fmpy's write_csv replays, pose for pose."""
    import base64
    import json
    import re
    import sys

    urdf = str(ROOT / "tests/data/urdf/mesh_arm/mesh_arm.urdf")
    fmu = tmp_path / "mesh_arm.fmu"
    run(triad, "build", urdf, "-o", str(fmu), cwd=tmp_path)
    csv_path, html = tmp_path / "run.csv", tmp_path / "run.html"
    run(sys.executable, str(ROOT / "examples/animate_fmpy.py"), str(fmu), urdf, "--stop", "1",
        "--csv", str(csv_path), "--html", str(html), "--triad", triad, cwd=tmp_path)
    header, data = read_csv(csv_path)
    payload = re.search(r'<script type="application/json" id="triad-data">(.*?)</script>', html.read_text(), re.S)
    page = json.loads(payload.group(1))
    assert page["frames"] == len(data)
    for body in page["bodies"]:
        r = np.frombuffer(base64.b64decode(body["r"]), dtype="<f8").reshape(-1, 3)
        k = header.index(f"body.{body['name']}.r[1]")
        assert np.max(np.abs(r - data[:, k:k + 3])) <= 1e-6


BALL = "examples/specs/bouncing_ball.toml"


def payload(html):
    import json
    import re

    m = re.search(r'<script type="application/json" id="triad-data">(.*?)</script>', html, re.S)
    return json.loads(m.group(1))


def lum(img, x, y, r=1):
    """Mean luminance of the (2r+1)^2 patch at page pixel (x, y)."""
    xi, yi = int(round(x)), int(round(y))
    return float(img[yi - r:yi + r + 1, xi - r:xi + r + 1].mean())


def on_page(x, y, margin=4):
    return margin <= x < SIZE[0] - margin and margin <= y < SIZE[1] - margin


def shot_pair(b, setup, change, restore, path):
    """The page after the script `setup` (also written to `path`) and after `change` on top of
    it, as images; then `restore`."""
    b.evaluate(setup)
    b.next_frame()
    a = image(b.screenshot(str(path)))
    b.evaluate(change)
    b.next_frame()
    e = image(b.screenshot())
    b.evaluate(restore)
    b.next_frame()
    return a, e


def check_ground(b, name):
    """The ground's pixels: every checker cell near the model whose centre, projected from the
    page's reported plane, is well inside the page shows its cell's tone (odd cells darker)."""
    g = b.evaluate("window.triad.ground")
    a, e = shot_pair(
        b,
        "window.triad.setRobotVisible(false); window.triad.showForces(false); window.triad.setHelpersVisible(false)",
        "window.triad.setGroundVisible(false)",
        "window.triad.setGroundVisible(true); window.triad.setRobotVisible(true); window.triad.setHelpersVisible(true)",
        SHOTS / f"{name}_ground.png")
    mask = changed(a, e, tol=0.03)
    assert mask.mean() > 0.15, f"{name}: the ground covers only {mask.mean():.1%} of the page"
    n, h, cell = np.array(g["normal"]), g["height"], g["cell"]
    assert np.allclose(n, [0, 0, 1]), n
    corners = np.array(g["corners"])
    assert np.allclose(corners[:, 2], h), "the drawn square lies in the plane"
    tones = {0: [], 1: []}
    for iu in range(-12, 12):
        for iv in range(-12, 12):
            centre = [(iu + 0.5) * cell, (iv + 0.5) * cell, h]
            x, y, _ = b.evaluate(f"window.triad.project({centre[0]}, {centre[1]}, {centre[2]})")
            x1, y1, _ = b.evaluate(f"window.triad.project({centre[0] + cell}, {centre[1]}, {centre[2]})")
            x2, y2, _ = b.evaluate(f"window.triad.project({centre[0]}, {centre[1] + cell}, {centre[2]})")
            small = min(np.hypot(x1 - x, y1 - y), np.hypot(x2 - x, y2 - y))
            inside = np.all(corners[:, :2].min(axis=0) < centre[:2]) and np.all(centre[:2] < corners[:, :2].max(axis=0))
            if not inside or not on_page(x, y, 10) or small < 14:
                continue
            assert covered(mask, x, y, r=1), f"{name}: no ground at cell ({iu}, {iv})"
            tones[(iu + iv) & 1].append(lum(a, x, y))
    assert len(tones[0]) >= 10 and len(tones[1]) >= 10, f"{name}: too few cells seen: {tones}"
    assert max(tones[1]) < min(tones[0]) - 0.03, (
        f"{name}: the checker's tones do not follow the cells of the plane z = {h}: "
        f"light {min(tones[0]):.3f}..{max(tones[0]):.3f}, dark {min(tones[1]):.3f}..{max(tones[1]):.3f}")
    return g


def arrow_pixels(b, name):
    """The pixels the force arrows add (robot and ground hidden)."""
    a, e = shot_pair(
        b,
        "window.triad.setRobotVisible(false); window.triad.setGroundVisible(false); window.triad.showForces(true)",
        "window.triad.showForces(false)",
        "window.triad.setRobotVisible(true); window.triad.setGroundVisible(true); window.triad.showForces(true)",
        SHOTS / f"{name}.png")
    return changed(a, e)


def check_arrow(b, name, base, tip):
    """The arrow's pixels cover the segment from the projected base to the projected tip, reach
    the tip and go no further, and stay near the segment."""
    mask = arrow_pixels(b, name)
    (x0, y0, _), (x1, y1, _) = (b.evaluate(f"window.triad.project({p[0]}, {p[1]}, {p[2]})") for p in (base, tip))
    assert on_page(x0, y0) and on_page(x1, y1), f"{name}: the arrow is off the page"
    d = np.array([x1 - x0, y1 - y0])
    length = np.linalg.norm(d)
    assert length > 40, f"{name}: the arrow is only {length:.0f} px long"
    for s in (0.05, 0.3, 0.6, 0.9, 0.98):
        assert covered(mask, x0 + s * d[0], y0 + s * d[1], r=2), f"{name}: no arrow pixel at {s:.0%} of its length"
    ys, xs = np.nonzero(mask)
    rel = np.stack([xs - x0, ys - y0], axis=1)
    along = rel @ (d / length)
    across = np.abs(rel @ (np.array([-d[1], d[0]]) / length))
    assert across.max() < 0.012 * SIZE[0] + 0.2 * length, f"{name}: pixels {across.max():.0f} px off the arrow"
    assert abs(along.max() - length) <= 3 + 0.03 * length, (
        f"{name}: the arrow reaches {along.max():.0f} px, its tip is {length:.0f} px from its base")
    assert along.min() >= -12, f"{name}: pixels {-along.min():.0f} px behind the base"


def test_ground_and_contact_forces(chromium, triad, tmp_path):
    """The bouncing ball: its ground, and its contact force as an arrow (see the module doc)."""
    result, page = tmp_path / "ball.csv", tmp_path / "ball.html"
    run(triad, "simulate", str(ROOT / BALL), "--stop", "3", "--step", "0.01", "-o", str(result),
        "--animate", str(page), cwd=tmp_path)
    header, data = read_csv(result)
    col = {name: i for i, name in enumerate(header)}
    pay = payload(page.read_text())
    L = pay["length"]
    f = data[:, [col[f"contact.shell.f[{i}]"] for i in (1, 2, 3)]]
    r = data[:, [col[f"body.ball.r[{i}]"] for i in (1, 2, 3)]]
    SHOTS.mkdir(parents=True, exist_ok=True)
    with Browser(chromium, *SIZE) as b:
        b.open(page, "play=0&ui=0&forces=1&t=1")
        b.wait_for("window.triad && window.triad.ready", timeout=60)
        assert b.evaluate("window.triad.contacts") == ["shell"]
        show(b, 1.0)
        g = check_ground(b, "ball_t1")
        assert g["height"] == 0.0
        scale = b.evaluate("window.triad.forceScale()")
        assert scale == pay["forces"]["scale"] > 0

        # a force of a fair length at the default scale: the arrow from the ball's lowest point
        # (on the ground under its centre) along contact.shell.f
        lengths = np.linalg.norm(f, axis=1) / scale
        k = next(k for k in range(len(data)) if data[k, 0] > 1.0 and 0.3 * L < lengths[k] < 1.2 * L)
        t = data[k, 0]
        show(b, t)
        (arrow,) = b.evaluate("window.triad.arrows()")
        base = np.array([r[k, 0], r[k, 1], g["height"]])
        tip = base + f[k] / scale
        assert arrow["visible"] and not arrow["cut"], arrow
        assert np.allclose(arrow["force"], f[k], rtol=1e-6, atol=1e-9), (arrow["force"], f[k])
        assert np.allclose(arrow["base"], base, atol=1e-9), (arrow["base"], base)
        assert np.allclose(arrow["tip"], tip, atol=1e-6), (arrow["tip"], tip)
        check_arrow(b, "ball_force", base, tip)

        # the first impact (about 1440 N, tilted by friction): cut at 2 L at the default scale;
        # at 1000 N per m drawn whole
        k = int(np.argmax(np.linalg.norm(f, axis=1)))
        show(b, data[k, 0])
        (arrow,) = b.evaluate("window.triad.arrows()")
        assert arrow["cut"] and np.isclose(np.linalg.norm(np.subtract(arrow["tip"], arrow["base"])), 2 * L)
        b.evaluate("window.triad.setForceScale(1000)")
        b.next_frame()
        (arrow,) = b.evaluate("window.triad.arrows()")
        base = np.array([r[k, 0], r[k, 1], g["height"]])
        tip = base + f[k] / 1000
        assert abs(f[k, 0]) > 0.05 * abs(f[k, 2]), "friction tilts the first impact's force"
        assert not arrow["cut"] and np.allclose(arrow["tip"], tip, atol=1e-6), (arrow, tip)
        check_arrow(b, "ball_impact", base, tip)
        b.evaluate(f"window.triad.setForceScale({scale})")

        # in flight: no force, no arrow
        show(b, 0.2)
        assert np.all(f[int(np.argmin(np.abs(data[:, 0] - 0.2)))] == 0)
        (arrow,) = b.evaluate("window.triad.arrows()")
        assert not arrow["visible"]
        assert not arrow_pixels(b, "ball_flight").any(), "an arrow for a zero force"

        # the collision shapes on demand: the wireframe over the ball
        show(b, 1.0)
        b.evaluate("window.triad.showForces(false)")
        b.next_frame()
        plain = image(b.screenshot())
        b.evaluate("window.triad.showCollision(true)")
        b.next_frame()
        wired = image(b.screenshot(str(SHOTS / "ball_collision.png")))
        k = int(np.argmin(np.abs(data[:, 0] - 1.0)))
        x, y, _ = b.evaluate(f"window.triad.project({r[k, 0]}, {r[k, 1]}, {r[k, 2]})")
        assert covered(changed(plain, wired, tol=0.03), x, y, r=12), "no wireframe on the ball"

        b.evaluate("window.triad.setUi(true); window.triad.showCollision(false); window.triad.showForces(true)")
        show(b, t)
        b.screenshot(str(SHOTS / "ball_ui.png"))
        errors = [e for e in b.events if e.get("method") == "Runtime.exceptionThrown"
                  or (e.get("method") == "Runtime.consoleAPICalled" and e["params"].get("type") in ("error", "warning"))]
        assert not errors, errors


TUMBLING_BOX = """
name = "TumblingBox"
[experiment]
stop = 1.5
step = 0.01
[ground]
damping = 1.0
friction = 0.6
[[body]]
name = "box"
mass = 2.0
inertia = [0.0083, 0.0283, 0.0333]
position = [0.0, 0.0, 0.5]
orientation = [0.9238795325112867, 0.3826834323650898, 0.1, 0.0]
angular_velocity = [1.0, 2.0, 0.0]
[[collision]]
body = "box"
box = { size = [0.4, 0.2, 0.1] }
"""


def test_box_contact_point(chromium, triad, tmp_path):
    """A box tumbling onto the ground: its arrow starts at the centre of pressure of its corners
    in the ground, each weighted by its depth (one corner, an edge, a face), on the ground: to
    1e-6 m on one corner, 5e-4 m (a thousandth of the box) between several."""
    import itertools

    spec = tmp_path / "box.toml"
    spec.write_text(TUMBLING_BOX)
    result, page = tmp_path / "box.csv", tmp_path / "box.html"
    run(triad, "simulate", str(spec), "-o", str(result), "--animate", str(page), cwd=tmp_path)
    header, data = read_csv(result)
    col = {name: i for i, name in enumerate(header)}
    half = np.array([0.2, 0.1, 0.05])
    checked = {1: 0, 2: 0}
    with Browser(chromium, *SIZE) as b:
        b.open(page, "play=0&ui=0&forces=1")
        b.wait_for("window.triad && window.triad.ready", timeout=60)
        for k in range(len(data)):
            f = data[k, [col[f"contact.box_1.f[{i}]"] for i in (1, 2, 3)]]
            if not np.any(f):
                continue
            r = data[k, [col[f"body.box.r[{i}]"] for i in (1, 2, 3)]]
            R = np.array([[data[k, col[f"body.box.R[{i},{j}]"]] for j in (1, 2, 3)] for i in (1, 2, 3)])
            corners = [r + R @ (half * s) for s in itertools.product((-1, 1), repeat=3)]
            depths = [(-c[2], c) for c in corners if c[2] < 0]
            if not depths:
                continue
            w = sum(d for d, _ in depths)
            expected = sum(d * c for d, c in depths) / w
            expected[2] = 0.0
            b.evaluate(f"window.triad.setTime({data[k, 0]})")
            b.next_frame()
            (arrow,) = b.evaluate("window.triad.arrows()")
            assert arrow["visible"]
            # (the page's f32 orientations move a corner by ~5e-8 m; the depths of ~1e-4 m that
            # weigh several corners then move their centre by up to ~1e-4 m)
            tol = 1e-6 if len(depths) == 1 else 5e-4
            assert np.allclose(arrow["base"], expected, atol=tol), (data[k, 0], arrow["base"], expected)
            checked[min(len(depths), 2)] += 1
    assert checked[1] >= 3 and checked[2] >= 3, f"frames on one corner and on several: {checked}"


def test_fmu_documentation_scene_ground(chromium, triad, tmp_path):
    """The bouncing ball FMU's documentation/scene.html: the ball in the air over its ground."""
    import zipfile

    fmu = tmp_path / "ball.fmu"
    run(triad, "build", str(ROOT / BALL), "-o", str(fmu), cwd=tmp_path)
    with zipfile.ZipFile(fmu) as z:
        z.extract("documentation/scene.html", tmp_path)
    SHOTS.mkdir(parents=True, exist_ok=True)
    with Browser(chromium, *SIZE) as b:
        b.open(tmp_path / "documentation" / "scene.html", "ui=0")
        b.wait_for("window.triad && window.triad.ready", timeout=60)
        assert b.evaluate("window.triad.frames") == 1
        check_ground(b, "ball_fmu_scene")


if __name__ == "__main__":
    raise SystemExit(pytest.main([__file__, "-q"]))
