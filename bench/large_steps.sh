#!/usr/bin/env bash
# Steps too large for the motion: each model run at fixed steps h = 0.02 … 0.2 s (10 s of
# motion; chain100 2 s) at order 2, order 4 (triple jump) and order 4 with five stages
# (step_profile: its default start, tolerance 1e-10). Prints per run whether every step
# completed, |E − E₀ − W| at the end (J) and the wall-clock µs per step (noisy: compare within
# one run only).
#   bash bench/large_steps.sh            (≈ 3 min)
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
cargo build --release --quiet --example step_profile
BIN="$ROOT/target/release/examples/step_profile"
echo "| model | h (s) | order 2 | order 4, 3 stages | order 4, 5 stages |"
echo "|---|---|---|---|---|"
for m in double_pendulum top free fourbar chain10 chain100; do
  for h in 0.02 0.05 0.08 0.1 0.15 0.2; do
    span=10
    [ "$m" = chain100 ] && span=2
    n=$(python3 -c "print(max(1, round($span / $h)))")
    line="| $m | $h"
    for env in "" "TRIAD_ORDER4=1" "TRIAD_ORDER4=1 TRIAD_STAGES5=1"; do
      # shellcheck disable=SC2086 # $env is zero or more VAR=value words
      if out=$(env $env "$BIN" "$m" "$n" "$h" 2>&1); then
        e=$(echo "$out" | grep -o "work = [-0-9.e]*" | cut -d' ' -f3)
        us=$(echo "$out" | tail -1 | grep -o "[0-9.]* µs")
        line="$line | $e J, $us"
      else
        line="$line | failed: $(echo "$out" | grep -o 'step: [A-Za-z]*' | head -1)"
      fi
    done
    echo "$line |"
  done
done
