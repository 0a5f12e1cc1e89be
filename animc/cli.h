// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the animc subcommands: argument parsing, encode flags, progress line,
// errors to exit codes.
#pragma once
#include <map>
#include <set>
#include <string>
#include <vector>

#include "api.h"

namespace animc::cli {

// "--name value" options, "--flag" switches and positional arguments. Unknown names are
// errors, so a typo never passes silently.
class Args {
 public:
  // value_options take a value; switches do not.
  Status parse(const std::vector<std::string>& argv, const std::set<std::string>& value_options,
               const std::set<std::string>& switches);
  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const { return values_.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback = "") const;
  Result<double> number(const std::string& name, double fallback) const;
  Result<long long> integer(const std::string& name, long long fallback) const;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

// --codec --iframe-interval, the Affine-Octree's --profile --max-error --bits --max-depth and
// the wavelet's --step --bpv --target-kg --parametric-bits (options of the codec not chosen are errors).
extern const std::set<std::string> kEncodeOptions;
// The wavelet's --i-frames-only (no temporal prediction: every frame decodes on its own) and
// --progressive-p-frames (P-frames a decoder may cut).
extern const std::set<std::string> kEncodeSwitches;
Result<EncodeSettings> encodeSettingsFrom(const Args& args);

// Progress on stderr, at most ten updates a second, only when stderr is a terminal or
// --progress was given.
ProgressFn progressLine(const char* label, bool force);
void endProgressLine();

// Whether a path names an .ams file (by its extension), which compare and bench read as one.
bool isAmsPath(const std::string& path);

// Prints "animc: <message>" on stderr and returns the exit status for the code.
int fail(const Status& status);

int runEncode(const std::vector<std::string>& argv);
int runDecode(const std::vector<std::string>& argv);
int runInfo(const std::vector<std::string>& argv);
int runCompare(const std::vector<std::string>& argv);
int runBench(const std::vector<std::string>& argv);

}  // namespace animc::cli
