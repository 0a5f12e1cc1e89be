// SPDX-License-Identifier: Apache-2.0
// Codec 5's parts (docs/format.md, section 16): vertices moving apart are cut into parts that
// cost fewer bits than one basis for all, and coarser cuts are unions of finer ones; the labels and the part table of a
// group payload are checked before any part is decoded; a group's reconstruction is bounded as a whole.
// (trajectory_test.cpp runs every rate mode of both trajectory codecs.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "animc/animc.h"
#include "codecs/trajectory/clusters.h"
#include "codecs/trajectory/parted_group.h"
#include "group_codec_support.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::Coded;
using testing_support::decodeAll;
using testing_support::gridFrame;
using testing_support::gridTopology;
using testing_support::kgError;
const auto encode = testing_support::encodeCollecting;

// Two grids side by side, not joined: one waves, the other turns and drifts. One basis for
// both needs the components of each motion on every vertex.
constexpr int kGridX = 10, kGridY = 8;

std::vector<std::vector<float>> twoMotionFrames(int frames) {
  std::vector<std::vector<float>> all;
  for (int f = 0; f < frames; ++f) {
    std::vector<float> xyz = gridFrame(kGridX, kGridY, f, 1.0, 0.0);
    const std::vector<float> other = gridFrame(kGridX, kGridY, 2 * f + 7, 0.5, 1.5);
    for (size_t i = 0; i < other.size(); ++i) xyz.push_back(other[i] + (i % 3 == 0 ? 2.0f : 0.0f));
    all.push_back(std::move(xyz));
  }
  return all;
}

MemorySequence twoMotions(int frames) {
  const Topology grid = gridTopology(kGridX, kGridY);
  Topology both;
  both.vertex_count = 2 * grid.vertex_count;
  both.triangles = grid.triangles;
  for (const Triangle& t : grid.triangles)
    both.triangles.push_back({t[0] + grid.vertex_count, t[1] + grid.vertex_count, t[2] + grid.vertex_count});
  return MemorySequence(both, twoMotionFrames(frames), 25.0, "two motions");
}

EncoderOptions atKg(const char* codec, double target) {
  EncoderOptions o;
  o.codec = codec;
  o.set("target-kg", target);
  return o;
}

TEST(TrajectoryParts, VerticesMovingApartCostLessInParts) {
  const MemorySequence seq = twoMotions(48);
  for (double target : {0.1, 0.5}) {
    const Coded whole = encode(seq, atKg("trajectory", target));
    const Coded parts = encode(seq, atKg("trajectory2", target));
    EXPECT_EQ(decodeAll(parts.bytes), parts.reconstructions);
    EXPECT_LE(kgError(seq, parts.reconstructions), target);
    EXPECT_LT(double(parts.bytes.size()), 0.9 * double(whole.bytes.size())) << "target " << target;
  }
}

// The coarser cuts the encoder judges are unions of the finer cut's parts; on the two grids,
// two parts are the grids.
TEST(TrajectoryParts, MergedPartsAreUnionsOfTheFinerOnes) {
  std::vector<float> frames;
  for (const std::vector<float>& xyz : twoMotionFrames(24)) frames.insert(frames.end(), xyz.begin(), xyz.end());
  const uint32_t grid = kGridX * kGridY, vertices = 2 * grid;
  uint32_t fine_count = 0, coarse_count = 0;
  const std::vector<uint8_t> fine = clusterTrajectories(frames.data(), vertices, 24, 8, fine_count);
  ASSERT_EQ(fine_count, 8u);
  const std::vector<uint8_t> coarse = mergeParts(frames.data(), vertices, 24, fine, fine_count, 2, coarse_count);
  ASSERT_EQ(coarse_count, 2u);
  std::vector<int> coarse_of(fine_count, -1);
  for (uint32_t v = 0; v < vertices; ++v) {
    if (coarse_of[fine[v]] < 0) coarse_of[fine[v]] = coarse[v];
    EXPECT_EQ(coarse_of[fine[v]], coarse[v]) << "vertex " << v;
    EXPECT_EQ(coarse[v], v < grid ? 0 : 1) << "vertex " << v;
  }
  const std::vector<uint8_t> whole = mergeParts(frames.data(), vertices, 24, fine, fine_count, 1, coarse_count);
  EXPECT_EQ(coarse_count, 1u);
  EXPECT_TRUE(std::all_of(whole.begin(), whole.end(), [](uint8_t l) { return l == 0; }));
}

