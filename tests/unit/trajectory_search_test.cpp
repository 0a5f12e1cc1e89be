// SPDX-License-Identifier: Apache-2.0
// The trajectory encoder's parts: the leading components by subspace iteration equal the full
// eigendecomposition's, also when added in several steps; components merged from disjoint
// sets equal their union's; the step search finds a boundary within its tolerance in few
// trials, following the slope it measures, and ends when no step can be acceptable.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "codecs/trajectory/components.h"
#include "codecs/trajectory/step_search.h"
#include "core/parallel.h"

namespace animc {
namespace {

// Trajectories of a known spectrum: singular values 1000 * 0.9^k over `rank` components, a
// fixed random basis on each side.
RowMatrixF spectrumTrajectories(Eigen::Index rows, Eigen::Index cols, Eigen::Index rank) {
  std::mt19937 random(7);
  std::normal_distribution<double> normal;
  auto gaussian = [&](Eigen::Index r, Eigen::Index c) {
    Eigen::MatrixXd m(r, c);
    for (Eigen::Index j = 0; j < c; ++j)
      for (Eigen::Index i = 0; i < r; ++i) m(i, j) = normal(random);
    return Eigen::MatrixXd(Eigen::HouseholderQR<Eigen::MatrixXd>(m).householderQ() * Eigen::MatrixXd::Identity(r, c));
  };
  const Eigen::MatrixXd u = gaussian(rows, rank), v = gaussian(cols, rank);
  Eigen::VectorXd sigma(rank);
  for (Eigen::Index k = 0; k < rank; ++k) sigma[k] = 1000 * std::pow(0.9, double(k));
  return (u * sigma.asDiagonal() * v.transpose()).cast<float>();
}

// Every component of the same trajectories (the decomposition's full path).
Components allOf(const RowMatrixF& x) {
  TrajectoryDecomposition d(x);
  Components pc = d.none();
  d.extend(pc, x.cols(), 0);
  return pc;
}

void expectSameLeading(const Components& got, const Components& all, Eigen::Index count) {
  ASSERT_GE(got.sigma.size(), count);
  for (Eigen::Index k = 0; k < count; ++k) {
    EXPECT_NEAR(got.sigma[k], all.sigma[k], 1e-4 * all.sigma[0]) << "component " << k;
    // The same vector up to its sign, and the coefficients with it.
    const double sign = got.basis.col(k).dot(all.basis.col(k)) < 0 ? -1 : 1;
    EXPECT_LT((got.basis.col(k) * sign - all.basis.col(k)).norm(), 1e-3) << "component " << k;
    EXPECT_LT((got.coefficients.col(k) * sign - all.coefficients.col(k)).norm(), 1e-3 * all.sigma[0])
        << "component " << k;
  }
}

TEST(TrajectoryComponents, LeadingOnesEqualTheFullDecompositions) {
  const RowMatrixF x = spectrumTrajectories(900, 600, 120);
  const Components all = allOf(x);
  EXPECT_TRUE(all.complete);
  TrajectoryDecomposition d(x);
  Components leading = d.none();
  d.extend(leading, 24, 0);
  EXPECT_FALSE(leading.complete);
  ASSERT_EQ(leading.sigma.size(), 24);
  expectSameLeading(leading, all, 24);
  // Then 24 more, of what the first leave out: the same as the first 48 at once.
  d.extend(leading, 24, 0);
  expectSameLeading(leading, all, 48);
  EXPECT_LE(leading.sigma.squaredNorm(), leading.energy * (1 + 1e-6));
}

TEST(TrajectoryComponents, NearTheRankEveryComponentIsComputed) {
  const RowMatrixF x = spectrumTrajectories(50, 90, 40);
  TrajectoryDecomposition d(x);
  Components pc = d.none();
  d.extend(pc, 40, 0);
  EXPECT_TRUE(pc.complete);
  EXPECT_EQ(pc.sigma.size(), 50);  // min(rows, columns)
  EXPECT_NEAR(pc.sigma.squaredNorm(), pc.energy, 1e-6 * pc.energy);
}

// The mean trajectory is part of what the encoder writes: it must be the bits that Eigen's
// colwise().mean() of the rows in double gave 1.x's encoder, which adds the rows in order.
// Rows of very different sizes make any other order give other bits.
TEST(TrajectoryComponents, TheMeanIsEigensColumnMeanToTheBit) {
  RowMatrixF x(1001, 45);
  std::mt19937 random(3);
  std::normal_distribution<float> normal;
  for (Eigen::Index r = 0; r < x.rows(); ++r)
    for (Eigen::Index c = 0; c < x.cols(); ++c) x(r, c) = normal(random) * (r % 4 == 0 ? 1e16f : r % 3 ? 1.0f : 1e-8f);
  const Eigen::RowVectorXd eigen = x.cast<double>().colwise().mean();
  const Eigen::RowVectorXd mean = TrajectoryDecomposition(x).none().mean;
  ASSERT_EQ(mean.size(), eigen.size());
  for (Eigen::Index c = 0; c < x.cols(); ++c) EXPECT_EQ(mean[c], eigen[c]) << "column " << c;
  // The order matters for these rows (so the test can fail): pairs of rows first differ.
  Eigen::RowVectorXd pairwise = Eigen::RowVectorXd::Zero(x.cols());
  for (Eigen::Index r = 0; r + 1 < x.rows(); r += 2) pairwise += x.row(r).cast<double>() + x.row(r + 1).cast<double>();
  pairwise = (pairwise + x.row(x.rows() - 1).cast<double>()) / double(x.rows());
  EXPECT_NE(pairwise, eigen);
}

// More trajectories than one chunk of the Gram matrix's rows: the chunks are summed apart on
// threads and added in order, the same components on any number of threads.
TEST(TrajectoryComponents, AGramOfManyChunksIsTheSameOnAnyNumberOfThreads) {
  const RowMatrixF x = spectrumTrajectories(150000, 9, 9);
  Components one;
  {
    ThreadBudget budget(1);
    one = allOf(x);
  }
  ASSERT_TRUE(one.complete);
  for (unsigned threads : {2u, 3u}) {
    ThreadBudget budget(threads);
    const Components got = allOf(x);
    EXPECT_TRUE(got.sigma == one.sigma) << threads << " threads";
    EXPECT_TRUE(got.basis == one.basis) << threads << " threads";
  }
}

// The rows of x, split into two sets by row parity, their own means differing (the union's
// mean is not the sets'). Every component of each set, merged, gives the union's.
TEST(TrajectoryComponents, MergedFromCompleteSetsEqualTheUnions) {
  RowMatrixF x = spectrumTrajectories(300, 60, 20);
  for (Eigen::Index r = 0; r < x.rows(); r += 2) x.row(r).array() += 5.0f;
  RowMatrixF even(x.rows() / 2, x.cols()), odd(x.rows() / 2, x.cols());
  std::vector<RowSource> rows(size_t(x.rows()));
  for (Eigen::Index r = 0; r < x.rows(); ++r) {
    (r % 2 ? odd : even).row(r / 2) = x.row(r);
    rows[size_t(r)] = {uint32_t(r % 2), uint32_t(r / 2)};
  }
  const Components a = allOf(even), b = allOf(odd), all = allOf(x);
  const Components merged = mergedComponents({{&a, a.sigma.size()}, {&b, b.sigma.size()}}, rows);
  EXPECT_TRUE(merged.complete);
  EXPECT_NEAR(merged.energy, all.energy, 1e-6 * all.energy);
  EXPECT_LT((merged.mean - all.mean).norm(), 1e-4);
  expectSameLeading(merged, all, 20);
}

// A merge that takes only a set's leading components leaves the rest out: the union's
// energy stays whole, its components carry only what was taken.
TEST(TrajectoryComponents, MergedComponentsLeaveOutWhatIsNotTaken) {
  const RowMatrixF x = spectrumTrajectories(200, 40, 30);
  const Components a = allOf(x.topRows(100)), b = allOf(x.bottomRows(100));
  std::vector<RowSource> rows(200);
  for (uint32_t r = 0; r < 200; ++r) rows[r] = {r / 100, r % 100};
  const Components merged = mergedComponents({{&a, 5}, {&b, 5}}, rows);
  const double taken = a.sigma.head(5).squaredNorm() + b.sigma.head(5).squaredNorm();
  EXPECT_NEAR(merged.energy, allOf(x).energy, 1e-6 * merged.energy);
  EXPECT_LE(merged.sigma.size(), 12);  // 5 + 5 directions and 2 mean offsets
  EXPECT_NEAR(merged.sigma.squaredNorm(),
              taken + 100 * (a.mean - merged.mean).squaredNorm() + 100 * (b.mean - merged.mean).squaredNorm(),
              1e-4 * taken);
}

TEST(StepSearch, FindsTheBoundaryWithinItsToleranceInFewTrials) {
  for (const double boundary : {-7.3, -2.05, 0.4}) {
    StepSearch s;
    s.lowest = -30;
    s.highest = 5;
    s.guess = boundary + 1.5;  // a model off by a factor of almost 3
    s.slope = 2;
    int trials = 0;
    // A squared error: slope 2, with a ripple the secant steps must live with.
    const double u = searchStep(s, [&](double v) {
      ++trials;
      return 2 * (v - boundary) + 0.01 * std::sin(40 * v);
    });
    EXPECT_LE(u, boundary + 0.01) << boundary;
    EXPECT_GE(u, boundary - s.tolerance - 0.01) << boundary;
    EXPECT_LE(trials, 10) << boundary;
  }
}

// An excess growing at 1.2 per unit where the model says 2 (sydney_md2's at a KG target): the
// steps follow the slope the trials measure, where the model's would creep up on the boundary
// (each step falling short by 40 %), a trial or two per halving of the excess.
TEST(StepSearch, FollowsTheSlopeItMeasuresBeforeABracket) {
  for (const double start : {0.5, 1.0, 2.0}) {
    StepSearch s;
    s.lowest = -30;
    s.highest = 5;
    s.guess = -4 + start;
    s.slope = 2;
    int trials = 0;
    const double u = searchStep(s, [&](double v) {
      ++trials;
      return 1.2 * (v + 4);
    });
    EXPECT_LE(u, -4.0) << start;
    EXPECT_GE(u, -4 - s.tolerance) << start;
    EXPECT_LE(trials, 5) << start;
  }
}

TEST(StepSearch, TakesAnEndWhenEveryOrNoStepIsAcceptable) {
  StepSearch s;
  s.lowest = -20;
  s.highest = 3;
  s.guess = -5;
  EXPECT_EQ(searchStep(s, [](double) { return -1.0; }), s.highest);
  int trials = 0;
  // Finer steps that do not lower the error (too few components): the lowest, soon.
  EXPECT_EQ(searchStep(s, [&](double v) {
              ++trials;
              return 0.5 + 0.001 * v;
            }),
            s.lowest);
  EXPECT_LE(trials, 6);
  // An error of zero everywhere (a static group) is acceptable at any step.
  EXPECT_EQ(searchStep(s, [](double) { return -HUGE_VAL; }), s.highest);
}

}  // namespace
}  // namespace animc
