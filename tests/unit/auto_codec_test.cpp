// SPDX-License-Identifier: Apache-2.0
// `--codec auto`: each group coded by the smallest candidate, the file decoding to the
// encoder's reconstructions whatever codec each group took, and the error bound of the mode
// holding for every group.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "animc/animc.h"
#include "codecs/auto/sampling.h"
#include "container/container_reader.h"
#include "group_codec_support.h"
#include "io/byte_source.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::Coded;
using testing_support::cubeSide;
using testing_support::DecodeOrder;
using testing_support::gridSequence;
using testing_support::kgError;
using testing_support::largestVertexError;
const auto encode = testing_support::encodeCollecting;
// Backwards: every group is entered by random access.
std::vector<std::vector<float>> decodeAll(const std::vector<uint8_t>& bytes) {
  return testing_support::decodeAll(bytes, DecodeOrder::kBackward);
}

// How many groups each candidate (its index in the file) coded: the first byte of each
// group's first frame.
std::map<int, int> groupsByCandidate(const std::vector<uint8_t>& bytes) {
  std::map<int, int> count;
  auto reader = ContainerReader::open(memorySource(bytes.data(), bytes.size()), "auto", DecoderLimits());
  EXPECT_TRUE(reader.ok());
  if (!reader.ok()) return count;
  std::vector<uint8_t> payload;
  for (size_t g = 0; g < reader.value()->groupCount(); ++g) {
    EXPECT_TRUE(reader.value()->beginGroup(g).ok());
    auto got = reader.value()->nextFrame(payload);
    EXPECT_TRUE(got.ok() && got.value() && !payload.empty());
    if (got.ok() && got.value() && !payload.empty()) ++count[payload[0]];
  }
  return count;
}

EncoderOptions options(const std::string& codec, const std::string& flag, double value, uint32_t interval) {
  EncoderOptions o;
  o.codec = codec;
  o.set(flag, value);
  o.iframe_interval = interval;
  return o;
}

// With groups of one to three frames the candidates trade places.
TEST(AutoCodec, MixedGroupsDecodeToTheReconstructionsAndTakeTheSmallest) {
  const MemorySequence seq = gridSequence(12, 10, 24, 1.0, 1.0);
  for (uint32_t interval : {1u, 2u, 6u}) {
    const Coded coded = encode(seq, options("auto", "max-error", 0.01, interval));
    EXPECT_EQ(decodeAll(coded.bytes), coded.reconstructions) << "interval " << interval;
    // Never more than the smaller candidate alone, plus the candidate byte of each frame and
    // the candidates' parameters in the header.
    const size_t trajectory = encode(seq, options("trajectory2", "max-error", 0.01, interval)).bytes.size();
    const size_t octree = encode(seq, options("affine-octree", "max-error", 0.01, interval)).bytes.size();
    EXPECT_LE(coded.bytes.size(), std::min(trajectory, octree) + seq.frames().size() + 64) << "interval " << interval;
    // Every vertex within each frame's bound: the affine-octree codec's cube is the previous
    // decoded frame's, the trajectory codec's the frame's own; allow the larger.
    for (size_t f = 0; f < seq.frames().size(); ++f) {
      const std::vector<float>& original = seq.frames()[f];
      const double side = std::max(cubeSide(original), f > 0 ? cubeSide(coded.reconstructions[f - 1]) : 0.0);
      ASSERT_LE(largestVertexError(coded.reconstructions[f], original), 0.01 * side * (1 + 1e-5))
          << "frame " << f << " interval " << interval;
    }
  }
  // One-frame groups go to the affine-octree codec (candidate 1) but for the odd one,
  // three-frame groups to the trajectory codec (0), and two-frame groups mix them.
  EXPECT_GE(groupsByCandidate(encode(seq, options("auto", "max-error", 0.01, 1)).bytes)[1], 22);
  EXPECT_EQ(groupsByCandidate(encode(seq, options("auto", "max-error", 0.01, 3)).bytes), (std::map<int, int>{{0, 8}}));
  EXPECT_EQ(groupsByCandidate(encode(seq, options("auto", "max-error", 0.01, 2)).bytes).size(), 2u);
}

