// --kp, --ki: the PI gains of `sysid track` and `sysid pipeline`, shown with PiOptions'
// defaults (the paper's gains) and the actuator-delay preset's.
#ifndef SYSID_APPS_CLI_PI_FLAGS_HPP_
#define SYSID_APPS_CLI_PI_FLAGS_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <utility>

#include "sysid/control.hpp"

namespace sysid::cli {

/// Adds --kp and --ki bound to `pi`; `prefix` starts the help text (e.g. "PI "). Returns the
/// two options (for extra checks).
std::pair<CLI::Option*, CLI::Option*> AddPiGainOptions(CLI::App* cmd, PiOptions& pi,
                                                       const std::string& prefix);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_PI_FLAGS_HPP_
