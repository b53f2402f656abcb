#!/usr/bin/env bash
# fmi2DoStep of the glibc-2.17 linux64 runtime (scripts/platforms.sh) against the host build
# (cargo build --release), in the same run: tests/harness/fmi_harness.c drives robot_arm's FMU
# through STEPS fmi2DoStep (1 s, inputs set and every output read at each step; the harness
# repeats the steps after a state restore and after a reset), whole process timed, the two
# libraries alternated ROUNDS times. Prints both medians and their ratio (BENCHMARKS "Platforms").
#
#     bash bench/platforms_step.sh [STEPS=6500] [ROUNDS=5]
set -euo pipefail
cd "$(dirname "$0")/.."
STEPS=${1:-6500}
ROUNDS=${2:-5}
RUNTIME=${TRIAD_RUNTIME_DIR:-target/runtime}
[ -f "$RUNTIME/linux64/libtriad.so" ] || { echo "no $RUNTIME/linux64/libtriad.so: bash scripts/platforms.sh --only linux64" >&2; exit 1; }
cargo build --release --quiet
W=target/bench_platforms
rm -rf "$W" && mkdir -p "$W/fmu"
gcc -O2 -o "$W/fmi_harness" tests/harness/fmi_harness.c -ldl -lm
target/release/triad build modelDescription/robot_arm/spec.toml --platforms host -o "$W/robot_arm.fmu" >/dev/null
(cd "$W/fmu" && unzip -q ../robot_arm.fmu)
python3 - "$W" "$RUNTIME/linux64/libtriad.so" target/release/libtriad.so "$STEPS" "$ROUNDS" <<'PY'
import statistics, subprocess, sys, time
w, old, host, steps, rounds = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
times = {old: [], host: []}
for _ in range(rounds):
    for lib in (old, host):
        t = time.perf_counter()
        p = subprocess.run([f"{w}/fmi_harness", lib, f"{w}/fmu", steps], capture_output=True, text=True)
        times[lib].append(time.perf_counter() - t)
        assert p.returncode == 0, p.stdout[-2000:]
a, b = statistics.median(times[old]), statistics.median(times[host])
print(f"glibc 2.17 runtime: median {a:.3f} s {['%.3f' % x for x in times[old]]}")
print(f"host build:         median {b:.3f} s {['%.3f' % x for x in times[host]]}")
print(f"ratio 2.17 / host: {a / b:.3f}")
PY
