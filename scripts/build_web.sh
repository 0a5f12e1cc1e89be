#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds the WebAssembly decoder (web/CMakeLists.txt) with Debian's emscripten, installed when
# missing, into build-web/, and copies it to web/dist/animc.wasm, where the npm package
# (web/package.json, `npm pack` in web/) and the player take it. Debian ships emscripten's
# system libraries prebuilt, so nothing is compiled but the project's own sources.
#   usage: build_web.sh [BUILD_DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/host_setup.sh"
install_missing_packages build_web emscripten libeigen3-dev
build=${1:-$root/build-web}
# Debian's emscripten runs its JavaScript tools with the machine's node, which finds Debian's
# acorn only through NODE_PATH when that node is not Debian's own.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
emcmake cmake -S "$root/web" -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"$(nproc)"
mkdir -p "$root/web/dist"
cp "$build/animc.wasm" "$root/web/dist/animc.wasm.tmp"
mv "$root/web/dist/animc.wasm.tmp" "$root/web/dist/animc.wasm"
echo "build_web: $root/web/dist/animc.wasm ($(stat -c %s "$root/web/dist/animc.wasm") bytes)"
