// SPDX-License-Identifier: Apache-2.0
// The wavelet codec end to end on real data, through the library's API and .ams files:
// round trips at several rates, rate-distortion and progressive-decoding monotonicity,
// truncated streams, P-frame drift, random access.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "codec_test_support.h"
#include "metrics/sequence_metrics.h"
#include "test_sequences.h"
#include "wavelet_test_support.h"

namespace animc {
namespace {

using testing_support::decodeAll;
using testing_support::decodedMetrics;
using testing_support::expectSeeksMatch;
using testing_support::kgError;
using testing_support::realSequence;
using testing_support::tempPath;

const char* const kSequences[] = {"chickenCrossing", "oa_angelyss_lower", "oa_gargoyle_upper", "sydney_md2"};

// One test per real sequence, so that one the data folders lack is listed as not run.
class WaveletOnSequence : public ::testing::TestWithParam<const char*> {};
class WaveletProgressiveOnSequence : public ::testing::TestWithParam<const char*> {};

EncodeSettings waveletSettings(double step, double bits_per_vertex, bool p_frames = true) {
  EncodeSettings s;
  s.options = WaveletOptions();
  s.wavelet().step = step;
  s.wavelet().bits_per_vertex = bits_per_vertex;
  s.wavelet().temporal_prediction = p_frames;
  return s;
}

bool allFinite(const std::vector<std::vector<float>>& frames) {
  for (const auto& f : frames)
    for (float v : f)
      if (!std::isfinite(v)) return false;
  return true;
}

struct Encoded {
  EncodeSummary report;
  std::vector<std::vector<float>> encoder_view;  // what the encoder says the decoder will produce
};

Encoded encodeTo(MemorySequence& seq, const EncodeSettings& settings, const std::string& path) {
  Encoded e;
  seq.rewind();
  const size_t floats = 3 * size_t(seq.topology().vertex_count);
  auto observe = [&](int64_t, const float*, const float* recon) { e.encoder_view.emplace_back(recon, recon + floats); };
  auto report = encodeSequence(seq, settings, path, {}, observe);
  EXPECT_TRUE(report.ok()) << report.status().message();
  if (report.ok()) e.report = report.value();
  return e;
}

// Every shared sequence, quality mode and fixed rate: the file decodes to exactly what the
// encoder predicted (closed loop), the error is small in quality mode and each frame keeps
// to its budget in fixed-rate mode.
TEST_P(WaveletOnSequence, RoundTripsAtSeveralRates) {
  const char* name = GetParam();
  ANIMC_REQUIRE_SEQUENCE(name);
  {
    MemorySequence seq = realSequence(name, 60);
    const uint32_t n = seq.topology().vertex_count;
    struct Rate { double step, bpv, max_kg; };
    for (const Rate rate : {Rate{1e-3, 0, 1.0}, Rate{1e-4, 0, 0.1}, Rate{1e-4, 2, 1e9}, Rate{1e-4, 8, 1e9}}) {
      SCOPED_TRACE(std::string(name) + " step " + std::to_string(rate.step) + " bpv " + std::to_string(rate.bpv));
      const std::string path = tempPath("wavelet_rt.ams");
      const Encoded e = encodeTo(seq, waveletSettings(rate.step, rate.bpv), path);
      const auto decoded = decodeAll(path);
      ASSERT_EQ(decoded.size(), seq.frames().size());
      EXPECT_EQ(decoded, e.encoder_view);
      EXPECT_TRUE(allFinite(decoded));
      EXPECT_LT(kgError(seq, decoded), rate.max_kg);
      if (rate.bpv > 0) {
        // Detail frames stop at the budget; the container adds a length varint per frame.
        const double budget = double(e.report.static_bytes) + (seq.frames().size() - 1) * (rate.bpv * n / 8 + 4);
        EXPECT_LE(double(e.report.bytes), budget + 40);
      }
      std::remove(path.c_str());
    }
  }
}

// More bits, less error: over fixed rates and over quality steps, on every shared sequence.
TEST_P(WaveletOnSequence, ErrorFallsAsTheRateRises) {
  const char* name = GetParam();
  ANIMC_REQUIRE_SEQUENCE(name);
  {
    MemorySequence seq = realSequence(name, 40);
    double previous_kg = INFINITY;
    uint64_t previous_bytes = 0;
    for (double bpv : {1.0, 2.0, 4.0, 8.0, 16.0}) {
      const std::string path = tempPath("wavelet_rate.ams");
      const Encoded e = encodeTo(seq, waveletSettings(1e-5, bpv), path);
      const double kg = kgError(seq, decodeAll(path));
      EXPECT_LT(kg, previous_kg) << name << " at " << bpv << " bpv";
      EXPECT_GT(e.report.bytes, previous_bytes) << name << " at " << bpv << " bpv";
      previous_kg = kg;
      previous_bytes = e.report.bytes;
      std::remove(path.c_str());
    }
    previous_kg = INFINITY;
    for (double step : {1e-2, 3e-3, 1e-3, 3e-4}) {
      const std::string path = tempPath("wavelet_step.ams");
      encodeTo(seq, waveletSettings(step, 0), path);
      const double kg = kgError(seq, decodeAll(path));
      EXPECT_LT(kg, previous_kg) << name << " at step " << step;
      previous_kg = kg;
      std::remove(path.c_str());
    }
  }
}

// I-frames only: each frame decodes on its own, so decoding more bitplanes or more bytes of
// every frame can only bring the sequence closer to the original.
TEST_P(WaveletProgressiveOnSequence, ErrorFallsAsMoreOfTheStreamIsDecoded) {
  const char* name = GetParam();
  ANIMC_REQUIRE_SEQUENCE(name);
  {
    MemorySequence seq = realSequence(name, 30);
    const std::string path = tempPath("wavelet_progressive.ams");
    encodeTo(seq, waveletSettings(1e-4, 0, false), path);
    const double full_kg = kgError(seq, decodeAll(path));
    double previous_kg = INFINITY;
    for (int planes : {2, 4, 6, 8, 10, 12, 14}) {
      WaveletDecodeControl c;
      c.max_bitplanes = planes;
      const auto decoded = decodeAll(path, c);
      ASSERT_EQ(decoded.size(), seq.frames().size());
      const double kg = kgError(seq, decoded);
      EXPECT_LT(kg, previous_kg) << name << ", " << planes << " bitplanes";
      EXPECT_GE(kg, full_kg) << name << ", " << planes << " bitplanes";
      previous_kg = kg;
    }
    previous_kg = INFINITY;
    for (uint64_t bytes : {40, 100, 300, 1000, 3000}) {
      WaveletDecodeControl c;
      c.max_payload_bytes = bytes;
      const double kg = kgError(seq, decodeAll(path, c));
      EXPECT_LE(kg, previous_kg) << name << ", " << bytes << " bytes per frame";
      EXPECT_GE(kg, full_kg) << name << ", " << bytes << " bytes per frame";
      previous_kg = kg;
    }
    std::remove(path.c_str());
  }
}

std::string sequenceName(const ::testing::TestParamInfo<const char*>& info) { return info.param; }

INSTANTIATE_TEST_SUITE_P(Real, WaveletOnSequence, ::testing::ValuesIn(kSequences), sequenceName);
INSTANTIATE_TEST_SUITE_P(Real, WaveletProgressiveOnSequence, ::testing::Values("chickenCrossing", "sydney_md2"),
                         sequenceName);

// A stream cut very short (one bitplane, a few bytes per frame), with intra frames every 10
// frames, still decodes to the right number of finite frames.
TEST(WaveletSequence, ATruncatedStreamDecodesToACoarserValidSequence) {
  ANIMC_REQUIRE_SEQUENCE("chickenCrossing");
  MemorySequence seq = realSequence("chickenCrossing", 40);
  const std::string path = tempPath("wavelet_cut.ams");
  EncodeSettings settings = waveletSettings(1e-4, 0, false);
  settings.iframe_interval = 10;
  encodeTo(seq, settings, path);
  const double full_kg = kgError(seq, decodeAll(path));
  for (const WaveletDecodeControl c : {WaveletDecodeControl{1, 0}, WaveletDecodeControl{0, 2},
                                        WaveletDecodeControl{0, 60}, WaveletDecodeControl{3, 200}}) {
    SCOPED_TRACE("planes " + std::to_string(c.max_bitplanes) + ", bytes " + std::to_string(c.max_payload_bytes));
    const auto decoded = decodeAll(path, c);
    ASSERT_EQ(decoded.size(), seq.frames().size());
    EXPECT_TRUE(allFinite(decoded));
    EXPECT_GT(kgError(seq, decoded), full_kg);
  }
  std::remove(path.c_str());
}

// A P-frame decoded from part of its payload would corrupt the rest of its group when its
// contexts come from the previous frame: such files (the default) are refused progressive
// decoding, with a message that says how to encode for it.
TEST(WaveletSequence, ProgressiveDecodingOfPFramesIsRefused) {
  ANIMC_REQUIRE_SEQUENCE("sydney_md2");
  MemorySequence seq = realSequence("sydney_md2", 5);
  const std::string path = tempPath("wavelet_p_progressive.ams");
  encodeTo(seq, waveletSettings(1e-3, 0, true), path);
  for (const WaveletDecodeControl c : {WaveletDecodeControl{2, 0}, WaveletDecodeControl{0, 100}}) {
    auto ams = AmsSource::open(path, DecoderLimits(), c);
    ASSERT_FALSE(ams.ok());
    EXPECT_NE(ams.status().message().find("--progressive-p-frames"), std::string::npos) << ams.status().message();
  }
  EXPECT_TRUE(AmsSource::open(path).ok());
  std::remove(path.c_str());
}

// Progressive P-frames decode whole exactly as the encoder predicted, and cut to a coarser,
// valid sequence: the less is cut the smaller the error. The drift of cut frames stops at
// each parametric frame, which is never cut and refers to nothing before it.
TEST(WaveletSequence, ProgressivePFramesDecodeCutAndDriftStopsAtParametricFrames) {
  ANIMC_REQUIRE_SEQUENCE("chickenCrossing");
  MemorySequence seq = realSequence("chickenCrossing", 40);
  const std::string path = tempPath("wavelet_progressive_p.ams");
  EncodeSettings settings = waveletSettings(1e-4, 0, true);
  settings.wavelet().progressive_p_frames = true;
  settings.iframe_interval = 10;
  const Encoded e = encodeTo(seq, settings, path);
  EXPECT_EQ(e.report.intra_frames, 4u);
  const auto full = decodeAll(path);
  ASSERT_EQ(full.size(), 40u);
  EXPECT_EQ(full, e.encoder_view);
  const double full_kg = kgError(seq, full);
  double previous_kg = INFINITY;
  for (int planes : {2, 4, 6, 8, 10}) {  // these frames have up to 12
    SCOPED_TRACE(std::to_string(planes) + " bitplanes");
    WaveletDecodeControl c;
    c.max_bitplanes = planes;
    const auto decoded = decodeAll(path, c);
    ASSERT_EQ(decoded.size(), 40u);
    EXPECT_TRUE(allFinite(decoded));
    const double kg = kgError(seq, decoded);
    EXPECT_LT(kg, previous_kg);
    EXPECT_GT(kg, full_kg);
    previous_kg = kg;
    for (size_t f : {10, 20, 30}) EXPECT_EQ(decoded[f], full[f]) << "parametric frame " << f;
    EXPECT_NE(decoded[19], full[19]) << "the P-frame before a parametric frame was not cut";
  }
  const auto cut_bytes = decodeAll(path, WaveletDecodeControl{0, 60});
  ASSERT_EQ(cut_bytes.size(), 40u);
  EXPECT_TRUE(allFinite(cut_bytes));
  EXPECT_GT(kgError(seq, cut_bytes), full_kg);
  std::remove(path.c_str());
}

// Closed-loop P-frames over all 400 frames of chickenCrossing: the error of late frames is
// no larger than that of early ones, whatever the motion did in between.
TEST(WaveletSequence, PFrameDriftStaysBoundedOverChickenCrossing) {
  ANIMC_REQUIRE_SEQUENCE("chickenCrossing");
  MemorySequence seq = realSequence("chickenCrossing", 0);
  ASSERT_EQ(seq.frames().size(), 400u);
  const std::string path = tempPath("wavelet_drift.ams");
  const Encoded e = encodeTo(seq, waveletSettings(1e-3, 0), path);
  EXPECT_EQ(e.report.intra_frames, 1u);
  const auto decoded = decodeAll(path);
  ASSERT_EQ(decoded.size(), 400u);
  const SequenceMetrics metrics = decodedMetrics(seq, decoded);
  auto meanRms = [&](size_t first, size_t last) {
    double sum = 0;
    for (size_t f = first; f < last; ++f) sum += metrics.per_frame[f].rms;
    return sum / double(last - first);
  };
  const double early = meanRms(1, 101), late = meanRms(300, 400);
  EXPECT_GT(early, 0);
  EXPECT_LT(late, 1.5 * early);
  // Quantisation at step 1e-3 of the diagonal: no frame may stray far beyond it.
  const double step = 1e-3 * testing_support::bboxDiagonal(seq.frames()[0]);
  for (size_t f = 0; f < decoded.size(); ++f) EXPECT_LT(metrics.per_frame[f].rms, 3 * step) << "frame " << f;
  std::remove(path.c_str());
}

// With intra frames every K frames, decoding frame k alone gives frame k of a full decode.
TEST(WaveletSequence, RandomAccessMatchesAFullDecode) {
  ANIMC_REQUIRE_SEQUENCE("sydney_md2");
  MemorySequence seq = realSequence("sydney_md2", 30);
  const std::string path = tempPath("wavelet_seek.ams");
  EncodeSettings settings = waveletSettings(3e-4, 0);
  settings.iframe_interval = 8;
  const Encoded e = encodeTo(seq, settings, path);
  EXPECT_EQ(e.report.intra_frames, 4u);
  const auto full = decodeAll(path);
  auto ams = AmsSource::open(path);
  ASSERT_TRUE(ams.ok()) << ams.status().message();
  ASSERT_NO_FATAL_FAILURE(expectSeeksMatch(*ams.value(), full, {29, 0, 8, 13, 17, 24}));
  std::remove(path.c_str());
}

// Progressive decoding is a wavelet feature: asking it of an Affine-Octree file is an error.
TEST(WaveletSequence, ProgressiveDecodingOfAnotherCodecIsRefused) {
  ANIMC_REQUIRE_SEQUENCE("sydney_md2");
  MemorySequence seq = realSequence("sydney_md2", 3);
  const std::string path = tempPath("octree_progressive.ams");
  seq.rewind();
  ASSERT_TRUE(encodeSequence(seq, EncodeSettings(), path).ok());
  WaveletDecodeControl c;
  c.max_bitplanes = 2;
  auto ams = AmsSource::open(path, DecoderLimits(), c);
  ASSERT_FALSE(ams.ok());
  EXPECT_NE(ams.status().message().find("wavelet"), std::string::npos);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace animc
