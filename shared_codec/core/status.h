// SPDX-License-Identifier: Apache-2.0
// Error handling for the codec library: nothing in shared_codec throws; every fallible call
// returns a Status or a Result<T> whose message names the file, field or byte offset at fault.
#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace animc {

// Stable values: animc maps them to exit codes (docs/format.md lists them).
enum class StatusCode : int {
  kOk = 0,
  kInvalidArgument = 2,  // the caller asked for something impossible (bad option value)
  kIoError = 3,          // the operating system refused a read, write or rename
  kBadInput = 4,         // an input sequence is unusable (NaN, differing counts, bad faces)
  kTruncated = 5,        // a container ends before a field it announces
  kCorrupt = 6,          // a container field or checksum is wrong
  kUnsupported = 7,      // a format version, codec id or codec profile this build does not read
  kLimitExceeded = 8,    // a count or size above the decoder's ceilings (DecoderLimits, container/format.h)
  kCancelled = 9,        // the progress callback asked to stop
};

const char* statusCodeName(StatusCode code);

class [[nodiscard]] Status {
 public:
  Status() = default;
  Status(StatusCode code, std::string message) : code_(code), message_(std::move(message)) {}

  static Status okStatus() { return Status(); }
  bool ok() const { return code_ == StatusCode::kOk; }
  StatusCode code() const { return code_; }
  const std::string& message() const { return message_; }
  // Prefixes context ("frames/12.ply: ") so messages read outermost first.
  Status withContext(const std::string& context) const {
    return ok() ? *this : Status(code_, context + ": " + message_);
  }

 private:
  StatusCode code_ = StatusCode::kOk;
  std::string message_;
};

inline Status invalidArgument(std::string m) { return {StatusCode::kInvalidArgument, std::move(m)}; }
inline Status ioError(std::string m) { return {StatusCode::kIoError, std::move(m)}; }
inline Status badInput(std::string m) { return {StatusCode::kBadInput, std::move(m)}; }
inline Status truncated(std::string m) { return {StatusCode::kTruncated, std::move(m)}; }
inline Status corrupt(std::string m) { return {StatusCode::kCorrupt, std::move(m)}; }
inline Status unsupported(std::string m) { return {StatusCode::kUnsupported, std::move(m)}; }
inline Status limitExceeded(std::string m) { return {StatusCode::kLimitExceeded, std::move(m)}; }
inline Status cancelled() { return {StatusCode::kCancelled, "cancelled"}; }

// A value or the Status explaining why there is none (C++17 has no std::expected).
template <class T>
class [[nodiscard]] Result {
 public:
  Result(T value) : v_(std::move(value)) {}  // NOLINT: implicit by design, like StatusOr
  Result(Status status) : v_(std::move(status)) {}  // NOLINT
  bool ok() const { return v_.index() == 0; }
  const Status& status() const {
    static const Status kOkStatus;
    return ok() ? kOkStatus : std::get<1>(v_);
  }
  T& value() & { return std::get<0>(v_); }
  const T& value() const& { return std::get<0>(v_); }
  T&& value() && { return std::get<0>(std::move(v_)); }

 private:
  std::variant<T, Status> v_;
};

}  // namespace animc

#define ANIMC_CONCAT_INNER(a, b) a##b
#define ANIMC_CONCAT(a, b) ANIMC_CONCAT_INNER(a, b)

#define ANIMC_RETURN_IF_ERROR(expr)            \
  do {                                         \
    ::animc::Status animc_status_ = (expr);    \
    if (!animc_status_.ok()) return animc_status_; \
  } while (0)

#define ANIMC_ASSIGN_OR_RETURN_IMPL(tmp, decl, expr) \
  auto tmp = (expr);                                 \
  if (!tmp.ok()) return tmp.status();                \
  decl = std::move(tmp).value()

#define ANIMC_ASSIGN_OR_RETURN(decl, expr) \
  ANIMC_ASSIGN_OR_RETURN_IMPL(ANIMC_CONCAT(animc_result_, __LINE__), decl, expr)
