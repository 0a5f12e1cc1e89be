// SPDX-License-Identifier: Apache-2.0
#include "seqio/sequence_formats.h"

#include <cctype>

#include "seqio/byte_input.h"
#include "seqio/gltf_writer.h"
#include "seqio/mdd_format.h"
#include "seqio/obj_format.h"
#include "seqio/off_format.h"
#include "seqio/pc2_format.h"
#include "seqio/ply_reader.h"
#include "seqio/ply_writer.h"

namespace animc {
namespace {

const FrameFileCodec kPlyCodec = {parsePly, writePlyFile, nullptr};
const FrameFileCodec kOffCodec = {parseOff, writeOffFile, nullptr};
const FrameFileCodec kObjCodec = {parseObj, writeObjFile, objTriangleOrigin};

const PointCacheCodec kPc2Codec = {openPc2, [](const std::string& path, uint32_t points, int64_t frames, double) {
                                     return createPc2Sink(path, points, frames);  // PC2 has no field for the frame rate
                                   }};
const PointCacheCodec kMddCodec = {openMdd, createMddSink};

const AnimatedMeshCodec kGlbCodec = {createGlbSink};
const AnimatedMeshCodec kGltfCodec = {createGltfSink};

// Output sizes. PLY is binary (floats, then a count byte and 3 ints a triangle); OFF and OBJ
// are ASCII at typical widths of 9-digit floats and indices, every frame with its faces.
uint64_t plyBytes(uint64_t v, uint64_t t, uint64_t f) { return (256 + 12 * v + 13 * t) * f; }
uint64_t offBytes(uint64_t v, uint64_t t, uint64_t f) { return (32 + 30 * v + 24 * t) * f; }
uint64_t objBytes(uint64_t v, uint64_t t, uint64_t f) { return (64 + 40 * v + 26 * t) * f; }
uint64_t pc2Bytes(uint64_t v, uint64_t, uint64_t f) { return 32 + 12 * v * f; }
uint64_t mddBytes(uint64_t v, uint64_t, uint64_t f) { return 8 + (4 + 12 * v) * f; }
// glTF: the faces once, a morph target a frame, and a frame-by-frame weight matrix; the text
// form holds all of it as base64 (4 characters for 3 bytes).
uint64_t gltfBytes(uint64_t v, uint64_t t, uint64_t f) {
  const uint64_t binary = gltfBinaryBytes(v, t, f);
  return binary == kGltfTooLarge ? binary : binary / 3 * 4 + 4096 + 256 * f;
}

const std::vector<SequenceFormatSpec> kFormats = {
    {SequenceFormat::kPly, "ply", ".ply", &kPlyCodec, nullptr, nullptr, false, plyBytes},
    {SequenceFormat::kOff, "off", ".off", &kOffCodec, nullptr, nullptr, false, offBytes},
    {SequenceFormat::kPc2, "pc2", ".pc2", nullptr, &kPc2Codec, nullptr, false, pc2Bytes},
    {SequenceFormat::kMdd, "mdd", ".mdd", nullptr, &kMddCodec, nullptr, true, mddBytes},
    {SequenceFormat::kObj, "obj", ".obj", &kObjCodec, nullptr, nullptr, false, objBytes},
    {SequenceFormat::kGlb, "glb", ".glb", nullptr, nullptr, &kGlbCodec, true, glbBytes},
    {SequenceFormat::kGltf, "gltf", ".gltf", nullptr, nullptr, &kGltfCodec, true, gltfBytes},
};

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

const std::vector<SequenceFormatSpec>& sequenceFormats() { return kFormats; }

const SequenceFormatSpec& formatSpec(SequenceFormat format) { return kFormats[size_t(format)]; }

const SequenceFormatSpec* frameFileFormatOf(const std::string& path) {
  for (const SequenceFormatSpec& spec : kFormats)
    if (spec.frame_file && endsWithNoCase(path, spec.extension)) return &spec;
  return nullptr;
}

const SequenceFormatSpec* pointCacheFormatOf(const std::string& path) {
  for (const SequenceFormatSpec& spec : kFormats)
    if (spec.point_cache &&
        (endsWithNoCase(path, spec.extension) || endsWithNoCase(path, std::string(spec.extension) + ".xz")))
      return &spec;
  return nullptr;
}

Result<SequenceFormat> formatFromName(const std::string& name) {
  std::string lower;
  for (char c : name) lower += char(std::tolower(static_cast<unsigned char>(c)));
  for (const SequenceFormatSpec& spec : kFormats)
    if (lower == spec.name) return spec.format;
  return invalidArgument("unknown sequence format '" + name + "' (expected one of " + formatNames(", ") + ")");
}

std::string formatNames(const char* separator) {
  std::string names;
  for (const SequenceFormatSpec& spec : kFormats) names += std::string(names.empty() ? "" : separator) + spec.name;
  return names;
}

SequenceFormat outputFormatOf(const std::string& path) {
  for (const SequenceFormatSpec& spec : kFormats)
    if (endsWith(path, spec.extension)) return spec.format;
  return SequenceFormat::kPly;
}

namespace {

// "a, b or c"
std::string alternatives(const std::vector<std::string>& items) {
  std::string list;
  for (size_t i = 0; i < items.size(); ++i) list += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  return list;
}

}  // namespace

std::string frameFileExtensionList() {
  std::vector<std::string> extensions;
  for (const SequenceFormatSpec& spec : kFormats)
    if (spec.frame_file) extensions.push_back(spec.extension);
  return alternatives(extensions);
}

std::string pointCacheExtensionList() {
  std::vector<std::string> extensions;
  for (const SequenceFormatSpec& spec : kFormats)
    if (spec.point_cache) extensions.insert(extensions.end(), {spec.extension, std::string(spec.extension) + ".xz"});
  return alternatives(extensions);
}

}  // namespace animc
