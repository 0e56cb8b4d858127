#include "cli/common.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>

#include "sysid/error.hpp"

namespace sysid::cli {

GlobalOptions& Globals() {
  static GlobalOptions options;
  return options;
}

bool ProgressEnabled() { return Globals().progress || isatty(STDERR_FILENO) == 1; }

namespace {
bool progress_open = false;
}

void Progress(const std::string& message) {
  if (!ProgressEnabled()) return;
  std::fprintf(stderr, "\r%s\033[K", message.c_str());
  std::fflush(stderr);
  progress_open = true;
}

void ProgressDone() {
  if (progress_open) std::fputc('\n', stderr);
  progress_open = false;
}

namespace {
std::vector<std::string>& Notes() {
  static std::vector<std::string> notes;
  return notes;
}
}  // namespace

void NoteOnSuccess(const std::string& line) { Notes().push_back(line); }

void PrintNotes() {
  for (const auto& n : Notes()) std::cerr << n << '\n';
  Notes().clear();
}

void PrintJson(const nlohmann::json& j) { std::cout << j.dump(2) << '\n'; }

std::string Table::Render() const {
  std::vector<size_t> width(header_.size(), 0);
  auto widen = [&](const std::vector<std::string>& row) {
    for (size_t i = 0; i < row.size() && i < width.size(); ++i)
      width[i] = std::max(width[i], row[i].size());
  };
  widen(header_);
  for (const auto& r : rows_) widen(r);
  std::string out;
  auto emit = [&](const std::vector<std::string>& row) {
    for (size_t i = 0; i < row.size() && i < width.size(); ++i) {
      // The last column is not padded: no trailing blanks.
      out += i + 1 < row.size() ? fmt::format("{:<{}}  ", row[i], width[i]) : row[i];
    }
    out += '\n';
  };
  emit(header_);
  std::vector<std::string> rule;
  for (size_t w : width) rule.emplace_back(w, '-');
  emit(rule);
  for (const auto& r : rows_) emit(r);
  return out;
}

void RethrowWithFlag(const OptionsError& e, const std::map<std::string, std::string>& field_flags,
                     const std::string& fallback) {
  const auto flag = field_flags.find(e.field());
  if (flag == field_flags.end() && fallback.empty()) throw e;
  throw e.WithMessage((flag == field_flags.end() ? fallback : flag->second) + ": " + e.what());
}

CLI::Validator FiniteRange(double lo, double hi) {
  const CLI::Range range(lo, hi);  // only for its help text, "FLOAT in [lo - hi]"
  return CLI::Validator(
      [lo, hi](std::string& input) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(input, v) || !std::isfinite(v))
          return fmt::format("Value {} is not a finite number (expected one in [{:g}, {:g}])",
                             input, lo, hi);
        if (v < lo || v > hi) return fmt::format("Value {} is outside [{:g}, {:g}]", input, lo, hi);
        return {};
      },
      range.get_description());
}

namespace {
// CLI11's PositiveNumber / NonNegativeNumber print their upper end, the largest double, as a
// 309-digit number ("Value 0 not in range 0.000000 to 17976931348623157...").
CLI::Validator NumberAbove(bool strict) {
  CLI::Validator v(strict ? "POSITIVE" : "NONNEGATIVE");
  v.operation([strict](std::string& input) -> std::string {
    double x = 0;
    if (!CLI::detail::lexical_cast(input, x) || std::isnan(x))
      return "Value " + input + " is not a number";
    if (!std::isfinite(x)) return "Value " + input + " is not a finite number";
    if (strict ? !(x > 0) : !(x >= 0))
      return "Value " + input + ": expected a number " + (strict ? "> 0" : ">= 0");
    return {};
  });
  return v;
}
}  // namespace

CLI::Validator PositiveNumber() { return NumberAbove(true); }
CLI::Validator NonNegativeNumber() { return NumberAbove(false); }

bool EndsWithCsv(const std::string& path) {
  return path.size() >= 4 && (path.compare(path.size() - 4, 4, ".csv") == 0 ||
                              path.compare(path.size() - 4, 4, ".CSV") == 0);
}

std::string Num(double value, int digits) { return fmt::format("{:.{}g}", value, digits); }

std::string FormatHiddenSizes(const std::vector<int>& sizes) {
  if (sizes.size() >= 3) {
    const int step = sizes[1] - sizes[0];
    bool even = step > 0;
    for (size_t i = 2; i < sizes.size() && even; ++i) even = sizes[i] - sizes[i - 1] == step;
    if (even) return fmt::format("{}:{}:{}", sizes.front(), sizes.back(), step);
  }
  std::string out;
  for (size_t i = 0; i < sizes.size(); ++i) out += (i ? "," : "") + std::to_string(sizes[i]);
  return out;
}

CLI::Option* AddOutputOption(CLI::App* cmd, std::string& path, const std::string& what) {
  return cmd->add_option("-o,--output", path, what + " (written atomically)")
      ->type_name("FILE");
}

CLI::Option* AddOffFlag(CLI::App* cmd, const std::string& name, bool& target,
                        const std::string& what) {
  return cmd->add_flag_callback(
      name, [&target] { target = false; }, what);
}

CLI::Option* AddDeprecatedAlias(CLI::App* cmd, const std::string& old_flag, CLI::Option* current,
                                double& target, const CLI::Validator& check) {
  const std::string current_name = current->get_name();
  CLI::Option* alias = cmd->add_option_function<double>(
      old_flag,
      [&target, old_flag, current, current_name](const double& value) {
        // Checked here, not by excludes(): that would list the hidden alias, nameless, under
        // the current option's --help as "Excludes: ".
        if (current->count() > 0) throw CLI::ExcludesError(old_flag, current_name);
        std::cerr << "sysid: note: " << old_flag << " is deprecated; use " << current_name
                  << " (the old spelling is kept for one release)\n";
        target = value;
      },
      "deprecated spelling of " + current_name);
  alias->check(check);
  alias->group("");  // hidden from --help
  return alias;
}

std::string ForTerminal(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    // C0 controls and DEL, and the C1 controls U+0080..U+009F (UTF-8 C2 80..C2 9F: CSI among
    // them); line breaks stay, multi-line messages keep their lines.
    const bool c1 = c == 0xC2 && i + 1 < text.size() &&
                    static_cast<unsigned char>(text[i + 1]) >= 0x80 &&
                    static_cast<unsigned char>(text[i + 1]) <= 0x9F;
    if ((c < 0x20 && c != '\n') || c == 0x7F || c1) {
      const auto byte = c1 ? static_cast<unsigned char>(text[++i]) : c;
      out += fmt::format("\\x{:02X}", byte);
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

CLI::Option* AddSeedOption(CLI::App* cmd, std::uint64_t& seed, const std::string& what) {
  return cmd->add_option("--seed", seed, what)
      ->check(CLI::Range(std::uint64_t{0}, std::uint64_t{1} << 62))
      ->capture_default_str();
}

CLI::Option* AddThreadsOption(CLI::App* cmd, int& threads, const std::string& what) {
  return cmd->add_option("--threads", threads, what)
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
}

CLI::Option* AddVerboseFlag(CLI::App* cmd, bool& verbose) {
  return cmd->add_flag("-v,--verbose", verbose,
                       "print the full report (every diagnostic) instead of the brief one");
}

}  // namespace sysid::cli
