// SPDX-License-Identifier: Apache-2.0
// Sequence I/O: round trips through every writer, the PLY / OFF / PC2 / MDD readers (including
// streamed .xz), and the validation messages for bad inputs.
#include <gtest/gtest.h>
#include <lzma.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "core/atomic_file.h"
#include "core/memory_sequence.h"
#include "scratch_folder.h"
#include "seqio/frame_files.h"
#include "seqio/sequence_io.h"
#include "test_sequences.h"

namespace animc {
namespace {

namespace fs = std::filesystem;
using Frames = std::vector<std::vector<float>>;

// --- helpers -----------------------------------------------------------------------------

class SeqioTest : public testing_support::ScratchFolderTest {
 protected:
  SeqioTest() : ScratchFolderTest("seqio") {}
  void writeFile(const std::string& name, const std::string& bytes) const {
    std::ofstream(path(name), std::ios::binary) << bytes;
  }
  size_t fileCount() const {
    return size_t(std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
};

// Two quads' worth of faces on 5 vertices: a quad (fan-triangulated to 2) and a triangle.
Topology smallTopology() { return Topology{5, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}}}; }

// Values that stress float formatting: negative, tiny, large, non-terminating decimals.
Frames makeFrames(uint32_t vertex_count, int frame_count) {
  Frames frames(frame_count, std::vector<float>(vertex_count * 3));
  for (int f = 0; f < frame_count; ++f)
    for (size_t i = 0; i < frames[f].size(); ++i)
      frames[f][i] = float(std::pow(-1.7, double(i % 7)) / 3.0 + f * 0.1) * (i == 4 ? 1e20f : 1.f);
  frames[0][2] = 1.2345e-30f;
  return frames;
}

Status writeAll(FrameSink& sink, const Frames& frames) {
  for (const std::vector<float>& xyz : frames) ANIMC_RETURN_IF_ERROR(sink.write(xyz.data()));
  return sink.finish();
}

std::string errorOf(const Status& status) { return status.ok() ? "OK" : status.message(); }
template <class T>
std::string errorOf(const Result<T>& result) {
  return errorOf(result.status());
}

// Error text from opening `path` and reading every frame.
std::string sequenceError(const std::string& path, const std::string& mesh_path) {
  auto source = openSequence(path, mesh_path);
  if (!source.ok()) return errorOf(source);
  return errorOf(readFrames(*source.value()));
}

enum class Encoding { kAscii, kLittle, kBig };

// Serialises PLY values the way a file in `encoding` stores them (the test host is
// little-endian, checked in SeqioTest.HostIsLittleEndian).
struct PlyBody {
  Encoding encoding;
  std::string bytes;

