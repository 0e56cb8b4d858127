#include "cli/motion_flags.hpp"

#include <algorithm>
#include <iostream>

#include "cli/common.hpp"

namespace sysid::cli {

void MotionFlags::Add(CLI::App* cmd, const std::string& derivative_help,
                      const std::string& default_filter) {
  cmd->add_option("--derivative", derivative,
                  derivative_help + ": central, butterworth, savgol. Given, v and a come from x "
                                    "by it even when the recording has v, a columns (without "
                                    "it those columns are used)")
      ->check(CLI::IsMember({"central", "butterworth", "savgol"}))
      ->default_str(default_filter);
  cmd->add_option("--cutoff", cutoff_hz, "Butterworth cut-off [Hz]")
      ->check(PositiveNumber())
      ->capture_default_str();
  cmd->add_option("--velocity-column", velocity_column,
                  "measured-velocity column [m/s] used when a recording has no x")
      ->capture_default_str();
  recording.Add(cmd);
}

void MotionFlags::ApplyTo(MotionOptions& motion) const {
  if (!derivative.empty()) {
    motion.derivative.method = ParseDerivativeMethod(derivative);
    motion.prefer_velocity_column = false;  // the one rule: --derivative derives from x
  }
  motion.derivative.cutoff_hz = cutoff_hz;
  motion.velocity_column = velocity_column;
  applied_ = motion;
}

std::string MotionSourceNote(const std::string& from) {
  const bool columns = from.rfind("column", 0) == 0 && from.find(" (a:") == std::string::npos;
  return "sysid: v, a: " + from +
         (columns ? " of the recording as they are (give --derivative to derive them from x)"
                  : "");
}

std::vector<Recording> MotionFlags::ReadRecordings(const std::vector<std::string>& paths) const {
  ReadOptions ro;
  ro.any_of_columns = {"x", velocity_column};
  ro.mapping = recording.Mapping();
  std::vector<Recording> recs;
  std::vector<std::string> sources;
  for (const auto& p : paths) {
    recs.push_back(ReadRecording(p, ro));
    if (applied_) {
      const std::string from = MotionSource(recs.back(), *applied_);
      if (std::find(sources.begin(), sources.end(), from) == sources.end()) {
        sources.push_back(from);
        NoteOnSuccess(MotionSourceNote(from));
      }
    }
    // x in mm read as metres gives 1000x speeds that every pulse accepts: say so up front.
    for (const auto& w : UnitSanityWarnings(recs.back()))
      std::cerr << "sysid: warning: " << w << '\n';
  }
  return recs;
}

CLI::Option* AddMotionRecordings(CLI::App* cmd, std::vector<std::string>& paths) {
  return cmd
      ->add_option("recordings", paths,
                   "recording CSVs: t [s], u [V] and x [m] or a velocity column [m/s]")
      ->type_name("REC.csv");
}

void AddModelAndRecordings(CLI::App* cmd, std::string& model, const std::string& model_help,
                           std::vector<std::string>& recordings) {
  cmd->add_option("--model", model, model_help)->required()->type_name("M.json");
  AddMotionRecordings(cmd, recordings)->required();
}

}  // namespace sysid::cli
