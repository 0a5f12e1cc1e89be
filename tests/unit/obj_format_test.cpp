// SPDX-License-Identifier: Apache-2.0
// OBJ frames: what exporters write (every corner form, negative indices, polygons, the
// statements that are skipped, CRLF), the errors naming file and line, frames whose faces
// differ, and numbered patterns of frame files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/memory_sequence.h"
#include "scratch_folder.h"
#include "seqio/frame_files.h"
#include "seqio/obj_format.h"
#include "seqio/sequence_io.h"

namespace animc {
namespace {

namespace fs = std::filesystem;

Result<Mesh> parse(const std::string& text) {
  return parseObj(reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

std::string errorOf(const Status& status) { return status.ok() ? "OK" : status.message(); }
template <class T>
std::string errorOf(const Result<T>& result) {
  return errorOf(result.status());
}

// Five vertices as Blender writes them (with normals, texture coordinates, groups, smoothing
// and materials), a quad and a triangle, in CRLF lines and no newline at the end.
const char kExported[] =
    "# Blender 4.2\r\nmtllib walk.mtl\r\no Body\r\n"
    "v 0.1 -2.5 3\r\nv 1e-7 4 5 1.0\r\nv -6 7.75 8 0.5 0.25 1\r\nv 9 10 11.5\r\nv -12 13 1e20\r\n"
    "vn 0 0 1\r\nvn 0 1 0\r\nvt 0 0\r\nvt 1 0\r\nvt 1 1\r\n"
    "g part\r\ns 1\r\nusemtl skin\r\n"
    "f 1/1/1 2/2/1 3/3/1 4/1/1 # a quad\r\n"
    "l 1 2\r\np 3\r\n"
    "f -5//-1 -2/-3 5\r\n"
    "\t f 1 3 5\t";

TEST(ObjFormat, ReadsWhatExportersWrite) {
  Result<Mesh> mesh = parse(kExported);
  ASSERT_TRUE(mesh.ok()) << errorOf(mesh);
  EXPECT_EQ(mesh.value().positions,
            (std::vector<float>{0.1f, -2.5f, 3, 1e-7f, 4, 5, -6, 7.75f, 8, 9, 10, 11.5f, -12, 13, 1e20f}));
  EXPECT_EQ(mesh.value().topology.vertex_count, 5u);
  // The quad is cut as a fan from its first corner, in the same order for every frame.
  EXPECT_EQ(mesh.value().topology.triangles, (std::vector<Triangle>{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 2, 4}}));
}

TEST(ObjFormat, ErrorsNameTheLine) {
  struct Case {
    std::string text, expected;
  };
  const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::vector<Case> cases = {
      {"v 0 0\n", "line 1: vertex 0 has fewer than 3 coordinates"},
      {"v 0 0 x1\n", "line 1: bad number 'x1'"},
      {"v 0 0 0\nv 0 nan 0\n", "line 2: vertex 1 has a non-finite coordinate"},
      {v3 + "f 1 2 4\n", "line 4: vertex index 4 out of range (3 defined so far)"},
      {v3 + "f 1 2 -4\n", "line 4: vertex index -4 out of range (3 defined so far)"},
      {v3 + "f 0 1 2\n", "line 4: bad vertex index '0'"},
      {v3 + "f 1 2 3.5\n", "line 4: bad vertex index '3.5'"},
      {v3 + "f 1/1 2 3\n", "line 4: texture coordinate index 1 out of range (0 defined so far)"},
      {v3 + "vn 0 0 1\nf 1//2 2 3\n", "line 5: normal index 2 out of range (1 defined so far)"},
      {v3 + "f 1/ 2 3\n", "line 4: bad texture coordinate index ''"},
      {v3 + "f 1// 2 3\n", "line 4: bad normal index ''"},
      {v3 + "vt 0 0\nvn 0 0 1\nf 1/1/1/1 2 3\n", "line 6: bad normal index '1/1'"},
      {v3 + "f 1 2\n", "line 4: a face of 2 vertices (at least 3 needed)"},
      {v3 + "\r\n# only vertices\r\n", "empty mesh (0 triangles)"},
      {"", "empty mesh (0 vertices)"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.text);
    EXPECT_NE(errorOf(parse(c.text)).find(c.expected), std::string::npos) << errorOf(parse(c.text));
  }
}

TEST(ObjFormat, TriangleOriginNamesTheFaceLine) {
  const std::string text = kExported;
  const auto* data = reinterpret_cast<const uint8_t*>(text.data());
  EXPECT_EQ(objTriangleOrigin(data, text.size(), 0), "the face on line 17");
  EXPECT_EQ(objTriangleOrigin(data, text.size(), 1), "the face on line 17");
  EXPECT_EQ(objTriangleOrigin(data, text.size(), 2), "the face on line 20");
  EXPECT_EQ(objTriangleOrigin(data, text.size(), 3), "the face on line 21");
}

class ObjSequenceTest : public testing_support::ScratchFolderTest {
 protected:
  ObjSequenceTest() : ScratchFolderTest("obj") {}
  void writeFile(const std::string& name, const std::string& bytes) const {
    fs::create_directories(fs::path(path(name)).parent_path());
    std::ofstream(path(name), std::ios::binary) << bytes;
  }
  std::string sequenceError(const std::string& input) const {
    auto source = openSequence(input, "");
    if (!source.ok()) return errorOf(source);
    return errorOf(readFrames(*source.value()));
  }
};

TEST_F(ObjSequenceTest, FramesWithOtherFacesNameTheFileAndFaceLine) {
  writeFile("walk/0.obj", kExported);
  writeFile("walk/1.obj", kExported);
  std::string other = kExported;
  other.replace(other.find("f -5//-1 -2/-3 5"), 16, "f -5//-1 -3/-3 5");
  writeFile("walk/2.obj", other);
  EXPECT_NE(sequenceError(path("walk"))
                .find("walk/2.obj (frame 2): face list differs from frame 0 (first at the face on line 20)"),
            std::string::npos)
      << sequenceError(path("walk"));
  writeFile("walk/2.obj", std::string(kExported) + "\nv 1 1 1\n");
  EXPECT_NE(sequenceError(path("walk")).find("walk/2.obj (frame 2): vertex count 6 differs from frame 0 (5)"),
            std::string::npos);
  writeFile("walk/2.obj", "v 0 0 0\nf 1 1 1 1\nv 1 1 1\nf 1 2 9\n");
  EXPECT_NE(sequenceError(path("walk")).find("walk/2.obj: line 4: vertex index 9 out of range"), std::string::npos)
      << sequenceError(path("walk"));
}

// Frames 3..12 as frame_003.obj ... frame_012.obj beside files that do not match.
TEST_F(ObjSequenceTest, NumberedPatterns) {
  for (int f = 3; f <= 12; ++f) {
    std::string text = kExported;
    text.replace(text.find("v 0.1"), 5, "v " + std::to_string(f));
    char name[32];
    std::snprintf(name, sizeof(name), "walk/frame_%03d.obj", f);
    writeFile(name, text);
  }
  writeFile("walk/frame_01.obj", kExported);    // too narrow for %03d
  writeFile("walk/frame_0013.obj", kExported);  // a leading zero past the width
  writeFile("walk/frame_013.obj.bak", kExported);
  writeFile("walk/other_013.obj", kExported);
  auto paths = listNumberedFrames(path("walk/frame_%03d.obj"));
  ASSERT_TRUE(paths.ok()) << errorOf(paths);
  ASSERT_EQ(paths.value().size(), 10u);
  EXPECT_EQ(fs::path(paths.value().front()).filename(), "frame_003.obj");
  EXPECT_EQ(fs::path(paths.value().back()).filename(), "frame_012.obj");

  auto frames = readFrames(*openSequence(path("walk/frame_%03d.obj"), "").value());
  ASSERT_TRUE(frames.ok()) << errorOf(frames);
  ASSERT_EQ(frames.value().size(), 10u);
  EXPECT_EQ(frames.value()[0][0], 3.f);
  EXPECT_EQ(frames.value()[9][0], 12.f);

  writeFile("plain/f7.obj", kExported);
  writeFile("plain/f8.obj", kExported);
  writeFile("plain/f10.obj", kExported);
  writeFile("plain/f08.obj", kExported);  // not how %d writes 8
  EXPECT_EQ(sequenceError(path("plain/f%d.obj")),
            path("plain/f%d.obj") + ": frame 9 is missing (the files run from 7 to 10)");
  fs::remove(path("plain/f10.obj"));
  EXPECT_EQ(listNumberedFrames(path("plain/f%d.obj")).value().size(), 2u);

  EXPECT_NE(sequenceError(path("walk/frame_%3d.obj")).find("one %d or %0Nd"), std::string::npos);
  EXPECT_NE(sequenceError(path("walk/frame_%03d_%d.obj")).find("one %d or %0Nd"), std::string::npos);
  EXPECT_NE(sequenceError(path("walk/frame_%03d.stl")).find("must be .ply, .off or .obj frames"), std::string::npos);
  EXPECT_NE(sequenceError(path("walk/take_%03d.obj")).find("no file matches the pattern"), std::string::npos);
  EXPECT_NE(sequenceError(path("none/f_%d.obj")).find("cannot list the directory"), std::string::npos);
  // A file whose name holds a '%' is that file, not a pattern.
  writeFile("plain/100%.obj", kExported);
  EXPECT_EQ(sequenceError(path("plain/100%.obj")), "OK");
}

TEST_F(ObjSequenceTest, WrittenFramesReadBackExactlyInEveryFrameFileFormat) {
  Mesh mesh = parse(kExported).value();
  for (const SequenceFormatSpec& spec : sequenceFormats()) {
    if (!spec.frame_file) continue;
    SCOPED_TRACE(spec.name);
    const std::string file = path(std::string("one") + spec.extension);
    ASSERT_TRUE(spec.frame_file->write(file, mesh.topology, mesh.positions.data()).ok());
    auto back = readMesh(file);
    ASSERT_TRUE(back.ok()) << errorOf(back);
    EXPECT_EQ(back.value().positions, mesh.positions);
    EXPECT_EQ(back.value().topology.triangles, mesh.topology.triangles);
  }
}

}  // namespace
}  // namespace animc
