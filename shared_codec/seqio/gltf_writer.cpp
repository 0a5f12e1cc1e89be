// SPDX-License-Identifier: Apache-2.0
#include "seqio/gltf_writer.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <new>
#include <vector>

#include "animc/version.h"
#include "core/atomic_file.h"
#include "seqio/endian.h"

namespace animc {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67;   // "glTF"
constexpr uint32_t kJsonChunk = 0x4E4F534A;  // "JSON"
constexpr uint32_t kBinChunk = 0x004E4942;   // "BIN\0"
constexpr uint64_t kGlbHeaderBytes = 12, kChunkHeaderBytes = 8;
constexpr size_t kReservedNumberChars = 24;  // "-1.1754943508222875e-38" and a spare
// A morph target a frame and an F x F weight matrix: past this, no viewer would play the file,
// and the matrix alone would take 16 GiB.
constexpr uint64_t kMaxFrames = 65536;

// Where each part sits in the BIN buffer: indices, frame 0, one target a frame, then the F + 1
// key times and F + 1 rows of F weights (the last key ends the last frame, which would
// otherwise last no time at all in a player).
struct Layout {
  uint64_t vertices, triangles, frames;
  uint64_t keys() const { return frames + 1; }
  uint64_t positions() const { return 12 * triangles; }
  uint64_t target(uint64_t k) const { return positions() + 12 * vertices * (1 + k); }
  uint64_t times() const { return target(frames); }
  uint64_t weights() const { return times() + 4 * keys(); }
  uint64_t total() const { return weights() + 4 * keys() * frames; }
};

struct Bounds {
  float min[3] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max(),
                  std::numeric_limits<float>::max()};
  float max[3] = {std::numeric_limits<float>::lowest(), std::numeric_limits<float>::lowest(),
                  std::numeric_limits<float>::lowest()};
  void add(const float* xyz, size_t points) {
    for (size_t i = 0; i < 3 * points; ++i) {
      min[i % 3] = std::min(min[i % 3], xyz[i]);
      max[i % 3] = std::max(max[i % 3], xyz[i]);
    }
  }
};

// A bound as the shortest decimal of the float's exact value (the validator compares declared
// bounds with the data), or, for sizing the reserved JSON chunk, the most room one can take.
void appendBound(std::string& out, float value, bool reserve) {
  if (reserve) {
    out.append(kReservedNumberChars, '0');
    return;
  }
  char text[40];
  auto result = std::to_chars(text, text + sizeof(text), double(value));
  out.append(text, result.ptr);
}

void appendVec3(std::string& out, const char* key, const float* v, bool reserve) {
  out += std::string(",\"") + key + "\":[";
  for (int axis = 0; axis < 3; ++axis) {
    if (axis) out += ',';
    appendBound(out, v[axis], reserve);
  }
  out += ']';
}

std::string decimal(uint64_t value) { return std::to_string(value); }

void appendAccessors(std::string& out, const Layout& layout, const std::vector<Bounds>& bounds, float last_time,
                     bool reserve) {
  out += "\"accessors\":[{\"bufferView\":0,\"componentType\":5125,\"count\":" + decimal(3 * layout.triangles) +
         ",\"type\":\"SCALAR\"}";
  for (uint64_t k = 0; k <= layout.frames; ++k) {  // frame 0, then the targets
    const uint64_t offset = k == 0 ? 0 : layout.target(k - 1) - layout.positions();
    out += ",{\"bufferView\":1,\"byteOffset\":" + decimal(offset) +
           ",\"componentType\":5126,\"count\":" + decimal(layout.vertices) + ",\"type\":\"VEC3\"";
    appendVec3(out, "min", bounds[k].min, reserve);
    appendVec3(out, "max", bounds[k].max, reserve);
    out += '}';
  }
  out += ",{\"bufferView\":2,\"componentType\":5126,\"count\":" + decimal(layout.keys()) +
         ",\"type\":\"SCALAR\",\"min\":[0],\"max\":[";
  appendBound(out, last_time, reserve);
  out += "]},{\"bufferView\":2,\"byteOffset\":" + decimal(4 * layout.keys()) +
         ",\"componentType\":5126,\"count\":" + decimal(layout.keys() * layout.frames) + ",\"type\":\"SCALAR\"}]";
}

