// The one way library code reports a violated option rule (Ceres' OPTION_GE family): the
// error carries owner, field, value and rule as members, so readers that position it in a file
// (ValidateOptions) or name a flag for it (the CLI) never search its message.
#ifndef SYSID_CORE_OPTION_RULE_HPP_
#define SYSID_CORE_OPTION_RULE_HPP_

#include <fmt/format.h>

#include <string>
#include <utility>

#include "sysid/error.hpp"

namespace sysid::internal {

/// Throws OptionsError(owner, field, value, rule), the value formatted with fmt's "{}" (the
/// shortest text that reads back as the same number; strings as they are).
///   FailOption("PlateauOptions", "window_fraction", 1.5, "0 < window_fraction <= 1");
/// reads "PlateauOptions::window_fraction = 1.5. Violated constraint: 0 < window_fraction <= 1".
template <class Value>
[[noreturn]] void FailOption(std::string owner, std::string field, const Value& value,
                             std::string rule) {
  throw OptionsError(std::move(owner), std::move(field), fmt::format("{}", value), std::move(rule));
}

/// FailOption unless `ok`.
template <class Value>
void RequireOption(bool ok, std::string owner, std::string field, const Value& value,
                   std::string rule) {
  if (!ok) FailOption(std::move(owner), std::move(field), value, std::move(rule));
}

}  // namespace sysid::internal

#endif  // SYSID_CORE_OPTION_RULE_HPP_
