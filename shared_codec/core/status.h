// SPDX-License-Identifier: Apache-2.0
// Error handling for the codec library: nothing in shared_codec throws; every fallible call
// returns a Status or a Result<T> whose message names the file, field or byte offset at fault.
#pragma once
#include <string>
#include <utility>

#include "animc/animc.h"

namespace animc {

inline Status invalidArgument(std::string m) { return {StatusCode::kInvalidArgument, std::move(m)}; }
inline Status ioError(std::string m) { return {StatusCode::kIoError, std::move(m)}; }
inline Status badInput(std::string m) { return {StatusCode::kBadInput, std::move(m)}; }
inline Status truncated(std::string m) { return {StatusCode::kTruncated, std::move(m)}; }
inline Status corrupt(std::string m) { return {StatusCode::kCorrupt, std::move(m)}; }
inline Status unsupported(std::string m) { return {StatusCode::kUnsupported, std::move(m)}; }
inline Status limitExceeded(std::string m) { return {StatusCode::kLimitExceeded, std::move(m)}; }
inline Status cancelled() { return {StatusCode::kCancelled, "cancelled"}; }

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