// Everything but the buffer: the scene, the mesh and its targets, the animation, the views
// and the accessors, as members of the top-level object (no braces).
std::string documentBody(const Layout& layout, const std::vector<Bounds>& bounds, float last_time, bool reserve) {
  const uint64_t f = layout.frames;
  std::string out =
      "\"asset\":{\"version\":\"2.0\",\"generator\":\"animcompress " ANIMC_VERSION_STRING
      "\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0,\"name\":\"animation\"}],"
      "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":1},\"indices\":0,\"mode\":4,\"targets\":[";
  for (uint64_t k = 0; k < f; ++k) out += (k ? ",{\"POSITION\":" : "{\"POSITION\":") + decimal(2 + k) + "}";
  out += "]}],\"extras\":{\"targetNames\":[";
  char name[32];
  for (uint64_t k = 0; k < f; ++k) {
    std::snprintf(name, sizeof(name), "%s\"frame_%05llu\"", k ? "," : "", static_cast<unsigned long long>(k));
    out += name;
  }
  out += "]}}],\"animations\":[{\"name\":\"frames\",\"samplers\":[{\"input\":" + decimal(2 + f) +
         ",\"output\":" + decimal(3 + f) +
         ",\"interpolation\":\"STEP\"}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0," +
         "\"path\":\"weights\"}}]}],\"bufferViews\":[{\"buffer\":0,\"byteLength\":" + decimal(layout.positions()) +
         ",\"target\":34963},{\"buffer\":0,\"byteOffset\":" + decimal(layout.positions()) +
         ",\"byteLength\":" + decimal(layout.times() - layout.positions()) +
         ",\"byteStride\":12,\"target\":34962},{\"buffer\":0,\"byteOffset\":" + decimal(layout.times()) +
         ",\"byteLength\":" + decimal(layout.total() - layout.times()) + "}],";
  appendAccessors(out, layout, bounds, last_time, reserve);
  return out;
}

// Standard base64 of a byte stream written in pieces.
class Base64Writer {
 public:
  explicit Base64Writer(AtomicFile& file) : file_(file) {}
  Status write(const uint8_t* data, size_t size) {
    text_.clear();
    for (size_t i = 0; i < size; ++i) {
      pending_[pending_size_++] = data[i];
      if (pending_size_ == 3) encodePending();
    }
    return file_.write(text_.data(), text_.size());
  }
  Status finish() {
    text_.clear();
    if (pending_size_ > 0) {
      const size_t used = pending_size_;
      while (pending_size_ < 3) pending_[pending_size_++] = 0;
      encodePending();
      text_.replace(text_.size() - (3 - used), 3 - used, 3 - used, '=');
    }
    return file_.write(text_.data(), text_.size());
  }

 private:
  void encodePending() {
    static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const uint32_t bits = uint32_t(pending_[0]) << 16 | uint32_t(pending_[1]) << 8 | pending_[2];
    for (int shift = 18; shift >= 0; shift -= 6) text_ += kAlphabet[(bits >> shift) & 63];
    pending_size_ = 0;
  }
  AtomicFile& file_;
  uint8_t pending_[3] = {0, 0, 0};
  size_t pending_size_ = 0;
  std::string text_;
};

class GltfSink : public FrameSink {
 public:
  GltfSink(std::string path, const Topology& topology, int64_t frame_count, double frame_rate, bool binary)
      : path_(std::move(path)), layout_{topology.vertex_count, topology.triangles.size(), uint64_t(frame_count)},
        frame_rate_(frame_rate), binary_(binary), bounds_(size_t(frame_count) + 1), base64_(file_) {}

