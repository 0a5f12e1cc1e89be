// SPDX-License-Identifier: Apache-2.0
// A trajectory-coded .ams read back group by group as the codec's integers, for the design
// measurements of this folder (trajectory_bits.cpp, trajectory_contexts.cpp,
// trajectory_basis_dct.cpp).
#pragma once
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "api.h"
#include "codecs/trajectory/components.h"
#include "codecs/trajectory/group_coding.h"
#include "container/container_reader.h"
#include "seqio/sequence_io.h"

struct TrajectoryFile {
  std::unique_ptr<animc::AmsSource> source;  // its settings, mesh and sizes
  std::unique_ptr<animc::ContainerReader> reader;
  std::unique_ptr<animc::CodingOrder> order;

  // Opens path, or says why not on stderr, after `tool`.
  bool open(const char* tool, const std::string& path) {
    auto s = animc::AmsSource::open(path);
    auto r = animc::ContainerReader::open(path);
    if (!s.ok() || !r.ok()) {
      std::fprintf(stderr, "%s: %s: cannot open\n", tool, path.c_str());
      return false;
    }
    if (s.value()->settings().codec() != animc::CodecId::kTrajectory) {
      std::fprintf(stderr, "%s: %s: not a trajectory-coded file\n", tool, path.c_str());
      return false;
    }
    source = std::move(s.value());
    reader = std::move(r.value());
    order = std::make_unique<animc::CodingOrder>(source->topology());
    return true;
  }
  size_t groups() const { return reader->groupCount(); }
  // Group g's first payload (its Frame_Type byte first) and its integers.
  bool read(size_t g, std::vector<uint8_t>& payload, animc::TrajectoryGroup& group) {
    if (!reader->beginGroup(g).ok() || !reader->nextFrame(payload).ok() || payload.empty()) return false;
    return animc::readTrajectoryGroup(animc::ByteReader(payload.data() + 1, payload.size() - 1), *order, UINT64_MAX,
                                      group)
        .ok();
  }
};

// The leading `count` principal components of the first `frames` frames of a sequence, its
// trajectories in `order`'s rows, computed as the trajectory encoder computes them
// (TrajectoryDecomposition); false if the sequence cannot be read.
inline bool recomputeComponents(const std::string& sequence, const std::string& mesh, const animc::CodingOrder& order,
                                uint32_t frames, uint32_t count, animc::Components& pc) {
  auto source = animc::openSequence(sequence, mesh);
  if (!source.ok()) return false;
  const uint32_t n = uint32_t(order.vertex.size());
  animc::RowMatrixF x(n, 3 * frames);
  std::vector<float> xyz;
  for (uint32_t t = 0; t < frames; ++t) {
    auto more = source.value()->next(xyz);
    if (!more.ok() || !more.value() || xyz.size() != size_t(3) * n) return false;
    for (uint32_t p = 0; p < n; ++p)
      for (uint32_t axis = 0; axis < 3; ++axis) x(p, axis * frames + t) = xyz[size_t(order.vertex[p]) * 3 + axis];
  }
  animc::TrajectoryDecomposition decomposition(std::move(x));
  pc = decomposition.none();
  decomposition.extend(pc, count, 0);
  return true;
}

// A file of one trajectory group, its integers, and its leading components computed again from
// its sequence (as many as the group sends).
struct OneGroup {
  std::string path;
  TrajectoryFile file;
  animc::TrajectoryGroup group;
  animc::Components pc;
};

// main() of a tool measuring one such file: `tool FILE.ams SEQUENCE MESH`.
inline int measureOneGroup(const char* tool, int argc, char** argv, int (*measure)(const OneGroup& one)) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: %s FILE.ams SEQUENCE MESH\n", tool);
    return 2;
  }
  OneGroup one;
  one.path = argv[1];
  if (!one.file.open(tool, one.path)) return 1;
  std::vector<uint8_t> payload;
  if (one.file.groups() != 1 || !one.file.read(0, payload, one.group)) {
    std::fprintf(stderr, "%s: %s: not a trajectory file of one group\n", tool, argv[1]);
    return 1;
  }
  if (!recomputeComponents(argv[2], argv[3], *one.file.order, one.group.frames, one.group.components, one.pc)) {
    std::fprintf(stderr, "%s: cannot read %s\n", tool, argv[2]);
    return 1;
  }
  return measure(one);
}

// main() of a tool measuring each file its command line names: 1 if any failed.
inline int measureEach(int argc, char** argv, int (*measure)(const std::string& path)) {
  int failures = 0;
  for (int i = 1; i < argc; ++i) failures += measure(argv[i]);
  return failures ? 1 : 0;
}
