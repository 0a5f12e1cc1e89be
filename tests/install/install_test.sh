#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The installed package as a user meets it: `cmake --install` of this build into a fresh prefix,
# then examples/ built as a separate project against it (CMake package, shared and static, and
# pkg-config), run, and its frame 17 compared with what the installed animc decodes.
#   install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix

cmake --install "$build" --prefix "$prefix" >/dev/null
for f in include/animc/animc.h include/animc/version.h lib/libanimc.a lib/libanimc.so bin/animc \
         lib/cmake/animcompress/animcompressConfig.cmake lib/pkgconfig/animc.pc; do
  [[ -e $prefix/$f ]] || { echo "FAIL: $f not installed"; exit 1; }
done

# frame_17_matches NAME PROGRAM: the program's stream and frame 17 against `animc decode`.
frame_17_matches() {
  local name=$1 program=$2 out=$work/$1
  mkdir -p "$out"
  "$program" "$out/stream.ams" "$out/frame17.bin"
  "$prefix/bin/animc" decode "$out/stream.ams" --frames 17 -o "$out/frame17.pc2" >/dev/null
  # A PC2 file is a 32-byte header, then the frames' floats.
  tail -c +33 "$out/frame17.pc2" > "$out/frame17_cli.bin"
  if ! cmp -s "$out/frame17.bin" "$out/frame17_cli.bin"; then
    echo "FAIL: $name: frame 17 differs from animc decode's"
    exit 1
  fi
  [[ $(stat -c %s "$out/frame17.bin") == $((40 * 40 * 12)) ]] || { echo "FAIL: $name: frame 17 size"; exit 1; }
  echo "ok: $name"
}

for linkage in shared static; do
  static=OFF
  [[ $linkage == static ]] && static=ON
  cmake -S "$source/examples" -B "$work/build-$linkage" -DCMAKE_PREFIX_PATH="$prefix" \
        -DANIMC_EXAMPLE_STATIC=$static >/dev/null
  cmake --build "$work/build-$linkage" >/dev/null
  frame_17_matches "cmake-$linkage" "$work/build-$linkage/encode_decode"
done
if ldd "$work/build-static/encode_decode" | grep -q libanimc; then
  echo "FAIL: the static example loads libanimc.so"
  exit 1
fi

export PKG_CONFIG_PATH=$prefix/lib/pkgconfig
[[ $(pkg-config --modversion animc) == "$(sed -n 's/^#define ANIMC_VERSION_STRING "\(.*\)"/\1/p' "$prefix/include/animc/version.h")" ]]
# shellcheck disable=SC2046 # pkg-config's output is a list of words
c++ "$source/examples/encode_decode.cpp" -o "$work/pkgconfig_example" $(pkg-config --cflags --libs animc) \
    -Wl,-rpath,"$prefix/lib"
frame_17_matches pkg-config "$work/pkgconfig_example"
