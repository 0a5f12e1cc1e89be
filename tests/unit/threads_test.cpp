// SPDX-License-Identifier: Apache-2.0
// Threads: parallelFor and its budget, then the promise of EncoderOptions::threads and
// DecoderOptions::threads: for every codec and mode, the same bytes and the same frames
// whatever the number of threads, reconstructions that match the decoder when groups are
// coded in batches, and Decoder::frames() equal to frame() in a loop.
#include <gtest/gtest.h>

#include <atomic>
#include <new>
#include <string>
#include <vector>

#include "animc/animc.h"
#include "api.h"
#include "core/adjacency.h"
#include "core/parallel.h"
#include "group_codec_support.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::Coded;
using testing_support::decodeAll;
using testing_support::encodeCollecting;
using testing_support::gridSequence;

TEST(ParallelFor, RunsEveryItemOnceOnTheBudgetsThreads) {
  ThreadBudget budget(3);
  std::vector<std::atomic<int>> runs(100);
  std::vector<unsigned> inner(100);
  parallelFor(runs.size(), [&](size_t i) {
    ++runs[i];
    inner[i] = ThreadBudget::current();
  });
  for (size_t i = 0; i < runs.size(); ++i) {
    EXPECT_EQ(runs[i], 1) << i;
    EXPECT_EQ(inner[i], 1u) << i;  // 3 threads for 100 items: nothing left for a loop inside
  }
  EXPECT_EQ(ThreadBudget::current(), 3u);
}

TEST(ParallelFor, ASingleItemKeepsTheWholeBudgetAndSmallWorkStaysOnOneThread) {
  ThreadBudget budget(4);
  unsigned inside = 0;
  parallelFor(1, [&](size_t) { inside = ThreadBudget::current(); });
  EXPECT_EQ(inside, 4u);
  parallelFor(8, 1.0, [&](size_t) { inside = ThreadBudget::current(); });
  EXPECT_EQ(inside, 1u);
}

TEST(ParallelFor, AnItemsExceptionReachesTheCaller) {
  ThreadBudget budget(2);
  EXPECT_THROW(parallelFor(50,
                           [](size_t i) {
                             if (i == 7) throw std::bad_alloc();
                           }),
               std::bad_alloc);
  EXPECT_THROW(runBeside([] { throw std::bad_alloc(); }, [] {}), std::bad_alloc);
  int both = 0;
  runBeside([&] { both += 1; }, [&] { both += 2; });
  EXPECT_EQ(both, 3);
}

TEST(ParallelFor, ZeroMeansOneThreadPerCore) {
  EXPECT_GE(resolveThreads(0), 1u);
  EXPECT_EQ(resolveThreads(5), 5u);
}

TEST(MeshTables, AdjacencyRowsAreTheSameOnAnyNumberOfThreads) {
  // Triangles enough for several blocks of the edge listing, whose rows fill in any order.
  const Topology mesh = testing_support::gridTopology(300, 300);
  auto rowsOn = [&](unsigned threads) {
    ThreadBudget budget(threads);
    const VertexAdjacency adjacency(mesh);
    std::vector<std::vector<uint32_t>> rows;
    for (uint32_t v = 0; v < mesh.vertex_count; ++v) rows.emplace_back(adjacency.begin(v), adjacency.end(v));
    return rows;
  };
  const auto one = rowsOn(1);
  EXPECT_EQ(one[301], (std::vector<uint32_t>{0, 1, 300, 302, 601, 602}));  // sorted, each once
  EXPECT_EQ(rowsOn(2), one);
  EXPECT_EQ(rowsOn(3), one);
}

TEST(AffineOctreeThreads, SubtreesSearchedOnThreadsCodeTheSameBytes) {
  // More vertices than the root cell searches on one thread: its children go to threads.
  const MemorySequence seq = gridSequence(200, 200, 5, 1.0, 1.0);
  EncoderOptions options;
  options.codec = "affine-octree";
  options.set("max-error", 0.002);
  options.threads = 1;
  const Coded one = encodeCollecting(seq, options);
  ASSERT_FALSE(one.bytes.empty());
  for (uint32_t threads : {2u, 3u}) {
    options.threads = threads;
    EXPECT_EQ(encodeCollecting(seq, options).bytes, one.bytes) << threads << " threads";
  }
}

struct Mode {
  std::string name;
  std::string codec;
  std::vector<std::pair<std::string, std::string>> values;
  uint32_t iframe_interval;
};

