// SPDX-License-Identifier: Apache-2.0
#include "codecs/trajectory/components.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/parallel.h"

namespace animc {
namespace {

// The products of a group's large matrices are cut into blocks of a fixed size that threads
// share: the blocks, never the thread count, decide what each product computes.
constexpr Eigen::Index kProductColumns = 64;
constexpr Eigen::Index kProductRows = 1024;

template <class Scalar>
using Columns = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
template <class Scalar>
using Rows = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The mean of each column, summed in double from the first row to the last, as Eigen's
// colwise().mean() sums a row-major matrix (the same additions in the same order, so the same
// bits), in one pass over the rows where Eigen walks the whole matrix once per column.
Eigen::RowVectorXd columnMeans(const Rows<float>& x) {
  if (x.rows() == 0) return x.cast<double>().colwise().mean();
  Eigen::RowVectorXd sum = x.row(0).cast<double>();
  for (Eigen::Index r = 1; r < x.rows(); ++r) sum += x.row(r).cast<double>();
  return sum / double(x.rows());
}

// Rows of a Gram matrix summed into one partial matrix, from zero and in order; the partial
// matrices are then added in order. Up to this many rows there is one, and the sums are those
// of a single pass.
constexpr Eigen::Index kGramChunkRows = 64 * kProductRows;

// The lower triangle of a^T a in double, all that the eigensolver reads (the rest is zero):
// on threads by blocks of columns and chunks of rows, each chunk summed over blocks of rows
// converted to double.
template <class Matrix>
Eigen::MatrixXd lowerGram(const Matrix& a) {
  const Eigen::Index d = a.cols(), n = a.rows();
  const size_t column_blocks = size_t((d + kProductColumns - 1) / kProductColumns);
  const size_t chunks = std::max<size_t>(1, size_t((n + kGramChunkRows - 1) / kGramChunkRows));
  std::vector<Eigen::MatrixXd> partial(chunks, Eigen::MatrixXd::Zero(d, d));
  const double task_cost = double(std::min(n, kGramChunkRows)) * double(d) * double(kProductColumns) / 2;
  parallelFor(column_blocks * chunks, task_cost, [&](size_t task) {
    const size_t chunk = task / column_blocks;
    const Eigen::Index j = Eigen::Index(task % column_blocks) * kProductColumns, w = std::min(kProductColumns, d - j);
    const Eigen::Index end = std::min(n, Eigen::Index(chunk + 1) * kGramChunkRows);
    for (Eigen::Index r = Eigen::Index(chunk) * kGramChunkRows; r < end; r += kProductRows) {
      const Eigen::MatrixXd tall = a.block(r, j, std::min(kProductRows, end - r), d - j).template cast<double>();
      partial[chunk].block(j, j, d - j, w).noalias() += tall.transpose() * tall.leftCols(w);
    }
  });
  Eigen::MatrixXd gram = std::move(partial[0]);
  for (size_t chunk = 1; chunk < chunks; ++chunk) gram += partial[chunk];
  return gram;
}

// a * b in b's precision, a block of rows of a at a time, each computed in rows of its own
// (one block's memory) and stored by columns, as the callers keep it.
template <class Scalar>
Columns<Scalar> productByRows(const RowMatrixF& a, const Columns<Scalar>& b) {
  Columns<Scalar> out(a.rows(), b.cols());
  const size_t blocks = size_t((a.rows() + kProductRows - 1) / kProductRows);
  parallelFor(blocks, double(kProductRows) * double(a.cols()) * double(b.cols()), [&](size_t i) {
    const Eigen::Index r = Eigen::Index(i) * kProductRows, h = std::min(kProductRows, a.rows() - r);
    Rows<Scalar> block(h, b.cols());
    block.noalias() = a.middleRows(r, h).template cast<Scalar>() * b;
    out.middleRows(r, h) = block;
  });
  return out;
}

// x := x * b for a square b, in double, a block of rows at a time: a large product that needs
// no second matrix of x's size.
void multiplyRowsInPlace(RowMatrixF& x, const Eigen::MatrixXd& b) {
  const size_t blocks = size_t((x.rows() + kProductRows - 1) / kProductRows);
  parallelFor(blocks, double(kProductRows) * double(x.cols()) * double(b.cols()), [&](size_t i) {
    const Eigen::Index r = Eigen::Index(i) * kProductRows, h = std::min(kProductRows, x.rows() - r);
    const Rows<double> block = x.middleRows(r, h).cast<double>() * b;
    x.middleRows(r, h) = block.cast<float>();
  });
}

// a^T * b in float, a block of columns of b at a time.
Eigen::MatrixXf transposedProductByColumns(const RowMatrixF& a, const Eigen::MatrixXf& b) {
  Eigen::MatrixXf out(a.cols(), b.cols());
  const size_t blocks = size_t((b.cols() + kProductColumns - 1) / kProductColumns);
  parallelFor(blocks, double(a.rows()) * double(a.cols()) * double(kProductColumns), [&](size_t i) {
    const Eigen::Index j = Eigen::Index(i) * kProductColumns, w = std::min(kProductColumns, b.cols() - j);
    out.middleCols(j, w).noalias() = a.transpose() * b.middleCols(j, w);
  });
  return out;
}

// An orthonormal basis of the columns of a (Householder QR: the same bits on every run).
Eigen::MatrixXf orthonormal(const Eigen::MatrixXf& a) {
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(a.cast<double>());
  const Eigen::MatrixXd q = qr.householderQ() * Eigen::MatrixXd::Identity(a.rows(), a.cols());
  return q.cast<float>();
}

// A fixed start for the subspace iteration: values in [-1, 1) from a hash of their index
// (SplitMix64), the same on every platform.
Eigen::MatrixXf fixedStart(Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXf m(rows, cols);
  uint64_t state = 0;
  for (Eigen::Index j = 0; j < cols; ++j)
    for (Eigen::Index i = 0; i < rows; ++i) {
      uint64_t z = (state += 0x9E3779B97F4A7C15ull);
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      z ^= z >> 31;
      m(i, j) = float(double(z >> 11) * 0x1.0p-52 - 1);
    }
  return m;
}

// The `count` largest eigenvalues of a Gram matrix as singular values, largest first, and
// their eigenvectors (the solver sorts ascending).
void leadingPairs(const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& solver, Eigen::Index count,
                  Eigen::VectorXd& sigma, Eigen::MatrixXd& vectors) {
  const Eigen::Index dim = solver.eigenvalues().size();
  sigma.resize(count);
  vectors.resize(dim, count);
  for (Eigen::Index k = 0; k < count; ++k) {
    sigma[k] = std::sqrt(std::max(0.0, solver.eigenvalues()[dim - 1 - k]));
    vectors.col(k) = solver.eigenvectors().col(dim - 1 - k);
  }
}

// Subspace iteration: the extra directions it carries beyond those asked for, and its passes
// over the trajectories. The leading components converge as (sigma_extra / sigma_k)^(2p+1)
// (Halko, Martinsson & Tropp 2011); those asked for are well inside the subspace.
Eigen::Index extraDirections(Eigen::Index count) { return std::max<Eigen::Index>(16, count / 2); }
constexpr int kMaxPowerIterations = 8;
constexpr double kSettled = 1e-3;

}  // namespace

Components mergedComponents(const std::vector<MergedSet>& sets, const std::vector<RowSource>& rows, double least) {
  const Eigen::Index dim = sets.front().components->mean.size();
  Components pc;
  pc.complete = true;
  pc.mean = Eigen::RowVectorXd::Zero(dim);
  Eigen::Index width = 0;
  for (const MergedSet& set : sets) {
    pc.mean += double(set.components->coefficients.rows()) * set.components->mean;
    width += set.used + 1;
  }
  pc.mean /= double(rows.size());
  // The union's centred trajectories, as far as the components taken carry them, have the
  // scatter m m^T.
  Eigen::MatrixXd m(dim, width);
  Eigen::Index column = 0;
  for (const MergedSet& set : sets) {
    const Components& c = *set.components;
    const double n = double(c.coefficients.rows());
    const Eigen::RowVectorXd offset = c.mean - pc.mean;
    m.middleCols(column, set.used) = c.basis.leftCols(set.used) * c.sigma.head(set.used).asDiagonal();
    m.col(column + set.used) = std::sqrt(n) * offset.transpose();
    column += set.used + 1;
    pc.energy += c.energy + n * offset.squaredNorm();
  }
  // Its eigenvectors from the smaller of the two Gram matrices, those of less energy than
  // `least` (or none, beyond the rank of m) dropped.
  const bool by_columns = width <= dim;
  const Eigen::MatrixXd gram = by_columns ? Eigen::MatrixXd(m.transpose() * m) : Eigen::MatrixXd(m * m.transpose());
  Eigen::MatrixXd vectors;
  leadingPairs(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram), gram.rows(), pc.sigma, vectors);
  Eigen::Index kept = 0;
  while (kept < pc.sigma.size() && pc.sigma[kept] > 1e-9 * pc.sigma[0] && pc.sigma[kept] * pc.sigma[kept] >= least)
    ++kept;
  pc.sigma.conservativeResize(kept);
  if (by_columns) {
    pc.basis = m * vectors.leftCols(kept);
    for (Eigen::Index k = 0; k < kept; ++k) pc.basis.col(k) /= pc.sigma[k];
  } else {
    pc.basis = vectors.leftCols(kept);
  }
  // A row's coefficients: its set's reconstruction, less the union's mean, on the new basis.
  std::vector<Eigen::MatrixXf> to_union;
  std::vector<Eigen::RowVectorXf> offset_on_union;
  for (const MergedSet& set : sets) {
    const Components& c = *set.components;
    to_union.push_back((c.basis.leftCols(set.used).transpose() * pc.basis).cast<float>());
    offset_on_union.push_back(((c.mean - pc.mean) * pc.basis).cast<float>());
  }
  pc.coefficients.resize(Eigen::Index(rows.size()), kept);
  const double row_cost = double(kept) * double(width) / double(sets.size());
  parallelForBlocks(rows.size(), size_t(kProductRows), row_cost, [&](size_t, size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      const RowSource source = rows[r];
      const MergedSet& set = sets[source.set];
      pc.coefficients.row(Eigen::Index(r)) =
          set.components->coefficients.row(source.row).head(set.used) * to_union[source.set] +
          offset_on_union[source.set];
    }
  });
  return pc;
}

