#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the node packages the tests run (tests/gltf/package.json: the Khronos glTF validator
# and three.js)
# from the npm registry into the cache, never into the tree: $ANIMC_CACHE_DIR/node/gltf
# (default /var/cache/animcompress). Idempotent: nothing is fetched while the cached lock file
# equals the tree's. Node and npm come from Debian when the machine has neither.
#   usage: setup_node_tools.sh        (prints the node_modules folder it made or found)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/host_setup.sh"
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  install_missing_packages node_tools nodejs npm
fi
target=${ANIMC_CACHE_DIR:-/var/cache/animcompress}/node/gltf
if [[ -d $target/node_modules/gltf-validator ]] && cmp -s "$target/package-lock.json" "$root/tests/gltf/package-lock.json"; then
  echo "$target/node_modules"
  exit 0
fi
mkdir -p "$target"
cp "$root/tests/gltf/package.json" "$root/tests/gltf/package-lock.json" "$target/"
(cd "$target" && npm ci --no-audit --no-fund --loglevel=error >&2)
echo "$target/node_modules"
