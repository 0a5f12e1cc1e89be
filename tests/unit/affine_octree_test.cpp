// SPDX-License-Identifier: Apache-2.0
// Round trips of the Affine-Octree codec through the .ams container, both profiles.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "api.h"
#include "codecs/affine_octree/cell_kernels.h"
#include "codecs/affine_octree/octree_shared.h"
#include "codecs/affine_octree/options.h"
#include "codecs/affine_octree/predictive_octree.h"
#include "codec_test_support.h"
#include "test_sequences.h"

namespace animc {
namespace {

using testing_support::decodeAll;
using testing_support::expectSeeksMatch;
using testing_support::gridSequence;
using testing_support::tempPath;
using testing_support::worstRelativeError;

struct Case {
  Profile profile;
  double max_error;
  uint32_t iframe_interval;
};

class AffineOctreeRoundTrip : public ::testing::TestWithParam<Case> {};

TEST_P(AffineOctreeRoundTrip, EveryVertexWithinMaxErrorAndDecoderMatchesEncoder) {
  MemorySequence seq = gridSequence(24, 20, 30, 1.0, 1.0);
  EncodeSettings settings;
  settings.octree().profile = GetParam().profile;
  settings.octree().max_error = GetParam().max_error;
  settings.iframe_interval = GetParam().iframe_interval;
  const std::string path = tempPath("roundtrip.ams");
  std::vector<std::vector<float>> encoder_view;
  const size_t floats = 3 * size_t(seq.topology().vertex_count);
  auto report = encodeSequence(seq, settings, path, {},
                               [&](int64_t, const float*, const float* r) { encoder_view.emplace_back(r, r + floats); });
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report.value().frames, 30);
  const auto decoded = decodeAll(path);
  ASSERT_EQ(decoded.size(), 30u);
  EXPECT_EQ(decoded, encoder_view);  // closed loop: both sides hold the same frames
  EXPECT_LE(worstRelativeError(seq.frames(), decoded), GetParam().max_error);
  const uint64_t raw = 12ull * 24 * 20 * 30;
  EXPECT_LT(report.value().bytes, raw / 3);
  std::remove(path.c_str());
}

INSTANTIATE_TEST_SUITE_P(Profiles, AffineOctreeRoundTrip,
                         ::testing::Values(Case{Profile::kPaper, 0.01, 0}, Case{Profile::kPaper, 0.001, 7},
                                           Case{Profile::kPredictive, 0.01, 0}, Case{Profile::kPredictive, 0.001, 7},
                                           Case{Profile::kPredictive, 0.1, 0}));

TEST(AffineOctree, RigidMotionCodesOneCellPerFrame) {
  MemorySequence seq = gridSequence(30, 30, 12, 0.0, 1.0);
  EncodeSettings settings;
  settings.octree().profile = Profile::kPaper;
  const std::string path = tempPath("rigid.ams");
  auto report = encodeSequence(seq, settings, path);
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report.value().intra_frames, 1u);
  EXPECT_EQ(report.value().cells, 11u);
  std::remove(path.c_str());
}

// The default profile predicts rigid motion with one affine too, but its splits are chosen by
// rate + distortion, and the reference frame's own quantisation noise is distortion that
// smaller cells can fit and keep fitted. So rigid motion is not exactly one cell a frame
// there; it must still cost far less than deformation does. 40 frames, because which splits
// the first few frames choose, while the models still learn, swings widely with small
// changes to the coder (from 1 to over 150 cells a frame on this grid); the steady state does not.
TEST(AffineOctree, DefaultProfileCodesRigidMotionFarCheaperThanDeformation) {
  EncodeSettings settings;
  const std::string path = tempPath("rigid_default.ams");
  MemorySequence rigid = gridSequence(30, 30, 40, 0.0, 1.0);
  auto r = encodeSequence(rigid, settings, path);
  ASSERT_TRUE(r.ok()) << r.status().message();
  MemorySequence deforming = gridSequence(30, 30, 40, 1.0, 1.0);
  auto d = encodeSequence(deforming, settings, path);
  ASSERT_TRUE(d.ok()) << d.status().message();
  const auto motion = [](const EncodeSummary& e) { return e.bytes - e.static_bytes; };
  EXPECT_LT(motion(r.value()) * 3, motion(d.value()));
  EXPECT_LT(r.value().cells * 2, d.value().cells);
  std::remove(path.c_str());
}

