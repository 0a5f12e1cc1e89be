// SPDX-License-Identifier: Apache-2.0
// The public API (animc/animc.h) as a program uses it: options by name, memory and file sinks,
// decoding from memory and from a file, random access, verify(), errors, threads.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <thread>

#include "animc/animc.h"
#include "api.h"  // encodeSequence: the settings path of animc and the plugins
#include "scratch_folder.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::gridSequence;

class PublicApi : public testing_support::ScratchFolderTest {
 protected:
  PublicApi() : ScratchFolderTest("public_api") {}
};

struct Grid {
  uint32_t vertices = 0;
  std::vector<uint32_t> triangles;
  std::vector<std::vector<float>> frames;
};

Grid grid(int frames) {
  MemorySequence seq = gridSequence(12, 10, frames, 1.0, 1.0);
  Grid g;
  g.vertices = seq.topology().vertex_count;
  for (const Triangle& t : seq.topology().triangles) g.triangles.insert(g.triangles.end(), t.begin(), t.end());
  g.frames = seq.frames();
  return g;
}

// The stream of `g` under `options` in memory (empty on failure, with a test failure).
std::vector<uint8_t> encode(const Grid& g, const EncoderOptions& options) {
  std::vector<uint8_t> bytes;
  auto encoder = Encoder::create(options, g.vertices, g.triangles.data(), g.triangles.size() / 3, memorySink(&bytes));
  EXPECT_TRUE(encoder.ok()) << encoder.status().message();
  if (!encoder.ok()) return {};
  for (const std::vector<float>& frame : g.frames) EXPECT_TRUE(encoder.value().addFrame(frame.data()).ok());
  auto summary = encoder.value().finish();
  EXPECT_TRUE(summary.ok()) << summary.status().message();
  if (summary.ok()) {
    EXPECT_EQ(summary.value().bytes, bytes.size());
  }
  return bytes;
}

std::vector<std::vector<float>> decodeInOrder(Decoder& decoder) {
  std::vector<std::vector<float>> frames;
  std::vector<float> xyz(3 * size_t(decoder.info().vertices));
  for (int64_t k = 0; k < decoder.info().frames; ++k) {
    EXPECT_TRUE(decoder.frame(k, xyz.data()).ok());
    frames.push_back(xyz);
  }
  return frames;
}

std::vector<uint8_t> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

EncoderOptions octree(double max_error, uint32_t iframe_interval) {
  EncoderOptions o;
  o.set("max-error", max_error);
  o.iframe_interval = iframe_interval;
  return o;
}

TEST_F(PublicApi, MemoryAndFileSinksWriteTheBytesOfEncodeSequence) {
  const Grid g = grid(20);
  const std::vector<uint8_t> memory = encode(g, octree(0.005, 7));
  ASSERT_FALSE(memory.empty());

  auto sink = fileSink(path("api.ams"));
  ASSERT_TRUE(sink.ok());
  auto encoder = Encoder::create(octree(0.005, 7), g.vertices, g.triangles.data(), g.triangles.size() / 3,
                                 std::move(sink).value());
  ASSERT_TRUE(encoder.ok());
  for (const std::vector<float>& frame : g.frames) ASSERT_TRUE(encoder.value().addFrame(frame.data()).ok());
  ASSERT_TRUE(encoder.value().finish().ok());
  EXPECT_EQ(readFile(path("api.ams")), memory);

  // The internal settings path of animc and the plugins: the same bytes.
  MemorySequence seq = gridSequence(12, 10, 20, 1.0, 1.0);
  EncodeSettings settings;
  settings.octree().max_error = 0.005;
  settings.iframe_interval = 7;
  ASSERT_TRUE(encodeSequence(seq, settings, path("settings.ams")).ok());
  EXPECT_EQ(readFile(path("settings.ams")), memory);
}

