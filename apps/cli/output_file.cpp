#include "cli/output_file.hpp"

#include <fmt/format.h>

#include <fstream>
#include <memory>

#include "sysid/error.hpp"
#include "sysid/io_output.hpp"

namespace sysid::cli {
namespace fs = std::filesystem;
namespace {

std::string Head(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

}  // namespace

bool WrittenBySysid(const fs::path& path) { return HasGeneratorMark(Head(path)); }

void CheckOutputFile(const std::string& path, bool force, const std::string& flag) {
  if (path.empty() || force) return;
  if (WritesThrough(path)) return;  // /dev/stdout, a FIFO, a device: nothing is replaced
  std::error_code ec;
  const auto status = fs::status(path, ec);  // follows links: the file a link names
  if (!fs::is_regular_file(status) || WrittenBySysid(path)) return;
  throw OptionsError(fmt::format(
      "{} {}: exists and was not written by sysid (it does not start with sysid's generator "
      "mark, '# generator: sysid ...' or '\"_generator\": \"sysid ...'); "
      "refusing to replace it: choose another name, or pass --force",
      flag, path));
}

void GuardOutputFiles(CLI::App* cmd,
                      std::vector<std::pair<const std::string*, std::string>> outputs) {
  auto force = std::make_shared<bool>(false);
  if (cmd->get_option_no_throw("--force") == nullptr)
    cmd->add_flag("--force", *force,
                  "replace an existing output file that sysid did not write (one without sysid's "
                  "generator mark)");
  cmd->parse_complete_callback([cmd, outputs = std::move(outputs), force] {
    const CLI::Option* flag = cmd->get_option_no_throw("--force");
    const bool forced = *force || (flag != nullptr && flag->count() > 0);
    for (const auto& [path, name] : outputs) CheckOutputFile(*path, forced, name);
  });
}

}  // namespace sysid::cli
