// SPDX-License-Identifier: Apache-2.0
// libFuzzer harness: arbitrary frames of a small mesh encoded to memory by the public Encoder
// with settings taken from the input, decoded by the public Decoder, and written by a sequence
// writer and read back. A refusal by the encoder is fine; a crash, a sanitizer report, a decoded
// frame that differs from what the encoder said the decoder would produce, a vertex beyond the
// max error (affine-octree, trajectory and auto within a max error), a sequence above its KG
// target (trajectory, auto and wavelet), or a written frame that does not read back the same
// is a bug, reported by abort().
//
// Input = 4 control bytes, then coordinates:
//   [0] bit 0: codec (0: affine-octree, or with bit 2 set trajectory (bit 1 clear; codec 5,
//       trajectory2, when bit 1 of [3] is set) or auto (bit 1 set); 1: wavelet); bits 1-2: profile or detail-frame kind
//       (wavelet: 0 P-frames at a step, or at a KG target when [3] is odd; 1 progressive P-frames; 2 I-frames only; 3 a
//       fixed rate); bits 3-7: I-frame interval
//   [1] bits 0-6: grid width - 2 (mod 7); bit 7: random triangles over the grid's vertices
//       (as many as the grid has) instead of the grid's
//   [2] bits 0-4: grid height - 2 (mod 7); bits 5-7: the decoded frames are written as
//       3 OBJ frames, 4 PLY frames, 5 OFF frames, 6 PC2, 7 MDD (0-2: not written)
//   [3] quality (max error, step, KG target); trajectory and auto: bit 0 set, a max error, else
//       a KG target; trajectory2: 2 + (bits 2-7 mod 7) parts at most
//   the four bytes XORed, mod 64: below 48, 1 + that many triangles per connectivity piece
//       (.ams format 2 when there is more than one piece), else one piece (format 1)
//   then int16 coordinates (scaled by 1/256), x y z per vertex per frame, until they run out
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

#include "animc/animc.h"
#include "fuzz_support.h"
#include "seqio/mdd_format.h"
#include "seqio/pc2_format.h"
#include "seqio/sequence_io.h"

namespace {

constexpr size_t kControlBytes = 4;
constexpr int kMaxFrames = 12;

struct Mesh {
  uint32_t vertices = 0;
  std::vector<uint32_t> triangles;
};

Mesh grid(uint32_t width, uint32_t height) {
  Mesh m;
  m.vertices = width * height;
  for (uint32_t y = 0; y + 1 < height; ++y)
    for (uint32_t x = 0; x + 1 < width; ++x) {
      const uint32_t v = y * width + x;
      m.triangles.insert(m.triangles.end(), {v, v + 1, v + width, v + 1, v + width + 1, v + width});
    }
  return m;
}

// The grid's vertices with as many triangles, their corners drawn from a generator seeded by
// the control bytes: non-manifold edges, repeated corners and unused vertices included.
Mesh randomTriangles(uint32_t width, uint32_t height, const uint8_t* control) {
  Mesh m = grid(width, height);
  uint32_t state = 0x9E3779B9u ^ (uint32_t(control[1]) << 16 | uint32_t(control[2]) << 8 | control[3]);
  for (uint32_t& corner : m.triangles) {
    state ^= state << 13, state ^= state >> 17, state ^= state << 5;  // xorshift32
    corner = state % m.vertices;
  }
  return m;
}

animc::EncoderOptions options(const uint8_t* control) {
  animc::EncoderOptions o;
  const int kind = (control[0] >> 1) & 3;
  o.iframe_interval = control[0] >> 3;
  // The connectivity in pieces of 1 to 48 triangles (format 2 when there is more than one)
  // for three control words in four, else whole (format 1): the grids have up to 98 triangles.
  const unsigned mix = (control[0] ^ control[1] ^ control[2] ^ control[3]) % 64;
  o.connectivity_piece = mix < 48 ? 1 + mix : 0;
  if ((control[0] & 1) == 0 && kind == 2) {
    o.codec = control[3] & 2 ? "trajectory2" : "trajectory";
    if (control[3] & 2) o.set("parts", double(2 + (control[3] >> 2) % 7));
    if (control[3] & 1) o.set("max-error", 0.0005 + 0.2 * control[3] / 255.0);
    else o.set("target-kg", 0.05 + 5.0 * control[3] / 255.0);
  } else if ((control[0] & 1) == 0 && kind == 3) {
    // Mixes trajectory and affine-octree groups within a max error, trajectory and wavelet
    // groups at a KG target; short groups as well.
    o.codec = "auto";
    if (control[3] & 1) o.set("max-error", 0.0005 + 0.2 * control[3] / 255.0);
    else o.set("target-kg", 0.05 + 5.0 * control[3] / 255.0);
    o.set("group-frames", 3.0);
  } else if ((control[0] & 1) == 0) {
    o.codec = "affine-octree";
    o.set("profile", kind & 1 ? "paper" : "predictive");
    o.set("max-error", 0.0005 + 0.2 * control[3] / 255.0);
  } else {
    o.codec = "wavelet";
    o.set("step", 1e-4 + 0.05 * control[3] / 255.0);
    // At a KG target, with the fine step the target needs (docs/wavelet.md: the step bounds
    // the finest plane), from 0.5 %, where a 1e-5 step reaches any target.
    if (kind == 0 && (control[3] & 1)) {
      o.set("step", 1e-5);
      o.set("target-kg", 0.5 + 4.5 * control[3] / 255.0);
    }
    if (kind == 1) o.set("progressive-p-frames", "1");
    if (kind == 2) o.set("i-frames-only", "1");
    if (kind == 3) o.set("bpv", double(1 + control[3] % 8));
  }
  return o;
}

[[noreturn]] void bug(const char* what, int64_t frame, double value = 0, double bound = 0) {
  std::fprintf(stderr, "round trip: %s at frame %lld (%g, bound %g)\n", what, (long long)frame, value, bound);
  std::abort();
}

// The largest side of the bounding box of a frame (the affine-octree's cube side).
double largestSide(const std::vector<float>& xyz) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < xyz.size(); ++i) {
    lo[i % 3] = std::fmin(lo[i % 3], xyz[i]);
    hi[i % 3] = std::fmax(hi[i % 3], xyz[i]);
  }
  return std::fmax(hi[0] - lo[0], std::fmax(hi[1] - lo[1], hi[2] - lo[2]));
}

