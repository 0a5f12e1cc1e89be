#include "codecs/wavelet/bitplane_coder.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "entropy/range_coder.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

constexpr uint8_t kHasCheckpoints = 0x80;
constexpr uint32_t kMaxMagnitude = (1u << kMaxBitplanes) - 1;
// Worst case of what finish() adds to the committed bytes (cache, a rare 0xFF run, 4 bytes).
constexpr uint64_t kFlushSlack = 6;

// Significance models: the odds of becoming significant change sharply from plane to plane
// and between coarse and fine levels, and rise when the vertex's other components or the
// parent already are significant.
constexpr int kNeighbourContexts = 6;
struct SignificanceModels {
  BitModel model[kMaxBitplanes][kBitplaneClasses][kNeighbourContexts];
};

// The state both sides keep per coefficient: the magnitude bits known so far and the sign.
struct CoefficientState {
  std::vector<uint32_t> known;  // magnitude >> (current plane)
  std::vector<uint8_t> negative;
  explicit CoefficientState(size_t count) : known(count, 0), negative(count, 0) {}
};

// The middle of what is still unknown: magnitude in [known, known + 1) * 2^plane steps.
double reconstruct(uint32_t known, bool negative, int plane, double step) {
  if (known == 0) return 0.0;
  const double magnitude = (double(known) + 0.5) * std::ldexp(step, plane);
  return negative ? -magnitude : magnitude;
}

// Plane of coefficient j after `planes` planes from the top, the last stopping before `stop`.
void reconstructAll(const CoefficientState& s, int top, int planes, size_t stop, double step,
                    std::vector<double>& decoded) {
  decoded.assign(s.known.size(), 0.0);
  if (planes == 0) return;
  for (size_t j = 0; j < s.known.size(); ++j) {
    const int received = j < stop ? planes : planes - 1;
    decoded[j] = reconstruct(s.known[j], s.negative[j], top - received, step);
  }
}

int neighbourContext(const std::vector<uint32_t>& known, const BitplaneLayout& layout, size_t j) {
  const size_t group = j - j % 3;
  int siblings = 0;
  for (size_t i = group; i < group + 3; ++i) siblings += i != j && known[i] != 0;
  const uint32_t parent = layout.parents[j];
  const bool parent_significant = parent != kNoParent && known[parent] != 0;
  return 2 * siblings + (parent_significant ? 1 : 0);
}

int bitLength(uint32_t v) { return v == 0 ? 0 : 32 - __builtin_clz(v); }

uint64_t headerEstimate(int planes, bool checkpoints) {
  return 1 + 3 * 3 + (checkpoints ? 2 * uint64_t(planes) : 0);
}

}  // namespace

