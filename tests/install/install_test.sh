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
header_version=$(sed -n 's/^#define ANIMC_VERSION_STRING "\(.*\)"/\1/p' "$prefix/include/animc/version.h")
[[ $(pkg-config --modversion animc) == "$header_version" ]] || { echo "FAIL: pkg-config version"; exit 1; }
# shellcheck disable=SC2046 # pkg-config's output is a list of words
c++ "$source/examples/encode_decode.cpp" -o "$work/pkgconfig_example" $(pkg-config --cflags --libs animc) \
    -Wl,-rpath,"$prefix/lib"
frame_17_matches pkg-config "$work/pkgconfig_example"

# The Python module from the install's site folder: the same sheet, frame 17 alone.
site=$prefix/lib/python3/dist-packages
if ! compgen -G "$site/animcompress*.so" >/dev/null; then
  echo "skip: python: no animcompress module installed (built with -DANIMC_BUILD_PYTHON=OFF)"
  exit 0
fi
PYTHONPATH=$site /usr/bin/python3 - "$work/python" <<'PY'
import os, sys
import numpy as np
import animcompress as ac
out = sys.argv[1]
os.makedirs(out)
side, frames = 40, 50
y, x = np.mgrid[0:side, 0:side].astype(np.float32)
sheet = [np.stack([x, y, 3 * np.sin(0.2 * x + 0.15 * f)], axis=-1).reshape(-1, 3) for f in range(frames)]
v = (np.arange(side - 1)[:, None] * side + np.arange(side - 1)[None, :]).ravel()
faces = np.concatenate([np.stack([v, v + 1, v + side], 1), np.stack([v + 1, v + side + 1, v + side], 1)])
data = ac.encode(np.array(sheet), faces, max_error=0.002, iframe_interval=10)
open(out + '/stream.ams', 'wb').write(data)
ac.open(data)[17].astype('<f4').tofile(out + '/frame17.bin')
PY
"$prefix/bin/animc" decode "$work/python/stream.ams" --frames 17 -o "$work/python/frame17.pc2" >/dev/null
tail -c +33 "$work/python/frame17.pc2" | cmp -s - "$work/python/frame17.bin" ||
  { echo "FAIL: python: frame 17 differs from animc decode's"; exit 1; }
echo "ok: python"
