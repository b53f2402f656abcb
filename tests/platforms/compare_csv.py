"""Compares two result CSVs of `triad simulate` (the same columns), column by column:
|a - b| <= atol + rtol * max|b| over the column (atol for columns that are zero up to round-off). Used for the CLI built for another platform, whose
libm rounds differently. Prints the worst column; exits 1 when a column differs by more.

    python tests/platforms/compare_csv.py A.csv B.csv [--rtol 1e-9] [--atol 1e-12]
"""
import argparse
import csv
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("a")
    ap.add_argument("b")
    ap.add_argument("--rtol", type=float, default=1e-9)
    ap.add_argument("--atol", type=float, default=1e-12)
    args = ap.parse_args()
    with open(args.a, newline="") as f:
        a = list(csv.reader(f))
    with open(args.b, newline="") as f:
        b = list(csv.reader(f))
    if a[0] != b[0] or len(a) != len(b):
        print(f"{args.a} and {args.b} differ in columns or rows", file=sys.stderr)
        return 1
    worst = (0.0, "")
    for j, name in enumerate(a[0]):
        col_a = [float(r[j]) for r in a[1:]]
        col_b = [float(r[j]) for r in b[1:]]
        allowed = args.atol + args.rtol * max(abs(v) for v in col_b)
        d = max(abs(x - y) for x, y in zip(col_a, col_b))
        worst = max(worst, (d / allowed, name))
    print(f"largest difference / allowed: {worst[0]:.2e} ({worst[1]})")
    if worst[0] > 1.0:
        print(f"more than atol {args.atol:g} + rtol {args.rtol:g} x the column's scale", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
