// SPDX-License-Identifier: Apache-2.0
// libFuzzer harness: the MeshLab adapter's checks (meshlab_adapter/layer_checks.h) without
// MeshLab. Layers with deleted vertices and faces, as MeshLab keeps them until it compacts a
// mesh, become frames as the plugins make them (on a stand-in for CMeshO), checked against a
// plain count of the live elements; then a range of an .ams stream is planned for import
// with memory and work limits from the input, and checked against what each limit allows. A
// crash, a sanitizer report, a frame that differs from the count, or a plan that lets through
// what a limit forbids (or refuses what all allow) is a bug, reported by abort().
//
// Input = 8 control bytes, the layers' description ([7] bytes), then the .ams stream:
//   [0] layers - 1 (mod 4)     [1] first frame (int8)   [2] last frame (int8, < 0: the last)
//   [3] memory limit (MB)      [4] log2 of an element's bytes (mod 24)
//   [5] log2 of the work limit in vertex-frames (mod 19)   [6] layers MeshLab made - the range's
//   (int8)   [7] length of the layers' description
// Each layer: vertex slots - 1 (mod 16), two bytes of deleted flags, faces (mod 20), and per
// face three corner bytes (bit 7 of the first: deleted; the slot is the rest mod the slots).
// A layer after the first whose first byte is even is the first layer again with other
// positions and a deleted vertex appended when bit 1 is set: the same live topology.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "animc/animc.h"
#include "layer_checks.h"
#include "seqio/mesh_checks.h"
#include "../unit/stand_in_layer.h"

