// SPDX-License-Identifier: Apache-2.0
// Builds the flat JSON objects every --json output of the project prints. Numbers are written
// locale-independently (a host such as MeshLab may have switched LC_NUMERIC to a decimal
// comma), and anything JSON cannot represent (inf, NaN) becomes null.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace animc {

// Significant digits of every JSON number: %.10g is far below float noise for our figures.
constexpr int kJsonDigits = 10;

// v with `digits` significant digits, as printf("%.*g") would in the C locale;
// non-finite values read "inf", "-inf" or "nan" (for text output; JSON uses null instead).
std::string formatDouble(double v, int digits = kJsonDigits);

// Appends s as a quoted JSON string. Quotes, backslashes and control characters are escaped;
// bytes that are not valid UTF-8 (say, from a file name) become U+FFFD so the output stays
// valid JSON.
void appendJsonString(std::string_view s, std::string& out);

// Appends v as a JSON number, or null when v is not finite.
void appendJsonNumber(double v, std::string& out);

// One flat JSON object, members in insertion order. Keys are not checked for duplicates.
//   JsonObject o; o.add("ratio", 20.5).add("codec", "affine-octree"); std::string s = o.str();
class JsonObject {
 public:
  JsonObject& add(std::string_view key, double value);
  JsonObject& add(std::string_view key, bool value);
  JsonObject& add(std::string_view key, std::string_view value);
  // Without this overload a string literal would pick add(key, bool). nullptr writes null.
  JsonObject& add(std::string_view key, const char* value);
  // Integers are written exactly (byte counts can exceed the 10 digits of a double member).
  template <class T, std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  JsonObject& add(std::string_view key, T value) {
    if constexpr (std::is_signed_v<T>) return addInteger(key, static_cast<int64_t>(value));
    else return addUnsigned(key, static_cast<uint64_t>(value));
  }
  // An array of numbers; non-finite elements become null.
  JsonObject& add(std::string_view key, const std::vector<double>& values);
  JsonObject& addNull(std::string_view key);
  // `json` must already be one valid JSON value (a nested object from another writer);
  // an empty string is written as null rather than producing broken output.
  JsonObject& addRaw(std::string_view key, std::string_view json);

  bool empty() const { return body_.empty(); }
  // The object, "{...}", without a trailing newline.
  std::string str() const;
  // Appends str() to out without the extra copy.
  void appendTo(std::string& out) const;

 private:
  JsonObject& addInteger(std::string_view key, int64_t value);
  JsonObject& addUnsigned(std::string_view key, uint64_t value);
  void appendKey(std::string_view key);

  std::string body_;  // the members, comma separated, without the braces
};

}  // namespace animc
