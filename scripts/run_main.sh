#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The README's first command: install, build, stage MeshLab with our plugins, then compress the
# sample animation (24 PLY frames loaded as layers) in meshlabserver with the Compress
# Animation Layers filter and print the figures it logged.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
cmake --install build --prefix build/stage >/dev/null
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
(cd "$out" && "$OLDPWD/scripts/meshlabserver.sh" -i "$OLDPWD"/samples/sydney/frames/frame_*.ply \
   -s "$OLDPWD/samples/compress.mlx" >log.txt 2>&1) || { cat "$out/log.txt" >&2; exit 1; }
# meshlabserver prints the filter's log as "LOG: <level> <line>".
sed -n 's/^LOG: [0-9] //p' "$out/log.txt"