void encodeBitplanes(const double* values, const BitplaneLayout& layout,
                     const BitplaneEncodeSettings& settings, std::vector<uint8_t>& out,
                     std::vector<double>& decoded) {
  const size_t count = layout.count;
  std::vector<uint32_t> magnitude(count);
  uint32_t largest = 0;
  for (size_t j = 0; j < count; ++j) {
    const double q = std::floor(std::fabs(values[j]) / settings.step);
    magnitude[j] = q < double(kMaxMagnitude) ? uint32_t(q) : kMaxMagnitude;  // NaN -> 0
    largest = std::max(largest, magnitude[j]);
  }
  const int top = bitLength(largest);
  const int lowest = settings.max_planes > 0 ? std::max(0, top - settings.max_planes) : 0;
  out.push_back(uint8_t(top | (settings.checkpoints ? kHasCheckpoints : 0)));
  CoefficientState state(count);
  if (top == 0) {
    decoded.assign(count, 0.0);
    return;
  }
  const uint64_t header = headerEstimate(top - lowest, settings.checkpoints);
  const uint64_t budget = settings.byte_budget == 0 ? UINT64_MAX
                          : settings.byte_budget > header ? settings.byte_budget - header : 0;
  std::vector<uint8_t> range;
  std::vector<uint64_t> checkpoints;
  auto models = std::make_unique<SignificanceModels>();
  RangeEncoder rc(range);
  int planes = 0;
  size_t stop = count;
  for (int p = top - 1; p >= lowest && stop == count; --p) {
    for (size_t j = 0; j < count; ++j) {
      if (range.size() + kFlushSlack > budget) {
        stop = j;
        break;
      }
      if (j == 0) ++planes;
      const int bit = int((magnitude[j] >> p) & 1);
      if (state.known[j] != 0) {
        rc.encodeRaw(uint32_t(bit), 1);
      } else {
        rc.encode(models->model[p][layout.classes[j]][neighbourContext(state.known, layout, j)], bit);
        if (bit) {
          state.negative[j] = values[j] < 0;
          rc.encodeRaw(state.negative[j], 1);
        }
      }
      state.known[j] = (state.known[j] << 1) | uint32_t(bit);
    }
    if (stop == count && settings.checkpoints) {  // bytes a decoder needs for this plane
      RangeEncoder probe(rc);
      const size_t before = range.size();
      probe.finish();
      checkpoints.push_back(range.size());
      range.resize(before);
    }
  }
  if (stop == 0) stop = count;  // the last plane begun is complete
  rc.finish();
  ByteWriter w;
  w.varint(uint64_t(planes));
  w.varint(stop);
  w.varint(range.size());
  if (settings.checkpoints)
    for (int i = 0; i + 1 < planes; ++i) w.varint(checkpoints[i] - (i ? checkpoints[i - 1] : 0));
  out.insert(out.end(), w.bytes().begin(), w.bytes().end());
  out.insert(out.end(), range.begin(), range.end());
  reconstructAll(state, top, planes, stop, settings.step, decoded);
}

Status decodeBitplanes(ByteReader& in, const BitplaneLayout& layout,
                       const BitplaneDecodeSettings& settings, std::vector<double>& decoded,
                       int* planes_decoded) {
  const size_t count = layout.count;
  if (planes_decoded) *planes_decoded = 0;
  ANIMC_ASSIGN_OR_RETURN(uint8_t head, in.u8("Plane_Count"));
  const int top = head & ~kHasCheckpoints;
  const bool has_checkpoints = head & kHasCheckpoints;
  if (top > kMaxBitplanes) return corrupt("bitplanes: plane count " + std::to_string(top) + " above 31");
  CoefficientState state(count);
  if (top == 0) {
    decoded.assign(count, 0.0);
    return Status();
  }
  ANIMC_ASSIGN_OR_RETURN(uint64_t coded, in.varint("Coded_Planes"));
  ANIMC_ASSIGN_OR_RETURN(uint64_t stop, in.varint("Last_Plane_Stop"));
  ANIMC_ASSIGN_OR_RETURN(uint64_t range_bytes, in.varint("Range_Bytes"));
  if (coded > uint64_t(top) || stop > count || (coded > 0 && stop == 0))
    return corrupt("bitplanes: coded planes or stop out of range");
  std::vector<uint64_t> checkpoints;
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
    stop = count;
  }
  if (settings.max_planes > 0 && planes > settings.max_planes) {
    planes = settings.max_planes;
    stop = count;
  }
  const size_t available = std::min<uint64_t>(in.remaining(), range_bytes);
  RangeDecoder rc(in.cursor(), available);
  auto models = std::make_unique<SignificanceModels>();
  for (int i = 0; i < planes; ++i) {
    const int p = top - 1 - i;
    const size_t end = i + 1 == planes ? size_t(stop) : count;
    for (size_t j = 0; j < end; ++j) {
      uint32_t bit;
      if (state.known[j] != 0) {
        bit = rc.decodeRaw(1);
      } else {
        bit = uint32_t(rc.decode(models->model[p][layout.classes[j]][neighbourContext(state.known, layout, j)]));
        if (bit) state.negative[j] = uint8_t(rc.decodeRaw(1));
      }
      state.known[j] = (state.known[j] << 1) | bit;
    }
  }
  if (!cut && planes == int(coded) && rc.overran()) return corrupt("bitplanes: coded data ends early");
  ANIMC_RETURN_IF_ERROR(in.skip(available, "Bitplane_Data"));
  reconstructAll(state, top, planes, size_t(stop), settings.step, decoded);
  if (planes_decoded) *planes_decoded = planes;
  return Status();
}

}  // namespace animc
