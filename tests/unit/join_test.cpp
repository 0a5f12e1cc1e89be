// SPDX-License-Identifier: Apache-2.0
// joinStreams: parts of a sequence encoded apart join into the bytes of the whole sequence's
// encode (every codec, parts a whole number of I-frame intervals long but the last); parts that
// do not belong together, or a damaged one, are refused and nothing is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "animc/animc.h"
#include "group_codec_support.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::encodeCollecting;
using testing_support::gridSequence;

MemorySequence framesOf(const MemorySequence& seq, size_t first, size_t last) {
  std::vector<std::vector<float>> frames(seq.frames().begin() + first, seq.frames().begin() + last);
  return MemorySequence(seq.topology(), std::move(frames), 25.0, "part");
}

EncoderOptions optionsFor(const std::string& codec, uint32_t interval) {
  EncoderOptions o;
  o.codec = codec;
  o.iframe_interval = interval;
  return o;
}

Result<std::vector<uint8_t>> join(const std::vector<std::vector<uint8_t>>& parts) {
  std::vector<StreamPart> refs;
  for (size_t i = 0; i < parts.size(); ++i)
    refs.push_back({"part " + std::to_string(i), parts[i].data(), parts[i].size()});
  std::vector<uint8_t> out;
  auto joined = joinStreams(refs, memorySink(&out));
  if (!joined.ok()) {
    EXPECT_TRUE(out.empty()) << "a failed join left bytes";
    return joined.status();
  }
  return out;
}

class JoinEveryCodec : public ::testing::TestWithParam<std::pair<std::string, uint32_t>> {};

TEST_P(JoinEveryCodec, PartsOfWholeIntervalsJoinIntoTheWholeEncode) {
  const auto [codec, interval] = GetParam();
  const MemorySequence seq = gridSequence(14, 12, 40, 1.0, 1.0);
  const EncoderOptions options = optionsFor(codec, interval);
  const std::vector<uint8_t> whole = encodeCollecting(seq, options).bytes;
  // Parts of 2, 1 and 3 intervals, then the rest.
  std::vector<std::vector<uint8_t>> parts;
  size_t first = 0;
  for (size_t intervals : {2, 1, 3, 100}) {
    const size_t last = std::min<size_t>(seq.frames().size(), first + intervals * interval);
    parts.push_back(encodeCollecting(framesOf(seq, first, last), options).bytes);
    first = last;
    if (first == seq.frames().size()) break;
  }
  ASSERT_GE(parts.size(), 3u);
  auto joined = join(parts);
  ASSERT_TRUE(joined.ok()) << joined.status().message();
  EXPECT_EQ(joined.value(), whole);
  auto one = join({whole});
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(one.value(), whole);
}

INSTANTIATE_TEST_SUITE_P(Join, JoinEveryCodec,
                         ::testing::Values(std::make_pair(std::string("affine-octree"), 8u),
                                           std::make_pair(std::string("wavelet"), 9u),
                                           std::make_pair(std::string("trajectory"), 6u),
                                           std::make_pair(std::string("auto"), 5u)),
                         [](const auto& info) {
                           std::string name = info.param.first;
                           for (char& c : name) c = c == '-' ? '_' : c;
                           return name;
                         });

TEST(Join, PartsOfOtherLengthsStillMakeAValidFile) {
  const MemorySequence seq = gridSequence(14, 12, 20, 1.0, 1.0);
  const EncoderOptions options = optionsFor("trajectory", 0);
  auto joined = join(
      {encodeCollecting(framesOf(seq, 0, 7), options).bytes, encodeCollecting(framesOf(seq, 7, 20), options).bytes});
  ASSERT_TRUE(joined.ok()) << joined.status().message();
  auto decoder = Decoder::openMemory(joined.value().data(), joined.value().size());
  ASSERT_TRUE(decoder.ok());
  EXPECT_EQ(decoder.value().info().frames, 20);
  EXPECT_EQ(decoder.value().info().groups, 2u);
  EXPECT_TRUE(decoder.value().verify().ok());
}

