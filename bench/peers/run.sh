#!/usr/bin/env bash
# Runs the peers harness (../shared/peers) with triad beside MuJoCo, Pinocchio, Exudyn and PyBullet
# in one run: triad in process (orders 2 and 4) and through its FMU under fmpy.
#   bash bench/peers/run.sh [--quick] [extra bench.py args]
# Results: target/peers/results*/ (accuracy.json, scaling.json, tables.md, summary.md, plots).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/../.." && pwd)"
SHARED="${TRIAD_SHARED:-$ROOT/../shared}"
cd "$ROOT"
cargo build --release --quiet --bin triad --example peers_native
VENV="$ROOT/target/venv-peers"
if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import mujoco, pinocchio, exudyn, pybullet, fmpy" 2>/dev/null; then
  python3 -m venv "$VENV"
  "$VENV/bin/pip" install -q mujoco pin exudyn numpy scipy matplotlib pybullet example-robot-data fmpy
fi
WORK="$ROOT/target/peers"
mkdir -p "$WORK"
# the harness writes its models/ and cache/ beside itself: run a copy
rm -rf "$WORK/harness" && mkdir -p "$WORK/harness"
(cd "$SHARED/peers" && tar --exclude=./results --exclude='*.png' -cf - .) | (cd "$WORK/harness" && tar -xf -)
chmod -R u+w "$WORK/harness"
cd "$WORK/harness"
PY="$VENV/bin/python"
ENGINE="$PY $ROOT/bench/peers/triad_engine.py --model {model} --h {h} --t-end {t_end} --dt-out {dt_out} --out {out} --method {method}"
OUT="${TRIAD_PEERS_OUT:-$WORK/results}"
# every engine on a finer grid of fixed steps than the harness's default (so that "the cheapest
# run reaching an error" is not decided by a coarse grid)
H="${TRIAD_PEERS_H:-1e-4,2e-4,5e-4,1e-3,2e-3,5e-3,1e-2,2e-2,5e-2}"
"$PY" bench.py --external triad="$ENGINE --variant native" --external triad-fmu="$ENGINE --variant fmu" \
  --external-methods EM2,EM4,EM4s5 --h "$H" --out "$OUT" "$@"
# triad's tolerance sweep: error-controlled steps, ceiling and communication step 0.1 s, rtol on
# a 1-2-5 grid like the fixed steps (order 4: 1e-2 ... 1e-9, order 2: 1e-3 ... 1e-6)
RTOLS() { local e m out=""; for e in $(seq "$2" "$3"); do for m in 5 2 1; do out+="$1-${m}e-$e,"; done; done; echo "$out"; }
SWEEP="${TRIAD_PEERS_RTOL:-$(RTOLS EMa2 4 6)EMa2-1e-3,$(RTOLS EMa4 3 9)EMa4-1e-2}"
"$PY" bench.py --engines '' --external triad="$ENGINE --variant native" \
  --external-methods "$SWEEP" \
  --h 0.1 --no-scaling --out "$OUT/adaptive" "$@"
"$PY" - "$OUT" <<'PY'
import json, os, sys
out = sys.argv[1]
acc = json.load(open(os.path.join(out, "accuracy.json")))
acc += json.load(open(os.path.join(out, "adaptive", "accuracy.json")))
json.dump(acc, open(os.path.join(out, "accuracy.json"), "w"), indent=1)
PY
"$PY" report.py --res "$OUT" --png-dir "$OUT"
