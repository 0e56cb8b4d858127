// The rule for every "-o FILE" of the CLI (issue #29): a command replaces only files it can
// prove sysid wrote, told by what sysid writes into them; --force replaces any other regular
// file. A FIFO or a device is written through and a symbolic link is followed
// (WriteFileAtomically), so neither is ever replaced.
#ifndef SYSID_APPS_CLI_OUTPUT_FILE_HPP_
#define SYSID_APPS_CLI_OUTPUT_FILE_HPP_

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace sysid::cli {

/// True when the first 64 KB of the regular file `path` carry sysid's writing: a CSV whose
/// leading '#' metadata holds a key only sysid writes (stage, procedure, derive, model,
/// content, ff, waveform_name, resampled), a CSV table with the comment or header sysid gives
/// it (the dominance table, simulation events), or a JSON object with sysid's unit block
/// ("units": {"a1p": "1/s", ...}), its network type ("tanh-mlp"), its stage note or the fit
/// block of a hysteresis model ("fit_time_s").
bool WrittenBySysid(const std::filesystem::path& path);

/// Checks "FLAG PATH" before any work (throws OptionsError, exit 1): nothing there, not a
/// regular file (the writer writes through or refuses it), a file WrittenBySysid, or `force`.
void CheckOutputFile(const std::string& path, bool force, const std::string& flag = "-o");

/// Applies CheckOutputFile to each (path, flag) of `cmd` once its flags are parsed, before it
/// runs, with --force as its flag (added when `cmd` has none; a command's own --force, which
/// replaces its output folder, also replaces a file). The paths must outlive the parse.
void GuardOutputFiles(CLI::App* cmd, std::vector<std::pair<const std::string*, std::string>> outputs);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_OUTPUT_FILE_HPP_
