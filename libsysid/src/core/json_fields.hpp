// The JSON of a described struct (sysid/serialize.hpp): one writer and one positioned reader
// for every type that lists its fields in Serialize, so the keys, their order, the allowed keys
// and the reading cannot drift from the struct.
#ifndef SYSID_SRC_CORE_JSON_FIELDS_HPP_
#define SYSID_SRC_CORE_JSON_FIELDS_HPP_

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/json_text.hpp"
#include "sysid/serialize.hpp"

namespace sysid::internal {

/// The JSON of a field type that is not a number, bool, string, list of numbers or described
/// struct (an enum, a list of records, an optional), specialised next to the type's other JSON:
///   static nlohmann::ordered_json Write(const V& value);
///   static void Read(const JsonNode& node, V& value);  // from the key's value, replacing it
/// Left undefined, so a field of a type without one does not compile.
template <class V>
struct JsonForm;

/// The field names of a described struct, in Serialize order.
class FieldNameArchive {
 public:
  template <class V>
  void Visit(const NameValue<V>& nv) {
    names.emplace_back(nv.name());
  }
  std::vector<std::string> names;
};

using ::sysid::IsDescribed;

template <class T>
std::vector<std::string> FieldNamesOf(const T& o) {
  FieldNameArchive a;
  const_cast<T&>(o).Serialize(&a);  // visits the names only
  return std::move(a.names);
}

/// The types ReadOptional reads with its type check (the rules are Validate()'s).
template <class V>
constexpr bool kReadsAsScalar =
    std::is_same_v<V, double> || std::is_same_v<V, int> || std::is_same_v<V, bool> ||
    std::is_same_v<V, std::string> || std::is_same_v<V, std::uint64_t> ||
    std::is_same_v<V, std::vector<double>> || std::is_same_v<V, std::vector<int>>;

template <class T>
nlohmann::ordered_json WriteFields(const T& o);
template <class T>
void ReadFields(const JsonNode& node, T& o, const std::vector<std::string>& allowed_extra = {});

template <class V>
nlohmann::ordered_json FieldJson(const V& v, FieldForm form) {
  if constexpr (IsDescribed<V>::value) {
    return WriteFields(v);
  } else if constexpr (kReadsAsScalar<V>) {
    if constexpr (std::is_same_v<V, double>)
      if (form != FieldForm::kPlain) return NumberOrNull(v);
    return nlohmann::ordered_json(v);
  } else {
    return JsonForm<V>::Write(v);
  }
}

/// Reads `key` of `object` over `v` when the key is present (an absent key keeps the default).
template <class V>
void ReadField(const JsonNode& object, const char* key, V& v, FieldForm form) {
  if constexpr (std::is_same_v<V, double>) {
    if (form != FieldForm::kPlain) {
      if (!object.Has(key)) return;
      const JsonNode node = object.Get(key);
      const double inf = std::numeric_limits<double>::infinity();
      v = node.json().is_null() ? (form == FieldForm::kUpperLimit ? inf : -inf) : node.Number();
      return;
    }
  }
  if constexpr (kReadsAsScalar<V>) {
    ReadOptional(object, key, v);
  } else if (object.Has(key)) {
    if constexpr (IsDescribed<V>::value)
      ReadFields(object.Get(key), v);
    else
      JsonForm<V>::Read(object.Get(key), v);
  }
}

class JsonWriteArchive {
 public:
  template <class V>
  void Visit(const NameValue<V>& nv) {
    json[nv.name()] = FieldJson(*nv.value(), nv.form());
  }
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
};

class JsonReadArchive {
 public:
  explicit JsonReadArchive(const JsonNode& node) : node_(node) {}
  template <class V>
  void Visit(const NameValue<V>& nv) {
    ReadField(node_, nv.name(), *nv.value(), nv.form());
  }

 private:
  const JsonNode& node_;
};

/// The object of T's fields, keys in Serialize order.
template <class T>
nlohmann::ordered_json WriteFields(const T& o) {
  JsonWriteArchive a;
  const_cast<T&>(o).Serialize(&a);  // the writer only reads the fields
  return std::move(a.json);
}

/// Checks `node` is an object of T's keys (plus `allowed_extra`), then reads each present key
/// over `o`'s value.
template <class T>
void ReadFields(const JsonNode& node, T& o, const std::vector<std::string>& allowed_extra) {
  node.ExpectObject(FieldNamesOf(o), allowed_extra);
  JsonReadArchive a(node);
  o.Serialize(&a);
}

/// The text of a described struct (the form of every options struct's ToJson).
template <class T>
std::string FieldsToJson(const T& o, int indent) {
  return DumpJson(WriteFields(o), indent);
}

/// A described options struct from text: its defaults, overwritten by the document's keys, then
/// Validate() (OptionsFromJson).
template <class T>
T FieldsFromJson(std::string_view text, const std::string& source_name) {
  return OptionsFromJson<T>(text, source_name,
                            [](const JsonNode& node, T& o) { ReadFields(node, o); });
}

/// A list of names (fact ids, network inputs): an array of non-empty strings.
template <>
struct JsonForm<std::vector<std::string>> {
  static nlohmann::ordered_json Write(const std::vector<std::string>& names) {
    return NamesJson(names);
  }
  static void Read(const JsonNode& list, std::vector<std::string>& names) {
    ReadNames(list, names);
  }
};

/// A range: [low, high].
template <>
struct JsonForm<std::pair<double, double>> {
  static nlohmann::ordered_json Write(const std::pair<double, double>& r) {
    return nlohmann::ordered_json::array({r.first, r.second});
  }
  static void Read(const JsonNode& node, std::pair<double, double>& r) {
    const std::vector<double> v = node.Numbers(2);
    r = {v[0], v[1]};
  }
};

/// A list of values of a type with a JsonForm (ranges): an array that replaces the list.
template <class V>
struct JsonForm<std::vector<V>> {
  static nlohmann::ordered_json Write(const std::vector<V>& list) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const V& v : list) j.push_back(JsonForm<V>::Write(v));
    return j;
  }
  static void Read(const JsonNode& node, std::vector<V>& list) {
    node.ExpectArray();
    list.assign(node.Size(), V{});
    for (size_t i = 0; i < node.Size(); ++i) JsonForm<V>::Read(node.Element(i), list[i]);
  }
};

/// An optional value: null when unset, and read back from null.
template <class V>
struct JsonForm<std::optional<V>> {
  static nlohmann::ordered_json Write(const std::optional<V>& v) {
    return v ? JsonForm<V>::Write(*v) : nlohmann::ordered_json(nullptr);
  }
  static void Read(const JsonNode& node, std::optional<V>& v) {
    if (node.json().is_null()) {
      v.reset();
    } else {
      V value{};
      JsonForm<V>::Read(node, value);
      v = std::move(value);
    }
  }
};

/// A vector of numbers, NaN as null.
template <>
struct JsonForm<Eigen::VectorXd> {
  static nlohmann::ordered_json Write(const Eigen::VectorXd& v) { return VectorJson(v); }
  static void Read(const JsonNode& node, Eigen::VectorXd& v) { v = VectorFromJson(node); }
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_CORE_JSON_FIELDS_HPP_
