#!/usr/bin/env bash
# Builds triad's FMU runtime (the cdylib every FMU carries, `--no-default-features`) for every
# platform on this one Linux machine, and optionally the portable distribution:
#
#     bash scripts/platforms.sh                    # all runtimes into target/runtime/<platform>/
#     bash scripts/platforms.sh --only win64,linux64
#     bash scripts/platforms.sh --dist             # and dist/triad-<version>/ (CLI + runtime/)
#     TRIAD_DIST_EXE=0 bash scripts/platforms.sh --dist   # the distribution without triad.exe
#
# Platforms and their files (the layout `triad build` reads, docs/guide/platforms.md):
#   linux64/libtriad.so        x86_64 Linux, glibc >= 2.17   cargo-zigbuild, rustup's toolchain
#   win64/triad.dll            x86_64 Windows                Debian's rustc 1.96 + build-std, mingw-w64
#   darwin64/libtriad.dylib    macOS x86_64 (>= 10.12) + arm64 (>= 11.0), one universal file
#                                                            cargo-zigbuild + build-std (Debian's rustc)
#   aarch64-linux/libtriad.so  aarch64 Linux, glibc >= 2.17  cargo-zigbuild + build-std (Debian's rustc)
#
# Idempotent: toolchains are installed once (apt: Debian's rustc-web 1.96 with its library
# source, mingw-w64, wine64, qemu-user, the aarch64 C library; pip: ziglang, cargo-zigbuild and
# lief in target/platforms/tools), and every build keeps its standard library and objects in
# target/<triple>/fmu, so a second run only relinks what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD

ALL="linux64 win64 darwin64 aarch64-linux"
ONLY=$ALL
DIST=0
while [ $# -gt 0 ]; do
  case "$1" in
    --only) ONLY=${2//,/ }; shift 2 ;;
    --only=*) ONLY=${1#--only=}; ONLY=${ONLY//,/ }; shift ;;
    --dist) DIST=1; shift ;;
    -h|--help) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "platforms.sh: unknown argument $1 (--only LIST, --dist)" >&2; exit 2 ;;
  esac
done
for p in $ONLY; do
  case " $ALL " in *" $p "*) ;; *) echo "platforms.sh: unknown platform $p (one of: $ALL)" >&2; exit 2 ;; esac
done

OUT=$ROOT/target/runtime
TOOLS=$ROOT/target/platforms/tools
LOGS=$ROOT/target/platforms/logs
mkdir -p "$OUT" "$LOGS"
stamp() { date +%s; }
T0=$(stamp)

# ---- toolchains -------------------------------------------------------------------------------
APT=(rustc-web cargo-web rust-web-src libstd-rust-web-dev gcc-mingw-w64-x86-64 wine64 qemu-user
     libc6-arm64-cross gcc-aarch64-linux-gnu)
