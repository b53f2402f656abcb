#!/usr/bin/env bash
# Speed of the core step against a peer measured in the same run: MuJoCo (Euler, RK4; the peers'
# protocol) before and after triad's criterion step benches (double pendulum, chain100,
# chain1000; order 2, h = 1e-3, 2 s runs from the initial state), then the table of
# bench/speed_table.py. The machine is shared and its speed drifts by ×2 within minutes, so the
# ratios to MuJoCo are the figures to compare with the targets, not the raw µs.
#   bash bench/speed.sh            (MEASURE=seconds per criterion bench, default 5)
# Results: target/speed/ (mujoco_before.json, criterion.txt, mujoco_after.json, windows.txt,
# table.md).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
SHARED="${TRIAD_SHARED:-$ROOT/../shared}"
cd "$ROOT"
VENV="$ROOT/target/venv-peers"
if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import mujoco, numpy" 2>/dev/null; then
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install -q mujoco numpy
fi
OUT="$ROOT/target/speed"
mkdir -p "$OUT"
cargo bench --bench step --no-run --quiet
cargo build --release --quiet --example step_profile
"$VENV/bin/python" bench/mujoco_same_run.py --shared "$SHARED" --out "$OUT/mujoco_before.json"
cargo bench --bench step -- --warm-up-time 1 --measurement-time "${MEASURE:-5}" \
  'em/step/(double_pendulum|chain100|chain1000)$' 2>&1 | tee "$OUT/criterion.txt"
"$VENV/bin/python" bench/mujoco_same_run.py --shared "$SHARED" --out "$OUT/mujoco_after.json"
# the whole 2 s run (2000 steps) of chain100 and chain1000, alternating, three times each: the
# cost ratio over the same simulated motion (criterion's few seconds cover only the first
# steps of chain1000's run)
: > "$OUT/windows.txt"
for _ in 1 2 3; do
  for m in chain100 chain1000; do
    target/release/examples/step_profile "$m" 2000 | tee -a "$OUT/windows.txt"
  done
done
"$VENV/bin/python" bench/speed_table.py "$OUT"
