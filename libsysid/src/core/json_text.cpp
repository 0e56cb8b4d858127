#include "core/json_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
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

namespace {

std::string FormatBound(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// What a value is, for "found ...": the number as written, a quoted (printable) string, or the
// kind of container.
std::string Found(const nlohmann::json& j) {
  if (j.is_string()) return "string \"" + Printable(j.get_ref<const std::string&>(), 40) + "\"";
  if (j.is_number()) return j.dump();
  if (j.is_boolean()) return j.get<bool>() ? "true" : "false";
  if (j.is_null()) return "null";
  if (j.is_object()) return "an object";
  return "an array of " + std::to_string(j.size()) + " value" + (j.size() == 1 ? "" : "s");
}

std::string EscapePointerToken(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

std::string Join(const std::vector<std::string>& keys) {
  std::string out;
  for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

}  // namespace

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

bool NumberRule::Accepts(double v) const {
  if (!std::isfinite(v)) return false;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string NumberRule::Describe() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return std::string("a number in ") + (lo_open ? "(" : "[") + FormatBound(lo) + ", " +
           FormatBound(hi) + (hi_open ? ")" : "]");
  if (has_lo) return std::string("a number ") + (lo_open ? "> " : ">= ") + FormatBound(lo);
  if (has_hi) return std::string("a number ") + (hi_open ? "< " : "<= ") + FormatBound(hi);
  return "a finite number";
}

// ---- JsonNode ----

void JsonNode::Fail(const std::string& what) const {
  throw InputError(doc_->Where(pointer_) + ": " + (pointer_.empty() ? "" : name_ + ": ") + what);
}

void JsonNode::Expected(const std::string& expected) const {
  Fail("expected " + expected + ", found " + Found(*json_));
}

bool JsonNode::Has(const std::string& key) const {
  return json_->is_object() && json_->contains(key);
}

JsonNode JsonNode::Get(const std::string& key) const {
  if (!json_->is_object()) Expected("an object");
  const auto it = json_->find(key);
  if (it == json_->end()) Fail("missing required key '" + key + "'");
  return JsonNode(doc_, &*it, pointer_ + "/" + EscapePointerToken(key),
                  pointer_.empty() ? key : name_ + "." + key);
}

JsonNode JsonNode::Element(size_t index) const {
  SYSID_CHECK(json_->is_array() && index < json_->size(), name_);
  return JsonNode(doc_, &(*json_)[index], pointer_ + "/" + std::to_string(index),
                  (pointer_.empty() ? "" : name_) + "[" + std::to_string(index) + "]");
}

void JsonNode::ExpectObject(const std::vector<std::string>& known,
                            const std::vector<std::string>& allowed_extra) const {
  if (!json_->is_object()) Expected("an object with keys " + Join(known));
  for (const auto& item : json_->items()) {
    const std::string& key = item.key();
    if (!key.empty() && key[0] == '_') continue;
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    if (std::find(allowed_extra.begin(), allowed_extra.end(), key) != allowed_extra.end()) continue;
    throw InputError(doc_->Where(pointer_ + "/" + EscapePointerToken(key)) + ": unknown key '" +
                     Printable(key, 40) + "'" + (pointer_.empty() ? "" : " in '" + name_ + "'") +
                     " (expected " + Join(known) + ")");
  }
}

void JsonNode::ExpectArray(size_t size, bool non_empty) const {
  const std::string what = size != 0 ? "an array of " + std::to_string(size) + " values"
                           : non_empty ? "a non-empty array"
                                       : "an array";
  if (!json_->is_array() || (size != 0 && json_->size() != size) || (non_empty && json_->empty()))
    Expected(what);
}

double JsonNode::Number(const NumberRule& rule) const {
  if (!json_->is_number() || !rule.Accepts(json_->get<double>())) Expected(rule.Describe());
  return json_->get<double>();
}

double JsonNode::NumberOrNaN(const NumberRule& rule) const {
  if (json_->is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!json_->is_number() || !rule.Accepts(json_->get<double>()))
    Expected(rule.Describe() + " or null");
  return json_->get<double>();
}

bool JsonNode::Boolean() const {
  if (!json_->is_boolean()) Expected("true or false");
  return json_->get<bool>();
}

long JsonNode::Integer(long lo, long hi) const {
  const std::string what =
      "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!json_->is_number_integer()) Expected(what);
  if (json_->is_number_unsigned() &&
      json_->get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<long>::max()))
    Expected(what);
  const long v = json_->get<long>();
  if (v < lo || v > hi) Expected(what);
  return v;
}

std::string JsonNode::String(bool non_empty) const {
  if (!json_->is_string() || (non_empty && json_->get_ref<const std::string&>().empty()))
    Expected(non_empty ? "a non-empty string" : "a string");
  return json_->get<std::string>();
}

std::vector<double> JsonNode::Numbers(size_t size, const NumberRule& rule) const {
  ExpectArray(size);
  std::vector<double> out;
  out.reserve(json_->size());
  for (size_t i = 0; i < json_->size(); ++i) out.push_back(Element(i).Number(rule));
  return out;
}

// ---- JsonDocument ----

JsonDocument::JsonDocument(std::string_view text, std::string source)
    : text_(text), source_(std::move(source)), json_(ParseJsonText(text, source_)) {}

// Walks the (already validated) text once and records where each value and member key is
// written, by JSON pointer. Iterative, so deep nesting cannot overflow the stack; every index
// is bounds-checked so that it stays safe even on text nlohmann would reject.
const std::vector<std::pair<std::string, JsonDocument::Place>>& JsonDocument::Places() const {
  if (indexed_) return places_;
  indexed_ = true;
  const std::string_view t = text_;
  const size_t n = t.size();
  size_t i = t.substr(0, 3) == "\xEF\xBB\xBF" ? 3 : 0;
  auto ws = [&] {
    while (i < n && (t[i] == ' ' || t[i] == '\t' || t[i] == '\n' || t[i] == '\r')) ++i;
  };
  auto skip_string = [&] {  // at '"'
    ++i;
    while (i < n && t[i] != '"') i += t[i] == '\\' ? 2 : 1;
    if (i < n) ++i;
  };
  struct Frame {
    bool object;
    size_t index;
    std::string pointer;
  };
  constexpr size_t kMaxIndexedDepth = 64;
  std::vector<Frame> stack;
  std::string pointer;
  size_t key_at = std::string_view::npos;
  enum { kValue, kKey, kAfter, kDone } state = kValue;
  while (state != kDone) {
    if (state == kValue) {
      ws();
      if (i >= n) break;
      // Values nested deeper than any file of ours are not indexed (their pointers would make
      // the index quadratic); an error there is reported at the deepest indexed ancestor.
      const bool indexed = stack.size() <= kMaxIndexedDepth;
      if (indexed) places_.push_back({pointer, {key_at == std::string_view::npos ? i : key_at, i}});
      if (!indexed) pointer.clear();
      const char c = t[i];
      if (c == '{' || c == '[') {
        stack.push_back({c == '{', 0, pointer});
        ++i;
        ws();
        if (i < n && (t[i] == '}' || t[i] == ']')) {
          ++i;
          stack.pop_back();
          state = kAfter;
        } else if (c == '{') {
          state = kKey;
        } else {
          pointer = stack.back().pointer + "/0";
          key_at = std::string_view::npos;
        }
      } else {
        if (c == '"') {
          skip_string();
        } else {
          while (i < n && std::string_view(",]} \t\r\n").find(t[i]) == std::string_view::npos) ++i;
        }
        state = kAfter;
      }
    } else if (state == kKey) {
      ws();
      if (i >= n || t[i] != '"') break;
      key_at = i;
      skip_string();
      std::string key;
      try {
        key = nlohmann::json::parse(t.substr(key_at, i - key_at)).get<std::string>();
      } catch (const nlohmann::json::exception&) {
        break;
      }
      ws();
      if (i >= n || t[i] != ':') break;
      ++i;
      pointer = stack.back().pointer + "/" + EscapePointerToken(key);
      state = kValue;
    } else {  // kAfter
      ws();
      if (stack.empty() || i >= n) break;
      if (t[i] == ',') {
        ++i;
        Frame& f = stack.back();
        if (f.object) {
          state = kKey;
        } else {
          pointer = f.pointer + "/" + std::to_string(++f.index);
          key_at = std::string_view::npos;
          state = kValue;
        }
      } else if (t[i] == '}' || t[i] == ']') {
        ++i;
        stack.pop_back();
      } else {
        break;
      }
    }
  }
  return places_;
}

bool JsonDocument::Contains(const std::string& pointer) const {
  for (const auto& [p, place] : Places()) {
    (void)place;
    if (p == pointer) return true;
  }
  return false;
}

std::string JsonDocument::Where(const std::string& pointer) const {
  std::string p = pointer;
  for (;;) {
    // Duplicate keys: nlohmann keeps the last one, so does this search.
    const Place* found = nullptr;
    for (const auto& [q, place] : Places())
      if (q == p) found = &place;
    if (found) return source_ + ":" + TextPosition(text_, found->key);
    if (p.empty()) return source_ + ":1:1";
    p = p.substr(0, p.rfind('/'));
  }
}

std::string JsonDocument::FindSuffix(const std::string& suffix, const std::string& prefix) const {
  for (const auto& [p, place] : Places()) {
    (void)place;
    if (p.size() >= suffix.size() + prefix.size() && p.compare(0, prefix.size(), prefix) == 0 &&
        p.compare(p.size() - suffix.size(), suffix.size(), suffix) == 0)
      return p;
  }
  return "";
}

void JsonDocument::FailValidation(const OptionsError& e, const std::string& pointer) const {
  if (e.rule().empty())
    throw InputError((pointer.empty() ? source_ : Where(pointer)) + ": " + e.what());
  const std::string& rule = e.rule();
  const std::string& value = e.value();
  if (pointer.empty() || !Contains(pointer))
    throw InputError(source_ + ":1:1: " + e.field() + ": expected " + rule + ", found " + value +
                     " (the built-in default)");
  // The dotted name of `pointer`: walk the document so array indices print as [i].
  std::string name;
  const nlohmann::json* j = &json_;
  size_t at = 1;
  while (at <= pointer.size() && j) {
    const size_t next = std::min(pointer.find('/', at), pointer.size());
    std::string token = pointer.substr(at, next - at);
    if (j->is_array()) {
      const size_t k = std::stoul(token);
      name += "[" + token + "]";
      j = k < j->size() ? &(*j)[k] : nullptr;
    } else {
      size_t tilde;
      while ((tilde = token.find("~1")) != std::string::npos) token.replace(tilde, 2, "/");
      while ((tilde = token.find("~0")) != std::string::npos) token.replace(tilde, 2, "~");
      name += (name.empty() ? "" : ".") + token;
      const auto it = j->is_object() ? j->find(token) : j->end();
      j = it != j->end() ? &*it : nullptr;
    }
    at = next + 1;
  }
  throw InputError(Where(pointer) + ": " + name + ": expected " + rule + ", found " + value);
}

nlohmann::ordered_json NumberOrNull(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json VectorJson(const Eigen::VectorXd& v) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) j.push_back(NumberOrNull(v[i]));
  return j;
}

nlohmann::ordered_json MatrixJson(const Eigen::MatrixXd& m) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) j.push_back(VectorJson(m.row(i).transpose()));
  return j;
}

