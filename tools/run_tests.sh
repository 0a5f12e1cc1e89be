#!/usr/bin/env bash
# The README's second command (and CI's): install, build, run every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
cd build
ctest --output-on-failure -j"$(nproc)" --timeout 900
