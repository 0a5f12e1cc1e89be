// SPDX-License-Identifier: Apache-2.0
// Bad input to encodeSequence and openSequence: every case gives a non-ok Status whose message
// names the problem, and (outputs being atomic) leaves nothing behind: no file at the target
// path, no temporary beside it, and an earlier file at the target untouched.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "api.h"
#include "seqio/sequence_io.h"
#include "test_sequences.h"

namespace animc {
namespace {

namespace fs = std::filesystem;
using testing_support::gridFrame;
using testing_support::gridSequence;
using testing_support::gridTopology;

constexpr int kNx = 5, kNy = 4;  // 20 vertices, 24 triangles

class EncodeInput : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / ("animc_encode_input_" + std::string(info->name()) + "_" +
                                             std::to_string(getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "out");
    out_ = (dir_ / "out" / "x.ams").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // Encodes and expects failure with `code` and every one of `words` in the message; the
  // output directory must be left empty.
  void expectRefused(FrameSource& source, const EncodeSettings& settings, StatusCode code,
                     const std::vector<std::string>& words, const ProgressFn& progress = {}) {
    auto report = encodeSequence(source, settings, out_, progress);
    ASSERT_FALSE(report.ok()) << "encoded " << source.where();
    const Status& s = report.status();
    EXPECT_EQ(s.code(), code) << statusCodeName(s.code()) << ": " << s.message();
    for (const std::string& w : words)
      EXPECT_NE(s.message().find(w), std::string::npos) << "'" << w << "' not in: " << s.message();
    expectNoOutput();
  }
  void expectNoOutput() const {
    EXPECT_FALSE(fs::exists(out_)) << "a failed encode left " << out_;
    for (const auto& entry : fs::directory_iterator(dir_ / "out"))
      ADD_FAILURE() << "a failed encode left " << entry.path();
  }

  fs::path dir_;
  std::string out_;
};

MemorySequence withValue(int frame, int vertex, int axis, float value) {
  MemorySequence seq = gridSequence(kNx, kNy, 5, 1.0, 0.5);
  std::vector<std::vector<float>> frames = seq.frames();
  frames[frame][3 * vertex + axis] = value;
  return MemorySequence(seq.topology(), std::move(frames), 25.0, "grid");
}

TEST_F(EncodeInput, NaNCoordinateNamesFrameAndVertex) {
  MemorySequence seq = withValue(3, 7, 1, std::numeric_limits<float>::quiet_NaN());
  expectRefused(seq, {}, StatusCode::kBadInput, {"frame 3", "vertex 7", "NaN"});
}

// The message blames frame 3 only: source.where(), read after next() has moved on, says
// "grid frame 4" and must not be used as the context.
TEST_F(EncodeInput, NaNMessageDoesNotNameTheNextFrame) {
  MemorySequence seq = withValue(3, 7, 1, std::numeric_limits<float>::quiet_NaN());
  const std::string m = encodeSequence(seq, {}, out_).status().message();
  EXPECT_NE(m.find("frame 3"), std::string::npos) << m;
  EXPECT_EQ(m.find("frame 4"), std::string::npos) << m;
}

TEST_F(EncodeInput, InfiniteAndHugeCoordinatesAreRefused) {
  MemorySequence inf = withValue(0, 0, 0, -std::numeric_limits<float>::infinity());
  expectRefused(inf, {}, StatusCode::kBadInput, {"frame 0", "vertex 0", "infinite"});
  MemorySequence huge = withValue(2, 19, 2, 1e31f);
  expectRefused(huge, {}, StatusCode::kBadInput, {"frame 2", "vertex 19", "huge"});
  MemorySequence negative = withValue(4, 11, 0, -1e31f);
  expectRefused(negative, {}, StatusCode::kBadInput, {"frame 4", "vertex 11"});
  // The limit itself is fine.
  MemorySequence edge = withValue(1, 3, 0, 1e30f);
  EXPECT_NE(encodeSequence(edge, {}, out_).status().code(), StatusCode::kBadInput);
}

// A frame of several blocks of coordinates is checked (and gathered) on threads: the first bad
// vertex is still the one named, and a refused frame leaves the encoder as it was.
TEST_F(EncodeInput, ALargeBadFrameOnThreadsNamesItsFirstVertexAndAddsNothing) {
  constexpr int kSide = 300;  // 270 000 coordinates: more than one block
  const Topology mesh = gridTopology(kSide, kSide);
  std::vector<std::vector<float>> frames;
  for (int f = 0; f < 2; ++f) frames.push_back(gridFrame(kSide, kSide, f, 1.0, 0.5));
  EncoderOptions options;
  options.codec = "trajectory";
  options.threads = 2;
  auto encodeWith = [&](bool bad_frame_first, std::vector<uint8_t>& bytes) {
    auto encoder = Encoder::create(options, mesh.vertex_count, mesh.triangles.front().data(), mesh.triangles.size(),
                                   memorySink(&bytes));
    ASSERT_TRUE(encoder.ok()) << encoder.status().message();
    ASSERT_TRUE(encoder.value().addFrame(frames[0].data()).ok());
    if (bad_frame_first) {
      std::vector<float> bad = frames[1];
      bad[3 * 89000 + 2] = std::numeric_limits<float>::infinity();  // the second block
      bad[3 * 5000 + 1] = std::numeric_limits<float>::quiet_NaN();  // the first
      const Status s = encoder.value().addFrame(bad.data());
      EXPECT_EQ(s.code(), StatusCode::kBadInput);
      EXPECT_NE(s.message().find("frame 1: vertex 5000 "), std::string::npos) << s.message();
    }
    ASSERT_TRUE(encoder.value().addFrame(frames[1].data()).ok());
    ASSERT_TRUE(encoder.value().finish().ok());
  };
  std::vector<uint8_t> plain, after_refusal;
  encodeWith(false, plain);
  encodeWith(true, after_refusal);
  ASSERT_FALSE(plain.empty());
  EXPECT_EQ(plain, after_refusal);
}

TEST_F(EncodeInput, ShortFrameIsRefused) {
  std::vector<std::vector<float>> frames;
  for (int f = 0; f < 4; ++f) frames.push_back(gridFrame(kNx, kNy, f, 1.0, 0.5));
  frames[2].resize(frames[2].size() - 3);
  MemorySequence seq(gridTopology(kNx, kNy), std::move(frames), 25.0, "short");
  expectRefused(seq, {}, StatusCode::kBadInput, {"frame 2", "19 vertices", "expected 20"});
}

TEST_F(EncodeInput, BadTopologyIsRefused) {
  std::vector<std::vector<float>> one_frame = {gridFrame(kNx, kNy, 0, 0, 0)};
  MemorySequence no_triangles(Topology{kNx * kNy, {}}, one_frame);
  expectRefused(no_triangles, {}, StatusCode::kBadInput, {"no triangles"});
  Topology out_of_range = gridTopology(kNx, kNy);
  out_of_range.triangles[5][1] = kNx * kNy;
  MemorySequence bad_index(out_of_range, one_frame);
  expectRefused(bad_index, {}, StatusCode::kBadInput, {"triangle 5", "vertex 20"});
}

TEST_F(EncodeInput, ZeroFramesAreRefused) {
  MemorySequence empty(gridTopology(kNx, kNy), {});
  expectRefused(empty, {}, StatusCode::kBadInput, {"no frames"});
}

// A square (4 vertices) in ASCII PLY; `faces` is the face section, one "3 a b c" per line.
std::string plyText(int frame, const std::string& faces, int face_count) {
  std::ostringstream o;
  o << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    << "property float z\nelement face " << face_count << "\nproperty list uchar int vertex_indices\n"
    << "end_header\n";
  for (int v = 0; v < 4; ++v) o << (v & 1) << ' ' << (v >> 1) << ' ' << 0.1 * frame << '\n';
  o << faces;
  return o.str();
}

TEST_F(EncodeInput, PlyFramesWithDifferentFacesAreRefused) {
  fs::create_directories(dir_ / "frames");
  std::ofstream(path("frames/f1.ply")) << plyText(0, "3 0 1 3\n3 0 3 2\n", 2);
  std::ofstream(path("frames/f2.ply")) << plyText(1, "3 0 1 3\n3 0 3 2\n", 2);
  std::ofstream(path("frames/f10.ply")) << plyText(2, "3 0 1 2\n3 1 3 2\n", 2);  // third, by natural order
  auto source = openSequence(path("frames"), "");
  ASSERT_TRUE(source.ok()) << source.status().message();
  expectRefused(*source.value(), {}, StatusCode::kBadInput, {"f10.ply", "face list differs", "triangle 0"});

  // A different number of faces, against a --mesh.
  std::ofstream(path("frames/f10.ply")) << plyText(2, "3 0 1 3\n", 1);
  source = openSequence(path("frames"), path("frames/f1.ply"));
  ASSERT_TRUE(source.ok()) << source.status().message();
  expectRefused(*source.value(), {}, StatusCode::kBadInput, {"f10.ply", "face list differs", "1 triangles"});
}

TEST_F(EncodeInput, Pc2PointCountMustMatchTheMesh) {
  const Topology five{5, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}};
  auto sink = createSequenceSink(path("five.pc2"), SequenceFormat::kPc2, five, 25.0, 2);
  ASSERT_TRUE(sink.ok()) << sink.status().message();
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0.5f, 0.5f, 1};
  ASSERT_TRUE(sink.value()->write(xyz.data()).ok());
  ASSERT_TRUE(sink.value()->write(xyz.data()).ok());
  ASSERT_TRUE(sink.value()->finish().ok());
  std::ofstream(path("square.ply")) << plyText(0, "3 0 1 3\n3 0 3 2\n", 2);