TrajectoryDecomposition::TrajectoryDecomposition(RowMatrixF x) : mean_(columnMeans(x)), centred_(std::move(x)) {
  // Rows are centred and measured a block at a time, on any thread; the energy adds the
  // rows' in order, whatever the thread count.
  const Eigen::RowVectorXf mean = mean_.cast<float>();
  const Eigen::Index rows = centred_.rows();
  std::vector<double> row_energy(static_cast<size_t>(rows));
  const size_t blocks = size_t((rows + kProductRows - 1) / kProductRows);
  parallelFor(blocks, 2.0 * double(kProductRows) * double(centred_.cols()), [&](size_t i) {
    const Eigen::Index r = Eigen::Index(i) * kProductRows, end = std::min(rows, r + kProductRows);
    for (Eigen::Index v = r; v < end; ++v) {
      centred_.row(v) -= mean;
      row_energy[size_t(v)] = centred_.row(v).cast<double>().squaredNorm();
    }
  });
  for (double e : row_energy) energy_ += e;
}

Components TrajectoryDecomposition::none() const {
  Components pc;
  pc.mean = mean_;
  pc.energy = energy_;
  pc.basis.resize(centred_.cols(), 0);
  pc.coefficients.resize(centred_.rows(), 0);
  return pc;
}