TEST(AffineOctree, RandomAccessEqualsFullDecode) {
  MemorySequence seq = gridSequence(16, 16, 40, 1.0, 0.5);
  EncodeSettings settings;
  settings.iframe_interval = 8;
  const std::string path = tempPath("random.ams");
  ASSERT_TRUE(encodeSequence(seq, settings, path).ok());
  const auto full = decodeAll(path);
  ASSERT_EQ(full.size(), 40u);
  auto ams = AmsSource::open(path);
  ASSERT_TRUE(ams.ok());
  EXPECT_EQ(ams.value()->info().sections.size(), 4u + 5u);  // HEAD CONN INDX END + 5 groups
  ASSERT_NO_FATAL_FAILURE(expectSeeksMatch(*ams.value(), full, {39, 0, 17, 8, 23, 7}));
  std::remove(path.c_str());
}

// Every cell a walk reaches lists, in increasing order, the vertices of its parent in its
// octant: split() copies in chunks that may write before a child's range, which must never
// reach a cell the walk has yet to visit. Clustered points make many empty and one-vertex
// children; the walk stops at random cells, as the coders' walks do.
struct PartitionWalk {
  explicit PartitionWalk(SimdPath path) : partition(path) {}
  OctreePartition partition;
  std::vector<double> unit;
  int levels = 10;
  std::mt19937 rng{7};

  static int octantAt(const double* p, int depth) {
    int o = 0;
    for (int a = 0; a < 3; ++a) {
      const uint32_t g = uint32_t(std::min(65535.0, std::max(0.0, p[a] * 65536.0)));
      o |= int((g >> (15 - depth)) & 1) << a;
    }
    return o;
  }
  void walk(const Cell& cell, const std::vector<uint32_t>& expected) {
    const uint32_t* v = partition.vertices(cell);
    ASSERT_EQ(std::vector<uint32_t>(v, v + (cell.end - cell.begin)), expected) << "depth " << cell.depth;
    if (cell.depth >= levels || expected.size() < 2 || rng() % 4 == 0) return;
    Cell children[8];
    partition.split(cell, children);
    for (int c = 0; c < 8; ++c) {
      std::vector<uint32_t> inside;
      for (uint32_t i : expected)
        if (octantAt(&unit[3 * size_t(i)], cell.depth) == c) inside.push_back(i);
      ASSERT_NO_FATAL_FAILURE(walk(children[c], inside));
    }
  }
};

TEST(OctreePartition, SplitsAreStablePartitionsByOctant) {
  for (SimdPath path : availableSimdPaths()) {
  SCOPED_TRACE(int(path));
  PartitionWalk w(path);
  std::uniform_real_distribution<double> uniform(0, 1);
  for (int trial = 0; trial < 60; ++trial) {
    const uint32_t n = 1 + w.rng() % (trial % 2 ? 2000 : 300);
    const int clusters = 1 + int(w.rng() % 4);
    w.unit.resize(3 * size_t(n));
    for (double& x : w.unit)
      x = clusters == 1 ? uniform(w.rng) : std::floor(uniform(w.rng) * clusters) / clusters + 0.01 * uniform(w.rng);
    w.levels = 1 + int(w.rng() % kMaxDepthLimit);
    std::vector<uint32_t> all(n);
    for (uint32_t i = 0; i < n; ++i) all[i] = i;
    ASSERT_NO_FATAL_FAILURE(w.walk(w.partition.reset(w.unit, w.levels), all));
    ASSERT_NO_FATAL_FAILURE(w.walk(w.partition.restart(), all));
  }
  }
}

