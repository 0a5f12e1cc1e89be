// SPDX-License-Identifier: Apache-2.0
#include "seqio/pc2_format.h"

#include <cstring>

#include "seqio/byte_input.h"
#include "seqio/endian.h"
#include "seqio/point_cache.h"

namespace animc {
namespace {

constexpr char kMagic[12] = "POINTCACHE2";  // the 12th byte is the terminating NUL
constexpr size_t kHeaderBytes = 32;
constexpr int32_t kVersion = 1;

}  // namespace

Result<std::unique_ptr<FrameSource>> openPc2(const std::string& path, const Topology& topology,
                                             const std::string& mesh_name) {
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<ByteInput> input, openByteInput(path));
  uint8_t header[kHeaderBytes];
  ANIMC_RETURN_IF_ERROR(readHeader(*input, path, header, kHeaderBytes));
  if (std::memcmp(header, kMagic, sizeof(kMagic)) != 0)
    return corrupt(path + ": not a PC2 file (bad magic)");
  int32_t version = int32_t(loadLe32(header + 12));
  if (version != kVersion)
    return unsupported(path + ": PC2 version " + std::to_string(version) + " (only 1 is supported)");
  int32_t points = int32_t(loadLe32(header + 16));
  int32_t samples = int32_t(loadLe32(header + 28));
  ANIMC_RETURN_IF_ERROR(checkPointCount(path, points, topology, mesh_name));
  if (samples <= 0)
    return badInput(path + ": header announces " + std::to_string(samples) + " frames");
  ANIMC_RETURN_IF_ERROR(checkPointCacheSize(*input, path, kHeaderBytes, samples, uint32_t(points)));
  PointCacheLayout layout;
  layout.name = path;
  layout.frame_count = samples;
  // PC2 stores no frames per second: its sample_rate is the step between samples measured in
  // scene frames, and the scene's own rate is not recorded. So report the usual 25 fps.
  layout.frame_rate = 25.0;
  return makePointCacheSource(std::move(input), topology, std::move(layout));
}

Result<std::unique_ptr<FrameSink>> createPc2Sink(const std::string& path, uint32_t point_count,
                                                 int64_t frame_count) {
  std::vector<uint8_t> header(kHeaderBytes);
  std::memcpy(header.data(), kMagic, sizeof(kMagic));
  storeLe32(&header[12], uint32_t(kVersion));
  storeLe32(&header[16], point_count);
  storeLe32(&header[20], floatToBits(0.0f));  // start frame
  storeLe32(&header[24], floatToBits(1.0f));  // sample rate: one sample per frame
  storeLe32(&header[28], uint32_t(frame_count));
  auto write_header = [&header](AtomicFile& file) {
    return file.write(header.data(), header.size());
  };
  return makePointCacheSink(path, write_header, /*big_endian=*/false, point_count, frame_count);
}

}  // namespace animc