void TrajectoryDecomposition::extend(Components& pc, Eigen::Index count, double negligible) {
  if (pc.complete) return;
  // Near the rank, the full eigendecomposition of a Gram matrix costs less than iterating.
  const Eigen::Index have = pc.sigma.size(), width = count + extraDirections(count);
  if (4 * (have + width) >= 3 * rank()) {
    pc = all();
    return;
  }
  appendLeading(pc, count, width, negligible);
}

Components TrajectoryDecomposition::all() {
  Components pc;
  pc.mean = mean_;
  pc.energy = energy_;
  pc.complete = true;
  RowMatrixF& x = centred_;
  // The smaller of the two Gram matrices: trajectories (row x row) or vertices (n x n).
  const bool by_trajectory = x.cols() <= x.rows();
  const Eigen::MatrixXd gram = by_trajectory ? lowerGram(x) : lowerGram(x.transpose());
  const Eigen::Index dim = gram.rows();
  Eigen::MatrixXd vectors;
  leadingPairs(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram), dim, pc.sigma, vectors);
  if (by_trajectory) {
    pc.basis = vectors;
    multiplyRowsInPlace(x, pc.basis);  // as many components as trajectory values
    pc.coefficients = std::move(x);
  } else {
    pc.basis = x.cast<double>().transpose() * vectors;  // x is small: fewer vertices than 3G
    for (Eigen::Index k = 0; k < dim; ++k) {
      if (pc.sigma[k] > 0) pc.basis.col(k) /= pc.sigma[k];
      vectors.col(k) *= pc.sigma[k];
    }
    pc.coefficients = vectors.cast<float>();
  }
  centred_ = RowMatrixF();
  return pc;
}

