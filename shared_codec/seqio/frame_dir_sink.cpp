// SPDX-License-Identifier: Apache-2.0
#include "seqio/frame_dir_sink.h"

#include <fcntl.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <vector>

#include "core/atomic_file.h"
#include "core/stale_temporaries.h"
#include "core/temp_registry.h"
#include "seqio/sequence_formats.h"

namespace animc {
namespace fs = std::filesystem;
namespace {

bool isEmptyDirectory(const std::string& dir) {
  std::error_code ec;
  return fs::is_empty(dir, ec) && !ec;
}

// Puts the finished `temp` folder at `dir`, whose old content (if any) is then removed. With
// renameat2(RENAME_EXCHANGE) readers of `dir` see the old frames or the new ones, never a mix
// and never no folder; where the kernel or file system lacks it, the old folder is first
// renamed aside.
Status swapIntoPlace(const std::string& temp, const std::string& dir) {
  std::error_code ec;
  if (!fs::exists(dir, ec) || isEmptyDirectory(dir)) {
    fs::remove(dir, ec);
    if (std::rename(temp.c_str(), dir.c_str()) != 0)
      return ioError(dir + ": cannot move the decoded frames into place: " + std::strerror(errno));
    return Status();
  }
  std::string old = temp;
  if (renameat2(AT_FDCWD, temp.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) != 0) {
    // Not registered for signal handlers (core/temp_registry.h), and named so that no later
    // run removes it as stale (core/stale_temporaries.h): a run killed between these renames
    // leaves the old frames under this name rather than deleting them.
    old = temporaryPathBeside(dir) + ".old";
    if (std::rename(dir.c_str(), old.c_str()) != 0)
      return ioError(dir + ": cannot move the old frames aside: " + std::strerror(errno));
    if (std::rename(temp.c_str(), dir.c_str()) != 0) {
      const std::string why = std::strerror(errno);
      std::rename(old.c_str(), dir.c_str());
      return ioError(dir + ": cannot move the decoded frames into place: " + why);
    }
  }
  fs::remove_all(old, ec);
  if (ec) return ioError(old + ": the old frames were replaced but not removed: " + ec.message());
  return Status();
}

class FrameDirSink : public FrameSink {
 public:
  FrameDirSink(std::string dir, SequenceFormat format, Topology topology, int64_t frame_count)
      : dir_(std::move(dir)),
        format_(format),
        topology_(std::move(topology)),
        frame_count_(frame_count) {}

  ~FrameDirSink() override {
    if (finished_ || !created_temp_) return;
    std::error_code ec;
    for (const std::string& path : written_) fs::remove(path, ec);
    fs::remove(temp_, ec);
    unregisterTemporary(temp_slot_);
  }

  Status open(ExistingOutput existing) {
    // A link to a folder stays a link: the folder it leads to is the one replaced.
    ANIMC_ASSIGN_OR_RETURN(target_, replacedPath(dir_));
    temp_ = temporaryPathBeside(target_);
    removeStaleTemporaries(fs::path(temp_).parent_path().string());
    std::error_code ec;
    if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec))
      return ioError(dir_ + ": exists and is not a directory");
    if (existing == ExistingOutput::kRefuse && fs::exists(dir_, ec) && !isEmptyDirectory(dir_))
      return invalidArgument(dir_ + ": the folder is not empty; frames are written only into a new or "
                             "empty folder (--replace replaces the folder and everything in it)");
    // Errors name the folder the user asked for, not the temporary.
    const fs::path parent = fs::path(temp_).parent_path();
    if (!parent.empty() && !fs::is_directory(parent, ec))
      return ioError(dir_ + ": no such directory " + parent.string());
    // Registered before it is created, so that a signal arriving in between still finds it.
    temp_slot_ = registerTemporary(temp_, TemporaryKind::kFolder);
    if (!fs::create_directory(temp_, ec)) {
      unregisterTemporary(temp_slot_);
      temp_slot_ = -1;
      return ioError(dir_ + ": cannot create a folder in " + (parent.empty() ? "." : parent.string()) +
                     ": " + (ec ? ec.message() : temp_ + " exists"));
    }
    created_temp_ = true;
    return Status();
  }

  Status write(const float* xyz) override {
    if (int64_t(written_.size()) == frame_count_)
      return invalidArgument(dir_ + ": more frames written than the " +
                             std::to_string(frame_count_) + " announced");
    std::string path = (fs::path(temp_) / frameFileName(int64_t(written_.size()), format_)).string();
    ANIMC_RETURN_IF_ERROR(formatSpec(format_).frame_file->write(path, topology_, xyz));
    written_.push_back(std::move(path));
    return Status();
  }

  Status finish() override {
    if (int64_t(written_.size()) != frame_count_)
      return invalidArgument(dir_ + ": " + std::to_string(written_.size()) +
                             " frames written but " + std::to_string(frame_count_) + " announced");
    Status placed = swapIntoPlace(temp_, target_);
    if (!placed.ok()) return dir_ == target_ ? placed : placed.withContext(dir_);
    // Only now: until the swap a signal must still find the folder. (After an exchange the
    // temporary's name holds the old frames, which were to be removed anyway.)
    unregisterTemporary(temp_slot_);
    finished_ = true;
    return Status();
  }

 private:
  std::string dir_;
  std::string target_;  // dir_, or the folder its symbolic links lead to
  std::string temp_;
  SequenceFormat format_;
  Topology topology_;
  int64_t frame_count_;
  std::vector<std::string> written_;
  bool created_temp_ = false;
  int temp_slot_ = -1;  // in the registry of temporaries
  bool finished_ = false;
};

}  // namespace

std::string frameFileName(int64_t index, SequenceFormat format) {
  char name[48];
  std::snprintf(name, sizeof(name), "frame_%05lld%s", static_cast<long long>(index), formatSpec(format).extension);
  return name;
}

Result<std::unique_ptr<FrameSink>> createFrameDirSink(const std::string& dir, SequenceFormat format,
                                                      const Topology& topology, int64_t frame_count,
                                                      ExistingOutput existing) {
  auto sink = std::make_unique<FrameDirSink>(dir, format, topology, frame_count);
  ANIMC_RETURN_IF_ERROR(sink->open(existing));
  return std::unique_ptr<FrameSink>(std::move(sink));
}

}  // namespace animc
