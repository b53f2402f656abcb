#!/usr/bin/env bash
# Installs what triad needs on a fresh Debian machine: the Python venv (.venv) used by the FMU
# tests, the examples and the main job (the Rust build needs no system library: the plots' font
# is embedded). Idempotent: steps already done are skipped.
#
#     bash scripts/setup.sh            # the above
#     bash scripts/setup.sh --browser  # and Debian's chromium, for the 3-D replay's browser test
#                                      # (tests/python/test_animate.py); .ci/run asks for it
#     bash scripts/setup.sh --importers  # and Debian's libclang-dev, for the Rust FMI 3 importer
#                                      # of tests/python/test_fmi3_rust_importer.py (fmi-sys runs
#                                      # bindgen); .ci/run asks for it
# (the options combine: --browser --importers)
set -euo pipefail
cd "$(dirname "$0")/.."

# /dev/null must be the null device (see .ci/run): repair a machine where it became a file
if [ ! -c /dev/null ] && [ "$(id -u)" = 0 ]; then
  rm -f /dev/null && mknod -m 666 /dev/null c 1 3
fi

packages=()
for arg in "$@"; do
  case "$arg" in
    --browser) packages+=(chromium) ;;
    --importers) packages+=(libclang-dev) ;;
    *) echo "setup: unknown option $arg (--browser, --importers)" >&2; exit 2 ;;
  esac
done
need_apt=()
for pkg in "${packages[@]}"; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need_apt+=("$pkg")
done
if [ ${#need_apt[@]} -gt 0 ]; then
  echo "setup: installing ${need_apt[*]}"
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need_apt[@]}" >/dev/null
fi

if [ ! -x .venv/bin/python ] || ! .venv/bin/python -c "import fmpy" >/dev/null 2>&1 \
   || ! cmp -s tests/python/requirements.txt .venv/.requirements 2>/dev/null \
   || ! cmp -s tests/python/requirements-nodeps.txt .venv/.requirements-nodeps 2>/dev/null; then
  echo "setup: creating .venv"
  python3 -m venv .venv
  .venv/bin/pip install -q --upgrade pip
  .venv/bin/pip install -q -r tests/python/requirements.txt
  .venv/bin/pip install -q --no-deps -r tests/python/requirements-nodeps.txt
  cp tests/python/requirements.txt .venv/.requirements
  cp tests/python/requirements-nodeps.txt .venv/.requirements-nodeps
fi
