#!/usr/bin/env bash
# Runs the staged meshlabserver (cmake --install build --prefix build/stage) headless: under
# xvfb-run (MeshLab needs a GL context even without a window), with HOME and the XDG folders in
# build/meshlab-home so MeshLab, Qt and Mesa write nothing into the real home.
#   usage: tools/meshlabserver.sh [meshlabserver arguments...]
#   env:   ANIMC_STAGE (default build/stage), ANIMC_MESHLAB_BIN (default meshlabserver)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
stage=${ANIMC_STAGE:-$root/build/stage}
program="$stage/bin/${ANIMC_MESHLAB_BIN:-meshlabserver}"
[ -x "$program" ] || { echo "meshlabserver.sh: $program missing; run: cmake --install build --prefix build/stage" >&2; exit 2; }

home=${ANIMC_MESHLAB_HOME:-$root/build/meshlab-home}
mkdir -p "$home/.config/VCG" "$home/.cache" "$home/run"
chmod 700 "$home/run"
settings="$home/.config/VCG/MeshLab_64bit_fp.conf"
# Without a GPU memory budget meshlabserver logs "no additional memory available" per layer.
[ -f "$settings" ] || cat > "$settings" <<'INI'
[General]
MeshLab%3A%3ASystem%3A%3AmaxGPUMemDedicatedToGeometry="<!DOCTYPE MeshLabSettings>\n<Param value=\"350\" type=\"RichInt\" name=\"MeshLab::System::maxGPUMemDedicatedToGeometry\"/>\n"
INI
export HOME="$home" XDG_CONFIG_HOME="$home/.config" XDG_CACHE_HOME="$home/.cache" \
       XDG_RUNTIME_DIR="$home/run" MESA_SHADER_CACHE_DISABLE=true
exec xvfb-run -a -s "-screen 0 1280x1024x24" "$program" "$@"
