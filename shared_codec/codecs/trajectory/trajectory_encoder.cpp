// SPDX-License-Identifier: Apache-2.0
// The trajectory encoders (codecs 3 and 5): principal components of a group's trajectories
// (Eigen), one set for the whole mesh (codec 3) or one per part of it (codec 5), then the
// coarsest coefficient step, common to the parts, that meets the target error, measured on
// the frames the decoder will produce.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <utility>

#include "codecs/trajectory/clusters.h"
#include "codecs/trajectory/group_coding.h"
#include "codecs/trajectory/group_frames.h"
#include "codecs/trajectory/part_encoder.h"
#include "codecs/trajectory/parted_group.h"
#include "codecs/trajectory/step_search.h"
#include "codecs/trajectory/trajectory_codec.h"
#include "core/parallel.h"

namespace animc {
namespace {

// The trajectories of one group: at most this many values (128 MB in float). Since
// the components are at most 3 x frames, the coefficients then stay within the decoders'
// kMaxTrajectoryCoefficients too.
constexpr uint64_t kMaxGroupValues = uint64_t(1) << 25;
static_assert(kMaxGroupValues <= kMaxTrajectoryCoefficients, "a group's coefficients must fit the format's limit");
// The components computed first: for the whole mesh, and for each part of a cut into several
// (a part needs fewer, and the first cut's parts would otherwise cost more passes over the
// trajectories than the whole mesh's).
constexpr Eigen::Index kFirstComponents = 64;
constexpr Eigen::Index kFirstPartComponents = 32;
// Codec 5's scores of its cuts wobble a little from one count of parts to the next (on the
// golden files' 30 frames of sydney_md2 at KG 0.5 %, 2 parts score 0.2 % above 4 and 1 part
// below both), but past a cut this much above the best, fewer parts scored worse still on the
// shared sequences at KG 0.1-1 %: the coarser cuts are not scored.
constexpr double kCloseScore = 1.05;
// Rounds of refinement of the chosen cut's basis and coefficients (PartEncoder::refine()).
// Each round takes back more of the quantisation error; a third gained less on the shared
// sequences than the second, for as much time (docs/trajectory.md, "Quantisation").
constexpr int kRefinementRounds = 2;

class TrajectoryEncoder final : public GroupEncoder {
 public:
  // max_parts 0: codec 3's groups; otherwise codec 5's, of at most max_parts parts.
  TrajectoryEncoder(const TrajectoryOptions& options, uint32_t max_parts, const Topology& topology, SimdPath path)
      : topology_(topology), order_(topology), max_parts_(max_parts) {
    context_.options = options;
    context_.path = path;
    context_.mesh_vertices = topology.vertex_count;
  }

  uint32_t maxGroupFrames() const override {
    const uint64_t by_memory = std::max<uint64_t>(1, kMaxGroupValues / (uint64_t(3) * vertices()));
    return uint32_t(std::min<uint64_t>(context_.options.group_frames, by_memory));
  }

  void encodeGroup(const float* frames, uint32_t frame_count, std::vector<std::vector<uint8_t>>& payloads) override {
    decoded_.clear();  // the last group's, no longer asked for
    prepare(frames, frame_count);
    Candidate chosen = chooseParts();
    current_ = &chosen;
    std::vector<TrajectoryGroup> groups(chosen.count());
    for (uint32_t c = 0; c < chosen.count(); ++c) {
      chosen.encoders[c]->quantise(chosen.step, groups[c]);
      chosen.encoders[c]->release();  // before the decoded frames take as much memory
    }
    std::vector<uint8_t> payload;
    write(groups, payload);
    payloads.assign(frame_count, std::vector<uint8_t>{kTrajectoryNextFrame});
    payloads[0] = std::move(payload);
    mesh_parts_ = std::move(chosen.mesh_parts);
    decoded_.resize(groups.size());
    for (uint32_t c = 0; c < groups.size(); ++c) {
      GroupBasis basis = dequantisedBasis(groups[c]);
      decoded_[c].reset(basis, groups[c], orderOf(c), context_.path);
    }
    current_ = nullptr;
    trial_groups_.clear();
    context_.original = nullptr;
  }

  bool reconstruction(uint32_t k, float* xyz) const override {
    if (!parted()) {
      decoded_[0].frame(k, xyz);
      return true;
    }
    for (size_t c = 0; c < decoded_.size(); ++c) decoded_[c].frameInto(k, mesh_parts_->members[c].data(), xyz);
    return true;
  }

