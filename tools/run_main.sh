#!/usr/bin/env bash
# The README's first command: install, build, then compress the sample animation and print
# its figures.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
build/tools/animc/animc encode samples/sydney/sydney_50.pc2.xz --mesh samples/sydney/sydney_md2.ply \
  -o "$out/sydney_50.ams" --max-error 0.01
