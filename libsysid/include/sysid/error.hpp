// Error types of libsysid. Bad input (files, data, options) throws a subclass of sysid::Error
// whose message reads like a compiler's: "runs/p3.csv:128:3: column 'u': expected a number,
// found \"1,2e\"". Non-convergence is not an exception: it is a termination value and a message
// in the algorithm's result.
#ifndef SYSID_ERROR_HPP_
#define SYSID_ERROR_HPP_

#include <stdexcept>
#include <string>
#include <utility>

namespace sysid {

/// Base of every error libsysid throws on purpose.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Bad input data: a recording, a model file, a table. The CLI exits with code 2.
class InputError : public Error {
 public:
  using Error::Error;
};

/// An option that violates its documented rule. The CLI exits with code 1 (usage).
/// A rule on one field carries its parts as members: `owner()` (the options struct,
/// "NeuralTrainingOptions"; may be empty), `field()` (a dotted path such as
/// "candidates[1].gain"), `value()` (as text) and `rule()`, so a caller can position or rename
/// the error (a JSON file's FILE:LINE:COL, a command-line flag) without parsing the message.
/// Errors that are no rule on one field have an empty `rule()` and maybe a `field()`.
class OptionsError : public Error {
 public:
  using Error::Error;
  OptionsError(const std::string& message, std::string field)
      : Error(message), field_(std::move(field)) {}
  /// A rule on one field; the message reads "OWNER::FIELD = VALUE. Violated constraint: RULE"
  /// ("FIELD = VALUE. ..." without an owner). Library code raises it through
  /// internal::FailOption (core/option_rule.hpp), which formats the value.
  OptionsError(std::string owner, std::string field, std::string value, std::string rule)
      : Error(Compose(owner, field, value, rule)),
        owner_(std::move(owner)),
        field_(std::move(field)),
        value_(std::move(value)),
        rule_(std::move(rule)) {}

  const std::string& owner() const { return owner_; }  ///< empty when not given
  const std::string& field() const { return field_; }  ///< empty when not given
  const std::string& value() const { return value_; }  ///< empty when not a rule
  const std::string& rule() const { return rule_; }    ///< empty when not a rule

  /// The same error (members kept) with another message: context added to it ("--hidden: " +
  /// what()) or a path in it replaced.
  OptionsError WithMessage(const std::string& message) const {
    OptionsError e(*this);
    static_cast<Error&>(e) = Error(message);
    return e;
  }

 private:
  static std::string Compose(const std::string& owner, const std::string& field,
                             const std::string& value, const std::string& rule) {
    return (owner.empty() ? "" : owner + "::") + field + " = " + value +
           ". Violated constraint: " + rule;
  }
  std::string owner_;
  std::string field_;
  std::string value_;
  std::string rule_;
};

/// Numerical trouble that leaves no usable answer (singular system, unidentifiable
/// parameters, NaN). The CLI exits with code 3.
class NumericalError : public Error {
 public:
  using Error::Error;
};

/// A broken internal invariant (a bug in libsysid, never the user's fault).
class InternalError : public Error {
 public:
  using Error::Error;
};

namespace internal {
[[noreturn]] void ThrowInternal(const char* condition, const char* file, int line,
                                const std::string& detail);
}  // namespace internal

}  // namespace sysid

/// Throws sysid::InternalError with the condition, file:line and an optional detail string.
#define SYSID_CHECK(condition, detail)                                              \
  do {                                                                              \
    if (!(condition))                                                               \
      ::sysid::internal::ThrowInternal(#condition, __FILE__, __LINE__, (detail));   \
  } while (false)

#endif  // SYSID_ERROR_HPP_
