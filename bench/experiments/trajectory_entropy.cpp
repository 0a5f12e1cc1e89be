// SPDX-License-Identifier: Apache-2.0
// Design measurement for the trajectory codec's next entropy layer (issue 40: decoding at
// 100 M vertices/s a core). Each part of each group of a codec-5 file is read back
// (readTrajectoryGroup) and turned into the values its coder codes, in its order, each with
// its model: the mean's and basis rows' differences along time, the coefficients less their
// predictions (group_coding.cpp). Those values, with their models known in advance (so both
// coders below decode the same work), are then coded two ways:
//   adaptive  today's: the codec's range coder and classed integer models
//             (entropy/classed_integer.h), one chain through every value;
//   static    each model's magnitude classes (0 for zero, 1..30, 31 = escape to 5 raw bits)
//             with counts measured by the encoder and sent with the stream (their cost is
//             estimated below), coded by rANS (Duda 2013) with 12-bit frequencies, four
//             interleaved states and byte-wise renormalisation, the symbol found by a table;
//             the sign and low bits raw, as today.
// For each it prints the bytes and the best of 15 decoding times of the whole stream (values
// into an array, no prediction or reconstruction), as JSON.
//   usage: trajectory_entropy FILE.ams (codec 5, trajectory2)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <vector>

#include "codecs/trajectory/parted_group.h"
#include "entropy/classed_integer.h"
#include "trajectory_file.h"

