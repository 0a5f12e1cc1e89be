// SPDX-License-Identifier: GPL-3.0-or-later
#include "layer_frames.h"

#include <vcg/complex/allocate.h>

#include <functional>
#include <new>

#include "seqio/mesh_checks.h"

namespace animc::meshlab {
namespace {

// Index of every live vertex among the live vertices (-1 for deleted ones).
std::vector<int64_t> liveVertexIndex(const CMeshO& cm) {
  std::vector<int64_t> index(cm.vert.size(), -1);
  int64_t next = 0;
  for (size_t i = 0; i < cm.vert.size(); ++i)
    if (!cm.vert[i].IsD()) index[i] = next++;
  return index;
}

Topology layerTopology(const CMeshO& cm) {
  const std::vector<int64_t> index = liveVertexIndex(cm);
  Topology t;
  t.vertex_count = uint32_t(cm.vn);
  t.triangles.reserve(size_t(cm.fn));
  for (const CFaceO& f : cm.face) {
    if (f.IsD()) continue;
    Triangle tri;
    for (int k = 0; k < 3; ++k) tri[k] = uint32_t(index[size_t(f.cV(k) - &cm.vert[0])]);
    t.triangles.push_back(tri);
  }
  return t;
}

}  // namespace

void layerPositions(const MeshModel& layer, std::vector<float>& xyz) {
  xyz.resize(3 * size_t(layer.cm.vn));
  float* out = xyz.data();
  for (const CVertexO& v : layer.cm.vert) {
    if (v.IsD()) continue;
    *out++ = float(v.cP()[0]);
    *out++ = float(v.cP()[1]);
    *out++ = float(v.cP()[2]);
  }
}

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
  source->topology_ = layerTopology(layers[0]->cm);
  const Status s = checkTopology(source->topology_);
  if (!s.ok()) return s.withContext(layerName(md, *layers[0]));
  return source;
}

Result<bool> LayerFrameSource::next(std::vector<float>& xyz) {
  if (next_ >= layers_.size()) return false;
  const MeshModel& layer = *layers_[next_];
  if (next_ > 0) {
    const Status same = checkSameTopology(layerTopology(layer.cm), topology_, layerName(md_, *layers_[0]));
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

Status checkLayerMemory(const std::string& path, const Topology& topology, int64_t first, int64_t last,
                        int64_t max_megabytes) {
  const double megabytes = double(last - first + 1) * double(layerBytes(topology)) / (1 << 20);
  if (megabytes <= double(max_megabytes)) return Status();
  // Built as a string: a fixed buffer would cut the message at a long path.
  return limitExceeded("frames " + std::to_string(first) + " to " + std::to_string(last) + " of " + path +
                       " would take about " + std::to_string(int64_t(megabytes + 0.5)) + " MB as layers (" +
                       std::to_string(topology.vertex_count) + " vertices and " +
                       std::to_string(topology.triangles.size()) + " triangles each), above the memory limit of " +
                       std::to_string(max_megabytes) +
                       " MB: load fewer frames (First frame, Last frame) or raise the limit (Memory limit (MB) "
                       "when opening, or ANIMC_MEMORY_LIMIT_MB)");
}

}  // namespace

uint64_t layerBytes(const Topology& topology) {
  // The optional attributes MeshLab enables on loaded layers (colour, quality, adjacency) take
  // about as much again as the fixed part of each element.
  constexpr uint64_t kLayerOverhead = 64 << 10;
  return 2 * (uint64_t(topology.vertex_count) * sizeof(CVertexO) +
              uint64_t(topology.triangles.size()) * sizeof(CFaceO)) +
         kLayerOverhead;
}

namespace {

// An opened .ams file and the checked range [first, last] of its frames to make layers of.
struct AmsRange {
  std::unique_ptr<AmsSource> source;
  int64_t first = 0;
  int64_t last = 0;
};

Result<AmsRange> openAmsRange(const std::string& path, const AmsImport& range) {
  AmsRange r;
  DecoderLimits limits;
  limits.max_vertex_frames = range.max_vertex_frames;
  ANIMC_ASSIGN_OR_RETURN(r.source, AmsSource::open(path, limits));
  const int64_t frames = r.source->frameCount();
  r.first = range.first_frame;
  r.last = range.last_frame < 0 ? frames - 1 : range.last_frame;
  if (r.first < 0 || r.first > r.last || r.last >= frames)
    return invalidArgument("frames " + std::to_string(r.first) + " to " + std::to_string(r.last) +
                           " asked for, but " + path + " has frames 0 to " + std::to_string(frames - 1));
  ANIMC_RETURN_IF_ERROR(
      checkLayerMemory(path, r.source->topology(), r.first, r.last, range.max_layer_megabytes));
  const Status work = r.source->checkDecodeWork(r.first, r.last + 1);
  if (!work.ok())  // the library names its own knobs; MeshLab users have these
    return Status(work.code(), work.message() +
                                   "; in MeshLab: Decode work limit (million vertex-frames) when opening, or "
                                   "ANIMC_MAX_VERTEX_FRAMES");
  ANIMC_RETURN_IF_ERROR(r.source->seek(r.first));
  return r;
}

// Decodes the range frame by frame into the layers layer_for(frame) gives, labelled by frame
// number. The caller undoes what was made when this fails.
Status decodeIntoLayers(const std::string& path, AmsRange& r, const std::function<MeshModel*(int64_t)>& layer_for,
                        const ProgressFn& progress) {
  std::vector<float> xyz;
  int64_t frame = r.first;
  try {
    for (; frame <= r.last; ++frame) {
      Result<bool> more = r.source->next(xyz);
      if (!more.ok()) return more.status();
      if (!more.value()) return truncated(path + ": frame " + std::to_string(frame) + " is missing");
      MeshModel& layer = *layer_for(frame);
      layer.setLabel(frameLabel(frame));
      fillMesh(layer, r.source->topology(), xyz.data());
      const int percent = int(100 * (frame - r.first + 1) / (r.last - r.first + 1));
      if (progress && !progress(percent, "decoding frames")) return cancelled();
    }
  } catch (const std::bad_alloc&) {
    // The estimate was below the limit but the machine has less: the caller gives it back.
    return limitExceeded("out of memory after " + std::to_string(frame - r.first) + " layers of " + path +
                         ": load fewer frames or lower the memory limit");
  }
  return Status();
}

}  // namespace

Result<QList<MeshModel*>> importAms(const std::string& path, const AmsImport& range,
                                    MeshDocument* md, MeshModel* first_layer,
                                    const ProgressFn& progress) {
  ANIMC_ASSIGN_OR_RETURN(AmsRange r, openAmsRange(path, range));
  if (md == nullptr && (first_layer == nullptr || r.last > r.first))
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
  return r.last - r.first + 1;
}

Status importAmsInto(const std::string& path, const AmsImport& range, const QList<MeshModel*>& layers,
                     const ProgressFn& progress) {
  ANIMC_ASSIGN_OR_RETURN(AmsRange r, openAmsRange(path, range));
  if (r.last - r.first + 1 != layers.size())
    return invalidArgument("MeshLab made " + std::to_string(layers.size()) + " layers for " +
                           std::to_string(r.last - r.first + 1) + " frames of " + path);
  int next = 0;
  const Status s = decodeIntoLayers(path, r, [&](int64_t) { return layers[next++]; }, progress);
  if (!s.ok())
    for (MeshModel* m : layers) compat::clearLayer(*m);
  return s;
}

}  // namespace animc::meshlab