TEST(TrajectoryParts, OnePartIsTheWholeMesh) {
  const MemorySequence seq = twoMotions(20);
  EncoderOptions one = atKg("trajectory2", 0.3);
  one.set("parts", 1.0);
  const Coded coded = encode(seq, one);
  EXPECT_EQ(decodeAll(coded.bytes), coded.reconstructions);
  EXPECT_LE(kgError(seq, coded.reconstructions), 0.3);
  EXPECT_FALSE(atKg("trajectory2", 0.3).set("parts", 0.0).validate().ok());
  EXPECT_FALSE(atKg("trajectory2", 0.3).set("parts", 65.0).validate().ok());
}

TEST(TrajectoryParts, AGroupCostingMoreMultiplyAddsIsRefused) {
  const MemorySequence seq = twoMotions(30);
  const Coded coded = encode(seq, atKg("trajectory2", 0.3));
  DecoderOptions options;
  options.limits.max_multiply_adds = 3 * 160 * 30;  // one component for every vertex: the group has more
  auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size(), options);
  ASSERT_TRUE(decoder.ok());
  std::vector<float> xyz(3 * size_t(seq.topology().vertex_count));
  const Status refused = decoder.value().frame(3, xyz.data());
  EXPECT_EQ(refused.code(), StatusCode::kLimitExceeded);
  EXPECT_NE(refused.message().find("max_multiply_adds"), std::string::npos) << refused.message();
}

// A payload of two parts of a 6 x 5 grid (left and right), 2 frames, no components: what the
// tests below damage.
struct TwoParts {
  TwoParts() : mesh(gridTopology(6, 5)), order(mesh), labels(30) {
    for (uint32_t v = 0; v < 30; ++v) labels[v] = v % 6 < 3 ? 0 : 1;
    MeshParts parts(mesh, labels, 2);
    std::vector<TrajectoryGroup> groups(2);
    for (TrajectoryGroup& g : groups) {
      g.frames = 2;
      g.coefficient_step = g.mean_step = 1;
      g.mean.assign(6, 3);
    }
    writePartedGroup(2, labels, order, parts, groups, payload);
  }
  Status read(const std::vector<uint8_t>& bytes) {
    PartedGroupHead head;
    return readPartedGroupHead(ByteReader(bytes.data() + 1, bytes.size() - 1), order, head);
  }
  // Where the first part's Frame_Count is: after Frame_Type, Frame_Count, Part_Count, the
  // labels and the first part's length.
  size_t firstPartAt() const {
    const size_t labels_length = payload[4] | payload[5] << 8 | payload[6] << 16 | payload[7] << 24;
    return 8 + labels_length + 4;
  }
  Topology mesh;
  CodingOrder order;
  std::vector<uint8_t> labels;
  std::vector<uint8_t> payload;
};

TEST(TrajectoryParts, TheLabelsAndPartTableAreRead) {
  TwoParts two;
  PartedGroupHead head;
  ASSERT_TRUE(readPartedGroupHead(ByteReader(two.payload.data() + 1, two.payload.size() - 1), two.order, head).ok());
  EXPECT_EQ(head.frames, 2u);
  EXPECT_EQ(head.part_count, 2u);
  EXPECT_EQ(head.labels, two.labels);
  ASSERT_EQ(head.parts.size(), 2u);
  EXPECT_EQ(head.multiply_adds, 0u);
}

TEST(TrajectoryParts, DamagedPartTablesAreCorrupt) {
  TwoParts two;
  auto withByte = [&](size_t at, uint8_t value) {
    std::vector<uint8_t> bytes = two.payload;
    bytes[at] = value;
    return two.read(bytes);
  };
  for (uint8_t count : {0, 31, 65}) EXPECT_EQ(withByte(3, count).code(), StatusCode::kCorrupt) << int(count);
  const Status three = withByte(3, 3);  // the labels name 2 parts: the third holds no vertex
  EXPECT_EQ(three.code(), StatusCode::kCorrupt);
  EXPECT_NE(three.message().find("no vertex"), std::string::npos) << three.message();
  const Status frames = withByte(two.firstPartAt(), 3);
  EXPECT_EQ(frames.code(), StatusCode::kCorrupt);
  EXPECT_NE(frames.message().find("a part of 3 frames"), std::string::npos) << frames.message();
  std::vector<uint8_t> longer = two.payload;
  longer.push_back(0);
  EXPECT_EQ(two.read(longer).code(), StatusCode::kCorrupt);
  for (size_t cut = 1; cut < two.payload.size(); ++cut) {
    const std::vector<uint8_t> bytes(two.payload.begin(), two.payload.begin() + cut);
    EXPECT_FALSE(two.read(bytes).ok()) << "cut at " << cut;
  }
}

}  // namespace
}  // namespace animc