  Status open(const Topology& topology) {
    ANIMC_RETURN_IF_ERROR(file_.open(path_));
    if (binary_) {
      json_bytes_ = reservedJsonBytes();
      const uint64_t total = kGlbHeaderBytes + 2 * kChunkHeaderBytes + json_bytes_ + layout_.total();
      if (total > std::numeric_limits<uint32_t>::max())
        return limitExceeded(path_ + ": a .glb holds at most 4 GiB and these frames need " + decimal(total) +
                             " bytes (decode fewer frames, or write --format gltf)");
      uint8_t head[kGlbHeaderBytes + kChunkHeaderBytes];
      storeLe32(head, kGlbMagic);
      storeLe32(head + 4, 2);
      storeLe32(head + 8, uint32_t(total));
      storeLe32(head + 12, uint32_t(json_bytes_));
      storeLe32(head + 16, kJsonChunk);
      ANIMC_RETURN_IF_ERROR(file_.write(head, sizeof(head)));
      const std::string spaces(json_bytes_, ' ');  // the JSON comes at finish()
      ANIMC_RETURN_IF_ERROR(file_.write(spaces.data(), spaces.size()));
      uint8_t bin[kChunkHeaderBytes];
      storeLe32(bin, uint32_t(layout_.total()));
      storeLe32(bin + 4, kBinChunk);
      ANIMC_RETURN_IF_ERROR(file_.write(bin, sizeof(bin)));
    } else {
      const std::string head = "{\"buffers\":[{\"byteLength\":" + decimal(layout_.total()) +
                               ",\"uri\":\"data:application/octet-stream;base64,";
      ANIMC_RETURN_IF_ERROR(file_.write(head.data(), head.size()));
    }
    std::vector<uint8_t> indices(size_t(layout_.positions()));
    for (size_t t = 0; t < topology.triangles.size(); ++t)
      for (int c = 0; c < 3; ++c) storeLe32(&indices[12 * t + 4 * c], topology.triangles[t][c]);
    return emit(indices.data(), indices.size());
  }

  Status write(const float* xyz) override {
    if (written_ == layout_.frames)
      return invalidArgument(path_ + ": more frames written than the " + decimal(layout_.frames) + " announced");
    const size_t values = 3 * size_t(layout_.vertices);
    if (written_ == 0) {
      base_.assign(xyz, xyz + values);
      bounds_[0].add(xyz, layout_.vertices);
      ANIMC_RETURN_IF_ERROR(emitFloats(xyz, values));
    }
    displacement_.resize(values);
    for (size_t i = 0; i < values; ++i) displacement_[i] = xyz[i] - base_[i];
    bounds_[1 + written_].add(displacement_.data(), layout_.vertices);
    ANIMC_RETURN_IF_ERROR(emitFloats(displacement_.data(), values));
    ++written_;
    return Status();
  }

  Status finish() override {
    if (written_ != layout_.frames)
      return invalidArgument(path_ + ": " + decimal(written_) + " frames written but " + decimal(layout_.frames) +
                             " announced");
    std::vector<float> row(size_t(layout_.keys()));
    for (uint64_t k = 0; k < layout_.keys(); ++k) row[k] = keyTime(k);
    const float last_time = row.back();
    ANIMC_RETURN_IF_ERROR(emitFloats(row.data(), row.size()));
    row.resize(size_t(layout_.frames));
    for (uint64_t k = 0; k < layout_.keys(); ++k) {  // from key k on, target k alone (the last again)
      std::fill(row.begin(), row.end(), 0.f);
      row[std::min(k, layout_.frames - 1)] = 1.f;
      ANIMC_RETURN_IF_ERROR(emitFloats(row.data(), row.size()));
    }
    const std::string body = documentBody(layout_, bounds_, last_time, /*reserve=*/false);
    if (binary_) {
      std::string json = "{" + body + ",\"buffers\":[{\"byteLength\":" + decimal(layout_.total()) + "}]}";
      json.resize(json_bytes_, ' ');
      ANIMC_RETURN_IF_ERROR(file_.seek(kGlbHeaderBytes + kChunkHeaderBytes));
      ANIMC_RETURN_IF_ERROR(file_.write(json.data(), json.size()));
    } else {
      ANIMC_RETURN_IF_ERROR(base64_.finish());
      const std::string tail = "\"}]," + body + "}\n";
      ANIMC_RETURN_IF_ERROR(file_.write(tail.data(), tail.size()));
    }
    return file_.commit();
  }

