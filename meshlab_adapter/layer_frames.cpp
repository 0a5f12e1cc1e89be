// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_frames.h"

#include <vcg/complex/allocate.h>

#include <functional>
#include <new>

#include "seqio/mesh_checks.h"

namespace animc::meshlab {

QList<MeshModel*> frameLayers(const MeshDocument& md, bool visible_only) {
  QList<MeshModel*> layers;
  for (MeshModel* m : compat::layers(md))
    if (!visible_only || m->isVisible()) layers << m;
  return layers;
}

std::string layerName(const MeshDocument* md, const MeshModel& layer) {
  const int index = md != nullptr ? compat::layers(*md).indexOf(const_cast<MeshModel*>(&layer)) : -1;
  return "layer " + std::to_string(index) + " ('" + layer.label().toStdString() + "')";
}

Result<std::unique_ptr<LayerFrameSource>> LayerFrameSource::create(const MeshDocument* md,
                                                                  const QList<MeshModel*>& layers) {
  if (layers.isEmpty()) return badInput("there are no layers to use as frames");
  std::unique_ptr<LayerFrameSource> source(new LayerFrameSource(md));
  source->layers_ = layers;
  source->topology_ = liveTopology(layers[0]->cm);
  const Status s = checkTopology(source->topology_);
  if (!s.ok()) return s.withContext(layerName(md, *layers[0]));
  return source;
}

Result<bool> LayerFrameSource::next(std::vector<float>& xyz) {
  if (next_ >= layers_.size()) return false;
  const MeshModel& layer = *layers_[next_];
  if (next_ > 0) {
    const Status same = checkSameTopology(liveTopology(layer.cm), topology_, layerName(md_, *layers_[0]));
    if (!same.ok()) return same.withContext(where());
  }
  layerPositions(layer, xyz);
  ++next_;
  return true;
}

std::string LayerFrameSource::where() const {
  if (next_ >= layers_.size()) return "after the last layer";
  return layerName(md_, *layers_[next_]);
}

void fillMesh(MeshModel& layer, const Topology& topology, const float* xyz) {
  CMeshO& cm = layer.cm;
  auto v = vcg::tri::Allocator<CMeshO>::AddVertices(cm, topology.vertex_count);
  for (uint32_t i = 0; i < topology.vertex_count; ++i, ++v)
    v->P() = Point3m(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  auto f = vcg::tri::Allocator<CMeshO>::AddFaces(cm, topology.triangles.size());
  for (const Triangle& t : topology.triangles) {
    for (int k = 0; k < 3; ++k) f->V(k) = &cm.vert[t[k]];
    ++f;
  }
  compat::updateBoxAndNormals(layer);
}

namespace {

// "frame_00012"
QString frameLabel(int64_t frame) { return QString("frame_%1").arg(frame, 5, 10, QChar('0')); }

constexpr LayerElementBytes kElementBytes = {sizeof(CVertexO), sizeof(CFaceO)};

// An opened .ams file and the checked range [first, last] of its frames to make layers of.
struct AmsRange {
  std::unique_ptr<AmsSource> source;
  FrameRange frames;
};

Result<AmsRange> openAmsRange(const std::string& path, const AmsImport& range) {
  AmsRange r;
  ANIMC_ASSIGN_OR_RETURN(r.source, AmsSource::open(path, range.decoderLimits()));
  ANIMC_ASSIGN_OR_RETURN(r.frames, planAmsImport(path, *r.source, range, kElementBytes));
  return r;
}

// Decodes the range frame by frame into the layers layer_for(frame) gives, labelled by frame
// number. The caller undoes what was made when this fails.
Status decodeIntoLayers(const std::string& path, AmsRange& r, const std::function<MeshModel*(int64_t)>& layer_for,
                        const ProgressFn& progress) {
  std::vector<float> xyz;
  int64_t frame = r.frames.first;
  try {
    for (; frame <= r.frames.last; ++frame) {
      Result<bool> more = r.source->next(xyz);
      if (!more.ok()) return more.status();
      if (!more.value()) return truncated(path + ": frame " + std::to_string(frame) + " is missing");
      MeshModel& layer = *layer_for(frame);
      layer.setLabel(frameLabel(frame));
      fillMesh(layer, r.source->topology(), xyz.data());
      const int percent = int(100 * (frame - r.frames.first + 1) / r.frames.count());
      if (progress && !progress(percent, "decoding frames")) return cancelled();
    }
  } catch (const std::bad_alloc&) {
    // The estimate was below the limit but the machine has less: the caller gives it back.
    return limitExceeded("out of memory after " + std::to_string(frame - r.frames.first) + " layers of " + path +
                         ": load fewer frames or lower the memory limit");
  }
  return Status();
}

}  // namespace

Result<QList<MeshModel*>> importAms(const std::string& path, const AmsImport& range,
                                    MeshDocument* md, MeshModel* first_layer,
                                    const ProgressFn& progress) {
  ANIMC_ASSIGN_OR_RETURN(AmsRange r, openAmsRange(path, range));
  if (md == nullptr && (first_layer == nullptr || r.frames.last > r.frames.first))
    return invalidArgument("no document to add the frames to as layers");
  QList<MeshModel*> layers;
  auto layer_for = [&](int64_t) {
    MeshModel* layer = layers.isEmpty() && first_layer != nullptr ? first_layer : md->addNewMesh("", "", false);
    layers << layer;
    return layer;
  };
  const Status s = decodeIntoLayers(path, r, layer_for, progress);
  if (s.ok()) return layers;
  for (MeshModel* m : layers)
    if (m != first_layer) compat::removeLayer(*md, m);
  if (first_layer != nullptr) compat::clearLayer(*first_layer);
  return s;
}

Result<int64_t> amsFrameCount(const std::string& path, const AmsImport& range) {
  ANIMC_ASSIGN_OR_RETURN(AmsRange r, openAmsRange(path, range));
  return r.frames.count();
}

Status importAmsInto(const std::string& path, const AmsImport& range, const QList<MeshModel*>& layers,
                     const ProgressFn& progress) {
  ANIMC_ASSIGN_OR_RETURN(AmsRange r, openAmsRange(path, range));
  ANIMC_RETURN_IF_ERROR(checkLayerCount(path, r.frames, layers.size()));
  int next = 0;
  const Status s = decodeIntoLayers(path, r, [&](int64_t) { return layers[next++]; }, progress);
  if (!s.ok())
    for (MeshModel* m : layers) compat::clearLayer(*m);
  return s;
}

}  // namespace animc::meshlab
