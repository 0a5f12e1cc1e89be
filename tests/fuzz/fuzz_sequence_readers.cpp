// SPDX-License-Identifier: Apache-2.0
// libFuzzer harness: the sequence readers (PLY ascii/binary, OFF, OBJ, PC2, MDD, the .xz
// streaming of point caches, frame folders and .txt frame lists, with and without a mesh) on
// arbitrary bytes, reading every frame. Any Status is fine; a crash, sanitizer report, leak, hang or
// huge allocation is a bug.
//
// Input = 2 control bytes, then one or more files separated by kSeparator:
//   [0] modulo 7, the format: .ply, .off, .pc2, .mdd, .pc2.xz, .mdd.xz, .obj;
//       [0] / 7 modulo 4, the layout:
//         0  one file: frame files (PLY, OFF, OBJ) as a one-frame sequence, point caches with
//            a topology of [1] + 1 vertices and no faces
//         1  frame files: a folder of frames, one file each; caches: a PLY mesh, then the cache
//         2  frame files: a .txt frame list, then the frames it may name (f0.ply, f1.ply, ...
//            beside it); caches: an OFF mesh, then the cache
//         3  frame files: a PLY mesh the frames must match, then a folder of frames;
//            caches: as 1
//   [1] layout 0 point caches: the mesh's vertex count minus 1 (the readers check the cache
//       against it)
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "seqio/mdd_format.h"
#include "seqio/pc2_format.h"
#include "seqio/sequence_io.h"

namespace {

namespace fs = std::filesystem;

constexpr size_t kControlBytes = 2;
constexpr const char* kSuffixes[] = {".ply", ".off", ".pc2", ".mdd", ".pc2.xz", ".mdd.xz", ".obj"};
constexpr int kFormats = 7;
constexpr int kLayouts = 4;

bool isPointCache(int format) { return format >= 2 && format < 6; }
constexpr char kSeparator[] = "#next#";
constexpr size_t kMaxFiles = 8;

struct Part {
  const uint8_t* data;
  size_t size;
};

std::vector<Part> splitFiles(const uint8_t* data, size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  const std::string_view separator(kSeparator);
  std::vector<Part> parts;
  size_t begin = 0;
  while (parts.size() + 1 < kMaxFiles) {
    const size_t end = all.find(separator, begin);
    if (end == std::string_view::npos) break;
    parts.push_back({data + begin, end - begin});
    begin = end + separator.size();
  }
  parts.push_back({data + begin, size - begin});
  return parts;
}

animc::Result<std::unique_ptr<animc::FrameSource>> openOneFile(const std::string& path, const uint8_t* control) {
  const int format = control[0] % kFormats;
  if (!isPointCache(format)) return animc::openSequence(path, "");
  animc::Topology topology;
  topology.vertex_count = uint32_t(control[1]) + 1;
  const bool mdd = format % 2 == 1;
  return mdd ? animc::openMdd(path, topology, "mesh.ply") : animc::openPc2(path, topology, "mesh.ply");
}

// Writes the parts as the layout's files in a fresh scratch folder and opens them; an error
// of the file system is not the readers' and ends the run without one.
animc::Result<std::unique_ptr<animc::FrameSource>> openLayout(const fs::path& dir, int format, int layout,
                                                              const std::vector<Part>& parts) {
  std::error_code error;
  fs::remove_all(dir, error);
  fs::create_directories(dir / "frames", error);
  if (error) return animc::ioError("scratch folder");
  auto write = [&](const fs::path& path, const Part& part) {
    return animc::fuzz::writeScratch(path.string(), part.data, part.size);
  };
  const std::string suffix = kSuffixes[format];
  if (isPointCache(format)) {  // a mesh, then the cache
    const fs::path mesh = dir / (layout == 2 ? "mesh.off" : "mesh.ply"), cache = dir / ("cache" + suffix);
    static const uint8_t kNothing = 0;
    if (!write(mesh, parts[0]) || !write(cache, parts.size() > 1 ? parts[1] : Part{&kNothing, 0}))
      return animc::ioError("scratch file");
    return animc::openSequence(cache.string(), mesh.string());
  }
  size_t first_frame = 0;
  std::string mesh;
  fs::path sequence = dir / "frames";
  if (layout == 2) {
    sequence = dir / "frames" / "list.txt";
    if (!write(sequence, parts[0])) return animc::ioError("scratch file");
    first_frame = 1;
  } else if (layout == 3) {
    mesh = (dir / "mesh.ply").string();
    if (!write(mesh, parts[0])) return animc::ioError("scratch file");
    first_frame = 1;
  }
  for (size_t i = first_frame; i < parts.size(); ++i)
    if (!write(dir / "frames" / ("f" + std::to_string(i - first_frame) + suffix), parts[i]))
      return animc::ioError("scratch file");
  return animc::openSequence(sequence.string(), mesh);
}

void readAll(animc::FrameSource& source) {
  std::vector<float> xyz;
  for (;;) {
    auto more = source.next(xyz);
    if (!more.ok() || !more.value()) return;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kControlBytes) return 0;
  const int format = data[0] % kFormats, layout = data[0] / kFormats % kLayouts;
  animc::Result<std::unique_ptr<animc::FrameSource>> source = animc::ioError("not opened");
  if (layout == 0) {
    const std::string path = animc::fuzz::scratchPath(kSuffixes[format]);
    if (!animc::fuzz::writeScratch(path, data + kControlBytes, size - kControlBytes)) return 0;
    source = openOneFile(path, data);
  } else {
    const std::vector<Part> parts = splitFiles(data + kControlBytes, size - kControlBytes);
    source = openLayout(animc::fuzz::scratchPath(".d"), format, layout, parts);
  }
  if (source.ok()) readAll(*source.value());
  return 0;
}