Eigen::VectorXd VectorFromJson(const JsonNode& node, size_t size) {
  node.ExpectArray(size);
  Eigen::VectorXd v(static_cast<Eigen::Index>(node.Size()));
  for (size_t i = 0; i < node.Size(); ++i)
    v[static_cast<Eigen::Index>(i)] = node.Element(i).NumberOrNaN();
  return v;
}

Eigen::MatrixXd MatrixFromJson(const JsonNode& node, size_t rows, size_t cols) {
  node.ExpectArray(rows);
  if (rows == 0 && node.Size() != 0) node.Expected("an empty array");
  Eigen::MatrixXd m(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(cols));
  for (size_t i = 0; i < rows; ++i)
    m.row(static_cast<Eigen::Index>(i)) = VectorFromJson(node.Element(i), cols).transpose();
  return m;
}

Termination TerminationFromJson(const JsonNode& node) {
  const std::string s = node.String();
  for (auto t : {Termination::kConverged, Termination::kBudgetExhausted, Termination::kFailure})
    if (ToString(t) == s) return t;
  node.Expected("a termination (" + ToString(Termination::kConverged) + ", " +
                ToString(Termination::kBudgetExhausted) + " or " +
                ToString(Termination::kFailure) + ")");
}

void ReadOptional(const JsonNode& object, const char* key, double& field) {
  if (object.Has(key)) field = object.Get(key).Number();
}

