// SPDX-License-Identifier: Apache-2.0
// The codec table (codecs/codec_registry.h): each entry is found by its id, its name and its
// options, and its parameters survive being written and read back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <functional>
#include <string>

#include "api.h"
#include "codecs/codec_registry.h"
#include "codecs/frame_group_encoder.h"
#include "report/report.h"
#include "test_sequences.h"

namespace animc {
namespace {

// A command line without options: every codec's defaults.
class NoOptions : public OptionValues {
 public:
  bool has(const std::string&) const override { return false; }
  std::string get(const std::string&, const std::string& fallback) const override { return fallback; }
};

TEST(CodecRegistry, EveryEntryIsFoundAndRoundTripsItsParameters) {
  ASSERT_EQ(allCodecs().size(), std::variant_size_v<CodecOptions>);
  for (const CodecEntry* codec : allCodecs()) {
    SCOPED_TRACE(codec->name);
    EXPECT_EQ(findCodec(uint8_t(codec->id)), codec);
    ASSERT_TRUE(findCodecByName(codec->name).ok());
    EXPECT_EQ(findCodecByName(codec->name).value(), codec);
    auto options = codec->fromFlags(NoOptions());
    ASSERT_TRUE(options.ok()) << options.status().message();
    EXPECT_EQ(&codecOf(options.value()), codec) << "the options type is not the codec's";
    EXPECT_TRUE(codec->validate(options.value()).ok());
    ByteWriter written;
    codec->write(options.value(), written);
    ByteReader reader(written.bytes().data(), written.size());
    auto read = codec->read(reader);
    ASSERT_TRUE(read.ok()) << read.status().message();
    ByteWriter again;
    codec->write(read.value(), again);
    EXPECT_EQ(again.bytes(), written.bytes());
    EXPECT_FALSE(codec->describe(options.value()).empty());
    EXPECT_FALSE(codec->settings(options.value()).empty());
  }
  EXPECT_EQ(findCodec(0), nullptr);
  EXPECT_EQ(findCodec(uint8_t(allCodecs().size() + 1)), nullptr);
  EXPECT_NE(findCodecByName("mpeg").status().message().find("affine-octree"), std::string::npos);
}

// Every codec, in a few settings, through every SimdPath this build and CPU run: the encoders
// write the same payloads and the decoders give the same frames, so files are identical on
// every CPU. (CI also builds without the AVX2 kernels and checks the golden files with it.)
// What one setting writes and decodes on one kernel path.
struct PathOutput {
  std::vector<std::vector<uint8_t>> payloads;
  std::vector<std::vector<float>> frames;
};
using CodeOnPath = std::function<void(const EncodeSettings&, SimdPath, PathOutput&)>;

// Each setting coded by code() on every path this build and CPU run: every path must write and
// decode what the portable one does.
void expectEveryPathAlike(const std::vector<EncodeSettings>& settings, const CodeOnPath& code) {
  const std::vector<SimdPath> paths = availableSimdPaths();
  for (const EncodeSettings& s : settings) {
    SCOPED_TRACE(describeSettings(s));
    std::vector<PathOutput> out(paths.size());
    for (size_t p = 0; p < paths.size(); ++p) {
      code(s, paths[p], out[p]);
      if (::testing::Test::HasFatalFailure()) return;
    }
    for (size_t p = 1; p < paths.size(); ++p) {
      EXPECT_EQ(out[0].payloads, out[p].payloads) << "path " << int(paths[p]);
      EXPECT_EQ(out[0].frames, out[p].frames) << "path " << int(paths[p]);
    }
  }
}

// Decodes payload with decoder into a new frame of out, after the payload itself.
void decodeInto(FrameDecoder& decoder, const std::vector<uint8_t>& payload, PathOutput& out) {
  out.payloads.push_back(payload);
  out.frames.emplace_back();
  ASSERT_TRUE(decoder.decodeFrame(ByteReader(payload.data(), payload.size()), out.frames.back(), nullptr).ok());
}

TEST(CodecRegistry, EverySimdPathWritesAndDecodesTheSameBytes) {
  if (availableSimdPaths().size() < 2) GTEST_SKIP() << "not run: this build or CPU has one kernel path only";
  std::vector<EncodeSettings> settings(5);
  settings[0].octree().profile = Profile::kPaper;
  settings[1].octree().profile = Profile::kPredictive;
  settings[2].wavelet().step = 1e-3;
  settings[3].wavelet().progressive_p_frames = true;
  settings[4].wavelet().local_frames = true;
  const MemorySequence seq = testing_support::gridSequence(14, 11, 12, 1.0, 0.5);
  expectEveryPathAlike(settings, [&](const EncodeSettings& s, SimdPath path, PathOutput& out) {
    auto encoder = s.entry().makeEncoder(s.options, seq.topology(), path);
    auto decoder = s.entry().makeDecoder(s.options, seq.topology(), {}, "grid", path);
    ASSERT_TRUE(decoder.ok()) << decoder.status().message();
    for (size_t f = 0; f < seq.frames().size(); ++f) {
      FrameCodingStats stats;
      std::vector<uint8_t> payload;
      encoder->encodeFrame(seq.frames()[f].data(), f % 5 == 0, payload, stats);
      ASSERT_NO_FATAL_FAILURE(decodeInto(*decoder.value(), payload, out));
    }
  });
}

// The same for the codecs that code whole groups, on a grid of 21 x 7 vertices (147: the
// trajectory kernel's 16-lane steps, then a step of 3 vertices) in groups of 8 frames.
TEST(CodecRegistry, EverySimdPathWritesAndDecodesTheSameGroups) {
  if (availableSimdPaths().size() < 2) GTEST_SKIP() << "not run: this build or CPU has one kernel path only";
  std::vector<EncodeSettings> settings(3);
  settings[0].trajectory();
  settings[1].trajectory().rate_value = 0.05;  // a KG target of 0.05 %: more components
  settings[2].automatic();
  const MemorySequence seq = testing_support::gridSequence(21, 7, 20, 1.0, 0.5);
  std::vector<float> all;
  for (const auto& frame : seq.frames()) all.insert(all.end(), frame.begin(), frame.end());
  const uint32_t frame_count = uint32_t(seq.frames().size());
  expectEveryPathAlike(settings, [&](const EncodeSettings& s, SimdPath path, PathOutput& out) {
    auto encoder = s.entry().makeGroupEncoder(s.options, seq.topology(), path);
    auto decoder = s.entry().makeDecoder(s.options, seq.topology(), {}, "grid", path);
    ASSERT_TRUE(decoder.ok()) << decoder.status().message();
    const size_t size = 3 * size_t(seq.topology().vertex_count);
    for (uint32_t first = 0; first < frame_count; first += 8) {
      std::vector<std::vector<uint8_t>> group;
      encoder->encodeGroup(all.data() + first * size, std::min<uint32_t>(8, frame_count - first), group);
      for (const auto& payload : group) ASSERT_NO_FATAL_FAILURE(decodeInto(*decoder.value(), payload, out));
    }
    ASSERT_EQ(out.frames.size(), frame_count);
  });
}

// ctest runs this a second time with ANIMC_SIMD=portable (simd_portable_forced in
// tests/CMakeLists.txt): the fuzzers' way to reach the portable kernels in an AVX2 build.
// ANIMC_SIMD=avx2 keeps a CPU with AVX-512 on the AVX2 kernels.
TEST(SimdPathChoice, AnimcSimdSelectsTheKernelsAsked) {
  const char* forced = std::getenv("ANIMC_SIMD");
  if (forced != nullptr && std::string(forced) == "portable") {
    EXPECT_EQ(bestSimdPath(), SimdPath::kPortable);
    return;
  }
#if ANIMC_AVX2_PATH
  EXPECT_EQ(bestSimdPath() != SimdPath::kPortable, kCpuHasAvx2);
  const bool avx2_asked = forced != nullptr && std::string(forced) == "avx2";
  EXPECT_EQ(bestSimdPath() == SimdPath::kAvx512, kCpuHasAvx512 && !avx2_asked);
#else
  EXPECT_EQ(bestSimdPath(), SimdPath::kPortable);
#endif
}

// A codec whose decoder refuses everything: the encoder's own output can then not be decoded,
// which only a bug would cause. A frame-by-frame codec coding groups reports it and goes on.
class RefusingDecoder final : public FrameDecoder {
 public:
  Status decodeFrame(ByteReader, std::vector<float>&, bool*) override { return corrupt("refused"); }
};

TEST(FrameGroupEncoder, ReportsAPayloadItsDecoderRefusesWithoutCrashing) {
  CodecEntry refusing = *findCodec(uint8_t(CodecId::kAffineOctree));
  refusing.makeDecoder = [](const CodecOptions&, const Topology&, const DecoderOptions&, const std::string&,
                            SimdPath) -> Result<std::unique_ptr<FrameDecoder>> {
    return std::unique_ptr<FrameDecoder>(std::make_unique<RefusingDecoder>());
  };
  const MemorySequence sequence = testing_support::gridSequence(6, 5, 3, 0.1, 0.2);
  auto encoder = makeFrameGroupEncoder(refusing, AffineOctreeOptions(), sequence.topology(), SimdPath::kPortable);
  std::vector<float> frames;
  for (const auto& f : sequence.frames()) frames.insert(frames.end(), f.begin(), f.end());
  std::vector<std::vector<uint8_t>> payloads;
  encoder->encodeGroup(frames.data(), 3, payloads);
  ASSERT_EQ(payloads.size(), 3u);
  std::vector<float> xyz(frames.size() / 3);
  EXPECT_FALSE(encoder->reconstruction(0, xyz.data()));
  EXPECT_FALSE(encoder->reconstruction(2, xyz.data()));
  // The same encoder with the codec's own decoder reconstructs the frames.
  auto working = makeFrameGroupEncoder(*findCodec(uint8_t(CodecId::kAffineOctree)), AffineOctreeOptions(),
                                       sequence.topology(), SimdPath::kPortable);
  working->encodeGroup(frames.data(), 3, payloads);
  EXPECT_TRUE(working->reconstruction(2, xyz.data()));
}

}  // namespace
}  // namespace animc