// Which frames of the stream are intra frames: the first frame of each frame group, the only
// frames a decoder allowed the work of a single frame can reach. The I-frame interval alone does
// not say: the affine-octree encoder also codes an intra frame on its own when it cannot predict
// one (a vertex too far from the previous frame's cube, docs/affine_octree.md "Frames and groups").
std::vector<bool> intraFrames(const std::vector<uint8_t>& stream, uint32_t vertices, int frames) {
  animc::DecoderOptions one_frame;
  one_frame.limits.max_vertex_frames = vertices;
  auto decoder = animc::Decoder::openMemory(stream.data(), stream.size(), one_frame);
  if (!decoder.ok()) bug("the encoder's stream does not open with a one-frame limit", 0);
  std::vector<bool> intra(frames);
  for (int f = 0; f < frames; ++f) intra[f] = decoder.value().checkDecodeWork(f, f + 1).ok();
  return intra;
}

// The side of the cube the max error is a fraction of. docs/affine_octree.md: the bounding cube
// of the reconstructed previous frame, of the frame itself for an intra frame; docs/trajectory.md:
// the frame's own box; docs/auto.md: that of the codec of the group, so the larger of the two.
// Each codec takes 1 for the box of a point.
double cubeSide(const std::string& codec, const std::vector<float>& original, const std::vector<float>* previous) {
  auto side = [](const std::vector<float>& xyz) {
    const double s = largestSide(xyz);
    return s == 0 ? 1.0 : s;
  };
  if (codec == "affine-octree" && previous) return side(*previous);
  if (codec == "auto" && previous) return std::fmax(side(original), side(*previous));
  return side(original);
}

