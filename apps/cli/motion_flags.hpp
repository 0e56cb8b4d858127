// --derivative, --cutoff, --velocity-column: how identify, tune-delay, refine and dominance get
// velocity (and acceleration) from a recording's position or a measured-velocity column.
#ifndef SYSID_APPS_CLI_MOTION_FLAGS_HPP_
#define SYSID_APPS_CLI_MOTION_FLAGS_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/recording_flags.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"

namespace sysid::cli {

struct MotionFlags {
  std::string derivative;  ///< empty: keep the algorithm's default filter
  double cutoff_hz = MotionOptions{}.derivative.cutoff_hz;            ///< [Hz] Butterworth cut-off
  std::string velocity_column = MotionOptions{}.velocity_column;  ///< used when a recording has no x
  RecordingFlags recording;  ///< --var, --rate, --scale (MAT/HDF5 files, renamed columns)

  /// Adds the three flags and the recording flags (--var, --rate, --scale); `derivative_help` says
  /// what the filter is for, `default_filter` names the filter the algorithm's options choose
  /// (shown as the default).
  void Add(CLI::App* cmd, const std::string& derivative_help, const std::string& default_filter);
  /// Sets the filter, cut-off and velocity column of `motion`.
  void ApplyTo(MotionOptions& motion) const;
  /// Reads recordings with t, u and x or the velocity column. Throws InputError.
  std::vector<Recording> ReadRecordings(const std::vector<std::string>& paths) const;
};

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_MOTION_FLAGS_HPP_
