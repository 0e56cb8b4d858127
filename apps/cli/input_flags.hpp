// --input, --hold, --pulses, --pulse-*, --waveform: the input signal u(t) [V] of a simulation,
// from a table, a pulse train or one of the paper's named waveforms.
#ifndef SYSID_APPS_CLI_INPUT_FLAGS_HPP_
#define SYSID_APPS_CLI_INPUT_FLAGS_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/recording_flags.hpp"
#include "sysid/input.hpp"

namespace sysid::cli {

struct InputFlags {
  std::string input_path;
  std::string hold = "zoh";
  std::vector<double> pulses;
  PulseTrainSpec pulse_train;  // on, off, repeats, start: the flags' defaults are the library's
  std::string waveform;
  RecordingFlags recording;  ///< --var, --rate, --scale for the --input table

  /// Adds the flags (--input, --hold, --pulses, --pulse-on, --pulse-off, --pulse-repeats,
  /// --pulse-start, --waveform); the three sources exclude each other.
  void Add(CLI::App* cmd);
  /// The chosen input; OptionsError unless exactly one source is given, InputError for a bad
  /// table.
  NamedWaveform Choose() const;
};

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_INPUT_FLAGS_HPP_
