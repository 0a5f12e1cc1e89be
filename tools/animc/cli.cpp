#include "cli.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace animc::cli {

const std::set<std::string> kEncodeOptions = {"codec", "profile", "max-error", "bits",
                                              "iframe-interval", "max-depth"};

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

Result<EncodeSettings> encodeSettingsFrom(const Args& args) {
  EncodeSettings s;
  const std::string codec = args.get("codec", "affine-octree");
  if (codec != "affine-octree") return invalidArgument("unknown codec '" + codec + "' (affine-octree)");
  const std::string profile = args.get("profile", "default");
  if (profile == "paper") s.octree.profile = Profile::kPaper;
  else if (profile == "default") s.octree.profile = Profile::kDefault;
  else return invalidArgument("unknown profile '" + profile + "' (paper, default)");
  ANIMC_ASSIGN_OR_RETURN(s.octree.max_error, args.number("max-error", s.octree.max_error));
  ANIMC_ASSIGN_OR_RETURN(long long bits, args.integer("bits", s.octree.bits));
  ANIMC_ASSIGN_OR_RETURN(long long depth, args.integer("max-depth", s.octree.max_depth));
  ANIMC_ASSIGN_OR_RETURN(long long interval, args.integer("iframe-interval", 0));
  if (bits < kMinBits || bits > kMaxBits) return invalidArgument("--bits must be in [8, 24]");
  if (depth < 1 || depth > kMaxDepthLimit) return invalidArgument("--max-depth must be in [1, 16]");
  if (interval < 0 || interval > 0x7fffffff) return invalidArgument("--iframe-interval must be >= 0");
  s.octree.bits = int(bits);
  s.octree.max_depth = int(depth);
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

int fail(const Status& status) {
  endProgressLine();
  std::fprintf(stderr, "animc: %s\n", status.message().c_str());
  return int(status.code());
}

}  // namespace animc::cli