namespace {

using animc::testing::StandInLayer;
using animc::testing::StandInVertex;

constexpr size_t kControlBytes = 8;

[[noreturn]] void bug(const char* what) {
  std::fprintf(stderr, "layer checks: %s\n", what);
  std::abort();
}

// The bytes of the layers' description, zeros past its end.
struct ByteReader {
  const uint8_t* data;
  size_t size;
  size_t at = 0;
  uint8_t next() { return at < size ? data[at++] : 0; }
};

StandInLayer readLayer(ByteReader& in) {
  StandInLayer layer;
  const size_t slots = 1 + in.next() % 16;
  const unsigned deleted = in.next() | unsigned(in.next()) << 8;
  for (size_t i = 0; i < slots; ++i)
    layer.vert.push_back({{float(in.next()), float(i), 0.5f}, ((deleted >> i) & 1) != 0});
  const size_t faces = in.next() % 20;
  for (size_t f = 0; f < faces; ++f) {
    const uint8_t a = in.next(), b = in.next(), c = in.next();
    layer.addFace((a & 0x7f) % slots, b % slots, c % slots, (a & 0x80) != 0);
  }
  return layer;
}

// The first layer with new positions; with a deleted vertex appended when `grow`. Its faces
// point into its own vertices.
StandInLayer sameLiveTopology(const StandInLayer& first, ByteReader& in, bool grow) {
  StandInLayer layer;
  layer.vert = first.vert;
  for (StandInVertex& v : layer.vert) v.p[0] = float(in.next());
  if (grow) layer.vert.push_back({{0, 0, 0}, true});
  for (const auto& f : first.face)
    layer.addFace(size_t(f.cV(0) - first.vert.data()), size_t(f.cV(1) - first.vert.data()),
                  size_t(f.cV(2) - first.vert.data()), f.IsD());
  return layer;
}

// The frame of a layer by a plain count: each live vertex's number is the count of live
// vertices before it.
animc::Topology countedTopology(const StandInLayer& layer) {
  animc::Topology t;
  for (const auto& f : layer.face) {
    if (f.IsD()) continue;
    animc::Triangle tri;
    for (int k = 0; k < 3; ++k) {
      const StandInVertex* corner = f.cV(k);
      uint32_t before = 0;
      for (const StandInVertex* v = layer.vert.data(); v < corner; ++v) before += !v->IsD();
      tri[k] = corner->IsD() ? UINT32_MAX : before;
    }
    t.triangles.push_back(tri);
  }
  for (const StandInVertex& v : layer.vert) t.vertex_count += !v.IsD();
  return t;
}

bool sameTopology(const animc::Topology& a, const animc::Topology& b) {
  return a.vertex_count == b.vertex_count && a.triangles == b.triangles;
}

// As LayerFrameSource takes layers: the first one's topology checked, each later one's the same.
void checkLayers(const std::vector<StandInLayer>& layers) {
  std::vector<animc::Topology> topologies;
  for (const StandInLayer& layer : layers) {
    topologies.push_back(animc::meshlab::liveTopology(layer));
    if (!sameTopology(topologies.back(), countedTopology(layer))) bug("a layer's frame is not its live elements");
    std::vector<float> xyz;
    animc::meshlab::livePositions(layer, xyz);
    std::vector<float> counted;
    for (const StandInVertex& v : layer.vert)
      if (!v.IsD()) counted.insert(counted.end(), v.p.begin(), v.p.end());
    if (xyz != counted) bug("a layer's positions are not its live vertices'");
  }
  if (!animc::checkTopology(topologies[0]).ok()) return;
  for (const animc::Triangle& t : topologies[0].triangles)
    for (uint32_t corner : t)
      if (corner >= topologies[0].vertex_count) bug("a checked frame has a corner beyond its vertices");
  for (size_t k = 1; k < topologies.size(); ++k)
    if (animc::checkSameTopology(topologies[k], topologies[0], "layer 0").ok() !=
        sameTopology(topologies[k], topologies[0]))
      bug("the same-topology check disagrees with a comparison");
}

// What each check allows, computed apart from planAmsImport.
struct Expected {
  bool range_ok = false;
  bool memory_ok = false;
  bool work_ok = false;
  bool all() const { return range_ok && memory_ok && work_ok; }
};

Expected expectedPlan(animc::AmsSource& source, const animc::Decoder& unlimited_output,
                      const animc::meshlab::AmsImport& range, const animc::meshlab::LayerElementBytes& element) {
  Expected e;
  const int64_t frames = source.frameCount();
  const int64_t first = range.first_frame, last = range.last_frame < 0 ? frames - 1 : range.last_frame;
  e.range_ok = first >= 0 && first <= last && last < frames;
  if (!e.range_ok) return e;
  // Small enough not to overflow: at most 256 layers of 2^16 vertices of 2^23 bytes.
  const uint64_t bytes = animc::meshlab::layerBytes(source.topology(), element);
  e.memory_ok = uint64_t(last - first + 1) * bytes <= uint64_t(range.max_layer_megabytes) << 20;
  // The work alone: the same limits with no output limit.
  e.work_ok = unlimited_output.checkDecodeWork(first, last + 1).ok();
  return e;
}

void checkImport(const uint8_t* control, const uint8_t* stream, size_t size) {
  animc::DecoderOptions options;
  options.limits.max_vertices = 1 << 16;
  options.limits.max_triangles = 1 << 17;
  options.limits.max_frame_bytes = 1 << 22;
  options.limits.max_vertex_frames = uint64_t(1) << (control[5] % 19);
  options.limits.max_output_bytes = uint64_t(control[3]) << 20;
  auto decoder = animc::Decoder::openMemory(stream, size, options);
  if (!decoder.ok()) return;
  animc::AmsSource source(std::move(decoder).value());
  animc::DecoderOptions work_only = options;
  work_only.limits.max_output_bytes = UINT64_MAX;
  auto unlimited_output = animc::Decoder::openMemory(stream, size, work_only);
  if (!unlimited_output.ok()) bug("a stream opened once and not twice");
  animc::meshlab::AmsImport range;
  range.first_frame = int8_t(control[1]);
  range.last_frame = int8_t(control[2]);
  range.max_layer_megabytes = control[3];
  range.max_vertex_frames = options.limits.max_vertex_frames;
  const animc::meshlab::LayerElementBytes element = {uint64_t(1) << (control[4] % 24), uint64_t(1) << (control[4] % 24)};
  const Expected expected = expectedPlan(source, unlimited_output.value(), range, element);
  const auto plan = animc::meshlab::planAmsImport("fuzz.ams", source, range, element);
  if (!plan.ok()) {
    if (plan.status().message().empty()) bug("a refusal without a message");
    // Allowed by every limit, a range may still be refused by the seek to its first frame,
    // in a damaged stream: a fresh source must fail that seek too.
    if (expected.all()) {
      auto again = animc::Decoder::openMemory(stream, size, options);
      if (!again.ok()) bug("a stream opened once and not twice");
      animc::AmsSource fresh(std::move(again).value());
      if (fresh.seek(range.first_frame).ok()) bug("a range every limit allows was refused");
    }
    return;
  }
  if (!expected.range_ok) bug("a range outside the file was planned");
  if (!expected.memory_ok) bug("a range above the memory limit was planned");
  if (!expected.work_ok) bug("a range above the work limit was planned");
  const animc::meshlab::FrameRange r = plan.value();
  if (r.first != range.first_frame || (range.last_frame >= 0 && r.last != range.last_frame))
    bug("the plan is not the range asked for");
  const int delta = int8_t(control[6]);
  if (animc::meshlab::checkLayerCount("fuzz.ams", r, r.count() + delta).ok() != (delta == 0))
    bug("the layer count check disagrees with the range");
  // The layers' frames, as the importer decodes them: the first must be frame `first`.
  std::vector<float> xyz, direct(3 * size_t(source.topology().vertex_count));
  for (int64_t frame = r.first; frame <= r.last; ++frame) {
    auto more = source.next(xyz);
    if (!more.ok() || !more.value()) return;  // a damaged stream
    if (frame != r.first) continue;
    auto again = animc::Decoder::openMemory(stream, size, options);
    if (again.ok() && again.value().frame(frame, direct.data()).ok() && xyz != direct)
      bug("the planned import does not start at its first frame");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < kControlBytes) return 0;
  const size_t description = std::min<size_t>(data[7], size - kControlBytes);
  ByteReader in{data + kControlBytes, description};
  std::vector<StandInLayer> layers;
  layers.push_back(readLayer(in));
  for (int k = 1; k <= data[0] % 4; ++k) {
    const uint8_t kind = in.next();
    layers.push_back(kind % 2 == 0 ? sameLiveTopology(layers[0], in, (kind & 2) != 0) : readLayer(in));
  }
  checkLayers(layers);
  const size_t stream = kControlBytes + description;
  if (stream < size) checkImport(data, data + stream, size - stream);
  return 0;
}
