// --derivative, --cutoff, --velocity-column: how identify, tune-delay, refine and dominance get
// velocity (and acceleration) from a recording's position or a measured-velocity column.
#ifndef SYSID_APPS_CLI_MOTION_FLAGS_HPP_
#define SYSID_APPS_CLI_MOTION_FLAGS_HPP_

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cli/field_flag.hpp"
#include "cli/recording_flags.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"

namespace sysid::cli {

/// "sysid: v, a: columns v, a (give --derivative to derive them from x)" and the like: the
/// line every command prints (stdout for compare's table, stderr elsewhere; no newline) naming
/// where v and a came from, `from` being MotionSource's words.
std::string MotionSourceNote(const std::string& from);

/// The positional recording files of a command that reads them with MotionFlags::ReadRecordings
/// (t, u and x or a velocity column); the caller makes it required where it is.
CLI::Option* AddMotionRecordings(CLI::App* cmd, std::vector<std::string>& paths);
/// A required --model file (M.json, described by `model_help`) and required recordings
/// (AddMotionRecordings): the inputs of tune-delay, refine and dominance.
void AddModelAndRecordings(CLI::App* cmd, std::string& model, const std::string& model_help,
                           std::vector<std::string>& recordings);

struct MotionFlags {
  /// empty: the recording's v, a columns when present, else x with the algorithm's default
  /// filter; given: v, a from x with this filter (MotionOptions::prefer_velocity_column off).
  std::string derivative;
  double cutoff_hz = MotionOptions{}.derivative.cutoff_hz;            ///< [Hz] Butterworth cut-off
  std::string velocity_column = MotionOptions{}.velocity_column;  ///< used when a recording has no x
  RecordingFlags recording;  ///< --var, --rate, --scale (MAT/HDF5 files, renamed columns)

  /// Adds the three flags and the recording flags (--var, --rate, --scale); `derivative_help` says
  /// what the filter is for, `default_filter` names the filter the algorithm's options choose
  /// (shown as the default).
  void Add(CLI::App* cmd, const std::string& derivative_help, const std::string& default_filter);
  /// Records (cli/field_flag.hpp) the fields of `motion`, a member of the command's described
  /// `options`, that the flags set through ApplyTo. Call after Add.
  template <class Options>
  void Bind(CLI::App* cmd, Options& options, const MotionOptions& motion) const {
    CLI::Option* derivative_flag = cmd->get_option("--derivative");
    BindField(cmd, derivative_flag, options, motion.derivative.method);
    BindField(cmd, derivative_flag, options, motion.prefer_velocity_column);
    BindField(cmd, cmd->get_option("--cutoff"), options, motion.derivative.cutoff_hz);
    BindField(cmd, cmd->get_option("--velocity-column"), options, motion.velocity_column);
  }
  /// Sets the filter, cut-off, velocity column and the column rule of `motion`, and keeps a
  /// copy for ReadRecordings' note.
  void ApplyTo(MotionOptions& motion) const;
  /// Reads recordings with t, u and x or the velocity column. Throws InputError. Prints on
  /// stderr the unit warnings (UnitSanityWarnings) and, after ApplyTo, queues where v and a
  /// will come from (MotionSourceNote, once per distinct source; NoteOnSuccess).
  std::vector<Recording> ReadRecordings(const std::vector<std::string>& paths) const;

 private:
  mutable std::optional<MotionOptions> applied_;
};

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_MOTION_FLAGS_HPP_