  template <class T>
  void put(T value) {
    if (encoding == Encoding::kAscii) {
      char text[64];
      auto end = std::is_floating_point<T>::value
                     ? std::to_chars(text, text + 64, value).ptr
                     : std::to_chars(text, text + 64, int64_t(value)).ptr;
      bytes.append(text, end).push_back(' ');
      return;
    }
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (encoding == Encoding::kBig) std::reverse(raw, raw + sizeof(T));
    bytes.append(raw, sizeof(T));
  }
};

const float kPositions[15] = {0.1f, -2.5f, 3.3333333f, 1e-7f, 4,   5,  -6,   7.75f,
                              8,    9,     10,         11.5f, -12, 13, 1e20f};

// A PLY with properties around x, y (double), z, an ignored list, polygon faces with flags,
// and an extra element; it holds kPositions and smallTopology().
std::string richPly(Encoding encoding) {
  const char* names[] = {"ascii", "binary_little_endian", "binary_big_endian"};
  std::string header =
      std::string("ply\nformat ") + names[int(encoding)] +
      " 1.0\ncomment test file\nobj_info generated\nelement vertex 5\nproperty uchar red\n"
      "property float x\nproperty double confidence\nproperty double y\n"
      "property list uchar short junk\nproperty float z\nelement face 2\nproperty int flags\n"
      "property list ushort uint vertex_indices\nelement edge 1\nproperty int vertex1\n"
      "property int vertex2\nend_header\n";
  PlyBody body{encoding, ""};
  for (int v = 0; v < 5; ++v) {
    body.put<uint8_t>(200);
    body.put<float>(kPositions[3 * v]);
    body.put<double>(0.5);
    body.put<double>(kPositions[3 * v + 1]);
    body.put<uint8_t>(2), body.put<int16_t>(-3), body.put<int16_t>(4);
    body.put<float>(kPositions[3 * v + 2]);
  }
  body.put<int32_t>(-1), body.put<uint16_t>(4);
  for (uint32_t i : {0, 1, 2, 3}) body.put<uint32_t>(i);
  body.put<int32_t>(7), body.put<uint16_t>(3);
  for (uint32_t i : {0, 3, 4}) body.put<uint32_t>(i);
  body.put<int32_t>(0), body.put<int32_t>(1);
  return header + body.bytes;
}

const std::string kTrianglePly =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
    "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

std::vector<uint8_t> xzCompress(const std::string& bytes) {
  std::vector<uint8_t> out(bytes.size() + bytes.size() / 2 + 1024);
  size_t out_size = 0;
  lzma_ret rc = lzma_easy_buffer_encode(6, LZMA_CHECK_CRC64, nullptr,
                                        reinterpret_cast<const uint8_t*>(bytes.data()),
                                        bytes.size(), out.data(), &out_size, out.size());
  EXPECT_EQ(rc, LZMA_OK);
  out.resize(out_size);
  return out;
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Writes frames through the PC2 sink, returns the file's bytes.
std::string pc2Bytes(const std::string& path, const Frames& frames) {
  auto sink =
      createSequenceSink(path, SequenceFormat::kPc2, smallTopology(), 25, int64_t(frames.size()));
  EXPECT_TRUE(sink.ok()) << errorOf(sink);
  EXPECT_TRUE(writeAll(*sink.value(), frames).ok());
  return fileBytes(path);
}

// --- PLY and OFF meshes ------------------------------------------------------------------

TEST_F(SeqioTest, HostIsLittleEndian) {
  uint16_t one = 1;
  uint8_t first;
  std::memcpy(&first, &one, 1);
  ASSERT_EQ(first, 1) << "PlyBody assumes a little-endian host";
}

TEST_F(SeqioTest, PlyAllEncodingsWithExtraPropertiesAndPolygons) {
  for (Encoding encoding : {Encoding::kAscii, Encoding::kLittle, Encoding::kBig}) {
    SCOPED_TRACE(int(encoding));
    writeFile("rich.ply", richPly(encoding));
    auto mesh = readMesh(path("rich.ply"));
    ASSERT_TRUE(mesh.ok()) << errorOf(mesh);
    EXPECT_EQ(mesh.value().topology.vertex_count, 5u);
    EXPECT_EQ(mesh.value().topology.triangles, smallTopology().triangles);
    EXPECT_EQ(mesh.value().positions, std::vector<float>(kPositions, kPositions + 15));
  }
}

TEST_F(SeqioTest, OffWithCommentsAndPolygons) {
  writeFile("m.off",
            "OFF # header comment\n# a comment line\n5 2 0\n"
            "0.1 -2.5 3.3333333\n1e-07 4 5\n-6 7.75 8\n\n9 10 11.5\n-12 13 1e20\n"
            "4 0 1 2 3  255 0 0\n3 0 3 4 # trailing comment\n");
  auto mesh = readMesh(path("m.off"));
  ASSERT_TRUE(mesh.ok()) << errorOf(mesh);
  EXPECT_EQ(mesh.value().topology.triangles, smallTopology().triangles);
  EXPECT_EQ(mesh.value().positions, std::vector<float>(kPositions, kPositions + 15));
}

TEST_F(SeqioTest, BadPlyInputsAreRejectedWithReasons) {
  struct Case {
    std::string from, to, expected;
  } cases[] = {
      {"3 0 1 2\n", "2 0 1\n", "face 0 has 2 vertices"},
      {"3 0 1 2\n", "3 0 1 3\n", "vertex index 3 out of range"},
      {"3 0 1 2\n", "3 0 -1 2\n", "vertex index -1 out of range"},
      {"1 0 0\n", "1 nan 0\n", "vertex 1 has a non-finite coordinate"},
      {"0 1 0\n", "0 1 -inf\n", "vertex 2 has a non-finite coordinate"},
      {"1 0 0\n", "1 3e30 0\n", "vertex 1: coordinate too large"},
      {"element face 1", "element face 0", "empty mesh (0 triangles)"},
      {"0 1 0\n3 0 1 2\n", "0 1", "announces 3 vertex elements"},
      {"0 1 0\n3 0 1 2\n", "0.0000 1.0000 0.0000\n3 0 1", "data ends early"},
      {"0 1 0\n", "0 1 zero\n", "bad number 'zero'"},
      {"element vertex 3", "element vertex 300000000", "announces 300000000 vertex"},
      {"element vertex 3", "element vertex 99999999999", "announces"},
      {"property float z\n", "", "lacks an x, y or z"},
      {"format ascii", "format binary_middle_endian", "unknown format"},
      {"end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "end_he", "no end_header"},
  };
  for (const Case& c : cases) {
    writeFile("bad.ply", replaced(kTrianglePly, c.from, c.to));
    std::string error = errorOf(readMesh(path("bad.ply")));
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.expected << " / " << error;
    EXPECT_NE(error.find("bad.ply"), std::string::npos) << error;
  }
}

TEST_F(SeqioTest, TruncatedAndAbsurdBinaryPly) {
  std::string ply = richPly(Encoding::kLittle);
  writeFile("cut.ply", ply.substr(0, ply.size() - 3));
  EXPECT_NE(errorOf(readMesh(path("cut.ply"))).find("ends early"), std::string::npos);
  writeFile("huge.ply", replaced(ply, "element vertex 5", "element vertex 4000000000"));
  EXPECT_NE(errorOf(readMesh(path("huge.ply"))).find("announces 4000000000"), std::string::npos);
  std::string empty = replaced(replaced(kTrianglePly, "vertex 3", "vertex 0"), "face 1", "face 0");
  writeFile("empty.ply", empty);
  EXPECT_NE(errorOf(readMesh(path("empty.ply"))).find("empty mesh (0 vertices)"),
            std::string::npos);
}

// A binary PLY of one triangle whose header declares `declared` faces, followed by
// `padding` zero bytes: as many faces as the bytes hold would each take 13 bytes (a uchar
// count and three int indices).
std::string binaryTrianglePly(uint64_t declared, size_t padding) {
  std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face " + std::to_string(declared) +
      "\nproperty list uchar int vertex_indices\nend_header\n";
  PlyBody body{Encoding::kLittle, ""};
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) body.put<float>(v);
  body.put<uint8_t>(3);
  for (int32_t i : {0, 1, 2}) body.put<int32_t>(i);
  return header + body.bytes + std::string(padding, '\0');
}

// A header may declare far more faces than the file holds. The reader reserved 12 bytes per
// declared face before reading any (1.2 GB for a 100 MB file declaring 10^8 faces) and then
// failed on whatever it read first; it must say the file is too short for its faces instead.
TEST_F(SeqioTest, PlyDeclaringMoreFacesThanItsBytesHoldIsTruncated) {
  writeFile("faces.ply", binaryTrianglePly(1000, 987));  // 1000 face bytes: at most 76 faces
  auto mesh = readMesh(path("faces.ply"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kTruncated) << errorOf(mesh);
  EXPECT_NE(errorOf(mesh).find("declares 1000 faces but the 1000 bytes left can hold at most 76"),
            std::string::npos) << errorOf(mesh);
  EXPECT_NE(errorOf(mesh).find("faces.ply: data ends early (truncated file)"), std::string::npos)
      << errorOf(mesh);

  // The attack at a hundredth of its size: a byte per declared face (enough for the header
  // check, which counts a list as its length alone), 10^6 faces in 1 MB.
  writeFile("faces.ply", binaryTrianglePly(1000000, 1000000));
  mesh = readMesh(path("faces.ply"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kTruncated) << errorOf(mesh);
  EXPECT_NE(errorOf(mesh).find("declares 1000000 faces but the 1000013 bytes left can hold at most 76924"),
            std::string::npos) << errorOf(mesh);

  // ASCII: "3 0 1 2" is the shortest face there is, so "\n3 0 1 2\n" holds one, not three.
  writeFile("faces.ply", replaced(kTrianglePly, "element face 1", "element face 3"));
  mesh = readMesh(path("faces.ply"));
  EXPECT_EQ(mesh.status().code(), StatusCode::kTruncated) << errorOf(mesh);
  EXPECT_NE(errorOf(mesh).find("declares 3 faces but the 9 bytes left can hold at most 1"),
            std::string::npos) << errorOf(mesh);

  // Files whose faces fill their bytes exactly are still read.
  writeFile("faces.ply", binaryTrianglePly(1, 0));
  EXPECT_TRUE(readMesh(path("faces.ply")).ok()) << errorOf(readMesh(path("faces.ply")));
  writeFile("faces.ply", kTrianglePly);
  EXPECT_TRUE(readMesh(path("faces.ply")).ok()) << errorOf(readMesh(path("faces.ply")));
}

// Found by fuzzing: an element with no properties takes no bytes, so the data-size check
// lets any count through, and skipping it one instance at a time would loop 2^64 times (when
// the compiler keeps the empty loop: clang does, gcc -O2 drops it).
TEST_F(SeqioTest, PlyElementWithoutPropertiesAndAHugeCountIsSkippedAtOnce) {
  writeFile("empty_element.ply",
            replaced(kTrianglePly, "element face", "element junk 18446744073709551615\nelement face"));
  auto mesh = readMesh(path("empty_element.ply"));
  ASSERT_TRUE(mesh.ok()) << errorOf(mesh);
  EXPECT_EQ(mesh.value().topology.triangles.size(), 1u);
}

TEST_F(SeqioTest, BadOffInputsAreRejectedWithReasons) {
  const std::string good = "OFF\n3 1 0\n0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n3 0 1 2\n";
  struct Case {
    std::string from, to, expected;
  } cases[] = {
      {"3 0 1 2", "2 0 1", "face 0 has 2 vertices"},
      {"3 0 1 2", "3 0 1 7", "vertex index 7 out of range"},
      {"1.0 0.0 0.0\n", "1 0 nan\n", "vertex 1 has a non-finite coordinate"},
      {"1.0 0.0 0.0\n", "1e31 0 0\n", "vertex 1: coordinate too large"},
      {"3 1 0", "3 0 0", "empty mesh (0 triangles)"},
      {"3 1 0", "0 0 0", "empty mesh (0 vertices)"},
      {"3 1 0", "3000000 1 0", "header announces 3000000 vertices"},
      {"0.0 1.0 0.0\n3 0 1 2\n", "0.0 1.0 0.0\n", "file ends at face 0"},
      {"0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n3 0 1 2\n", "0 0 0\n1 0 0\n0 1",
       "announces 3 vertices and 1 faces"},
      {"0.0 1.0 0.0", "0.0 1.0", "vertex 2 has fewer than 3 coordinates"},
      {"0.0 1.0 0.0", "0.0 1.0 x", "bad number 'x'"},
      {"OFF", "PFF", "not an OFF file"},
  };
  for (const Case& c : cases) {
    writeFile("bad.off", replaced(good, c.from, c.to));
    std::string error = errorOf(readMesh(path("bad.off")));
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.expected << " / " << error;
    EXPECT_NE(error.find("bad.off"), std::string::npos) << error;
  }
}

// --- round trips -------------------------------------------------------------------------

TEST_F(SeqioTest, RoundTripEveryFormat) {
  Topology topology = smallTopology();
  Frames frames = makeFrames(topology.vertex_count, 4);
  for (const SequenceFormatSpec& spec : sequenceFormats()) {
    if (spec.animated_mesh) continue;  // written only: gltf_output checks them
    const SequenceFormat format = spec.format;
    std::string out = path(std::string("seq") + (spec.frame_file ? "_" : ".") + spec.name);
    SCOPED_TRACE(out);
    auto sink = createSequenceSink(out, format, topology, 30.0, int64_t(frames.size()));
    ASSERT_TRUE(sink.ok()) << errorOf(sink);
    ASSERT_TRUE(writeAll(*sink.value(), frames).ok());
    std::string mesh = spec.point_cache ? path("seq_ply/frame_00000.ply") : "";
    auto source = openSequence(out, mesh);
    ASSERT_TRUE(source.ok()) << errorOf(source);
    EXPECT_EQ(source.value()->topology().triangles, topology.triangles);
    EXPECT_EQ(source.value()->topology().vertex_count, topology.vertex_count);
    EXPECT_EQ(source.value()->frameCount(), 4);
    EXPECT_DOUBLE_EQ(source.value()->frameRate(), format == SequenceFormat::kMdd ? 30.0 : 25.0);
    auto read = readFrames(*source.value());
    ASSERT_TRUE(read.ok()) << errorOf(read);
    EXPECT_EQ(read.value(), frames);  // bit-exact floats
  }
  EXPECT_TRUE(fs::exists(path("seq_off/frame_00003.off")));
  EXPECT_TRUE(fs::exists(path("seq_obj/frame_00003.obj")));
}

TEST_F(SeqioTest, FrameDirectoryInNaturalOrderAndListFile) {
  Topology topology = smallTopology();
  Frames frames = makeFrames(topology.vertex_count, 3);
  fs::create_directories(path("walk"));
  const char* names[] = {"f2.ply", "f10.ply", "f1.ply"};  // frames 1, 2, 0 in natural order
  const int order[] = {1, 2, 0};
  for (int i = 0; i < 3; ++i) {
    auto sink = createSequenceSink(path("tmp"), SequenceFormat::kPly, topology, 25, 1);
    ASSERT_TRUE(sink.ok());
    ASSERT_TRUE(writeAll(*sink.value(), {frames[order[i]]}).ok());
    fs::rename(path("tmp/frame_00000.ply"), path(std::string("walk/") + names[i]));
  }
  writeFile("walk/readme.txt", "not a frame");
  auto read = readFrames(*openSequence(path("walk"), path("walk/f1.ply")).value());
  ASSERT_TRUE(read.ok()) << errorOf(read);
  EXPECT_EQ(read.value(), frames);

  writeFile("list.txt", "# frames\nwalk/f1.ply\n\n  walk/f2.ply\r\n" + path("walk/f10.ply") + "\n");
  auto listed = openSequence(path("list.txt"), "");
  ASSERT_TRUE(listed.ok()) << errorOf(listed);
  EXPECT_EQ(listed.value()->frameCount(), 3);
  EXPECT_EQ(readFrames(*listed.value()).value(), frames);

  auto single = openSequence(path("walk/f10.ply"), "");
  ASSERT_TRUE(single.ok());
  EXPECT_EQ(readFrames(*single.value()).value(), Frames{frames[2]});
}

TEST_F(SeqioTest, NaturalOrder) {
  std::vector<std::string> names = {"a10", "a2", "b1", "a02x", "a1", "a", "a2x"};
  std::sort(names.begin(), names.end(), naturalLess);
  EXPECT_EQ(names, (std::vector<std::string>{"a", "a1", "a2", "a02x", "a2x", "a10", "b1"}));
}

TEST_F(SeqioTest, FramesMustShareConnectivity) {
  fs::create_directories(path("walk"));
  writeFile("walk/0000.ply", kTrianglePly);
  writeFile("walk/0001.ply", kTrianglePly);
  writeFile("walk/0002.ply",
            replaced(replaced(kTrianglePly, "vertex 3", "vertex 4"), "0 1 0\n", "0 1 0\n0 0 1\n"));
  EXPECT_NE(sequenceError(path("walk"), "").find("walk/0002.ply (frame 2): vertex count 4 differs from frame 0 (3)"),
            std::string::npos)
      << sequenceError(path("walk"), "");
  writeFile("walk/0002.ply", replaced(kTrianglePly, "3 0 1 2", "3 0 2 1"));
  EXPECT_NE(sequenceError(path("walk"), "").find("0002.ply (frame 2): face list differs from frame 0"),
            std::string::npos);
  writeFile("walk/0002.ply", replaced(kTrianglePly, "0 1 0\n", "0 inf 0\n"));
  EXPECT_NE(sequenceError(path("walk"), "").find("0002.ply: vertex 2 has a non-finite"),
            std::string::npos);
  writeFile("other.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 2 1\n");
  EXPECT_NE(sequenceError(path("walk/0000.ply"), path("other.off"))
                .find("face list differs from the mesh"),
            std::string::npos);
  writeFile("list.txt", "walk/0000.ply\nwalk/0001.obj\n");
  EXPECT_NE(sequenceError(path("list.txt"), "").find("list.txt line 2"), std::string::npos);
  fs::create_directories(path("empty"));
  EXPECT_NE(sequenceError(path("empty"), "").find("no .ply, .off or .obj frames"), std::string::npos);
  EXPECT_NE(sequenceError(path("x.stl"), "").find("unrecognised input"), std::string::npos);
}

// An error in a frame of a .txt list names the list and the line to fix, then the frame.
TEST_F(SeqioTest, FrameListErrorsNameTheListAndLine) {
  fs::create_directories(path("walk"));
  writeFile("walk/good.ply", kTrianglePly);
  writeFile("walk/bad.ply", replaced(kTrianglePly, "0 1 0\n", "0 inf 0\n"));
  writeFile("walk/other.ply", replaced(kTrianglePly, "3 0 1 2", "3 0 2 1"));
  const std::string list = path("list.txt");
  struct Case {
    std::string lines, expected;
  } cases[] = {
      {"# frames\nwalk/good.ply\n\nwalk/bad.ply\n",
       list + " line 4: " + path("walk/bad.ply") + ": vertex 2 has a non-finite"},
      {"walk/good.ply\nwalk/missing.ply\n", list + " line 2: " + path("walk/missing.ply") + ": "},
      {"walk/good.ply\n  walk/other.ply\r\n",
       list + " line 2: " + path("walk/other.ply") + " (frame 1): face list differs from frame 0"},
      {"\n\nwalk/bad.ply\nwalk/good.ply\n",  // frame 0, read when the list is opened
       list + " line 3: " + path("walk/bad.ply") + ": vertex 2 has a non-finite"},
  };
  for (const Case& c : cases) {
    writeFile("list.txt", c.lines);
    const std::string error = sequenceError(list, "");
    EXPECT_EQ(error.find(c.expected), 0u) << c.expected << "\n" << error;
  }
  // With --mesh, a frame 0 whose faces differ from the mesh's is named by its line too.
  writeFile("list.txt", "walk/other.ply\n");
  EXPECT_EQ(sequenceError(list, path("walk/good.ply"))
                .find(list + " line 1: " + path("walk/other.ply") + " (frame 0): face list differs from the mesh"),
            0u)
      << sequenceError(list, path("walk/good.ply"));
}

// --- point caches ------------------------------------------------------------------------

TEST_F(SeqioTest, PointCacheErrors) {
  writeFile("mesh.ply", richPly(Encoding::kLittle));
  std::string mesh = path("mesh.ply");
  std::string good = pc2Bytes(path("good.pc2"), makeFrames(5, 3));
  const size_t frame_bytes = 5 * 12;
  EXPECT_NE(sequenceError(path("good.pc2"), "")
                .find("--mesh is required for point-cache input (.pc2, .pc2.xz, .mdd or .mdd.xz: they hold no faces)"),
            std::string::npos);
  writeFile("cut.pc2", good.substr(0, good.size() - 1));
  EXPECT_NE(sequenceError(path("cut.pc2"), mesh).find("cut.pc2: truncated at frame 2 of 3"),
            std::string::npos);
  writeFile("long.pc2", good + "x");
  EXPECT_NE(sequenceError(path("long.pc2"), mesh).find("does not match its header"),
            std::string::npos);
  writeFile("absurd.pc2", replaced(good, std::string("\3\0\0\0", 4), "\xff\xff\xff\x7f"));
  EXPECT_NE(sequenceError(path("absurd.pc2"), mesh).find("truncated at frame 3 of 2147483647"),
            std::string::npos);
  writeFile("points.pc2", replaced(good, std::string("\5\0\0\0", 4), std::string("\6\0\0\0", 4)));
  EXPECT_NE(sequenceError(path("points.pc2"), mesh).find("point count 6 differs from the mesh"),
            std::string::npos);
  writeFile("magic.pc2", "POINTCACHE3" + good.substr(11));
  EXPECT_NE(sequenceError(path("magic.pc2"), mesh).find("not a PC2 file"), std::string::npos);
  writeFile("header.pc2", good.substr(0, 20));
  EXPECT_NE(sequenceError(path("header.pc2"), mesh).find("header"), std::string::npos);

  std::string nan_frame = good;
  float nan = std::numeric_limits<float>::quiet_NaN(), huge = 2e30f;
  std::memcpy(&nan_frame[32 + 2 * frame_bytes + 4 * 4], &nan, 4);  // frame 2, vertex 1, y
  writeFile("nan.pc2", nan_frame);
  std::string error = sequenceError(path("nan.pc2"), mesh);
  EXPECT_NE(error.find("nan.pc2 frame 2: vertex 1 has a non-finite coordinate"), std::string::npos)
      << error;
  std::memcpy(&nan_frame[32 + 2 * frame_bytes + 4 * 4], &huge, 4);
  writeFile("huge.pc2", nan_frame);
  EXPECT_NE(sequenceError(path("huge.pc2"), mesh).find("vertex 1: coordinate too large"),
            std::string::npos);
}

TEST_F(SeqioTest, MddErrors) {
  writeFile("mesh.ply", richPly(Encoding::kLittle));
  auto sink = createSequenceSink(path("good.mdd"), SequenceFormat::kMdd, smallTopology(), 24, 3);
  ASSERT_TRUE(sink.ok());
  ASSERT_TRUE(writeAll(*sink.value(), makeFrames(5, 3)).ok());
  std::string good = fileBytes(path("good.mdd"));
  EXPECT_EQ(good.size(), 8 + 3 * 4 + 3 * 60u);
  writeFile("cut.mdd", good.substr(0, good.size() - 61));
  EXPECT_NE(sequenceError(path("cut.mdd"), path("mesh.ply")).find("truncated at frame 1 of 3"),
            std::string::npos);
  writeFile("absurd.mdd", std::string("\x40\0\0\0\0\0\0\5", 8) + good.substr(8));
  EXPECT_NE(sequenceError(path("absurd.mdd"), path("mesh.ply")).find("truncated"),
            std::string::npos);
  writeFile("zero.mdd", std::string("\0\0\0\0\0\0\0\5", 8));
  EXPECT_NE(sequenceError(path("zero.mdd"), path("mesh.ply")).find("announces 0 frames"),
            std::string::npos);
}

TEST_F(SeqioTest, CompressedPointCachesStreamAndReportTruncation) {
  writeFile("mesh.ply", richPly(Encoding::kLittle));
  Frames frames = makeFrames(5, 3);
  std::string good = pc2Bytes(path("plain.pc2"), frames);
  auto writeXz = [&](const std::string& name, const std::string& bytes) {
    std::vector<uint8_t> xz = xzCompress(bytes);
    writeFile(name, std::string(xz.begin(), xz.end()));
  };
  writeXz("good.pc2.xz", good);
  auto source = openSequence(path("good.pc2.xz"), path("mesh.ply"));
  ASSERT_TRUE(source.ok()) << errorOf(source);
  EXPECT_EQ(readFrames(*source.value()).value(), frames);

  writeXz("cut.pc2.xz", good.substr(0, good.size() - 7));
  EXPECT_NE(sequenceError(path("cut.pc2.xz"), path("mesh.ply")).find("truncated at frame 2 of 3"),
            std::string::npos);
  writeXz("long.pc2.xz", good + "trailing");
  EXPECT_NE(sequenceError(path("long.pc2.xz"), path("mesh.ply")).find("data continues after"),
            std::string::npos);
  std::string compressed = fileBytes(path("good.pc2.xz"));
  writeFile("broken.pc2.xz", compressed.substr(0, compressed.size() - 20));
  EXPECT_NE(sequenceError(path("broken.pc2.xz"), path("mesh.ply")), "OK");
  writeFile("notxz.mdd.xz", good);
  EXPECT_NE(sequenceError(path("notxz.mdd.xz"), path("mesh.ply")).find("not an xz file"),
            std::string::npos);
}

TEST(SeqioRealData, SydneyPc2Xz) {
  ANIMC_REQUIRE_SEQUENCE("sydney_md2");
  const std::string dir = testing_support::sequenceDir("sydney_md2");
  auto mesh = readMesh(dir + "sydney_md2.ply");
  ASSERT_TRUE(mesh.ok()) << errorOf(mesh);
  auto source = openSequence(dir + "sydney_md2.pc2.xz", dir + "sydney_md2.ply");
  ASSERT_TRUE(source.ok()) << errorOf(source);
  EXPECT_EQ(source.value()->topology().vertex_count, 342u);
  EXPECT_EQ(source.value()->topology().triangles.size(), 679u);
  EXPECT_EQ(source.value()->topology().triangles, mesh.value().topology.triangles);
  EXPECT_EQ(source.value()->frameCount(), 198);
  auto frames = readFrames(*source.value());
  ASSERT_TRUE(frames.ok()) << errorOf(frames);
  ASSERT_EQ(frames.value().size(), 198u);
  EXPECT_EQ(frames.value()[0], mesh.value().positions);
  EXPECT_NE(frames.value()[1], frames.value()[0]);
}

// --- writers -----------------------------------------------------------------------------

TEST_F(SeqioTest, AtomicFileCommitsOrLeavesNothing) {
  {
    AtomicFile file;
    ASSERT_TRUE(file.open(path("out.bin")).ok());
    ASSERT_TRUE(file.write("hello world", 11).ok());
    EXPECT_EQ(file.tell(), 11u);
    ASSERT_TRUE(file.seek(0).ok());
    ASSERT_TRUE(file.write("J", 1).ok());
    EXPECT_FALSE(fs::exists(path("out.bin")));  // invisible until commit
    ASSERT_TRUE(file.commit().ok());
  }
  EXPECT_EQ(fileBytes(path("out.bin")), "Jello world");
  {
    AtomicFile file;
    ASSERT_TRUE(file.open(path("out.bin")).ok());
    ASSERT_TRUE(file.write("partial", 7).ok());
  }
  EXPECT_EQ(fileBytes(path("out.bin")), "Jello world");  // old content kept, temp removed
  EXPECT_EQ(fileCount(), 1u);
  AtomicFile bad;
  EXPECT_EQ(bad.open(path("missing/dir/out.bin")).code(), StatusCode::kIoError);
}

TEST_F(SeqioTest, SinkWithoutFinishLeavesNoFile) {
  Frames frames = makeFrames(5, 3);
  for (SequenceFormat format :
       {SequenceFormat::kPly, SequenceFormat::kOff, SequenceFormat::kPc2, SequenceFormat::kMdd}) {
    auto sink = createSequenceSink(path("out"), format, smallTopology(), 25, 3);
    ASSERT_TRUE(sink.ok()) << errorOf(sink);
    ASSERT_TRUE(sink.value()->write(frames[0].data()).ok());
    ASSERT_TRUE(sink.value()->write(frames[1].data()).ok());
    Status early = sink.value()->finish();  // 2 of 3 frames
    EXPECT_NE(errorOf(early).find("2 frames written but 3 announced"), std::string::npos);
    sink.value().reset();
    EXPECT_EQ(fileCount(), 0u) << int(format);
  }
  auto sink = createSequenceSink(path("x.pc2"), SequenceFormat::kPc2, smallTopology(), 25, 1);
  ASSERT_TRUE(sink.value()->write(frames[0].data()).ok());
  EXPECT_NE(errorOf(sink.value()->write(frames[1].data())).find("more frames"), std::string::npos);
}

// Told to replace a folder, the sink replaces it as a whole: no frame of the longer earlier
// run, of the other format or anything else is left to be mixed into the new sequence.
TEST_F(SeqioTest, FrameDirectorySinkReplacesAnEarlierLongerRunWhenTold) {
  Frames frames = makeFrames(5, 3);
  for (int count : {3, 2}) {
    auto sink = createSequenceSink(path("out"), SequenceFormat::kPly, smallTopology(), 25, count,
                                   ExistingOutput::kReplace);
    ASSERT_TRUE(sink.ok());
    ASSERT_TRUE(writeAll(*sink.value(), Frames(frames.begin(), frames.begin() + count)).ok());
  }
  auto source = openSequence(path("out"), "");
  ASSERT_TRUE(source.ok());
  EXPECT_EQ(source.value()->frameCount(), 2);
  EXPECT_EQ(fileCount(), 1u) << "a temporary folder is left";
  EXPECT_EQ(std::distance(fs::directory_iterator(path("out")), fs::directory_iterator()), 2);
}

// A folder that holds anything is refused unless the caller says to replace it (it used to
// lose its frame files of the other format or with higher numbers); an empty one is used.
TEST_F(SeqioTest, FrameDirectorySinkRefusesAFolderThatHoldsFiles) {
  fs::create_directories(path("inputs"));
  writeFile("inputs/frame_00000.off", "an input");
  writeFile("inputs/frame_00007.ply", "another");
  for (SequenceFormat format : {SequenceFormat::kPly, SequenceFormat::kOff}) {
    auto sink = createSequenceSink(path("inputs"), format, smallTopology(), 25, 1);
    ASSERT_FALSE(sink.ok());
    EXPECT_NE(errorOf(sink).find("not empty"), std::string::npos) << errorOf(sink);
  }
  EXPECT_EQ(fileBytes(path("inputs/frame_00000.off")), "an input");
  EXPECT_EQ(fileBytes(path("inputs/frame_00007.ply")), "another");
  EXPECT_EQ(std::distance(fs::directory_iterator(path("inputs")), fs::directory_iterator()), 2);
  EXPECT_EQ(fileCount(), 1u) << "a temporary folder is left";
  fs::create_directories(path("empty"));
  auto sink = createSequenceSink(path("empty"), SequenceFormat::kPly, smallTopology(), 25, 1);
  ASSERT_TRUE(sink.ok()) << errorOf(sink);
  ASSERT_TRUE(writeAll(*sink.value(), makeFrames(5, 1)).ok());
  EXPECT_TRUE(fs::exists(path("empty/frame_00000.ply")));
}

// While frames are written the destination still holds the old sequence (what a reader, or a
// run killed part-way, sees); a sink that fails late leaves it exactly as it was.
TEST_F(SeqioTest, FrameDirectorySinkKeepsTheOldFramesUntilItFinishes) {
  const Frames old_frames = makeFrames(5, 3);
  Frames new_frames = makeFrames(5, 4);
  for (std::vector<float>& frame : new_frames)
    for (float& v : frame) v += 1.0f;
  auto first = createSequenceSink(path("out"), SequenceFormat::kPly, smallTopology(), 25, 3);
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(writeAll(*first.value(), old_frames).ok());
  const std::string old_bytes = fileBytes(path("out/frame_00002.ply"));
  {
    auto sink = createSequenceSink(path("out"), SequenceFormat::kPly, smallTopology(), 25, 4,
                                   ExistingOutput::kReplace);
    ASSERT_TRUE(sink.ok()) << errorOf(sink);
    for (int f = 0; f < 3; ++f) ASSERT_TRUE(sink.value()->write(new_frames[f].data()).ok());
    EXPECT_EQ(readFrames(*openSequence(path("out"), "").value()).value(), old_frames);
  }  // destroyed before its fourth frame: the decode failed
  EXPECT_EQ(readFrames(*openSequence(path("out"), "").value()).value(), old_frames);
  EXPECT_EQ(fileBytes(path("out/frame_00002.ply")), old_bytes);
  EXPECT_EQ(fileCount(), 1u) << "the temporary folder is left";
}

// A link to a folder of frames stays a link: the folder it leads to gets the new frames.
TEST_F(SeqioTest, FrameDirectorySinkThroughASymbolicLink) {
  const Frames frames = makeFrames(5, 3);
  fs::create_directories(path("real"));
  fs::create_symlink("real", path("link"));
  for (int count : {3, 2}) {
    auto sink = createSequenceSink(path("link"), SequenceFormat::kPly, smallTopology(), 25, count,
                                   ExistingOutput::kReplace);
    ASSERT_TRUE(sink.ok()) << errorOf(sink);
    ASSERT_TRUE(writeAll(*sink.value(), Frames(frames.begin(), frames.begin() + count)).ok());
    EXPECT_TRUE(fs::is_symlink(fs::symlink_status(path("link")))) << count;
    ASSERT_TRUE(fs::is_directory(path("real")));
    EXPECT_EQ(std::distance(fs::directory_iterator(path("real")), fs::directory_iterator()), count);
  }
  EXPECT_EQ(readFrames(*openSequence(path("link"), "").value()).value(),
            Frames(frames.begin(), frames.begin() + 2));
  EXPECT_EQ(fileCount(), 2u) << "a temporary folder is left";
}

TEST_F(SeqioTest, SinkArgumentsAndFormatNames) {
  EXPECT_EQ(formatFromName("PC2").value(), SequenceFormat::kPc2);
  EXPECT_EQ(formatFromName("off").value(), SequenceFormat::kOff);
  EXPECT_EQ(formatFromName("OBJ").value(), SequenceFormat::kObj);
  EXPECT_NE(errorOf(formatFromName("stl"))
                .find("unknown sequence format 'stl' (expected one of "
                      "ply, off, pc2, mdd, obj, glb, gltf)"),
            std::string::npos);
  EXPECT_FALSE(createSequenceSink(path("a.mdd"), SequenceFormat::kMdd, smallTopology(), 0, 3).ok());
  EXPECT_FALSE(
      createSequenceSink(path("a.pc2"), SequenceFormat::kPc2, smallTopology(), 25, 0).ok());
  Topology broken{2, {{0, 1, 2}}};
  EXPECT_FALSE(createSequenceSink(path("d"), SequenceFormat::kPly, broken, 25, 1).ok());
  EXPECT_FALSE(createSequenceSink(path("d.glb"), SequenceFormat::kGlb, broken, 25, 1).ok());
  EXPECT_NE(errorOf(createSequenceSink(path("d.glb"), SequenceFormat::kGlb, smallTopology(), 0, 1))
                .find("frame rate must be positive for glb"),
            std::string::npos);
  EXPECT_EQ(fileCount(), 0u);
  // A glTF output holds a morph target and a row of weights per frame: at most 65 536 frames,
  // and its size, which grows with F^2, is "too large" for more rather than a wrapped number.
  EXPECT_NE(errorOf(createSequenceSink(path("d.glb"), SequenceFormat::kGlb, smallTopology(), 25, 65537))
                .find("at most 65536"),
            std::string::npos);
  for (SequenceFormat format : {SequenceFormat::kGlb, SequenceFormat::kGltf}) {
    EXPECT_EQ(sequenceOutputBytes(format, smallTopology(), int64_t(1) << 31), ~uint64_t(0));
    EXPECT_GT(sequenceOutputBytes(format, smallTopology(), 65536), uint64_t(4) * 65536 * 65536);
  }
  // A glTF sink takes exactly the frames it announced, and leaves nothing when not finished.
  Frames frames = makeFrames(smallTopology().vertex_count, 3);
  for (SequenceFormat format : {SequenceFormat::kGlb, SequenceFormat::kGltf}) {
    auto sink = createSequenceSink(path("a.gl"), format, smallTopology(), 25, 2);
    ASSERT_TRUE(sink.ok()) << errorOf(sink);
    EXPECT_FALSE(writeAll(*sink.value(), {frames[0]}).ok());
    EXPECT_FALSE(writeAll(*sink.value(), {frames[1], frames[2]}).ok());
  }
  EXPECT_EQ(fileCount(), 0u);
}

}  // namespace
}  // namespace animc
