// SPDX-License-Identifier: Apache-2.0
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "codec_test_support.h"
#include "core/memory_sequence.h"
#include "metrics/compare_sequences.h"
#include "metrics/sequence_metrics.h"
#include "report/encode_metrics.h"
#include "report/json_writer.h"
#include "report/report.h"
#include "test_sequences.h"

namespace animc {
namespace {

using Frame = std::vector<float>;
constexpr double kInf = std::numeric_limits<double>::infinity();

SequenceMetrics measure(uint32_t n, const std::vector<Frame>& original,
                        const std::vector<Frame>& reconstructed) {
  MetricsAccumulator acc(n);
  for (size_t f = 0; f < original.size(); ++f) {
    acc.addFrame(original[f].data(), reconstructed[f].data());
  }
  return acc.finish();
}

// A deterministic, non-degenerate wobbling shape (no RNG so failures reproduce anywhere).
std::vector<Frame> wobble(uint32_t n, int frames, double phase) {
  std::vector<Frame> seq(frames, Frame(3 * n));
  for (int f = 0; f < frames; ++f) {
    for (uint32_t v = 0; v < n; ++v) {
      const double t = v * 0.7 + f * 0.3 + phase;
      seq[f][3 * v + 0] = static_cast<float>(std::sin(t) * 2 + v * 0.1);
      seq[f][3 * v + 1] = static_cast<float>(std::cos(1.3 * t) + f * 0.05);
      seq[f][3 * v + 2] = static_cast<float>(std::sin(0.5 * t) * 3);
    }
  }
  return seq;
}

TEST(MetricsAccumulator, ExactReconstructionIsPerfect) {
  const std::vector<Frame> seq = wobble(20, 5, 0.0);
  const SequenceMetrics m = measure(20, seq, seq);
  EXPECT_EQ(m.frames, 5);
  EXPECT_EQ(m.vertices, 20u);
  EXPECT_EQ(m.kg_error, 0.0);
  EXPECT_EQ(m.psnr, kInf);
  EXPECT_EQ(m.max_error, 0.0);
  EXPECT_EQ(m.max_error_rel_diag, 0.0);
  EXPECT_EQ(m.max_error_rel_cube, 0.0);
  EXPECT_EQ(m.rms_error, 0.0);
  EXPECT_EQ(m.rms_error_rel_diag, 0.0);
  EXPECT_GT(m.bbox_diagonal, 0.0);
  ASSERT_EQ(m.per_frame.size(), 5u);
  for (const FrameError& f : m.per_frame) {
    EXPECT_EQ(f.rms, 0.0);
    EXPECT_EQ(f.max, 0.0);
  }
}

// 2 frames, 3 vertices, every figure worked out by hand.
// Frame 0: (0,0,0) (4,0,0) (0,2,0): largest bbox side 4.
// Frame 1: (0,0,0) (2,0,0) (0,2,0): largest side 2, but S_1 = max(2, 4) = 4.
// Errors: frame 0 moves vertex 0 by (0.75, 1, 0) -> 1.25; frame 1 moves vertex 2 by
// (0, 0, 1.5) -> 1.5. Sequence bbox [0,4]x[0,2]x[0,0]: dmax = sqrt(20).
TEST(MetricsAccumulator, HandComputedTinyCase) {
  const std::vector<Frame> original = {{0, 0, 0, 4, 0, 0, 0, 2, 0}, {0, 0, 0, 2, 0, 0, 0, 2, 0}};
  const std::vector<Frame> decoded = {{0.75f, 1, 0, 4, 0, 0, 0, 2, 0},
                                      {0, 0, 0, 2, 0, 0, 0, 2, 1.5f}};
  const SequenceMetrics m = measure(3, original, decoded);

  const double sum_sq_error = 1.25 * 1.25 + 1.5 * 1.5;  // 3.8125
  const double mse = sum_sq_error / 6;
  const double dmax = std::sqrt(20.0);
  // Centred sums: frame 0 x {0,4,0} -> 32/3, y {0,0,2} -> 8/3; frame 1 x and y -> 8/3 each.
  const double sum_sq_centred = 40.0 / 3 + 16.0 / 3;

  EXPECT_EQ(m.frames, 2);
  EXPECT_EQ(m.vertices, 3u);
  EXPECT_NEAR(m.bbox_diagonal, dmax, 1e-12);
  EXPECT_NEAR(m.kg_error, 100 * std::sqrt(sum_sq_error / sum_sq_centred), 1e-9);
  EXPECT_NEAR(m.kg_error, 45.19304, 1e-4);
  EXPECT_NEAR(m.psnr, 10 * std::log10(20.0 / mse), 1e-9);
  EXPECT_NEAR(m.psnr, 14.97968, 1e-4);
  EXPECT_NEAR(m.max_error, 1.5, 1e-12);
  EXPECT_NEAR(m.max_error_rel_diag, 1.5 / dmax, 1e-12);
  // 1.5 / 4 uses frame 0's side; frame 1's own side would give 0.75.
  EXPECT_NEAR(m.max_error_rel_cube, 0.375, 1e-12);
  EXPECT_NEAR(m.rms_error, std::sqrt(mse), 1e-12);
  EXPECT_NEAR(m.rms_error_rel_diag, std::sqrt(mse) / dmax, 1e-12);
  ASSERT_EQ(m.per_frame.size(), 2u);
  EXPECT_NEAR(m.per_frame[0].max, 1.25, 1e-12);
  EXPECT_NEAR(m.per_frame[0].rms, std::sqrt(1.5625 / 3), 1e-12);
  EXPECT_NEAR(m.per_frame[1].max, 1.5, 1e-12);
  EXPECT_NEAR(m.per_frame[1].rms, std::sqrt(2.25 / 3), 1e-12);
}

// The side of frame f-1 only counts for frame f: a big frame 0 must not rescue frame 2.
TEST(MetricsAccumulator, CubeScaleLooksBackOneFrameOnly) {
  const std::vector<Frame> original = {
      {0, 0, 0, 8, 0, 0}, {0, 0, 0, 2, 0, 0}, {0, 0, 0, 1, 0, 0}};
  const std::vector<Frame> decoded = {
      {0, 0, 0, 8, 0, 0}, {0, 0, 0, 2, 0, 0}, {0, 0.5f, 0, 1, 0, 0}};
  const SequenceMetrics m = measure(2, original, decoded);
  EXPECT_NEAR(m.max_error_rel_cube, 0.5 / 2, 1e-12);  // S_2 = max(1, 2), not 8
}

TEST(MetricsAccumulator, TranslationErrorEqualsOffset) {
  const double d[3] = {0.3, -0.4, 1.2};  // |d| = 1.3
  const std::vector<Frame> original = wobble(50, 4, 0.5);
  std::vector<Frame> moved = original;
  for (Frame& frame : moved) {
    for (size_t i = 0; i < frame.size(); ++i) frame[i] = static_cast<float>(frame[i] + d[i % 3]);
  }
  const SequenceMetrics m = measure(50, original, moved);
  EXPECT_NEAR(m.max_error, 1.3, 1e-5);
  EXPECT_NEAR(m.rms_error, 1.3, 1e-5);
  for (const FrameError& f : m.per_frame) {
    EXPECT_NEAR(f.rms, 1.3, 1e-5);
    EXPECT_NEAR(f.max, 1.3, 1e-5);
  }
  EXPECT_NEAR(m.max_error_rel_diag, 1.3 / m.bbox_diagonal, 1e-5);
  EXPECT_NEAR(m.psnr, 10 * std::log10(m.bbox_diagonal * m.bbox_diagonal / (1.3 * 1.3)), 1e-4);
}

TEST(MetricsAccumulator, KgErrorIsScaleInvariant) {
  const std::vector<Frame> original = wobble(30, 6, 0.0);
  const std::vector<Frame> decoded = wobble(30, 6, 0.01);
  auto scaled = [](std::vector<Frame> seq, float s) {
    for (Frame& frame : seq) {
      for (float& x : frame) x *= s;
    }
    return seq;
  };
  const SequenceMetrics base = measure(30, original, decoded);
  const SequenceMetrics big = measure(30, scaled(original, 3.5f), scaled(decoded, 3.5f));
  ASSERT_GT(base.kg_error, 0.0);
  EXPECT_NEAR(big.kg_error, base.kg_error, 1e-5 * base.kg_error);
  EXPECT_NEAR(big.psnr, base.psnr, 1e-4);  // PSNR is relative to dmax, so invariant too
  EXPECT_NEAR(big.max_error_rel_cube, base.max_error_rel_cube, 1e-5 * base.max_error_rel_cube);
  EXPECT_NEAR(big.max_error, 3.5 * base.max_error, 1e-5 * big.max_error);
}

TEST(MetricsAccumulator, FinishIsASnapshot) {
  const std::vector<Frame> original = wobble(10, 3, 0.0);
  const std::vector<Frame> decoded = wobble(10, 3, 0.02);
  MetricsAccumulator acc(10);
  acc.addFrame(original[0].data(), decoded[0].data());
  const SequenceMetrics first = acc.finish();
  EXPECT_EQ(first.frames, 1);
  acc.addFrame(original[1].data(), decoded[1].data());
  acc.addFrame(original[2].data(), decoded[2].data());
  const SequenceMetrics all = acc.finish();
  EXPECT_EQ(all.frames, 3);
  EXPECT_EQ(all.per_frame.size(), 3u);
  EXPECT_EQ(acc.finish().kg_error, all.kg_error);
}

// An encode keeps no per-frame record (PerFrameErrors::kDrop): its memory must not grow with
// the frame count (a 625 KB .pc2.xz of 33 M frames once took 537 MB), and the totals are the
// same as with the records.
TEST(MetricsAccumulator, DroppingPerFrameErrorsKeepsTheTotals) {
  const std::vector<Frame> original = wobble(10, 200, 0.0);
  const std::vector<Frame> decoded = wobble(10, 200, 0.02);
  MetricsAccumulator kept(10), dropped(10, PerFrameErrors::kDrop);
  for (size_t f = 0; f < original.size(); ++f) {
    kept.addFrame(original[f].data(), decoded[f].data());
    dropped.addFrame(original[f].data(), decoded[f].data());
  }
  const SequenceMetrics a = kept.finish(), b = dropped.finish();
  EXPECT_EQ(a.per_frame.size(), 200u);
  EXPECT_TRUE(b.per_frame.empty());
  EXPECT_EQ(b.frames, 200);
  EXPECT_EQ(a.kg_error, b.kg_error);
  EXPECT_EQ(a.psnr, b.psnr);
  EXPECT_EQ(a.max_error, b.max_error);
  EXPECT_EQ(a.max_error_rel_cube, b.max_error_rel_cube);
  EXPECT_EQ(a.rms_error, b.rms_error);
}

TEST(MetricsAccumulator, EmptyAndDegenerateSequences) {
  const SequenceMetrics empty = MetricsAccumulator(7).finish();
  EXPECT_EQ(empty.frames, 0);
  EXPECT_EQ(empty.psnr, kInf);
  EXPECT_EQ(empty.kg_error, 0.0);
  EXPECT_EQ(empty.bbox_diagonal, 0.0);

  // A single point that never moves: every scale is 0.
  const std::vector<Frame> point = {{1, 2, 3}, {1, 2, 3}};
  const SequenceMetrics exact = measure(1, point, point);
  EXPECT_EQ(exact.kg_error, 0.0);
  EXPECT_EQ(exact.max_error_rel_cube, 0.0);
  EXPECT_EQ(exact.max_error_rel_diag, 0.0);
  EXPECT_EQ(exact.psnr, kInf);
  const std::vector<Frame> off = {{1, 2, 3}, {1, 2, 4}};
  const SequenceMetrics wrong = measure(1, point, off);
  EXPECT_EQ(wrong.kg_error, kInf);
  EXPECT_EQ(wrong.max_error_rel_cube, kInf);
  EXPECT_EQ(wrong.psnr, -kInf);
  EXPECT_NEAR(wrong.max_error, 1.0, 1e-12);
}

TEST(MetricsAccumulator, NaNInReconstructionIsNotHidden) {
  const std::vector<Frame> original = {{0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}};
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<Frame> decoded = {{0, 0, nan, 1, 1, 1}, {0, 0, 0, 1, 1, 2}};
  const SequenceMetrics m = measure(2, original, decoded);
  EXPECT_TRUE(std::isnan(m.max_error));
  EXPECT_TRUE(std::isnan(m.max_error_rel_cube));
  EXPECT_TRUE(std::isnan(m.kg_error));
  EXPECT_TRUE(std::isnan(m.psnr));
}

// A mesh far from the origin: the KG denominator must not cancel away. Coordinates are
// multiples of 0.5, so shifting by 2^20 is exact in float and the figures must not change.
TEST(MetricsAccumulator, KgDenominatorStableFarFromOrigin) {
  std::vector<Frame> original = {{0, 0, 0, 1, 0.5f, 0, 2, 1, 0.5f, 0.5f, 1.5f, 1},
                                 {0.5f, 0, 0, 1, 1, 0, 2.5f, 1, 0.5f, 0.5f, 2, 1}};
  std::vector<Frame> decoded = original;
  decoded[0][4] += 0.5f;
  decoded[1][9] -= 0.5f;
  const SequenceMetrics base = measure(4, original, decoded);
  for (auto* seq : {&original, &decoded}) {
    for (Frame& frame : *seq) {
      for (float& x : frame) x += 1048576.0f;
    }
  }
  const SequenceMetrics far = measure(4, original, decoded);
  ASSERT_GT(base.kg_error, 0.0);
  EXPECT_NEAR(far.kg_error, base.kg_error, 1e-9 * base.kg_error);
  EXPECT_NEAR(far.psnr, base.psnr, 1e-9);
}

// A sequence of n-vertex frames (the topology is not looked at by the metrics).
MemorySequence memorySequence(uint32_t n, std::vector<Frame> frames, const std::string& name) {
  Topology t;
  t.vertex_count = n;
  return MemorySequence(t, std::move(frames), 25.0, name);
}

TEST(CompareSequences, SameFiguresAsTheAccumulator) {
  const std::vector<Frame> original = wobble(20, 6, 0.0), decoded = wobble(20, 6, 0.01);
  MemorySequence a = memorySequence(20, original, "a"), b = memorySequence(20, decoded, "b");
  std::vector<int> percents;
  auto m = compareSequences(a, b, [&](int percent, const char*) { percents.push_back(percent); return true; });
  ASSERT_TRUE(m.ok()) << m.status().message();
  const SequenceMetrics expected = measure(20, original, decoded);
  EXPECT_EQ(m.value().frames, 6);
  EXPECT_EQ(m.value().kg_error, expected.kg_error);
  EXPECT_EQ(m.value().max_error, expected.max_error);
  EXPECT_EQ(m.value().per_frame.back().rms, expected.per_frame.back().rms);
  EXPECT_EQ(percents, (std::vector<int>{16, 33, 50, 66, 83, 100}));
}

TEST(CompareSequences, CountsMustAgree) {
  MemorySequence a = memorySequence(20, wobble(20, 3, 0), "a"), b = memorySequence(21, wobble(21, 3, 0), "b");
  auto vertices = compareSequences(a, b);
  EXPECT_EQ(vertices.status().code(), StatusCode::kBadInput);
  EXPECT_EQ(vertices.status().message(), "b frame 0: 21 vertices, the original has 20");
  MemorySequence longer = memorySequence(20, wobble(20, 4, 0), "longer");
  a.rewind();
  EXPECT_EQ(compareSequences(a, longer).status().message(), "the original has fewer frames (3)");
  a.rewind();
  longer.rewind();
  EXPECT_EQ(compareSequences(longer, a).status().message(), "the reconstruction has fewer frames (3)");
}

TEST(CompareSequences, ReadErrorsAndCancellationEndIt) {
  std::vector<Frame> short_frame = wobble(20, 3, 0);
  short_frame[1].resize(30);
  MemorySequence a = memorySequence(20, wobble(20, 3, 0), "a"), bad = memorySequence(20, short_frame, "bad");
  EXPECT_EQ(compareSequences(a, bad).status().message(), "bad frame 1: has 10 vertices, expected 20");
  a.rewind();
  MemorySequence b = memorySequence(20, wobble(20, 3, 0), "b");
  auto stopped = compareSequences(a, b, [](int percent, const char*) { return percent < 50; });
  EXPECT_EQ(stopped.status().code(), StatusCode::kCancelled);
}

// The observer sees each frame as it was given with the frame a decoder will output, in
// order, whether the codec codes frame by frame, in groups, or gathers groups for threads.
TEST(EncodeObserver, SeesEachOriginalWithItsDecodedFrame) {
  MemorySequence original = testing_support::gridSequence(5, 4, 11, 1.0, 1.0);
  std::vector<EncodeSettings> settings(4);
  settings[1].trajectory().group_frames = 4;  // three groups
  settings[2].trajectory().group_frames = 4;
  settings[2].threads = 2;  // two groups coded at once
  settings[3].iframe_interval = 3;
  settings[3].threads = 2;  // frames gathered into groups for the threads
  for (const EncodeSettings& s : settings) {
    const std::string path = testing_support::tempPath("observed.ams");
    std::vector<Frame> given, shown;
    auto keep = [&](int64_t frame, const float* xyz, const float* reconstruction) {
      EXPECT_EQ(frame, int64_t(shown.size()));
      given.emplace_back(xyz, xyz + 3 * 20);
      shown.emplace_back(reconstruction, reconstruction + 3 * 20);
    };
    original.rewind();
    ASSERT_TRUE(encodeSequence(original, s, path, {}, keep).ok()) << s.entry().name;
    std::vector<Frame> frames;
    original.rewind();
    for (Frame xyz; original.next(xyz).value();) frames.push_back(xyz);
    EXPECT_EQ(given, frames) << s.entry().name;
    EXPECT_EQ(shown, testing_support::decodeAll(path)) << s.entry().name;
    std::remove(path.c_str());
  }
}

// The observer sees what a decoder of the file will output, so its figures are those of
// comparing the original with the decoded file.
TEST(MeasuringObserver, MeasuresWhatTheDecoderOutputs) {
  MemorySequence original = testing_support::gridSequence(5, 4, 6, 1.0, 1.0);
  const std::string path = testing_support::tempPath("measured.ams");
  MetricsAccumulator metrics(20);  // the 5 x 4 grid's vertices
  std::vector<Frame> shown;
  auto keep = [&](int64_t frame, const float*, const float* reconstruction) {
    EXPECT_EQ(frame, int64_t(shown.size()));
    shown.emplace_back(reconstruction, reconstruction + 3 * 20);
  };
  ASSERT_TRUE(encodeSequence(original, EncodeSettings(), path, {}, measuringObserver(metrics, keep)).ok());
  ASSERT_EQ(shown.size(), 6u);
  EXPECT_EQ(shown, testing_support::decodeAll(path));
  original.rewind();
  auto ams = AmsSource::open(path);
  ASSERT_TRUE(ams.ok()) << ams.status().message();
  auto compared = compareSequences(original, *ams.value());
  ASSERT_TRUE(compared.ok()) << compared.status().message();
  const SequenceMetrics m = metrics.finish();
  EXPECT_GT(m.max_error, 0.0);
  EXPECT_EQ(m.kg_error, compared.value().kg_error);
  EXPECT_EQ(m.max_error, compared.value().max_error);
  EXPECT_EQ(m.psnr, compared.value().psnr);
  std::remove(path.c_str());
}

TEST(MetricsSizeFigures, Arithmetic) {
  // 1000 vertices x 50 frames = 50000 samples, raw 600000 bytes.
  const SizeFigures s = sizeFigures(30000, 10000, 1000, 50);
  EXPECT_DOUBLE_EQ(s.ratio, 20.0);
  EXPECT_DOUBLE_EQ(s.bpvf, 8.0 * 30000 / 50000);  // 4.8
  EXPECT_DOUBLE_EQ(s.motion_bpvf, 8.0 * 20000 / 50000);  // 3.2

  const SizeFigures empty_file = sizeFigures(0, 0, 1000, 50);
  EXPECT_EQ(empty_file.ratio, kInf);
  EXPECT_EQ(empty_file.bpvf, 0.0);
  EXPECT_EQ(sizeFigures(100, 0, 0, 0).ratio, 0.0);
  EXPECT_EQ(sizeFigures(100, 0, 0, 0).bpvf, kInf);
  // Above 2^32 bytes and frames: no integer overflow.
  const SizeFigures huge = sizeFigures(uint64_t{1} << 40, 0, 4000000000u, 1000000);
  EXPECT_DOUBLE_EQ(huge.ratio, 12.0 * 4e9 * 1e6 / 1099511627776.0);
}

TEST(MetricsFormat, JsonHasEveryKeyAndNullForInf) {
  const std::vector<Frame> seq = {{0, 0, 0, 1, 0, 0}};
  const SequenceMetrics m = measure(2, seq, seq);
  JsonObject o;
  addMetrics(o, m, false);
  EXPECT_EQ(o.str(),
            "{\"frames\":1,\"vertices\":2,\"kg_error\":0,\"psnr\":null,\"max_error\":0,"
            "\"max_error_rel_diag\":0,\"max_error_rel_cube\":0,\"rms_error\":0,"
            "\"rms_error_rel_diag\":0,\"bbox_diagonal\":1}");
}

TEST(MetricsFormat, JsonPerFrameArraysOnlyWhenAsked) {
  const std::vector<Frame> original = {{0, 0, 0}, {0, 0, 0}};
  const std::vector<Frame> decoded = {{0, 0, 0.5f}, {0, 0, 0}};
  const SequenceMetrics m = measure(1, original, decoded);
  JsonObject without_arrays, with_arrays;
  addMetrics(without_arrays, m, false);
  addMetrics(with_arrays, m, true);
  const std::string without = without_arrays.str(), with = with_arrays.str();
  EXPECT_EQ(without.find("per_frame"), std::string::npos);
  EXPECT_NE(with.find(",\"per_frame_rms\":[0.5,0],\"per_frame_max\":[0.5,0]}"),
            std::string::npos)
      << with;
}

TEST(MetricsFormat, TextHasOneLinePerFigure) {
  const std::vector<Frame> original = {{0, 0, 0, 4, 0, 0, 0, 2, 0}, {0, 0, 0, 2, 0, 0, 0, 2, 0}};
  const std::vector<Frame> decoded = {{0.75f, 1, 0, 4, 0, 0, 0, 2, 0},
                                      {0, 0, 0, 2, 0, 0, 0, 2, 1.5f}};
  const std::string text = formatMetricsText(measure(3, original, decoded));
  EXPECT_NE(text.find("frames: 2\n"), std::string::npos) << text;
  EXPECT_NE(text.find("vertices: 3\n"), std::string::npos) << text;
  EXPECT_NE(text.find("kg_error: 45.193 %\n"), std::string::npos) << text;
  EXPECT_NE(text.find("psnr: 14.9797 dB\n"), std::string::npos) << text;
  EXPECT_NE(text.find("max_error: 1.5\n"), std::string::npos) << text;
  EXPECT_NE(text.find("max_error_rel_cube: 0.375\n"), std::string::npos) << text;
  EXPECT_NE(text.find("bbox_diagonal: 4.47214\n"), std::string::npos) << text;
  size_t lines = 0;
  for (char c : text) lines += c == '\n';
  EXPECT_EQ(lines, 10u);
  EXPECT_EQ(text.back(), '\n');

  const std::vector<Frame> seq = {{0, 0, 0, 1, 0, 0}};
  EXPECT_NE(formatMetricsText(measure(2, seq, seq)).find("psnr: inf dB\n"), std::string::npos);
}

TEST(MetricsFormat, EncodeSummaryLinesAndSpeed) {
  EncodeSummary r;
  r.vertices = 1000;
  r.frames = 50;
  r.bytes = 30000;
  r.static_bytes = 10000;
  r.encode_seconds = 0.025;  // 50000 vertex positions: 2 M vertices/s
  EXPECT_DOUBLE_EQ(encodeMvps(r), 2.0);
  const std::vector<Frame> seq = {{0, 0, 0, 1, 0, 0}};
  const SequenceMetrics m = measure(2, seq, seq);
  const EncodeSettings settings;
  const std::string result = describeSettings(settings) + formatSizeText(30000, 10000, 1000, 50);
  EXPECT_EQ(formatEncodeResult(settings, r), result);
  EXPECT_EQ(formatEncodeSummary(settings, r, m, "; note"),
            result + formatMetricsText(m) + "encode time: 0.025 s (2.00 M vertices/s); note\n");

  // No measurable time: no speed either, rather than a huge or infinite one.
  r.encode_seconds = 0;
  EXPECT_EQ(encodeMvps(r), 0.0);
  const std::string summary = formatEncodeSummary(settings, r, m);
  EXPECT_NE(summary.find("\nencode time: 0.000 s (0.00 M vertices/s)\n"), std::string::npos) << summary;
}

TEST(JsonWriter, EscapesQuotesBackslashesAndControls) {
  std::string out;
  appendJsonString(std::string_view("a\"b\\c\n\t\r\b\f\x01\x1f\x7f", 13), out);
  EXPECT_EQ(out, "\"a\\\"b\\\\c\\n\\t\\r\\b\\f\\u0001\\u001f\x7f\"");
  out.clear();
  appendJsonString(std::string_view("nul\0end", 7), out);
  EXPECT_EQ(out, "\"nul\\u0000end\"");
}

TEST(JsonWriter, KeepsValidUtf8AndReplacesInvalidBytes) {
  std::string out;
  appendJsonString("caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80", out);  // é € 😀
  EXPECT_EQ(out, "\"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x98\x80\"");
  out.clear();
  // Lone continuation, truncated sequence, overlong '/', UTF-16 surrogate, latin-1 byte.
  appendJsonString("a\x80 \xe2\x82 \xc0\xaf \xed\xa0\x80 \xe9", out);
  EXPECT_EQ(out,
            "\"a\\ufffd \\ufffd\\ufffd \\ufffd\\ufffd \\ufffd\\ufffd\\ufffd \\ufffd\"");
}

TEST(JsonWriter, NumbersAndNonFinite) {
  std::string out;
  appendJsonNumber(20.5, out);
  out += ' ';
  appendJsonNumber(1.0 / 3.0, out);
  out += ' ';
  appendJsonNumber(1e300, out);
  out += ' ';
  appendJsonNumber(-2.5e-7, out);
  out += ' ';
  appendJsonNumber(kInf, out);
  out += ' ';
  appendJsonNumber(-kInf, out);
  out += ' ';
  appendJsonNumber(std::nan(""), out);
  EXPECT_EQ(out, "20.5 0.3333333333 1e+300 -2.5e-07 null null null");
  EXPECT_EQ(formatDouble(kInf), "inf");
  EXPECT_EQ(formatDouble(-kInf), "-inf");
  EXPECT_EQ(formatDouble(123456.789, 6), "123457");
}

TEST(JsonObject, BuildsFlatObject) {
  JsonObject o;
  EXPECT_TRUE(o.empty());
  EXPECT_EQ(o.str(), "{}");
  const std::string path = "dir/\"odd\".ams";
  o.add("ratio", 20.5)
      .add("codec", "affine-octree")
      .add("ok", true)
      .add("failed", false)
      .add("path", path)
      .add("frames", int64_t{-1})
      .add("bytes", uint64_t{12345678901234567890u})
      .add("count", 7)
      .add("scale", 0.25f)
      .add("psnr", kInf)
      .add("missing", static_cast<const char*>(nullptr))
      .addNull("none")
      .addRaw("metrics", "{\"a\":1}")
      .addRaw("empty_raw", "")
      .add("list", std::vector<double>{1, 2.5, kInf});
  EXPECT_FALSE(o.empty());
  EXPECT_EQ(o.str(),
            "{\"ratio\":20.5,\"codec\":\"affine-octree\",\"ok\":true,\"failed\":false,"
            "\"path\":\"dir/\\\"odd\\\".ams\",\"frames\":-1,\"bytes\":12345678901234567890,"
            "\"count\":7,\"scale\":0.25,\"psnr\":null,\"missing\":null,\"none\":null,"
            "\"metrics\":{\"a\":1},\"empty_raw\":null,\"list\":[1,2.5,null]}");
}

TEST(JsonObject, EscapesKeysAndAppendsWithoutNewline) {
  JsonObject o;
  o.add("we\"ird\nkey", 1);
  std::string out = "[";
  o.appendTo(out);
  out += "]";
  EXPECT_EQ(out, "[{\"we\\\"ird\\nkey\":1}]");
}

}  // namespace
}  // namespace animc
