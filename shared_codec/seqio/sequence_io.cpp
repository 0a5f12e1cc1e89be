// SPDX-License-Identifier: Apache-2.0
#include "seqio/sequence_io.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "seqio/byte_input.h"
#include "seqio/frame_dir_sink.h"
#include "seqio/frame_files.h"
#include "seqio/mesh_checks.h"

namespace animc {
namespace {

constexpr int64_t kMaxInt32 = 2147483647;  // PC2 / MDD counts and PLY indices are int32

Result<std::unique_ptr<FrameSource>> openPointCache(const std::string& path, const std::string& mesh_path,
                                                    const PointCacheCodec& codec) {
  if (mesh_path.empty())
    return invalidArgument(path + ": --mesh is required for point-cache input (" + pointCacheExtensionList() +
                           ": they hold no faces)");
  ANIMC_ASSIGN_OR_RETURN(Mesh mesh, readMesh(mesh_path));
  return codec.open(path, mesh.topology, mesh_path);
}

Result<std::vector<FrameFile>> frameFiles(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    ANIMC_ASSIGN_OR_RETURN(std::vector<std::string> paths, listFrameDirectory(path));
    return unlistedFrameFiles(paths);
  }
  if (endsWithNoCase(path, ".txt")) return readFrameList(path);
  if (isFramePattern(path)) {
    ANIMC_ASSIGN_OR_RETURN(std::vector<std::string> paths, listNumberedFrames(path));
    return unlistedFrameFiles(paths);
  }
  if (frameFileFormatOf(path)) return unlistedFrameFiles({path});
  return invalidArgument(path + ": unrecognised input (expected " + frameFileExtensionList() +
                         " frames (one file, a directory, a .txt list or a pattern such as " +
                         "frame_%04d.obj), or a point cache: " + pointCacheExtensionList() + ")");
}

Status checkSinkArguments(const std::string& path, const SequenceFormatSpec& spec, const Topology& topology,
                          double frame_rate, int64_t frame_count) {
  if (frame_count < 1 || frame_count > kMaxInt32)
    return invalidArgument(path + ": cannot write " + std::to_string(frame_count) + " frames");
  if (topology.vertex_count == 0 || topology.vertex_count > kMaxInt32)
    return invalidArgument(path + ": cannot write " + std::to_string(topology.vertex_count) +
                           " vertices");
  if (spec.stores_frame_rate && !(std::isfinite(frame_rate) && frame_rate > 0))
    return invalidArgument(path + ": frame rate must be positive for " + spec.name);
  if (!spec.point_cache) return checkTopology(topology).withContext(path);
  return Status();
}

}  // namespace

Result<Mesh> readMesh(const std::string& path) {
  const SequenceFormatSpec* spec = frameFileFormatOf(path);
  if (!spec) return invalidArgument(path + ": not a " + frameFileExtensionList() + " mesh");
  ANIMC_ASSIGN_OR_RETURN(std::vector<uint8_t> bytes, readWholeFile(path));
  Result<Mesh> mesh = spec->frame_file->parse(bytes.data(), bytes.size());
  if (!mesh.ok()) return mesh.status().withContext(path);
  return mesh;
}

Result<std::unique_ptr<FrameSource>> openSequence(const std::string& path,
                                                  const std::string& mesh_path) {
  if (path.empty()) return invalidArgument("no input sequence given");
  if (const SequenceFormatSpec* cache = pointCacheFormatOf(path))
    return openPointCache(path, mesh_path, *cache->point_cache);
  ANIMC_ASSIGN_OR_RETURN(std::vector<FrameFile> frames, frameFiles(path));
  if (mesh_path.empty()) return openFrameFiles(std::move(frames), nullptr, "");
  ANIMC_ASSIGN_OR_RETURN(Mesh mesh, readMesh(mesh_path));
  return openFrameFiles(std::move(frames), &mesh.topology, mesh_path);
}

uint64_t sequenceOutputBytes(SequenceFormat format, const Topology& topology, int64_t frames) {
  return formatSpec(format).output_bytes(topology.vertex_count, topology.triangles.size(),
                                         uint64_t(std::max<int64_t>(frames, 0)));
}

Result<std::vector<std::string>> sequenceInputFiles(const std::string& path,
                                                    const std::string& mesh_path) {
  std::vector<std::string> files;
  if (pointCacheFormatOf(path)) {
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
  const SequenceFormatSpec& spec = formatSpec(format);
  ANIMC_RETURN_IF_ERROR(checkSinkArguments(path, spec, topology, frame_rate, frame_count));
  if (spec.point_cache) return spec.point_cache->create_sink(path, topology.vertex_count, frame_count, frame_rate);
  if (spec.animated_mesh) return spec.animated_mesh->create_sink(path, topology, frame_count, frame_rate);
  return createFrameDirSink(path, format, topology, frame_count, existing);
}

}  // namespace animc
