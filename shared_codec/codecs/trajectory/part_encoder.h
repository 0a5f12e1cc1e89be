// SPDX-License-Identifier: Apache-2.0
// One part of a trajectory group for the encoder: the principal components of its vertices'
// trajectories, which of them to send at a coefficient step and the part quantised at it
// (docs/trajectory.md). A codec-3 group is one part holding every vertex; a codec-5 group is
// the parts of a clustering of its vertices. The step itself is chosen for the whole group
// (trajectory_encoder.cpp), which shares what is common to its parts in a GroupContext.
#pragma once
#include <Eigen/Dense>
#include <cstdint>
#include <memory>
#include <vector>

#include "codecs/trajectory/components.h"
#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/options.h"
#include "codecs/trajectory/row_quantiser.h"
#include "core/simd_math.h"

namespace animc {

// What the parts of one group share.
struct GroupContext {
  TrajectoryOptions options;
  SimdPath path = SimdPath::kPortable;
  const float* original = nullptr;  // the group's frames, 3 floats a vertex of the whole mesh
  uint32_t mesh_vertices = 0;
  uint32_t frames = 0;
  double diagonal = 0;             // of the group's first frame's bounding box
  std::vector<double> cube_sides;  // of each frame (kMaxError)
  double spread = 0;               // sum of |x - centroid|^2 over the frames (kTargetKg)
  // Rounds of PartEncoder::refine() in each quantisation: none while a first step is searched.
  int refinement_rounds = 0;

  // The squared error over the group a rate mode allows: the KG target's, or for a max
  // error, every vertex at `share` of the bound.
  double allowance(double share) const;
  double allowedAtMost() const { return allowance(1); }
  // A guess the trials correct: on the shared sequences the largest error was 5 to 20 times
  // the root mean square (docs/trajectory.md, "Rate control").
  double modelledAllowance() const { return allowance(0.1); }
};

// The squared error a bit buys at a uniform quantiser's slope, per squared step: 2 ln 2 / 12.
constexpr double kBitSlope = 0.1155;

// The energy of a component below which it is never worth sending at step q, in a part of
// `vertices` vertices over `frames` frames: the error it removes is less than the cost of its
// coefficients and basis values all zero.
double leastWorthSending(double q, uint32_t vertices, uint32_t frames);

// The error of a part's decoded frames at one step.
struct PartError {
  double squared = 0;               // summed over the part's vertices and frames
  std::vector<double> frame_worst;  // per frame, the largest squared distance (kMaxError)
};

class PartEncoder {
 public:
  // The part's vertices are those of `order`; `members`, when not empty, maps them (the
  // order's vertex indices) to the mesh's vertices, in increasing order. Both must outlive
  // the part.
  PartEncoder(const GroupContext& group, const CodingOrder& order, const std::vector<uint32_t>& members);
  // The same part with components made elsewhere (their rows in the order's), complete: no
  // more can be computed for it.
  PartEncoder(const GroupContext& group, const CodingOrder& order, const std::vector<uint32_t>& members, Components pc);

  uint32_t vertices() const { return vertices_; }
  const CodingOrder& order() const { return order_; }
  uint32_t meshVertex(uint32_t v) const { return members_.empty() ? v : members_[v]; }
  const Components& components() const { return pc_; }
  // The row of the part's vertex v (an index into its members) in the trajectories and
  // the coefficients: its position in the coding order.
  uint32_t row(uint32_t v) const { return position_[v]; }

  // Computes `count` more leading components (or all of them).
  void extend(Eigen::Index count);
  // Drops the decomposition and the components (after the group is quantised).
  void release();

  // Whether quantising the part refines its basis and coefficients (refine()), when the group
  // asks for it.
  bool refinable() const;

  // Whether a component weaker than all of the part's would never be worth sending at step q.
  bool carriesEnough(double q) const;
  // Whether the part's components cannot do, before any search (q the model's step, doubled).
  bool clearlyTooFew(double q) const;
  // Whether none of the weakest eighth of the part's components is sent at step q.
  bool sendsNoneOfTheWeakest(float q) const;
  // The energy of a component below which it is never worth sending at step q.
  double leastWorthSending(double q) const;
  // How many more components step q probably needs.
  Eigen::Index moreComponents(double q) const;
  // Energy the components computed leave out.
  double leftOut() const { return std::max(0.0, pc_.energy - pc_.sigma.squaredNorm()); }
  // The largest coefficient's magnitude (0 without components).
  double largestCoefficient() const;

  // The part as quantised at step: into g.
  void quantise(double step, TrajectoryGroup& g) const;
  // The error of the frames the decoder will make of the part at step.
  PartError measure(double step, bool frame_worst) const;

 private:
  struct ColumnStats;
  struct Selection;
  RowMatrixF trajectories() const;
  const float* vertexOf(uint32_t t, uint32_t v) const {
    return group_.original + (size_t(t) * group_.mesh_vertices + meshVertex(v)) * 3;
  }
  double share() const { return double(vertices_) / double(group_.mesh_vertices); }
  double negligibleEnergy() const;
  std::vector<ColumnStats> columnStats(double q, Eigen::Index first) const;
  Selection selection(double q, Eigen::Index first = 0) const;
  Selection quantiseHeader(double step, TrajectoryGroup& g) const;
  void refine(double q, Selection& chosen) const;
  RowPrices rowPrices(double q, double weight, double row_step) const;
  bool worthSending(Eigen::Index k, double q, const ColumnStats& column, const std::vector<int32_t>& basis,
                    float basis_step) const;

  const GroupContext& group_;
  const CodingOrder& order_;
  const std::vector<uint32_t>& members_;
  uint32_t vertices_;
  std::vector<uint32_t> position_;  // in coding order, of each of the part's vertices
  std::unique_ptr<TrajectoryDecomposition> decomposition_;
  Components pc_;
};

}  // namespace animc
