"""Table of bench/speed.sh: triad's criterion step times against MuJoCo measured in the same run,
and the issue's targets restated as ratios to the peer figures they were set against.

    python bench/speed_table.py target/speed
"""
import json
import os
import sys

# the targets (µs) and the MuJoCo figures of the run they were set against (issue 2)
TARGETS = {"double_pendulum": 5.0, "chain100": 300.0}
MUJOCO_THEN = {"double_pendulum": {"Euler": 2.9, "RK4": 13.0}, "chain100": {"Euler": 212.0, "RK4": 689.0}}


def criterion_us(root, name):
    p = os.path.join(root, "target", "criterion", "em", "step", name, "new", "estimates.json")
    with open(p) as f:
        return json.load(f)["median"]["point_estimate"] / 1e3


def main():
    out = sys.argv[1]
    root = os.path.abspath(os.path.join(out, "..", ".."))
    runs = [json.load(open(os.path.join(out, f))) for f in ("mujoco_before.json", "mujoco_after.json")]
    lines = ["| model | triad EM2 (µs) | MuJoCo Euler (µs) | MuJoCo RK4 (µs) | triad / RK4 | target / RK4 then "
             "| triad / Euler | target / Euler then | target met in peer units |",
             "|---|---|---|---|---|---|---|---|---|"]
    t = {}
    for name in ("double_pendulum", "chain100"):
        t[name] = criterion_us(root, name)
        mj = {m: sum(r[f"{name}/{m}"]["median_us"] for r in runs) / len(runs) for m in ("Euler", "RK4")}
        then = MUJOCO_THEN[name]
        r_rk4, r_eu = t[name] / mj["RK4"], t[name] / mj["Euler"]
        g_rk4, g_eu = TARGETS[name] / then["RK4"], TARGETS[name] / then["Euler"]
        met = "yes" if (r_rk4 <= g_rk4 and r_eu <= g_eu) else ("RK4 only" if r_rk4 <= g_rk4 else "no")
        lines.append(f"| {name} | {t[name]:.2f} | {mj['Euler']:.2f} | {mj['RK4']:.2f} | {r_rk4:.3f} | {g_rk4:.3f} "
                     f"| {r_eu:.2f} | {g_eu:.2f} | {met} |")
    wpath = os.path.join(out, "windows.txt")
    if os.path.exists(wpath):
        w = {}
        for line in open(wpath):
            # "chain100: 2000 steps, 3.127 iterations (1.024 with a fresh Jacobian) per step, 495.94 µs per step"
            name = line.split(":")[0]
            w.setdefault(name, []).append(float(line.split(",")[-1].split()[0]))
        if "chain100" in w and "chain1000" in w:
            m100, m1000 = sorted(w["chain100"])[len(w["chain100"]) // 2], sorted(w["chain1000"])[len(w["chain1000"]) // 2]
            lines.append("")
            lines.append(f"whole 2 s runs (2000 steps, median of {len(w['chain1000'])}): chain100 {m100:.1f} µs, "
                         f"chain1000 {m1000:.0f} µs per step; cost(1000)/cost(100) = {m1000 / m100:.2f} (target ≤ 15)")
    try:
        t1000 = criterion_us(root, "chain1000")
        lines.append("")
        lines.append(f"criterion: cost(chain1000) / cost(chain100) = {t1000:.0f} / {t['chain100']:.1f} = "
                     f"{t1000 / t['chain100']:.2f} (chain1000's bench covers only the first steps of its run)")
    except FileNotFoundError:
        pass
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(out, "table.md"), "w") as f:
        f.write(text + "\n")


if __name__ == "__main__":
    main()
