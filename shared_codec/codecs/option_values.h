// SPDX-License-Identifier: Apache-2.0
// Named option values as text (a command line's "--name value" pairs), which a codec's
// registry entry reads its options from, so a front end needs no code per codec option.
#pragma once
#include <string>

#include "core/status.h"

namespace animc {

class OptionValues {
 public:
  virtual ~OptionValues() = default;
  virtual bool has(const std::string& name) const = 0;
  // The value given for `name`, or fallback when it was not given (a switch's value is "1").
  virtual std::string get(const std::string& name, const std::string& fallback = "") const = 0;

  // The value as a number or an integer; an error naming the option when it is not one.
  Result<double> number(const std::string& name, double fallback) const;
  Result<long long> integer(const std::string& name, long long fallback) const;
};

}  // namespace animc
