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
"$PY" bench.py --external triad="$ENGINE --variant native" --external triad-fmu="$ENGINE --variant fmu" \
  --external-methods EM2,EM4 --out "$OUT" "$@"
"$PY" report.py --res "$OUT" --png-dir "$OUT"