 private:
  // A group cut into parts, each with its encoder, while a count of parts is chosen and its
  // step searched.
  struct Candidate {
    std::vector<std::unique_ptr<PartEncoder>> encoders;  // of each part
    std::vector<uint8_t> labels;                         // codec 5: the part of each vertex
    std::unique_ptr<MeshParts> mesh_parts;               // codec 5: the sub-meshes of the parts
    double step = NAN;                                   // the coefficient step, or a guess of it
    uint32_t count() const { return uint32_t(encoders.size()); }
  };

  uint32_t vertices() const { return context_.mesh_vertices; }
  bool parted() const { return max_parts_ > 0; }
  const float* vertexOf(uint32_t t, uint32_t v) const { return context_.original + (size_t(t) * vertices() + v) * 3; }
  const CodingOrder& orderOf(uint32_t part) const { return parted() ? *mesh_parts_->orders[part] : order_; }
  const std::vector<std::unique_ptr<PartEncoder>>& parts() const { return current_->encoders; }

  // The counts of parts tried, most first: codec 3, one part; codec 5, the most parts asked
  // for, then half as many each time, and 2 and 1. A mesh moving as a few large parts pays for
  // the labels and bases of more parts than it has (docs/trajectory.md, "Parts").
  std::vector<uint32_t> partCounts() const {
    if (!parted()) return {1};
    std::vector<uint32_t> counts = {max_parts_};
    for (uint32_t fewer = max_parts_ / 2; fewer > 2; fewer /= 2) counts.push_back(fewer);
    for (uint32_t fewer : {2u, 1u})
      if (fewer < max_parts_) counts.push_back(fewer);
    return counts;
  }

  void prepare(const float* frames, uint32_t frame_count) {
    context_.original = frames;
    context_.refinement_rounds = 0;
    context_.frames = frame_count;
    const std::array<double, 3> s = boxSides(0);
    context_.diagonal = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    context_.cube_sides.clear();  // measure() compares with them at every step the search tries
    if (context_.options.rate == TrajectoryRate::kMaxError) {
      context_.cube_sides.resize(frame_count);
      parallelFor(frame_count, 6.0 * vertices(), [&](size_t t) { context_.cube_sides[t] = cubeSide(uint32_t(t)); });
    }
    context_.spread = context_.options.rate == TrajectoryRate::kTargetKg ? spread() : 0;
  }

  // The first count of parts is cut and searched in full. Each other count is a coarser cut,
  // whose parts are unions of the first's, with components merged from the first's: it is
  // judged at the first cut's step, by its bits and error together, in one trial, until one
  // scores well above the best. Only the best coarser cut, if it beats the first, is then
  // decomposed and searched (docs/trajectory.md, "Parts").
  Candidate chooseParts() {
    const std::vector<uint32_t> counts = partCounts();
    uint32_t count = 0;
    std::vector<uint8_t> labels =
        parted() ? clusterTrajectories(context_.original, vertices(), context_.frames, counts[0], count)
                 : std::vector<uint8_t>();
    Candidate first = cut(std::move(labels), count);
    search(first);
    if (counts.size() == 1) return refined(std::move(first));
    const double q = first.step;
    double best_cost = cost(first, q);
    Candidate coarser;  // the best of the merged cuts, once one beats the first
    for (size_t i = 1; i < counts.size(); ++i) {
      if (counts[i] >= first.count()) continue;  // the mesh has fewer vertices
      Candidate merged = mergedFrom(first, counts[i], q);
      const double merged_cost = cost(merged, q);
      if (merged_cost > kCloseScore * best_cost) break;  // fewer parts only score worse
      if (merged_cost >= best_cost) continue;
      best_cost = merged_cost;
      coarser = std::move(merged);
    }
    if (coarser.count() == 0) return refined(std::move(first));
    first = Candidate();  // the memory of its components
    // The merged components left out the fine parts' weakest: the parts kept get their own.
    Candidate chosen = cut(std::move(coarser.labels), coarser.count());
    chosen.step = q;
    search(chosen);
    return refined(std::move(chosen));
  }

