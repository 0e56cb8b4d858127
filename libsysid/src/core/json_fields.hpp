// The JSON of a described struct (sysid/serialize.hpp): one writer and one positioned reader
// for every type that lists its fields in Serialize, so the keys, their order, the allowed keys
// and the reading cannot drift from the struct.
#ifndef SYSID_SRC_CORE_JSON_FIELDS_HPP_
#define SYSID_SRC_CORE_JSON_FIELDS_HPP_

#include <cstdint>
#include <limits>
#include <optional>
#include <stdexcept>
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

class FieldNameArchive;

using ::sysid::IsDescribed;

/// The types ReadOptional reads with its type check (the rules are Validate()'s).
template <class V>
constexpr bool kReadsAsScalar =
    std::is_same_v<V, double> || std::is_same_v<V, int> || std::is_same_v<V, long> ||
    std::is_same_v<V, bool> || std::is_same_v<V, std::string> ||
    std::is_same_v<V, std::uint64_t> || std::is_same_v<V, std::vector<double>> ||
    std::is_same_v<V, std::vector<int>>;

template <class T>
nlohmann::ordered_json WriteFields(const T& o);
template <class T>
void ReadFields(const JsonNode& node, T& o, const std::vector<std::string>& allowed_extra = {});

template <class V>
struct IsList : std::false_type {};
template <class V>
struct IsList<std::vector<V>> : std::true_type {};

template <class V>
struct IsPairList : std::false_type {};
template <class A, class B>
struct IsPairList<std::vector<std::pair<A, B>>> : std::true_type {};
/// A list of pairs that only PairKeys can write: a pair of numbers alone has a JsonForm.
template <class V>
constexpr bool kNeedsPairKeys =
    IsPairList<V>::value && !std::is_same_v<V, std::vector<std::pair<double, double>>>;

/// One side of a pair written as an object (NameValue::PairKeys): a name, or a number with NaN
/// as null.
inline nlohmann::ordered_json PairSideJson(const std::string& s) { return s; }
inline nlohmann::ordered_json PairSideJson(double v) { return NumberOrNull(v); }
inline void ReadPairSide(const JsonNode& node, std::string& s) { s = node.String(); }
inline void ReadPairSide(const JsonNode& node, double& v) { v = node.NumberOrNaN(); }

template <class V>
nlohmann::ordered_json FieldJson(const NameValue<V>& nv) {
  const V& v = *nv.value();
  if constexpr (IsDescribed<V>::value) {
    return WriteFields(v);
  } else if constexpr (kReadsAsScalar<V>) {
    if constexpr (std::is_same_v<V, double>)
      if (nv.form() != FieldForm::kPlain) return NumberOrNull(v);
    return nlohmann::ordered_json(v);
  } else {
    if constexpr (IsPairList<V>::value) {
      if (nv.first_key() != nullptr) {
        nlohmann::ordered_json list = nlohmann::ordered_json::array();
        for (const auto& [first, second] : v)
          list.push_back(
              {{nv.first_key(), PairSideJson(first)}, {nv.second_key(), PairSideJson(second)}});
        return list;
      }
    }
    if constexpr (kNeedsPairKeys<V>)
      throw std::logic_error(std::string(nv.name()) + ": a list of pairs needs PairKeys");
    else
      return JsonForm<V>::Write(v);
  }
}

/// An integer field's range: the field's Minimum and Maximum within its type's.
template <class V>
long IntegerBound(double bound) {
  const long lo = static_cast<long>(std::numeric_limits<V>::min());
  const long hi = static_cast<long>(std::numeric_limits<V>::max());
  if (bound <= static_cast<double>(lo)) return lo;
  if (bound >= static_cast<double>(hi)) return hi;
  return static_cast<long>(bound);
}

/// Reads the field's key of `object` over its value when the key is present (an absent key keeps
/// the value, or is an error when the field is Required).
template <class V>
void ReadField(const JsonNode& object, const NameValue<V>& nv) {
  const char* key = nv.name();
  V& v = *nv.value();
  if (!object.Has(key)) {
    if (nv.required()) object.Get(key);  // throws "missing required key"
    return;
  }
  const JsonNode node = object.Get(key);
  if constexpr (std::is_same_v<V, double>) {
    const NumberRule rule{nv.lo(), nv.hi(), nv.lo_open(), false};
    const double inf = std::numeric_limits<double>::infinity();
    if (nv.form() == FieldForm::kNaNAsNull)
      v = node.NumberOrNaN(rule);
    else if (nv.form() != FieldForm::kPlain && node.json().is_null())
      v = nv.form() == FieldForm::kUpperLimit ? inf : -inf;
    else
      v = node.Number(rule);
  } else if constexpr (std::is_same_v<V, int> || std::is_same_v<V, long>) {
    v = static_cast<V>(node.Integer(IntegerBound<V>(nv.lo()), IntegerBound<V>(nv.hi())));
  } else if constexpr (kReadsAsScalar<V>) {
    ReadOptional(object, key, v);
  } else if constexpr (IsDescribed<V>::value) {
    ReadFields(node, v);
  } else {
    if constexpr (IsPairList<V>::value) {
      if (nv.first_key() != nullptr) {
        node.ExpectArray();
        v.assign(node.Size(), {});
        for (size_t i = 0; i < node.Size(); ++i) {
          const JsonNode e = node.Element(i);
          e.ExpectObject({nv.first_key(), nv.second_key()});
          ReadPairSide(e.Get(nv.first_key()), v[i].first);
          ReadPairSide(e.Get(nv.second_key()), v[i].second);
        }
        return;
      }
    }
    if constexpr (kNeedsPairKeys<V>)
      throw std::logic_error(std::string(nv.name()) + ": a list of pairs needs PairKeys");
    else
      JsonForm<V>::Read(node, v);
  }
}

