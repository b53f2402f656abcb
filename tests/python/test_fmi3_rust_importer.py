"""FMI 3.0 FMUs under a second importer: the Rust `fmi` crate of crates.io (issue 37).

`tests/importers/rust_fmi` (its own cargo workspace and lock file, built here into
`target/importers/rust_fmi`) is `fmi3_run`, a small Co-Simulation driver on `fmi` 0.8. For every
shipped model (`modelDescription/*/spec.toml`), built here with `TRIAD_BIN` as FMI 3 and FMI 2:

- the crate's schema (`fmi-schema`) parses the FMI 3 modelDescription.xml; the only problems it
  may report are its own known gaps (`schema-gap`: standard Float64 attributes such as `unit`,
  which fmi-schema 0.8.0 does not know and rejects), anything else fails the test;
- it reads the instantiationToken (the FMI 2 GUID) and the arrays' dimensions (`body.*.R` 3x3,
  every array as fmpy reads it);
- it runs the FMU with constant non-zero inputs on fmpy's output grid, and every output element
  equals, bit for bit, fmpy's `simulate_fmu` of the FMI 2 FMU with the same inputs.

Building `fmi3_run` needs cargo and libclang (fmi-sys runs bindgen; `bash scripts/setup.sh
--importers` installs Debian's libclang-dev): without them the tests skip, saying why, and fail
under `CI=true`.
"""
import csv
import glob
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

import conftest

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
CRATE = ROOT / "tests" / "importers" / "rust_fmi"
TARGET = ROOT / "target" / "importers" / "rust_fmi"
SPECS = sorted(ROOT.glob("modelDescription/*/spec.toml"))
NAMES = [s.parent.name for s in SPECS]

STOP = 1.0  # at most this much simulated time per model
MAX_STEPS = 1000
# what fmi3_run may report as fmi-schema's gaps: FMI 3.0 attributes of Float64 (fmi3Variable.xsd)
SCHEMA_GAPS = {"quantity", "unit", "displayUnit", "relativeQuantity", "unbounded", "nominal"}


def _unavailable(why):
    if conftest.IN_CI:
        pytest.fail(f"{why} -- CI=true, so this is a failure, not a skip")
    pytest.skip(why)


def _libclang():
    if os.environ.get("LIBCLANG_PATH"):
        return True
    patterns = ["/usr/lib/llvm-*/lib/libclang*.so*", "/usr/lib/*-linux-gnu/libclang*.so*", "/usr/lib/libclang*.so*"]
    # libclang-cpp is the C++ library, not the C API bindgen loads
    return any("libclang-cpp" not in p for pat in patterns for p in glob.glob(pat))


