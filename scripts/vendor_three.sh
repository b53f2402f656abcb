#!/usr/bin/env bash
# Brings three.js into viewer/vendor/ reproducibly: `npm pack`s the pinned version from the npm
# registry, checks its integrity hash, and bundles the parts the viewer uses
# (viewer/vendor/three_entry.js) with the pinned esbuild into one minified script,
# viewer/vendor/three.bundle.min.js, with three's LICENSE beside it. The outputs are committed
# and inlined into every page by `include_str!`, so building triad never needs npm; run this only
# to change the version (then commit the three files it writes).
#
#     bash scripts/vendor_three.sh          # rewrite viewer/vendor/
#     bash scripts/vendor_three.sh --check  # rebuild in a temporary folder, compare with the committed files
set -euo pipefail
cd "$(dirname "$0")/.."

THREE_VERSION=0.187.0
THREE_INTEGRITY="sha512-Qiu7R+Cmh8CstZsY1uJOSWnVlfo7ZtNLV7mF8Jltk3LB3AtDu9cRZlcnRKkAk8Y4z6KKw35z7Y7Urd7jWY8etA=="
ESBUILD_VERSION=0.28.2

out=viewer/vendor
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# the pinned tarball, checked against its integrity hash (npm's sha512, base64)
(cd "$work" && npm pack --silent "three@$THREE_VERSION" >/dev/null)
tarball="$work/three-$THREE_VERSION.tgz"
got="sha512-$(openssl dgst -sha512 -binary "$tarball" | base64 -w0)"
if [ "$got" != "$THREE_INTEGRITY" ]; then
  echo "vendor_three: integrity mismatch for three@$THREE_VERSION: $got" >&2
  exit 1
fi

# the bundler (npm checks its integrity against the registry's), and three from the tarball
mkdir -p "$work/build"
cp "$out/three_entry.js" "$work/build/"
(cd "$work/build" && echo '{"private":true}' >package.json \
  && npm install --silent --no-audit --no-fund --no-save "$tarball" "esbuild@$ESBUILD_VERSION" >/dev/null)
"$work/build/node_modules/.bin/esbuild" "$work/build/three_entry.js" --bundle --minify \
  --format=iife --target=es2020 --legal-comments=none --charset=utf8 \
  --log-level=warning --outfile="$work/three.bundle.min.js"
{
  echo "/* three.js $THREE_VERSION (MIT, see three.LICENSE), the parts listed in three_entry.js,"
  echo "   bundled by scripts/vendor_three.sh with esbuild $ESBUILD_VERSION */"
  cat "$work/three.bundle.min.js"
} >"$work/bundle.js"
tar -xzf "$tarball" -C "$work" package/LICENSE

if [ "${1:-}" = "--check" ]; then
  cmp "$work/bundle.js" "$out/three.bundle.min.js"
  cmp "$work/package/LICENSE" "$out/three.LICENSE"
  echo "vendor_three: viewer/vendor matches three@$THREE_VERSION"
else
  cp "$work/bundle.js" "$out/three.bundle.min.js"
  cp "$work/package/LICENSE" "$out/three.LICENSE"
  echo "vendor_three: wrote $out/three.bundle.min.js ($(wc -c <"$out/three.bundle.min.js") bytes) and $out/three.LICENSE"
fi
