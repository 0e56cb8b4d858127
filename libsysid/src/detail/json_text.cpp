#include <cmath>
#include <cstdlib>
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
  } catch (const nlohmann::json::out_of_range& e) {
    // nlohmann reports a number too large for a double (406) without a position: find the first
    // number literal outside strings that overflows, so the message names it like a parse error.
    bool in_string = false;
    for (size_t i = 0; i < text.size(); ++i) {
      const char c = text[i];
      if (in_string) {
        if (c == '\\') ++i;
        else if (c == '"') in_string = false;
        continue;
      }
      if (c == '"') { in_string = true; continue; }
      if ((c == '-' || (c >= '0' && c <= '9')) &&
          (i == 0 || std::string_view("0123456789.eE+-").find(text[i - 1]) == std::string_view::npos)) {
        size_t end = i + 1;
        while (end < text.size() && std::string_view("0123456789.eE+-").find(text[end]) != std::string_view::npos) ++end;
        const std::string literal(text.substr(i, end - i));
        const double v = std::strtod(literal.c_str(), nullptr);
        if (std::isinf(v))
          throw InputError(source + ":" + TextPosition(text, i) +
                           ": expected a finite number, found " + literal);
        i = end - 1;
      }
    }
    throw InputError(source + ": invalid JSON: " + std::string(e.what()));
  }
}

}  // namespace sysid::detail
