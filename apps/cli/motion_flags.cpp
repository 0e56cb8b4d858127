#include "cli/motion_flags.hpp"

namespace sysid::cli {

void MotionFlags::Add(CLI::App* cmd, const std::string& derivative_help) {
  cmd->add_option("--derivative", derivative, derivative_help)
      ->check(CLI::IsMember({"central", "butterworth", "savgol"}));
  cmd->add_option("--cutoff", cutoff_hz, "Butterworth cut-off [Hz], default 50")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--velocity-column", velocity_column,
                  "measured-velocity column [m/s] used when a recording has no x (default v)");
}

void MotionFlags::ApplyTo(MotionOptions& motion) const {
  if (!derivative.empty()) motion.derivative.method = ParseDerivativeMethod(derivative);
  motion.derivative.cutoff_hz = cutoff_hz;
  motion.velocity_column = velocity_column;
}

std::vector<Recording> MotionFlags::ReadRecordings(const std::vector<std::string>& paths) const {
  ReadOptions ro;
  ro.any_of_columns = {"x", velocity_column};
  std::vector<Recording> recs;
  for (const auto& p : paths) recs.push_back(ReadRecording(p, ro));
  return recs;
}

}  // namespace sysid::cli