 private:
  // Frame k's key time: k / rate rounded down to a float, so that a player asked for exactly
  // k / rate (in double) is at or past the key and shows frame k, not frame k - 1.
  float keyTime(uint64_t k) const {
    const double exact = double(k) / frame_rate_;
    const float time = float(exact);
    return double(time) > exact ? std::nextafter(time, 0.f) : time;
  }

  // The JSON at its longest, rounded up to the 4 bytes a chunk is aligned to.
  uint64_t reservedJsonBytes() const {
    const std::string body = documentBody(layout_, bounds_, 0.f, /*reserve=*/true);
    const uint64_t bytes = 2 + body.size() + std::string(",\"buffers\":[{\"byteLength\":}]").size() + 20;
    return (bytes + 3) / 4 * 4;
  }
  Status emit(const uint8_t* data, size_t size) {
    return binary_ ? file_.write(data, size) : base64_.write(data, size);
  }
  Status emitFloats(const float* values, size_t count) {
    bytes_.resize(4 * count);
    for (size_t i = 0; i < count; ++i) storeLe32(&bytes_[4 * i], floatToBits(values[i]));
    return emit(bytes_.data(), bytes_.size());
  }

  std::string path_;
  Layout layout_;
  double frame_rate_;
  bool binary_;
  std::vector<Bounds> bounds_;  // frame 0's positions, then each target's displacements
  AtomicFile file_;
  Base64Writer base64_;
  uint64_t json_bytes_ = 0;
  uint64_t written_ = 0;
  std::vector<float> base_, displacement_;
  std::vector<uint8_t> bytes_;
};

Result<std::unique_ptr<FrameSink>> createSink(const std::string& path, const Topology& topology, int64_t frame_count,
                                              double frame_rate, bool binary) {
  if (uint64_t(frame_count) > kMaxFrames)
    return invalidArgument(path + ": glTF output holds a morph target per frame, at most " + decimal(kMaxFrames) +
                           " (decode a range with --frames)");
  try {
    auto sink = std::make_unique<GltfSink>(path, topology, frame_count, frame_rate, binary);
    ANIMC_RETURN_IF_ERROR(sink->open(topology));
    return std::unique_ptr<FrameSink>(std::move(sink));
  } catch (const std::bad_alloc&) {
    return limitExceeded(path + ": out of memory preparing the glTF output");
  }
}

}  // namespace

Result<std::unique_ptr<FrameSink>> createGlbSink(const std::string& path, const Topology& topology, int64_t frame_count,
                                                 double frame_rate) {
  return createSink(path, topology, frame_count, frame_rate, /*binary=*/true);
}

Result<std::unique_ptr<FrameSink>> createGltfSink(const std::string& path, const Topology& topology,
                                                  int64_t frame_count, double frame_rate) {
  return createSink(path, topology, frame_count, frame_rate, /*binary=*/false);
}

uint64_t gltfBinaryBytes(uint64_t vertices, uint64_t triangles, uint64_t frames) {
  if (frames > kMaxFrames) return kGltfTooLarge;  // F^2 would overflow long before the counts do
  return Layout{vertices, triangles, frames}.total();
}

uint64_t glbBytes(uint64_t vertices, uint64_t triangles, uint64_t frames) {
  const uint64_t binary = gltfBinaryBytes(vertices, triangles, frames);
  // The JSON: about 2 * 3 * 24 characters of bounds and 100 of accessor a frame, and a name.
  return binary == kGltfTooLarge ? binary : 4096 + 280 * frames + binary;
}

}  // namespace animc
