#include <cmath>

#include "codecs/affine_octree/cell_kernels.h"
#include "codecs/affine_octree/predictive_octree.h"

namespace animc {

double residualStep(double max_error) { return 2.0 * max_error / std::sqrt(3.0) * 0.999; }

void CellPoints::gather(const PFrameInput& in, const uint32_t* idx, size_t n) {
  const size_t size = kPointStride * n;
  if (reference.size() < size) {  // the three grow together
    reference.resize(size);
    before.resize(size);
    target.resize(size);
  }
  count = n;
  has_before = in.before != nullptr;
  if (in.before) {
    const TwoCellFrames f =
        gatherPointsTwice(in.reference->data(), in.before->data(), in.cube, idx, n, reference.data(), before.data());
    reference_frame = f.first;
    before_frame = f.second;
  } else {
    reference_frame = gatherPoints(in.reference->data(), idx, n, reference.data());
  }
  if (in.target) copyPoints(in.target->data(), idx, n, target.data());
}

LeafModel leafModel(const CellPoints& points) {
  LeafModel m;
  m.frame = points.reference_frame;
  if (points.has_before) {
    // The cell's own motion from f-2 to f-1, assumed to continue.
    static const double kZero[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    fitCentred(points.before.data(), points.reference.data(), points.count, points.before_frame, kZero,
               m.prior);
  }
  return m;
}

CentredAffine codedAffine(const LeafModel& m, const int64_t coded[12], double step) {
  CentredAffine a = m.prior;
  const double st = step * kTranslationStep;
  const double sl = step * kLinearStep / m.frame.radius;
  for (int r = 0; r < 3; ++r) a.t[r] += double(coded[r]) * st;
  for (int k = 0; k < 9; ++k) a.L[k] += double(coded[3 + k]) * sl;
  return a;
}

}  // namespace animc
