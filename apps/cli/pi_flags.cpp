#include "cli/pi_flags.hpp"

#include <fmt/format.h>

namespace sysid::cli::internal {

std::pair<CLI::Option*, CLI::Option*> AddPiGainFlags(CLI::App* cmd, PiOptions& pi,
                                                     const std::string& prefix) {
  const PiOptions delay_stage = PiOptions::ForActuatorDelayStage();
  CLI::Option* kp =
      cmd->add_option("--kp", pi.kp_v_per_m,
                      fmt::format("{}proportional gain [V/m]; the default is the paper's, stable "
                                  "on the bundled stage (velocity source); the actuator-delay "
                                  "preset needs {} (docs/control.md)",
                                  prefix, delay_stage.kp_v_per_m))
          ->capture_default_str();
  CLI::Option* ki =
      cmd->add_option("--ki", pi.ki_v_per_m_s,
                      fmt::format("{}integral gain [V/(m s)]; the default is the paper's; "
                                  "actuator-delay preset: {}",
                                  prefix, delay_stage.ki_v_per_m_s))
          ->capture_default_str();
  return {kp, ki};
}

}  // namespace sysid::cli::internal