EncoderOptions optionsOf(const Mode& m, uint32_t threads) {
  EncoderOptions o;
  o.codec = m.codec;
  for (const auto& [name, value] : m.values) o.set(name, value);
  o.iframe_interval = m.iframe_interval;
  o.threads = threads;
  return o;
}

class EveryCodecAndMode : public ::testing::TestWithParam<Mode> {};

TEST_P(EveryCodecAndMode, BytesAndFramesDoNotDependOnTheThreadCount) {
  const MemorySequence seq = gridSequence(14, 12, 40, 1.0, 1.0);
  const Coded one = encodeCollecting(seq, optionsOf(GetParam(), 1));
  ASSERT_FALSE(one.bytes.empty());
  const std::vector<std::vector<float>> decoded = decodeAll(one.bytes);
  EXPECT_EQ(one.reconstructions, decoded);
  for (uint32_t threads : {2u, 3u, 0u}) {
    const Coded many = encodeCollecting(seq, optionsOf(GetParam(), threads));
    EXPECT_EQ(many.bytes, one.bytes) << threads << " threads";
    // Groups coded in batches: every reconstruction still comes, and is the decoder's.
    EXPECT_EQ(many.reconstructions, decoded) << threads << " threads";
  }
  for (uint32_t threads : {1u, 2u, 3u}) {
    DecoderOptions options;
    options.threads = threads;
    auto decoder = Decoder::openMemory(one.bytes.data(), one.bytes.size(), options);
    ASSERT_TRUE(decoder.ok()) << decoder.status().message();
    const size_t size = 3 * size_t(seq.topology().vertex_count);
    for (auto [first, last] : {std::pair<int64_t, int64_t>{0, 40}, {3, 29}, {17, 18}, {9, 40}}) {
      std::vector<float> frames(size_t(last - first) * size);
      ASSERT_TRUE(decoder.value().frames(first, last, frames.data()).ok()) << first << ":" << last;
      for (int64_t k = first; k < last; ++k)
        EXPECT_TRUE(
            std::equal(decoded[size_t(k)].begin(), decoded[size_t(k)].end(), frames.begin() + size_t(k - first) * size))
            << "frame " << k << " of " << first << ":" << last << ", " << threads << " threads";
    }
    EXPECT_TRUE(decoder.value().verify().ok()) << threads << " threads";
  }
}

INSTANTIATE_TEST_SUITE_P(
    Threads, EveryCodecAndMode,
    ::testing::Values(Mode{"octree_predictive", "affine-octree", {{"max-error", "0.004"}}, 8},
                      Mode{"octree_paper", "affine-octree", {{"profile", "paper"}}, 7},
                      Mode{"octree_one_group", "affine-octree", {}, 0},
                      // 20 groups: decoding batches of several groups a thread, one after the other
                      Mode{"octree_small_groups", "affine-octree", {}, 2},
                      Mode{"wavelet", "wavelet", {{"step", "0.001"}}, 9},
                      Mode{"wavelet_target_kg", "wavelet", {{"target-kg", "0.5"}}, 10},
                      Mode{"wavelet_progressive", "wavelet", {{"step", "0.001"}, {"progressive-p-frames", "1"}}, 12},
                      Mode{"trajectory_kg", "trajectory", {{"target-kg", "0.3"}}, 6},
                      Mode{"trajectory_max_error", "trajectory", {{"max-error", "0.01"}, {"group-frames", "11"}}, 0},
                      Mode{"trajectory_one_group", "trajectory", {{"target-kg", "0.3"}}, 0},
                      Mode{"trajectory2_kg", "trajectory2", {{"target-kg", "0.3"}}, 6},
                      Mode{"trajectory2_max_error", "trajectory2", {{"max-error", "0.01"}, {"parts", "3"}}, 0},
                      Mode{"auto_max_error", "auto", {{"max-error", "0.01"}}, 5},
                      Mode{"auto_target_kg", "auto", {{"target-kg", "0.3"}}, 13}),
    [](const ::testing::TestParamInfo<Mode>& info) { return info.param.name; });