namespace {

using animc::ClassedIntegerModel;

// The codec's models: the mean, each basis band, each coefficient band x prediction kind.
constexpr int kPredictionKinds = 3;
constexpr int kModels = 1 + animc::kCoefficientBands + animc::kCoefficientBands * kPredictionKinds;

struct Values {
  std::vector<uint8_t> model;
  std::vector<int32_t> value;
  void add(int m, int64_t v) {
    model.push_back(uint8_t(m));
    value.push_back(int32_t(v));
  }
};

// What group_coding.cpp codes for one part, in its order.
void collect(const animc::TrajectoryGroup& g, const animc::CodingOrder& order, Values& out) {
  const uint32_t frames = g.frames;
  auto row = [&](int model, const int32_t* values) {
    for (uint32_t c = 0; c < 3; ++c) {
      int64_t previous = 0;
      for (uint32_t t = 0; t < frames; ++t) {
        out.add(model, values[c * frames + t] - previous);
        previous = values[c * frames + t];
      }
    }
  };
  row(0, g.mean.data());
  for (uint32_t k = 0; k < g.components; ++k)
    row(1 + animc::coefficientBand(k), g.basis.data() + size_t(k) * 3 * frames);
  std::vector<int64_t> sum(g.components);
  for (uint32_t p = 0; p < order.vertex.size(); ++p) {
    const uint32_t begin = order.first[p], end = order.first[p + 1];
    std::fill(sum.begin(), sum.end(), 0);
    for (uint32_t i = begin; i < end; ++i)
      for (uint32_t k = 0; k < g.components; ++k)
        sum[k] += g.coefficients[size_t(order.earlier[i]) * g.components + k];
    for (uint32_t k = 0; k < g.components; ++k) {
      int64_t prediction = 0;
      int kind = 0;
      if (end > begin) {
        prediction = animc::roundedMean(sum[k], end - begin);
        kind = prediction == 0 ? 1 : 2;
      }
      const int model = 1 + animc::kCoefficientBands + animc::coefficientBand(k) * kPredictionKinds + kind;
      out.add(model, g.coefficients[size_t(p) * g.components + k] - prediction);
    }
  }
}

template <class Decode>
double bestSeconds(Decode decode) {
  double best = 1e30;
  for (int run = 0; run < 15; ++run) {
    const auto start = std::chrono::steady_clock::now();
    decode();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

// ---- adaptive: today's coder ----

size_t adaptiveBytes(const Values& v, std::vector<uint8_t>& coded, size_t& raw_start) {
  std::vector<ClassedIntegerModel> models(kModels);
  animc::RangeEncoder rc(coded);
  animc::RawBitWriter raw;
  for (size_t i = 0; i < v.value.size(); ++i) animc::encodeClassed(rc, raw, models[v.model[i]], v.value[i]);
  rc.finish();
  raw_start = coded.size();
  raw.appendTo(coded);
  return coded.size();
}

void adaptiveDecode(const Values& v, const std::vector<uint8_t>& coded, std::vector<int32_t>& out) {
  std::vector<ClassedIntegerModel> models(kModels);
  animc::RangeDecoder rc(coded.data(), coded.size());
  animc::RawBitReader raw(coded.data(), coded.size());
  const size_t n = v.value.size();
  for (size_t i = 0; i < n; ++i) out[i] = int32_t(animc::decodeClassed(rc, raw, models[v.model[i]]));
}

// The raw bits of a value of class c >= 1 (the sign, then the low bits), as encodeClassed()
// writes them.
inline void writeRawOfClass(animc::RawBitWriter& raw, uint32_t c, int64_t value) {
  const int low_bits = animc::lowBitsOfClass(c);
  const uint64_t magnitude = uint64_t(value < 0 ? -value : value);
  raw.write(uint32_t((uint64_t(value < 0) << low_bits) | (magnitude & ((uint64_t(1) << low_bits) - 1))),
            animc::rawBitsOfClass(c));
}

// The value of class c >= 1 from its raw bits (the sign, then the low bits), as
// decodeClassed() makes it.
inline int32_t valueOfClass(uint32_t c, animc::RawBitReader& raw) {
  const int low_bits = animc::lowBitsOfClass(c);
  const uint32_t r = raw.read(animc::rawBitsOfClass(c));
  const int64_t magnitude = int64_t(animc::magnitudeOf(c, r & ((1u << low_bits) - 1)));
  const int64_t negative = -int64_t(r >> low_bits);
  return int32_t((magnitude ^ negative) - negative);
}

// rANS with kStates interleaved states, value i in state i % kStates: the encoder's bytes
// come last to first (each state flushed at the end), so the decoder reads them in order.
constexpr int kStates = 4;

// Ends an encoding: the states, then the bytes reversed into the stream's order.
std::vector<uint8_t> finishStates(const uint32_t (&state)[kStates], std::vector<uint8_t>& reversed) {
  for (int k = kStates; k-- > 0;)
    for (int b = 0; b < 4; ++b) reversed.push_back(uint8_t(state[k] >> (8 * b)));
  return std::vector<uint8_t>(reversed.rbegin(), reversed.rend());
}

// Decodes the n values of a stream that starts at p: decode_one(state, p, i) gives value i.
template <class DecodeOne>
void decodeInterleaved(const uint8_t* p, size_t n, std::vector<int32_t>& out, DecodeOne decode_one) {
  uint32_t x[kStates];
  for (int k = 0; k < kStates; ++k) {
    x[k] = 0;
    for (int b = 3; b >= 0; --b) x[k] = (x[k] << 8) | *p++;
  }
  size_t i = 0;
  for (; i + kStates <= n; i += kStates)
    for (int k = 0; k < kStates; ++k) out[i + k] = decode_one(x[k], p, i + k);
  for (; i < n; ++i) out[i] = decode_one(x[i % kStates], p, i);
}

// ---- static: rANS over magnitude classes ----

constexpr int kClasses = 32;  // 0 = zero, 1..30, 31 = escape (5 raw bits more)
constexpr int kFrequencyBits = 12;
constexpr uint32_t kTotal = 1u << kFrequencyBits;
constexpr uint32_t kLow = 1u << 23;  // states live in [kLow, 256 kLow)

uint32_t classOf(int32_t v) {
  const uint32_t c = animc::magnitudeClass(uint64_t(v < 0 ? -int64_t(v) : v));
  return std::min<uint32_t>(c, kClasses - 1);
}

struct StaticModel {
  uint32_t frequency[kClasses] = {};
  uint32_t start[kClasses + 1] = {};
  uint8_t symbol_of_slot[kTotal] = {};
};

// Counts scaled to kTotal, every class seen keeping at least 1; returns the bits of sending
// them: per class seen, its index (5 bits) and its frequency (Elias gamma), and a class count.
double normalise(const std::vector<uint64_t>& counts, StaticModel& m) {
  uint64_t total = 0;
  for (uint64_t c : counts) total += c;
  if (total == 0) return 0;
  int64_t left = kTotal;
  int largest = 0;
  for (int s = 0; s < kClasses; ++s) {
    if (counts[s] == 0) continue;
    m.frequency[s] = std::max<uint32_t>(1, uint32_t(double(counts[s]) * kTotal / double(total)));
    left -= m.frequency[s];
    if (counts[s] > counts[largest]) largest = s;
  }
  m.frequency[largest] = uint32_t(std::max<int64_t>(1, int64_t(m.frequency[largest]) + left));  // the rest
  double bits = 5;
  for (int s = 0; s < kClasses; ++s) {
    m.start[s + 1] = m.start[s] + m.frequency[s];
    for (uint32_t slot = m.start[s]; slot < m.start[s + 1]; ++slot) m.symbol_of_slot[slot] = uint8_t(s);
    if (m.frequency[s] > 0) bits += 5 + 2 * std::floor(std::log2(double(m.frequency[s]))) + 1;
  }
  return bits;
}

struct StaticStream {
  std::vector<StaticModel> models = std::vector<StaticModel>(kModels);
  std::vector<uint8_t> rans;  // the states' flush first, then the renormalisation bytes
  std::vector<uint8_t> raw;   // RawBitWriter's bytes
  double table_bits = 0;
  double ideal_bits = 0;  // of the classes, at the measured frequencies
};

// Each model's classes counted over `sets`, scaled: the tables, and the bits of sending them.
double tablesOf(const std::vector<const Values*>& sets, std::vector<StaticModel>& models) {
  std::vector<std::vector<uint64_t>> counts(kModels, std::vector<uint64_t>(kClasses));
  for (const Values* v : sets)
    for (size_t i = 0; i < v->value.size(); ++i) ++counts[v->model[i]][classOf(v->value[i])];
  double bits = 0;
  for (int m = 0; m < kModels; ++m) bits += normalise(counts[m], models[m]);
  return bits;
}

// v coded with `models` (its own tables when null: their bits are counted in table_bits).
StaticStream staticEncode(const Values& v, const std::vector<StaticModel>* models = nullptr) {
  StaticStream s;
  if (models) {
    s.models = *models;
  } else {
    s.table_bits = tablesOf({&v}, s.models);
  }
  animc::RawBitWriter raw;
  for (size_t i = 0; i < v.value.size(); ++i) {
    const int32_t value = v.value[i];
    const uint32_t c = animc::magnitudeClass(uint64_t(value < 0 ? -int64_t(value) : value));
    s.ideal_bits -= std::log2(double(s.models[v.model[i]].frequency[classOf(value)]) / kTotal);
    if (c == 0) continue;
    if (c >= kClasses - 1) raw.write(c - (kClasses - 1), 5);
    writeRawOfClass(raw, c, value);
  }
  raw.appendTo(s.raw);
  // rANS codes last to first: value i goes through state i % kStates.
  std::vector<uint8_t> reversed;
  uint32_t state[kStates];
  std::fill(state, state + kStates, kLow);
  for (size_t i = v.value.size(); i-- > 0;) {
    const StaticModel& m = s.models[v.model[i]];
    const uint32_t c = classOf(v.value[i]), f = m.frequency[c];
    uint32_t& x = state[i % kStates];
    const uint32_t x_max = ((kLow >> kFrequencyBits) << 8) * f;
    while (x >= x_max) {
      reversed.push_back(uint8_t(x));
      x >>= 8;
    }
    x = ((x / f) << kFrequencyBits) + (x % f) + m.start[c];
  }
  s.rans = finishStates(state, reversed);
  return s;
}

__attribute__((always_inline)) inline int32_t decodeStatic(uint32_t& x, const uint8_t*& p, const StaticModel& m,
                                                          animc::RawBitReader& raw) {
  const uint32_t slot = x & (kTotal - 1);
  const uint32_t s = m.symbol_of_slot[slot];
  x = m.frequency[s] * (x >> kFrequencyBits) + slot - m.start[s];
  if (x < kLow) {  // one or two bytes
    x = (x << 8) | *p++;
    if (x < kLow) x = (x << 8) | *p++;
  }
  if (s == 0) return 0;
  return valueOfClass(s == kClasses - 1 ? s + raw.read(5) : s, raw);
}

void staticDecode(const Values& v, const StaticStream& s, std::vector<int32_t>& out) {
  animc::RawBitReader raw(s.raw.data(), s.raw.size());
  decodeInterleaved(s.rans.data(), v.value.size(), out, [&](uint32_t& x, const uint8_t*& p, size_t i) {
    return decodeStatic(x, p, s.models[v.model[i]], raw);
  });
}

// ---- adaptive rANS: today's models, rANS instead of the range coder ----
// The same models (zero flag, Low and High class symbols, raw bits) adapting as today, their
// spans coded by rANS at 15 bits with kStates interleaved states, value i in state i % kStates:
// no division in the decoder, and four chains instead of one.

constexpr uint32_t kAnsLow = 1u << 23;

struct Span {
  uint16_t start, frequency;
};

struct AnsStream {
  std::vector<uint8_t> rans;
  std::vector<uint8_t> raw;
};

AnsStream ansEncode(const Values& v) {
  std::vector<ClassedIntegerModel> models(kModels);
  std::vector<Span> spans;
  std::vector<uint32_t> first_span;  // of each value
  animc::RawBitWriter raw;
  for (size_t i = 0; i < v.value.size(); ++i) {
    first_span.push_back(uint32_t(spans.size()));
    ClassedIntegerModel& m = models[v.model[i]];
    const int64_t value = v.value[i];
    const uint32_t p0 = m.zero.p0;
    spans.push_back(value == 0 ? Span{0, uint16_t(p0)} : Span{uint16_t(p0), uint16_t(animc::kProbOne - p0)});
    m.zero.update(value != 0);
    if (value == 0) continue;
    const uint32_t c = animc::magnitudeClass(uint64_t(value < 0 ? -value : value));
    auto symbol = [&](animc::SymbolModel& model, uint32_t s) {
      spans.push_back({model.start[s], uint16_t(model.start[s + 1] - model.start[s])});
      model.update(s);
    };
    symbol(m.low, animc::lowSymbol(c));
    if (c >= animc::kFirstHighClass) symbol(m.high, animc::highSymbol(c));
    if (c >= animc::kFirstRawClass) raw.write(c - animc::kFirstRawClass, 5);
    writeRawOfClass(raw, c, value);
  }
  first_span.push_back(uint32_t(spans.size()));
  AnsStream out;
  raw.appendTo(out.raw);
  std::vector<uint8_t> reversed;
  uint32_t state[kStates];
  std::fill(state, state + kStates, kAnsLow);
  for (size_t i = v.value.size(); i-- > 0;) {
    uint32_t& x = state[i % kStates];
    for (uint32_t j = first_span[i + 1]; j-- > first_span[i];) {
      const uint32_t f = spans[j].frequency;
      const uint32_t x_max = ((kAnsLow >> animc::kProbBits) << 8) * f;
      while (x >= x_max) {
        reversed.push_back(uint8_t(x));
        x >>= 8;
      }
      x = ((x / f) << animc::kProbBits) + (x % f) + spans[j].start;
    }
  }
  out.rans = finishStates(state, reversed);
  return out;
}

__attribute__((always_inline)) inline void ansStep(uint32_t& x, const uint8_t*& p, uint32_t start, uint32_t frequency) {
  x = frequency * (x >> animc::kProbBits) + (x & (animc::kProbOne - 1)) - start;
  if (x < kAnsLow) {
    x = (x << 8) | *p++;
    if (x < kAnsLow) x = (x << 8) | *p++;
  }
}

__attribute__((always_inline)) inline uint32_t ansSymbol(uint32_t& x, const uint8_t*& p, animc::SymbolModel& m) {
  const uint32_t s = m.find(x & (animc::kProbOne - 1));
  ansStep(x, p, m.start[s], uint32_t(m.start[s + 1] - m.start[s]));
  m.update(s);
  return s;
}

__attribute__((always_inline)) inline int32_t ansValue(uint32_t& x, const uint8_t*& p, ClassedIntegerModel& m,
                                                      animc::RawBitReader& raw) {
  const uint32_t p0 = m.zero.p0;
  const int nonzero = (x & (animc::kProbOne - 1)) >= p0;
  ansStep(x, p, nonzero ? p0 : 0, nonzero ? animc::kProbOne - p0 : p0);
  m.zero.update(nonzero);
  if (!nonzero) return 0;
  uint32_t c = 1 + ansSymbol(x, p, m.low);
  if (c == animc::kFirstHighClass) {
    c = animc::kFirstHighClass + ansSymbol(x, p, m.high);
    if (c >= animc::kFirstRawClass) c = std::min(animc::kFirstRawClass + raw.read(5), animc::kMaxMagnitudeClass);
  }
  return valueOfClass(c, raw);
}

void ansDecode(const Values& v, const AnsStream& s, std::vector<int32_t>& out) {
  std::vector<ClassedIntegerModel> models(kModels);
  animc::RawBitReader raw(s.raw.data(), s.raw.size());
  decodeInterleaved(s.rans.data(), v.value.size(), out,
                    [&](uint32_t& x, const uint8_t*& p, size_t i) { return ansValue(x, p, models[v.model[i]], raw); });
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: trajectory_entropy FILE.ams\n");
    return 2;
  }
  auto source = animc::AmsSource::open(argv[1]);
  auto reader = animc::ContainerReader::open(argv[1]);
  if (!source.ok() || !reader.ok() || source.value()->settings().codec() != animc::CodecId::kTrajectory2) {
    std::fprintf(stderr, "trajectory_entropy: %s: not a trajectory2 file\n", argv[1]);
    return 1;
  }
  const animc::Topology& topology = source.value()->topology();
  const animc::CodingOrder mesh_order(topology);
  std::vector<Values> values;  // of each part of each group: each is coded on its own, as in the file
  size_t file_payload = 0;
  uint64_t vertex_frames = 0;
  std::vector<uint8_t> payload;
  for (size_t g = 0; g < reader.value()->groupCount(); ++g) {
    animc::PartedGroupHead head;
    if (!reader.value()->beginGroup(g).ok() || !reader.value()->nextFrame(payload).ok() || payload.empty() ||
        !animc::readPartedGroupHead(animc::ByteReader(payload.data() + 1, payload.size() - 1), mesh_order, head)
             .ok()) {
      std::fprintf(stderr, "trajectory_entropy: %s: group %zu unreadable\n", argv[1], g);
      return 1;
    }
    file_payload += payload.size();
    vertex_frames += uint64_t(head.frames) * topology.vertex_count;
    const animc::MeshParts parts(topology, head.labels, head.part_count);
    for (uint32_t c = 0; c < head.part_count; ++c) {
      animc::TrajectoryGroup part;
      if (!animc::readTrajectoryGroup(head.parts[c], *parts.orders[c], UINT64_MAX, part).ok()) return 1;
      values.emplace_back();
      collect(part, *parts.orders[c], values.back());
    }
  }
  size_t count = 0, adaptive_bytes = 0, adaptive_raw = 0, static_bytes = 0, static_raw = 0;
  double table_bits = 0, ideal_bits = 0, adaptive_seconds = 0, static_seconds = 0, ans_seconds = 0;
  size_t ans_bytes = 0;
  bool same = true;
  // Tables for all the parts of the file's groups together (these files have one group).
  std::vector<const Values*> all;
  for (const Values& v : values) all.push_back(&v);
  std::vector<StaticModel> shared(kModels);
  const double shared_table_bits = tablesOf(all, shared);
  size_t shared_bytes = 0;
  for (const Values& v : values) {
    const StaticStream coded = staticEncode(v, &shared);
    shared_bytes += coded.rans.size() + coded.raw.size();
  }
  for (const Values& v : values) {
    std::vector<uint8_t> adaptive;
    size_t raw_start = 0;
    adaptiveBytes(v, adaptive, raw_start);
    const StaticStream fixed = staticEncode(v);
    std::vector<int32_t> out(v.value.size());
    adaptive_seconds += bestSeconds([&] { adaptiveDecode(v, adaptive, out); });
    same &= out == v.value;
    static_seconds += bestSeconds([&] { staticDecode(v, fixed, out); });
    same &= out == v.value;
    const AnsStream ans = ansEncode(v);
    ans_seconds += bestSeconds([&] { ansDecode(v, ans, out); });
    same &= out == v.value;
    ans_bytes += ans.rans.size() + ans.raw.size();
    count += v.value.size();
    adaptive_bytes += adaptive.size();
    adaptive_raw += adaptive.size() - raw_start;
    static_bytes += fixed.rans.size() + fixed.raw.size();
    static_raw += fixed.raw.size();
    table_bits += fixed.table_bits;
    ideal_bits += fixed.ideal_bits + 8.0 * fixed.raw.size();
  }
  if (!same) {
    std::fprintf(stderr, "trajectory_entropy: a coder did not give its values back\n");
    return 1;
  }
  std::printf(
      "{\"values\": %zu, \"vertex_frames\": %llu, \"payload_bytes\": %zu, \"adaptive_bytes\": %zu, "
      "\"adaptive_raw_bytes\": %zu, \"static_bytes\": %zu, \"static_raw_bytes\": %zu, \"static_table_bytes\": %.0f, "
      "\"static_ideal_bytes\": %.0f, \"shared_bytes\": %zu, \"shared_table_bytes\": %.0f, "
      "\"adaptive_seconds\": %.6f, \"static_seconds\": %.6f, \"ans_bytes\": %zu, \"ans_seconds\": %.6f}\n",
      count, (unsigned long long)vertex_frames, file_payload, adaptive_bytes, adaptive_raw, static_bytes, static_raw,
      table_bits / 8, ideal_bits / 8, shared_bytes, shared_table_bits / 8, adaptive_seconds, static_seconds, ans_bytes, ans_seconds);
  return 0;
}
