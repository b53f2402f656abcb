"""An FMU state serialised in one process and deserialised in a fresh Python process continues
bit-identically: the fresh process must reproduce, bit for bit, the outputs that the first process
computes by simply continuing (canSerializeFMUstate, fmi.md pitfall 4)."""
import os
import subprocess
import sys
import tempfile

from fmu_driver import Driver

CONTINUE = r'''
import sys
sys.path.insert(0, sys.argv[1])
from fmu_driver import Driver
fmu, state, steps, h, t = sys.argv[2], sys.argv[3], int(sys.argv[4]), float(sys.argv[5]), float(sys.argv[6])
d = Driver(fmu, name="fresh", initialise=False)
with open(state, "rb") as f:
    s = d.fmu.deSerializeFMUstate(f.read())
d.fmu.setFMUstate(s)
d.fmu.freeFMUstate(s)
d.t = t
ins, outs = d.names("input"), d.names("output")
for n in range(steps):
    d.set(ins, [0.01 * (n + 1 + i) for i in range(len(ins))])
    d.step(h)
    print(" ".join(x.hex() for x in d.get(outs)))
d.close()
'''


def _run(d, steps, h, first):
    ins, outs = d.names("input"), d.names("output")
    lines = []
    for n in range(steps):
        d.set(ins, [0.01 * (first + n + 1 + i) for i in range(len(ins))])
        d.step(h)
        lines.append(" ".join(x.hex() for x in d.get(outs)))
    return lines


def test_serialize_then_continue_in_a_fresh_process(fmu):
    d = Driver(fmu)
    h = float(d.md.defaultExperiment.stepSize)
    _run(d, 10, h, 0)
    state = d.fmu.getFMUstate()
    data = d.fmu.serializeFMUstate(state)
    d.fmu.freeFMUstate(state)
    t = d.t
    # the uninterrupted continuation (inputs as in CONTINUE: first = 0 there)
    want = _run(d, 10, h, 0)
    d.close()
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "state.bin")
        with open(path, "wb") as f:
            f.write(bytes(data))
        here = os.path.dirname(os.path.abspath(__file__))
        out = subprocess.run([sys.executable, "-c", CONTINUE, here, fmu, path, "10", repr(h), repr(t)],
                             capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[:-1] == want
