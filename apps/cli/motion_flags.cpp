#include "cli/motion_flags.hpp"

namespace sysid::cli {

void MotionFlags::Add(CLI::App* cmd, const std::string& derivative_help,
                      const std::string& default_filter) {
  cmd->add_option("--derivative", derivative, derivative_help + ": central, butterworth, savgol")
      ->check(CLI::IsMember({"central", "butterworth", "savgol"}))
      ->default_str(default_filter);
  cmd->add_option("--cutoff", cutoff_hz, "Butterworth cut-off [Hz]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--velocity-column", velocity_column,
                  "measured-velocity column [m/s] used when a recording has no x")
      ->capture_default_str();
  recording.Add(cmd);
}

void MotionFlags::ApplyTo(MotionOptions& motion) const {
  if (!derivative.empty()) motion.derivative.method = ParseDerivativeMethod(derivative);
  motion.derivative.cutoff_hz = cutoff_hz;
  motion.velocity_column = velocity_column;
}

std::vector<Recording> MotionFlags::ReadRecordings(const std::vector<std::string>& paths) const {
  ReadOptions ro;
  ro.any_of_columns = {"x", velocity_column};
  ro.mapping = recording.Mapping();
  std::vector<Recording> recs;
  for (const auto& p : paths) recs.push_back(ReadRecording(p, ro));
  return recs;
}

}  // namespace sysid::cli
