// SPDX-License-Identifier: Apache-2.0
// libFuzzer harness: arbitrary frames of a small grid mesh encoded to memory by the public
// Encoder with settings taken from the input, then decoded by the public Decoder. A refusal is
// fine; a crash, a sanitizer report, or a decoded frame that differs from what the encoder
// said the decoder would produce (or, for the affine-octree codec, a vertex beyond the max
// error) is a bug, reported by abort().
//
// Input = 4 control bytes, then coordinates:
//   [0] bit 0: codec (0: affine-octree, or with bit 2 set trajectory (bit 1 clear) or auto
//       (bit 1 set); 1: wavelet); bits 1-2: profile or detail-frame kind;
//       bits 3-7: I-frame interval
//   [1] grid width - 2 (mod 7)   [2] grid height - 2 (mod 7)   [3] quality (max error, step)
//   then int16 coordinates (scaled by 1/256), x y z per vertex per frame, until they run out
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "animc/animc.h"

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

animc::EncoderOptions options(const uint8_t* control) {
  animc::EncoderOptions o;
  const int kind = (control[0] >> 1) & 3;
  o.iframe_interval = control[0] >> 3;
  if ((control[0] & 1) == 0 && kind == 2) {
    o.codec = "trajectory";
    o.set("target-kg", 0.05 + 5.0 * control[3] / 255.0);
  } else if ((control[0] & 1) == 0 && kind == 3) {
    o.codec = "auto";  // mixes trajectory and affine-octree groups; short groups as well
    o.set("max-error", 0.0005 + 0.2 * control[3] / 255.0);
    o.set("group-frames", 3.0);
  } else if ((control[0] & 1) == 0) {
    o.codec = "affine-octree";
    o.set("profile", kind & 1 ? "paper" : "predictive");
    o.set("max-error", 0.0005 + 0.2 * control[3] / 255.0);
  } else {
    o.codec = "wavelet";
    o.set("step", 1e-4 + 0.05 * control[3] / 255.0);
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

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kControlBytes) return 0;
  const Mesh mesh = grid(2 + data[1] % 7, 2 + data[2] % 7);
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
  const double max_error = o.codec == "affine-octree" ? std::strtod(o.values.at("max-error").c_str(), nullptr) : 0;
  const std::vector<bool> intra = intraFrames(stream, mesh.vertices, frames);
  std::vector<float> xyz(3 * size_t(mesh.vertices));
  // Backwards, so that every frame but the last is reached by random access.
  for (int f = frames - 1; f >= 0; --f) {
    if (!decoder.value().frame(f, xyz.data()).ok()) bug("a frame does not decode", f);
    if (xyz != expected[f]) bug("the decoder and the encoder disagree", f);
    if ((f == 0 || (o.iframe_interval > 0 && f % o.iframe_interval == 0)) && !intra[f])
      bug("a frame of the I-frame interval is not an intra frame", f);
    if (max_error == 0) continue;
    // docs/affine_octree.md, error bound: E times the side of the root cube, the bounding cube of
    // the reconstructed previous frame (of the frame itself for an intra frame; 1 if a point).
    double side = largestSide(intra[f] ? originals[f] : expected[f - 1]);
    if (side == 0) side = 1;
    for (size_t v = 0; v < xyz.size(); v += 3) {
      const double dx = xyz[v] - originals[f][v], dy = xyz[v + 1] - originals[f][v + 1],
                   dz = xyz[v + 2] - originals[f][v + 2];
      // Decoders output floats: rounding adds up to half a float step of each coordinate, more
      // than E * S when the cube is tiny next to the coordinates.
      const double rounding = 0x1p-24 * (std::fabs(xyz[v]) + std::fabs(xyz[v + 1]) + std::fabs(xyz[v + 2]));
      const double error = std::sqrt(dx * dx + dy * dy + dz * dz);
      const double bound = max_error * side * (1 + 1e-5) + rounding;
      if (error > bound) bug("error above the bound", f, error, bound);
    }
  }
  return 0;
}
