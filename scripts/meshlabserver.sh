#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Runs the staged meshlabserver (cmake --install build --prefix build/stage) headless: under
# xvfb-run (MeshLab needs a GL context even without a window), with HOME and the XDG folders in
# build/meshlab-home so MeshLab, Qt and Mesa write nothing into the real home.
#   usage: scripts/meshlabserver.sh [meshlabserver arguments...]
#   env:   ANIMC_STAGE (default build/stage), ANIMC_MESHLAB_BIN (default meshlabserver)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
stage=${ANIMC_STAGE:-$root/build/stage}
program="$stage/bin/${ANIMC_MESHLAB_BIN:-meshlabserver}"
[ -x "$program" ] || { echo "meshlabserver.sh: $program missing; run: cmake --install build --prefix build/stage" >&2; exit 2; }

source "$root/scripts/host_setup.sh"
use_private_meshlab_home "${ANIMC_MESHLAB_HOME:-$root/build/meshlab-home}"
exec xvfb-run -a -s "-screen 0 1280x1024x24" "$program" "$@"