void ReadOptional(const JsonNode& object, const char* key, int& field) {
  if (object.Has(key))
    field = static_cast<int>(object.Get(key).Integer(std::numeric_limits<int>::min(),
                                                     std::numeric_limits<int>::max()));
}

void ReadOptional(const JsonNode& object, const char* key, bool& field) {
  if (object.Has(key)) field = object.Get(key).Boolean();
}

void ReadOptional(const JsonNode& object, const char* key, std::string& field) {
  if (object.Has(key)) field = object.Get(key).String();
}

void ReadOptional(const JsonNode& object, const char* key, std::uint64_t& field) {
  if (object.Has(key)) field = Uint64FromJson(object.Get(key));
}

void ReadOptional(const JsonNode& object, const char* key, std::vector<double>& field) {
  if (object.Has(key)) field = object.Get(key).Numbers();
}

void ReadOptional(const JsonNode& object, const char* key, std::vector<int>& field) {
  if (!object.Has(key)) return;
  const JsonNode a = object.Get(key);
  a.ExpectArray();
  field.clear();
  for (size_t i = 0; i < a.Size(); ++i)
    field.push_back(static_cast<int>(
        a.Element(i).Integer(std::numeric_limits<int>::min(), std::numeric_limits<int>::max())));
}

nlohmann::ordered_json NamesJson(const std::vector<std::string>& names) { return names; }

