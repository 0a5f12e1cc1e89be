// SPDX-License-Identifier: Apache-2.0
#include "seqio/byte_input.h"

#include <lzma.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>

#include "core/large_memory.h"

namespace animc {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

Result<FilePtr> openForReading(const std::string& path) {
  FilePtr file(std::fopen(path.c_str(), "rb"));
  if (!file) return ioError(path + ": cannot open: " + std::strerror(errno));
  return file;
}

// Size from seeking to the end; -1 when the file is not seekable (a pipe).
int64_t fileSize(std::FILE* file) {
  if (std::fseek(file, 0, SEEK_END) != 0) return -1;
#ifdef _WIN32
  int64_t size = _ftelli64(file);
#else
  int64_t size = ftello(file);
#endif
  std::rewind(file);
  return size;
}

class PlainInput : public ByteInput {
 public:
  PlainInput(std::string path, FilePtr file)
      : path_(std::move(path)), file_(std::move(file)), size_(fileSize(file_.get())) {}

  Result<size_t> read(void* dst, size_t size) override {
    size_t got = std::fread(dst, 1, size, file_.get());
    if (got < size && std::ferror(file_.get()))
      return ioError(path_ + ": read failed: " + std::strerror(errno));
    return got;
  }
  int64_t size() const override { return size_; }

 private:
  std::string path_;
  FilePtr file_;
  int64_t size_;
};

// Streams the decompressed bytes of an .xz file through a fixed input buffer.
class XzInput : public ByteInput {
 public:
  XzInput(std::string path, FilePtr file) : path_(std::move(path)), file_(std::move(file)) {}
  ~XzInput() override { lzma_end(&stream_); }

  Status init() {
    // LZMA_CONCATENATED: "xz -c a b > c" produces several streams that belong together.
    lzma_ret rc = lzma_stream_decoder(&stream_, UINT64_MAX, LZMA_CONCATENATED);
    if (rc != LZMA_OK)
      return ioError(path_ + ": cannot start the xz decoder (code " + std::to_string(int(rc)) +
                     ")");
    return Status();
  }

  Result<size_t> read(void* dst, size_t size) override {
    stream_.next_out = static_cast<uint8_t*>(dst);
    stream_.avail_out = size;
    while (stream_.avail_out > 0 && !finished_) ANIMC_RETURN_IF_ERROR(step());
    return size - stream_.avail_out;
  }
  int64_t size() const override { return -1; }

 private:
  Status refill() {
    size_t got = std::fread(buffer_, 1, sizeof(buffer_), file_.get());
    if (got == 0 && std::ferror(file_.get()))
      return ioError(path_ + ": read failed: " + std::strerror(errno));
    stream_.next_in = buffer_;
    stream_.avail_in = got;
    at_eof_ = got == 0;
    return Status();
  }

  Status step() {
    if (stream_.avail_in == 0 && !at_eof_) ANIMC_RETURN_IF_ERROR(refill());
    lzma_ret rc = lzma_code(&stream_, at_eof_ ? LZMA_FINISH : LZMA_RUN);
    if (rc == LZMA_STREAM_END) {
      finished_ = true;
      return Status();
    }
    if (rc == LZMA_OK) return Status();
    if (rc == LZMA_BUF_ERROR && at_eof_)
      return truncated(path_ + ": compressed data ends early (xz stream incomplete)");
    if (rc == LZMA_FORMAT_ERROR) return corrupt(path_ + ": not an xz file (bad magic)");
    if (rc == LZMA_MEM_ERROR) return limitExceeded(path_ + ": out of memory in the xz decoder");
    return corrupt(path_ + ": xz data is corrupt (liblzma code " + std::to_string(int(rc)) + ")");
  }

  std::string path_;
  FilePtr file_;
  lzma_stream stream_ = LZMA_STREAM_INIT;
  uint8_t buffer_[1 << 16];
  bool at_eof_ = false;
  bool finished_ = false;
};

}  // namespace

bool endsWithNoCase(const std::string& name, const std::string& suffix) {
  if (suffix.size() > name.size()) return false;
  size_t offset = name.size() - suffix.size();
  for (size_t i = 0; i < suffix.size(); ++i) {
    unsigned char a = static_cast<unsigned char>(name[offset + i]);
    unsigned char b = static_cast<unsigned char>(suffix[i]);
    if (std::tolower(a) != std::tolower(b)) return false;
  }
  return true;
}

Result<std::unique_ptr<ByteInput>> openByteInput(const std::string& path) {
  ANIMC_ASSIGN_OR_RETURN(FilePtr file, openForReading(path));
  try {
    if (!endsWithNoCase(path, ".xz"))
      return std::unique_ptr<ByteInput>(new PlainInput(path, std::move(file)));
    auto xz = std::make_unique<XzInput>(path, std::move(file));
    ANIMC_RETURN_IF_ERROR(xz->init());
    return std::unique_ptr<ByteInput>(std::move(xz));
  } catch (const std::bad_alloc&) {
    return limitExceeded(path + ": out of memory opening the file");
  }
}

Result<std::vector<uint8_t>> readWholeFile(const std::string& path) {
  ANIMC_ASSIGN_OR_RETURN(FilePtr file, openForReading(path));
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return ioError(path + ": not a regular file");
  int64_t size = fileSize(file.get());
  if (size < 0) return ioError(path + ": cannot determine the file size");
  std::vector<uint8_t> bytes;
  try {
    resizeWithHugePages(bytes, static_cast<size_t>(size));
  } catch (const std::bad_alloc&) {
    return limitExceeded(path + ": file too large to load (" + std::to_string(size) + " bytes)");
  }
  if (std::fread(bytes.data(), 1, bytes.size(), file.get()) != bytes.size())
    return ioError(path + ": read failed: " + std::strerror(errno));
  return bytes;
}

}  // namespace animc
