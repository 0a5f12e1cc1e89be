// SPDX-License-Identifier: Apache-2.0
// The trajectory codecs (codec 3, and codec 5 which cuts each group into parts) through the
// public API: decoders give the encoder's reconstructions bit for bit, in order and at
// random; groups follow the I-frame interval and the group cap; every rate mode holds;
// damaged groups are refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "animc/animc.h"
#include "group_codec_support.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::Coded;
using testing_support::cubeSide;
using testing_support::decodeAll;
using testing_support::gridSequence;
using testing_support::kgError;
using testing_support::largestVertexError;
const auto encode = testing_support::encodeCollecting;

class Trajectory : public testing::TestWithParam<const char*> {
 protected:
  const char* codec() const { return GetParam(); }
  EncoderOptions trajectory(double target_kg) const {
    EncoderOptions o;
    o.codec = codec();
    o.set("target-kg", target_kg);
    return o;
  }
};

TEST_P(Trajectory, DecodesToTheEncodersReconstructionWithinTheTarget) {
  const MemorySequence seq = gridSequence(12, 10, 40, 1.0, 1.0);
  for (double target : {0.1, 1.0, 5.0}) {
    const Coded coded = encode(seq, trajectory(target));
    const auto decoded = decodeAll(coded.bytes);
    ASSERT_EQ(decoded.size(), 40u);
    EXPECT_EQ(decoded, coded.reconstructions) << "target " << target;
    const double kg = kgError(seq, decoded);
    EXPECT_LE(kg, target) << "target " << target;
    EXPECT_GT(kg, target / 4) << "a much finer step than needed, target " << target;
  }
}

TEST_P(Trajectory, AFinerTargetCostsMoreBytes) {
  const MemorySequence seq = gridSequence(12, 10, 40, 1.0, 1.0);
  EXPECT_GT(encode(seq, trajectory(0.1)).bytes.size(), encode(seq, trajectory(1.0)).bytes.size());
}

TEST_P(Trajectory, ReconstructionsComeWhenTheirGroupCloses) {
  const MemorySequence seq = gridSequence(12, 10, 20, 1.0, 1.0);
  EncoderOptions options = trajectory(0.5);
  options.iframe_interval = 8;
  const Coded coded = encode(seq, options);
  // Groups 0-7, 8-15 and 16-19 (the last closed by finish()).
  const std::vector<int64_t> expected = {0, 0, 0, 0, 0, 0, 0, 8, 8, 8, 8, 8, 8, 8, 8, 16, 16, 16, 16, 16};
  EXPECT_EQ(coded.known_after_each_frame, expected);
  ASSERT_EQ(coded.reconstructions.size(), 20u);

  auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size());
  ASSERT_TRUE(decoder.ok());
  EXPECT_EQ(decoder.value().info().codec, codec());
  EXPECT_EQ(decoder.value().info().groups, 3u);
  std::vector<float> xyz(3 * size_t(seq.topology().vertex_count));
  for (int64_t k : {17, 3, 19, 0, 9, 8, 15, 16}) {
    ASSERT_TRUE(decoder.value().frame(k, xyz.data()).ok());
    EXPECT_EQ(xyz, coded.reconstructions[size_t(k)]) << "frame " << k;
  }
}