void checkMaxError(const std::string& codec, double max_error, const std::vector<float>& original,
                   const std::vector<float>* previous, const std::vector<float>& xyz, int64_t frame) {
  const double side = cubeSide(codec, original, previous);
  double largest = 0;
  for (float v : original) largest = std::fmax(largest, std::fabs(v));
  // The trajectory codec's frames are sums of up to 3G float products, whose rounding can exceed
  // a tiny bound, which then holds only up to that rounding (docs/trajectory.md): checked where
  // the bound is well above it.
  if (codec != "affine-octree" && max_error * side < 0x1p-8 * largest) return;
  const double trajectory_rounding = codec == "affine-octree" ? 0 : 0x1p-12 * largest;
  for (size_t v = 0; v < xyz.size(); v += 3) {
    const double dx = xyz[v] - original[v], dy = xyz[v + 1] - original[v + 1], dz = xyz[v + 2] - original[v + 2];
    // Decoders output floats: rounding adds up to half a float step of each coordinate, more
    // than E * S when the cube is tiny next to the coordinates.
    const double rounding = 0x1p-24 * (std::fabs(xyz[v]) + std::fabs(xyz[v + 1]) + std::fabs(xyz[v + 2]));
    const double error = std::sqrt(dx * dx + dy * dy + dz * dz);
    const double bound = max_error * side * (1 + 1e-5) + rounding + trajectory_rounding;
    if (error > bound) bug("error above the bound", frame, error, bound);
  }
}

// A KG target X (docs/trajectory.md, docs/auto.md) bounds each group's squared error by
// (X/100)^2 times its spread (the squared distances to each frame's centroid), so the whole
// sequence's by the sum. Like the max error, it holds up to the float rounding of the
// trajectory codec's sums: checked where the bound is well above it.
void checkKgTarget(double target_percent, const std::vector<std::vector<float>>& originals,
                   const std::vector<std::vector<float>>& decoded) {
  double spread = 0, squared_error = 0, largest = 0;
  size_t coordinates = 0;
  for (size_t f = 0; f < originals.size(); ++f) {
    const std::vector<float>& x = originals[f];
    double centroid[3] = {0, 0, 0};
    for (size_t i = 0; i < x.size(); ++i) centroid[i % 3] += x[i];
    for (double& c : centroid) c /= double(x.size() / 3);
    for (size_t i = 0; i < x.size(); ++i) {
      spread += (x[i] - centroid[i % 3]) * (x[i] - centroid[i % 3]);
      squared_error += (double(x[i]) - decoded[f][i]) * (double(x[i]) - decoded[f][i]);
      largest = std::fmax(largest, std::fabs(x[i]));
    }
    coordinates += x.size();
  }
  const double allowed = (target_percent / 100) * (target_percent / 100) * spread;
  const double rounding = 0x1p-12 * largest;
  if (allowed < double(coordinates) * (0x1p-8 * largest) * (0x1p-8 * largest)) return;
  const double bound = allowed * (1 + 1e-5) + double(coordinates) * rounding * rounding;
  if (squared_error > bound) bug("KG error above the target", int64_t(originals.size()), squared_error, bound);
}

