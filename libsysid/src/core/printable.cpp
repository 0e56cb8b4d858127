#include "core/json_text.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include "sysid/error.hpp"

namespace sysid::internal {

bool HasControlByte(std::string_view s) {
  return std::any_of(s.begin(), s.end(), [](char c) {
    const auto b = static_cast<unsigned char>(c);
    return b < 0x20 || b == 0x7F;
  });
}

std::string OneLine(std::string_view s) {
  return HasControlByte(s) ? Printable(s, s.size()) : std::string(s);
}

std::string Printable(std::string_view s, size_t max_chars) {
  std::string out;
  size_t chars = 0;
  for (size_t i = 0; i < s.size(); ++chars) {
    if (chars >= max_chars) return out + "...";
    const auto c = static_cast<unsigned char>(s[i]);
    // A well-formed multi-byte UTF-8 character passes unless it is a C1 control (U+0080-U+009F).
    size_t len = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? 3 : c >= 0xC2 && c < 0xE0 ? 2 : 1;
    if (len > 1 && i + len <= s.size()) {
      bool ok = true;
      for (size_t k = 1; k < len; ++k) ok = ok && (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
      if (c == 0xC2 && static_cast<unsigned char>(s[i + 1]) < 0xA0) ok = false;
      if (ok) {
        out.append(s.substr(i, len));
        i += len;
        continue;
      }
    }
    if (c < 0x20 || c >= 0x7F) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
    ++i;
  }
  return out;
}

}  // namespace sysid::internal
