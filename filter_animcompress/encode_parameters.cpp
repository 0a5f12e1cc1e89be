#include "encode_parameters.h"

#include <QStringList>

namespace animc::meshlab {
namespace {

// Enum order is the script value: append, never reorder.
const QStringList kCodecs = {"Affine-Octree"};
const QStringList kProfiles = {"default", "paper"};

}  // namespace

void addEncodeParameters(RichParameterList& par) {
  const EncodeSettings defaults;
  par.addParam(RichEnum("Codec", 0, kCodecs, "Codec", "Affine-Octree: per-frame octree of affine motions (docs/affine_octree.md)."));
  par.addParam(RichEnum("Profile", 0, kProfiles, "Profile",
                        "default: our predictive octree (smaller files); paper: the method exactly as published."));
  par.addParam(RichFloat("MaxErrorPercent", float(100 * defaults.octree.max_error), "Max error (%)",
                         "Largest vertex error, in percent of the side of the frame's bounding cube "
                         "(the paper's ME; animc encode --max-error takes the same as a fraction)."));
  par.addParam(RichInt("Bits", defaults.octree.bits, "Bits",
                       "Paper profile: bits per affine parameter and stored coordinate (8 to 24)."));
  par.addParam(RichInt("IFrameInterval", int(defaults.iframe_interval), "I-frame interval",
                       "An intra frame every K frames, so playback can start there; 0 = only the first frame."));
}

Result<EncodeSettings> encodeSettingsFrom(const RichParameterList& par) {
  EncodeSettings s;
  const int codec = par.getEnum("Codec");
  if (codec != 0) return invalidArgument("unknown codec " + std::to_string(codec));
  const int profile = par.getEnum("Profile");
  if (profile < 0 || profile >= kProfiles.size()) return invalidArgument("unknown profile " + std::to_string(profile));
  s.octree.profile = profile == 0 ? Profile::kDefault : Profile::kPaper;
  const double percent = par.getFloat("MaxErrorPercent");
  if (!(percent >= 100 * kMinMaxError && percent <= 100 * kMaxMaxError))
    return invalidArgument("the max error must be between 0.0001 % and 50 % of the cube's side, not " +
                           std::to_string(percent) + " %");
  s.octree.max_error = percent / 100;
  s.octree.bits = par.getInt("Bits");
  const int interval = par.getInt("IFrameInterval");
  if (interval < 0) return invalidArgument("the I-frame interval must be 0 or more");
  s.iframe_interval = uint32_t(interval);
  ANIMC_RETURN_IF_ERROR(s.validate());
  return s;
}

}  // namespace animc::meshlab