TEST(EncoderThreads, GroupsAreKnownABatchAtATime) {
  const MemorySequence seq = gridSequence(12, 10, 20, 1.0, 1.0);
  Mode octree{"octree", "affine-octree", {}, 4};
  const Coded coded = encodeCollecting(seq, optionsOf(octree, 3));
  // Groups of 4 frames, three coded at once: the first 12 frames are known once the 12th is
  // added, the last 8 at finish().
  std::vector<int64_t> expected(20, 0);
  for (size_t k = 11; k < 20; ++k) expected[k] = 12;
  EXPECT_EQ(coded.known_after_each_frame, expected);
  EXPECT_EQ(coded.reconstructions.size(), 20u);
}

TEST(DecoderThreads, FramesRefusesARangeOutsideTheStreamOrAboveTheLimits) {
  const MemorySequence seq = gridSequence(12, 10, 20, 1.0, 1.0);
  Mode trajectory{"trajectory", "trajectory", {{"target-kg", "0.3"}}, 5};
  const Coded coded = encodeCollecting(seq, optionsOf(trajectory, 1));
  DecoderOptions options;
  options.limits.max_output_bytes = 12 * 120 * 3;  // three frames of 120 vertices
  auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size(), options);
  ASSERT_TRUE(decoder.ok());
  std::vector<float> xyz(3 * 120 * 20);
  EXPECT_EQ(decoder.value().frames(0, 21, xyz.data()).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decoder.value().frames(4, 4, xyz.data()).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decoder.value().frames(0, 4, xyz.data()).code(), StatusCode::kLimitExceeded);
  EXPECT_TRUE(decoder.value().frames(4, 7, xyz.data()).ok());
}

TEST(DecoderThreads, ReadersTakeSeveralGroupsAtOnceButOneGroupAFrameAtATime) {
  const MemorySequence seq = gridSequence(12, 10, 40, 1.0, 1.0);
  Mode groups{"groups", "affine-octree", {}, 4};
  Mode one_group{"one group", "trajectory", {{"target-kg", "0.3"}}, 0};
  const Coded grouped = encodeCollecting(seq, optionsOf(groups, 1));
  const Coded whole = encodeCollecting(seq, optionsOf(one_group, 1));
  DecoderOptions options;
  options.threads = 2;
  auto by_groups = Decoder::openMemory(grouped.bytes.data(), grouped.bytes.size(), options);
  auto single = Decoder::openMemory(whole.bytes.data(), whole.bytes.size(), options);
  ASSERT_TRUE(by_groups.ok() && single.ok());
  // Eight groups of 4 frames a run (four a thread), from a group's start or from inside one;
  // the run ends at the last group.
  EXPECT_EQ(decodeChunkEnd(by_groups.value(), 0), 32);
  EXPECT_EQ(decodeChunkEnd(by_groups.value(), 5), 36);
  EXPECT_EQ(decodeChunkEnd(by_groups.value(), 30), 40);
  // Within one group (the last one here) the frames come from the cursor one by one: a run
  // would only hold memory.
  EXPECT_EQ(decodeChunkEnd(by_groups.value(), 37), 38);
  EXPECT_EQ(decodeChunkEnd(single.value(), 0), 1);
  EXPECT_EQ(decodeChunkEnd(single.value(), 13), 14);
}

TEST(DecoderLimitsWork, ATrajectoryGroupCostingMoreMultiplyAddsIsRefused) {
  const MemorySequence seq = gridSequence(14, 12, 40, 1.0, 1.0);
  Mode trajectory{"trajectory", "trajectory", {{"target-kg", "0.3"}}, 0};
  const Coded coded = encodeCollecting(seq, optionsOf(trajectory, 1));
  std::vector<float> xyz(3 * size_t(seq.topology().vertex_count));
  for (uint32_t threads : {1u, 2u}) {
    DecoderOptions options;
    options.threads = threads;
    options.limits.max_multiply_adds = 3 * 168 * 40;  // one component's worth: the group has more
    auto decoder = Decoder::openMemory(coded.bytes.data(), coded.bytes.size(), options);
    ASSERT_TRUE(decoder.ok());
    const Status refused = decoder.value().frame(5, xyz.data());
    EXPECT_EQ(refused.code(), StatusCode::kLimitExceeded);
    EXPECT_NE(refused.message().find("max_multiply_adds"), std::string::npos) << refused.message();
    EXPECT_EQ(decoder.value().verify().code(), StatusCode::kLimitExceeded);
  }
  EXPECT_EQ(decodeAll(coded.bytes), coded.reconstructions);  // the default limits take it
}

}  // namespace
}  // namespace animc