need=()
for pkg in "${APT[@]}"; do dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg"); done
if [ ${#need[@]} -gt 0 ]; then
  echo "platforms: apt-get install ${need[*]}"
  if [ "$(id -u)" = 0 ]; then SUDO=""; else SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi
PIP_PINS=(ziglang==0.17.1 cargo-zigbuild==0.24.1 lief==1.0.0 pytest==9.2.0)
if [ ! -x "$TOOLS/bin/cargo-zigbuild" ] || ! printf '%s\n' "${PIP_PINS[@]}" | cmp -s - "$TOOLS/.pins"; then
  echo "platforms: pip install ${PIP_PINS[*]} into $TOOLS"
  python3 -m venv "$TOOLS"
  "$TOOLS/bin/pip" install -q "${PIP_PINS[@]}"
  printf '%s\n' "${PIP_PINS[@]}" > "$TOOLS/.pins"
fi
# zig and cargo-zigbuild alone in one folder, so that it can go before /usr/bin
ZIGBIN=$ROOT/target/platforms/bin
mkdir -p "$ZIGBIN"
ln -sf "$("$TOOLS/bin/python" -c 'import ziglang, os; print(os.path.dirname(ziglang.__file__))')/zig" "$ZIGBIN/zig"
ln -sf "$TOOLS/bin/cargo-zigbuild" "$ZIGBIN/cargo-zigbuild"
echo "platforms: toolchains ready ($(( $(stamp) - T0 )) s)"

ZIGPATH=$ZIGBIN:$PATH
# Debian's rustc 1.96 and its library source, for the targets rustup cannot fetch here
DEBPATH=$ZIGBIN:/usr/bin:$PATH
COMMON=(rustc --lib --crate-type cdylib --no-default-features --profile fmu --locked)
BUILD_STD=(-Zbuild-std=std,panic_unwind)

run_logged() { # name command... : runs, keeps the log, shows its tail on failure
  local name=$1; shift
  local t=$(stamp)
  if ! "$@" >"$LOGS/$name.log" 2>&1; then
    tail -40 "$LOGS/$name.log" >&2
    echo "platforms: $name failed (log: $LOGS/$name.log)" >&2
    exit 1
  fi
  echo "platforms: $name built in $(( $(stamp) - t )) s"
}

debian_env() { env -u RUSTUP_TOOLCHAIN -u RUSTC -u CARGO -u RUSTDOC PATH="$DEBPATH" RUSTC_BOOTSTRAP=1 "$@"; }

build_linux64() {
  run_logged linux64 env PATH="$ZIGPATH" cargo-zigbuild "${COMMON[@]}" \
    --target x86_64-unknown-linux-gnu.2.17
  install -D -m 755 target/x86_64-unknown-linux-gnu/fmu/libtriad.so "$OUT/linux64/libtriad.so"
}

build_win64() {
  run_logged win64 debian_env CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER=x86_64-w64-mingw32-gcc \
    cargo "${COMMON[@]}" "${BUILD_STD[@]}" --target x86_64-pc-windows-gnu
  install -D -m 755 target/x86_64-pc-windows-gnu/fmu/triad.dll "$OUT/win64/triad.dll"
}

build_aarch64_linux() {
  run_logged aarch64-linux debian_env cargo-zigbuild "${COMMON[@]}" "${BUILD_STD[@]}" \
    --target aarch64-unknown-linux-gnu.2.17
  install -D -m 755 target/aarch64-unknown-linux-gnu/fmu/libtriad.so "$OUT/aarch64-linux/libtriad.so"
}

build_darwin64() {
  # the install name is @rpath/libtriad.dylib, not the build path; 10.12 is the x86_64 floor,
  # rustc raises it to 11.0 for arm64 (the first macOS on Apple silicon)
  local rpath=(-C link-arg=-Wl,-install_name,@rpath/libtriad.dylib)
  for arch in x86_64 aarch64; do
    local floor=10.12
    [ "$arch" = aarch64 ] && floor=11.0
    run_logged "darwin64-$arch" debian_env MACOSX_DEPLOYMENT_TARGET=$floor \
      cargo-zigbuild "${COMMON[@]}" "${BUILD_STD[@]}" --target "$arch-apple-darwin" -- "${rpath[@]}"
  done
  mkdir -p "$OUT/darwin64"
  "$TOOLS/bin/python" tests/platforms/macho.py lipo "$OUT/darwin64/libtriad.dylib" \
    target/x86_64-apple-darwin/fmu/libtriad.dylib target/aarch64-apple-darwin/fmu/libtriad.dylib
}

for p in $ONLY; do
  case $p in
    linux64) build_linux64 ;;
    win64) build_win64 ;;
    darwin64) build_darwin64 ;;
    aarch64-linux) build_aarch64_linux ;;
  esac
done
ls -l $(for p in $ONLY; do ls "$OUT/$p"/* ; done)

if [ "$DIST" = 1 ]; then
  version=$(sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -1)
  dist=$ROOT/dist/triad-$version
  rm -rf "$dist" && mkdir -p "$dist"
  # the CLI for x86_64 Linux at glibc 2.17 (the plots' font is embedded: no fontconfig needed)
  run_logged dist-cli env PATH="$ZIGPATH" cargo-zigbuild zigbuild \
    --release --locked --bin triad --target x86_64-unknown-linux-gnu.2.17
  install -m 755 target/x86_64-unknown-linux-gnu/release/triad "$dist/triad"
  # triad.exe, the CLI for Windows (Debian's rustc + build-std, as the win64 runtime; its own
  # standard library build in target/x86_64-pc-windows-gnu/release); TRIAD_DIST_EXE=0 skips it
  if [ "${TRIAD_DIST_EXE:-1}" = 1 ]; then
    run_logged dist-exe debian_env CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER=x86_64-w64-mingw32-gcc \
      cargo build --release --locked --bin triad "${BUILD_STD[@]}" --target x86_64-pc-windows-gnu
    install -m 755 target/x86_64-pc-windows-gnu/release/triad.exe "$dist/triad.exe"
  fi
  cp -r "$OUT" "$dist/runtime"
  # the README with what it links to: the guide, its pictures, ARCHITECTURE and BENCHMARKS
  cp README.md ARCHITECTURE.md BENCHMARKS.md "$dist/"
  mkdir -p "$dist/docs" && cp -r docs/guide docs/*.png "$dist/docs/"
  echo "platforms: wrote $dist"
  ls -lR "$dist" | sed -n '1,40p'
fi
echo "platforms: done in $(( $(stamp) - T0 )) s"
