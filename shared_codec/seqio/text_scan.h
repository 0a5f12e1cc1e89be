// SPDX-License-Identifier: Apache-2.0
// Locale-independent number parsing and printing for the ASCII formats: a host application
// (MeshLab sets the user's locale) must not turn "1.5" into 1 the way strtod would under a
// comma locale.
#pragma once
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>

namespace animc {

inline bool isSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v';
}

inline bool parseDouble(std::string_view text, double* value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);  // from_chars rejects '+'
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, *value);
  return ec == std::errc() && ptr == end && !text.empty();
}

inline bool parseUint64(std::string_view text, uint64_t* value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, *value);
  return ec == std::errc() && ptr == end && !text.empty();
}

inline bool parseInt64(std::string_view text, int64_t* value) {
  if (!text.empty() && text[0] == '+') text.remove_prefix(1);
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, *value);
  return ec == std::errc() && ptr == end && !text.empty();
}

// 9 significant digits: what reads back as the same float.
inline void appendFloat(std::string& out, float value) {
  char text[32];
  auto result = std::to_chars(text, text + sizeof(text), value, std::chars_format::general, 9);
  out.append(text, result.ptr);
}

inline void appendUnsigned(std::string& out, uint64_t value) {
  char text[24];
  auto result = std::to_chars(text, text + sizeof(text), value);
  out.append(text, result.ptr);
}

// Walks whitespace-separated tokens of a character range.
class TokenCursor {
 public:
  TokenCursor(const char* begin, const char* end) : pos_(begin), end_(end) {}
  bool next(std::string_view* token) {
    while (pos_ < end_ && isSpace(*pos_)) ++pos_;
    if (pos_ == end_) return false;
    const char* start = pos_;
    while (pos_ < end_ && !isSpace(*pos_)) ++pos_;
    *token = std::string_view(start, size_t(pos_ - start));
    return true;
  }
  const char* position() const { return pos_; }

 private:
  const char* pos_;
  const char* end_;
};

}  // namespace animc
