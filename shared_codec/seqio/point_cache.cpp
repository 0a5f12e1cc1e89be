// SPDX-License-Identifier: Apache-2.0
#include "seqio/point_cache.h"

#include <new>

#include "core/atomic_file.h"
#include "seqio/endian.h"
#include "seqio/mesh_checks.h"

namespace animc {
namespace {

class PointCacheSource : public FrameSource {
 public:
  PointCacheSource(std::unique_ptr<ByteInput> input, Topology topology, PointCacheLayout layout)
      : input_(std::move(input)), topology_(std::move(topology)), layout_(std::move(layout)) {}

  const Topology& topology() const override { return topology_; }
  int64_t frameCount() const override { return layout_.frame_count; }
  double frameRate() const override { return layout_.frame_rate; }
  std::string where() const override { return layout_.name + " frame " + std::to_string(frame_); }

  Result<bool> next(std::vector<float>& xyz) override {
    if (frame_ == layout_.frame_count) {
      ANIMC_RETURN_IF_ERROR(checkNoTrailingData());
      return false;
    }
    size_t values = size_t(topology_.vertex_count) * 3;
    try {
      xyz.resize(values);
    } catch (const std::bad_alloc&) {
      return limitExceeded(where() + ": out of memory for one frame");
    }
    // Read into the caller's floats and converted there: no second frame-sized buffer.
    uint8_t* bytes = reinterpret_cast<uint8_t*>(xyz.data());
    ANIMC_ASSIGN_OR_RETURN(size_t got, input_->read(bytes, values * 4));
    if (got < values * 4)
      return truncated(layout_.name + ": truncated at frame " + std::to_string(frame_) + " of " +
                       std::to_string(layout_.frame_count));
    decodeInPlace(xyz.data(), values);
    ANIMC_RETURN_IF_ERROR(checkPositions(xyz.data(), topology_.vertex_count).withContext(where()));
    ++frame_;
    return true;
  }

 private:
  // Each value is read before its own 4 bytes are written.
  void decodeInPlace(float* xyz, size_t values) const {
    const uint8_t* in = reinterpret_cast<const uint8_t*>(xyz);
    for (size_t i = 0; i < values; ++i, in += 4)
      xyz[i] = bitsToFloat(layout_.big_endian ? loadBe32(in) : loadLe32(in));
  }

  // Sizes of plain files were checked when opening; a compressed stream is checked here.
  Status checkNoTrailingData() {
    if (input_->size() >= 0 || trailing_checked_) return Status();
    trailing_checked_ = true;
    uint8_t byte;
    ANIMC_ASSIGN_OR_RETURN(size_t got, input_->read(&byte, 1));
    if (got != 0)
      return corrupt(layout_.name + ": data continues after the " +
                     std::to_string(layout_.frame_count) + " frames its header announces");
    return Status();
  }

  std::unique_ptr<ByteInput> input_;
  Topology topology_;
  PointCacheLayout layout_;
  int64_t frame_ = 0;
  bool trailing_checked_ = false;
};

class PointCacheSink : public FrameSink {
 public:
  PointCacheSink(bool big_endian, uint32_t point_count, int64_t frame_count)
      : big_endian_(big_endian), point_count_(point_count), frame_count_(frame_count) {}

  Status open(const std::string& path, const HeaderWriter& write_header) {
    ANIMC_RETURN_IF_ERROR(file_.open(path));
    try {
      bytes_.resize(size_t(point_count_) * 12);
    } catch (const std::bad_alloc&) {
      return limitExceeded(path + ": out of memory for one frame");
    }
    return write_header(file_);
  }

  Status write(const float* xyz) override {
    if (written_ == frame_count_)
      return invalidArgument(file_.path() + ": more frames written than the " +
                             std::to_string(frame_count_) + " announced");
    uint8_t* out = bytes_.data();
    for (size_t i = 0; i < size_t(point_count_) * 3; ++i, out += 4) {
      uint32_t bits = floatToBits(xyz[i]);
      big_endian_ ? storeBe32(out, bits) : storeLe32(out, bits);
    }
    ANIMC_RETURN_IF_ERROR(file_.write(bytes_.data(), bytes_.size()));
    ++written_;
    return Status();
  }

  Status finish() override {
    if (written_ != frame_count_)
      return invalidArgument(file_.path() + ": " + std::to_string(written_) +
                             " frames written but " + std::to_string(frame_count_) + " announced");
    return file_.commit();
  }

 private:
  AtomicFile file_;  // removes the temporary file if finish() never commits
  bool big_endian_;
  uint32_t point_count_;
  int64_t frame_count_;
  int64_t written_ = 0;
  std::vector<uint8_t> bytes_;
};

}  // namespace

std::unique_ptr<FrameSource> makePointCacheSource(std::unique_ptr<ByteInput> input,
                                                  Topology topology, PointCacheLayout layout) {
  return std::make_unique<PointCacheSource>(std::move(input), std::move(topology),
                                            std::move(layout));
}

Status readHeader(ByteInput& input, const std::string& name, void* dst, size_t size) {
  ANIMC_ASSIGN_OR_RETURN(size_t got, input.read(dst, size));
  if (got < size)
    return truncated(name + ": file ends inside its " + std::to_string(size) + "-byte header");
  return Status();
}

Status checkPointCount(const std::string& name, int64_t point_count, const Topology& topology,
                       const std::string& mesh_name) {
  if (point_count != int64_t(topology.vertex_count))
    return badInput(name + ": point count " + std::to_string(point_count) +
                    " differs from the mesh " + mesh_name + " (" +
                    std::to_string(topology.vertex_count) + " vertices)");
  return Status();
}

Status checkPointCacheSize(const ByteInput& input, const std::string& name, uint64_t header_bytes,
                           int64_t frame_count, uint32_t point_count) {
  int64_t size = input.size();
  if (size < 0) return Status();  // compressed: truncation is reported frame by frame
  uint64_t frame_bytes = uint64_t(point_count) * 12;
  if (frame_bytes == 0) return badInput(name + ": the header announces 0 points");
  if (uint64_t(size) < header_bytes)
    return truncated(name + ": truncated before frame 0 of " + std::to_string(frame_count) +
                     " (file holds " + std::to_string(size) + " bytes)");
  uint64_t available = uint64_t(size) - header_bytes;
  uint64_t whole_frames = available / frame_bytes;
  if (whole_frames < uint64_t(frame_count))
    return truncated(name + ": truncated at frame " + std::to_string(whole_frames) + " of " +
                     std::to_string(frame_count) + " (file holds " + std::to_string(size) +
                     " bytes)");
  if (available != uint64_t(frame_count) * frame_bytes)
    return corrupt(name + ": file size " + std::to_string(size) + " does not match its header (" +
                   std::to_string(frame_count) + " frames of " + std::to_string(point_count) +
                   " points need " + std::to_string(header_bytes + frame_count * frame_bytes) +
                   " bytes)");
  return Status();
}

Result<std::unique_ptr<FrameSink>> makePointCacheSink(const std::string& path,
                                                      const HeaderWriter& write_header,
                                                      bool big_endian, uint32_t point_count,
                                                      int64_t frame_count) {
  auto sink = std::make_unique<PointCacheSink>(big_endian, point_count, frame_count);
  ANIMC_RETURN_IF_ERROR(sink->open(path, write_header));
  return std::unique_ptr<FrameSink>(std::move(sink));
}

}  // namespace animc