// A random access keeps the group it goes back into (the same payload bytes) and computes only
// the frame it hands out. Groups 0 and 2 hold the same frames, so their payloads are the same
// bytes too; any order of access must give the encoder's frames.
TEST_P(Trajectory, RandomAccessInAnyOrderGivesTheEncodersFrames) {
  std::vector<std::vector<float>> frames;
  for (int f = 0; f < 24; ++f) frames.push_back(testing_support::gridFrame(12, 10, f % 16, 1.0, 1.0));
  const MemorySequence seq(testing_support::gridTopology(12, 10), frames, 25.0, "repeated grid");
  EncoderOptions options = trajectory(0.5);
  options.iframe_interval = 8;
  const Coded coded = encode(seq, options);
  ASSERT_EQ(coded.reconstructions.size(), 24u);
  EXPECT_EQ(coded.reconstructions[17], coded.reconstructions[1]);
  EXPECT_NE(coded.reconstructions[9], coded.reconstructions[1]);

  std::vector<std::vector<int64_t>> orders = {{}, {}, {}};
  for (int64_t k = 23; k >= 0; --k) orders[0].push_back(k);                                   // backwards
  for (int64_t k = 0; k < 8; ++k) orders[1].insert(orders[1].end(), {k, 23 - k, 8 + k, 17});  // across groups
  for (int64_t k = 0; k < 24; k += 3) orders[2].insert(orders[2].end(), {k, k / 2});          // skipping ahead
  for (const auto& order : orders) {
    auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size());
    ASSERT_TRUE(decoder.ok());
    std::vector<float> xyz(3 * size_t(seq.topology().vertex_count));
    for (int64_t k : order) {
      ASSERT_TRUE(decoder.value().frame(k, xyz.data()).ok());
      EXPECT_EQ(xyz, coded.reconstructions[size_t(k)]) << "frame " << k;
    }
    std::vector<float> range(xyz.size() * 5);
    ASSERT_TRUE(decoder.value().frames(5, 10, range.data()).ok());
    for (size_t k = 5; k < 10; ++k)
      EXPECT_TRUE(std::equal(coded.reconstructions[k].begin(), coded.reconstructions[k].end(),
                             range.begin() + (k - 5) * xyz.size()))
          << "frame " << k << " of a range after random access";
  }
}

TEST_P(Trajectory, StaticBytesLeaveTheGroupToMotion) {
  // The first frame record carries the whole group: counting it as static would report almost
  // no motion (animc's "motion only" figure).
  const MemorySequence seq = gridSequence(12, 10, 20, 1.0, 1.0);
  const Coded coded = encode(seq, trajectory(0.5));
  auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size());
  ASSERT_TRUE(decoder.ok());
  const StreamInfo& info = decoder.value().info();
  EXPECT_LT(info.static_bytes, info.bytes / 2);
  EXPECT_GT(info.static_bytes, 0u);
  std::vector<uint32_t> triangles;
  for (const Triangle& t : seq.topology().triangles) triangles.insert(triangles.end(), t.begin(), t.end());
  std::vector<uint8_t> bytes;
  auto encoder = Encoder::create(trajectory(0.5), 120, triangles.data(), triangles.size() / 3, memorySink(&bytes));
  ASSERT_TRUE(encoder.ok());
  for (const auto& frame : seq.frames()) ASSERT_TRUE(encoder.value().addFrame(frame.data()).ok());
  auto summary = encoder.value().finish();
  ASSERT_TRUE(summary.ok());
  EXPECT_EQ(summary.value().static_bytes, info.static_bytes);
}

TEST_P(Trajectory, GroupFramesCapsTheGroupWithoutAnInterval) {
  const MemorySequence seq = gridSequence(12, 10, 20, 1.0, 1.0);
  EncoderOptions options = trajectory(0.5);
  options.set("group-frames", 6.0);
  const Coded coded = encode(seq, options);
  auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size());
  ASSERT_TRUE(decoder.ok());
  EXPECT_EQ(decoder.value().info().groups, 4u);  // 6 + 6 + 6 + 2
  EXPECT_EQ(decodeAll(coded.bytes), coded.reconstructions);
}

TEST_P(Trajectory, AFixedStepBoundsTheErrorBySize) {
  const MemorySequence seq = gridSequence(12, 10, 30, 1.0, 1.0);
  EncoderOptions fine, coarse;
  fine.codec = coarse.codec = codec();
  fine.set("step", 1e-4);
  coarse.set("step", 1e-2);
  const Coded a = encode(seq, fine), b = encode(seq, coarse);
  EXPECT_LT(kgError(seq, decodeAll(a.bytes)), kgError(seq, decodeAll(b.bytes)));
  EXPECT_GT(a.bytes.size(), b.bytes.size());
}

TEST_P(Trajectory, MaxErrorBoundsEveryVertexOfEveryFrame) {
  const MemorySequence seq = gridSequence(12, 10, 30, 1.0, 1.0);
  for (double bound : {0.002, 0.02}) {
    EncoderOptions options;
    options.codec = codec();
    options.set("max-error", bound);
    options.iframe_interval = 16;
    const Coded coded = encode(seq, options);
    const auto decoded = decodeAll(coded.bytes);
    ASSERT_EQ(decoded, coded.reconstructions);
    double worst = 0;  // the largest error, in units of its frame's bound
    for (size_t f = 0; f < decoded.size(); ++f) {
      const std::vector<float>& original = seq.frames()[f];
      worst = std::max(worst, largestVertexError(decoded[f], original) / (bound * cubeSide(original)));
    }
    EXPECT_LE(worst, 1.0) << "max error " << bound;
    EXPECT_GT(worst, 0.25) << "a much finer step than the bound needs, max error " << bound;
  }
}

