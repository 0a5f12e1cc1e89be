// SPDX-License-Identifier: Apache-2.0
#include "codecs/option_values.h"

#include <cstdlib>

namespace animc {

Result<double> OptionValues::number(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  const std::string s = get(name);
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0') return invalidArgument("--" + name + ": not a number: " + s);
  return v;
}

Result<long long> OptionValues::integer(const std::string& name, long long fallback) const {
  if (!has(name)) return fallback;
  const std::string s = get(name);
  char* end = nullptr;
  const long long v = std::strtoll(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0') return invalidArgument("--" + name + ": not an integer: " + s);
  return v;
}

}  // namespace animc
