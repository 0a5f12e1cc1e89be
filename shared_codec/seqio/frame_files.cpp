// SPDX-License-Identifier: Apache-2.0
#include "seqio/frame_files.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <new>
#include <string_view>
#include <utility>

#include "seqio/byte_input.h"
#include "seqio/mesh_checks.h"
#include "seqio/sequence_io.h"

namespace animc {
namespace fs = std::filesystem;
namespace {

bool isDigit(char c) { return c >= '0' && c <= '9'; }

// Compares the digit runs starting at a[i] and b[j] by value; advances i and j past them.
int compareNumbers(const std::string& a, size_t& i, const std::string& b, size_t& j) {
  size_t a_end = i, b_end = j;
  while (a_end < a.size() && isDigit(a[a_end])) ++a_end;
  while (b_end < b.size() && isDigit(b[b_end])) ++b_end;
  size_t a_start = i, b_start = j;
  while (a_start + 1 < a_end && a[a_start] == '0') ++a_start;  // "007" == "7" by value
  while (b_start + 1 < b_end && b[b_start] == '0') ++b_start;
  int result = 0;
  if (a_end - a_start != b_end - b_start)
    result = a_end - a_start < b_end - b_start ? -1 : 1;
  else
    result = a.compare(a_start, a_end - a_start, b, b_start, b_end - b_start);
  i = a_end;
  j = b_end;
  return result;
}

bool isFrameFile(const std::string& name) { return frameFileFormatOf(name) != nullptr; }

std::string trim(std::string_view line) {
  const char* kSpace = " \t\r\n";
  size_t begin = line.find_first_not_of(kSpace);
  if (begin == std::string_view::npos) return std::string();
  return std::string(line.substr(begin, line.find_last_not_of(kSpace) + 1 - begin));
}

// "list.txt line 3: " before a listed frame's messages.
Status withListing(const Status& status, const FrameFile& frame) {
  return frame.listed_at.empty() ? status : status.withContext(frame.listed_at);
}

// Where triangle t of the frame file at `path` came from, in its format's words (the file is
// read again: this is for an error message only).
std::function<std::string(size_t)> triangleOrigin(const std::string& path) {
  const SequenceFormatSpec* spec = frameFileFormatOf(path);
  if (!spec || !spec->frame_file->triangle_origin) return nullptr;
  return [path, describe = spec->frame_file->triangle_origin](size_t t) {
    Result<std::vector<uint8_t>> bytes = readWholeFile(path);
    if (!bytes.ok()) return "triangle " + std::to_string(t);
    return describe(bytes.value().data(), bytes.value().size(), t);
  };
}

// Frame `index`'s mesh; `reference` (may be null) is the topology it must have,
// `reference_name` names that in messages, which name the file and the frame.
Result<Mesh> readFrame(const FrameFile& frame, size_t index, const Topology* reference,
                       const std::string& reference_name) {
  Result<Mesh> mesh = readMesh(frame.path);
  if (!mesh.ok()) return withListing(mesh.status(), frame);
  if (reference) {
    Status same = checkSameTopology(mesh.value().topology, *reference, reference_name, triangleOrigin(frame.path));
    if (!same.ok()) return withListing(same.withContext(frame.path + " (frame " + std::to_string(index) + ")"), frame);
  }
  return mesh;
}

// The parts of a numbered pattern's file name around its "%d" or "%0Nd".
struct FramePattern {
  std::string folder, prefix, suffix;
  size_t width = 0;  // N of "%0Nd"; 0 for "%d"
};

Result<FramePattern> parsePattern(const std::string& pattern) {
  const fs::path path(pattern);
  const std::string name = path.filename().string();
  const size_t percent = name.find('%');
  size_t end = percent + 1, width = 0;
  if (end < name.size() && name[end] == '0') {
    while (++end < name.size() && isDigit(name[end]) && width < 100) width = width * 10 + size_t(name[end] - '0');
    if (width == 0) end = name.size();  // "%0d": not a width
  }
  if (end >= name.size() || name[end] != 'd' || name.find('%', end) != std::string::npos)
    return invalidArgument(pattern + ": a numbered pattern has one %d or %0Nd in its file name " +
                           "(frame_%04d.obj), and nothing else with a '%'");
  FramePattern parsed{path.parent_path().string(), name.substr(0, percent), name.substr(end + 1), width};
  if (parsed.folder.empty()) parsed.folder = ".";
  if (!isFrameFile(parsed.suffix))
    return invalidArgument(pattern + ": the pattern's files must be " + frameFileExtensionList() + " frames");
  return parsed;
}

// The frame number in `name` if it is one of the pattern's files (as printf would have
// written it: zero-padded to the width, no other leading zero), else -1.
long long patternNumber(const FramePattern& pattern, const std::string& name) {
  if (name.size() <= pattern.prefix.size() + pattern.suffix.size() ||
      name.compare(0, pattern.prefix.size(), pattern.prefix) != 0 ||
      name.compare(name.size() - pattern.suffix.size(), pattern.suffix.size(), pattern.suffix) != 0)
    return -1;
  const std::string digits =
      name.substr(pattern.prefix.size(), name.size() - pattern.prefix.size() - pattern.suffix.size());
  if (digits.size() > 15 || !std::all_of(digits.begin(), digits.end(), isDigit)) return -1;
  const bool padded = digits.size() == std::max<size_t>(pattern.width, 1);
  if (!padded && (digits.size() < pattern.width || digits[0] == '0')) return -1;
  return std::stoll(digits);
}

class FrameFileSource : public FrameSource {
 public:
  FrameFileSource(std::vector<FrameFile> frames, Mesh first)
      : frames_(std::move(frames)),
        topology_(std::move(first.topology)),
        first_positions_(std::move(first.positions)) {}

