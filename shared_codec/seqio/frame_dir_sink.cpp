// SPDX-License-Identifier: Apache-2.0
#include "seqio/frame_dir_sink.h"

#include <cstdio>
#include <filesystem>
#include <vector>

#include "seqio/off_format.h"
#include "seqio/ply_writer.h"
#include "seqio/text_scan.h"

namespace animc {
namespace fs = std::filesystem;
namespace {

const char* extension(SequenceFormat format) {
  return format == SequenceFormat::kOff ? ".off" : ".ply";
}

// The frame number of a name this sink would write, or -1.
int64_t frameNumber(const std::string& name, SequenceFormat format) {
  const std::string prefix = "frame_", suffix = extension(format);
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return -1;
  std::string digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  uint64_t number;
  if (digits.find_first_not_of("0123456789") != std::string::npos ||
      !parseUint64(digits, &number) || number > uint64_t(INT64_MAX))
    return -1;
  return int64_t(number);
}

class FrameDirSink : public FrameSink {
 public:
  FrameDirSink(std::string dir, SequenceFormat format, Topology topology, int64_t frame_count)
      : dir_(std::move(dir)),
        format_(format),
        topology_(std::move(topology)),
        frame_count_(frame_count) {}

  ~FrameDirSink() override {
    if (finished_) return;
    std::error_code ec;
    for (const std::string& path : written_) fs::remove(path, ec);
    if (created_dir_) fs::remove(dir_, ec);  // fails, harmlessly, if someone else added files
  }

  Status open() {
    std::error_code ec;
    if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
      return ioError(dir_ + ": exists and is not a directory");
    created_dir_ = fs::create_directories(dir_, ec);
    if (ec) return ioError(dir_ + ": cannot create the directory: " + ec.message());
    return Status();
  }

  Status write(const float* xyz) override {
    if (int64_t(written_.size()) == frame_count_)
      return invalidArgument(dir_ + ": more frames written than the " +
                             std::to_string(frame_count_) + " announced");
    std::string path = (fs::path(dir_) / frameFileName(int64_t(written_.size()), format_)).string();
    ANIMC_RETURN_IF_ERROR(format_ == SequenceFormat::kOff ? writeOffFile(path, topology_, xyz)
                                                          : writePlyFile(path, topology_, xyz));
    written_.push_back(std::move(path));
    return Status();
  }

  Status finish() override {
    if (int64_t(written_.size()) != frame_count_)
      return invalidArgument(dir_ + ": " + std::to_string(written_.size()) +
                             " frames written but " + std::to_string(frame_count_) + " announced");
    ANIMC_RETURN_IF_ERROR(removeStaleFrames());
    finished_ = true;
    return Status();
  }

 private:
  // Frame files of an earlier run: higher numbers, or the other extension. A reader of the
  // directory must not mix them into this sequence.
  bool isStale(const std::string& name) const {
    SequenceFormat other =
        format_ == SequenceFormat::kOff ? SequenceFormat::kPly : SequenceFormat::kOff;
    return frameNumber(name, format_) >= frame_count_ || frameNumber(name, other) >= 0;
  }

  Status removeStaleFrames() {
    std::error_code ec;
    std::vector<fs::path> stale;
    for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec))
      if (isStale(it->path().filename().string())) stale.push_back(it->path());
    if (ec) return ioError(dir_ + ": cannot list the directory: " + ec.message());
    for (const fs::path& path : stale) {
      if (!fs::remove(path, ec) && ec)
        return ioError(path.string() + ": cannot remove a stale frame: " + ec.message());
    }
    return Status();
  }

  std::string dir_;
  SequenceFormat format_;
  Topology topology_;
  int64_t frame_count_;
  std::vector<std::string> written_;
  bool created_dir_ = false;
  bool finished_ = false;
};

}  // namespace

std::string frameFileName(int64_t index, SequenceFormat format) {
  char name[48];
  std::snprintf(name, sizeof(name), "frame_%05lld%s", static_cast<long long>(index),
                extension(format));
  return name;
}

Result<std::unique_ptr<FrameSink>> createFrameDirSink(const std::string& dir, SequenceFormat format,
                                                      const Topology& topology,
                                                      int64_t frame_count) {
  auto sink = std::make_unique<FrameDirSink>(dir, format, topology, frame_count);
  ANIMC_RETURN_IF_ERROR(sink->open());
  return std::unique_ptr<FrameSink>(std::move(sink));
}

}  // namespace animc
