// The causal inverse of a Prandtl–Ishlinskii model, one sample at a time.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/option_rule.hpp"
#include "pi_terms.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_stepper.hpp"

namespace sysid {

PiInverseStepper::PiInverseStepper(const PrandtlIshlinskiiModel& model, double dt_s)
    : dt_s_(dt_s) {
  if (!model.invertible())
    throw NumericalError(model.kind() + " model not invertible: " + model.why_not_invertible());
  const PiParameters& p = model.pi();
  const double span = p.input_max_v - p.input_min_v;
  lo_ = p.input_min_v - model.range_margin() * span;
  hi_ = p.input_max_v + model.range_margin() * span;
  offset_m_ = p.offset_m;
  closed_form_ = p.form == PiForm::kClassical;
  // Through the constructor: the inverse parameters pass the same rules as any model's.
  p_ = closed_form_ ? PrandtlIshlinskiiModel(model.InverseParameters()).pi() : p;
  if (p.form == PiForm::kRateDependent) {
    if (!(dt_s > 0) || !std::isfinite(dt_s))
      internal::FailOption("Invert", "dt_s", dt_s, "dt_s > 0");
    // An error e in u_{k-1} moves the next step's rate by e/dt and its output by up to
    // (q0 |u| + sum q_i |z_i|) e / dt, which u_k undoes at the slope p0: the inverse's errors
    // grow by that gain per step. Refuse when it reaches 1 on the input range.
    const double level = std::max(std::abs(lo_), std::abs(hi_));
    double q_sum = 0;
    for (double q : p.rate_weights) q_sum += q;
    const double gain = q_sum * level / (dt_s * p.polynomial[0]);
    if (!(gain < 1))
      throw NumericalError(fmt::format(
          "rdpi model not invertible at dt = {:.6g} s: rate_weights: the inverse's error gain "
          "(q_0 + ... + q_n) max|u| / (dt p0) = {:.3g} >= 1 (an error in one step's input "
          "feeds the next step's rate and grows); sample slower or fit with smaller rate weights",
          dt_s, gain));
  }
  z0_ = internal::InitialState(p_);
  Reset();
}

void PiInverseStepper::Reset() {
  z_ = z0_;  // same size: no allocation after construction
  u1_ = u2_ = 0;
  k_ = 0;
  saturation_ = {};
}

double PiInverseStepper::Step(double x_ref_m) {
  const internal::PiLayout l = internal::LayoutOf(p_);
  saturation_ = {};
  double u = 0;
  if (closed_form_) {
    u = internal::PiOutputStep(p_, l, x_ref_m - offset_m_, 0.0, z_.data());
    if (!(u >= lo_ && u <= hi_)) {
      saturation_.saturated = true;
      saturation_.needed_u_v = u;
      u = u > hi_ ? hi_ : lo_;  // NaN (an overflowing sum) to lo: a defined output
    }
    return u;
  }
  const double rho = l.rate() && k_ >= 2 ? std::abs(u1_ - u2_) / dt_s_ : 0.0;
  auto output = [&](double uk) { return internal::PiTrialOutput(p_, l, uk, rho, z_.data()); };
  double a = lo_, b = hi_;
  const double y = x_ref_m;
  const double y_lo = output(a), y_hi = output(b);
  if (y_lo > y || y_hi < y || !(y == y)) {
    saturation_.saturated = true;
    saturation_.above = !(y_lo > y);
    saturation_.bound_output_m = saturation_.above ? y_hi : y_lo;
    u = saturation_.above ? b : a;
  } else {
    // Bisection on the bracket to adjacent doubles: the function is monotone but only piecewise
    // smooth (kinks where operators start or stop moving), and 64 halvings of a finite bracket
    // reach the last bit.
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (a + b);
      if (mid <= a || mid >= b) break;
      (output(mid) < y ? a : b) = mid;
    }
    const double ua = output(a), ub = output(b);
    u = (y - ua <= ub - y) ? a : b;
  }
  for (size_t i = 0; i < z_.size(); ++i) z_[i] = PlayStep(u, p_.thresholds[i], z_[i]);
  u2_ = u1_;
  u1_ = u;
  ++k_;
  return u;
}

}  // namespace sysid
