// SPDX-License-Identifier: Apache-2.0
// libFuzzer harness: an .ams stream decoded from memory through the public Decoder, every
// codec, with random access and the wavelet codec's progressive decoding. Any Status is fine; a
// crash, sanitizer report, leak, hang or huge allocation is a bug, and so is a random access
// that gives other bits than the decoding in order (bit 5).
//
// Input = 4 control bytes, then the file:
//   [0] bit 0: repair section CRCs first, so mutations reach the parsers behind them
//       bit 1: progressive decoding with the limits of bytes [2] and [3]
//       bit 2: seek to frame [1] (modulo the frame count) before decoding
//       bit 3: decode the frames as one range through Decoder::frames() on two threads
//              (several groups at once) instead of frame() by frame()
//       bit 4: the file is the start of a stream still arriving: decode the stream of its
//              whole groups (wholeGroupsOf(), as the WebAssembly player does)
//       bit 5: after the frames decoded one by one in order, go back to some of them, last
//              first, each a random access: it must give the same bits (else an abort)
//   [2] max bitplanes (modulo 65; 0 = all)   [3] max payload bytes / 4 (0 = all)
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "animc/animc.h"
#include "container/crc32.h"
#include "container/format.h"

namespace {

using animc::DecoderLimits;

constexpr size_t kControlBytes = 4;
// Decoding stops after this many decoded vertices (frames x vertex count): a legit file may
// ask for far more work than one fuzz input should take, and later frames of a group run the
// same code as the first ones.
constexpr uint64_t kVertexBudget = uint64_t(1) << 16;

// Rewrites each section's CRC (the GRUP CRC skips First_Frame and Frame_Count), walking the
// sections while their lengths fit in the file.
void repairCrcs(std::vector<uint8_t>& file) {
  uint64_t offset = animc::kFileHeaderBytes;
  while (offset + animc::kSectionOverhead <= file.size()) {
    uint64_t length = 0;
    for (int k = 0; k < 8; ++k) length |= uint64_t(file[offset + 4 + k]) << (8 * k);
    if (length > file.size() - offset - animc::kSectionOverhead) return;
    const bool group = std::equal(file.begin() + offset, file.begin() + offset + 4, animc::kTagGroup);
    const uint64_t skip = group && length >= animc::kGroupFieldBytes ? animc::kGroupFieldBytes : 0;
    const uint64_t crc_at = offset + 12 + length;
    const uint32_t crc = animc::crc32Update(0, file.data() + offset + 12 + skip, length - skip);
    for (int k = 0; k < 4; ++k) file[crc_at + k] = uint8_t(crc >> (8 * k));
    offset = crc_at + 4;
  }
}

// Limits small enough that one input cannot allocate much, yet above every seed.
DecoderLimits fuzzLimits() {
  DecoderLimits limits;
  limits.max_vertices = 1 << 16;
  limits.max_triangles = 1 << 17;
  limits.max_frame_bytes = 1 << 22;
  limits.max_vertex_frames = 4 * kVertexBudget;  // bounds the frames a random access skips
  limits.max_multiply_adds = uint64_t(1) << 28;  // a trajectory group's reconstruction
  return limits;
}

void decode(const std::vector<uint8_t>& stream, const uint8_t* control) {
  animc::DecoderOptions options;
  options.limits = fuzzLimits();
  options.threads = 2;
  if (control[0] & 2) {
    options.progressive.max_bitplanes = control[2] % 65;
    options.progressive.max_payload_bytes = uint64_t(control[3]) * 4;
  }
  auto opened = animc::Decoder::openMemory(stream.data(), stream.size(), options);
  if (!opened.ok()) return;
  animc::Decoder& decoder = opened.value();
  const int64_t frames = decoder.info().frames;
  const int64_t first = (control[0] & 4) ? int64_t(control[1]) % frames : 0;
  if (control[0] & 8) {
    const int64_t vertices = std::max<int64_t>(1, decoder.info().vertices);
    const int64_t last = std::min<int64_t>(frames, first + std::max<int64_t>(1, int64_t(kVertexBudget) / vertices));
    std::vector<float> range(3 * size_t(decoder.info().vertices) * size_t(last - first));
    (void)decoder.frames(first, last, range.data());
    return;
  }
  std::vector<float> xyz(3 * size_t(decoder.info().vertices));
  std::vector<std::vector<float>> decoded;  // in order from `first`, for bit 5
  uint64_t work = 0;
  for (int64_t k = first; k < frames && work < kVertexBudget; ++k, work += decoder.info().vertices) {
    if (!decoder.frame(k, xyz.data()).ok()) break;
    if (control[0] & 32) decoded.push_back(xyz);
  }
  // At most 16 random accesses, each decoding at most what the pass in order did.
  const size_t step = std::max<size_t>(1, decoded.size() / 16);
  for (size_t i = decoded.size(); i-- > 0;) {
    if (i % step != 0 && i + 1 != decoded.size()) continue;
    const int64_t k = first + int64_t(i);
    const animc::Status status = decoder.frame(k, xyz.data());
    // Going back into the group re-counts its work from the group's start: a late `first` may
    // pass the fuzzing limit there, where the pass in order, already inside the group, did not.
    if (status.code() == animc::StatusCode::kLimitExceeded) continue;
    const bool same = status.ok() && std::memcmp(xyz.data(), decoded[i].data(), xyz.size() * sizeof(float)) == 0;
    if (!same) {
      std::fprintf(stderr, "frame %lld: a random access does not give the frame decoded in order\n",
                   static_cast<long long>(k));
      std::abort();
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kControlBytes) return 0;
  std::vector<uint8_t> file(data + kControlBytes, data + size);
  if (data[0] & 1) repairCrcs(file);
  if (data[0] & 16) {
    std::vector<uint8_t> whole;
    auto frames = animc::wholeGroupsOf(file.data(), file.size(), animc::memorySink(&whole));
    if (!frames.ok() || frames.value() == 0) return 0;
    file = std::move(whole);
  }
  decode(file, data);
  return 0;
}
