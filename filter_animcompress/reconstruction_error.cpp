#include "reconstruction_error.h"

#include <algorithm>
#include <cstdio>

#include "error_colouring.h"
#include "layer_frames.h"
#include "metrics/sequence_metrics.h"
#include "seqio/mesh_checks.h"

namespace animc::meshlab {
namespace {

struct LayerRuns {
  QList<MeshModel*> originals;
  QList<MeshModel*> reconstructions;
};

// The two runs of `count` layers starting at the chosen layers (count 0: as many as fit).
Result<LayerRuns> layerRuns(const MeshDocument& md, const RichParameterList& par) {
  const int first_original = md.meshList.indexOf(par.getMesh("OriginalFirst"));
  const int first_reconstructed = md.meshList.indexOf(par.getMesh("ReconstructedFirst"));
  if (first_original < 0 || first_reconstructed < 0) return invalidArgument("choose two layers of the document");
  if (first_original == first_reconstructed)
    return invalidArgument("the original and reconstructed runs start at the same layer");
  const int fit = first_original < first_reconstructed
                      ? std::min(first_reconstructed - first_original, md.size() - first_reconstructed)
                      : std::min(first_original - first_reconstructed, md.size() - first_original);
  const int count = par.getInt("FrameCount") > 0 ? par.getInt("FrameCount") : fit;
  if (count > fit)
    return invalidArgument("runs of " + std::to_string(count) + " layers starting at layers " +
                           std::to_string(first_original) + " and " + std::to_string(first_reconstructed) +
                           " overlap or run past the last layer (at most " + std::to_string(fit) + " fit)");
  LayerRuns runs;
  for (int i = 0; i < count; ++i) {
    runs.originals << md.meshList[first_original + i];
    runs.reconstructions << md.meshList[first_reconstructed + i];
  }
  return runs;
}

// Frame i of both runs, checked against the first original's topology.
Status readPair(LayerFrameSource& originals, LayerFrameSource& reconstructions,
                std::vector<float>& original, std::vector<float>& reconstructed) {
  Result<bool> a = originals.next(original);
  if (!a.ok()) return a.status();
  Result<bool> b = reconstructions.next(reconstructed);
  if (!b.ok()) return b.status();
  if (!a.value() || !b.value()) return invalidArgument("ran out of layers");
  return Status();
}

}  // namespace

void addErrorParameters(MeshDocument& md, RichParameterList& par) {
  const int n = md.size();
  MeshModel* first = n > 0 ? md.meshList[0] : nullptr;
  MeshModel* middle = n > 1 ? md.meshList[n / 2] : first;
  par.addParam(RichMesh("OriginalFirst", first, &md, "First original layer",
                        "The original frames are this layer and the ones after it."));
  par.addParam(RichMesh("ReconstructedFirst", middle, &md, "First reconstructed layer",
                        "The reconstructed frames are this layer and the ones after it (after "
                        "Compress Animation Layers: the first 'decoded' layer)."));
  par.addParam(RichInt("FrameCount", 0, "Frames", "How many frames to compare; 0 = as many as fit."));
  par.addParam(RichFloat("ScaleMax", 0.0f, "Colour scale max",
                         "Error shown in full red, in mesh units; 0 = the largest error of the whole animation."));
}

std::string measureReconstructionError(MeshDocument& md, const RichParameterList& par,
                                       vcg::CallBackPos* cb, const LogFn& log) {
  Result<LayerRuns> runs = layerRuns(md, par);
  if (!runs.ok()) return runs.status().message();
  if (runs.value().originals.isEmpty()) return "no frames to compare";
  auto originals = LayerFrameSource::create(runs.value().originals);
  if (!originals.ok()) return originals.status().message();
  auto reconstructions = LayerFrameSource::create(runs.value().reconstructions);
  if (!reconstructions.ok()) return reconstructions.status().message();
  const Status same = checkSameTopology(reconstructions.value()->topology(), originals.value()->topology(),
                                        layerName(*runs.value().originals[0]));
  if (!same.ok()) return same.withContext(layerName(*runs.value().reconstructions[0])).message();

  // Measure everything first, so a bad layer late in the run leaves every layer untouched.
  const int frames = runs.value().originals.size();
  MetricsAccumulator metrics(originals.value()->topology().vertex_count);
  std::vector<float> original, reconstructed;
  for (int i = 0; i < frames; ++i) {
    const Status s = readPair(*originals.value(), *reconstructions.value(), original, reconstructed);
    if (!s.ok()) return s.message();
    metrics.addFrame(original.data(), reconstructed.data());
    if (cb != nullptr) cb(50 * (i + 1) / frames, "measuring errors");
  }
  const SequenceMetrics m = metrics.finish();
  const float scale = par.getFloat("ScaleMax") > 0 ? par.getFloat("ScaleMax") : float(m.max_error);
  originals = LayerFrameSource::create(runs.value().originals);
  reconstructions = LayerFrameSource::create(runs.value().reconstructions);
  for (int i = 0; i < frames; ++i) {
    (void)readPair(*originals.value(), *reconstructions.value(), original, reconstructed);
    MeshModel& shown = *runs.value().reconstructions[i];
    storeVertexError(shown, original.data(), reconstructed.data());
    colourByQuality(shown, scale);
    if (cb != nullptr) cb(50 + 50 * (i + 1) / frames, "colouring layers");
  }

  char line[200];
  for (int i = 0; i < frames; ++i) {
    std::snprintf(line, sizeof line, "frame %d: '%s' vs '%s': rms %.6g, max %.6g", i,
                  qUtf8Printable(runs.value().originals[i]->label()),
                  qUtf8Printable(runs.value().reconstructions[i]->label()), m.per_frame[size_t(i)].rms,
                  m.per_frame[size_t(i)].max);
    log(line);
  }
  logLines(log, formatMetricsText(m));
  std::snprintf(line, sizeof line, "colour scale: blue = 0, red = %.6g (mesh units)", double(scale));
  log(line);
  return {};
}

}  // namespace animc::meshlab
