#include "detail/json_text.hpp"

#include "sysid/error.hpp"

namespace sysid::detail {

std::string TextPosition(std::string_view text, size_t pos) {
  long line = 1, col = 1;
  for (size_t i = 0; i < pos && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else {
      ++col;
    }
  }
  return std::to_string(line) + ":" + std::to_string(col);
}

std::string JsonKeyPosition(std::string_view text, const std::string& key,
                            const std::string& parent) {
  size_t from = 0;
  if (!parent.empty()) {
    const size_t p = text.find("\"" + parent + "\"");
    if (p != std::string_view::npos) from = p;
  }
  const size_t p = key.empty() ? std::string_view::npos : text.find("\"" + key + "\"", from);
  return p == std::string_view::npos ? "1:1" : TextPosition(text, p);
}

nlohmann::json ParseJsonText(std::string_view text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset just past the offending character.
    const size_t at = e.byte > 0 ? e.byte - 1 : 0;
    std::string what = e.what();
    const size_t cut = what.find("parse error");
    if (cut != std::string::npos) what = what.substr(cut);
    throw InputError(source + ":" + TextPosition(text, at) + ": invalid JSON: " + what);
  }
}

}  // namespace sysid::detail