  auto source = openSequence(path("five.pc2"), path("square.ply"));
  ASSERT_FALSE(source.ok());
  const std::string& m = source.status().message();
  EXPECT_EQ(source.status().code(), StatusCode::kBadInput) << m;
  for (const char* w : {"five.pc2", "point count 5", "square.ply", "4 vertices"})
    EXPECT_NE(m.find(w), std::string::npos) << "'" << w << "' not in: " << m;
  // Without --mesh a point cache cannot be read at all.
  source = openSequence(path("five.pc2"), "");
  EXPECT_EQ(source.status().code(), StatusCode::kInvalidArgument) << source.status().message();
  EXPECT_NE(source.status().message().find("--mesh"), std::string::npos) << source.status().message();
}

TEST_F(EncodeInput, CancelledEncodeLeavesNoFileAndKeepsAnEarlierOne) {
  MemorySequence seq = gridSequence(kNx, kNy, 10, 1.0, 0.5);
  int calls = 0;
  const ProgressFn stop_at_third = [&](int, const char*) { return ++calls < 3; };
  expectRefused(seq, {}, StatusCode::kCancelled, {"cancel"}, stop_at_third);
  EXPECT_EQ(calls, 3);

  std::ofstream(out_) << "earlier";
  seq.rewind();
  calls = 0;
  auto report = encodeSequence(seq, {}, out_, stop_at_third);
  EXPECT_EQ(report.status().code(), StatusCode::kCancelled);
  std::ifstream in(out_);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "earlier") << "a cancelled encode replaced the file at its target";
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_ / "out"), fs::directory_iterator()), 1)
      << "temporary left beside the target";
}

