// SPDX-License-Identifier: Apache-2.0
// Design measurement for the trajectory codec's next version (issue 40): where the bytes of a
// trajectory-coded .ams go. Each group payload is read back (readTrajectoryGroup) and written
// again with parts left out, the codec's own writer measuring them:
//   head          Frame_Type, counts and the steps (13 + 4 K bytes);
//   mean          the mean trajectory: the group written with no component, less the head;
//   basis         the K basis vectors: the group with every coefficient 0, less the above;
//   coefficients  the rest of the payload (its zeros' few bytes are counted with the basis).
// And what the mean and the basis would cost with a second-order prediction along time (each
// value from the two before it, b[t-1] + (b[t-1] - b[t-2]), instead of the value before it):
// the rows are rewritten so that the codec's own first-order coder sees second differences.
// Prints one JSON object a file: those bytes summed over the groups, the components of each
// group, and the file's other bytes (header, connectivity, the one-byte frame records).
// trajectory_bits.py builds it (one g++ line against build/'s libanimc.a) and runs it.
//   usage: trajectory_bits FILE.ams...
#include <cstdio>
#include <string>
#include <vector>

#include "trajectory_file.h"

namespace {

struct Parts {
  double head = 0, mean = 0, basis = 0, coefficients = 0, group_payloads = 0;
  double mean_second_order = 0, basis_second_order = 0;
  std::vector<uint32_t> components;
};

size_t written(const animc::TrajectoryGroup& g, const animc::CodingOrder& order) {
  std::vector<uint8_t> out;
  animc::writeTrajectoryGroup(g, order, out);
  return out.size() + 1;  // and the Frame_Type byte read before the group
}

// A row of 3G values (x over the G frames, then y, then z) rewritten so that its first
// differences are the second differences of the original (the first two values of each
// coordinate kept as they are, as a first-order coder sees them).
void toSecondOrder(int32_t* row, uint32_t frames) {
  for (uint32_t c = 0; c < 3; ++c) {
    int32_t* b = row + size_t(c) * frames;
    std::vector<int64_t> w(frames);
    for (uint32_t t = 0; t < frames; ++t)
      w[t] = t < 2 ? b[t] : w[t - 1] + int64_t(b[t]) - 2 * int64_t(b[t - 1]) + b[t - 2];
    for (uint32_t t = 0; t < frames; ++t) b[t] = int32_t(w[t]);
  }
}

void addGroup(const std::vector<uint8_t>& payload, const animc::TrajectoryGroup& g, const animc::CodingOrder& order,
              Parts& parts) {
  animc::TrajectoryGroup no_components = g;
  no_components.components = 0;
  no_components.basis.clear();
  no_components.basis_step.clear();
  no_components.coefficients.clear();
  animc::TrajectoryGroup zero_coefficients = g;
  std::fill(zero_coefficients.coefficients.begin(), zero_coefficients.coefficients.end(), 0);
  const double head = 13 + 4.0 * g.components;
  const double mean_end = double(written(no_components, order)), basis_end = double(written(zero_coefficients, order));
  parts.head += head;
  parts.mean += mean_end - 13;
  parts.basis += basis_end - mean_end - 4.0 * g.components;
  parts.coefficients += double(payload.size()) - basis_end;
  parts.group_payloads += double(payload.size());
  animc::TrajectoryGroup second = zero_coefficients;
  const size_t row = size_t(3) * g.frames;
  toSecondOrder(second.mean.data(), g.frames);
  for (uint32_t k = 0; k < g.components; ++k) toSecondOrder(second.basis.data() + k * row, g.frames);
  animc::TrajectoryGroup second_mean = no_components;
  second_mean.mean = second.mean;
  const double second_mean_end = double(written(second_mean, order));
  parts.mean_second_order += second_mean_end - 13;
  parts.basis_second_order += double(written(second, order)) - second_mean_end - 4.0 * g.components;
  parts.components.push_back(g.components);
}

int measure(const std::string& path) {
  TrajectoryFile file;
  if (!file.open("trajectory_bits", path)) return 1;
  const animc::CodingOrder& order = *file.order;
  animc::AmsSource* source = file.source.get();
  Parts parts;
  std::vector<uint8_t> payload;
  for (size_t g = 0; g < file.groups(); ++g) {
    animc::TrajectoryGroup group;
    if (file.read(g, payload, group)) addGroup(payload, group, order, parts);
  }
  std::printf("{\"file\": \"%s\", \"vertices\": %u, \"frames\": %lld, \"file_bytes\": %llu, \"head\": %.0f, "
              "\"mean\": %.0f, \"basis\": %.0f, \"coefficients\": %.0f, \"mean_second_order\": %.0f, "
              "\"basis_second_order\": %.0f, \"components\": [",
              path.c_str(), unsigned(order.vertex.size()), (long long)source->frameCount(),
              (unsigned long long)source->info().file_bytes, parts.head, parts.mean, parts.basis,
              parts.coefficients, parts.mean_second_order, parts.basis_second_order);
  for (size_t i = 0; i < parts.components.size(); ++i) std::printf("%s%u", i ? ", " : "", parts.components[i]);
  std::printf("]}\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return measureEach(argc, argv, measure); }