TEST_P(Trajectory, BpvfFillsItsBudget) {
  const MemorySequence seq = gridSequence(12, 10, 40, 1.0, 1.0);
  const double vertex_frames = 40.0 * seq.topology().vertex_count;
  EncoderOptions coarsest;
  coarsest.codec = codec();
  coarsest.set("step", 1.0);  // next to nothing but the container and the mean
  const double overhead = double(encode(seq, coarsest).bytes.size());
  double previous = 0;
  for (double budget : {0.5, 2.0, 8.0}) {
    EncoderOptions options;
    options.codec = codec();
    options.set("bpvf", budget);
    const Coded coded = encode(seq, options);
    EXPECT_EQ(decodeAll(coded.bytes), coded.reconstructions);
    const double bpvf = 8 * (double(coded.bytes.size()) - overhead) / vertex_frames;
    EXPECT_LE(bpvf, budget) << "budget " << budget;
    EXPECT_GT(bpvf, budget / 2) << "budget " << budget;
    EXPECT_GT(double(coded.bytes.size()), previous);
    previous = double(coded.bytes.size());
  }
}

TEST_P(Trajectory, OneFrameAndStillSequences) {
  const MemorySequence one = gridSequence(5, 4, 1, 1.0, 1.0);
  const Coded coded = encode(one, trajectory(0.3));
  EXPECT_EQ(decodeAll(coded.bytes), coded.reconstructions);
  EXPECT_LE(kgError(one, coded.reconstructions), 0.3);

  std::vector<std::vector<float>> same(10, one.frames()[0]);
  const MemorySequence still(one.topology(), same, 25.0, "still");
  const Coded still_coded = encode(still, trajectory(0.3));
  EXPECT_EQ(decodeAll(still_coded.bytes), still_coded.reconstructions);
  EXPECT_LE(kgError(still, still_coded.reconstructions), 0.3);
}

TEST_P(Trajectory, OptionsAreChecked) {
  EncoderOptions both = trajectory(0.3);
  both.set("step", 1e-3);
  EXPECT_FALSE(both.validate().ok());
  EncoderOptions bound;
  bound.codec = codec();
  EXPECT_TRUE(bound.set("max-error", 0.01).validate().ok());
  EXPECT_FALSE(bound.set("bpvf", 2.0).validate().ok());
  EXPECT_FALSE(trajectory(0).validate().ok());
  EXPECT_FALSE(trajectory(0.3).set("group-frames", 0.0).validate().ok());
  EXPECT_FALSE(trajectory(0.3).set("group-frames", 2000.0).validate().ok());
  EXPECT_FALSE(trajectory(0.3).set("bits", 12.0).validate().ok());
  EXPECT_TRUE(trajectory(0.3).set("group-frames", 64.0).validate().ok());
}

// Every cut and every single-byte change of a small stream is refused with an error or
// decodes to some frames: never a crash (the fuzzers go further).
TEST_P(Trajectory, DamagedStreamsAreRefusedOrDecodedSafely) {
  const MemorySequence seq = gridSequence(6, 5, 8, 1.0, 1.0);
  const Coded coded = encode(seq, trajectory(0.5));
  int refused = 0;
  for (size_t cut = 0; cut < coded.bytes.size(); ++cut) {
    auto decoder = Decoder::openMemory(coded.bytes.data(), cut);
    refused += !decoder.ok() || !decoder.value().verify().ok();
  }
  EXPECT_EQ(refused, int(coded.bytes.size())) << "a cut stream passed verify()";
  for (size_t i = 0; i < coded.bytes.size(); ++i) {
    std::vector<uint8_t> bytes = coded.bytes;
    bytes[i] ^= 0x5A;
    auto decoder = Decoder::openMemory(bytes.data(), bytes.size());
    if (decoder.ok()) (void)decoder.value().verify();
  }
}

INSTANTIATE_TEST_SUITE_P(Codecs, Trajectory, testing::Values("trajectory", "trajectory2"));

}  // namespace
}  // namespace animc