  // The cut chosen, its step searched again from the one found, now with its basis and
  // coefficients refined in every quantisation, which lowers the squared error at a step.
  // The cuts are compared and the components chosen without it, which it changes little. A
  // max error is not refined: the fits lower the sum of squares, not the largest error, which
  // they moved either way. Nor is a cut of parts too large to refine.
  Candidate refined(Candidate candidate) {
    if (context_.options.rate == TrajectoryRate::kMaxError) return candidate;
    const auto& parts = candidate.encoders;
    if (std::none_of(parts.begin(), parts.end(), [](const auto& part) { return part->refinable(); })) return candidate;
    context_.refinement_rounds = kRefinementRounds;
    current_ = &candidate;
    candidate.step = chooseStep(candidate.step);
    current_ = nullptr;
    return candidate;
  }

  // The group as one part, the whole mesh (codec 3), or in the `count` parts of `labels`
  // (codec 5), with the components the model's step asks for.
  Candidate cut(std::vector<uint8_t> labels, uint32_t count) {
    static const std::vector<uint32_t> kWholeMesh;
    Candidate candidate;
    if (!parted()) {
      candidate.encoders.push_back(std::make_unique<PartEncoder>(context_, order_, kWholeMesh));
    } else {
      candidate.labels = std::move(labels);
      candidate.mesh_parts = std::make_unique<MeshParts>(topology_, candidate.labels, count);
      for (uint32_t c = 0; c < count; ++c)
        candidate.encoders.push_back(std::make_unique<PartEncoder>(context_, *candidate.mesh_parts->orders[c],
                                                                   candidate.mesh_parts->members[c]));
    }
    current_ = &candidate;
    const Eigen::Index first = candidate.count() > 1 ? kFirstPartComponents : kFirstComponents;
    for (const auto& part : parts()) part->extend(first);
    extendForModel();
    current_ = nullptr;
    return candidate;
  }

  // The cut of at most `most` parts that are unions of the fine cut's, each with components
  // merged from those of its fine parts that step q might send.
  Candidate mergedFrom(const Candidate& fine, uint32_t most, double q) const {
    Candidate coarse;
    uint32_t count = 0;
    coarse.labels = mergeParts(context_.original, vertices(), context_.frames, fine.labels, fine.count(), most, count);
    coarse.mesh_parts = std::make_unique<MeshParts>(topology_, coarse.labels, count);
    std::vector<uint32_t> index_in_fine(vertices());
    for (const std::vector<uint32_t>& members : fine.mesh_parts->members)
      for (uint32_t i = 0; i < members.size(); ++i) index_in_fine[members[i]] = i;
    for (uint32_t c = 0; c < count; ++c) {
      const CodingOrder& order = *coarse.mesh_parts->orders[c];
      const std::vector<uint32_t>& members = coarse.mesh_parts->members[c];
      std::vector<MergedSet> sets;
      std::vector<int> set_of(fine.count(), -1);
      std::vector<RowSource> rows(order.vertex.size());
      for (size_t p = 0; p < rows.size(); ++p) {
        const uint32_t v = members[order.vertex[p]], f = fine.labels[v];
        if (set_of[f] < 0) {
          set_of[f] = int(sets.size());
          sets.push_back({&fine.encoders[f]->components(), 0});
        }
        rows[p] = {uint32_t(set_of[f]), fine.encoders[f]->row(index_in_fine[v])};
      }
      for (uint32_t f = 0; f < fine.count(); ++f)
        if (set_of[f] >= 0) sets[size_t(set_of[f])].used = worthMerging(*fine.encoders[f], q);
      const double least = leastWorthSending(q, uint32_t(members.size()), context_.frames);
      coarse.encoders.push_back(
          std::make_unique<PartEncoder>(context_, order, members, mergedComponents(sets, rows, least)));
    }
    return coarse;
  }

  // The components of a fine part a merge takes at step q: those worth sending in the part
  // itself (a union needs no weaker ones unless the same weak motion runs through its parts).
  static Eigen::Index worthMerging(const PartEncoder& part, double q) {
    const Eigen::VectorXd& sigma = part.components().sigma;
    const double least = part.leastWorthSending(q);
    Eigen::Index k = 0;
    while (k < sigma.size() && sigma[k] * sigma[k] >= least) ++k;
    return k;
  }

  // The bits of the candidate's payload at step q plus its squared error in bits, at the
  // error a bit buys at that step.
  double cost(Candidate& candidate, double q) {
    current_ = &candidate;
    const double bits = 8.0 * double(trialPayloadSize(q));
    const double error = measure(q).squared;
    current_ = nullptr;
    return bits + error / (kBitSlope * q * q);
  }

  // The payload of groups, the parts of the candidate being coded.
  void write(const std::vector<TrajectoryGroup>& groups, std::vector<uint8_t>& out) const {
    if (!parted()) return writeTrajectoryGroup(groups[0], order_, out);
    writePartedGroup(context_.frames, current_->labels, order_, *current_->mesh_parts, groups, out);
  }

