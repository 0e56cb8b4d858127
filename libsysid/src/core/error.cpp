#include "sysid/error.hpp"

#include <string>

namespace sysid::internal {

void ThrowInternal(const char* condition, const char* file, int line,
                   const std::string& detail) {
  std::string msg = std::string(file) + ":" + std::to_string(line) +
                    ": internal error: check failed: " + condition;
  if (!detail.empty()) msg += " (" + detail + ")";
  throw InternalError(msg);
}

}  // namespace sysid::internal
