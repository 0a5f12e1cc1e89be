// SPDX-License-Identifier: GPL-3.0-or-later
#include "reconstruction_error.h"

#include <algorithm>
#include <cstdio>

#include "error_colouring.h"
#include "layer_frames.h"
#include "metrics/compare_sequences.h"
#include "report/report.h"
#include "seqio/mesh_checks.h"

namespace animc::meshlab {
namespace {

struct LayerRuns {
  QList<MeshModel*> originals;
  QList<MeshModel*> reconstructions;
};

// The two runs of `count` layers starting at the chosen layers (count 0: as many as fit).
Result<LayerRuns> layerRuns(MeshDocument& md, const RichParameterList& par) {
  const QList<MeshModel*> all = compat::layers(md);
  const int first_original = all.indexOf(compat::meshValue(par, "OriginalFirst", md));
  const int first_reconstructed = all.indexOf(compat::meshValue(par, "ReconstructedFirst", md));
  if (first_original < 0 || first_reconstructed < 0) return invalidArgument("choose two layers of the document");
  if (first_original == first_reconstructed)
    return invalidArgument("the original and reconstructed runs start at the same layer");
  const int fit = first_original < first_reconstructed
                      ? std::min(first_reconstructed - first_original, all.size() - first_reconstructed)
                      : std::min(first_original - first_reconstructed, all.size() - first_original);
  const int count = par.getInt("FrameCount") > 0 ? par.getInt("FrameCount") : fit;
  if (count > fit)
    return invalidArgument("runs of " + std::to_string(count) + " layers starting at layers " +
                           std::to_string(first_original) + " and " + std::to_string(first_reconstructed) +
                           " overlap or run past the last layer (at most " + std::to_string(fit) + " fit)");
  LayerRuns runs;
  for (int i = 0; i < count; ++i) {
    runs.originals << all[first_original + i];
    runs.reconstructions << all[first_reconstructed + i];
  }
  return runs;
}

// Both runs' figures; every layer is checked against the first original's topology on the
// way, so a bad layer ends the filter before any layer was changed.
Result<SequenceMetrics> measureRuns(const MeshDocument& md, const LayerRuns& runs, vcg::CallBackPos* cb) {
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<LayerFrameSource> originals, LayerFrameSource::create(&md, runs.originals));
  ANIMC_ASSIGN_OR_RETURN(std::unique_ptr<LayerFrameSource> reconstructions,
                         LayerFrameSource::create(&md, runs.reconstructions));
  const Status same = checkSameTopology(reconstructions->topology(), originals->topology(),
                                        layerName(&md, *runs.originals[0]));
  if (!same.ok()) return same.withContext(layerName(&md, *runs.reconstructions[0]));
  ProgressFn first_half;  // of the progress bar; colouring the layers is the second
  if (cb != nullptr) first_half = [cb](int percent, const char* what) { return cb(percent / 2, what); };
  return compareSequences(*originals, *reconstructions, first_half);
}

// Stores each reconstruction's per-vertex error as its quality and colours it on one scale.
// measureRuns has checked every layer already.
void colourRuns(const LayerRuns& runs, float scale, vcg::CallBackPos* cb) {
  const int frames = runs.originals.size();
  std::vector<float> original, reconstructed;
  for (int i = 0; i < frames; ++i) {
    layerPositions(*runs.originals[i], original);
    layerPositions(*runs.reconstructions[i], reconstructed);
    MeshModel& shown = *runs.reconstructions[i];
    std::vector<Scalarm> errors(original.size() / 3);
    MetricsAccumulator(uint32_t(errors.size()))
        .addFrame(original.data(), reconstructed.data(), [&](uint32_t v, double e) { errors[v] = Scalarm(e); });
    storeQuality(shown, errors);
    colourByQuality(shown, scale);
    if (cb != nullptr) cb(50 + 50 * (i + 1) / frames, "colouring layers");
  }
}

void logFigures(const LayerRuns& runs, const SequenceMetrics& m, float scale, const LogFn& log) {
  char line[200];
  for (int i = 0; i < runs.originals.size(); ++i) {
    std::snprintf(line, sizeof line, "frame %d: '%s' vs '%s': rms %.6g, max %.6g", i,
                  qUtf8Printable(runs.originals[i]->label()), qUtf8Printable(runs.reconstructions[i]->label()),
                  m.per_frame[size_t(i)].rms, m.per_frame[size_t(i)].max);
    log(line);
  }
  logLines(log, formatMetricsText(m));
  std::snprintf(line, sizeof line, "colour scale: blue = 0, red = %.6g (mesh units)", double(scale));
  log(line);
}

}  // namespace

void addErrorParameters(const MeshDocument& md, RichParameterList& par) {
  const QList<MeshModel*> all = compat::layers(md);
  const int n = all.size();
  MeshModel* first = n > 0 ? all[0] : nullptr;
  MeshModel* middle = n > 1 ? all[n / 2] : first;
  compat::addMeshParameter(par, "OriginalFirst", first, md, "First original layer",
                           "The original frames are this layer and the ones after it.");
  compat::addMeshParameter(par, "ReconstructedFirst", middle, md, "First reconstructed layer",
                           "The reconstructed frames are this layer and the ones after it (after "
                           "Compress Animation Layers: the first 'decoded' layer).");
  par.addParam(RichInt("FrameCount", 0, "Frames", "How many frames to compare; 0 = as many as fit."));
  par.addParam(RichFloat("ScaleMax", 0.0f, "Colour scale max",
                         "Error shown in full red, in mesh units; 0 = the largest error of the whole animation."));
}

std::string measureReconstructionError(MeshDocument& md, const RichParameterList& par,
                                       vcg::CallBackPos* cb, const LogFn& log) {
  Result<LayerRuns> runs = layerRuns(md, par);
  if (!runs.ok()) return runs.status().message();
  if (runs.value().originals.isEmpty()) return "no frames to compare";
  // Measure everything first, so a bad layer late in the run leaves every layer untouched.
  Result<SequenceMetrics> m = measureRuns(md, runs.value(), cb);
  if (!m.ok()) return m.status().message();
  const float scale = par.getFloat("ScaleMax") > 0 ? par.getFloat("ScaleMax") : float(m.value().max_error);
  colourRuns(runs.value(), scale, cb);
  logFigures(runs.value(), m.value(), scale, log);
  return {};
}

}  // namespace animc::meshlab
