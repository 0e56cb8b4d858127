// --var, --rate, --scale: where a command's recordings get their columns when the files are MAT
// or HDF5, or name their columns differently (sysid::SourceMapping). One helper for every
// command that reads recordings, so the flags mean the same everywhere.
#ifndef SYSID_APPS_CLI_RECORDING_FLAGS_HPP_
#define SYSID_APPS_CLI_RECORDING_FLAGS_HPP_

#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

#include "sysid/io.hpp"

namespace sysid::cli {

struct RecordingFlags {
  std::vector<std::string> vars;    ///< "t=NAME,u=NAME" (repeatable)
  double rate_hz = 0;               ///< [Hz] 0: the file's own t
  std::vector<std::string> scales;  ///< "x=1e-6" (repeatable, comma-separated)

  /// Adds --var, --rate and --scale to `cmd`.
  void Add(CLI::App* cmd);
  /// The mapping the flags describe. Throws OptionsError (exit 1) naming the flag.
  SourceMapping Mapping() const;
  /// `options` with the flags' mapping.
  ReadOptions Apply(ReadOptions options) const;
};

/// Splits "a=b,c=d[:,2]" at the commas outside brackets into (key, value) pairs; `flag` names
/// the option in errors (OptionsError).
std::vector<std::pair<std::string, std::string>> ParseAssignments(
    const std::vector<std::string>& items, const std::string& flag);
/// A finite number from `text` (whole string), or OptionsError naming `flag`.
double ParseFlagNumber(const std::string& text, const std::string& flag);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_RECORDING_FLAGS_HPP_
