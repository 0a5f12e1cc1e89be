#include <cmath>

#include "codecs/affine_octree/predictive_octree.h"

namespace animc {
struct PredictiveOctreeDecoder::Walk {
  const PFrameInput& in;
  double step;
  RangeDecoder rc;
  std::vector<double>& recon;
};

Status PredictiveOctreeDecoder::decode(const PFrameInput& in, ByteReader payload,
                                       std::vector<double>& recon) {
  recon.resize(in.reference->size());
  contexts_.beginFrame();
  Walk w{in, residualStep(in.max_error), RangeDecoder(payload.cursor(), payload.remaining()), recon};
  ANIMC_RETURN_IF_ERROR(decodeCell(w, partition_.reset(*in.reference)));
  if (w.rc.overran()) return corrupt("octree frame: coded data ends early or is damaged");
  return Status();
}

Status PredictiveOctreeDecoder::decodeCell(Walk& w, const Cell& cell) {
  const uint32_t n = cell.end - cell.begin;
  if (n == 0) return Status();
  if (w.rc.overran()) return corrupt("octree frame: coded data ends early or is damaged");
  if (canSplit(cell, w.in.max_depth) && w.rc.decode(models_->split[cell.depth])) {
    Cell children[8];
    partition_.split(cell, children);
    for (const Cell& child : children) ANIMC_RETURN_IF_ERROR(decodeCell(w, child));
    return Status();
  }
  return decodeLeaf(w, cell);
}

Status PredictiveOctreeDecoder::decodeLeaf(Walk& w, const Cell& cell) {
  const uint32_t n = cell.end - cell.begin;
  const uint32_t* idx = partition_.vertices(cell);
  PredictiveModels& pm = *models_;
  int64_t coded[12] = {0};
  for (int r = 0; r < 3; ++r) coded[r] = decodeInt(w.rc, pm.ints, kCtxTranslation);
  if (n >= kMinLinearVertices)
    for (int k = 0; k < 9; ++k) coded[3 + k] = decodeInt(w.rc, pm.ints, kCtxLinear);
  const LeafModel m = leafModel(w.in, cell, idx);
  const CentredAffine a = codedAffine(m, coded, w.step);
  const bool all_zero = w.rc.decode(pm.residuals_zero[n <= kMinLinearVertices]);
  for (uint32_t i = 0; i < n; ++i) {
    const size_t v = 3 * size_t(idx[i]);
    predictVertex(w.in, m, a, idx[i], &w.recon[v]);
    int64_t r[3] = {0, 0, 0};
    for (int ax = 0; ax < 3 && !all_zero; ++ax) {
      r[ax] = decodeInt(w.rc, pm.ints, kCtxResidual + contexts_.context(idx[i], ax));
      w.recon[v + ax] += double(r[ax]) * w.step;
    }
    contexts_.set(idx[i], r);
  }
  return Status();
}

}  // namespace animc
