// SPDX-License-Identifier: Apache-2.0
#include "seqio/sequence_io.h"

#include <cctype>
#include <cmath>
#include <filesystem>

#include "seqio/byte_input.h"
#include "seqio/frame_dir_sink.h"
#include "seqio/frame_files.h"
#include "seqio/mdd_format.h"
#include "seqio/mesh_checks.h"
#include "seqio/off_format.h"
#include "seqio/pc2_format.h"
#include "seqio/ply_reader.h"

namespace animc {
namespace {

constexpr int64_t kMaxInt32 = 2147483647;  // PC2 / MDD counts and PLY indices are int32

bool isPointCache(const std::string& path, const char* extension) {
  return endsWithNoCase(path, extension) || endsWithNoCase(path, std::string(extension) + ".xz");
}

Result<std::unique_ptr<FrameSource>> openPointCache(const std::string& path,
                                                    const std::string& mesh_path, bool mdd) {
  if (mesh_path.empty())
    return invalidArgument(path + ": --mesh is required for PC2/MDD input (they hold no faces)");
  ANIMC_ASSIGN_OR_RETURN(Mesh mesh, readMesh(mesh_path));
  return mdd ? openMdd(path, mesh.topology, mesh_path) : openPc2(path, mesh.topology, mesh_path);
}

Result<std::vector<FrameFile>> frameFiles(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    ANIMC_ASSIGN_OR_RETURN(std::vector<std::string> paths, listFrameDirectory(path));
    return unlistedFrameFiles(paths);
  }
  if (endsWithNoCase(path, ".txt")) return readFrameList(path);
  if (endsWithNoCase(path, ".ply") || endsWithNoCase(path, ".off"))
    return unlistedFrameFiles({path});
  return invalidArgument(path + ": unrecognised input (expected .ply, .off, .pc2, .mdd, " +
                         ".pc2.xz, .mdd.xz, a directory of frames or a .txt list)");
}

Status checkSinkArguments(const std::string& path, SequenceFormat format, const Topology& topology,
                          double frame_rate, int64_t frame_count) {
  if (frame_count < 1 || frame_count > kMaxInt32)
    return invalidArgument(path + ": cannot write " + std::to_string(frame_count) + " frames");
  if (topology.vertex_count == 0 || topology.vertex_count > kMaxInt32)
    return invalidArgument(path + ": cannot write " + std::to_string(topology.vertex_count) +
                           " vertices");
  if (format == SequenceFormat::kMdd && !(std::isfinite(frame_rate) && frame_rate > 0))
    return invalidArgument(path + ": frame rate must be positive for MDD");
  if (format == SequenceFormat::kPly || format == SequenceFormat::kOff)
    return checkTopology(topology).withContext(path);
  return Status();
}

}  // namespace

Result<SequenceFormat> formatFromName(const std::string& name) {
  std::string lower;
  for (char c : name) lower += char(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "ply") return SequenceFormat::kPly;
  if (lower == "off") return SequenceFormat::kOff;
  if (lower == "pc2") return SequenceFormat::kPc2;
  if (lower == "mdd") return SequenceFormat::kMdd;
  return invalidArgument("unknown sequence format '" + name + "' (expected ply, off, pc2 or mdd)");
}

Result<Mesh> readMesh(const std::string& path) {
  bool ply = endsWithNoCase(path, ".ply");
  if (!ply && !endsWithNoCase(path, ".off"))
    return invalidArgument(path + ": not a .ply or .off mesh");
  ANIMC_ASSIGN_OR_RETURN(std::vector<uint8_t> bytes, readWholeFile(path));
  Result<Mesh> mesh =
      ply ? parsePly(bytes.data(), bytes.size()) : parseOff(bytes.data(), bytes.size());
  if (!mesh.ok()) return mesh.status().withContext(path);
  return mesh;
}

Result<std::unique_ptr<FrameSource>> openSequence(const std::string& path,
                                                  const std::string& mesh_path) {
  if (path.empty()) return invalidArgument("no input sequence given");
  if (isPointCache(path, ".pc2")) return openPointCache(path, mesh_path, /*mdd=*/false);
  if (isPointCache(path, ".mdd")) return openPointCache(path, mesh_path, /*mdd=*/true);
  ANIMC_ASSIGN_OR_RETURN(std::vector<FrameFile> frames, frameFiles(path));
  if (mesh_path.empty()) return openFrameFiles(std::move(frames), nullptr, "");
  ANIMC_ASSIGN_OR_RETURN(Mesh mesh, readMesh(mesh_path));
  return openFrameFiles(std::move(frames), &mesh.topology, mesh_path);
}

uint64_t sequenceOutputBytes(SequenceFormat format, const Topology& topology, int64_t frames) {
  const uint64_t n = topology.vertex_count, t = topology.triangles.size(), f = uint64_t(std::max<int64_t>(frames, 0));
  switch (format) {
    case SequenceFormat::kPc2: return 32 + 12 * n * f;
    case SequenceFormat::kMdd: return 8 + (4 + 12 * n) * f;
    case SequenceFormat::kPly: return (256 + 12 * n + 13 * t) * f;  // binary: floats, then count + 3 ints
    case SequenceFormat::kOff: return (32 + 30 * n + 24 * t) * f;   // ASCII: typical widths of %g and indices
  }
  return 0;
}

Result<std::vector<std::string>> sequenceInputFiles(const std::string& path,
                                                    const std::string& mesh_path) {
  std::vector<std::string> files;
  if (isPointCache(path, ".pc2") || isPointCache(path, ".mdd")) {
    files.push_back(path);
  } else {
    ANIMC_ASSIGN_OR_RETURN(std::vector<FrameFile> frames, frameFiles(path));
    for (const FrameFile& frame : frames) files.push_back(frame.path);
    if (endsWithNoCase(path, ".txt")) files.push_back(path);
  }
  if (!mesh_path.empty()) files.push_back(mesh_path);
  return files;
}

Result<std::unique_ptr<FrameSink>> createSequenceSink(const std::string& path,
                                                      SequenceFormat format,
                                                      const Topology& topology, double frame_rate,
                                                      int64_t frame_count, ExistingOutput existing) {
  ANIMC_RETURN_IF_ERROR(checkSinkArguments(path, format, topology, frame_rate, frame_count));
  switch (format) {
    case SequenceFormat::kPc2:
      return createPc2Sink(path, topology.vertex_count, frame_count);
    case SequenceFormat::kMdd:
      return createMddSink(path, topology.vertex_count, frame_count, frame_rate);
    case SequenceFormat::kPly:
    case SequenceFormat::kOff:
      return createFrameDirSink(path, format, topology, frame_count, existing);
  }
  return invalidArgument(path + ": unknown output format");
}

}  // namespace animc