TEST_F(EncodeInput, InvalidOptionsAreRefused) {
  struct Case {
    double max_error;
    int bits;
    int max_depth;
    const char* word;
  };
  for (const Case& c : {Case{0.0, 16, 10, "max error"}, Case{2.0, 16, 10, "max error"},
                        Case{-0.01, 16, 10, "max error"}, Case{std::nan(""), 16, 10, "max error"},
                        Case{0.01, 30, 10, "bits"}, Case{0.01, 7, 10, "bits"}, Case{0.01, 16, 0, "depth"},
                        Case{0.01, 16, 17, "depth"}}) {
    for (Profile profile : {Profile::kPaper, Profile::kPredictive}) {
      SCOPED_TRACE(std::string(c.word) + " " + profileName(profile));
      MemorySequence seq = gridSequence(kNx, kNy, 3, 1.0, 0.5);
      EncodeSettings settings;
      settings.octree().profile = profile;
      settings.octree().max_error = c.max_error;
      settings.octree().bits = c.bits;
      settings.octree().max_depth = c.max_depth;
      EXPECT_EQ(settings.validate().code(), StatusCode::kInvalidArgument);
      expectRefused(seq, settings, StatusCode::kInvalidArgument, {c.word});
    }
  }
}

}  // namespace
}  // namespace animc
