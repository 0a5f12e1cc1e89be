// SPDX-License-Identifier: Apache-2.0
// Reading and writing animated-mesh sequences in the interchange formats of
// sequence_formats.h: frame files (PLY, OFF, OBJ: one file per frame) and point caches (PC2,
// MDD, optionally .xz-compressed). Every reader validates what it returns (see mesh_checks.h)
// and every writer writes atomically.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/sequence.h"
#include "seqio/sequence_formats.h"

namespace animc {

// A single mesh in a frame-file format (.ply ascii or binary, either byte order; .off; .obj),
// validated.
Result<Mesh> readMesh(const std::string& path);

// `path`: a point cache (.pc2 / .mdd, optionally .pc2.xz / .mdd.xz, decompressed while
// streaming), or frame files: a single .ply / .off / .obj (one frame), a directory of them
// (natural order of their names: 2 before 10), a numbered pattern such as walk_%04d.obj
// (frame_files.h), or a .txt list with one frame path per line (relative paths are taken
// from the list's directory; blank lines and lines starting with '#' are skipped).
// `mesh_path`: the connectivity, required for point caches; for frame files optional, and
// when given the frames must have its vertex count and face list.
Result<std::unique_ptr<FrameSource>> openSequence(const std::string& path,
                                                  const std::string& mesh_path);

// About how many bytes createSequenceSink(format, topology, frames) writes (frame files
// repeat the faces in every frame, so a small .ams of a dense mesh can expand enormously):
// for refusing an output before writing it.
uint64_t sequenceOutputBytes(SequenceFormat format, const Topology& topology, int64_t frames);

// Every file openSequence(path, mesh_path) reads: the point cache or the frame files (and the
// .txt list naming them), and the mesh. An output must be none of them.
Result<std::vector<std::string>> sequenceInputFiles(const std::string& path,
                                                    const std::string& mesh_path);

// What a sink does with a frame-file output folder that already holds files.
enum class ExistingOutput {
  kRefuse,   // an error: the folder may hold anything, and none of it is the sink's to delete
  kReplace,  // the finished frames replace the folder and everything in it
};

// Point caches: `path` is the file, replaced atomically. Frame files: `path` is a folder (its
// parent must exist) that receives frame_00000.ply, frame_00001.ply, ... (binary
// little-endian PLY, ASCII OFF and OBJ) as a whole at finish() (frame_dir_sink.h).
// `frame_count` must be exactly the number of frames written before finish(); `frame_rate`
// is stored by MDD only.
Result<std::unique_ptr<FrameSink>> createSequenceSink(const std::string& path,
                                                      SequenceFormat format,
                                                      const Topology& topology, double frame_rate,
                                                      int64_t frame_count,
                                                      ExistingOutput existing = ExistingOutput::kRefuse);

}  // namespace animc