  // The candidate's step, and the leading components only, as many as that step might send:
  // more while the weakest of a part's could still be worth its bits.
  void search(Candidate& candidate) {
    current_ = &candidate;
    for (;;) {
      candidate.step = chooseStep(candidate.step);
      if (!extendForStep(candidate.step)) break;
      extendForModel();
    }
    current_ = nullptr;
  }

  // More components for the parts that clearly have too few at the model's step. The model's
  // step can be off by half: the parts are judged at twice it.
  void extendForModel() {
    for (;;) {
      const double optimistic = 2 * predictedStep();
      bool any = false;
      for (const auto& part : parts()) {
        if (part->components().complete || !part->clearlyTooFew(optimistic)) continue;
        part->extend(part->moreComponents(optimistic));
        any = true;
      }
      if (!any) return;
    }
  }

  // More components for the parts whose weakest could still be worth their bits at step q;
  // whether any part had some.
  bool extendForStep(double q) {
    bool any = false;
    for (const auto& part : parts()) {
      if (part->components().complete || part->carriesEnough(q) || part->sendsNoneOfTheWeakest(float(q))) continue;
      part->extend(part->moreComponents(q));
      any = true;
    }
    return any;
  }

  // The sides of frame t's bounding box.
  std::array<double, 3> boxSides(uint32_t t) const {
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (uint32_t v = 0; v < vertices(); ++v)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], double(vertexOf(t, v)[c]));
        hi[c] = std::max(hi[c], double(vertexOf(t, v)[c]));
      }
    return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  }

  // The largest side of frame t's bounding box, 1 for a point (the affine-octree's cube).
  double cubeSide(uint32_t t) const {
    const std::array<double, 3> s = boxSides(t);
    const double side = std::max({s[0], s[1], s[2]});
    return side > 0 ? side : 1;
  }

  // Sum over the group's frames of |x - centroid of its frame|^2: the KG error's denominator.
  double spread() const {
    double sum = 0;
    for (uint32_t t = 0; t < context_.frames; ++t) {
      double centroid[3] = {0, 0, 0};
      for (uint32_t v = 0; v < vertices(); ++v)
        for (int c = 0; c < 3; ++c) centroid[c] += vertexOf(t, v)[c];
      for (double& c : centroid) c /= vertices();
      for (uint32_t v = 0; v < vertices(); ++v)
        for (int c = 0; c < 3; ++c) sum += (vertexOf(t, v)[c] - centroid[c]) * (vertexOf(t, v)[c] - centroid[c]);
    }
    return sum;
  }

  // The step the search will probably choose (a model's), or the fixed step; infinity for a
  // budget (no prediction).
  double predictedStep() const {
    switch (context_.options.rate) {
      case TrajectoryRate::kTargetKg:
      case TrajectoryRate::kMaxError: return std::exp2(modelledStep(stepRange()));
      case TrajectoryRate::kStep: return chooseStep();
      case TrajectoryRate::kBitsPerVertexFrame: return HUGE_VAL;
    }
    return HUGE_VAL;
  }

  // The coefficient step of the rate mode: fixed, or searched on its logarithm (the error
  // grows and the size falls with the step), starting from `near` (a step found before, for
  // components or parts that differ little), or else from a model's prediction.
  double chooseStep(double near = NAN) const {
    const double value = context_.options.rate_value;
    StepSearch search = stepRange();
    const bool known = std::isfinite(near) && near > 0;
    std::function<double(double)> excess;
    switch (context_.options.rate) {
      case TrajectoryRate::kStep: return std::max(value * context_.diagonal, std::exp2(search.lowest));
      case TrajectoryRate::kTargetKg: {
        search.guess = known ? std::log2(near) : modelledStep(search);
        search.slope = 2;  // a squared error
        const double allowed = context_.allowedAtMost();
        excess = [&, allowed](double u) { return log2Ratio(measure(std::exp2(u)).squared, allowed); };
        break;
      }
      case TrajectoryRate::kMaxError:
        search.guess = known ? std::log2(near) : modelledStep(search);
        excess = [&](double u) { return log2Ratio(measure(std::exp2(u)).worst, 1) / 2; };
        break;
      case TrajectoryRate::kBitsPerVertexFrame: {
        // The size falls as the step grows: the search runs on -u.
        const double budget = value * vertices() * context_.frames / 8;
        search = {-search.highest, -search.lowest, known ? -std::log2(near) : 8 - search.highest};
        search.slope = 0.5;
        excess = [&, budget](double v) { return log2Ratio(double(trialPayloadSize(std::exp2(-v))), budget); };
        return std::exp2(-searchStep(search, excess));
      }
    }
    return std::exp2(searchStep(search, excess));
  }

  // The payload of the group at step q, in trial_groups_ (their buffers kept from one trial to
  // the next: a large group's would otherwise be new pages at every trial).
  size_t trialPayloadSize(double q) const {
    trial_groups_.resize(parts().size());
    for (size_t c = 0; c < parts().size(); ++c) parts()[c]->quantise(q, trial_groups_[c]);
    std::vector<uint8_t> payload;
    write(trial_groups_, payload);
    return payload.size();
  }

  // log2 of the finest step the payload allows, and of a step past any error.
  StepSearch stepRange() const {
    double largest = 0;
    for (const auto& part : parts()) largest = std::max(largest, part->largestCoefficient());
    const double scale = std::max({largest, context_.diagonal, 1e-30});
    StepSearch search;
    search.lowest = std::log2(std::max(largest / kMaxQuantised, scale * 1e-12));
    search.highest = std::log2(2 * scale);
    return search;
  }

  static double log2Ratio(double value, double bound) {
    if (value <= 0) return -HUGE_VAL;
    return bound > 0 ? std::log2(value / bound) : HUGE_VAL;
  }

  // log2 of the step at which a model of the squared error meets the modelled allowance:
  // every component costs its energy or a uniform quantiser's error on each of its part's
  // vertices, whichever is smaller (reverse water-filling), plus what the components computed
  // leave out.
  double modelledStep(const StepSearch& range) const {
    const double allowed = context_.modelledAllowance();
    auto model = [&](double u) {
      double e = 0;
      for (const auto& part : parts()) {
        const Components& pc = part->components();
        const double per_component = part->vertices() * std::exp2(2 * u) / 12;
        double part_error = part->leftOut();
        for (Eigen::Index k = 0; k < pc.sigma.size(); ++k)
          part_error += std::min(pc.sigma[k] * pc.sigma[k], per_component);
        e += part_error;
      }
      return e;
    };
    double lo = range.lowest, hi = range.highest;
    for (int i = 0; i < 50; ++i) {
      const double mid = (lo + hi) / 2;
      (model(mid) <= allowed ? lo : hi) = mid;
    }
    return lo;
  }

  struct GroupError {
    double squared = 0;  // summed over the group's vertices and frames
    double worst = 0;    // the largest squared distance over the max error's (kMaxError)
  };

  // The error of the frames the decoder will make of the group at `step`.
  GroupError measure(double step) const {
    const bool max_error = context_.options.rate == TrajectoryRate::kMaxError;
    GroupError e;
    std::vector<double> frame_worst(max_error ? context_.frames : 0, 0);
    for (const auto& part : parts()) {
      const PartError p = part->measure(step, max_error);
      e.squared += p.squared;
      for (size_t t = 0; t < frame_worst.size(); ++t) frame_worst[t] = std::max(frame_worst[t], p.frame_worst[t]);
    }
    for (size_t t = 0; t < frame_worst.size(); ++t) {
      const double bound = context_.options.rate_value * context_.cube_sides[t];
      e.worst = std::max(e.worst, frame_worst[t] / (bound * bound));
    }
    return e;
  }

  const Topology& topology_;
  CodingOrder order_;  // of the whole mesh
  uint32_t max_parts_;
  GroupContext context_;
  const Candidate* current_ = nullptr;     // the candidate being coded
  std::unique_ptr<MeshParts> mesh_parts_;  // codec 5: the last group's parts
  std::vector<GroupFrames> decoded_;       // the last group's parts as decoded
  mutable std::vector<TrajectoryGroup> trial_groups_;
};

}  // namespace

std::unique_ptr<GroupEncoder> makeTrajectoryEncoder(const TrajectoryOptions& options, const Topology& topology,
                                                    SimdPath path) {
  return std::make_unique<TrajectoryEncoder>(options, 0, topology, path);
}

std::unique_ptr<GroupEncoder> makeTrajectory2Encoder(const Trajectory2Options& options, const Topology& topology,
                                                     SimdPath path) {
  return std::make_unique<TrajectoryEncoder>(options.trajectory, options.parts, topology, path);
}

}  // namespace animc