  const Topology& topology() const override { return topology_; }
  int64_t frameCount() const override { return int64_t(frames_.size()); }
  std::string where() const override {
    return next_ < frames_.size() ? frames_[next_].path : frames_.back().path + " (end)";
  }

  Result<bool> next(std::vector<float>& xyz) override {
    if (next_ == frames_.size()) return false;
    if (next_ == 0) {
      xyz.swap(first_positions_);
      std::vector<float>().swap(first_positions_);
    } else {
      ANIMC_ASSIGN_OR_RETURN(Mesh mesh, readFrame(frames_[next_], next_, &topology_, "frame 0"));
      xyz.swap(mesh.positions);
    }
    ++next_;
    return true;
  }

 private:
  std::vector<FrameFile> frames_;
  Topology topology_;
  std::vector<float> first_positions_;  // frame 0, read when opening to learn the topology
  size_t next_ = 0;
};

}  // namespace

std::vector<FrameFile> unlistedFrameFiles(const std::vector<std::string>& paths) {
  std::vector<FrameFile> frames;
  for (const std::string& path : paths) frames.push_back({path, ""});
  return frames;
}

bool naturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (isDigit(a[i]) && isDigit(b[j])) {
      int order = compareNumbers(a, i, b, j);
      if (order != 0) return order < 0;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  if (i < a.size() || j < b.size()) return j < b.size();  // a is a prefix of b
  return a < b;  // equal by value ("7" and "007"): any fixed order
}

Result<std::vector<std::string>> listFrameDirectory(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.' || !isFrameFile(name)) continue;
    std::error_code type_ec;
    if (it->is_regular_file(type_ec)) names.push_back(name);
  }
  if (ec) return ioError(dir + ": cannot list the directory: " + ec.message());
  if (names.empty()) return badInput(dir + ": no " + frameFileExtensionList() + " frames in the directory");
  std::sort(names.begin(), names.end(), naturalLess);
  std::vector<std::string> paths;
  for (const std::string& name : names) paths.push_back((fs::path(dir) / name).string());
  return paths;
}

bool isFramePattern(const std::string& path) {
  std::error_code ec;  // a file that exists is itself, whatever its name holds ("100%.ply")
  return fs::path(path).filename().string().find('%') != std::string::npos && !fs::exists(path, ec);
}

Result<std::vector<std::string>> listNumberedFrames(const std::string& pattern) {
  ANIMC_ASSIGN_OR_RETURN(FramePattern parsed, parsePattern(pattern));
  std::vector<std::pair<long long, std::string>> numbered;
  std::error_code ec;
  for (fs::directory_iterator it(parsed.folder, ec), end; !ec && it != end; it.increment(ec)) {
    const long long number = patternNumber(parsed, it->path().filename().string());
    std::error_code type_ec;
    if (number >= 0 && it->is_regular_file(type_ec)) numbered.push_back({number, it->path().string()});
  }
  if (ec) return ioError(parsed.folder + ": cannot list the directory: " + ec.message());
  if (numbered.empty()) return badInput(pattern + ": no file matches the pattern");
  std::sort(numbered.begin(), numbered.end());
  std::vector<std::string> paths;
  for (size_t i = 0; i < numbered.size(); ++i) {
    if (numbered[i].first != numbered[0].first + (long long)i)
      return badInput(pattern + ": frame " + std::to_string(numbered[0].first + (long long)i) +
                      " is missing (the files run from " + std::to_string(numbered[0].first) + " to " +
                      std::to_string(numbered.back().first) + ")");
    paths.push_back(std::move(numbered[i].second));
  }
  return paths;
}

Result<std::vector<FrameFile>> readFrameList(const std::string& list_path) {
  ANIMC_ASSIGN_OR_RETURN(std::vector<uint8_t> bytes, readWholeFile(list_path));
  std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  fs::path base = fs::path(list_path).parent_path();
  std::vector<FrameFile> frames;
  size_t line_number = 0;
  for (size_t pos = 0; pos < text.size();) {
    size_t eol = std::min(text.find('\n', pos), text.size());
    std::string entry = trim(text.substr(pos, eol - pos));
    pos = eol + 1;
    ++line_number;
    if (entry.empty() || entry[0] == '#') continue;
    if (!isFrameFile(entry))
      return badInput(list_path + " line " + std::to_string(line_number) + ": '" + entry + "' is not a " +
                      frameFileExtensionList() + " file");
    // An absolute entry replaces base.
    frames.push_back({(base / entry).string(), list_path + " line " + std::to_string(line_number)});
  }
  if (frames.empty()) return badInput(list_path + ": the list names no frames");
  return frames;
}

Result<std::unique_ptr<FrameSource>> openFrameFiles(std::vector<FrameFile> frames,
                                                    const Topology* reference,
                                                    const std::string& reference_name) {
  if (frames.empty()) return badInput("no frames to read");
  ANIMC_ASSIGN_OR_RETURN(Mesh first, readFrame(frames[0], 0, reference, "the mesh " + reference_name));
  return std::unique_ptr<FrameSource>(new FrameFileSource(std::move(frames), std::move(first)));
}

}  // namespace animc
