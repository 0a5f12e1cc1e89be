#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Installs every Debian package animcompress needs (bookworm, as root). Idempotent: packages
# already present are left alone and apt is not touched at all when nothing is missing.
set -euo pipefail

PACKAGES=(
  cmake g++ make pkg-config        # build
  libeigen3-dev liblzma-dev        # shared_codec
  libgtest-dev                     # unit tests
  xz-utils python3 python3-numpy   # sample data, benchmark baseline, metrics cross-check
  pybind11-dev python3-pybind11 python3-dev python3-pytest  # the Python module and its tests
  python3-distributed              # examples/dask_compress.py and its test (a Dask LocalCluster)
  clang libclang-rt-dev            # the libFuzzer harnesses (tests/fuzz) of CI's short campaign
  gnuplot-nox                      # bench/rd_plot.py (rate-distortion plot of the benchmarks)
  gltfpack                         # bench/bench_gltf.py (glTF sizes beside a web user's other choice)
  blender                          # the Blender add-on's tests (blender/io_anim_ams), headless
  emscripten                       # the WebAssembly decoder (scripts/build_web.sh, web/)
  chromium                         # the player's browser test (web/test/player_browser.mjs), headless
  meshlab qtbase5-dev libqt5opengl5-dev libglew-dev  # MeshLab 2020.09 and what its headers need
  mesa-common-dev libglu1-mesa-dev
  xvfb xauth                       # meshlabserver and meshlab need an X server, even headless
)

source "$(dirname "$0")/host_setup.sh"
install_missing_packages setup "${PACKAGES[@]}"
echo "setup: all packages present"

# The node packages the tests run (the glTF validator, three.js, puppeteer-core), from npm into
# the cache.
bash "$(dirname "$0")/setup_node_tools.sh" >/dev/null

# MeshLab's headers come from Debian's source package, into a cache outside the tree.
bash "$(dirname "$0")/fetch_meshlab_sdk.sh"
# MeshLab 2025.07 (float and double: PyMeshLab's scalar) and 2022.02 (float) are built from
# Debian's source packages once per machine, also cached (nothing happens when the cache is
# complete). Only 2025.07 float gets its GUI (the screenshots); the others need the library
# and io_base alone, half the build.
bash "$(dirname "$0")/fetch_meshlab_2022plus.sh" 2025.07 float
bash "$(dirname "$0")/fetch_meshlab_2022plus.sh" 2025.07 double --no-gui
bash "$(dirname "$0")/fetch_meshlab_2022plus.sh" 2022.02 float --no-gui
