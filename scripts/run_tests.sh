#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The README's second command (and CI's): install, build, run every test; then every test
# again under AddressSanitizer and UBSan, where the corrupt-file tests earn their keep; then a
# short fuzzing campaign.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
bash scripts/build_web.sh
(cd build && ctest --output-on-failure -j"$(nproc)" --timeout 900)

# The plugins for MeshLab 2025.07 (float), 2022.02 (Debian 13, Ubuntu 24.04) and 2025.07 built
# with double (PyMeshLab's scalar, meshlab.net's "d" builds), against the SDKs setup.sh built,
# and their end-to-end tests through mlxrun (MeshLab 2022+ has no meshlabserver). Each builds
# only what those tests run: the library and its unit tests were built and run above.
meshlab_end_to_end() {  # BUILD_DIR, then cmake options
  local dir=$1
  shift
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DANIMC_BUILD_PYTHON=OFF -DANIMC_BUILD_TESTS=ON "$@" >/dev/null
  cmake --build "$dir" -j"$(nproc)" --target animc filter_animcompress io_animstream mlxrun compress_failure_host \
    fail_large_allocations
  (cd "$dir" && ctest --output-on-failure -R meshlab --timeout 900)
}
meshlab_end_to_end build-meshlab2025 -DANIMC_MESHLAB=2025.07
meshlab_end_to_end build-meshlab2022 -DANIMC_MESHLAB=2022.02
meshlab_end_to_end build-meshlab2025d -DANIMC_MESHLAB=2025.07 -DANIMC_MESHLAB_SCALAR=double

# The portable build (no AVX2 kernels, what other CPUs run): its unit tests, and the golden
# files, which an AVX2 build wrote, so both builds must write and decode the same bytes.
cmake -S . -B build-portable -DCMAKE_BUILD_TYPE=Release -DANIMC_NO_AVX2=ON -DANIMC_BUILD_PLUGINS=OFF \
  -DANIMC_BUILD_PYTHON=OFF >/dev/null
cmake --build build-portable -j"$(nproc)"
(cd build-portable && ctest --output-on-failure -j"$(nproc)" --timeout 900 -E web_player)

# The plugins are left out here: MeshLab itself is not built with the sanitizers; the Python
# module too, as an ASan library cannot be loaded into an uninstrumented python3.
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DANIMC_SANITIZE=ON -DANIMC_BUILD_PLUGINS=OFF \
  -DANIMC_BUILD_PYTHON=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --output-on-failure -j"$(nproc)" --timeout 900 -E web_player)

# A short fuzzing campaign: every libFuzzer harness (clang, ASan, UBSan) for a minute from the
# in-tree corpus (tests/fuzz/corpus). Long campaigns: tests/fuzz/README.md.
cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DANIMC_BUILD_FUZZERS=ON -DANIMC_BUILD_TESTS=OFF \
  -DANIMC_BUILD_PLUGINS=OFF -DANIMC_BUILD_PYTHON=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc)"
bash tests/fuzz/campaign.sh build-fuzz 60 build-fuzz/campaign --parallel
# The same on the portable kernels, which CPUs without AVX2 run (core/simd_math.h).
ANIMC_SIMD=portable bash tests/fuzz/campaign.sh build-fuzz 20 build-fuzz/campaign-portable --parallel
# And on the AVX2 kernels where the CPU would run AVX-512 ones (the same kernels elsewhere).
ANIMC_SIMD=avx2 bash tests/fuzz/campaign.sh build-fuzz 20 build-fuzz/campaign-avx2 --parallel
