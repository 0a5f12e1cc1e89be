// SPDX-License-Identifier: Apache-2.0
#include "codecs/wavelet/bitplane_coder.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "codecs/wavelet/bitplane_contexts.h"
#include "core/simd_math.h"
#include "entropy/range_coder.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

// reconstructCoefficients without branches on the magnitude or the sign (both close to
// random in the low planes): the offset and the zero picked by masks, the sign XORed in, and
// the bit length of k >= 1 read from the exponent of double(k), which is exact.
void reconstructPortable(const uint32_t* k, const uint8_t* negative, size_t n, int q, double scale, double* out,
                         uint8_t* bit_lengths, uint8_t* was_negative) {
  for (size_t i = 0; i < n; ++i) {
    const double dk = double(k[i]);
    const double magnitude = (dk + (k[i] == 1 ? kFreshOffset : kRefinedOffset)) * scale;
    const uint64_t nonzero = 0ull - uint64_t(k[i] != 0);
    uint64_t bits, dk_bits;
    std::memcpy(&bits, &magnitude, sizeof bits);
    std::memcpy(&dk_bits, &dk, sizeof dk_bits);
    bits = (bits & nonzero) ^ (uint64_t(negative[i] != 0) << 63);
    std::memcpy(&out[i], &bits, sizeof bits);
    if (bit_lengths) {
      bit_lengths[i] = uint8_t(((dk_bits >> 52) - 1022 + uint64_t(q)) & nonzero);
      was_negative[i] = negative[i];
    }
  }
}

#if ANIMC_AVX2_PATH
typedef int32_t IntOctet __attribute__((vector_size(32)));
typedef uint8_t ByteQuad __attribute__((vector_size(4)));
typedef uint8_t Bytes16 __attribute__((vector_size(16)));

// Four coefficients at a time, the same operations lane by lane.
ANIMC_TARGET_AVX2 void reconstructAvx2(const uint32_t* k, const uint8_t* negative, size_t n, int q, double scale,
                                       double* out, uint8_t* bit_lengths, uint8_t* was_negative) {
  const Quad fresh = splatQuad(kFreshOffset), refined = splatQuad(kRefinedOffset), scales = splatQuad(scale);
  const IntQuad length_bias = {1022 - q, 1022 - q, 1022 - q, 1022 - q};
  size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    IntQuad kq;
    ByteQuad nq;
    std::memcpy(&kq, k + i, sizeof kq);  // k < 2^31: as signed, the same values
    std::memcpy(&nq, negative + i, sizeof nq);
    const Quad dk = __builtin_convertvector(kq, Quad);
    const QuadMask one = __builtin_convertvector(kq == 1, QuadMask);
    const QuadMask nonzero = __builtin_convertvector(kq != 0, QuadMask);
    const QuadMask sign = __builtin_convertvector(nq != 0, QuadMask) << 63;
    const Quad magnitude = (dk + (one ? fresh : refined)) * scales;
    const QuadMask bits = (QuadMask(magnitude) & nonzero) ^ sign;
    storeQuad(out + i, Quad(bits));
    if (bit_lengths) {
      const IntOctet halves = IntOctet(dk);
      const IntQuad high = __builtin_shufflevector(halves, halves, 1, 3, 5, 7);  // sign and exponent
      const Bytes16 wide = Bytes16(((high >> 20) - length_bias) & (kq != 0));
      const ByteQuad lengths = __builtin_shufflevector(wide, wide, 0, 4, 8, 12);  // the low byte of each
      std::memcpy(bit_lengths + i, &lengths, sizeof lengths);
      std::memcpy(was_negative + i, negative + i, 4);
    }
  }
  reconstructPortable(k + i, negative + i, n - i, q, scale, out + i, bit_lengths ? bit_lengths + i : nullptr,
                      was_negative ? was_negative + i : nullptr);
}
#endif

}  // namespace

void reconstructCoefficients([[maybe_unused]] SimdPath path, const uint32_t* k, const uint8_t* negative, size_t n, int q, double scale, double* out,
                             uint8_t* bit_lengths, uint8_t* was_negative) {
#if ANIMC_AVX2_PATH
  if (useAvx2(path)) return reconstructAvx2(k, negative, n, q, scale, out, bit_lengths, was_negative);
#endif
  reconstructPortable(k, negative, n, q, scale, out, bit_lengths, was_negative);
}


struct BitplaneWorkspace {
  BitplaneContexts models;
  BitplaneState state;
  std::vector<uint8_t> range;
  std::vector<uint64_t> checkpoints;
};

