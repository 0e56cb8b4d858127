// The Prandtl–Ishlinskii model: parameters' rules, simulation and the inverses (closed form for
// the classical model, a bracketed monotone solve per sample for the others).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/option_rule.hpp"
#include "pi_terms.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_stepper.hpp"

namespace sysid {
namespace {

[[noreturn]] void Fail(const std::string& field, double value, const std::string& rule) {
  internal::FailOption("PiParameters", field, value, rule);
}

void RequireFinite(const std::vector<double>& v, const std::string& name) {
  for (size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) Fail(fmt::format("{}[{}]", name, i), v[i], "a finite number");
}

// The input polynomial's slope dP/du = sum_j j a_j u^(j-1) [m/V].
double PolynomialSlope(const std::vector<double>& a, double u) {
  double slope = 0, power = 1;
  for (size_t j = 0; j < a.size(); ++j, power *= u) slope += static_cast<double>(j + 1) * a[j] * power;
  return slope;
}

// Grid over the widened input range for the polynomial's slope (gpi): 2001 points resolve a
// quartic's sign changes far below the range's span.
constexpr int kSlopeGrid = 2001;

}  // namespace

void PiParameters::Validate() const {
  const size_t n = thresholds.size();
  if (n > static_cast<size_t>(kMaxPlayOperators))
    Fail("thresholds", static_cast<double>(n),
         fmt::format("at most {} operators (kMaxPlayOperators)", kMaxPlayOperators));
  for (size_t i = 0; i < n; ++i) {
    const std::string f = fmt::format("thresholds[{}]", i);
    if (!std::isfinite(thresholds[i]) || !(thresholds[i] > 0)) Fail(f, thresholds[i], f + " > 0 [V], finite");
    if (i > 0 && !(thresholds[i] > thresholds[i - 1]))
      Fail(f, thresholds[i],
           fmt::format("{} > thresholds[{}] = {} (strictly increasing)", f, i - 1, thresholds[i - 1]));
  }
  if (weights.size() != n)
    Fail("weights", static_cast<double>(weights.size()), fmt::format("one weight per threshold ({})", n));
  RequireFinite(weights, "weights");
  const size_t m = polynomial.size();
  if (form == PiForm::kPolynomial ? (m < 2 || m > 5) : m != 1)
    Fail("polynomial", static_cast<double>(m),
         form == PiForm::kPolynomial ? "gpi: 2 to 5 coefficients a_1..a_m"
                                     : "pi, rdpi: one coefficient (p0)");
  RequireFinite(polynomial, "polynomial");
  if (form == PiForm::kRateDependent ? rate_weights.size() != n + 1 : !rate_weights.empty())
    Fail("rate_weights", static_cast<double>(rate_weights.size()),
         form == PiForm::kRateDependent ? fmt::format("rdpi: n + 1 = {} values q_0..q_n", n + 1)
                                        : "empty unless the form is rdpi");
  RequireFinite(rate_weights, "rate_weights");
  if (!std::isfinite(offset_m)) Fail("offset_m", offset_m, "a finite number");
  if (!std::isfinite(initial_input_v)) Fail("initial_input_v", initial_input_v, "a finite number");
  if (!initial_state.empty()) {
    if (initial_state.size() != n)
      Fail("initial_state", static_cast<double>(initial_state.size()),
           fmt::format("empty or one state per threshold ({})", n));
    // States some input history reaches: |z_i - z_{i-1}| <= r_i - r_{i-1} (z_{-1} the
    // initial input, r_{-1} = 0); 1e-12 relative for rounding.
    for (size_t i = 0; i < n; ++i) {
      const double previous = i == 0 ? initial_input_v : initial_state[i - 1];
      const double band = thresholds[i] - (i == 0 ? 0.0 : thresholds[i - 1]);
      if (!std::isfinite(initial_state[i]) ||
          std::abs(initial_state[i] - previous) >
              band + 1e-12 * (thresholds[i] + std::abs(previous)))
        Fail(fmt::format("initial_state[{}]", i), initial_state[i],
             i == 0 ? fmt::format("|initial_state[0] - initial_input_v| <= thresholds[0] = {} "
                                  "(a state some input history reaches)", thresholds[0])
                    : fmt::format("|initial_state[{0}] - initial_state[{1}]| <= thresholds[{0}] "
                                  "- thresholds[{1}] = {2} (a state some input history reaches)",
                                  i, i - 1, band));
    }
  }
  if (!std::isfinite(input_min_v)) Fail("input_min_v", input_min_v, "a finite number");
  if (!std::isfinite(input_max_v) || !(input_max_v > input_min_v))
    Fail("input_max_v", input_max_v, fmt::format("input_max_v > input_min_v = {}", input_min_v));
}

PrandtlIshlinskiiModel::PrandtlIshlinskiiModel(PiParameters p, std::vector<double> std_errors,
                                               double range_margin)
    : p_(std::move(p)), std_errors_(std::move(std_errors)), range_margin_(range_margin) {
  p_.Validate();
  const internal::PiLayout l = internal::LayoutOf(p_);
  if (std_errors_.empty()) std_errors_.assign(static_cast<size_t>(l.size()), NAN);
  if (std_errors_.size() != static_cast<size_t>(l.size()))
    throw OptionsError(fmt::format("PrandtlIshlinskiiModel: {} standard errors for {} parameters",
                                   std_errors_.size(), l.size()),
                       "std_errors");
  if (!(range_margin_ >= 0) || !std::isfinite(range_margin_))
    internal::FailOption("PiFitOptions", "range_margin", range_margin_,
                         "range_margin >= 0, finite");
  // Why the model may not be monotone in u (then no inverse).
  const double p0 = p_.polynomial[0];
  if (p_.form == PiForm::kClassical) {
    double sum = 0;
    for (size_t i = 0; i <= p_.weights.size(); ++i) {
      sum += i == 0 ? p0 : p_.weights[i - 1];
      if (!(sum > 0)) {
        why_not_invertible_ =
            i == 0 ? fmt::format("polynomial[0] (p0) = {:.6g} m/V: the inverse needs p0 > 0", p0)
                   : fmt::format("weights[{}]: p0 + w_1 + ... + w_{} = {:.6g} m/V: the inverse "
                                 "needs every partial sum > 0", i - 1, i, sum);
        break;
      }
    }
    return;
  }
  for (size_t i = 0; i < p_.weights.size() && why_not_invertible_.empty(); ++i)
    if (p_.weights[i] < 0)
      why_not_invertible_ =
          fmt::format("weights[{}] = {:.6g} m/V: the inverse needs w_i >= 0", i, p_.weights[i]);
  for (size_t i = 0; i < p_.rate_weights.size() && why_not_invertible_.empty(); ++i)
    if (p_.rate_weights[i] < 0)
      why_not_invertible_ = fmt::format("rate_weights[{}] = {:.6g} m*s/V^2: the inverse needs "
                                        "q_i >= 0", i, p_.rate_weights[i]);
  if (!why_not_invertible_.empty()) return;
  const double span = p_.input_max_v - p_.input_min_v;
  const double lo = p_.input_min_v - range_margin_ * span, hi = p_.input_max_v + range_margin_ * span;
  for (int g = 0; g < kSlopeGrid; ++g) {
    const double u = lo + (hi - lo) * g / (kSlopeGrid - 1);
    const double slope = PolynomialSlope(p_.polynomial, u);
    if (!(slope > 0)) {
      why_not_invertible_ = fmt::format(
          "polynomial: the input function's slope dP/du = {:.6g} m/V at u = {:.6g} V inside the "
          "model's input range [{:.6g}, {:.6g}] V: the inverse needs dP/du > 0", slope, u, lo, hi);
      return;
    }
  }
}

Eigen::VectorXd PrandtlIshlinskiiModel::Simulate(const Eigen::VectorXd& u, double dt_s) const {
  if (p_.form == PiForm::kRateDependent && (!(dt_s > 0) || !std::isfinite(dt_s)))
    internal::FailOption("Simulate", "dt_s", dt_s, "dt_s > 0");
  const internal::PiLayout l = internal::LayoutOf(p_);
  std::vector<double> z = internal::InitialState(p_);
  Eigen::VectorXd y(u.size());
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    // The input's rate over the previous step (sysid/hysteresis.hpp).
    const double rho = l.rate() && k >= 2 ? std::abs(u[k - 1] - u[k - 2]) / dt_s : 0.0;
    y[k] = internal::PiOutputStep(p_, l, u[k], rho, z.data());
  }
  return y;
}

