// --kp, --ki: the PI gains of `sysid track`, `sysid margins` and `sysid pipeline`, shown with
// PiOptions' defaults (the paper's gains) and the actuator-delay preset's, and recorded as the
// fields they set (cli/field_flag.hpp).
#ifndef SYSID_APPS_CLI_PI_FLAGS_HPP_
#define SYSID_APPS_CLI_PI_FLAGS_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <utility>

#include "cli/field_flag.hpp"
#include "sysid/control.hpp"

namespace sysid::cli {

namespace internal {
/// The two options, not recorded.
std::pair<CLI::Option*, CLI::Option*> AddPiGainFlags(CLI::App* cmd, PiOptions& pi,
                                                     const std::string& prefix);
}  // namespace internal

/// Adds --kp and --ki bound to `pi`, a member of the command's described `options` (a nested
/// PiOptions, or `options` itself), and records them as setting its kp_v_per_m and
/// ki_v_per_m_s (BindField); `prefix` starts the help text (e.g. "PI "). Returns the two
/// options (for extra checks).
template <class Options>
std::pair<CLI::Option*, CLI::Option*> AddPiGainOptions(CLI::App* cmd, Options& options,
                                                       PiOptions& pi, const std::string& prefix) {
  const auto gains = internal::AddPiGainFlags(cmd, pi, prefix);
  BindField(cmd, gains.first, options, pi.kp_v_per_m);
  BindField(cmd, gains.second, options, pi.ki_v_per_m_s);
  return gains;
}

/// The same for a command whose described struct is `pi` itself.
inline std::pair<CLI::Option*, CLI::Option*> AddPiGainOptions(CLI::App* cmd, PiOptions& pi,
                                                              const std::string& prefix) {
  return AddPiGainOptions(cmd, pi, pi, prefix);
}

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_PI_FLAGS_HPP_
