// SPDX-License-Identifier: Apache-2.0
// Helpers shared by the codec tests: temp paths, full decodes, the error bound check.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "api.h"
#include "codecs/affine_octree/octree_shared.h"

namespace animc::testing_support {

inline std::string tempPath(const std::string& name) {
  return ::testing::TempDir() + "/animc_" + std::to_string(getpid()) + "_" + name;
}

// Every frame of the file; progressive: what to leave out of each (wavelet files).
inline std::vector<std::vector<float>> decodeAll(const std::string& path, const WaveletDecodeControl& progressive = {}) {
  auto ams = AmsSource::open(path, DecoderLimits(), progressive);
  EXPECT_TRUE(ams.ok()) << ams.status().message();
  std::vector<std::vector<float>> frames;
  if (!ams.ok()) return frames;
  std::vector<float> xyz;
  for (;;) {
    auto more = ams.value()->next(xyz);
    EXPECT_TRUE(more.ok()) << more.status().message();
    if (!more.ok() || !more.value()) break;
    frames.push_back(xyz);
  }
  return frames;
}

// Random access: seeking to each frame k of the open file and reading one frame gives full[k]
// (full: every frame of a whole decode). Fatal failures stop at the first bad seek or read.
inline void expectSeeksMatch(AmsSource& ams, const std::vector<std::vector<float>>& full,
                             std::initializer_list<int64_t> frames) {
  std::vector<float> xyz;
  for (int64_t k : frames) {
    ASSERT_TRUE(ams.seek(k).ok());
    auto got = ams.next(xyz);
    ASSERT_TRUE(got.ok() && got.value());
    EXPECT_EQ(xyz, full[size_t(k)]) << "frame " << k;
  }
}

// Which frames of the file are intra frames: the first frame of each frame group, the only
// frames a decoder allowed the work of a single frame can reach. The I-frame interval alone does
// not say: the affine-octree encoder also codes an intra frame on its own when it cannot predict
// one (docs/affine_octree.md, "Frames and groups").
inline std::vector<bool> intraFrames(const std::string& path) {
  auto whole = Decoder::openFile(path);
  EXPECT_TRUE(whole.ok()) << whole.status().message();
  if (!whole.ok()) return {};
  DecoderOptions one_frame;
  one_frame.limits.max_vertex_frames = whole.value().info().vertices;
  auto limited = Decoder::openFile(path, one_frame);
  EXPECT_TRUE(limited.ok()) << limited.status().message();
  if (!limited.ok()) return {};
  std::vector<bool> intra;
  for (int64_t f = 0; f < whole.value().info().frames; ++f)
    intra.push_back(limited.value().checkDecodeWork(f, f + 1).ok());
  return intra;
}

// Largest vertex error of frame f divided by the side of the root cube the codec used
// (the bounding cube of the reconstructed frame f-1, or of frame f itself for frame 0).
inline double worstRelativeError(const std::vector<std::vector<float>>& original,
                          const std::vector<std::vector<float>>& decoded) {
  double worst = 0;
  for (size_t f = 0; f < original.size(); ++f) {
    const std::vector<float>& ref = f == 0 ? original[0] : decoded[f - 1];
    const RootCube cube = boundingCube(std::vector<double>(ref.begin(), ref.end()));
    for (size_t i = 0; i < original[f].size(); i += 3) {
      const double e = std::hypot(original[f][i] - decoded[f][i], original[f][i + 1] - decoded[f][i + 1],
                                  original[f][i + 2] - decoded[f][i + 2]);
      worst = std::max(worst, e / cube.side);
    }
  }
  return worst;
}

}  // namespace animc::testing_support
