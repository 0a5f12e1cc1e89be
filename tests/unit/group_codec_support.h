// SPDX-License-Identifier: Apache-2.0
// Helpers of the tests of codecs that code whole groups (trajectory, auto): a sequence
// through the public Encoder with every reconstruction collected as its group closes, whole
// decodes (in order, or backwards so that every group is entered by random access), a frame's
// cube side and the largest vertex error.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "animc/animc.h"
#include "core/memory_sequence.h"

namespace animc::testing_support {

struct Coded {
  std::vector<uint8_t> bytes;
  std::vector<std::vector<float>> reconstructions;  // from the encoder, frame by frame
  std::vector<int64_t> known_after_each_frame;     // reconstructedFrames() after each addFrame
};

inline Coded encodeCollecting(const MemorySequence& seq, const EncoderOptions& options) {
  Coded out;
  std::vector<uint32_t> triangles;
  for (const Triangle& t : seq.topology().triangles) triangles.insert(triangles.end(), t.begin(), t.end());
  auto encoder = Encoder::create(options, seq.topology().vertex_count, triangles.data(), triangles.size() / 3,
                                 memorySink(&out.bytes));
  EXPECT_TRUE(encoder.ok()) << encoder.status().message();
  if (!encoder.ok()) return out;
  Encoder& e = encoder.value();
  auto collect = [&] {
    for (int64_t k = int64_t(out.reconstructions.size()); k < e.reconstructedFrames(); ++k) {
      const float* r = e.reconstruction(k);
      EXPECT_NE(r, nullptr) << "frame " << k;
      if (r != nullptr) out.reconstructions.emplace_back(r, r + 3 * size_t(seq.topology().vertex_count));
    }
  };
  for (const std::vector<float>& frame : seq.frames()) {
    EXPECT_TRUE(e.addFrame(frame.data()).ok());
    out.known_after_each_frame.push_back(e.reconstructedFrames());
    collect();
  }
  EXPECT_TRUE(e.finish().ok());
  collect();
  return out;
}

enum class DecodeOrder { kForward, kBackward };

inline std::vector<std::vector<float>> decodeAll(const std::vector<uint8_t>& bytes,
                                                 DecodeOrder order = DecodeOrder::kForward) {
  auto decoder = Decoder::openMemory(bytes.data(), bytes.size());
  EXPECT_TRUE(decoder.ok()) << decoder.status().message();
  std::vector<std::vector<float>> frames;
  if (!decoder.ok()) return frames;
  const int64_t count = decoder.value().info().frames;
  frames.resize(size_t(count));
  std::vector<float> xyz(3 * size_t(decoder.value().info().vertices));
  for (int64_t i = 0; i < count; ++i) {
    const int64_t k = order == DecodeOrder::kForward ? i : count - 1 - i;
    EXPECT_TRUE(decoder.value().frame(k, xyz.data()).ok());
    frames[size_t(k)] = xyz;
  }
  return frames;
}

// The largest side of a frame's bounding box (the affine-octree codec's cube).
inline double cubeSide(const std::vector<float>& xyz) {
  float lo[3] = {xyz[0], xyz[1], xyz[2]}, hi[3] = {xyz[0], xyz[1], xyz[2]};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], xyz[i]);
    hi[i % 3] = std::max(hi[i % 3], xyz[i]);
  }
  return std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
}

// The largest distance between a vertex of `a` and the same vertex of `b`.
inline double largestVertexError(const std::vector<float>& a, const std::vector<float>& b) {
  double worst = 0;
  for (size_t v = 0; v + 2 < a.size(); v += 3)
    worst = std::max(worst, std::hypot(double(a[v]) - b[v], double(a[v + 1]) - b[v + 1], double(a[v + 2]) - b[v + 2]));
  return worst;
}

}  // namespace animc::testing_support
