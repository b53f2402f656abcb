"""MuJoCo's cost per step on the peers' models, for comparison with triad's criterion figures
measured in the same run (see bench/speed.sh).

Protocol of the peers harness (../shared/peers, "cost"): the model's initial state, 2 s of
simulated time at h = 1e-3, `mj_step` looped in C between output samples (dt_out = 0.01);
the wall time of the stepping only, median over `--repeat` runs after one warm-up run.

    python bench/mujoco_same_run.py --shared ../shared --repeat 5 --out target/speed/mujoco.json
"""
import argparse
import json
import os
import statistics
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--shared", required=True, help="path of the shared folder (design/, peers/)")
    ap.add_argument("--models", default="double_pendulum,chain100")
    ap.add_argument("--methods", default="Euler,RK4")
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--out", required=True)
    a = ap.parse_args()
    peers = os.path.join(a.shared, "peers")
    sys.path.insert(0, peers)
    sys.path.insert(0, os.path.join(peers, "engines"))
    import mujoco  # noqa: F401  (fails early with a clear message if missing)
    import nmodel as nm
    from mujoco_engine import Sim

    out = {}
    for name in a.models.split(","):
        model = nm.load(os.path.join(peers, "models", f"{name}.json"))
        for method in a.methods.split(","):
            sim = Sim(model, method, 1e-3)
            sim.run(2.0, 0.01)  # warm-up
            per_step = []
            for _ in range(a.repeat):
                _, _, _, wall, nsteps = sim.run(2.0, 0.01)
                per_step.append(wall / nsteps * 1e6)
            out[f"{name}/{method}"] = {
                "median_us": statistics.median(per_step),
                "min_us": min(per_step),
                "runs_us": per_step,
            }
            print(f"mujoco {method:6s} {name:16s} {statistics.median(per_step):9.2f} us/step "
                  f"(min {min(per_step):.2f})", flush=True)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out, "w") as f:
        json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
