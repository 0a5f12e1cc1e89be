// SPDX-License-Identifier: Apache-2.0
// How auto estimates a frame-by-frame candidate's size on a group before deciding whether to
// code the whole group with it (docs/auto.md): runs of a few frames spread over the group,
// each coded as a group of its own.
#pragma once
#include <cstdint>
#include <vector>

namespace animc {

constexpr uint32_t kSampleRunFrames = 4;
constexpr uint32_t kMostSampleRuns = 4;

// The first frames of the runs that sample a group of frame_count frames: up to
// kMostSampleRuns runs of kSampleRunFrames, the first at the group's start and the last at its
// end, never more than half its frames; none (the group is coded in full) below
// 2 x kSampleRunFrames frames.
std::vector<uint32_t> sampleRunStarts(uint32_t frame_count);

}  // namespace animc