PiParameters PrandtlIshlinskiiModel::InverseParameters() const {
  if (p_.form != PiForm::kClassical)
    throw NumericalError(kind() + ": only the classical PI has a closed-form inverse");
  if (!invertible()) throw NumericalError("pi model not invertible: " + why_not_invertible_);
  const size_t n = p_.thresholds.size();
  const double w0 = p_.polynomial[0];
  const std::vector<double> z = internal::InitialState(p_);
  PiParameters inv;
  inv.form = PiForm::kClassical;
  inv.thresholds.resize(n);
  inv.weights.resize(n);
  inv.polynomial = {1.0 / w0};
  inv.offset_m = 0;  // the inverse acts on y - c
  // Kuhnen (2003): r'_i = sum_{j<=i} w_j (r_i - r_j), w'_i = -w_i / (S_i S_{i-1}).
  double partial = w0;  // S_{i-1}
  for (size_t i = 0; i < n; ++i) {
    const double r = p_.thresholds[i];
    double ri = w0 * r;
    for (size_t j = 0; j < i; ++j) ri += p_.weights[j] * (r - p_.thresholds[j]);
    inv.thresholds[i] = ri;
    const double next = partial + p_.weights[i];
    inv.weights[i] = -p_.weights[i] / (next * partial);
    partial = next;
  }
  // Initial states: z'_i = sum_{j<=i} w_j z_i + sum_{j>i} w_j z_j with z_0 = the initial input
  // (the inverse's own initial input is z'_0 = y(-1) - c).
  auto state = [&](size_t i) {  // i = 0..n, 0 the threshold-0 operator
    double s = 0;
    for (size_t j = 0; j <= n; ++j) {
      const double wj = j == 0 ? w0 : p_.weights[j - 1];
      const size_t at = j <= i ? i : j;
      s += wj * (at == 0 ? p_.initial_input_v : z[at - 1]);
    }
    return s;
  };
  inv.initial_input_v = state(0);
  inv.initial_state.resize(n);
  for (size_t i = 0; i < n; ++i) inv.initial_state[i] = state(i + 1);
  // Rounding may put a state a hair outside its (exact) band: clamp to it.
  for (size_t i = 0; i < n; ++i)
    inv.initial_state[i] = PlayStep(inv.initial_input_v, inv.thresholds[i], inv.initial_state[i]);
  // The inverse is valid on the output range; its own "input range" is unused (set wide).
  inv.input_min_v = -std::numeric_limits<double>::max() / 4;
  inv.input_max_v = std::numeric_limits<double>::max() / 4;
  // r'_i - r'_{i-1} = S_{i-1} (r_i - r_{i-1}) > 0: the inverse's thresholds increase too.
  // Weights near the largest double (1e308) overflow these sums: said as the model's failure,
  // not as an invalid field of parameters the user never wrote.
  const auto overflow = [&](const char* what, size_t i, double v) {
    return NumericalError(fmt::format(
        "pi model not invertible: its inverse's {}[{}] = {} overflows a double (the model's "
        "weights sum to {:.3g} m/V with p0 = {:.3g} m/V): rescale the model",
        what, i, v, partial, w0));
  };
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(inv.thresholds[i])) throw overflow("thresholds", i, inv.thresholds[i]);
    if (!std::isfinite(inv.weights[i])) throw overflow("weights", i, inv.weights[i]);
    if (!std::isfinite(inv.initial_state[i]))
      throw overflow("initial_state", i, inv.initial_state[i]);
  }
  if (!std::isfinite(inv.initial_input_v)) throw overflow("initial_input", 0, inv.initial_input_v);
  return inv;
}

