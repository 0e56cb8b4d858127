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
/// `field()` names the offending options field (e.g. "cutoff_hz") when the thrower knows it, so
/// a caller can name its own spelling of it (a command-line flag) without parsing the message.
class OptionsError : public Error {
 public:
  using Error::Error;
  OptionsError(const std::string& message, std::string field)
      : Error(message), field_(std::move(field)) {}
  const std::string& field() const { return field_; }  ///< empty when not given

 private:
  std::string field_;
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