void BitplaneWorkspaceDeleter::operator()(BitplaneWorkspace* w) const { delete w; }
BitplaneWorkspacePtr makeBitplaneWorkspace() { return BitplaneWorkspacePtr(new BitplaneWorkspace()); }

namespace {

constexpr uint8_t kHasCheckpoints = 0x80;
// Worst case of what finish() adds to the committed bytes (cache, a rare 0xFF run, 4 bytes).
constexpr uint64_t kFlushSlack = 6;

uint64_t headerEstimate(int planes, bool checkpoints) {
  return 1 + 3 * 3 + (checkpoints ? 2 * uint64_t(planes) : 0);
}

// The encoder's side of the plane walk: each decision's value comes from the magnitudes.
struct EncoderIo {
  static constexpr bool kEncodes = true;
  RangeEncoder* rc;
  int code(BitModel& m, int bit) {
    rc->encode(m, bit);
    return bit;
  }
  int raw(int bit) {
    rc->encodeRaw(uint32_t(bit), 1);
    return bit;
  }
};

// Holds the decoder by value: the walk copies it into a local for each plane, where its
// state can live in registers. decodeData, not decode: signs and many significance bits are
// close to random, and a branch on them mispredicts often. Refinement bits are raw: no
// branch either way.
struct DecoderIo {
  static constexpr bool kEncodes = false;
  RangeDecoder rc;
  int code(BitModel& m, int) { return rc.decodeData(m); }
  int raw(int) { return int(rc.decodeRaw(1)); }
};

// Local owner when the caller passes no workspace.
struct WorkspaceRef {
  BitplaneWorkspacePtr owned;
  BitplaneWorkspace* ws;
  explicit WorkspaceRef(BitplaneWorkspace* given) : owned(given ? nullptr : makeBitplaneWorkspace()), ws(given ? given : owned.get()) {}
};

}  // namespace

bool fitsBitplanes(const std::vector<double>& values, double step) {
  const double limit = double(kMaxBitplaneMagnitude) * step;
  for (double v : values)
    if (!(std::fabs(v) < limit)) return false;
  return true;
}

void encodeBitplanes(const double* values, const BitplaneLayout& layout,
                     const BitplaneEncodeSettings& settings, std::vector<uint8_t>& out,
                     std::vector<double>& decoded, BitplaneHistory* history,
                     BitplaneWorkspace* workspace) {
  WorkspaceRef ref(workspace);
  BitplaneWorkspace& ws = *ref.ws;
  BitplaneState& s = ws.state;
  s.start(layout, settings.context, settings.path);
  s.quantise(values, settings.step);
  const int top = s.topPlane();
  const int lowest = settings.max_planes > 0 ? std::max(0, top - settings.max_planes) : 0;
  out.push_back(uint8_t(top | (settings.checkpoints ? kHasCheckpoints : 0)));
  if (top == 0) {
    s.finish(0, 0, s.blockCount(), settings.step, decoded, history);
    return;
  }
  const uint64_t header = headerEstimate(top - lowest, settings.checkpoints);
  const uint64_t budget = settings.byte_budget == 0 ? UINT64_MAX
                          : settings.byte_budget > header ? settings.byte_budget - header : 0;
  std::vector<uint8_t>& range = ws.range;
  range.clear();
  ws.checkpoints.clear();
  ws.models.reset(top);
  RangeEncoder rc(range);
  EncoderIo io{&rc};
  const size_t blocks = s.blockCount();
  const size_t forced_stop = settings.last_plane_blocks > 0 ? std::min(settings.last_plane_blocks, blocks) : blocks;
  int planes = 0;
  size_t stop = blocks;
  for (int p = top - 1; p >= lowest && stop == blocks; --p) {
    const size_t end = p == lowest ? forced_stop : blocks;
    const size_t coded = s.codePlane(io, ws.models, p, end,
                                     [&](size_t) { return range.size() + kFlushSlack > budget; });
    if (coded > 0) ++planes;
    if (coded < blocks) stop = coded;
    if (stop == blocks && settings.checkpoints) {  // bytes a decoder needs for this plane
      RangeEncoder probe(rc);
      const size_t before = range.size();
      probe.finish();
      ws.checkpoints.push_back(range.size());
      range.resize(before);
    }
  }
  if (stop == 0) stop = blocks;  // the last plane begun is complete
  rc.finish();
  ByteWriter w;
  w.varint(uint64_t(planes));
  w.varint(stop);
  w.varint(range.size());
  if (settings.checkpoints)
    for (int i = 0; i + 1 < planes; ++i) w.varint(ws.checkpoints[i] - (i ? ws.checkpoints[i - 1] : 0));
  out.insert(out.end(), w.bytes().begin(), w.bytes().end());
  out.insert(out.end(), range.begin(), range.end());
  s.finish(top, planes, stop, settings.step, decoded, history);
}

