"""Compares two FMUs of one model built by triad on different platforms (the Linux CLI and
triad.exe under wine): the same entries in the same order, every entry byte-identical except
documentation/scene.html, the 3-D preview, whose initial poses come from the platform's libm
(a last-bit difference of a sine changes a float there); that one must have the same length.

    python tests/platforms/compare_fmu.py A.fmu B.fmu
"""
import sys
import zipfile

PREVIEW = "documentation/scene.html"


def main():
    a, b = (zipfile.ZipFile(p) for p in sys.argv[1:3])
    names_a, names_b = a.namelist(), b.namelist()
    if names_a != names_b:
        print(f"entries differ: {names_a} / {names_b}", file=sys.stderr)
        return 1
    preview = "identical too"
    for name in names_a:
        x, y = a.read(name), b.read(name)
        if x == y:
            continue
        if name == PREVIEW and len(x) == len(y):
            preview = f"{sum(p != q for p, q in zip(x, y))} bytes apart (libm round-off)"
            continue
        print(f"{name} differs", file=sys.stderr)
        return 1
    print(f"{len(names_a)} entries identical, but the preview: {preview}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
