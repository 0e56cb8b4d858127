// The one fractional-sample delay of the library (analytic inverse and its streaming stepper,
// trajectory regressors, dominance terms): y(t_k - tau) on the signal's own grid, as a batch
// (DelaySignal) and streaming (DelayLine), both through one split of tau and one interpolation.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/signal.hpp"

namespace sysid {

namespace {

// The rule both forms share: tau / dt = w + f samples, and y(t_k - tau) = (1 - f) y_{k-w} +
// f y_{k-w-1}.
struct DelaySplit {
  double whole = 0;  // w, as a double (it may exceed any integer type)
  double frac = 0;   // f in [0, 1)
};
DelaySplit SplitDelay(double dt_s, double tau_s) {
  const double shift = tau_s / dt_s;  // delay in samples, possibly fractional
  const double whole = std::floor(shift);
  return {whole, shift - whole};
}
double Interpolate(double y_hi, double y_lo, double frac) {
  return (1 - frac) * y_hi + frac * y_lo;
}

void CheckDelay(double dt_s, double tau_s) {
  if (!(dt_s > 0) || !(tau_s >= 0) || !std::isfinite(tau_s))
    internal::FailOption(
        "DelaySignal", !(dt_s > 0) ? "dt_s" : "tau_s",
        fmt::format("{} s (dt_s = {} s, tau_s = {} s)", !(dt_s > 0) ? dt_s : tau_s, dt_s, tau_s),
        "dt_s > 0, tau_s >= 0 and finite");
}

}  // namespace

DelayLine::DelayLine(double dt_s, double tau_s, long long max_pushes) {
  CheckDelay(dt_s, tau_s);
  const DelaySplit split = SplitDelay(dt_s, tau_s);
  const double whole = split.whole;
  frac_ = split.frac;
  // Past max_pushes every read is before the first sample: a shorter line gives the same values.
  const double cap = max_pushes >= 0 ? static_cast<double>(max_pushes) : whole;
  const double used = std::min(whole, cap);
  if (used + 2 > static_cast<double>(kMaxDelayLineSamples))
    internal::FailOption(
        "DelayLine", "tau_s", fmt::format("{} samples of dt_s", tau_s / dt_s),
        fmt::format("tau_s / dt_s + 2 <= {} (kMaxDelayLineSamples)", kMaxDelayLineSamples));
  whole_ = static_cast<long long>(used);
  ring_.assign(static_cast<size_t>(whole_ + 2), 0.0);
}

void DelayLine::Reset() {
  head_ = 0;
  count_ = 0;
}

double DelayLine::Push(double y_k) {
  const long long size = static_cast<long long>(ring_.size());
  if (count_ == 0) first_ = y_k;
  ring_[static_cast<size_t>(head_)] = y_k;
  // y_{k-w} and y_{k-w-1}: w and w + 1 slots behind the newest (k = count_).
  auto at = [&](long long back) {
    if (count_ < back) return first_;
    long long slot = head_ - back;
    if (slot < 0) slot += size;
    return ring_[static_cast<size_t>(slot)];
  };
  const double y_hi = at(whole_), y_lo = at(whole_ + 1);
  if (++head_ == size) head_ = 0;
  if (count_ < whole_ + 2) ++count_;
  return Interpolate(y_hi, y_lo, frac_);
}

Eigen::VectorXd DelaySignal(const Eigen::VectorXd& y, double dt_s, double tau_s,
                            DelayStart start) {
  Eigen::VectorXd out;
  DelaySignal(y, dt_s, tau_s, start, &out);
  return out;
}

void DelaySignal(const Eigen::VectorXd& y, double dt_s, double tau_s, DelayStart start,
                 Eigen::VectorXd* result) {
  SYSID_CHECK(result != &y, "DelaySignal: out must not alias y");
  CheckDelay(dt_s, tau_s);
  // DelayLine's rule on the whole signal at once (random access: no ring, no allocation beyond
  // `out`); the tests hold the two forms equal bit for bit.
  const DelaySplit split = SplitDelay(dt_s, tau_s);
  const Eigen::Index n = y.size();
  const auto whole = static_cast<Eigen::Index>(std::min(split.whole, static_cast<double>(n)));
  const double frac = split.frac;
  Eigen::VectorXd& out = *result;
  out.resize(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    // y(t_k - tau) lies between samples k - whole - 1 and k - whole.
    const Eigen::Index hi = k - whole, lo = hi - 1;
    if (start == DelayStart::kNaN && (hi < 0 || (hi == 0 && frac > 0))) {
      out[k] = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    out[k] = Interpolate(y[std::max<Eigen::Index>(hi, 0)], y[std::max<Eigen::Index>(lo, 0)], frac);
  }
}

}  // namespace sysid
