#!/usr/bin/env bash
# Installs every Debian package animcompress needs (bookworm, as root). Idempotent: packages
# already present are left alone and apt is not touched at all when nothing is missing.
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config        # build
  libeigen3-dev liblzma-dev        # shared_codec
  libgtest-dev                     # unit tests
  xz-utils python3 python3-numpy   # sample data, benchmark baseline, metrics cross-check
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
echo "setup: all packages present"