// The range finder of Halko, Martinsson & Tropp (2011) with power iterations, on the
// trajectories less pc's components (deflation: r = x - c b^T, applied as two products), then
// the components of r projected on the subspace found (Rayleigh-Ritz).
void TrajectoryDecomposition::appendLeading(Components& pc, Eigen::Index count, Eigen::Index width,
                                            double negligible) const {
  const RowMatrixF& x = centred_;
  const Eigen::MatrixXf basis = pc.basis.cast<float>();
  const RowMatrixF& coefficients = pc.coefficients;
  auto residualTimes = [&](const Eigen::MatrixXf& z) {  // r z, N x width
    Eigen::MatrixXf out = productByRows(x, z);
    if (basis.cols() > 0) out.noalias() -= coefficients * (basis.transpose() * z);
    return out;
  };
  auto residualTransposedTimes = [&](const Eigen::MatrixXf& q) {  // r^T q, 3G x width
    Eigen::MatrixXf out = transposedProductByColumns(x, q);
    if (basis.cols() > 0) out.noalias() -= basis * (coefficients.transpose() * q);
    return out;
  };
  // Power iterations until the energy of the `count` leading Ritz values settles.
  Eigen::MatrixXf q = orthonormal(residualTimes(fixedStart(x.cols(), width)));
  Eigen::MatrixXd projected = residualTransposedTimes(q).cast<double>();  // r^T q, 3G x width
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(projected.transpose() * projected, Eigen::EigenvaluesOnly);
  double captured = solver.eigenvalues().tail(count).sum();
  for (int i = 0; i < kMaxPowerIterations; ++i) {
    q = orthonormal(residualTimes(orthonormal(projected.cast<float>())));
    projected = residualTransposedTimes(q).cast<double>();
    solver.compute(projected.transpose() * projected, Eigen::EigenvaluesOnly);
    const double before = captured;
    captured = solver.eigenvalues().tail(count).sum();
    if (captured - before <= std::max(negligible, kSettled * captured)) break;
  }
  solver.compute(projected.transpose() * projected);
  const Eigen::Index have = pc.sigma.size();
  Eigen::VectorXd sigma;
  Eigen::MatrixXd rotation;
  leadingPairs(solver, count, sigma, rotation);
  pc.sigma.conservativeResize(have + count);
  pc.sigma.tail(count) = sigma;
  Eigen::MatrixXd added = projected * rotation;
  // The deflation in float leaves the new vectors a little of the earlier ones (their float
  // error over the new, weaker singular values), which their coefficients would multiply by
  // the earlier, strong singular values: project it out, twice (Gram-Schmidt), in double.
  for (int pass = 0; pass < 2 && have > 0; ++pass) added -= pc.basis * (pc.basis.transpose() * added);
  for (Eigen::Index k = 0; k < count; ++k) {
    const double norm = added.col(k).norm();
    if (norm > 0) added.col(k) /= norm;
  }
  pc.basis.conservativeResize(Eigen::NoChange, have + count);
  pc.basis.rightCols(count) = added;
  pc.coefficients.conservativeResize(Eigen::NoChange, have + count);
  pc.coefficients.rightCols(count) = productByRows(x, Eigen::MatrixXf(added.cast<float>()));
}

}  // namespace animc