TEST(Join, PartsThatDoNotBelongTogetherAreRefused) {
  const MemorySequence seq = gridSequence(14, 12, 20, 1.0, 1.0);
  const std::vector<uint8_t> a = encodeCollecting(framesOf(seq, 0, 10), optionsFor("affine-octree", 5)).bytes;
  const std::vector<uint8_t> other_codec = encodeCollecting(framesOf(seq, 10, 20), optionsFor("trajectory", 5)).bytes;
  const std::vector<uint8_t> other_interval =
      encodeCollecting(framesOf(seq, 10, 20), optionsFor("affine-octree", 10)).bytes;
  const MemorySequence smaller = gridSequence(10, 12, 10, 1.0, 1.0);
  const std::vector<uint8_t> other_mesh = encodeCollecting(smaller, optionsFor("affine-octree", 5)).bytes;
  for (const auto* b : {&other_codec, &other_interval, &other_mesh}) {
    auto joined = join({a, *b});
    EXPECT_EQ(joined.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(joined.status().message().find("part 1"), std::string::npos) << joined.status().message();
  }
  std::vector<uint8_t> damaged = encodeCollecting(framesOf(seq, 10, 20), optionsFor("affine-octree", 5)).bytes;
  damaged[damaged.size() - 200] ^= 0x40;  // in the last group's frames
  EXPECT_EQ(join({a, damaged}).status().code(), StatusCode::kCorrupt);
  EXPECT_EQ(join({}).status().code(), StatusCode::kInvalidArgument);
}


// A stream still arriving: each prefix opens as the whole groups it holds, whose frames are
// the whole stream's first frames; the whole stream gives itself back.
TEST(WholeGroupsOf, EveryPrefixOpensAsItsWholeGroups) {
  const MemorySequence seq = gridSequence(14, 12, 23, 1.0, 1.0);
  const std::vector<uint8_t> whole = encodeCollecting(seq, optionsFor("affine-octree", 5)).bytes;
  const size_t floats = seq.frames()[0].size();
  auto full = Decoder::openMemory(whole.data(), whole.size());
  ASSERT_TRUE(full.ok());
  std::vector<float> expected(floats * 23);
  ASSERT_TRUE(full.value().frames(0, 23, expected.data()).ok());
  uint64_t previous = 0;
  for (size_t size = 0; size <= whole.size(); size += 7) {
    std::vector<uint8_t> out;
    auto frames = wholeGroupsOf(whole.data(), size, memorySink(&out));
    ASSERT_TRUE(frames.ok()) << size << ": " << frames.status().message();
    ASSERT_GE(frames.value(), previous);
    ASSERT_TRUE(frames.value() % 5 == 0 || frames.value() == 23) << "whole groups only: " << frames.value();
    previous = frames.value();
    if (frames.value() == 0) {
      EXPECT_TRUE(out.empty());
      continue;
    }
    auto part = Decoder::openMemory(out.data(), out.size());
    ASSERT_TRUE(part.ok()) << size << ": " << part.status().message();
    const int64_t n = part.value().info().frames;
    ASSERT_EQ(uint64_t(n), frames.value());
    std::vector<float> got(floats * size_t(n));
    ASSERT_TRUE(part.value().frames(0, n, got.data()).ok());
    EXPECT_TRUE(std::equal(got.begin(), got.end(), expected.begin())) << size;
  }
  EXPECT_EQ(previous, 23u);
  // INDX (16 + 12 + 16 per group) and END (24) follow the last group.
  const size_t last_group_end = whole.size() - (16 + 12 + 16 * 5) - 24;
  std::vector<uint8_t> five_groups, four_groups;
  EXPECT_EQ(wholeGroupsOf(whole.data(), last_group_end, memorySink(&five_groups)).value(), 23u);
  EXPECT_EQ(wholeGroupsOf(whole.data(), last_group_end - 1, memorySink(&four_groups)).value(), 20u);
  std::vector<uint8_t> again;
  ASSERT_EQ(wholeGroupsOf(whole.data(), whole.size(), memorySink(&again)).value(), 23u);
  EXPECT_EQ(again, whole);
  std::vector<uint8_t> bad = whole;
  bad[1] = 'X';
  std::vector<uint8_t> none;
  EXPECT_EQ(wholeGroupsOf(bad.data(), bad.size(), memorySink(&none)).status().code(), StatusCode::kCorrupt);
  // First_Frame and Frame_Count, outside the group CRC, must follow on (the second group's here).
  auto sectionEnd = [&](size_t offset) {
    uint64_t length = 0;
    for (int k = 0; k < 8; ++k) length |= uint64_t(whole[offset + 4 + k]) << (8 * k);
    return offset + 16 + length;
  };
  const size_t second_group = sectionEnd(sectionEnd(sectionEnd(8)));
  for (size_t field : {second_group + 12, second_group + 20}) {
    std::vector<uint8_t> forged = whole, out;
    forged[field] ^= 1;
    auto frames = wholeGroupsOf(forged.data(), forged.size(), memorySink(&out));
    EXPECT_EQ(frames.status().code(), StatusCode::kCorrupt) << field;
    EXPECT_TRUE(out.empty());
  }
}

}  // namespace
}  // namespace animc
