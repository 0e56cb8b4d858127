// Argument checks shared by the signal functions (messages name the field and the rule).
#include <fmt/format.h>

#include <cmath>
#include <tuple>

#include "signal/checks.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid::internal {

void CheckSampleInterval(const char* where, double dt_s) {
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    throw OptionsError(
        fmt::format("{}: dt_s = {} s. Violated constraint: dt_s > 0 and finite", where, dt_s),
        "dt_s");
}

void CheckCutoff(const char* where, const char* field, double cutoff_hz, double dt_s) {
  const double nyquist_hz = 0.5 / dt_s;
  if (!(cutoff_hz > 0) || !(cutoff_hz < nyquist_hz))
    throw OptionsError(fmt::format(
                           "{}: {} = {} Hz. Violated constraint: 0 < {} < Nyquist frequency "
                           "0.5/dt_s = {} Hz",
                           where, field, cutoff_hz, field, nyquist_hz),
                       field);
}

void CheckButterworthOrder(const char* where, const char* field, int order) {
  if (order < 1 || order > kMaxButterworthOrder)
    throw OptionsError(fmt::format("{}: {} = {}. Violated constraint: 1 <= {} <= {}", where, field,
                                   order, field, kMaxButterworthOrder),
                       field);
}

void CheckSavitzkyGolay(const char* where, const char* window_field, int window,
                        const char* order_field, int order, int min_order) {
  if (window < 3 || window % 2 == 0)
    throw OptionsError(fmt::format("{}: {} = {}. Violated constraint: {} odd and >= 3", where,
                                   window_field, window, window_field),
                       window_field);
  // The limits that bound the filter's work and memory (sysid/signal.hpp).
  for (const auto& [field, value, limit, name] :
       {std::tuple{window_field, window, kMaxSavitzkyGolayWindow,
                   "kMaxSavitzkyGolayWindow, 10 s at 1 kHz"},
        std::tuple{order_field, order, kMaxSavitzkyGolayOrder, "kMaxSavitzkyGolayOrder"}})
    if (value > limit)
      throw OptionsError(fmt::format("{}: {} = {}. Violated constraint: {} <= {} ({})", where,
                                     field, value, field, limit, name),
                         field);
  if (order < min_order || order >= window)
    throw OptionsError(fmt::format("{}: {} = {}. Violated constraint: {} <= {} < {} = {}", where,
                                   order_field, order, min_order, order_field, window_field,
                                   window),
                       order_field);
}

void CheckLength(const char* where, Eigen::Index n, Eigen::Index min_n, const std::string& why) {
  if (n < min_n)
    throw InputError(
        fmt::format("{}: the signal has {} samples; {} needs at least {}", where, n, why, min_n));
}

void CheckFinite(const char* where, const Eigen::VectorXd& y) {
  if (y.allFinite()) return;  // vectorised; the loop below only locates the culprit
  for (Eigen::Index k = 0; k < y.size(); ++k)
    if (!std::isfinite(y[k]))
      throw InputError(
          fmt::format("{}: sample {} (0-based) is {}; expected a finite number", where, k, y[k]));
}

}  // namespace sysid::internal
