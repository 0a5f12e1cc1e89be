// SPDX-License-Identifier: Apache-2.0
#include "cli.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace animc::cli {

Status Args::parse(const std::vector<std::string>& argv, const std::set<std::string>& value_options,
                   const std::set<std::string>& switches) {
  for (size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() < 3 || a.compare(0, 2, "--") != 0) {
      if (a == "-o" && i + 1 < argv.size() && value_options.count("output")) {
        values_["output"] = argv[++i];
        continue;
      }
      positional_.push_back(a);
      continue;
    }
    const std::string name = a.substr(2);
    if (switches.count(name)) {
      values_[name] = "1";
    } else if (value_options.count(name)) {
      if (i + 1 >= argv.size()) return invalidArgument("--" + name + " needs a value");
      values_[name] = argv[++i];
    } else {
      return invalidArgument("unknown option --" + name);
    }
  }
  return Status();
}

std::string Args::get(const std::string& name, const std::string& fallback) const {
  auto it = values_.find(name);
  return it == values_.end() ? fallback : it->second;
}

Result<double> Args::number(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  const std::string s = get(name);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0') return invalidArgument("--" + name + ": not a number: " + s);
  return v;
}

Result<long long> Args::integer(const std::string& name, long long fallback) const {
  if (!has(name)) return fallback;
  const std::string s = get(name);
  char* end = nullptr;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0') return invalidArgument("--" + name + ": not an integer: " + s);
  return v;
}

namespace {

const std::set<std::string> kOctreeOptions = {"profile", "max-error", "bits", "max-depth"};
const std::set<std::string> kWaveletValueOptions = {"step", "bpv", "target-kg", "parametric-bits"};
const std::set<std::string> kWaveletSwitches = {"i-frames-only", "progressive-p-frames"};

// An option of the other codec is a mistake, not something to ignore.
Status rejectForeignOptions(const Args& args, const std::set<std::string>& foreign, const char* codec) {
  for (const std::string& name : foreign)
    if (args.has(name)) return invalidArgument("--" + name + " does not apply to --codec " + codec);
  return Status();
}

Status readOctreeOptions(const Args& args, AffineOctreeOptions& o) {
  const std::string profile = args.get("profile", "default");
  if (profile == "paper") o.profile = Profile::kPaper;
  else if (profile == "default") o.profile = Profile::kDefault;
  else return invalidArgument("unknown profile '" + profile + "' (paper, default)");
  ANIMC_ASSIGN_OR_RETURN(o.max_error, args.number("max-error", o.max_error));
  ANIMC_ASSIGN_OR_RETURN(long long bits, args.integer("bits", o.bits));
  ANIMC_ASSIGN_OR_RETURN(long long depth, args.integer("max-depth", o.max_depth));
  if (bits < kMinBits || bits > kMaxBits) return invalidArgument("--bits must be in [8, 24]");
  if (depth < 1 || depth > kMaxDepthLimit) return invalidArgument("--max-depth must be in [1, 16]");
  o.bits = int(bits);
  o.max_depth = int(depth);
  return Status();
}

Status readWaveletOptions(const Args& args, WaveletOptions& o) {
  ANIMC_ASSIGN_OR_RETURN(o.step, args.number("step", o.step));
  ANIMC_ASSIGN_OR_RETURN(o.bits_per_vertex, args.number("bpv", o.bits_per_vertex));
  ANIMC_ASSIGN_OR_RETURN(o.target_kg, args.number("target-kg", o.target_kg));
  ANIMC_ASSIGN_OR_RETURN(long long bits, args.integer("parametric-bits", o.parametric_bits));
  if (bits < kMinParametricBits || bits > kMaxParametricBits)
    return invalidArgument("--parametric-bits must be in [" + std::to_string(kMinParametricBits) + ", " +
                           std::to_string(kMaxParametricBits) + "]");
  o.parametric_bits = int(bits);
  o.temporal_prediction = !args.has("i-frames-only");
  o.progressive_p_frames = args.has("progressive-p-frames");
  return Status();
}

std::set<std::string> encodeOptionNames() {
  std::set<std::string> names = {"codec", "iframe-interval"};
  names.insert(kOctreeOptions.begin(), kOctreeOptions.end());
  names.insert(kWaveletValueOptions.begin(), kWaveletValueOptions.end());
  return names;
}

}  // namespace

const std::set<std::string> kEncodeOptions = encodeOptionNames();
const std::set<std::string> kEncodeSwitches = kWaveletSwitches;

Result<EncodeSettings> encodeSettingsFrom(const Args& args) {
  EncodeSettings s;
  const std::string codec = args.get("codec", "affine-octree");
  if (codec == "affine-octree") {
    ANIMC_RETURN_IF_ERROR(rejectForeignOptions(args, kWaveletValueOptions, "affine-octree"));
    ANIMC_RETURN_IF_ERROR(rejectForeignOptions(args, kWaveletSwitches, "affine-octree"));
    ANIMC_RETURN_IF_ERROR(readOctreeOptions(args, s.octree));
  } else if (codec == "wavelet") {
    s.codec = CodecId::kWavelet;
    ANIMC_RETURN_IF_ERROR(rejectForeignOptions(args, kOctreeOptions, "wavelet"));
    ANIMC_RETURN_IF_ERROR(readWaveletOptions(args, s.wavelet));
  } else {
    return invalidArgument("unknown codec '" + codec + "' (affine-octree, wavelet)");
  }
  ANIMC_ASSIGN_OR_RETURN(long long interval, args.integer("iframe-interval", 0));
  if (interval < 0 || interval > 0x7fffffff) return invalidArgument("--iframe-interval must be >= 0");
  s.iframe_interval = uint32_t(interval);
  ANIMC_RETURN_IF_ERROR(s.validate());
  return s;
}

namespace {
bool g_progress_shown = false;
}

ProgressFn progressLine(const char* label, bool force) {
  if (!force && !isatty(STDERR_FILENO)) return {};
  using Clock = std::chrono::steady_clock;
  auto last = std::make_shared<Clock::time_point>(Clock::now() - std::chrono::seconds(1));
  return [label, last](int percent, const char* what) {
    const auto now = Clock::now();
    if (percent < 100 && now - *last < std::chrono::milliseconds(100)) return true;
    *last = now;
    std::fprintf(stderr, "\r%s: %s %3d%%", label, what, percent);
    std::fflush(stderr);
    g_progress_shown = true;
    return true;
  };
}

void endProgressLine() {
  if (g_progress_shown) std::fputc('\n', stderr);
  g_progress_shown = false;
}

bool isAmsPath(const std::string& path) {
  return path.size() > 4 && path.compare(path.size() - 4, 4, ".ams") == 0;
}

int fail(const Status& status) {
  endProgressLine();
  std::fprintf(stderr, "animc: %s\n", status.message().c_str());
  return int(status.code());
}

}  // namespace animc::cli