// The decoded frames through a sequence writer (3 OBJ, 4 PLY, 5 OFF, 6 PC2, 7 MDD) and back
// through its reader: the same frames, bit for bit (OBJ and OFF are text with 9 significant
// digits, enough for any float), and for the frame files the same faces.
void writeAndReadBack(const Mesh& mesh, const std::vector<std::vector<float>>& frames, int writer) {
  using animc::SequenceFormat;
  const SequenceFormat format = writer == 3   ? SequenceFormat::kObj
                                : writer == 4 ? SequenceFormat::kPly
                                : writer == 5 ? SequenceFormat::kOff
                                : writer == 6 ? SequenceFormat::kPc2
                                              : SequenceFormat::kMdd;
  animc::Topology topology;
  topology.vertex_count = mesh.vertices;
  for (size_t i = 0; i < mesh.triangles.size(); i += 3)
    topology.triangles.push_back({mesh.triangles[i], mesh.triangles[i + 1], mesh.triangles[i + 2]});
  const bool folder = writer <= 5;
  const std::string path = animc::fuzz::scratchPath(folder ? "_frames" : writer == 6 ? ".pc2" : ".mdd");
  auto sink = animc::createSequenceSink(path, format, topology, 25.0, int64_t(frames.size()),
                                        animc::ExistingOutput::kReplace);
  if (!sink.ok()) bug("no sequence writer", 0);
  for (const std::vector<float>& frame : frames)
    if (!sink.value()->write(frame.data()).ok()) bug("a decoded frame was not written", 0);
  if (!sink.value()->finish().ok()) bug("the sequence writer did not finish", int64_t(frames.size()));
  auto source = folder ? animc::openSequence(path, "")
                : writer == 6 ? animc::openPc2(path, topology, "the mesh")
                              : animc::openMdd(path, topology, "the mesh");
  if (!source.ok()) bug("the written frames do not open", 0);
  if (folder && (source.value()->topology().vertex_count != topology.vertex_count ||
                 source.value()->topology().triangles != topology.triangles))
    bug("the written faces read back otherwise", 0);
  std::vector<float> xyz;
  for (size_t f = 0; f < frames.size(); ++f) {
    auto more = source.value()->next(xyz);
    if (!more.ok() || !more.value()) bug("a written frame does not read back", int64_t(f));
    if (xyz != frames[f]) bug("a written frame reads back otherwise", int64_t(f));
  }
  auto more = source.value()->next(xyz);
  if (!more.ok() || more.value()) bug("more frames read back than written", int64_t(frames.size()));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kControlBytes) return 0;
  const uint32_t width = 2 + (data[1] & 0x7f) % 7, height = 2 + (data[2] & 0x1f) % 7;
  const Mesh mesh = data[1] & 0x80 ? randomTriangles(width, height, data) : grid(width, height);
  const size_t frame_bytes = size_t(mesh.vertices) * 3 * 2;
  const int frames = int(std::min<size_t>(kMaxFrames, (size - kControlBytes) / frame_bytes));
  if (frames == 0) return 0;
  std::vector<std::vector<float>> originals(frames, std::vector<float>(3 * size_t(mesh.vertices)));
  for (int f = 0; f < frames; ++f)
    for (size_t i = 0; i < originals[f].size(); ++i) {
      int16_t v;
      std::memcpy(&v, data + kControlBytes + f * frame_bytes + 2 * i, 2);
      originals[f][i] = float(v) / 256.0f;
    }

  const animc::EncoderOptions o = options(data);
  std::vector<uint8_t> stream;
  auto encoder = animc::Encoder::create(o, mesh.vertices, mesh.triangles.data(), mesh.triangles.size() / 3,
                                        animc::memorySink(&stream));
  if (!encoder.ok()) return 0;  // e.g. a mesh the wavelet codec cannot use
  std::vector<std::vector<float>> expected;
  // Reconstructions come frame by frame, or a group at a time (trajectory).
  auto collect = [&] {
    for (int64_t k = int64_t(expected.size()); k < encoder.value().reconstructedFrames(); ++k) {
      const float* r = encoder.value().reconstruction(k);
      if (r == nullptr) bug("a known reconstruction is missing", k);
      expected.emplace_back(r, r + originals[0].size());
    }
  };
  for (const std::vector<float>& frame : originals) {
    if (!encoder.value().addFrame(frame.data()).ok()) bug("a finite frame was refused", int64_t(expected.size()));
    collect();
  }
  if (!encoder.value().finish().ok()) bug("finish failed", frames);
  collect();
  if (int(expected.size()) != frames) bug("reconstructions missing", int64_t(expected.size()));

  auto decoder = animc::Decoder::openMemory(stream.data(), stream.size());
  if (!decoder.ok()) bug("the encoder's stream does not open", 0);
  if (decoder.value().info().frames != frames) bug("frame count", frames);
  const auto max_error_value = o.values.find("max-error");
  const double max_error = max_error_value == o.values.end() ? 0 : std::strtod(max_error_value->second.c_str(), nullptr);
  const std::vector<bool> intra = intraFrames(stream, mesh.vertices, frames);
  std::vector<float> xyz(3 * size_t(mesh.vertices));
  // Backwards, so that every frame but the last is reached by random access.
  for (int f = frames - 1; f >= 0; --f) {
    if (!decoder.value().frame(f, xyz.data()).ok()) bug("a frame does not decode", f);
    if (xyz != expected[f]) bug("the decoder and the encoder disagree", f);
    if ((f == 0 || (o.iframe_interval > 0 && f % o.iframe_interval == 0)) && !intra[f])
      bug("a frame of the I-frame interval is not an intra frame", f);
    if (max_error > 0) checkMaxError(o.codec, max_error, originals[f], intra[f] ? nullptr : &expected[f - 1], xyz, f);
  }
  const auto target_kg = o.values.find("target-kg");
  if (target_kg != o.values.end())
    checkKgTarget(std::strtod(target_kg->second.c_str(), nullptr), originals, expected);
  const int writer = data[2] >> 5;
  if (writer >= 3) writeAndReadBack(mesh, expected, writer);
  return 0;
}
