// --fit-fraction F: a command that fits a model fits it on the first fraction F of each
// recording's duration; the rest is not used by the fit (a held-out part to score the model on
// with --t-start).
#ifndef SYSID_APPS_CLI_FIT_FRACTION_FLAG_HPP_
#define SYSID_APPS_CLI_FIT_FRACTION_FLAG_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "sysid/io.hpp"

namespace sysid::cli {

struct FitFractionFlag {
  double fraction = 1;  ///< 0 < F <= 1 [dimensionless]; 1: the whole recording

  /// Adds --fit-fraction to `cmd`.
  void Add(CLI::App* cmd);
  /// Each recording cut to t <= t0 + F (t_end - t0) (CropRecording), with a note on stderr per
  /// recording naming the part fitted and the part left out, `command` naming the command.
  /// Unchanged when F = 1. Throws OptionsError for F outside (0, 1], InputError when a part
  /// holds fewer than 2 samples.
  std::vector<Recording> FitPart(std::vector<Recording> recordings,
                                 const std::string& command) const;
};

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_FIT_FRACTION_FLAG_HPP_