BitplaneCutPreview::BitplaneCutPreview(SimdPath path, const double* values, const BitplaneLayout& layout,
                                       double step, BitplaneWorkspace* workspace)
    : layout_(layout), step_(step), workspace_(workspace) {
  BitplaneState& s = workspace_->state;
  s.start(layout, nullptr, path);
  s.quantise(values, step);
  planes_ = s.topPlane();
}

void BitplaneCutPreview::decoded(int planes, size_t blocks, std::vector<double>& out) const {
  workspace_->state.preview(std::min(planes, planes_), blocks, step_, out);
}

Status decodeBitplanes(ByteReader& in, const BitplaneLayout& layout,
                       const BitplaneDecodeSettings& settings, std::vector<double>& decoded,
                       int* planes_decoded, BitplaneHistory* history, BitplaneWorkspace* workspace) {
  if (planes_decoded) *planes_decoded = 0;
  ANIMC_ASSIGN_OR_RETURN(uint8_t head, in.u8("Plane_Count"));
  const int top = head & ~kHasCheckpoints;
  const bool has_checkpoints = head & kHasCheckpoints;
  if (top > kMaxBitplanes) return corrupt("bitplanes: plane count " + std::to_string(top) + " above 31");
  WorkspaceRef ref(workspace);
  BitplaneWorkspace& ws = *ref.ws;
  BitplaneState& s = ws.state;
  s.start(layout, settings.context, settings.path);
  const size_t blocks = s.blockCount();
  if (top == 0) {
    s.finish(0, 0, blocks, settings.step, decoded, history);
    return Status();
  }
  ANIMC_ASSIGN_OR_RETURN(uint64_t coded, in.varint("Coded_Planes"));
  ANIMC_ASSIGN_OR_RETURN(uint64_t stop, in.varint("Last_Plane_Stop"));
  ANIMC_ASSIGN_OR_RETURN(uint64_t range_bytes, in.varint("Range_Bytes"));
  if (coded > uint64_t(top) || stop > blocks || (coded > 0 && stop == 0))
    return corrupt("bitplanes: coded planes or stop out of range");
  std::vector<uint64_t>& checkpoints = ws.checkpoints;
  checkpoints.clear();
  for (uint64_t i = 0; has_checkpoints && i + 1 < coded; ++i) {
    ANIMC_ASSIGN_OR_RETURN(uint64_t delta, in.varint("Plane_Checkpoint"));
    const uint64_t at = (i ? checkpoints.back() : 0) + delta;
    if (delta > range_bytes || at > range_bytes) return corrupt("bitplanes: checkpoint beyond the data");
    checkpoints.push_back(at);
  }
  const bool cut = in.remaining() < range_bytes;
  if (!cut && in.remaining() > range_bytes) return corrupt("bitplanes: bytes after the coded data");
  if (cut && !has_checkpoints) return in.truncatedAt("Bitplane_Data");
  int planes = int(coded);
  if (cut) {  // the complete planes the bytes we have vouch for
    planes = 0;
    while (planes < int(checkpoints.size()) && checkpoints[planes] <= in.remaining()) ++planes;
    stop = blocks;
  }
  if (settings.max_planes > 0 && planes > settings.max_planes) {
    planes = settings.max_planes;
    stop = blocks;
  }
  const size_t available = std::min<uint64_t>(in.remaining(), range_bytes);
  DecoderIo io{RangeDecoder(in.cursor(), available)};
  ws.models.reset(top);
  for (int i = 0; i < planes; ++i) {
    const int p = top - 1 - i;
    const size_t end = i + 1 == planes ? size_t(stop) : blocks;
    const auto never = [](size_t) { return false; };
#if ANIMC_AVX2_PATH
    if (useAvx2(settings.path)) {
      s.codePlaneAvx2(io, ws.models, p, end, never);
      continue;
    }
#endif
    s.codePlane(io, ws.models, p, end, never);
  }
  if (!cut && planes == int(coded) && io.rc.overran()) return corrupt("bitplanes: coded data ends early");
  ANIMC_RETURN_IF_ERROR(in.skip(available, "Bitplane_Data"));
  s.finish(top, planes, size_t(stop), settings.step, decoded, history);
  if (planes_decoded) *planes_decoded = planes;
  return Status();
}

}  // namespace animc