TEST(AutoCodec, TargetKgHoldsAndTheFileNamesItsCandidates) {
  const MemorySequence seq = gridSequence(12, 10, 30, 1.0, 1.0);
  const Coded coded = encode(seq, options("auto", "target-kg", 0.5, 10));
  const auto decoded = decodeAll(coded.bytes);
  EXPECT_EQ(decoded, coded.reconstructions);
  EXPECT_LE(kgError(seq, decoded), 0.5);
  auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size());
  ASSERT_TRUE(decoder.ok());
  EXPECT_EQ(decoder.value().info().codec, "auto");
  EXPECT_NE(decoder.value().info().settings_text.find("trajectory2 or wavelet"), std::string::npos)
      << decoder.value().info().settings_text;
}

// The sample that decides whether the affine-octree or wavelet candidate codes a whole group
// costs at most half the group: runs inside it, in order, not overlapping, the first at its
// start and the last at its end, and four runs once the group is long enough.
TEST(AutoCodec, ASampleCodesAtMostHalfAGroupAndSpansIt) {
  EXPECT_TRUE(sampleRunStarts(2 * kSampleRunFrames - 1).empty());
  EXPECT_EQ(sampleRunStarts(15), (std::vector<uint32_t>{0}));
  EXPECT_EQ(sampleRunStarts(64), (std::vector<uint32_t>{0, 20, 40, 60}));
  for (uint32_t frames = 1; frames <= 1024; ++frames) {
    const std::vector<uint32_t> starts = sampleRunStarts(frames);
    ASSERT_LE(2 * starts.size() * kSampleRunFrames, frames) << frames;
    ASSERT_EQ(starts.empty(), frames < 2 * kSampleRunFrames) << frames;
    ASSERT_LE(starts.size(), kMostSampleRuns) << frames;
    if (frames >= 2 * kMostSampleRuns * kSampleRunFrames) {
      ASSERT_EQ(starts.size(), kMostSampleRuns) << frames;
    }
    for (size_t i = 1; i < starts.size(); ++i) ASSERT_GE(starts[i], starts[i - 1] + kSampleRunFrames) << frames;
    if (!starts.empty()) {
      ASSERT_EQ(starts.front(), 0u) << frames;
      ASSERT_LE(starts.back() + kSampleRunFrames, frames) << frames;
    }
    if (starts.size() > 1) {
      ASSERT_EQ(starts.back() + kSampleRunFrames, frames) << frames;
    }
  }
}

TEST(AutoCodec, OptionsAreChecked) {
  EXPECT_TRUE(options("auto", "max-error", 0.01, 0).validate().ok());
  EXPECT_FALSE(options("auto", "max-error", 0.01, 0).set("target-kg", 0.3).validate().ok());
  EXPECT_FALSE(options("auto", "step", 0.01, 0).validate().ok());
  EXPECT_FALSE(options("auto", "max-error", 0.9, 0).validate().ok());
}

TEST(AutoCodec, DamagedStreamsAreRefusedOrDecodedSafely) {
  const MemorySequence seq = gridSequence(6, 5, 6, 1.0, 1.0);
  const Coded coded = encode(seq, options("auto", "max-error", 0.01, 2));
  for (size_t cut = 0; cut < coded.bytes.size(); ++cut) {
    auto decoder = Decoder::openMemory(coded.bytes.data(), cut);
    EXPECT_TRUE(!decoder.ok() || !decoder.value().verify().ok()) << "cut at " << cut;
  }
  for (size_t i = 0; i < coded.bytes.size(); ++i) {
    std::vector<uint8_t> bytes = coded.bytes;
    bytes[i] ^= 0x5A;
    auto decoder = Decoder::openMemory(bytes.data(), bytes.size());
    if (decoder.ok()) (void)decoder.value().verify();
  }
}

}  // namespace
}  // namespace animc
