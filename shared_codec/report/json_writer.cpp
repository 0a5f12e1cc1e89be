// SPDX-License-Identifier: Apache-2.0
#include "report/json_writer.h"

#include <charconv>
#include <cmath>

namespace animc {
namespace {

constexpr char kHexDigits[] = "0123456789abcdef";
constexpr std::string_view kReplacementChar = "\\ufffd";

bool inRange(unsigned char c, unsigned char lo, unsigned char hi) { return c >= lo && c <= hi; }

// Length of the well-formed UTF-8 sequence starting at s[i] (a non-ASCII byte), or 0.
// The first continuation byte's range excludes overlong forms, surrogates and > U+10FFFF.
size_t utf8SequenceLength(std::string_view s, size_t i) {
  const auto lead = static_cast<unsigned char>(s[i]);
  size_t length = 0;
  unsigned char lo = 0x80, hi = 0xBF;
  if (inRange(lead, 0xC2, 0xDF)) {
    length = 2;
  } else if (inRange(lead, 0xE0, 0xEF)) {
    length = 3;
    if (lead == 0xE0) lo = 0xA0;
    if (lead == 0xED) hi = 0x9F;
  } else if (inRange(lead, 0xF0, 0xF4)) {
    length = 4;
    if (lead == 0xF0) lo = 0x90;
    if (lead == 0xF4) hi = 0x8F;
  } else {
    return 0;
  }
  if (s.size() - i < length) return 0;
  if (!inRange(static_cast<unsigned char>(s[i + 1]), lo, hi)) return 0;
  for (size_t k = 2; k < length; ++k) {
    if (!inRange(static_cast<unsigned char>(s[i + k]), 0x80, 0xBF)) return 0;
  }
  return length;
}

void appendEscapedAscii(unsigned char c, std::string& out) {
  switch (c) {
    case '"': out += "\\\""; return;
    case '\\': out += "\\\\"; return;
    case '\b': out += "\\b"; return;
    case '\f': out += "\\f"; return;
    case '\n': out += "\\n"; return;
    case '\r': out += "\\r"; return;
    case '\t': out += "\\t"; return;
    default: break;
  }
  if (c < 0x20) {
    out += "\\u00";
    out += kHexDigits[c >> 4];
    out += kHexDigits[c & 0xF];
  } else {
    out += static_cast<char>(c);
  }
}

template <class T>
void appendInteger(T value, std::string& out) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

}  // namespace

std::string formatDouble(double v, int digits) {
  if (std::isnan(v)) return "nan";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  // to_chars, unlike snprintf, ignores the C locale: a decimal comma would corrupt JSON.
  char buffer[64];
  const auto result =
      std::to_chars(buffer, buffer + sizeof(buffer), v, std::chars_format::general, digits);
  return std::string(buffer, result.ptr);
}

void appendJsonString(std::string_view s, std::string& out) {
  out += '"';
  size_t i = 0;
  while (i < s.size()) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      appendEscapedAscii(c, out);
      ++i;
      continue;
    }
    const size_t length = utf8SequenceLength(s, i);
    if (length == 0) {
      out += kReplacementChar;
      ++i;
    } else {
      out.append(s.data() + i, length);
      i += length;
    }
  }
  out += '"';
}

void appendJsonNumber(double v, std::string& out) {
  if (std::isfinite(v)) {
    out += formatDouble(v);
  } else {
    out += "null";
  }
}

JsonObject& JsonObject::add(std::string_view key, double value) {
  appendKey(key);
  appendJsonNumber(value, body_);
  return *this;
}

JsonObject& JsonObject::add(std::string_view key, bool value) {
  appendKey(key);
  body_ += value ? "true" : "false";
  return *this;
}

JsonObject& JsonObject::add(std::string_view key, std::string_view value) {
  appendKey(key);
  appendJsonString(value, body_);
  return *this;
}

JsonObject& JsonObject::add(std::string_view key, const char* value) {
  if (value == nullptr) return addNull(key);
  return add(key, std::string_view(value));
}

JsonObject& JsonObject::add(std::string_view key, const std::vector<double>& values) {
  appendKey(key);
  body_ += '[';
  for (size_t i = 0; i < values.size(); ++i) {
    if (i > 0) body_ += ',';
    appendJsonNumber(values[i], body_);
  }
  body_ += ']';
  return *this;
}

JsonObject& JsonObject::addNull(std::string_view key) {
  appendKey(key);
  body_ += "null";
  return *this;
}

JsonObject& JsonObject::addRaw(std::string_view key, std::string_view json) {
  if (json.empty()) return addNull(key);
  appendKey(key);
  body_ += json;
  return *this;
}

JsonObject& JsonObject::addInteger(std::string_view key, int64_t value) {
  appendKey(key);
  appendInteger(value, body_);
  return *this;
}

JsonObject& JsonObject::addUnsigned(std::string_view key, uint64_t value) {
  appendKey(key);
  appendInteger(value, body_);
  return *this;
}

std::string JsonObject::str() const {
  std::string out;
  appendTo(out);
  return out;
}

void JsonObject::appendTo(std::string& out) const {
  out += '{';
  out += body_;
  out += '}';
}

void JsonObject::appendKey(std::string_view key) {
  if (!body_.empty()) body_ += ',';
  appendJsonString(key, body_);
  body_ += ':';
}

}  // namespace animc
