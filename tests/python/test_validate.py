"""Every shipped FMU is clean for two independent checkers: fmpy's validator (XSD, variable names,
units, ModelStructure) reports nothing, and fmu-manipulation-toolbox's `fmutool -check` reports
neither an error nor a warning."""
import pathlib
import subprocess
import sys

from fmpy.validation import validate_fmu


def test_fmpy_validate_reports_nothing(fmu):
    assert validate_fmu(fmu) == []


def test_fmutool_check_is_clean(fmu):
    exe = pathlib.Path(sys.executable).with_name("fmutool")
    out = subprocess.run([str(exe), "-input", fmu, "-check"], capture_output=True, text=True, timeout=300)
    text = out.stdout + out.stderr
    assert out.returncode == 0, text
    bad = [l for l in text.splitlines() if any(k in l for k in ("ERROR", "CRITICAL", "WARNING"))]
    assert not bad, text
    assert "compliant with FMI-2.0" in text, text
    assert "No semantic error" in text, text
