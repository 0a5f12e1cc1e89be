// SPDX-License-Identifier: Apache-2.0
#include "io/byte_source.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

namespace animc {
namespace {

std::string at(uint64_t offset) { return " at byte " + std::to_string(offset); }

Status checkRange(uint64_t offset, size_t size, uint64_t total) {
  if (offset > total || size > total - offset) return truncated("read" + at(offset) + ": the stream ends early");
  return Status();
}

class FileSource final : public ByteSource {
 public:
  explicit FileSource(std::FILE* file, uint64_t size) : file_(file), size_(size) {}
  ~FileSource() override { std::fclose(file_); }
  uint64_t size() const override { return size_; }
  // Frame records are read a few bytes at a time (a length, then its payload), which would be a
  // seek and a read of the system each, for every frame a random access walks through: small
  // reads come from a window of the file read at once.
  Status readAt(uint64_t offset, void* out, size_t size) override {
    ANIMC_RETURN_IF_ERROR(checkRange(offset, size, size_));
    if (size == 0) return Status();
    if (size > kWindowBytes / 2) return read(offset, out, size);
    if (offset < window_offset_ || offset + size > window_offset_ + window_.size()) {
      window_.resize(size_t(std::min<uint64_t>(kWindowBytes, size_ - offset)));
      window_offset_ = offset;
      const Status s = read(offset, window_.data(), window_.size());
      if (!s.ok()) {
        window_.clear();
        return s;
      }
    }
    std::memcpy(out, window_.data() + (offset - window_offset_), size);
    return Status();
  }

 private:
  static constexpr size_t kWindowBytes = size_t(1) << 16;

  Status read(uint64_t offset, void* out, size_t size) {
    errno = 0;
    if (fseeko(file_, off_t(offset), SEEK_SET) != 0 || std::fread(out, 1, size, file_) != size) {
      const std::string why = errno ? std::string(": ") + std::strerror(errno) : "";
      return ioError("read failed" + at(offset) + why);
    }
    return Status();
  }

  std::FILE* file_;
  uint64_t size_;
  std::vector<uint8_t> window_;  // bytes [window_offset_, window_offset_ + size) of the file
  uint64_t window_offset_ = 0;
};

class MemorySource final : public ByteSource {
 public:
  MemorySource(const void* data, size_t size) : data_(static_cast<const uint8_t*>(data)), size_(size) {}
  uint64_t size() const override { return size_; }
  Status readAt(uint64_t offset, void* out, size_t size) override {
    ANIMC_RETURN_IF_ERROR(checkRange(offset, size, size_));
    if (size > 0) std::memcpy(out, data_ + offset, size);
    return Status();
  }

 private:
  const uint8_t* data_;
  uint64_t size_;
};

}  // namespace

Result<std::unique_ptr<ByteSource>> openFileSource(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return ioError(path + ": cannot open: " + std::strerror(errno));
  // fopen() opens a folder too; reading it would fail with no useful reason.
  struct stat st;
  if (fstat(fileno(file), &st) == 0 && S_ISDIR(st.st_mode)) {
    std::fclose(file);
    return ioError(path + ": is a directory, not an .ams file");
  }
  if (fseeko(file, 0, SEEK_END) != 0) {
    const std::string why = std::strerror(errno);
    std::fclose(file);
    return ioError(path + ": cannot seek (an .ams file is read out of order): " + why);
  }
  const uint64_t size = uint64_t(ftello(file));
  return std::unique_ptr<ByteSource>(new FileSource(file, size));
}

std::unique_ptr<ByteSource> memorySource(const void* data, size_t size) {
  return std::make_unique<MemorySource>(data, size);
}

}  // namespace animc
