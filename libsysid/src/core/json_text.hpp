// Private: JSON text helpers shared by the model, network and stage file parsers, so that every
// file error names "SOURCE:LINE:COLUMN: key: expected ..., found ..." the same way.
#ifndef SYSID_SRC_CORE_JSON_TEXT_HPP_
#define SYSID_SRC_CORE_JSON_TEXT_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/termination.hpp"

namespace sysid::internal {

/// "LINE:COLUMN" (1-based) of byte offset `pos` in `text`.
std::string TextPosition(std::string_view text, size_t pos);

/// "LINE:COLUMN" where the quoted `key` first appears, searching from the first appearance of
/// the quoted `parent` key when one is given (nested objects); "1:1" when absent.
std::string JsonKeyPosition(std::string_view text, const std::string& key,
                            const std::string& parent = "");

/// Parses `text`; a syntax error throws InputError "SOURCE:LINE:COLUMN: invalid JSON: ...".
nlohmann::json ParseJsonText(std::string_view text, const std::string& source);

/// `s` safe to print on a terminal: control bytes, DEL and NUL become \xHH, and text past
/// `max_chars` is cut with "...". Used wherever an error message quotes file data.
std::string Printable(std::string_view s, size_t max_chars = 80);

/// True when `s` holds a control byte (tab and newline included) or DEL.
bool HasControlByte(std::string_view s);

/// `s` as one line of text: unchanged unless it holds a control byte, then Printable(s), uncut.
/// For metadata, whose values come from users (comments, file names) and are written as
/// "# key: value" lines and printed by `sysid info`.
std::string OneLine(std::string_view s);

/// The accepted range of a number read from a file, with the rule as it is printed
/// ("a number > 0"). Every number must also be finite.
struct NumberRule {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static NumberRule Finite() { return {}; }
  static NumberRule Positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static NumberRule NonNegative() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static NumberRule Closed(double lo, double hi) { return {lo, hi, false, false}; }
  bool Accepts(double v) const;
  std::string Describe() const;  ///< "a number > 0", "a number in [0, 1]", "a finite number"
};

class JsonDocument;

/// One value of a parsed document together with its JSON pointer, so that any complaint about it
/// names the place in the text ("FILE:LINE:COL: rig.sample_rate_hz: expected a number > 0,
/// found 0"). Cheap to copy; valid while its document lives.
class JsonNode {
 public:
  const nlohmann::json& json() const { return *json_; }
  const std::string& pointer() const { return pointer_; }
  /// Dotted name of the value for messages: "rig.sample_rate_hz", "inputs[0].min", "(top)".
  const std::string& Name() const { return name_; }
  /// Throws InputError "SOURCE:LINE:COL: NAME: what" at this value's key (or the value itself
  /// for array elements and the root).
  [[noreturn]] void Fail(const std::string& what) const;
  /// Throws "...: NAME: expected <expected>, found <what this value is>".
  [[noreturn]] void Expected(const std::string& expected) const;

  bool Has(const std::string& key) const;
  /// A required member: the object must hold `key`, else "NAME: missing required key 'key'"
  /// at this object. This node must be an object (checked).
  JsonNode Get(const std::string& key) const;
  size_t Size() const { return json_->size(); }
  JsonNode Element(size_t index) const;

  /// Checks this is an object and every key is in `known` or starts with '_' (comments).
  /// `allowed_extra` keys ride along unread (reports, notes).
  void ExpectObject(const std::vector<std::string>& known,
                    const std::vector<std::string>& allowed_extra = {}) const;
  /// Checks this is an array with `size` elements (any size when 0, at least one when
  /// `non_empty`).
  void ExpectArray(size_t size = 0, bool non_empty = false) const;
  double Number(const NumberRule& rule = NumberRule::Finite()) const;
  /// A number, or null read as NaN (results write a quantity that does not exist as null).
  double NumberOrNaN(const NumberRule& rule = NumberRule::Finite()) const;
  bool Boolean() const;
  long Integer(long lo, long hi) const;
  std::string String(bool non_empty = false) const;
  std::vector<double> Numbers(size_t size = 0, const NumberRule& rule = NumberRule::Finite()) const;

 private:
  friend class JsonDocument;
  JsonNode(const JsonDocument* doc, const nlohmann::json* json, std::string pointer,
           std::string name)
      : doc_(doc), json_(json), pointer_(std::move(pointer)), name_(std::move(name)) {}
  const JsonDocument* doc_;
  const nlohmann::json* json_;
  std::string pointer_;
  std::string name_;
};

/// The names of `values` as a message lists them: "\"a\", \"b\" or \"c\"" when `quoted`,
/// else "a, b or c".
template <class E, class NameOf>
std::string ListNames(std::initializer_list<E> values, NameOf name_of, bool quoted) {
  std::string list;
  size_t i = 0;
  for (E value : values) {
    if (i > 0) list += (i + 1 == values.size()) ? " or " : ", ";
    const std::string name = name_of(value);
    list += quoted ? "\"" + name + "\"" : name;
    ++i;
  }
  return list;
}

/// The one of `values` whose name (`name_of`, the writer's: ToString) is `node`'s string, so an
/// enum's reader and writer share one list. Anything else is "expected \"a\", \"b\" or \"c\"",
/// or with `what` "expected a trainer (lm or ceres)".
template <class E, class NameOf>
E ReadName(const JsonNode& node, std::initializer_list<E> values, NameOf name_of,
           const char* what = nullptr) {
  const std::string s = node.String();
  for (E value : values)
    if (name_of(value) == s) return value;
  node.Expected(what ? std::string(what) + " (" + ListNames(values, name_of, false) + ")"
                     : ListNames(values, name_of, true));
}

/// A parsed JSON file that can say where each of its values is written.
class JsonDocument {
 public:
  /// Parses `text` (kept by reference: it must outlive the document); syntax errors and numbers
  /// beyond double range throw a positioned InputError.
  JsonDocument(std::string_view text, std::string source);
  JsonNode Root() const { return JsonNode(this, &json_, "", "(top)"); }
  const std::string& source() const { return source_; }

