// SPDX-License-Identifier: GPL-3.0-or-later
#include "encode_parameters.h"

#include <QStringList>

namespace animc::meshlab {
namespace {

// Enum order is the script value: append, never reorder.
const QStringList kCodecs = {"Affine-Octree", "Wavelet", "Trajectory", "Auto", "Trajectory 2"};
constexpr int kAutoCodec = 3;  // the default
constexpr int kTrajectory2Codec = 4;
const QStringList kProfiles = {"predictive", "paper"};
// How wavelet detail frames refer to the frame before them (animc encode: default,
// --progressive-p-frames, --i-frames-only).
const QStringList kWaveletFrames = {"P-frames", "progressive P-frames", "I-frames only"};

}  // namespace

void addEncodeParameters(RichParameterList& par) {
  const EncodeSettings defaults;
  const AffineOctreeOptions octree_defaults;
  const WaveletOptions wavelet_defaults;
  par.addParam(
      RichEnum("Codec", kAutoCodec, kCodecs, "Codec",
               "Affine-Octree: per-frame octree of affine motions, every vertex within the max error "
               "(docs/affine_octree.md). Wavelet: progressive wavelet coding on a mesh hierarchy, "
               "error set by the step or the bits per vertex (docs/wavelet.md). Trajectory: each group of frames "
               "as principal trajectories, the smallest files at a KG error; its groups are the I-frame "
               "interval, or up to 512 frames (docs/trajectory.md). Trajectory 2: the same with each group cut "
               "into up to 8 parts of the mesh that move together, each with its own basis: smaller files "
               "(docs/trajectory.md, \"Parts\"). Auto (the default): per group, the smaller "
               "of Trajectory 2 and Affine-Octree within the max error, or of Trajectory 2 and Wavelet at the "
               "target KG error when it is set (docs/auto.md)."));
  par.addParam(RichEnum(
      "Profile", 0, kProfiles, "Profile (Affine-Octree)",
      "predictive (the default): our predictive octree, smaller files; paper: the method exactly as published."));
  par.addParam(RichFloat("MaxErrorPercent", float(100 * octree_defaults.max_error), "Max error (%) (Affine-Octree)",
                         "Largest vertex error, in percent of the side of the frame's bounding cube "
                         "(the paper's ME; animc encode --max-error takes the same as a fraction)."));
  par.addParam(RichInt("Bits", octree_defaults.bits, "Bits (Affine-Octree)",
                       "Paper profile: bits per affine parameter and stored coordinate (8 to 24)."));
  par.addParam(RichFloat("WaveletStepPercent", float(100 * wavelet_defaults.step), "Step (% of diagonal) (Wavelet)",
                         "Finest quantisation step of the wavelet coefficients, in percent of the diagonal of "
                         "the first frame's bounding box (animc encode --step takes the same as a fraction). "
                         "Smaller: more accurate, larger file."));
  par.addParam(RichFloat("WaveletBitsPerVertex", float(wavelet_defaults.bits_per_vertex),
                         "Bits per vertex per frame (Wavelet)",
                         "Fixed rate: each frame is cut at this many bits per vertex (the paper's 1, 2, 4, 8); "
                         "0 = no limit, the step alone sets the quality."));
  par.addParam(RichFloat("WaveletTargetKG", float(wavelet_defaults.target_kg),
                         "Target KG error (%) (Wavelet, Trajectory, Trajectory 2, Auto)",
                         "Rate control by error: each frame (Wavelet) or group of frames (the others) gets the "
                         "fewest bits that keep the animation's KG error at or below this (Wavelet: down to "
                         "what the step allows). 0 = off for Wavelet and Auto (which then takes the max error), "
                         "0.3 % for Trajectory and Trajectory 2."));
  par.addParam(RichEnum("WaveletFrames", 0, kWaveletFrames, "Detail frames (Wavelet)",
                        "P-frames: each frame predicted from the last (smallest files). Progressive P-frames: "
                        "the same without temporal contexts, so a decoder may cut them (animc decode "
                        "--bitplanes / --max-bytes), with drift until the next I-frame; 0.6-5 % more bits. "
                        "I-frames only: every frame on its own, cuttable without drift; largest files."));
  par.addParam(RichInt("IFrameInterval", int(defaults.iframe_interval), "I-frame interval",
                       "An intra frame every K frames, so playback can start there; 0 = only the first frame."));
}

namespace {

// A float MeshLab (every 2020.09 build, the float 2022+ builds) keeps 0.3 as 0.30000001, and
// every MeshLab, double builds included, reads a script's values as floats (RichFloat from XML
// goes through QString::toFloat). The decimal the user typed (7 significant digits) is what
// animc would get from the same text, so both write the same file in every build.
double typedValue(const RichParameterList& par, const QString& name) {
  const double value = double(par.getFloat(name));
  return QString::number(value, 'g', 7).toDouble();
}

Status readOctreeParameters(const RichParameterList& par, AffineOctreeOptions& o) {
  const int profile = par.getEnum("Profile");
  if (profile < 0 || profile >= kProfiles.size()) return invalidArgument("unknown profile " + std::to_string(profile));
  o.profile = profile == 0 ? Profile::kPredictive : Profile::kPaper;
  const double percent = typedValue(par, "MaxErrorPercent");
  if (!(percent >= 100 * kMinMaxError && percent <= 100 * kMaxMaxError))
    return invalidArgument("the max error must be between 0.0001 % and 50 % of the cube's side, not " +
                           std::to_string(percent) + " %");
  o.max_error = percent / 100;
  o.bits = par.getInt("Bits");
  return Status();
}

Status readWaveletParameters(const RichParameterList& par, WaveletOptions& o) {
  o.step = typedValue(par, "WaveletStepPercent") / 100;
  o.bits_per_vertex = typedValue(par, "WaveletBitsPerVertex");
  o.target_kg = typedValue(par, "WaveletTargetKG");
  const int frames = par.getEnum("WaveletFrames");
  if (frames < 0 || frames >= kWaveletFrames.size())
    return invalidArgument("unknown wavelet detail-frame kind " + std::to_string(frames));
  o.progressive_p_frames = frames == 1;
  o.temporal_prediction = frames != 2;
  return Status();
}

// The trajectory codecs have no parameters of their own, so that every script written for the two
// earlier codecs still runs (MeshLab 2020.09's meshlabserver aborts on a script that lacks one
// of a filter's parameters): they take the target KG error of the wavelet codec (0 = their own
// default), and the I-frame interval, when set, as their group length.
Status readTrajectoryParameters(const RichParameterList& par, TrajectoryOptions& o) {
  const double target = typedValue(par, "WaveletTargetKG");
  if (target > 0) o.rate_value = target;
  return Status();
}

// Auto takes the max error, or the target KG error when it is set.
Status readAutoParameters(const RichParameterList& par, AutoOptions& o) {
  const double target = typedValue(par, "WaveletTargetKG");
  if (target > 0) {
    o.rate = TrajectoryRate::kTargetKg;
    o.rate_value = target;
  } else {
    o.rate = TrajectoryRate::kMaxError;
    o.rate_value = typedValue(par, "MaxErrorPercent") / 100;
  }
  o = withCandidates(o);
  return Status();
}

}  // namespace

Result<EncodeSettings> encodeSettingsFrom(const RichParameterList& par) {
  EncodeSettings s;
  const int codec = par.getEnum("Codec");
  if (codec < 0 || codec >= kCodecs.size()) return invalidArgument("unknown codec " + std::to_string(codec));
  if (codec == 1) {
    ANIMC_RETURN_IF_ERROR(readWaveletParameters(par, s.wavelet()));
  } else if (codec == 2) {
    ANIMC_RETURN_IF_ERROR(readTrajectoryParameters(par, s.trajectory()));
  } else if (codec == kTrajectory2Codec) {
    ANIMC_RETURN_IF_ERROR(readTrajectoryParameters(par, s.trajectory2().trajectory));
  } else if (codec == kAutoCodec) {
    ANIMC_RETURN_IF_ERROR(readAutoParameters(par, s.automatic()));
  } else {
    ANIMC_RETURN_IF_ERROR(readOctreeParameters(par, s.octree()));
  }
  const int interval = par.getInt("IFrameInterval");
  if (interval < 0) return invalidArgument("the I-frame interval must be 0 or more");
  s.iframe_interval = uint32_t(interval);
  s.threads = 0;  // every core, as animc: the bytes written are the same for any number
  ANIMC_RETURN_IF_ERROR(s.validate());
  return s;
}

}  // namespace animc::meshlab
