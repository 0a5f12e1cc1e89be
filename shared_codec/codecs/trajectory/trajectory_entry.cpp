// SPDX-License-Identifier: Apache-2.0
// The trajectory codec's entry in the codec table (codecs/codec_registry.h).
#include <cstdio>

#include "codecs/codec_registry.h"
#include "codecs/trajectory/trajectory_codec.h"

namespace animc {
namespace {

const TrajectoryOptions& trajectory(const CodecOptions& o) { return std::get<TrajectoryOptions>(o); }

Result<CodecOptions> fromFlags(const OptionValues& values) {
  TrajectoryOptions o;
  if (values.has("step") && values.has("target-kg"))
    return invalidArgument("--step and --target-kg exclude each other (a fixed step, or a target error)");
  ANIMC_ASSIGN_OR_RETURN(o.target_kg, values.number("target-kg", o.target_kg));
  ANIMC_ASSIGN_OR_RETURN(o.step, values.number("step", o.step));
  ANIMC_ASSIGN_OR_RETURN(long long frames, values.integer("group-frames", o.group_frames));
  if (frames < 1 || frames > kMaxTrajectoryGroupFrames)
    return invalidArgument("--group-frames must be in [1, " + std::to_string(kMaxTrajectoryGroupFrames) + "]");
  o.group_frames = uint32_t(frames);
  return CodecOptions(o);
}

std::string describe(const CodecOptions& options) {
  const TrajectoryOptions& o = trajectory(options);
  char text[160];
  if (o.step > 0)
    std::snprintf(text, sizeof text, "step %g of the diagonal, groups of up to %u frames", o.step, o.group_frames);
  else
    std::snprintf(text, sizeof text, "target KG %g %%, groups of up to %u frames", o.target_kg, o.group_frames);
  return text;
}

std::vector<SettingValue> settings(const CodecOptions& options) {
  const TrajectoryOptions& o = trajectory(options);
  return {{"target_kg_setting", o.target_kg}, {"step", o.step}, {"group_frames", int64_t(o.group_frames)}};
}

Status checkMesh(const Topology&) { return Status(); }

std::unique_ptr<GroupEncoder> makeEncoder(const CodecOptions& o, const Topology& topology, SimdPath path) {
  return makeTrajectoryEncoder(trajectory(o), topology, path);
}

Result<std::unique_ptr<FrameDecoder>> makeDecoder(const CodecOptions&, const Topology& topology,
                                                  const WaveletDecodeControl& control, const std::string& file,
                                                  SimdPath path) {
  if (control.partial())
    return invalidArgument(file + ": progressive decoding (fewer bitplanes or bytes) needs a wavelet-coded "
                           "file; this one is trajectory");
  return makeTrajectoryDecoder(topology, path);
}

}  // namespace

const CodecEntry kTrajectoryEntry = {
    CodecId::kTrajectory,
    "trajectory",
    {"target-kg", "step", "group-frames"},
    {},
    "[--target-kg X | --step S] [--group-frames G]\n"
    "           X: the KG error (in %) to reach with the fewest bits (default 0.3); S: a fixed\n"
    "           coefficient step, a fraction of the first frame's diagonal; G: the most frames\n"
    "           coded together when --iframe-interval does not set it (default 512)",
    fromFlags,
    validateOptions<TrajectoryOptions>,
    writeOptions<TrajectoryOptions>,
    readOptions<TrajectoryOptions>,
    describe,
    settings,
    checkMesh,
    nullptr,
    makeEncoder,
    makeDecoder,
};

}  // namespace animc
