"""A headless Chromium driven over the DevTools protocol on a pipe (`--remote-debugging-pipe`),
with the standard library only: open a page, evaluate JavaScript, take PNG screenshots.

Chromium is Debian's `chromium` package (`scripts/setup.sh --browser` installs it); WebGL runs on
its software rasteriser (SwiftShader), so no GPU or display is needed.

    python tests/python/browser.py PAGE.html OUT.png [--hash 't=1&play=0'] [--size 1200x800]

writes a screenshot of PAGE once its first frame is drawn (the still of docs/guide/see-the-motion.md is made so).
"""
import argparse
import base64
import fcntl
import json
import os
import select
import shutil
import subprocess
import tempfile
import time

CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable", "chrome")


def find_chromium():
    """Path of a Chromium (or Chrome) executable: $TRIAD_CHROMIUM, else the first on PATH."""
    env = os.environ.get("TRIAD_CHROMIUM")
    if env:
        return env if os.path.exists(env) else None
    for name in CANDIDATES:
        p = shutil.which(name)
        if p:
            return p
    return None


class Browser:
    """One headless Chromium with one page; a context manager."""

    def __init__(self, executable=None, width=1200, height=800):
        self.executable = executable or find_chromium()
        if not self.executable:
            raise RuntimeError("no Chromium found (install Debian's chromium: bash scripts/setup.sh --browser)")
        self.width, self.height = width, height
        self.profile = tempfile.mkdtemp(prefix="triad-chromium-")
        to_child_r, self._to_child = os.pipe()
        self._from_child, from_child_w = os.pipe()
        # the child's ends moved above 10 first, so that placing them at 3 and 4 clobbers nothing
        # (and dup2 onto another number makes them survive exec)
        high = [fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10) for fd in (to_child_r, from_child_w)]
        os.close(to_child_r)
        os.close(from_child_w)
        to_child_r, from_child_w = high

        def fds():
            os.dup2(to_child_r, 3)
            os.dup2(from_child_w, 4)

        args = [
            self.executable, "--headless", "--no-sandbox", "--remote-debugging-pipe",
            "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
            "--no-first-run", "--no-default-browser-check", "--disable-extensions",
            "--hide-scrollbars", "--mute-audio", "--disable-background-timer-throttling",
            "--disable-renderer-backgrounding", f"--user-data-dir={self.profile}",
            f"--window-size={width},{height}", "about:blank",
        ]
        self.proc = subprocess.Popen(args, preexec_fn=fds, close_fds=False,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(to_child_r)
        os.close(from_child_w)
        self._buf = b""
        self._id = 0
        self.events = []
        target = self.call("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.call("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
        self.call("Page.enable", session=True)
        self.call("Runtime.enable", session=True)
        self.call("Emulation.setDeviceMetricsOverride",
                  {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False}, session=True)

    # ---- protocol
    def _read(self, timeout):
        deadline = time.monotonic() + timeout
        while b"\0" not in self._buf:
            if time.monotonic() > deadline:
                raise TimeoutError("no answer from Chromium")
            ready, _, _ = select.select([self._from_child], [], [], 0.5)
            if ready:
                chunk = os.read(self._from_child, 1 << 20)
                if not chunk:
                    raise RuntimeError("Chromium closed the pipe (crashed?)")
                self._buf += chunk
        msg, self._buf = self._buf.split(b"\0", 1)
        return json.loads(msg)

    def call(self, method, params=None, session=False, timeout=60):
        """Sends one command and returns its result (raises on a protocol error)."""
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = self.session
        os.write(self._to_child, json.dumps(msg).encode() + b"\0")
        while True:
            reply = self._read(timeout)
            if reply.get("id") == self._id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                return reply.get("result", {})
            self.events.append(reply)

    # ---- page
    def open(self, path, fragment=""):
        url = "file://" + os.path.abspath(path) + (("#" + fragment) if fragment else "")
        self.call("Page.navigate", {"url": url}, session=True)

    def evaluate(self, expression, timeout=60):
        """The value of a JavaScript expression (promises awaited)."""
        r = self.call("Runtime.evaluate", {"expression": expression, "awaitPromise": True,
                                           "returnByValue": True}, session=True, timeout=timeout)
        if "exceptionDetails" in r:
            raise RuntimeError(f"{expression}: {r['exceptionDetails']}")
        return r["result"].get("value")

    def wait_for(self, expression, timeout=60):
        """Waits until the expression is truthy; returns its value."""
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            try:
                v = self.evaluate(expression)
            except RuntimeError:
                v = None
            if v:
                return v
            time.sleep(0.1)
        raise TimeoutError(f"waited {timeout} s for {expression}")

    def next_frame(self):
        """Waits until the page has drawn once more (two animation frames)."""
        self.evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))")

    def screenshot(self, path=None):
        """PNG bytes of the viewport (also written to `path` if given)."""
        png = base64.b64decode(self.call("Page.captureScreenshot", {"format": "png"}, session=True)["data"])
        if path:
            os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
            with open(path, "wb") as f:
                f.write(png)
        return png

    def close(self):
        try:
            self.call("Browser.close", timeout=10)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for fd in (self._to_child, self._from_child):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self.profile, ignore_errors=True)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("page")
    p.add_argument("out")
    p.add_argument("--hash", default="play=0", help="the page's URL fragment (t=..., play=0, ui=0, trace=...)")
    p.add_argument("--size", default="1200x800")
    a = p.parse_args()
    w, h = (int(x) for x in a.size.split("x"))
    with Browser(width=w, height=h) as b:
        b.open(a.page, a.hash)
        b.wait_for("window.triad && window.triad.ready")
        b.next_frame()
        b.screenshot(a.out)
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
