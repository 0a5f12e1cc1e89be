#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Builds a MeshLab 2022+ SDK the 2022+ plugins, mlxrun and their tests build against: the orig
# tarball of Debian's source package (the complete upstream tree, vcglib inside), configured with
# only io_base, then libmeshlab-common, io_base and the meshlab GUI. Debian's own binaries need a
# newer glibc than bookworm's, and there is no meshlab-dev, hence the build. Everything lands in a
# cache outside the source tree and is never committed.
#   usage: fetch_meshlab_2022plus.sh VERSION SCALAR [CACHE_DIR] [--no-gui]
#          VERSION 2025.07 | 2022.02, SCALAR float | double; default cache /var/cache/animcompress
#          --no-gui: only libmeshlab-common and io_base (what the plugins, mlxrun and their tests
#          need; the GUI, for scripts/gui_screenshots.sh, is half of the build)
# Result: CACHE_DIR/meshlab-VERSION-SCALAR/{src,build,distrib} and .complete, written last.
# Idempotent: does nothing when .complete is there. A run that stopped half-way is resumed: the
# tarball is unpacked again only when its unpacking did not finish, and make rebuilds only
# what is missing (a fresh build costs about 10 CPU-minutes).
set -euo pipefail

version=${1:?usage: fetch_meshlab_2022plus.sh VERSION SCALAR [CACHE_DIR]}
scalar=${2:?usage: fetch_meshlab_2022plus.sh VERSION SCALAR [CACHE_DIR]}
gui_target=meshlab  # empty with --no-gui
places=()
for arg in "${@:3}"; do
  case "$arg" in --no-gui) gui_target= ;; *) places+=("$arg") ;; esac
done
cache=${places[0]:-${ANIMC_CACHE_DIR:-/var/cache/animcompress}}
sdk="$cache/meshlab-$version-$scalar"
say() { echo "meshlab $version $scalar: $*"; }
die() { echo "meshlab $version $scalar: error: $*" >&2; exit 1; }

# Which Debian upload holds each release: the suite serves the Sources index apt verifies the
# tarball against. Only the orig tarball is fetched: the .dsc and .debian.tar.xz of these uploads
# answer 404 on deb.debian.org, and the build does not need them.
case "$version" in
  2025.07) debver=2025.07~dfsg-4;   suite=sid;    orig=meshlab_2025.07~dfsg.orig.tar.xz ;;
  2022.02) debver=2022.02+dfsg1-1;  suite=trixie; orig=meshlab_2022.02+dfsg1.orig.tar.xz ;;
  *) die "unknown version (known: 2025.07, 2022.02)" ;;
esac
case "$scalar" in
  float) double=OFF ;; double) double=ON ;; *) die "scalar must be float or double" ;;
esac

if [ -f "$sdk/.complete" ] && { [ -z "$gui_target" ] || [ -e "$sdk/distrib/meshlab" ]; }; then
  say "SDK present in $sdk"
  exit 0
fi

# fetch_orig DEST: the orig tarball into DEST through a private apt configuration (the system's
# sources stay untouched), downloaded under a temporary name and renamed once complete.
fetch_orig() {
  local dest=$1 work
  work=$(mktemp -d)
  chmod 755 "$work"  # apt downloads as the _apt user
  mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$work/dl"
  chmod -R 755 "$work"
  cat > "$work/sources.list" <<SRC
deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian $suite main
SRC
  local apt=(apt-get -qq -o "Dir::Etc::SourceList=$work/sources.list"
             -o "Dir::Etc::SourceParts=$work/none" -o "Dir::State::Lists=$work/lists"
             -o "Dir::Cache=$work/cache" -o "APT::Sandbox::User=root")
  "${apt[@]}" update || die "apt-get update of $suite deb-src failed"
  # --tar-only skips the .dsc and .debian.tar.xz; apt checks the tarball's hash from the index.
  (cd "$work/dl" && "${apt[@]}" source --download-only --tar-only "meshlab=$debver") \
    || die "apt-get source of meshlab=$debver failed"
  [ -s "$work/dl/$orig" ] || die "$orig did not arrive"
  mkdir -p "$(dirname "$dest")"
  mv "$work/dl/$orig" "$dest.part"
  mv "$dest.part" "$dest"
  rm -rf "$work"
}

tarball="$cache/downloads/$orig"
if [ ! -s "$tarball" ]; then
  say "downloading $orig from Debian $suite"
  fetch_orig "$tarball"
fi

if [ ! -f "$sdk/src/.unpacked" ]; then
  rm -rf "$sdk"
  mkdir -p "$sdk/src"
  tar -xJf "$tarball" -C "$sdk/src" --strip-components=1
  touch "$sdk/src/.unpacked"
fi
# 2022.02's CMake project is src/, 2025.07's the top of the tree (so its outputs land in
# build/src/distrib); the options were renamed.
if [ "$version" = 2022.02 ]; then
  project="$sdk/src/src"
  distrib=build/distrib
  options=(-DALLOW_OPTIONAL_EXTERNAL_MESHLAB_LIBRARIES=OFF -DALLOW_BUNDLED_GLEW=OFF
           -DBUILD_WITH_DOUBLE_SCALAR=$double)
else
  project="$sdk/src"
  distrib=build/src/distrib
  options=(-DMESHLAB_ALLOW_OPTIONAL_EXTERNAL_LIBRARIES=OFF -DMESHLAB_ALLOW_BUNDLED_SOURCE_GLEW=OFF
           -DMESHLAB_BUILD_WITH_DOUBLE_SCALAR=$double)
fi
[ -f "$project/CMakeLists.txt" ] || die "$tarball has no CMake project at $project"

say "configuring (log: $sdk/build.log)"
cmake -S "$project" -B "$sdk/build" -DCMAKE_BUILD_TYPE=Release -DVCG_ALLOW_BUNDLED_EIGEN=OFF \
  -DMESHLAB_PLUGINS=meshlabplugins/io_base "${options[@]}" >"$sdk/build.log" 2>&1 \
  || die "configure failed, see $sdk/build.log"
# Every core by default (a fresh CI machine waits on this build); ANIMC_MESHLAB_JOBS=1 leaves
# room for other work.
jobs=${ANIMC_MESHLAB_JOBS:-$(nproc)}
for targets in meshlab-common "${gui_target:+$gui_target }io_base"; do
  say "building $targets (-j$jobs)"
  start=$SECONDS
  # shellcheck disable=SC2086  # two targets in one word on purpose
  nice cmake --build "$sdk/build" -j"$jobs" --target $targets >>"$sdk/build.log" 2>&1 \
    || die "building $targets failed, see $sdk/build.log"
  say "built $targets in $((SECONDS - start)) s"
done

for f in libmeshlab-common.so plugins/libio_base.so ${gui_target}; do
  [ -e "$sdk/$distrib/$f" ] || die "the build made no $sdk/$distrib/$f"
done
ln -sfn "$distrib" "$sdk/distrib"
echo "$debver $scalar $(date -u +%FT%TZ)" > "$sdk/.complete"
say "SDK built in $sdk"
