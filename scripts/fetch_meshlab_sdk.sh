#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Fetches the MeshLab 2020.09 headers the plugins build against: src/common and the bundled
# vcglib from Debian's source package (there is no meshlab-dev). They land in a cache outside
# the source tree and are never committed. Idempotent: does nothing when the cache is complete.
#   usage: fetch_meshlab_sdk.sh [CACHE_DIR]     (default /var/cache/animcompress)
set -euo pipefail

cache=${1:-${ANIMC_CACHE_DIR:-/var/cache/animcompress}}
sdk="$cache/meshlab-2020.09"
if [ -f "$sdk/src/common/interfaces.h" ] && [ -f "$sdk/vcglib/vcg/complex/complex.h" ]; then
  echo "setup: MeshLab headers present in $sdk"
  exit 0
fi

# apt-get source needs a deb-src entry; add one for bookworm main if none exists.
if ! grep -rqs '^Types:.*deb-src\|^deb-src ' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  cat > /etc/apt/sources.list.d/animcompress-deb-src.sources <<'SRC'
Types: deb-src
URIs: http://deb.debian.org/debian
Suites: bookworm
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
SRC
fi
apt-get update -qq

work=$(mktemp -d)
chmod 755 "$work"  # apt-get source downloads as the _apt user
trap 'rm -rf "$work"' EXIT
(cd "$work" && apt-get source --download-only -qq meshlab >/dev/null)
orig=$(ls "$work"/meshlab_*.orig.tar.xz)
tar -xJf "$orig" -C "$work" --wildcards '*/vcglib/*' '*/src/common/*'
top=$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'meshlab*' | head -n1)
[ -f "$top/src/common/interfaces.h" ] || { echo "setup: $orig has no src/common/interfaces.h" >&2; exit 1; }

# Move into place atomically so an interrupted fetch never leaves a half cache behind.
mkdir -p "$cache"
rm -rf "$sdk.partial"
mv "$top" "$sdk.partial"
rm -rf "$sdk"
mv "$sdk.partial" "$sdk"
echo "setup: MeshLab headers unpacked into $sdk"