// Cells of more vertices than the split's buckets hold take a split of their own: the root of
// a large mesh, and here a crowded first-level cell too.
TEST(OctreePartition, CellsLargerThanTheBucketsSplitTheSameWay) {
  for (SimdPath path : availableSimdPaths()) {
  SCOPED_TRACE(int(path));
  PartitionWalk w(path);
  std::uniform_real_distribution<double> uniform(0, 1);
  const uint32_t n = 200000;
  w.unit.resize(3 * size_t(n));
  for (size_t i = 0; i < w.unit.size(); ++i) w.unit[i] = (i / 3) % 4 ? 0.5 * uniform(w.rng) : uniform(w.rng);
  w.levels = 4;
  std::vector<uint32_t> all(n);
  for (uint32_t i = 0; i < n; ++i) all[i] = i;
  Cell children[8];
  w.partition.split(w.partition.reset(w.unit, w.levels), children);
  for (int c = 0; c < 8; ++c) {
    std::vector<uint32_t> inside;
    for (uint32_t i : all)
      if (PartitionWalk::octantAt(&w.unit[3 * size_t(i)], 0) == c) inside.push_back(i);
    if (c == 0) {
      ASSERT_GT(inside.size(), 100000u);  // a first-level cell as large as a root
    }
    ASSERT_NO_FATAL_FAILURE(w.walk(children[c], inside));
  }
  }
}

