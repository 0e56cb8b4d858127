// The mark that tells a file sysid wrote from a user's (sysid/io_output.hpp).
#include <string>
#include <string_view>

#include "sysid/io_output.hpp"

namespace sysid {
namespace {

constexpr std::string_view kCsvLead = "# generator: sysid ";
constexpr std::string_view kJsonKey = "\"_generator\": \"sysid ";
constexpr std::string_view kMatLead = "MATLAB 5.0 MAT-file, sysid ";

bool StartsWith(std::string_view s, std::string_view lead) {
  return s.substr(0, lead.size()) == lead;
}

}  // namespace

std::string GeneratorName() { return std::string("sysid ") + SYSID_VERSION_TEXT; }

std::string GeneratorLine() { return "# generator: " + GeneratorName() + "\n"; }

std::string WithGeneratorKey(std::string_view json_text) {
  const size_t open = json_text.find_first_not_of(" \t\r\n");
  if (open == std::string_view::npos || json_text[open] != '{') return std::string(json_text);
  const size_t next = json_text.find_first_not_of(" \t\r\n", open + 1);
  const bool empty = next != std::string_view::npos && json_text[next] == '}';
  // nlohmann's layout: "{\n  \"key\": ..." with an indent, "{\"key\":..." without.
  const bool indented = open + 1 < json_text.size() && json_text[open + 1] == '\n';
  std::string out(json_text.substr(0, open + 1));
  out += indented ? "\n  \"_generator\": \"" : "\"_generator\":\"";
  out += GeneratorName() + "\"";
  if (!empty) out += ",";
  out += json_text.substr(open + 1);
  return out;
}

bool HasGeneratorMark(std::string_view head) {
  if (StartsWith(head, "\xEF\xBB\xBF")) head.remove_prefix(3);
  if (StartsWith(head, kCsvLead) || StartsWith(head, kMatLead)) return true;
  const size_t open = head.find_first_not_of(" \t\r\n");
  if (open == std::string_view::npos || head[open] != '{') return false;
  const size_t key = head.find_first_not_of(" \t\r\n", open + 1);
  if (key == std::string_view::npos) return false;
  // Compact JSON has no space after the colon.
  return StartsWith(head.substr(key), kJsonKey) ||
         StartsWith(head.substr(key), "\"_generator\":\"sysid ");
}

}  // namespace sysid
