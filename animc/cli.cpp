// SPDX-License-Identifier: Apache-2.0
#include "cli.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "core/file_identity.h"
#include "core/temp_registry.h"
#include "report/json_writer.h"
#include "seqio/sequence_io.h"

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

namespace {

std::set<std::string> flagsOfEveryCodec(bool switches) {
  std::set<std::string> names;
  for (const CodecEntry* codec : allCodecs())
    for (const std::string& name : switches ? codec->switch_flags : codec->value_flags) names.insert(name);
  return names;
}

}  // namespace

const std::set<std::string>& encodeOptions() {
  static const std::set<std::string> names = [] {
    std::set<std::string> names = flagsOfEveryCodec(false);
    names.insert({"codec", "iframe-interval", "threads", "frames", "connectivity-piece"});
    return names;
  }();
  return names;
}

const std::set<std::string>& encodeSwitches() {
  static const std::set<std::string> names = flagsOfEveryCodec(true);
  return names;
}

std::string codecUsage() {
  std::string text;
  for (const CodecEntry* codec : allCodecs())
    text += "         " + std::string(codec->name) + ": " + codec->usage + "\n";
  return text;
}

// Without --codec: auto, or affine-octree when a flag only it takes is given, so that every
// command line of animc 1.x (whose default it was) still means the same codec.
std::string defaultCodec(const Args& args) {
  for (const char* flag : {"profile", "bits", "max-depth"})
    if (args.has(flag)) return "affine-octree";
  return "auto";
}

// The command line as the library's EncoderOptions, which it checks (an option of a codec not
// chosen is refused there).
Result<EncodeSettings> encodeSettingsFrom(const Args& args) {
  EncoderOptions options;
  options.codec = args.get("codec", defaultCodec(args));
  for (bool switches : {false, true})
    for (const std::string& name : flagsOfEveryCodec(switches))
      if (args.has(name)) options.set(name, args.get(name));
  ANIMC_ASSIGN_OR_RETURN(long long interval, args.integer("iframe-interval", 0));
  if (interval < 0 || interval > 0x7fffffff) return invalidArgument("--iframe-interval must be >= 0");
  options.iframe_interval = uint32_t(interval);
  ANIMC_ASSIGN_OR_RETURN(long long piece, args.integer("connectivity-piece", kDefaultConnectivityPiece));
  if (piece < 0 || piece > 0xffffffffll)
    return invalidArgument("--connectivity-piece must be in [0, 2^32 - 1] (0 = one piece, .ams format 1)");
  options.connectivity_piece = uint32_t(piece);
  ANIMC_ASSIGN_OR_RETURN(options.threads, threadsFrom(args));
  return animc::encodeSettingsFrom(options);
}

Result<uint32_t> threadsFrom(const Args& args) {
  ANIMC_ASSIGN_OR_RETURN(long long threads, args.integer("threads", 0));
  if (threads < 0 || threads > 1024) return invalidArgument("--threads must be in [0, 1024] (0 = one per core)");
  return uint32_t(threads);
}

Result<DecoderLimits> decoderLimitsFrom(const Args& args) {
  DecoderLimits limits;
  ANIMC_ASSIGN_OR_RETURN(long long work, args.integer("max-vertex-frames", (long long)limits.max_vertex_frames));
  if (work < 1) return invalidArgument("--max-vertex-frames must be at least 1");
  limits.max_vertex_frames = uint64_t(work);
  ANIMC_ASSIGN_OR_RETURN(long long output, args.integer("max-output-bytes", (long long)limits.max_output_bytes));
  if (output < 0) return invalidArgument("--max-output-bytes must be at least 1 (0 = no limit)");
  limits.max_output_bytes = output == 0 ? UINT64_MAX : uint64_t(output);
  ANIMC_ASSIGN_OR_RETURN(long long adds, args.integer("max-multiply-adds", (long long)limits.max_multiply_adds));
  if (adds < 1) return invalidArgument("--max-multiply-adds must be at least 1");
  limits.max_multiply_adds = uint64_t(adds);
  return limits;
}

