#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs the plugins of a MeshLab 2022+ build without root, into the per-user folder that
# MeshLab of that release and scalar loads extra plugins from (the one Help > Plugin Info >
# Load Plugins copies into):
#   ${XDG_DATA_HOME:-~/.local/share}/VCG/MeshLab_64bit_{fp|dp}/MeshLabExtraPlugins/VERSION[d]
# MeshLab 2020.09 has no such folder: use the staged MeshLab (cmake --install) instead.
#   usage: scripts/install_user_plugins.sh [BUILD_DIR]      (default build-meshlab2025)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build-meshlab2025}
cache="$build/CMakeCache.txt"
[ -f "$cache" ] || { echo "install_user_plugins: no $cache: configure and build first" >&2; exit 2; }
setting() { sed -n "s/^$1:[A-Z]*=//p" "$cache"; }
version=$(setting ANIMC_MESHLAB)
scalar=$(setting ANIMC_MESHLAB_SCALAR)
case "$version" in
  2020.09|"") echo "install_user_plugins: $build is built for MeshLab 2020.09, which has no per-user plugin folder" >&2; exit 2 ;;
esac
# The folder is named after the version MeshLab reports: "d" appended in double builds.
if [ "$scalar" = double ]; then app=MeshLab_64bit_dp version="${version}d"; else app=MeshLab_64bit_fp; fi
dest="${XDG_DATA_HOME:-$HOME/.local/share}/VCG/$app/MeshLabExtraPlugins/$version"
mkdir -p "$dest"
for plugin in libfilter_animcompress.so libio_animstream.so; do
  [ -f "$build/plugins/$plugin" ] || { echo "install_user_plugins: $build/plugins/$plugin missing: build first" >&2; exit 2; }
  # Copied under a temporary name, then renamed: a running MeshLab never sees half a file.
  cp "$build/plugins/$plugin" "$dest/.$plugin.part"
  mv "$dest/.$plugin.part" "$dest/$plugin"
done
echo "install_user_plugins: plugins for MeshLab $version ($scalar) installed in $dest"
