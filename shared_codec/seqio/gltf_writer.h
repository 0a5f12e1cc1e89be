// SPDX-License-Identifier: Apache-2.0
// A sequence as one glTF 2.0 asset that any glTF viewer plays (Blender, three.js, ...): one
// mesh whose POSITION is frame 0, one morph target per frame (frame k minus frame 0, so
// target 0 is all zeros), and one animation driving the mesh's weights with STEP
// interpolation at the frame rate: from time k / rate, target k has weight 1 and every other
// 0, and a last key at F / rate gives the last frame its time too. The frames stream through
// the sink (memory O(vertices)); the weight matrix takes 4·F·(F + 1) bytes.
//
// .glb: the binary container (12-byte header, a JSON chunk, a BIN chunk); its JSON chunk is
// reserved at its largest possible size and padded with spaces, so that the accessors'
// bounds, known only once every frame is seen, can be written last. .gltf: the JSON with the
// buffer inlined as a base64 data URI ahead of everything that refers to it.
#pragma once
#include <cstdint>
#include <memory>
#include <string>

#include "core/sequence.h"

namespace animc {

Result<std::unique_ptr<FrameSink>> createGlbSink(const std::string& path, const Topology& topology, int64_t frame_count,
                                                 double frame_rate);
Result<std::unique_ptr<FrameSink>> createGltfSink(const std::string& path, const Topology& topology,
                                                  int64_t frame_count, double frame_rate);

// What the sizes below give for more frames than a glTF output takes (65 536): more than any
// output limit.
constexpr uint64_t kGltfTooLarge = ~uint64_t(0);

// The BIN buffer's bytes: indices, positions, targets, times and weights.
uint64_t gltfBinaryBytes(uint64_t vertices, uint64_t triangles, uint64_t frames);
// About how many bytes a .glb of these counts takes (an upper bound of its JSON included).
uint64_t glbBytes(uint64_t vertices, uint64_t triangles, uint64_t frames);

}  // namespace animc