Status parseRange(const std::string& text, int64_t count, int64_t& first, int64_t& last) {
  first = 0;
  last = count;
  if (text.empty()) return Status();
  const size_t colon = text.find(':');
  const std::string a = text.substr(0, colon);
  std::string b = colon == std::string::npos ? "" : text.substr(colon + 1);
  char* end = nullptr;
  if (!a.empty()) first = std::strtoll(a.c_str(), &end, 10);
  if (!a.empty() && *end) return invalidArgument("--frames: bad start '" + a + "'");
  if (colon == std::string::npos) {
    if (a.empty()) return invalidArgument("--frames: expected A:B");
    last = first + 1;
  } else if (!b.empty()) {
    last = std::strtoll(b.c_str(), &end, 10);
    if (*end) return invalidArgument("--frames: bad end '" + b + "'");
  }
  if (first < 0 || last > count || first >= last)
    return invalidArgument("--frames " + text + " is empty or outside [0, " + std::to_string(count) + ")");
  return Status();
}

namespace {

// Frames [first, last) of another source, the ones before skipped as they are read.
class FrameRangeSource final : public FrameSource {
 public:
  FrameRangeSource(std::unique_ptr<FrameSource> source, int64_t first, int64_t last)
      : source_(std::move(source)), first_(first), last_(last) {}
  const Topology& topology() const override { return source_->topology(); }
  int64_t frameCount() const override { return last_ - first_; }
  double frameRate() const override { return source_->frameRate(); }
  std::string where() const override { return source_->where(); }
  Result<bool> next(std::vector<float>& xyz) override {
    for (; next_ < first_; ++next_) {
      ANIMC_ASSIGN_OR_RETURN(bool more, source_->next(xyz));
      if (!more) return false;
    }
    if (next_ >= last_) return false;
    ++next_;
    return source_->next(xyz);
  }

 private:
  std::unique_ptr<FrameSource> source_;
  int64_t first_, last_, next_ = 0;
};

}  // namespace

Result<EncodeInput> openEncodeInput(const Args& args) {
  EncodeInput in;
  ANIMC_ASSIGN_OR_RETURN(in.settings, encodeSettingsFrom(args));
  ANIMC_ASSIGN_OR_RETURN(in.source, openSequence(args.positional()[0], args.get("mesh")));
  if (args.has("frames")) {
    const int64_t count = in.source->frameCount();
    if (count < 0) return invalidArgument("--frames needs an input whose frame count is known before reading it");
    int64_t first = 0, last = 0;
    ANIMC_RETURN_IF_ERROR(parseRange(args.get("frames"), count, first, last));
    in.source = std::make_unique<FrameRangeSource>(std::move(in.source), first, last);
  }
  ANIMC_ASSIGN_OR_RETURN(std::vector<std::string> inputs, sequenceInputFiles(args.positional()[0], args.get("mesh")));
  ANIMC_RETURN_IF_ERROR(refuseOutputOverInput(args.get("output"), inputs));
  return in;
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

bool isAmsPath(const std::string& path) { return path.size() > 4 && path.compare(path.size() - 4, 4, ".ams") == 0; }

std::string groupCodecsText(const EncodeSettings& settings, const std::vector<GroupCodecCount>& counts) {
  if (settings.codec() != CodecId::kAuto || counts.empty()) return "";
  std::string text;
  for (const GroupCodecCount& c : counts) text += (text.empty() ? " (" : ", ") + c.codec + " " + std::to_string(c.groups);
  return text + ")";
}

std::string groupCodecsJson(const std::vector<GroupCodecCount>& counts) {
  JsonObject o;
  for (const GroupCodecCount& c : counts) o.add(c.codec, c.groups);
  return o.str();
}

int fail(const Status& status) {
  endProgressLine();
  std::fprintf(stderr, "animc: %s\n", status.message().c_str());
  return int(status.code());
}

namespace {

extern "C" void removeTemporariesAndReraise(int signal_number) {
  removeRegisteredTemporaries();
  // SA_RESETHAND has put back the default action; the signal, blocked while this handler runs,
  // is delivered again when it returns and ends the process.
  raise(signal_number);
}

}  // namespace

void removeTemporariesOnSignals() {
  struct sigaction action = {};
  action.sa_handler = removeTemporariesAndReraise;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  for (int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction previous = {};
    if (sigaction(signal_number, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN) continue;
    sigaction(signal_number, &action, nullptr);
  }
}

}  // namespace animc::cli