/// The field names of a described struct, in Serialize order (an Inline struct's in its place).
class FieldNameArchive {
 public:
  template <class V>
  void Visit(const NameValue<V>& nv) {
    if constexpr (IsDescribed<V>::value)
      if (nv.inlined()) return nv.value()->Serialize(this);
    names.emplace_back(nv.name());
  }
  std::vector<std::string> names;
};

template <class T>
std::vector<std::string> FieldNamesOf(const T& o) {
  FieldNameArchive a;
  const_cast<T&>(o).Serialize(&a);  // visits the names only
  return std::move(a.names);
}

/// The "units" object of a struct whose fields state them (NameValue::Unit), in field order.
class UnitArchive {
 public:
  template <class V>
  void Visit(const NameValue<V>& nv) {
    if (nv.unit() != nullptr) json[nv.name()] = nv.unit();
  }
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
};

template <class T>
nlohmann::ordered_json FieldUnits(const T& o) {
  UnitArchive a;
  const_cast<T&>(o).Serialize(&a);  // visits the names only
  return std::move(a.json);
}

class JsonWriteArchive {
 public:
  template <class V>
  void Visit(const NameValue<V>& nv) {
    if constexpr (IsDescribed<V>::value)
      if (nv.inlined()) return nv.value()->Serialize(this);
    if constexpr (IsList<V>::value || std::is_same_v<V, std::string>)
      if (nv.omit_empty() && nv.value()->empty()) return;
    json[nv.name()] = FieldJson(nv);
  }
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
};

class JsonReadArchive {
 public:
  explicit JsonReadArchive(const JsonNode& node) : node_(node) {}
  template <class V>
  void Visit(const NameValue<V>& nv) {
    if constexpr (IsDescribed<V>::value)
      if (nv.inlined()) return nv.value()->Serialize(this);
    ReadField(node_, nv);
  }

 private:
  const JsonNode& node_;
};

/// The object of T's fields, keys in Serialize order, then the "units" of those that state one.
template <class T>
nlohmann::ordered_json WriteFields(const T& o) {
  JsonWriteArchive a;
  const_cast<T&>(o).Serialize(&a);  // the writer only reads the fields
  nlohmann::ordered_json units = FieldUnits(o);
  if (!units.empty()) a.json["units"] = std::move(units);
  return std::move(a.json);
}

/// Checks `node` is an object of T's keys (plus `allowed_extra`, and "units" when its fields
/// state them: read by no one), then reads each present key over `o`'s value.
template <class T>
void ReadFields(const JsonNode& node, T& o, const std::vector<std::string>& allowed_extra) {
  std::vector<std::string> extra = allowed_extra;
  if (!FieldUnits(o).empty()) extra.emplace_back("units");
  node.ExpectObject(FieldNamesOf(o), extra);
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

/// A list of described structs or of values of a type with a JsonForm (ranges): an array that
/// replaces the list.
template <class V>
struct JsonForm<std::vector<V>> {
  static nlohmann::ordered_json Write(const std::vector<V>& list) {
    nlohmann::ordered_json j = nlohmann::ordered_json::array();
    for (const V& v : list) {
      if constexpr (IsDescribed<V>::value)
        j.push_back(WriteFields(v));
      else
        j.push_back(JsonForm<V>::Write(v));
    }
    return j;
  }
  static void Read(const JsonNode& node, std::vector<V>& list) {
    node.ExpectArray();
    list.assign(node.Size(), V{});
    for (size_t i = 0; i < node.Size(); ++i) {
      if constexpr (IsDescribed<V>::value)
        ReadFields(node.Element(i), list[i]);
      else
        JsonForm<V>::Read(node.Element(i), list[i]);
    }
  }
};

/// A termination: its name (ToString).
template <>
struct JsonForm<Termination> {
  static nlohmann::ordered_json Write(const Termination& t) { return ToString(t); }
  static void Read(const JsonNode& node, Termination& t) { t = TerminationFromJson(node); }
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
