// Private: how the stage's Validate functions (the shared settings' and each plant's) report a
// violated rule, as "StageParameters::FIELD = VALUE. Violated constraint: RULE" with FIELD the
// stage file's path of the value.
#ifndef SYSID_SRC_STAGE_STAGE_RULES_HPP_
#define SYSID_SRC_STAGE_STAGE_RULES_HPP_

#include <cmath>
#include <sstream>
#include <string>

#include "core/option_rule.hpp"

namespace sysid::internal {

/// `v` with 17 significant digits, for the bounds a rule quotes.
inline std::string StageFmt(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

inline void StageRequire(bool ok, const std::string& field, double value, const std::string& rule) {
  if (!ok) FailOption("StageParameters", field, value, rule);
}

inline void StageRequireFinite(const std::string& field, double value) {
  StageRequire(std::isfinite(value), field, value, field + " is finite");
}

}  // namespace sysid::internal

#endif  // SYSID_SRC_STAGE_STAGE_RULES_HPP_