@pytest.fixture(scope="module")
def fmi3_run():
    """The importer, built once (cargo's own up-to-date check makes a rebuild cheap)."""
    cargo = shutil.which("cargo")
    if not cargo:
        _unavailable("cargo is not on PATH: cannot build the Rust fmi importer")
    if not _libclang():
        _unavailable("libclang is missing (fmi-sys runs bindgen): bash scripts/setup.sh --importers")
    done = subprocess.run(
        [cargo, "build", "--locked", "--quiet", "--manifest-path", str(CRATE / "Cargo.toml"), "--target-dir", str(TARGET)],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, f"building {CRATE} failed:\n{done.stderr[-4000:]}"
    exe = TARGET / "debug" / "fmi3_run"
    assert exe.exists(), exe
    return str(exe)


def _read_csv(path):
    """header, rows of floats parsed from the importer's round-trip strings."""
    with open(path, newline="") as f:
        lines = list(csv.reader(f))
    header = lines[0]
    rows = np.array([[float(x) for x in line] for line in lines[1:]], dtype=np.float64)
    return header, rows


@pytest.mark.parametrize("name", NAMES)
def test_rust_fmi_equals_fmpy_fmi2(fmi3_run, built, name, tmp_path):
    from fmpy import read_model_description, simulate_fmu

    fmu2, fmu3 = built(name)
    md2 = read_model_description(fmu2)
    md3 = read_model_description(fmu3)
    experiment = md3.defaultExperiment
    start = float(experiment.startTime)
    stop = min(float(experiment.stopTime), start + STOP)
    step = max(float(experiment.stepSize), (stop - start) / MAX_STEPS)

    # a few non-zero scalar inputs, held constant
    inputs = [v.name for v in md3.modelVariables if v.causality == "input" and v.type == "Float64" and not v.dimensions][:3]
    values = [0.3, -0.2, 0.15][: len(inputs)]

    out = tmp_path / "rust_fmi.csv"
    done = subprocess.run(
        [fmi3_run, fmu3, repr(stop), repr(step), str(out)] + [f"{n}={v!r}" for n, v in zip(inputs, values)],
        capture_output=True,
        text=True,
    )
    assert done.returncode == 0, f"fmi3_run failed on {name}:\n{done.stderr}\n{done.stdout[-2000:]}"
    facts = [line.split(" ") for line in done.stdout.splitlines()]

    # the crate's schema parsed our XML; what it could not parse is its own known gap
    gaps = {f[1] for f in facts if f[0] == "schema-gap"}
    assert gaps <= SCHEMA_GAPS, f"fmi-schema problems with {name}'s modelDescription.xml: {gaps - SCHEMA_GAPS}"

    # what the importer read: the token, the arrays
    read = {f[0]: f[1] for f in facts if f[0] in ("fmiVersion", "instantiationToken", "modelIdentifier")}
    assert read["fmiVersion"] == "3.0"
    assert read["instantiationToken"] == md3.instantiationToken == md2.guid
    assert read["modelIdentifier"] == md3.coSimulation.modelIdentifier
    variables = {f[1]: f for f in facts if f[0] == "variable"}
    assert list(variables) == [v.name for v in md3.modelVariables]
    for v in md3.modelVariables:
        if v.type != "Float64":
            continue
        dims = "x".join(str(d.start) for d in v.dimensions) or "-"
        assert variables[v.name][2:] == [v.causality, "Float64", dims], v.name
    bodies = [n for n in variables if n.startswith("body.") and n.endswith(".R")]
    assert bodies, f"{name} has no body.*.R"
    for b in bodies:
        assert variables[b][4] == "3x3", b

    header, rust = _read_csv(out)
    assert header[0] == "time"
    names2 = {v.name for v in md2.modelVariables}
    missing = [n for n in header[1:] if n not in names2]
    assert not missing, f"output elements without an FMI 2 scalar of that name: {missing[:5]}"
    assert len(header) - 1 == sum(1 for v in md2.modelVariables if v.causality == "output")

    signal = None
    if inputs:
        dtype = [("time", np.float64)] + [(n, np.float64) for n in inputs]
        signal = np.array([(start, *values), (stop, *values)], dtype=dtype)
    r2 = simulate_fmu(
        fmu2,
        fmi_type="CoSimulation",
        start_time=start,
        stop_time=stop,
        output_interval=step,
        input=signal,
        output=header[1:],
    )
    fmpy = np.column_stack([np.asarray(r2[n], dtype=np.float64) for n in header])
    # align by time (the same grid is expected; a different start row or grid is tolerated)
    times = rust[:, 0]
    common = np.intersect1d(times, fmpy[:, 0])
    assert len(common) == len(fmpy) and len(common) > 2, (
        f"{name}: time grids differ: fmi3_run {len(times)} rows {times[:3]}..., fmpy {len(fmpy)} rows {fmpy[:3, 0]}..."
    )
    a = rust[np.isin(times, common)]
    b = fmpy[np.isin(fmpy[:, 0], common)]
    for k, col in enumerate(header):
        if a[:, k].tobytes() != b[:, k].tobytes():
            diff = np.nanmax(np.abs(a[:, k] - b[:, k]))
            pytest.fail(f"{name}: {col} differs between the Rust fmi importer (FMI 3) and fmpy (FMI 2): max |diff| {diff}")
