// SPDX-License-Identifier: Apache-2.0
// What the MeshLab adapter checks and computes before it touches a layer, without MeshLab: the
// topology of a layer's live elements, and whether a range of an .ams file may become layers.
// layer_frames.cpp applies them to CMeshO; tests/unit/layer_checks_test.cpp and
// tests/fuzz/fuzz_layer_checks.cpp apply them to a stand-in with CMeshO's element interface,
// so they are tested and fuzzed in builds without MeshLab.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "api.h"
#include "core/sequence.h"

namespace animc::meshlab {

// A layer's frame: its live vertices in vector order, and its live faces' corners renumbered
// over them. MeshLab keeps deleted elements in place until a mesh is compacted. Mesh is CMeshO
// or any type with its element interface: vectors `vert` and `face` whose elements have IsD(),
// and faces cV(k), a pointer into `vert`. A live face with a deleted corner gets the corner
// UINT32_MAX, which checkTopology() refuses.
template <class Mesh>
Topology liveTopology(const Mesh& mesh) {
  std::vector<uint32_t> index(mesh.vert.size(), UINT32_MAX);
  uint32_t live = 0;
  for (size_t i = 0; i < mesh.vert.size(); ++i)
    if (!mesh.vert[i].IsD()) index[i] = live++;
  Topology t;
  t.vertex_count = live;
  for (const auto& f : mesh.face) {
    if (f.IsD()) continue;
    Triangle tri;
    for (int k = 0; k < 3; ++k) tri[k] = index[size_t(f.cV(k) - mesh.vert.data())];
    t.triangles.push_back(tri);
  }
  return t;
}

// A layer's live vertex positions, x y z per vertex in vector order.
template <class Mesh>
void livePositions(const Mesh& mesh, std::vector<float>& xyz) {
  xyz.clear();
  for (const auto& v : mesh.vert) {
    if (v.IsD()) continue;
    for (int c = 0; c < 3; ++c) xyz.push_back(float(v.cP()[c]));
  }
}

// The frames of an .ams file to load as layers and the limits that loading must respect.
struct AmsImport {
  int64_t first_frame = 0;
  int64_t last_frame = -1;  // < 0: the last frame of the file
  int64_t max_layer_megabytes = 4096;
  uint64_t max_vertex_frames = DecoderLimits().max_vertex_frames;

  // The limits to open the file with: the memory limit is the library's output limit, counted
  // in layer bytes (planAmsImport).
  DecoderLimits decoderLimits() const;
};

// What one vertex and one face take in a layer (sizeof CVertexO and CFaceO).
struct LayerElementBytes {
  uint64_t vertex = 0;
  uint64_t face = 0;
};

// What one layer of `topology` takes in MeshLab's memory, about: its elements and the optional
// attributes MeshLab enables on loaded layers.
uint64_t layerBytes(const Topology& topology, const LayerElementBytes& element);

// The checked frames [first, last] of an import.
struct FrameRange {
  int64_t first = 0;
  int64_t last = 0;
  int64_t count() const { return last - first + 1; }
};

// The range `range` asks of the open file `source` (named `path` in messages), once it lies in
// the file, its layers fit the memory limit and decoding it fits the work limit, with `source`
// positioned at its first frame. The limits are the source's: open it with
// range.decoderLimits(). Nothing is allocated per frame before these checks: a small
// file can describe millions of vertices over thousands of frames.
Result<FrameRange> planAmsImport(const std::string& path, AmsSource& source, const AmsImport& range,
                                 const LayerElementBytes& element);

// MeshLab 2022+ makes the layers of a multi-layer open itself: refuses when it made a number
// other than the range's frame count.
Status checkLayerCount(const std::string& path, const FrameRange& range, int64_t layers);

}  // namespace animc::meshlab
