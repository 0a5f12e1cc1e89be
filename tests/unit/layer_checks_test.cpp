// SPDX-License-Identifier: Apache-2.0
// The MeshLab adapter's checks (meshlab_adapter/layer_checks.h) on a stand-in layer and the
// golden files: what a layer with deleted elements becomes as a frame, and which ranges of an
// .ams file may become layers.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "api.h"
#include "layer_checks.h"
#include "seqio/mesh_checks.h"
#include "stand_in_layer.h"

namespace animc::meshlab {
namespace {

using testing::StandInLayer;

const std::string kGolden = std::string(ANIMC_SOURCE_DIR) + "/tests/golden/affine_octree_default.v1.groups.ams";
constexpr LayerElementBytes kElement = {100, 50};

// Five vertices, slot 1 deleted; a live face, a deleted one on the deleted vertex, a live one.
StandInLayer layerWithDeletedElements() {
  StandInLayer layer;
  for (int i = 0; i < 5; ++i) layer.vert.push_back({{float(i), 2.0f * i, 3.0f * i}, i == 1});
  layer.addFace(0, 2, 3);
  layer.addFace(0, 1, 2, /*deleted=*/true);
  layer.addFace(2, 3, 4);
  return layer;
}

TEST(LayerChecks, LiveTopologyRenumbersOverLiveVertices) {
  const Topology t = liveTopology(layerWithDeletedElements());
  EXPECT_EQ(t.vertex_count, 4u);
  const std::vector<Triangle> expected = {{0, 1, 2}, {1, 2, 3}};
  EXPECT_EQ(t.triangles, expected);
  EXPECT_TRUE(checkTopology(t).ok());
}

TEST(LayerChecks, LiveFaceOnDeletedVertexIsRefused) {
  StandInLayer layer = layerWithDeletedElements();
  layer.face[1].deleted = false;
  const Topology t = liveTopology(layer);
  ASSERT_EQ(t.triangles.size(), 3u);
  EXPECT_EQ(t.triangles[1][1], UINT32_MAX);
  EXPECT_FALSE(checkTopology(t).ok());
}

TEST(LayerChecks, LivePositionsSkipDeletedVertices) {
  std::vector<float> xyz = {7, 7};  // replaced, not appended to
  livePositions(layerWithDeletedElements(), xyz);
  const std::vector<float> expected = {0, 0, 0, 2, 4, 6, 3, 6, 9, 4, 8, 12};
  EXPECT_EQ(xyz, expected);
}

std::unique_ptr<AmsSource> openGolden(const AmsImport& range = AmsImport()) {
  auto source = AmsSource::open(kGolden, range.decoderLimits());
  EXPECT_TRUE(source.ok()) << source.status().message();
  return source.ok() ? std::move(source).value() : nullptr;
}

TEST(LayerChecks, PlanCoversTheWholeFileByDefaultAndSeeksToTheFirstFrame) {
  auto source = openGolden();
  ASSERT_TRUE(source);
  const int64_t frames = source->frameCount();
  ASSERT_GE(frames, 3);
  auto whole = planAmsImport(kGolden, *source, AmsImport(), kElement);
  ASSERT_TRUE(whole.ok()) << whole.status().message();
  EXPECT_EQ(whole.value().first, 0);
  EXPECT_EQ(whole.value().last, frames - 1);

  AmsImport range;
  range.first_frame = frames - 2;
  auto tail = planAmsImport(kGolden, *source, range, kElement);
  ASSERT_TRUE(tail.ok()) << tail.status().message();
  EXPECT_EQ(tail.value().count(), 2);
  std::vector<float> planned, expected(3 * size_t(source->topology().vertex_count));
  ASSERT_TRUE(source->next(planned).value());
  ASSERT_TRUE(source->decoder().frame(frames - 2, expected.data()).ok());
  EXPECT_EQ(planned, expected);
}

TEST(LayerChecks, PlanRefusesRangesOutsideTheFile) {
  auto source = openGolden();
  ASSERT_TRUE(source);
  const int64_t frames = source->frameCount();
  for (const auto& [first, last] : std::vector<std::pair<int64_t, int64_t>>{{-1, 0}, {2, 1}, {0, frames}, {frames, -1}}) {
    AmsImport range;
    range.first_frame = first;
    range.last_frame = last;
    const auto plan = planAmsImport("g.ams", *source, range, kElement);
    ASSERT_FALSE(plan.ok()) << first << " " << last;
    EXPECT_EQ(plan.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(plan.status().message().find("g.ams has frames 0 to " + std::to_string(frames - 1)), std::string::npos);
  }
}

TEST(LayerChecks, PlanRefusesRangesAboveTheMemoryLimit) {
  auto golden = openGolden();
  ASSERT_TRUE(golden);
  const uint64_t layer = layerBytes(golden->topology(), kElement);
  AmsImport range;
  range.last_frame = 1;  // two layers
  range.max_layer_megabytes = int64_t(2 * layer / (1 << 20));  // rounds down: below two layers
  if (2 * layer % (1 << 20) == 0) --range.max_layer_megabytes;
  auto limited = openGolden(range);
  ASSERT_TRUE(limited);
  const auto plan = planAmsImport("g.ams", *limited, range, kElement);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.status().code(), StatusCode::kLimitExceeded);
  EXPECT_NE(plan.status().message().find("Memory limit (MB)"), std::string::npos) << plan.status().message();
  EXPECT_EQ(plan.status().message().find("ANIMC_MAX_VERTEX_FRAMES"), std::string::npos) << plan.status().message();
  range.max_layer_megabytes = int64_t(2 * layer / (1 << 20)) + 1;
  auto enough = openGolden(range);
  ASSERT_TRUE(enough);
  EXPECT_TRUE(planAmsImport("g.ams", *enough, range, kElement).ok());
}

TEST(LayerChecks, PlanRefusesRangesAboveTheWorkLimitNamingMeshLabsKnobs) {
  AmsImport range;
  range.max_vertex_frames = 1;
  auto source = openGolden(range);
  ASSERT_TRUE(source);
  const auto plan = planAmsImport("g.ams", *source, range, kElement);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.status().code(), StatusCode::kLimitExceeded);
  EXPECT_NE(plan.status().message().find("ANIMC_MAX_VERTEX_FRAMES"), std::string::npos) << plan.status().message();
  EXPECT_EQ(plan.status().message().find("Memory limit"), std::string::npos) << plan.status().message();
}

TEST(LayerChecks, LayerCountMustMatchTheRange) {
  const FrameRange range{3, 5};
  EXPECT_TRUE(checkLayerCount("g.ams", range, 3).ok());
  const Status s = checkLayerCount("g.ams", range, 2);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "MeshLab made 2 layers for 3 frames of g.ams");
}

}  // namespace
}  // namespace animc::meshlab
