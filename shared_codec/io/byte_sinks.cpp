// SPDX-License-Identifier: Apache-2.0
// The two ByteSinks of the public API (animc/animc.h): a file written atomically, and memory.
#include <algorithm>
#include <cstring>

#include "core/atomic_file.h"
#include "core/status.h"

namespace animc {
namespace {

class FileSink final : public ByteSink {
 public:
  Status open(const std::string& path) { return file_.open(path); }
  Status write(const void* data, size_t size) override { return file_.write(data, size); }
  Status seek(uint64_t offset) override { return file_.seek(offset); }
  uint64_t tell() const override { return file_.tell(); }
  Status commit() override { return file_.commit(); }

 private:
  AtomicFile file_;  // its destructor removes an uncommitted temporary
};

class MemorySink final : public ByteSink {
 public:
  explicit MemorySink(std::vector<uint8_t>* out) : out_(out) { out_->clear(); }
  ~MemorySink() override {
    if (!committed_) out_->clear();
  }
  Status write(const void* data, size_t size) override {
    if (size == 0) return Status();
    const uint64_t end = position_ + size;
    if (end > out_->size()) out_->resize(end);
    std::memcpy(out_->data() + position_, data, size);
    position_ = end;
    return Status();
  }
  Status seek(uint64_t offset) override {
    if (offset > out_->size()) return invalidArgument("seek past the end of the written bytes");
    position_ = offset;
    return Status();
  }
  uint64_t tell() const override { return position_; }
  Status commit() override {
    committed_ = true;
    return Status();
  }

 private:
  std::vector<uint8_t>* out_;
  uint64_t position_ = 0;
  bool committed_ = false;
};

}  // namespace

ByteSink::~ByteSink() = default;

Result<std::unique_ptr<ByteSink>> fileSink(const std::string& path) {
  auto sink = std::make_unique<FileSink>();
  ANIMC_RETURN_IF_ERROR(sink->open(path));
  return std::unique_ptr<ByteSink>(std::move(sink));
}

std::unique_ptr<ByteSink> memorySink(std::vector<uint8_t>* out) { return std::make_unique<MemorySink>(out); }

}  // namespace animc
