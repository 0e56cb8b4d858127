#include "cli/field_flag.hpp"

#include <cxxabi.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <stdexcept>

namespace sysid::cli {
namespace {

// Function-local static: commands register from main() and from tests, never concurrently.
std::map<const CLI::App*, std::vector<ExposedOptions>>& Records() {
  static std::map<const CLI::App*, std::vector<ExposedOptions>> records;
  return records;
}

// "sysid::DelayTuningOptions" -> "DelayTuningOptions".
std::string TypeName(const std::type_info& type) {
  int status = 0;
  const std::unique_ptr<char, void (*)(void*)> demangled(
      abi::__cxa_demangle(type.name(), nullptr, nullptr, &status), std::free);
  std::string name = status == 0 && demangled ? demangled.get() : type.name();
  const size_t colon = name.rfind("::");
  return colon == std::string::npos ? name : name.substr(colon + 2);
}

}  // namespace

std::string FlagName(const CLI::Option* option) {
  if (!option->get_lnames().empty()) return "--" + option->get_lnames().front();
  if (!option->get_snames().empty()) return "-" + option->get_snames().front();
  return option->get_name(true);
}

std::vector<ExposedOptions> ExposedOptionsOf(const CLI::App* cmd) {
  const auto it = Records().find(cmd);
  return it == Records().end() ? std::vector<ExposedOptions>{} : it->second;
}

namespace internal {

void RecordFieldFlag(const CLI::App* cmd, const std::type_info& type, const void* options,
                     std::vector<std::string> fields, const std::string& path,
                     const std::string& flag) {
  const std::string name = TypeName(type);
  if (path.empty())
    throw std::logic_error("sysid " + cmd->get_name() + " " + flag +
                           ": the variable it sets is no field in " + name +
                           "::Serialize (cli/field_flag.hpp)");
  std::vector<ExposedOptions>& exposed = Records()[cmd];
  auto it = exposed.begin();
  while (it != exposed.end() && it->address != options) ++it;
  if (it == exposed.end()) {
    exposed.push_back({name, options, std::move(fields), {}});
    it = exposed.end() - 1;
  }
  it->bound.emplace_back(flag, path);
}

}  // namespace internal
}  // namespace sysid::cli