  /// "SOURCE:LINE:COL" of the key of the member at JSON pointer `pointer` (of the value for
  /// array elements); the nearest ancestor that is written in the text when it is not.
  std::string Where(const std::string& pointer) const;
  /// True when the value at `pointer` is written in the text.
  bool Contains(const std::string& pointer) const;
  /// The pointer of a written value whose pointer ends with `suffix` ("/sample_rate_hz",
  /// "/forward/coulomb_mps2") and starts with `prefix`; empty when none.
  std::string FindSuffix(const std::string& suffix, const std::string& prefix = "") const;

  /// Re-throws a Validate() error as a positioned InputError "SOURCE:LINE:COL: NAME: expected
  /// RULE, found VALUE" from its members (OptionsError::rule(), value()), where `pointer` is
  /// the JSON pointer of its field(); at "SOURCE:1:1" marked "(the built-in default)" when the
  /// field is not written in the file. An error without a rule keeps its message, placed at
  /// `pointer` (the file when empty).
  [[noreturn]] void FailValidation(const OptionsError& e, const std::string& pointer) const;

 private:
  struct Place {
    size_t key;    // offset of the key's quote (of the value for elements and the root)
    size_t value;  // offset of the value
  };
  const std::vector<std::pair<std::string, Place>>& Places() const;

  std::string_view text_;
  std::string source_;
  nlohmann::json json_;
  mutable std::vector<std::pair<std::string, Place>> places_;  // built on the first error
  mutable bool indexed_ = false;
};

/// `v`, or null when it is not finite (JSON has no NaN or infinity).
nlohmann::ordered_json NumberOrNull(double v);
/// A vector or matrix (rows of arrays) of numbers, NaN as null.
nlohmann::ordered_json VectorJson(const Eigen::VectorXd& v);
nlohmann::ordered_json MatrixJson(const Eigen::MatrixXd& m);
/// The inverses: numbers or null (NaN); a matrix must be rows x cols.
Eigen::VectorXd VectorFromJson(const JsonNode& node, size_t size = 0);
Eigen::MatrixXd MatrixFromJson(const JsonNode& node, size_t rows, size_t cols);

/// A Termination written by ToString ("converged", ...); anything else is a positioned error.
Termination TerminationFromJson(const JsonNode& node);

// ---- Options objects ----
// An options object's keys are all optional: an absent key keeps the field's value (the
// default), so a file names only what it changes. Values are checked for type here and for
// their rules by the struct's Validate() (ValidateOptions).
void ReadOptional(const JsonNode& object, const char* key, double& field);
/// An int in [INT_MIN, INT_MAX]; the rule is Validate()'s.
void ReadOptional(const JsonNode& object, const char* key, int& field);
void ReadOptional(const JsonNode& object, const char* key, bool& field);
void ReadOptional(const JsonNode& object, const char* key, std::string& field);
void ReadOptional(const JsonNode& object, const char* key, std::uint64_t& field);
void ReadOptional(const JsonNode& object, const char* key, std::vector<double>& field);
void ReadOptional(const JsonNode& object, const char* key, std::vector<int>& field);
/// A list of names (fact ids, network inputs): written as an array of strings, read as an array
/// of non-empty strings that replaces the list (JsonForm<std::vector<std::string>>).
nlohmann::ordered_json NamesJson(const std::vector<std::string>& names);
void ReadNames(const JsonNode& list, std::vector<std::string>& names);
/// A uint64 (a seed): JsonNode::Integer reads longs.
std::uint64_t Uint64FromJson(const JsonNode& node);
/// Runs `validate` (an options struct's Validate()); its OptionsError with a rule becomes an
/// InputError at the place of its field() in `doc` (FailValidation): the
/// top-level key when written there, else the first nested key of that name, else the
/// document's start with the message as it is. `base` (a JSON pointer such as
/// "/facts_options") is where the validated struct sits when it is nested: its keys are looked
/// up there first, so a key of the same name elsewhere does not take the error.
void ValidateOptions(const JsonDocument& doc, const std::function<void()>& validate,
                     const std::string& base = "");

/// The reader of an options struct T from text: its defaults, overwritten by the document's
/// keys through `read` (which checks keys and types), then T::Validate() (ValidateOptions).
template <class T, class Read>
T OptionsFromJson(std::string_view text, const std::string& source_name, Read read) {
  const JsonDocument doc(text, source_name);
  T options;
  read(doc.Root(), options);
  ValidateOptions(doc, [&] { options.Validate(); });
  return options;
}

/// Text of a library result object: `j` dumped with `indent` and a final newline (the form of
/// ModelToJson).
std::string DumpJson(const nlohmann::ordered_json& j, int indent);

}  // namespace sysid::internal

#endif  // SYSID_SRC_CORE_JSON_TEXT_HPP_