// The prior's one-pass kernel (which on AVX2 CPUs sums while it gathers, normalises frame f-2
// point by point and solves with a row per vector) against its definition written out of the
// frame-wide and portable pieces: normalise(), gatherPoints(), fitSums() about the first
// point, solveFit(). Bit for bit, since encoder and decoder may run either: every path this
// CPU runs against the portable pieces. It must also find an affine motion that the points
// follow exactly.
TEST(CellKernels, GatheredMotionIsTheFitOfTheNormalisedPoints) {
  for (SimdPath path : availableSimdPaths()) {
  SCOPED_TRACE(int(path));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> uniform(-1, 1);
  const double L_true[9] = {0.02, -0.01, 0.005, 0.01, -0.03, 0.0, 0.004, 0.02, 0.01};
  const double t_true[3] = {0.05, -0.02, 0.01};
  for (size_t n : {1, 2, 3, 5, 40, 300}) {
    const size_t count = 2 * n;  // the leaf takes every other vertex, in a shuffled order
    std::vector<double> before(3 * count), reference(3 * count);
    for (double& x : before) x = 3.0 + 7.0 * uniform(rng);  // world units
    const RootCube cube = boundingCube(before);
    std::vector<double> unit_before;
    normalise(SimdPath::kPortable, cube, before, unit_before);
    for (size_t v = 0; v < count; ++v) {
      const double* b = &unit_before[3 * v];
      for (int r = 0; r < 3; ++r)  // exact motion about the cube's centre, plus nothing
        reference[3 * v + r] = b[r] + t_true[r] + L_true[3 * r] * (b[0] - 0.5) +
                               L_true[3 * r + 1] * (b[1] - 0.5) + L_true[3 * r + 2] * (b[2] - 0.5);
    }
    std::vector<uint32_t> idx;
    for (uint32_t v = 0; v < count; v += 2) idx.push_back(v);
    std::shuffle(idx.begin(), idx.end(), rng);

    std::vector<double> out(kPointStride * n), scratch(kPointStride * n);
    CellFrame frame;
    CentredAffine motion;
    gatherWithMotion(path, reference.data(), before.data(), cube, idx.data(), n, out.data(), scratch.data(), frame, motion);

    std::vector<double> want_out(kPointStride * n), before_points(kPointStride * n, 0.0);
    const CellFrame want_frame = gatherPoints(SimdPath::kPortable, reference.data(), idx.data(), n, want_out.data());
    for (size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) before_points[kPointStride * i + a] = unit_before[3 * size_t(idx[i]) + a];
    const double origin[3] = {before_points[0], before_points[1], before_points[2]};
    const double no_prior[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    CentredAffine want;
    solveFit(fitSums(SimdPath::kPortable, before_points.data(), want_out.data(), n, origin), n, ridgeWeight(n, want_frame), no_prior,
             want);

    EXPECT_EQ(out, want_out) << n;
    for (int a = 0; a < 3; ++a) EXPECT_EQ(frame.centroid[a], want_frame.centroid[a]) << n;
    EXPECT_EQ(frame.radius, want_frame.radius) << n;
    for (int r = 0; r < 3; ++r) EXPECT_EQ(motion.t[r], want.t[r]) << n << " t" << r;
    for (int k = 0; k < 9; ++k) EXPECT_EQ(motion.L[k], want.L[k]) << n << " L" << k;
    // The translation is the mean motion, whatever the ridge: the applied one, taken at the
    // points' centroid rather than at the cube's centre.
    double centroid[3] = {0, 0, 0};
    for (size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) centroid[a] += before_points[kPointStride * i + a] / double(n);
    for (int r = 0; r < 3; ++r) {
      double t = t_true[r];
      for (int j = 0; j < 3; ++j) t += L_true[3 * r + j] * (centroid[j] - 0.5);
      EXPECT_NEAR(motion.t[r], t, 1e-12) << n << " t" << r;
    }
    if (n < 40) continue;
    // Enough points that the linear part is determined: the one applied, shrunk by the ridge
    // (10^-3 · n · r², against a spread of about n · r² / 10 here) by about 1 %.
    for (int k = 0; k < 9; ++k) EXPECT_NEAR(motion.L[k], L_true[k], 6e-4) << n << " L" << k;
  }
  }
}

// A leaf's points for the two tests below: reference u in a small cell, target q = u moved by
// a smooth deformation plus noise, gathered kPointStride apart.
struct LeafFixture {
  size_t n;
  std::vector<double> u, q;
  CellFrame frame;
  double prior_L[9];
  LeafFixture(size_t count, std::mt19937& rng) : n(count), u(kPointStride * count, 0.0), q(kPointStride * count, 0.0) {
    std::uniform_real_distribution<double> uniform(-1, 1);
    std::vector<double> xyz(3 * n);
    for (double& x : xyz) x = 0.4 + 0.05 * uniform(rng);
    std::vector<uint32_t> idx(n);
    for (uint32_t i = 0; i < n; ++i) idx[i] = i;
    frame = gatherPoints(bestSimdPath(), xyz.data(), idx.data(), n, u.data());
    for (size_t i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a)
        q[kPointStride * i + a] = u[kPointStride * i + a] + 0.01 + 0.03 * (u[kPointStride * i + (a + 1) % 3] - 0.4) +
                                  0.001 * uniform(rng);
    for (double& l : prior_L) l = 0.01 * uniform(rng);
  }
  // The fit's objective: squared error of the points plus the ridge's pull to the prior.
  double objective(const CentredAffine& m) const {
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
      double p[3];
      applyCentred(m, frame.centroid, &u[kPointStride * i], p);
      for (int a = 0; a < 3; ++a) sum += (q[kPointStride * i + a] - p[a]) * (q[kPointStride * i + a] - p[a]);
    }
    for (int k = 0; k < 9; ++k) sum += ridgeWeight(n, frame) * (m.L[k] - prior_L[k]) * (m.L[k] - prior_L[k]);
    return sum;
  }
};

