#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the node packages of each package folder below from the npm registry (its
# package-lock.json) into the cache, never into the tree: $ANIMC_CACHE_DIR/node/NAME (default
# /var/cache/animcompress). Idempotent: nothing is fetched while the cached lock file equals the
# tree's. Node and npm come from Debian when the machine has neither.
#   usage: setup_node_tools.sh [NAME]   (prints the node_modules folder of NAME, default gltf)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
source "$root/scripts/host_setup.sh"

# NAME, its folder in the tree, and a link to its node_modules made in that folder (or -).
PACKAGE_FOLDERS=(
  "gltf tests/gltf -"   # the Khronos glTF validator and three.js, for tests/gltf
  "web web web"         # three.js for the player, puppeteer-core for its browser test (web/)
)

if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  install_missing_packages node_tools nodejs npm
fi
cache=${ANIMC_CACHE_DIR:-/var/cache/animcompress}/node
for entry in "${PACKAGE_FOLDERS[@]}"; do
  read -r name folder link <<<"$entry"
  target=$cache/$name
  if ! cmp -s "$target/package-lock.json" "$root/$folder/package-lock.json" || [[ ! -d $target/node_modules ]]; then
    mkdir -p "$target"
    cp "$root/$folder/package.json" "$root/$folder/package-lock.json" "$target/"
    (cd "$target" && npm ci --no-audit --no-fund --loglevel=error >&2)
  fi
  # The player's page imports three from web/node_modules: a link, as the tree holds no packages.
  [[ $link == - ]] || ln -sfn "$target/node_modules" "$root/$link/node_modules"
done
echo "$cache/${1:-gltf}/node_modules"
