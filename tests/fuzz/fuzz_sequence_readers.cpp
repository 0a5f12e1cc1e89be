// SPDX-License-Identifier: Apache-2.0
// libFuzzer harness: the sequence readers (PLY ascii/binary, OFF, PC2, MDD, and the .xz
// streaming of point caches) on arbitrary bytes, reading every frame. Any Status is fine; a
// crash, sanitizer report, leak, hang or huge allocation is a bug.
//
// Input = 2 control bytes, then the file:
//   [0] modulo 6: .ply, .off, .pc2, .mdd, .pc2.xz, .mdd.xz
//   [1] point caches: the mesh's vertex count minus 1 (the readers check the cache against it)
// PLY and OFF go through openSequence as a one-frame sequence, point caches through their
// readers with a topology of that many vertices (caches hold no faces).
#include <cstdint>
#include <memory>
#include <vector>

#include "fuzz_support.h"
#include "seqio/mdd_format.h"
#include "seqio/pc2_format.h"
#include "seqio/sequence_io.h"

namespace {

constexpr size_t kControlBytes = 2;
constexpr const char* kSuffixes[] = {".ply", ".off", ".pc2", ".mdd", ".pc2.xz", ".mdd.xz"};

animc::Result<std::unique_ptr<animc::FrameSource>> open(const std::string& path, const uint8_t* control) {
  const int kind = control[0] % 6;
  if (kind < 2) return animc::openSequence(path, "");
  animc::Topology topology;
  topology.vertex_count = uint32_t(control[1]) + 1;
  const bool mdd = kind % 2 == 1;
  return mdd ? animc::openMdd(path, topology, "mesh.ply") : animc::openPc2(path, topology, "mesh.ply");
}

void readAll(animc::FrameSource& source) {
  std::vector<float> xyz;
  for (;;) {
    auto more = source.next(xyz);
    if (!more.ok() || !more.value()) return;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kControlBytes) return 0;
  const std::string path = animc::fuzz::scratchPath(kSuffixes[data[0] % 6]);
  if (!animc::fuzz::writeScratch(path, data + kControlBytes, size - kControlBytes)) return 0;
  auto source = open(path, data);
  if (source.ok()) readAll(*source.value());
  return 0;
}