// The rate-distortion quantisation weighs its choices by fitCentred()'s normal matrix instead
// of predicting points: moving the fit by (δt, δL) must add exactly n·|δt|² + Σ δLᵣᵀ·A·δLᵣ to
// its objective.
TEST(PredictiveOctree, FitNormalMatrixIsTheCurvatureOfItsObjective) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (size_t n : {1, 4, 30}) {
    const LeafFixture leaf(n, rng);
    CentredAffine fit;
    double normal[9];
    fitCentred(bestSimdPath(), leaf.u.data(), leaf.q.data(), n, leaf.frame, leaf.prior_L, fit, normal);
    for (int trial = 0; trial < 5; ++trial) {
      CentredAffine moved = fit;
      double want = 0;
      for (int r = 0; r < 3; ++r) {
        const double dt = 1e-3 * uniform(rng);
        moved.t[r] += dt;
        want += double(n) * dt * dt;
      }
      for (int r = 0; r < 3; ++r) {
        double dl[3];
        for (int k = 0; k < 3; ++k) moved.L[3 * r + k] += dl[k] = 0.05 * uniform(rng);
        for (int j = 0; j < 3; ++j)
          for (int k = 0; k < 3; ++k) want += dl[j] * normal[3 * j + k] * dl[k];
      }
      EXPECT_NEAR(leaf.objective(moved) - leaf.objective(fit), want, 1e-9 * want + 1e-15) << n;
    }
  }
}

// Each correction is the nearest value, one nearer zero, or zero: pure rate (weight 0) codes
// every correction as zero; a ruling distortion weight rounds the translation to nearest and
// the linear part to no more error than rounding to nearest (an entry of a row of L may
// instead offset the others' rounding); in between, the choice never costs more bits +
// weighted added error (measured by predicting the points) than rounding to nearest, and is
// not always that rounding. The choice is the one a greedy pass over the twelve entries in
// order makes when it measures each candidate's error by predicting the points.
TEST(PredictiveOctree, CorrectionsAreRoundedForRatePlusDistortion) {
  std::mt19937 rng(6);
  const PredictiveModels models;
  const CentredAffine prior;  // corrections are the fit itself
  int differs = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const size_t n = 4 + size_t(trial);
    const LeafFixture leaf(n, rng);
    CentredAffine fit;
    double normal[9];
    fitCentred(bestSimdPath(), leaf.u.data(), leaf.q.data(), n, leaf.frame, leaf.prior_L, fit, normal);
    const CorrectionSteps steps = correctionSteps(leaf.frame, n, 0.002);
    LeafModel model{leaf.frame, prior};
    int64_t nearest[12], coded[12];
    for (int r = 0; r < 3; ++r) nearest[r] = std::llround(fit.t[r] / steps.translation);
    for (int k = 0; k < 9; ++k) nearest[3 + k] = std::llround(fit.L[k] / steps.linear);
    const auto rate = [&](const int64_t c[12]) {
      double bits = 0;
      for (int r = 0; r < 3; ++r) bits += classedCost(models.translation[r], c[r]);
      for (int k = 0; k < 9; ++k) bits += classedCost(models.linear, c[3 + k]);
      return bits;
    };
    quantiseCorrections(models, fit, prior, steps, n, normal, 0.0, coded);
    for (int64_t c : coded) EXPECT_EQ(c, 0);
    const double base = leaf.objective(fit);
    const auto added = [&](const int64_t c[12]) { return leaf.objective(codedAffine(model, steps, c)) - base; };
    quantiseCorrections(models, fit, prior, steps, n, normal, 1e30, coded);
    for (int r = 0; r < 3; ++r) EXPECT_EQ(coded[r], nearest[r]) << r;
    EXPECT_LE(added(coded), added(nearest) * (1 + 1e-9)) << trial;

    const double weight = 2e6;  // about where the encoder works at ME 1 %
    const double bits = quantiseCorrections(models, fit, prior, steps, n, normal, weight, coded);
    EXPECT_DOUBLE_EQ(bits, rate(coded));
    const auto cost = [&](const int64_t c[12]) { return rate(c) + weight * added(c); };
    EXPECT_LE(cost(coded), cost(nearest) + 1e-9 * cost(nearest)) << trial;
    int64_t greedy[12];
    std::copy(nearest, nearest + 12, greedy);
    for (int k = 0; k < 12; ++k) {
      const int64_t m = nearest[k];
      int64_t best = m;
      double best_cost = cost(greedy);
      for (const int64_t c : {m - (m > 0) + (m < 0), int64_t(0)}) {
        greedy[k] = c;
        if (cost(greedy) < best_cost) best = c, best_cost = cost(greedy);
      }
      greedy[k] = best;
    }
    for (int k = 0; k < 12; ++k) EXPECT_EQ(coded[k], greedy[k]) << trial << " entry " << k;
    differs += !std::equal(coded, coded + 12, nearest);
  }
  EXPECT_GT(differs, 0);
}

