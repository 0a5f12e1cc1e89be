// SPDX-License-Identifier: Apache-2.0
#include "codecs/common/static_position_coder.h"

#include <algorithm>
#include <cmath>

#include "core/large_memory.h"
#include "entropy/integer_coder.h"
#include "io/byte_writer.h"

namespace animc {
namespace {

constexpr int kContexts = 3;  // by the size of the previous residual on the same axis
using IFrameModel = IntegerModel<kContexts>;

int contextOf(int64_t previous) {
  const int64_t m = previous < 0 ? -previous : previous;
  return m == 0 ? 0 : (m < 4 ? 1 : 2);
}

// Grid indices beyond this cannot come from a valid encoder (see encode()).
constexpr double kMaxGridIndex = 1u << 30;

}  // namespace

const VertexAdjacency& StaticPositionCoder::adjacency() const {
  if (!adjacency_) adjacency_ = std::make_unique<const VertexAdjacency>(topology_, VertexAdjacency::Neighbours::kLower);
  return *adjacency_;
}

void StaticPositionCoder::predict(const VertexAdjacency& adjacency, const std::vector<int64_t>& q, uint32_t v,
                                  int64_t pred[3]) const {
  // Rounded mean of the neighbours already decoded (lower index); else the previous vertex.
  int64_t sum[3] = {0, 0, 0};
  int64_t n = 0;
  for (const uint32_t* u = adjacency.begin(v); u != adjacency.end(v); ++u, ++n)
    for (int a = 0; a < 3; ++a) sum[a] += q[3 * size_t(*u) + a];
  for (int a = 0; a < 3; ++a) {
    if (n == 0) pred[a] = v > 0 ? q[3 * size_t(v - 1) + a] : 0;
    else pred[a] = (sum[a] >= 0 ? sum[a] + n / 2 : sum[a] - n / 2) / n;
  }
}

void StaticPositionCoder::encode(const std::vector<double>& xyz, double step, std::vector<uint8_t>& out,
                         std::vector<double>& recon) const {
  double min[3];
  for (int a = 0; a < 3; ++a) min[a] = xyz.empty() ? 0.0 : xyz[a];
  for (size_t i = 0; i < xyz.size(); i += 3)
    for (int a = 0; a < 3; ++a) min[a] = std::min(min[a], xyz[i + a]);
  ByteWriter header;
  for (double m : min) header.f64(m);
  header.f64(step);
  out.insert(out.end(), header.bytes().begin(), header.bytes().end());

  std::vector<int64_t> q;
  resizeWithHugePages(q, xyz.size());
  for (size_t i = 0; i < xyz.size(); ++i)
    q[i] = int64_t(std::llround(std::min((xyz[i] - min[i % 3]) / step, kMaxGridIndex)));
  IFrameModel model;
  RangeEncoder rc(out);
  int64_t previous[3] = {0, 0, 0};
  const VertexAdjacency& rows = adjacency();
  for (uint32_t v = 0; v < topology_.vertex_count; ++v) {
    int64_t pred[3];
    predict(rows, q, v, pred);
    for (int a = 0; a < 3; ++a) {
      const int64_t r = q[3 * size_t(v) + a] - pred[a];
      encodeInt(rc, model, contextOf(previous[a]), r);
      previous[a] = r;
    }
  }
  rc.finish();
  resizeWithHugePages(recon, xyz.size());
  for (size_t i = 0; i < xyz.size(); ++i) recon[i] = min[i % 3] + double(q[i]) * step;
}

Status StaticPositionCoder::decode(ByteReader& in, std::vector<double>& recon) const {
  double min[3];
  for (double& m : min) {
    ANIMC_ASSIGN_OR_RETURN(m, in.f64("IFrame_Min"));
    if (!std::isfinite(m) || std::fabs(m) > 1e30) return corrupt("intra frame: corner out of range");
  }
  ANIMC_ASSIGN_OR_RETURN(double step, in.f64("IFrame_Step"));
  if (!(step > 0 && step < 1e30)) return corrupt("intra frame: grid step out of range");
  RangeDecoder rc(in.cursor(), in.remaining());
  IFrameModel model;
  std::vector<int64_t> q(3 * size_t(topology_.vertex_count));
  int64_t previous[3] = {0, 0, 0};
  const VertexAdjacency& rows = adjacency();
  for (uint32_t v = 0; v < topology_.vertex_count; ++v) {
    int64_t pred[3];
    predict(rows, q, v, pred);
    for (int a = 0; a < 3; ++a) {
      const int64_t r = decodeInt(rc, model, contextOf(previous[a]));
      const int64_t value = pred[a] + r;
      if (value < -int64_t(kMaxGridIndex) || value > int64_t(kMaxGridIndex))
        return corrupt("intra frame: vertex " + std::to_string(v) + " off the grid");
      q[3 * size_t(v) + a] = value;
      previous[a] = r;
    }
    if (rc.overran()) return corrupt("intra frame: coded data ends early");
  }
  recon.resize(q.size());
  for (size_t i = 0; i < q.size(); ++i) recon[i] = min[i % 3] + double(q[i]) * step;
  return Status();
}

}  // namespace animc
