// The rule for every "-o FILE" of the CLI: a command replaces only files it can
// prove sysid wrote, told by the generator mark every writer puts first; --force replaces any
// other regular file. A FIFO or a device is written through and a symbolic link is followed
// (WriteFileAtomically), so neither is ever replaced.
#ifndef SYSID_APPS_CLI_OUTPUT_FILE_HPP_
#define SYSID_APPS_CLI_OUTPUT_FILE_HPP_

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace sysid::cli {

/// True when the regular file `path` starts with the generator mark every sysid writer puts
/// first (sysid::HasGeneratorMark: "# generator: sysid ..." in a CSV, a first key "_generator":
/// "sysid ..." in a JSON file, a MAT header naming sysid). Keys or metadata a user's own file
/// may hold ("stage", "fit_time_s", units) prove nothing.
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
