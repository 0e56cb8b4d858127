// --var, --rate, --scale, --t-start, --t-end: where a command's recordings get their columns when
// the files are MAT or HDF5, or name their columns differently (sysid::SourceMapping). One helper
// for every command that reads recordings, so the flags mean the same everywhere.
#ifndef SYSID_APPS_CLI_RECORDING_FLAGS_HPP_
#define SYSID_APPS_CLI_RECORDING_FLAGS_HPP_

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sysid/io.hpp"

namespace sysid::cli {

struct RecordingFlags {
  std::vector<std::string> vars;             ///< "t=NAME,u=NAME" (repeatable)
  double rate_hz = 0;                        ///< [Hz] 0: the file's own t
  std::vector<std::string> scales;           ///< "x=1e-6" (repeatable, comma-separated)
  std::optional<double> t_start_s, t_end_s;  ///< [s] the time window kept

  /// Adds --var, --rate, --scale and, with `window`, --t-start and --t-end to `cmd` (simulate's
  /// --input table goes without: its --t-end is the simulation's).
  void Add(CLI::App* cmd, bool window = true);
  /// The mapping the flags describe. Throws OptionsError (exit 1) naming the flag.
  SourceMapping Mapping() const;
  /// `options` with the flags' mapping.
  ReadOptions Apply(ReadOptions options) const;
};

/// The reader's provenance metadata of `rec` (source.COLUMN, scale.COLUMN for the `columns` a
/// new recording keeps, and sample_rate_hz, crop_s), for a writer that builds its output from
/// `rec` rather than copying it.
std::vector<std::pair<std::string, std::string>> ProvenanceOf(
    const Recording& rec, const std::vector<std::string>& columns);

/// Splits "a=b,c=d[:,2]" at the commas outside brackets into (key, value) pairs; `flag` names
/// the option in errors (OptionsError).
std::vector<std::pair<std::string, std::string>> ParseAssignments(
    const std::vector<std::string>& items, const std::string& flag);
/// A finite number from `text` (whole string), or OptionsError naming `flag`.
double ParseFlagNumber(const std::string& text, const std::string& flag);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_RECORDING_FLAGS_HPP_
