// SPDX-License-Identifier: Apache-2.0
// The principal components of a group's trajectories, for the trajectory encoder: all of them
// from a Gram matrix, or the leading ones only by subspace iteration (docs/trajectory.md,
// "Transform"). Large products are cut into blocks of a fixed size that threads share, so the
// results never depend on the thread count.
#pragma once
#include <Eigen/Dense>
#include <cstdint>
#include <vector>

namespace animc {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
using RowMatrixF = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The mean trajectory, unit basis vectors by decreasing singular value, and the coefficients
// of every trajectory (in the order of the rows given) on them.
struct Components {
  Eigen::RowVectorXd mean;  // 3G
  Eigen::MatrixXd basis;    // 3G x K, columns
  Eigen::VectorXd sigma;    // K
  RowMatrixF coefficients;  // N x K, a trajectory's contiguous (float: the frames' precision)
  double energy = 0;        // sum of the squared centred trajectories: sigma's and the rest's
  bool complete = false;    // every component there is (K = min(N, 3G)), none left out
};

// One of the sets of trajectories merged by mergedComponents(), of which its leading `used`
// components are taken.
struct MergedSet {
  const Components* components = nullptr;
  Eigen::Index used = 0;
};

// Where a row of a union of sets of trajectories comes from.
struct RowSource {
  uint32_t set = 0;
  uint32_t row = 0;
};

// The components of the union of disjoint sets of trajectories from the sets' own, without
// the trajectories: the principal directions of the sets' bases, each scaled by its singular
// values, and of their means' offsets from the union's mean. rows[r] is the source of the
// union's row r. What the components taken leave out stays out, and so do the union's
// components of less energy than `least`. The result is complete: nothing more can be
// computed for it.
Components mergedComponents(const std::vector<MergedSet>& sets, const std::vector<RowSource>& rows, double least = 0);

class TrajectoryDecomposition {
 public:
  // x: one trajectory a row (N x 3G); the decomposition keeps it, less its mean. The large
  // products run in float (the frames' own precision); what is solved, in double.
  explicit TrajectoryDecomposition(RowMatrixF x);

  // No component yet: the mean and the energy.
  Components none() const;
  // Appends the next `count` components to pc (the leading ones of what pc leaves out), or
  // makes pc every component when they would be most of them. The iteration stops when it
  // finds less than `negligible` more energy (or a thousandth of what it found). Every
  // component's coefficients take the trajectories' memory: pc is then complete, and the
  // decomposition has nothing left to give.
  void extend(Components& pc, Eigen::Index count, double negligible);

 private:
  Eigen::Index rank() const { return std::min(centred_.rows(), centred_.cols()); }
  Components all();
  void appendLeading(Components& pc, Eigen::Index count, Eigen::Index width, double negligible) const;

  Eigen::RowVectorXd mean_;
  RowMatrixF centred_;
  double energy_ = 0;
};

}  // namespace animc
