#include "core/json_text.hpp"

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "sysid/error.hpp"

namespace sysid::internal {

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

}  // namespace sysid::internal
