#include "cli/output_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <fstream>
#include <memory>
#include <string_view>

#include "sysid/error.hpp"
#include "sysid/io_output.hpp"

namespace sysid::cli {
namespace fs = std::filesystem;
namespace {

std::string Head(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(64 * 1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

bool Contains(std::string_view text, std::string_view part) {
  return text.find(part) != std::string_view::npos;
}

// The metadata keys only sysid's writers put in a recording (a user's own recording may carry
// units, a sample rate or notes, so those prove nothing).
constexpr std::array<std::string_view, 8> kSysidKeys{
    "stage", "procedure", "derive", "model", "content", "ff", "waveform_name", "resampled"};

bool CsvWrittenBySysid(std::string_view head) {
  size_t pos = 0;
  while (pos < head.size()) {
    const size_t end = std::min(head.find('\n', pos), head.size());
    std::string_view line = head.substr(pos, end - pos);
    pos = end + 1;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.rfind("# dominance of the inverse-model terms", 0) == 0) return true;
    // The header line: sysid's own tables.
    if (line.rfind("# ", 0) != 0)
      return line.rfind("source,rank,variable,rms,peak,", 0) == 0 ||  // dominance table
             line == "t,kind";                                         // simulation events
    const size_t colon = line.find(':');
    if (colon == std::string_view::npos) continue;
    const std::string_view key = line.substr(2, colon - 2);
    for (const auto k : kSysidKeys)
      if (key == k) return true;
  }
  return false;
}

}  // namespace

bool WrittenBySysid(const fs::path& path) {
  const std::string head = Head(path);
  const size_t first = head.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return false;
  if (head[first] == '{')
    return Contains(head, "\"a1p\": \"1/s\"") ||        // a model's unit block
           Contains(head, "\"type\": \"tanh-mlp\"") ||  // a network
           Contains(head, "\"note\": \"Virtual piezo stage for libsysid") ||
           Contains(head, "\"fit_time_s\":");  // a hysteresis model from `hysteresis fit`
  return CsvWrittenBySysid(head);
}

void CheckOutputFile(const std::string& path, bool force, const std::string& flag) {
  if (path.empty() || force) return;
  if (WritesThrough(path)) return;  // /dev/stdout, a FIFO, a device: nothing is replaced
  std::error_code ec;
  const auto status = fs::status(path, ec);  // follows links: the file a link names
  if (!fs::is_regular_file(status) || WrittenBySysid(path)) return;
  throw OptionsError(fmt::format(
      "{} {}: exists and was not written by sysid (none of the metadata or keys sysid writes); "
      "refusing to replace it: choose another name, or pass --force",
      flag, path));
}

void GuardOutputFiles(CLI::App* cmd,
                      std::vector<std::pair<const std::string*, std::string>> outputs) {
  auto force = std::make_shared<bool>(false);
  if (cmd->get_option_no_throw("--force") == nullptr)
    cmd->add_flag("--force", *force,
                  "replace an existing output file that sysid did not write (one without the "
                  "metadata or keys sysid writes)");
  cmd->parse_complete_callback([cmd, outputs = std::move(outputs), force] {
    const CLI::Option* flag = cmd->get_option_no_throw("--force");
    const bool forced = *force || (flag != nullptr && flag->count() > 0);
    for (const auto& [path, name] : outputs) CheckOutputFile(*path, forced, name);
  });
}

}  // namespace sysid::cli
