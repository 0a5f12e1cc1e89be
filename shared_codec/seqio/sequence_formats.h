// SPDX-License-Identifier: Apache-2.0
// The sequence formats, one row each: what a format is called, the extension its files carry,
// how one of its files is read or written, and about how many bytes it takes. Everything that
// opens or writes a sequence (sequence_io.h, frame_files.h, frame_dir_sink.h, the CLI's
// --format) asks this table, so a format is added here and in its own reader and writer.
#pragma once
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/sequence.h"

namespace animc {

// The on-disk formats (the values are not stored anywhere; the order is the table's).
enum class SequenceFormat { kPly, kOff, kPc2, kMdd, kObj, kGlb, kGltf };

// One mesh per file: a sequence is a folder, a .txt list or a numbered pattern of them.
struct FrameFileCodec {
  // Parses a whole file held in memory; messages name the line (or offset) but not the file.
  Result<Mesh> (*parse)(const uint8_t* data, size_t size);
  // Writes atomically, every float exactly.
  Status (*write)(const std::string& path, const Topology& topology, const float* xyz);
  // Where triangle `t` of the parsed file came from ("face 7, line 12"), for messages about a
  // frame whose faces differ; null when triangles are all the file says.
  std::string (*triangle_origin)(const uint8_t* data, size_t size, size_t t);
};

// Positions only, every frame in one file (optionally .xz), the faces from a separate mesh.
struct PointCacheCodec {
  // `mesh_name` names the mesh the topology came from, in messages.
  Result<std::unique_ptr<FrameSource>> (*open)(const std::string& path, const Topology& topology,
                                               const std::string& mesh_name);
  // `frame_rate` is stored where the format has room for it.
  Result<std::unique_ptr<FrameSink>> (*create_sink)(const std::string& path, uint32_t point_count, int64_t frame_count,
                                                    double frame_rate);
};

// The whole animation in one file, connectivity included, for viewers (glTF): written only.
struct AnimatedMeshCodec {
  Result<std::unique_ptr<FrameSink>> (*create_sink)(const std::string& path, const Topology& topology,
                                                    int64_t frame_count, double frame_rate);
};

struct SequenceFormatSpec {
  SequenceFormat format;
  const char* name;                  // as --format takes it: "ply"
  const char* extension;             // ".ply" (point caches also take it followed by ".xz")
  const FrameFileCodec* frame_file;  // exactly one of these three is set
  const PointCacheCodec* point_cache;
  const AnimatedMeshCodec* animated_mesh;
  bool stores_frame_rate;  // a writer then needs a positive, finite rate
  // About how many bytes `frames` frames of the mesh take in this format.
  uint64_t (*output_bytes)(uint64_t vertices, uint64_t triangles, uint64_t frames);
};

// Every format, in the order of SequenceFormat.
const std::vector<SequenceFormatSpec>& sequenceFormats();
const SequenceFormatSpec& formatSpec(SequenceFormat format);

// The frame-file format whose extension `path` ends with (any case), or null.
const SequenceFormatSpec* frameFileFormatOf(const std::string& path);
// The point-cache format `path` is (".pc2", ".pc2.xz", ... in any case), or null.
const SequenceFormatSpec* pointCacheFormatOf(const std::string& path);

// "ply", "off", ... (any case), for --format.
Result<SequenceFormat> formatFromName(const std::string& name);
// The format an output path asks for by its extension (frame-file formats name a folder,
// so anything else is the default, PLY frames).
SequenceFormat outputFormatOf(const std::string& path);

// "ply|off|pc2|mdd|obj" with "|" as `separator`: every format's name, for usage lines.
std::string formatNames(const char* separator);
// ".ply, .off or .obj": the frame-file extensions, for messages.
std::string frameFileExtensionList();
// ".pc2, .pc2.xz, .mdd or .mdd.xz": the point caches' names, for messages.
std::string pointCacheExtensionList();

}  // namespace animc
