// SPDX-License-Identifier: GPL-3.0-or-later
// MeshLab layers as animc frames and back: the one place where CMeshO meets shared_codec.
// A frame is a layer's live vertices in vector order; its triangles are its live faces with
// indices renumbered over those vertices, so deleted-but-not-compacted elements are skipped.
#pragma once
#include <QList>
#include <QString>
#include <memory>
#include <vector>


#include "api.h"
#include "core/sequence.h"
#include "layer_checks.h"
#include "meshlab_compat.h"

namespace animc::meshlab {

// The layers that are frames, in document order; with visible_only, hidden layers are skipped.
QList<MeshModel*> frameLayers(const MeshDocument& md, bool visible_only);

// "layer 3 ('frame_0003.ply')", for messages: the layer's position in its document, which
// differs from its position in a run of frames that starts later or skips hidden layers.
// MeshLab 2022+ layers do not know their document, hence md (null: the position is unknown,
// shown as -1).
std::string layerName(const MeshDocument* md, const MeshModel& layer);

// A layer's live vertex positions (x y z per vertex, in vector order), its topology unchecked:
// for layers a LayerFrameSource already went through.
inline void layerPositions(const MeshModel& layer, std::vector<float>& xyz) { livePositions(layer.cm, xyz); }

// The layers as a sequence of frames. Every layer must have the first one's vertex count and
// triangle list; next() fails with a message naming the first layer that does not.
class LayerFrameSource final : public FrameSource {
 public:
  // Fails when there are no layers or the first one has no vertices or no faces.
  static Result<std::unique_ptr<LayerFrameSource>> create(const MeshDocument* md, const QList<MeshModel*>& layers);

  const Topology& topology() const override { return topology_; }
  int64_t frameCount() const override { return layers_.size(); }
  Result<bool> next(std::vector<float>& xyz) override;
  std::string where() const override;

 private:
  explicit LayerFrameSource(const MeshDocument* md) : md_(md) {}
  const MeshDocument* md_;  // for messages only
  QList<MeshModel*> layers_;
  Topology topology_;
  int next_ = 0;
};

// Fills an empty CMeshO with one frame: topology.vertex_count vertices in order, then the
// triangles. Updates the bounding box and normals.
void fillMesh(MeshModel& layer, const Topology& topology, const float* xyz);

// Reads frames [first, last] of an .ams file as layers: the first one into `first_layer`
// (which must be empty; null: a new layer), the others into new layers added to md (which may
// be null only when first_layer is the one layer needed). Layers are labelled frame_00000,
// frame_00001, ... by frame number. The range is checked first (planAmsImport: memory and
// decoding work). On failure, running out of memory included, every layer this call added is
// removed again and first_layer is left empty.
Result<QList<MeshModel*>> importAms(const std::string& path, const AmsImport& range,
                                    MeshDocument* md, MeshModel* first_layer,
                                    const ProgressFn& progress);

// MeshLab 2022+ makes the layers of a multi-layer open itself, before the plugin sees the file:
// how many frames of `path` the range covers (checked as importAms checks it), and the decoding
// of that range into exactly those layers. On failure the layers are left empty.
Result<int64_t> amsFrameCount(const std::string& path, const AmsImport& range);
Status importAmsInto(const std::string& path, const AmsImport& range, const QList<MeshModel*>& layers,
                     const ProgressFn& progress);

}  // namespace animc::meshlab
