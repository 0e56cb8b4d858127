// Argument checks shared by the signal functions (messages name the field and the rule).
#include "signal/checks.hpp"

#include <fmt/format.h>

#include <cmath>
#include <tuple>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid::internal {

void CheckSampleInterval(const char* where, double dt_s) {
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    FailOption(where, "dt_s", fmt::format("{} s", dt_s), "dt_s > 0 and finite");
}

void CheckCutoff(const char* where, const char* field, double cutoff_hz, double dt_s) {
  const double nyquist_hz = 0.5 / dt_s;
  if (!(cutoff_hz > 0) || !(cutoff_hz < nyquist_hz))
    FailOption(where, field, fmt::format("{} Hz", cutoff_hz),
               fmt::format("0 < {} < Nyquist frequency 0.5/dt_s = {} Hz", field, nyquist_hz));
}

void CheckButterworthOrder(const char* where, const char* field, int order) {
  if (order < 1 || order > kMaxButterworthOrder)
    FailOption(where, field, order, fmt::format("1 <= {} <= {}", field, kMaxButterworthOrder));
}

void CheckSavitzkyGolay(const char* where, const char* window_field, int window,
                        const char* order_field, int order, int min_order) {
  if (window < 3 || window % 2 == 0)
    FailOption(where, window_field, window, fmt::format("{} odd and >= 3", window_field));
  // The limits that bound the filter's work and memory (sysid/signal.hpp).
  for (const auto& [field, value, limit, name] :
       {std::tuple{window_field, window, kMaxSavitzkyGolayWindow,
                   "kMaxSavitzkyGolayWindow, 10 s at 1 kHz"},
        std::tuple{order_field, order, kMaxSavitzkyGolayOrder, "kMaxSavitzkyGolayOrder"}})
    if (value > limit)
      FailOption(where, field, value, fmt::format("{} <= {} ({})", field, limit, name));
  if (order < min_order || order >= window)
    FailOption(where, order_field, order,
               fmt::format("{} <= {} < {} = {}", min_order, order_field, window_field, window));
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
