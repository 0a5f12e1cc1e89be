// SPDX-License-Identifier: Apache-2.0
// Shared pieces of the animc subcommands: argument parsing, encode flags, progress line,
// errors to exit codes.
#pragma once
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "api.h"

namespace animc::cli {

// "--name value" options, "--flag" switches and positional arguments. Unknown names are
// errors, so a typo never passes silently.
class Args : public OptionValues {
 public:
  // value_options take a value; switches do not.
  Status parse(const std::vector<std::string>& argv, const std::set<std::string>& value_options,
               const std::set<std::string>& switches);
  const std::vector<std::string>& positional() const { return positional_; }
  bool has(const std::string& name) const override { return values_.count(name) > 0; }
  std::string get(const std::string& name, const std::string& fallback = "") const override;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
};

// --codec, --iframe-interval and every codec's options (codec_registry.h): those of a codec
// not chosen are errors.
// (Functions, not constants: the codec table is not there yet while constants are made.)
const std::set<std::string>& encodeOptions();
// Every codec's switches, e.g. the wavelet's --i-frames-only.
const std::set<std::string>& encodeSwitches();
// "  affine-octree: [--profile paper|predictive] ...\n" for each codec, for the usage text.
std::string codecUsage();
Result<EncodeSettings> encodeSettingsFrom(const Args& args);

// What encode and bench start from: the settings of the flags and the input sequence (the
// first positional argument, with --mesh), once -o is known to be none of the input's files.
struct EncodeInput {
  EncodeSettings settings;
  std::unique_ptr<FrameSource> source;
};
Result<EncodeInput> openEncodeInput(const Args& args);

// --threads N: the threads encoding or decoding may use, 0 (the default) = one per core.
Result<uint32_t> threadsFrom(const Args& args);

// The decoder's limits with --max-vertex-frames V, --max-output-bytes B (0 = no limit) and
// --max-multiply-adds W applied (DecoderLimits::max_vertex_frames, max_output_bytes,
// max_multiply_adds).
Result<DecoderLimits> decoderLimitsFrom(const Args& args);

// Progress on stderr, at most ten updates a second, only when stderr is a terminal or
// --progress was given.
ProgressFn progressLine(const char* label, bool force);
void endProgressLine();

// --frames "A:B" (frames A to B-1; either side may be omitted, "A" alone is frame A) of a
// sequence of `count` frames: first and last, or why not.
Status parseRange(const std::string& text, int64_t count, int64_t& first, int64_t& last);

// Whether a path names an .ams file (by its extension), which compare and bench read as one.
bool isAmsPath(const std::string& path);

// Prints "animc: <message>" on stderr and returns the exit status for the code.
int fail(const Status& status);

// Of an auto file's groups: " (trajectory 7, affine-octree 1)"; "" for other codecs, whose
// groups are all theirs. And the counts as a JSON object: {"trajectory": 7, ...}.
std::string groupCodecsText(const EncodeSettings& settings, const std::vector<GroupCodecCount>& counts);
std::string groupCodecsJson(const std::vector<GroupCodecCount>& counts);

// Makes SIGINT, SIGTERM and SIGHUP remove the temporaries of the outputs being written
// (core/temp_registry.h), then end the process as the signal would have, so that the caller
// still sees "killed by the signal". A signal ignored at start (nohup) stays ignored.
void removeTemporariesOnSignals();

int runEncode(const std::vector<std::string>& argv);
int runDecode(const std::vector<std::string>& argv);
int runInfo(const std::vector<std::string>& argv);
int runTest(const std::vector<std::string>& argv);
int runCompare(const std::vector<std::string>& argv);
int runBench(const std::vector<std::string>& argv);
int runJoin(const std::vector<std::string>& argv);

}  // namespace animc::cli
