#include "core/json_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "sysid/error.hpp"

namespace sysid::internal {

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

}  // namespace sysid::internal