// A mesh that collapses to nearly a point and then spreads far out again (found by the
// round-trip fuzzer, tests/fuzz/fuzz_round_trip.cpp). After the collapse the reconstructed
// frame's cube has a side of about 4e-5, so in the default profile the vertex at (0, 35, 35),
// 8.5e5 sides away, needs a residual of 1.5e9 steps: beyond 2^30, so the encoder codes that
// frame as an intra frame, whose bound is E times its own cube's side, not the collapsed
// one's. The paper profile codes it as an inter frame (the far vertices escape to raw doubles).
// Every vertex must be within E·S as docs/affine_octree.md defines S, plus the rounding of the
// decoded floats (half a float step of each coordinate, more than E·S in a tiny cube).
TEST(AffineOctree, FarSpreadAfterCollapseStaysWithinTheBound) {
  Topology topology;
  topology.vertex_count = 4;
  topology.triangles = {{0, 1, 2}, {1, 3, 2}};
  const float a = -0.00390625f;
  const std::vector<std::vector<float>> frames = {
      {0, 0, 0, 0, 0, 0, 0, -1, a, a, a, a},
      {a, a, a, a, a, a, a, a, a, a, a, a},
      {a, a, a, 0.99609375f, 0, 0.02734375f, 0, 0, 0, 0, 35, 35},
  };
  const double max_error = 0.0005;
  for (Profile profile : {Profile::kPredictive, Profile::kPaper}) {
    SCOPED_TRACE(profile == Profile::kPaper ? "paper" : "predictive");
    MemorySequence seq(topology, frames);
    EncodeSettings settings;
    settings.octree().profile = profile;
    settings.octree().max_error = max_error;
    const std::string path = tempPath("collapse.ams");
    std::vector<std::vector<float>> encoder_view;
    auto report = encodeSequence(seq, settings, path, {},
                                 [&](int64_t, const float*, const float* r) { encoder_view.emplace_back(r, r + 12); });
    ASSERT_TRUE(report.ok()) << report.status().message();
    const auto decoded = decodeAll(path);
    ASSERT_EQ(decoded.size(), frames.size());
    EXPECT_EQ(decoded, encoder_view);
    const std::vector<bool> intra = testing_support::intraFrames(path);
    const std::vector<bool> expected_intra = {true, false, profile == Profile::kPredictive};
    EXPECT_EQ(intra, expected_intra);
    EXPECT_EQ(report.value().intra_frames, profile == Profile::kPredictive ? 2u : 1u);
    for (size_t f = 0; f < frames.size() && f < intra.size(); ++f) {
      const std::vector<float>& cube_of = intra[f] ? frames[f] : decoded[f - 1];
      const double side = boundingCube(std::vector<double>(cube_of.begin(), cube_of.end())).side;
      for (size_t i = 0; i < frames[f].size(); i += 3) {
        const float* d = &decoded[f][i];
        const double error = std::hypot(d[0] - frames[f][i], d[1] - frames[f][i + 1], d[2] - frames[f][i + 2]);
        const double rounding = 0x1p-24 * (std::fabs(d[0]) + std::fabs(d[1]) + std::fabs(d[2]));
        EXPECT_LE(error, max_error * side * (1 + 1e-9) + rounding) << "frame " << f << " vertex " << i / 3;
      }
    }
    std::remove(path.c_str());
  }
}

}  // namespace
}  // namespace animc