double PrandtlIshlinskiiModel::InverseGainRatio() const {
  if (!invertible()) return std::numeric_limits<double>::infinity();
  double weights = 0;
  for (double w : p_.weights) weights += std::max(w, 0.0);
  if (p_.form != PiForm::kPolynomial) {
    // After a reversal only the threshold-0 term moves (slope p0); after a long monotone
    // stretch every operator does (p0 + sum w). Quasi-static for rdpi (rate 0).
    const double p0 = p_.polynomial[0];
    return (p0 + weights) / p0;
  }
  const double span = p_.input_max_v - p_.input_min_v;
  const double lo = p_.input_min_v - range_margin_ * span, hi = p_.input_max_v + range_margin_ * span;
  double smallest = std::numeric_limits<double>::infinity(), largest = 0;
  for (int g = 0; g < kSlopeGrid; ++g) {
    const double s = PolynomialSlope(p_.polynomial, lo + (hi - lo) * g / (kSlopeGrid - 1));
    smallest = std::min(smallest, s);
    largest = std::max(largest, s);
  }
  return (largest + weights) / smallest;
}

Eigen::VectorXd PrandtlIshlinskiiModel::Invert(const Eigen::VectorXd& y_desired,
                                               double dt_s) const {
  if (!invertible()) throw NumericalError(kind() + " model not invertible: " + why_not_invertible_);
  for (Eigen::Index k = 0; k < y_desired.size(); ++k)
    if (!std::isfinite(y_desired[k]))
      throw InputError(fmt::format("reference sample {}: x = {}: expected a finite number [m]", k,
                                   y_desired[k]));
  const double span = p_.input_max_v - p_.input_min_v;
  const double lo = p_.input_min_v - range_margin_ * span, hi = p_.input_max_v + range_margin_ * span;
  auto out_of_range = [&](Eigen::Index k, const std::string& what) {
    return InputError(fmt::format(
        "reference sample {} (t = {:.6g} s): x = {:.9g} m is outside the {} model's range: {} "
        "(the training input range [{:.6g}, {:.6g}] V widened by {:g} % of its span)",
        k, static_cast<double>(k) * dt_s, y_desired[k], kind(), what, lo, hi,
        100 * range_margin_));
  };
  Eigen::VectorXd u(y_desired.size());
  PiInverseStepper stepper(*this, dt_s);  // rdpi: dt_s and the error gain checked here
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    u[k] = stepper.Step(y_desired[k]);
    const PiInverseSaturation& s = stepper.saturation();
    if (!s.saturated) continue;
    if (p_.form != PiForm::kClassical)
      throw out_of_range(k, s.above ? fmt::format("above the output {:.9g} m at u = {:.6g} V",
                                                  s.bound_output_m, hi)
                                    : fmt::format("below the output {:.9g} m at u = {:.6g} V",
                                                  s.bound_output_m, lo));
    if (std::isfinite(s.needed_u_v))
      throw out_of_range(k, fmt::format("it needs u = {:.6g} V", s.needed_u_v));
    // A reference near the largest double (1e308 m) overflows the inverse's sum (inf - inf):
    // its "u" is NaN or inf, no input to print ("it needs u = -nan V" said nothing). Say
    // which side of the model's reach x is instead: the forward model's output at the range's
    // ends from its state at sample k (u before k is in range: this is the first bad sample).
    // Only on this error path, so the cost of two simulations of k + 1 samples is no matter.
    auto reach = [&](double end) {
      Eigen::VectorXd path(k + 1);
      path.head(k) = u.head(k);
      path[k] = end;
      return Simulate(path, dt_s)[k];
    };
    const double y_hi = reach(hi), y_lo = reach(lo);
    const std::string side =
        y_desired[k] > y_hi   ? fmt::format("above the output {:.9g} m at u = {:.6g} V", y_hi, hi)
        : y_desired[k] < y_lo ? fmt::format("below the output {:.9g} m at u = {:.6g} V", y_lo, lo)
                              : std::string("no input in the range gives it");
    throw out_of_range(k, side + "; the input it needs overflows a double");
  }
  return u;
}

std::unique_ptr<HysteresisInverseStepper> PrandtlIshlinskiiModel::InverseStepper(
    double dt_s) const {
  if (!invertible()) throw NumericalError(kind() + " model not invertible: " + why_not_invertible_);
  return std::make_unique<PiInverseStepper>(*this, dt_s);
}

std::vector<HysteresisParameter> PrandtlIshlinskiiModel::parameters() const {
  const internal::PiLayout l = internal::LayoutOf(p_);
  const Eigen::VectorXd theta = internal::Pack(p_);
  std::vector<HysteresisParameter> out;
  for (int j = 0; j < l.size(); ++j)
    out.push_back({l.name(j), l.unit(j), theta[j], std_errors_[static_cast<size_t>(j)]});
  return out;
}

}  // namespace sysid