TEST_F(PublicApi, RandomAccessFromMemoryMatchesInOrderDecodingAndTheEncoder) {
  const Grid g = grid(30);
  EncoderOptions options = octree(0.002, 8);
  std::vector<uint8_t> bytes;
  auto encoder = Encoder::create(options, g.vertices, g.triangles.data(), g.triangles.size() / 3, memorySink(&bytes));
  ASSERT_TRUE(encoder.ok());
  std::vector<std::vector<float>> reconstructions;
  for (const std::vector<float>& frame : g.frames) {
    ASSERT_TRUE(encoder.value().addFrame(frame.data()).ok());
    const float* r = encoder.value().reconstruction();
    reconstructions.emplace_back(r, r + frame.size());
  }
  ASSERT_TRUE(encoder.value().finish().ok());

  auto decoder = Decoder::openMemory(bytes.data(), bytes.size());
  ASSERT_TRUE(decoder.ok()) << decoder.status().message();
  const StreamInfo& info = decoder.value().info();
  EXPECT_EQ(info.codec, "affine-octree");
  EXPECT_EQ(info.frames, 30);
  EXPECT_EQ(info.groups, 4u);
  EXPECT_EQ(info.bytes, bytes.size());
  EXPECT_EQ(std::vector<uint32_t>(decoder.value().triangles(), decoder.value().triangles() + g.triangles.size()),
            g.triangles);
  const auto in_order = decodeInOrder(decoder.value());
  EXPECT_EQ(in_order, reconstructions);
  std::vector<float> xyz(3 * size_t(g.vertices));
  for (int64_t k : {17, 3, 29, 0, 8, 7, 17}) {
    ASSERT_TRUE(decoder.value().frame(k, xyz.data()).ok());
    EXPECT_EQ(xyz, in_order[size_t(k)]) << "frame " << k;
  }
  EXPECT_EQ(decoder.value().frame(30, xyz.data()).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(decoder.value().frame(-1, xyz.data()).code(), StatusCode::kInvalidArgument);
}

TEST_F(PublicApi, OptionsAreCheckedByName) {
  EncoderOptions unknown;
  unknown.set("no-such-option", 1.0);
  EXPECT_EQ(unknown.validate().code(), StatusCode::kInvalidArgument);
  EncoderOptions foreign;
  foreign.set("step", 0.001);  // a wavelet option, affine-octree chosen
  EXPECT_NE(foreign.validate().message().find("step"), std::string::npos);
  EncoderOptions range;
  range.set("max-error", 2.0);
  EXPECT_FALSE(range.validate().ok());
  EncoderOptions codec;
  codec.codec = "mpeg";
  EXPECT_FALSE(codec.validate().ok());
  EncoderOptions wavelet;
  wavelet.codec = "wavelet";
  wavelet.set("step", 0.001).set("i-frames-only", "1");
  EXPECT_TRUE(wavelet.validate().ok()) << wavelet.validate().message();
  EXPECT_EQ(codecNames(), (std::vector<std::string>{"affine-octree", "wavelet", "trajectory", "auto", "trajectory2"}));
}

TEST_F(PublicApi, BadFramesAndMeshesAreRefused) {
  const Grid g = grid(2);
  std::vector<uint8_t> bytes;
  const std::vector<uint32_t> outside = {0, 1, g.vertices};
  EXPECT_EQ(Encoder::create({}, g.vertices, outside.data(), 1, memorySink(&bytes)).status().code(),
            StatusCode::kBadInput);
  EXPECT_EQ(Encoder::create({}, g.vertices, nullptr, 0, memorySink(&bytes)).status().code(), StatusCode::kBadInput);
  auto encoder = Encoder::create({}, g.vertices, g.triangles.data(), g.triangles.size() / 3, memorySink(&bytes));
  ASSERT_TRUE(encoder.ok());
  std::vector<float> nan = g.frames[0];
  nan[5] = std::nanf("");
  EXPECT_EQ(encoder.value().addFrame(nan.data()).code(), StatusCode::kBadInput);
  EXPECT_EQ(encoder.value().finish().status().code(), StatusCode::kBadInput);  // no frames
}

TEST_F(PublicApi, AnUnfinishedEncoderLeavesNothing) {
  const Grid g = grid(3);
  std::vector<uint8_t> bytes;
  {
    auto encoder = Encoder::create({}, g.vertices, g.triangles.data(), g.triangles.size() / 3, memorySink(&bytes));
    ASSERT_TRUE(encoder.ok());
    ASSERT_TRUE(encoder.value().addFrame(g.frames[0].data()).ok());
    EXPECT_FALSE(bytes.empty());
  }
  EXPECT_TRUE(bytes.empty());
  {
    auto sink = fileSink(path("never.ams"));
    ASSERT_TRUE(sink.ok());
    auto encoder = Encoder::create({}, g.vertices, g.triangles.data(), g.triangles.size() / 3, std::move(sink).value());
    ASSERT_TRUE(encoder.value().addFrame(g.frames[0].data()).ok());
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir_));
}

