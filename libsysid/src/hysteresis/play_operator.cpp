// The play operator and the names of the Prandtl–Ishlinskii forms.
#include <fmt/format.h>

#include <cmath>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace sysid {

Eigen::VectorXd PlayOperator(const Eigen::VectorXd& u, double r, double z0) {
  if (!(r >= 0) || !std::isfinite(r))
    internal::FailOption("PlayOperator", "r", r, "r >= 0, finite");
  if (!std::isfinite(z0)) internal::FailOption("PlayOperator", "z0", z0, "finite");
  Eigen::VectorXd z(u.size());
  double state = z0;
  for (Eigen::Index k = 0; k < u.size(); ++k) z[k] = state = PlayStep(u[k], r, state);
  return z;
}

std::string ToString(PiForm form) {
  switch (form) {
    case PiForm::kClassical: return "pi";
    case PiForm::kPolynomial: return "gpi";
    case PiForm::kRateDependent: return "rdpi";
  }
  return "pi";
}

PiForm PiFormFromString(const std::string& name) {
  if (name == "pi") return PiForm::kClassical;
  if (name == "gpi") return PiForm::kPolynomial;
  if (name == "rdpi") return PiForm::kRateDependent;
  throw OptionsError("Prandtl-Ishlinskii form '" + name + "': expected pi, gpi or rdpi", "form");
}

std::vector<double> UniformThresholds(double u_min, double u_max, int n) {
  if (!(u_max > u_min) || !std::isfinite(u_min) || !std::isfinite(u_max))
    throw InputError(fmt::format(
        "uniform thresholds need an input range with max > min, found [{}, {}] V", u_min, u_max));
  if (n < 1 || n > kMaxPlayOperators)
    internal::FailOption(
        "PiFitOptions", "operators", n,
        fmt::format("1 <= operators <= {} (kMaxPlayOperators)", kMaxPlayOperators));
  const double half_range = 0.5 * (u_max - u_min);
  std::vector<double> r(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) r[static_cast<size_t>(i)] = (i + 1) * half_range / (n + 1);
  return r;
}

double RecordingStep(const Recording& recording) {
  if (recording.rows() < 2)
    throw InputError(recording.source + ": expected at least 2 samples, found " +
                     std::to_string(recording.rows()));
  return AnalyzeSampling(recording.column("t")).nominal_dt_s;
}

}  // namespace sysid