void ReadNames(const JsonNode& list, std::vector<std::string>& names) {
  list.ExpectArray();
  names.clear();
  for (size_t i = 0; i < list.Size(); ++i) names.push_back(list.Element(i).String(true));
}

std::uint64_t Uint64FromJson(const JsonNode& node) {
  if (!node.json().is_number_unsigned()) node.Expected("an integer in [0, 2^64 - 1]");
  return node.json().get<std::uint64_t>();
}

void ValidateOptions(const JsonDocument& doc, const std::function<void()>& validate,
                     const std::string& base) {
  try {
    validate();
  } catch (const OptionsError& e) {
    // A rule on one field is placed at that field; any other error at the document's start.
    const std::string field = e.rule().empty() ? std::string() : e.field();
    std::string pointer;
    if (!field.empty()) {
      // "candidates[1].gain" -> "/candidates/1/gain"
      std::string tail;
      for (char c : field) {
        if (c == '.' || c == '[') tail += '/';
        else if (c != ']') tail += c;
      }
      // The field, else the nearest written part of it ("output_range" of "output_range.max").
      while (!tail.empty() && pointer.empty()) {
        if (!base.empty() && doc.Contains(base + "/" + tail)) pointer = base + "/" + tail;
        else if (!base.empty() && !doc.FindSuffix("/" + tail, base + "/").empty())
          pointer = doc.FindSuffix("/" + tail, base + "/");
        else if (doc.Contains("/" + tail)) pointer = "/" + tail;
        else pointer = doc.FindSuffix("/" + tail);
        const size_t cut = tail.rfind('/');
        tail = cut == std::string::npos ? "" : tail.substr(0, cut);
      }
    }
    if (pointer.empty()) throw InputError(doc.source() + ":1:1: " + e.what());
    doc.FailValidation(e, pointer);
  }
}

std::string DumpJson(const nlohmann::ordered_json& j, int indent) {
  return j.dump(indent) + "\n";
}

}  // namespace sysid::internal