TEST_F(PublicApi, DamagedStreamsAreRefusedWithTheirCause) {
  const std::vector<uint8_t> bytes = encode(grid(20), octree(0.01, 5));
  ASSERT_FALSE(bytes.empty());
  EXPECT_EQ(Decoder::openMemory(bytes.data(), bytes.size() - 30).status().code(), StatusCode::kTruncated);
  EXPECT_EQ(Decoder::openMemory(nullptr, 0).status().code(), StatusCode::kTruncated);

  // A flipped byte in the last group: opening checks the first group only, verify() all.
  std::vector<uint8_t> flipped = bytes;
  auto clean = Decoder::openMemory(bytes.data(), bytes.size());
  ASSERT_TRUE(clean.ok());
  ASSERT_TRUE(clean.value().verify().ok());
  flipped[flipped.size() - 120] ^= 0x40;
  auto opened = Decoder::openMemory(flipped.data(), flipped.size());
  ASSERT_TRUE(opened.ok()) << opened.status().message();
  EXPECT_EQ(opened.value().verify().code(), StatusCode::kCorrupt);

  DecoderOptions small;
  small.limits.max_vertex_frames = 10;
  auto limited = Decoder::openMemory(bytes.data(), bytes.size(), small);
  ASSERT_TRUE(limited.ok());
  std::vector<float> xyz(3 * size_t(limited.value().info().vertices));
  EXPECT_EQ(limited.value().frame(12, xyz.data()).code(), StatusCode::kLimitExceeded);
  EXPECT_EQ(Decoder::openFile(path("missing.ams")).status().code(), StatusCode::kIoError);
}

// max_output_bytes bounds a range's output, as floats or in the caller's own measure, before
// any work, and every frame() call; verify() keeps nothing, so it is not bounded by it.
TEST_F(PublicApi, OutputLimitRefusesRangesBeforeAnyWork) {
  const std::vector<uint8_t> bytes = encode(grid(20), octree(0.01, 5));
  ASSERT_FALSE(bytes.empty());
  auto probe = Decoder::openMemory(bytes.data(), bytes.size());
  ASSERT_TRUE(probe.ok());
  const uint64_t frame_bytes = 12 * uint64_t(probe.value().info().vertices);
  DecoderOptions small;
  small.limits.max_output_bytes = 3 * frame_bytes;
  auto limited = Decoder::openMemory(bytes.data(), bytes.size(), small);
  ASSERT_TRUE(limited.ok());
  Decoder& d = limited.value();
  EXPECT_TRUE(d.checkDecodeWork(2, 5).ok());
  const Status four = d.checkDecodeWork(2, 6);
  EXPECT_EQ(four.code(), StatusCode::kLimitExceeded);
  EXPECT_NE(four.message().find("DecoderLimits::max_output_bytes"), std::string::npos) << four.message();
  EXPECT_EQ(d.checkDecodeWork(2, 3, 3 * frame_bytes + 1).code(), StatusCode::kLimitExceeded);
  EXPECT_TRUE(d.checkDecodeWork(2, 6, 3 * frame_bytes).ok());
  EXPECT_TRUE(d.verify().ok());

  small.limits.max_output_bytes = frame_bytes - 1;
  auto tiny = Decoder::openMemory(bytes.data(), bytes.size(), small);
  ASSERT_TRUE(tiny.ok());
  std::vector<float> xyz(3 * size_t(tiny.value().info().vertices));
  EXPECT_EQ(tiny.value().frame(1, xyz.data()).code(), StatusCode::kLimitExceeded);
}

// Different objects on different threads: the same bytes and frames as on one thread.
TEST_F(PublicApi, IndependentObjectsRunInParallel) {
  const Grid g = grid(25);
  const std::vector<uint8_t> reference = encode(g, octree(0.003, 6));
  auto reference_decoder = Decoder::openMemory(reference.data(), reference.size());
  ASSERT_TRUE(reference_decoder.ok());
  const auto reference_frames = decodeInOrder(reference_decoder.value());
  constexpr int kThreads = 4;
  std::vector<std::vector<uint8_t>> streams(kThreads);
  std::vector<std::vector<std::vector<float>>> frames(kThreads);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      streams[t] = encode(g, octree(0.003, 6));
      auto decoder = Decoder::openMemory(reference.data(), reference.size());
      if (decoder.ok()) frames[t] = decodeInOrder(decoder.value());
    });
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) {
    EXPECT_EQ(streams[t], reference) << "thread " << t;
    EXPECT_EQ(frames[t], reference_frames) << "thread " << t;
  }
}

TEST(PublicApiVersion, TheLinkedLibraryIsThisRelease) { EXPECT_STREQ(animcVersion(), ANIMC_VERSION_STRING); }

}  // namespace
}  // namespace animc
