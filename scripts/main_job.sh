#!/usr/bin/env bash
# The main job: build the robot_arm FMU from its robot description (URDF), run it under fmpy in
# closed loop with a PD controller, write results.csv and results.png, and results.html: the
# 3-D replay of the run (open it in a browser).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cargo build --release --quiet
mkdir -p out
target/release/triad build modelDescription/robot_arm/robot_arm.urdf -o out/robot_arm.fmu
.venv/bin/python scripts/main_job.py out/robot_arm.fmu --stop 3 --csv results.csv --plot results.png
target/release/triad animate modelDescription/robot_arm/robot_arm.urdf results.csv -o results.html
