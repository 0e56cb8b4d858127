#include "core/json_text.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unordered_map>
#include <vector>

#include "sysid/error.hpp"

namespace sysid::internal {

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

namespace {

// What `c` is, for a message: a printable character quoted, else its byte value.
std::string DescribeByte(char c) {
  if (c == '\0') return "a NUL byte";
  const auto u = static_cast<unsigned char>(c);
  if (u >= 0x20 && u < 0x7F) return std::string("'") + c + "'";
  char buf[16];
  std::snprintf(buf, sizeof buf, "byte 0x%02X", u);
  return buf;
}

// What nlohmann's parser lets through on text it accepted: a key twice in one object (it keeps
// the last silently), and bytes after a NUL that it takes for the end of the text. Walks the
// text once, iteratively (no recursion however deep the nesting).
void CheckKeysAndEnd(std::string_view t, const std::string& source) {
  const size_t n = t.size();
  size_t i = t.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
  auto ws = [&] {
    while (i < n && (t[i] == ' ' || t[i] == '\t' || t[i] == '\n' || t[i] == '\r')) ++i;
  };
  auto skip_string = [&] {  // at '"'; returns whether the string held an escape
    bool escaped = false;
    ++i;
    while (i < n && t[i] != '"') {
      escaped = escaped || t[i] == '\\';
      i += t[i] == '\\' ? 2 : 1;
    }
    if (i < n) ++i;
    return escaped;
  };
  struct Frame {
    bool object;
    std::unordered_map<std::string, size_t> keys;  // key -> offset of its quote
  };
  std::vector<Frame> stack;
  enum { kValue, kKey, kAfter } state = kValue;
  for (;;) {
    ws();
    if (i >= n) return;  // nlohmann accepted the text: nothing is missing
    if (state == kValue) {
      const char c = t[i];
      if (c == '{' || c == '[') {  // an empty one closes at once in kKey / below
        stack.push_back({c == '{', {}});
        ++i;
        state = c == '{' ? kKey : kValue;
        continue;
      }
      if (c == ']') {  // an empty array (the text was accepted: nothing else gets here)
        ++i;
        stack.pop_back();
        state = kAfter;
        continue;
      }
      if (c == '"') {
        skip_string();
      } else {
        while (i < n && t[i] != '\0' &&
               std::string_view(",]} \t\r\n").find(t[i]) == std::string_view::npos)
          ++i;
      }
      state = kAfter;
    } else if (state == kKey) {
      if (t[i] == '}') {  // an empty object
        ++i;
        stack.pop_back();
        state = kAfter;
        continue;
      }
      if (t[i] != '"') return;  // not reached on accepted text
      const size_t at = i;
      const bool escaped = skip_string();
      std::string key(t.substr(at + 1, i - at - 2));
      if (escaped) {
        try {
          key = nlohmann::json::parse(t.substr(at, i - at)).get<std::string>();
        } catch (const nlohmann::json::exception&) {
          return;
        }
      }
      const auto [it, fresh] = stack.back().keys.emplace(key, at);
      if (!fresh)
        throw InputError(source + ":" + TextPosition(t, at) + ": duplicate key '" +
                         Printable(key) + "' (first at " + TextPosition(t, it->second) +
                         "): a key may appear once in an object");
      ws();
      if (i >= n || t[i] != ':') return;
      ++i;
      state = kValue;
    } else {  // kAfter
      if (stack.empty()) break;
      const char c = t[i++];
      if (c == ',') {
        state = stack.back().object ? kKey : kValue;
      } else if (c == '}' || c == ']') {
        stack.pop_back();
      } else {
        return;  // not reached on accepted text
      }
    }
  }
  if (i < n)
    throw InputError(source + ":" + TextPosition(t, i) + ": unexpected " + DescribeByte(t[i]) +
                     " after the JSON text; expected the end of the file");
}

}  // namespace

nlohmann::json ParseJsonText(std::string_view text, const std::string& source) {
  try {
    nlohmann::json j = nlohmann::json::parse(text);
    CheckKeysAndEnd(text, source);
    return j;
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

}  // namespace sysid::internal
