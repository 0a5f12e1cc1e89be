#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Runs mlxrun (MeshLab 2022+'s stand-in for meshlabserver) with HOME and the XDG folders in
# build-meshlab2025/meshlab-home, so MeshLab and Qt write nothing into the real home. No X
# server: mlxrun uses Qt's offscreen platform.
#   usage: scripts/mlxrun.sh [mlxrun arguments...]
#   env:   ANIMC_MLXRUN (default build-meshlab2025/bin/mlxrun), MLXRUN_PLUGIN_PATH (default: that
#          build's plugins/ and the MeshLab 2025.07 float SDK's io_base)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
program=${ANIMC_MLXRUN:-$root/build-meshlab2025/bin/mlxrun}
[ -x "$program" ] || { echo "mlxrun.sh: $program missing; build with -DANIMC_MESHLAB=2025.07" >&2; exit 2; }
export MLXRUN_PLUGIN_PATH=${MLXRUN_PLUGIN_PATH:-$(dirname "$(dirname "$program")")/plugins:${ANIMC_CACHE_DIR:-/var/cache/animcompress}/meshlab-2025.07-float/distrib/plugins}

source "$root/scripts/host_setup.sh"
use_private_meshlab_home "${ANIMC_MESHLAB_HOME:-$(dirname "$(dirname "$program")")/meshlab-home}"
exec "$program" "$@"
