// SPDX-License-Identifier: Apache-2.0
#include "seqio/mdd_format.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "seqio/byte_input.h"
#include "seqio/endian.h"
#include "seqio/point_cache.h"

namespace animc {
namespace {

constexpr size_t kTimesPerChunk = 4096;  // times are streamed: a long MDD stays O(points)

// Summary of the times array, enough to tell whether it encodes a constant frame rate.
struct TimeScan {
  int64_t count = 0;
  double first = 0, last = 0, min_step = INFINITY, max_step = -INFINITY;

  void add(double t) {
    if (count > 0) {
      min_step = std::min(min_step, t - last);
      max_step = std::max(max_step, t - last);
    } else {
      first = t;
    }
    last = t;
    ++count;
  }

  // Frames per second when the times are finite, increasing and evenly spaced (within 1%,
  // float32 times lose precision); 25 otherwise (Blender writes frame / fps, others zeros).
  double frameRate() const {
    if (count < 2 || !std::isfinite(first) || !std::isfinite(last) || !(min_step > 0)) return 25.0;
    double mean = (last - first) / double(count - 1);
    if (max_step - min_step > 0.01 * mean) return 25.0;
    double rate = 1.0 / mean;
    // Undo float32 rounding of i / 24 or i / 29.97: keep three decimals.
    rate = std::round(rate * 1000.0) / 1000.0;
    return rate >= 0.001 && rate <= 1e6 ? rate : 25.0;
  }
};

Result<double> scanTimes(ByteInput& input, const std::string& name, int64_t frames) {
  TimeScan scan;
  uint8_t chunk[kTimesPerChunk * 4];
  for (int64_t done = 0; done < frames;) {
    size_t want = size_t(std::min<int64_t>(frames - done, kTimesPerChunk));
    ANIMC_ASSIGN_OR_RETURN(size_t got, input.read(chunk, want * 4));
    if (got < want * 4)
      return truncated(name + ": truncated in the frame times (time " +
                       std::to_string(done + int64_t(got / 4)) + " of " + std::to_string(frames) +
                       ")");
    for (size_t i = 0; i < want; ++i) scan.add(bitsToFloat(loadBe32(chunk + 4 * i)));
    done += int64_t(want);
  }
  return scan.frameRate();
}

Status writeTimes(AtomicFile& file, int64_t frames, double frame_rate) {
  uint8_t chunk[kTimesPerChunk * 4];
  for (int64_t done = 0; done < frames;) {
    size_t count = size_t(std::min<int64_t>(frames - done, kTimesPerChunk));
    for (size_t i = 0; i < count; ++i)
      storeBe32(chunk + 4 * i, floatToBits(float(double(done + int64_t(i)) / frame_rate)));
    ANIMC_RETURN_IF_ERROR(file.write(chunk, count * 4));
    done += int64_t(count);
  }
  return Status();
}

}  // namespace

Result<std::unique_ptr<FrameSource>> openMdd(const std::string& path, const Topology& topology,
                                             const std::string& mesh_name) {
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<ByteInput> input, openByteInput(path));
  uint8_t header[8];
  ANIMC_RETURN_IF_ERROR(readHeader(*input, path, header, sizeof(header)));
  int32_t frames = int32_t(loadBe32(header));
  int32_t points = int32_t(loadBe32(header + 4));
  ANIMC_RETURN_IF_ERROR(checkPointCount(path, points, topology, mesh_name));
  if (frames <= 0)
    return badInput(path + ": header announces " + std::to_string(frames) + " frames");
  uint64_t header_bytes = 8 + 4 * uint64_t(frames);
  ANIMC_RETURN_IF_ERROR(checkPointCacheSize(*input, path, header_bytes, frames, uint32_t(points)));
  PointCacheLayout layout;
  layout.name = path;
  layout.big_endian = true;
  layout.frame_count = frames;
  ANIMC_ASSIGN_OR_RETURN(layout.frame_rate, scanTimes(*input, path, frames));
  return makePointCacheSource(std::move(input), topology, std::move(layout));
}

Result<std::unique_ptr<FrameSink>> createMddSink(const std::string& path, uint32_t point_count,
                                                 int64_t frame_count, double frame_rate) {
  auto write_header = [=](AtomicFile& file) {
    uint8_t counts[8];
    storeBe32(counts, uint32_t(frame_count));
    storeBe32(counts + 4, point_count);
    ANIMC_RETURN_IF_ERROR(file.write(counts, sizeof(counts)));
    return writeTimes(file, frame_count, frame_rate);
  };
  return makePointCacheSink(path, write_header, /*big_endian=*/true, point_count, frame_count);
}

}  // namespace animc
