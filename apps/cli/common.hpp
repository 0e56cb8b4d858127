// Conventions every sysid subcommand follows.
//
// Exit codes: 0 success; 1 usage error (bad flags, invalid option values); 2 bad input data
// (file content, model file); 3 numerical failure (singular system, no convergence).
// Results go to stdout (a readable table, or one JSON object with --json) or atomically to a
// file with -o. Progress goes to stderr, only when stderr is a terminal or --progress is given.
#ifndef SYSID_APPS_CLI_COMMON_HPP_
#define SYSID_APPS_CLI_COMMON_HPP_

#include <CLI/CLI.hpp>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sysid {
class OptionsError;
}

namespace sysid::cli {

enum ExitCode : int { kSuccess = 0, kUsage = 1, kBadInput = 2, kNumerical = 3 };

/// The stage presets, for the help of every option that takes one (generate --stage, stage
/// facts --stage, track --plant): StageParameters::Preset's names with what each is.
inline constexpr const char* kStagePresets =
    "virtual (the default, = drive-hysteresis: the calibrated velocity-source stage with the "
    "ceramic's asymmetric hysteresis and creep, 10 kHz loop, 1 kHz records), velocity-source "
    "(the same without hysteresis or creep, the default before it), virtual-1khz "
    "(velocity-source at a 1 kHz loop), drive-hysteresis-static (wider play operators, no "
    "creep) or actuator-delay (the older stage, on which the paper's feedforward does not "
    "help; docs/virtual_stage.md)";

/// Options shared by every subcommand (--json, --progress), filled by main().
struct GlobalOptions {
  bool progress = false;   ///< --progress: report progress on stderr even when not a terminal
};
GlobalOptions& Globals();

/// True when progress should be written to stderr (a terminal, or --progress).
bool ProgressEnabled();
/// Writes "\r<message>" style progress to stderr when ProgressEnabled().
void Progress(const std::string& message);
/// Ends a progress line (newline) if anything was written.
void ProgressDone();

/// Queues a line for stderr when the command succeeds (main prints the queue after it returns):
/// remarks such as where v and a came from, which would only clutter an error.
void NoteOnSuccess(const std::string& line);
/// Prints and clears the queued notes (main, after a successful command).
void PrintNotes();

/// Prints `j` to stdout (indented, newline-terminated).
void PrintJson(const nlohmann::json& j);

/// A simple aligned text table for human-readable output.
class Table {
 public:
  explicit Table(std::vector<std::string> header) : header_(std::move(header)) {}
  void AddRow(std::vector<std::string> row) { rows_.push_back(std::move(row)); }
  std::string Render() const;
 private:
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

/// Formats a double with `digits` significant digits (%.{digits}g).
std::string Num(double value, int digits = 6);

/// Hidden sizes as ParseHiddenSizes reads them: FIRST:LAST:STEP when evenly spaced, else a
/// comma-separated list (the shown default of --hidden).
std::string FormatHiddenSizes(const std::vector<int>& sizes);

/// Library option errors name their Options field (OptionsError::field()); the user typed
/// flags. Rethrows `e` as "FLAG: message" with the flag `field_flags` maps its field to, or
/// `fallback` when the field is not listed (e itself when fallback is empty).
[[noreturn]] void RethrowWithFlag(const OptionsError& e,
                                  const std::map<std::string, std::string>& field_flags,
                                  const std::string& fallback = "");

/// A floating-point option's range [lo, hi] that, unlike CLI::Range, also refuses NaN (every
/// comparison with NaN is false, so CLI::Range lets it through to the library's checks, whose
/// errors name a field instead of the flag). Same help text as CLI::Range(lo, hi).
CLI::Validator FiniteRange(double lo, double hi);

/// CLI::PositiveNumber and CLI::NonNegativeNumber (same help text) refusing NaN too, by the
/// flag's name: CLI11's comparisons are false for NaN, so its own checks let it through.
CLI::Validator PositiveNumber();
CLI::Validator NonNegativeNumber();

/// True when `path` ends in .csv or .CSV.
bool EndsWithCsv(const std::string& path);

/// Adds the standard "-o,--output FILE" option.
CLI::Option* AddOutputOption(CLI::App* cmd, std::string& path, const std::string& what);

/// A hidden, deprecated spelling `old_flag` of the option `current` (one name per quantity
/// across commands): it sets `target` as `current` does, checked by `check` (give the same
/// check as `current`), and prints "sysid: note: OLD is deprecated; use NEW" on stderr. The
/// two exclude each other.
/// A flag that switches `target` off (`--no-plots`): CLI11's "!--no-x" form prints the name as
/// "--no-x{false}" in --help.
CLI::Option* AddOffFlag(CLI::App* cmd, const std::string& name, bool& target,
                        const std::string& what);

CLI::Option* AddDeprecatedAlias(CLI::App* cmd, const std::string& old_flag, CLI::Option* current,
                                double& target, const CLI::Validator& check);

/// -v,--verbose: the table output becomes the result's FullReport() (every diagnostic) instead
/// of its BriefReport(); --json is unaffected.
CLI::Option* AddVerboseFlag(CLI::App* cmd, bool& verbose);

/// `text` safe for a terminal: control bytes other than line breaks as \xHH. Every error
/// message goes through it, since messages quote file names, and a name may hold an escape
/// sequence (a title change, a screen clear).
std::string ForTerminal(std::string_view text);

/// "--seed" into `seed` with the range every seed has, [0, 2^62]: CLI11 would read -1 into a
/// uint64 as 2^64 - 1. `what` is the help text.
CLI::Option* AddSeedOption(CLI::App* cmd, std::uint64_t& seed, const std::string& what);
/// "--threads" into `threads`, [0, 1024] (0 = all cores). `what` is the help text.
CLI::Option* AddThreadsOption(CLI::App* cmd, int& threads, const std::string& what);

}  // namespace sysid::cli

#endif  // SYSID_APPS_CLI_COMMON_HPP_
