// The residual tests' bounds and verdicts (validate.hpp: rules (a) and (b)).
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/validate.hpp"

namespace sysid {
namespace {

void CheckProbability(double p, const char* name) {
  if (!(p > 0 && p < 0.5))
    internal::FailOption("ResidualTestOptions", name, p, fmt::format("0 < {} < 0.5", name));
}

CorrelationTest Judge(std::string name, int first_lag, const Eigen::VectorXd& r_all,
                      Eigen::Index samples, const ResidualTestOptions& o) {
  CorrelationTest t;
  t.name = std::move(name);
  const int lags = o.max_lag - first_lag + 1;
  t.r = r_all.segment(first_lag, lags);
  for (int k = first_lag; k <= o.max_lag; ++k) t.lags.push_back(k);
  const double root_n = std::sqrt(static_cast<double>(samples));
  t.bound = o.z / root_n;
  t.strong_bound = NormalQuantile(1.0 - o.test_level / (2.0 * lags)) / root_n;
  t.allowed_outside = AllowedLagsOutside(lags, o.lag_probability, o.test_level);
  t.max_abs_r = t.r.cwiseAbs().maxCoeff();
  t.outside = static_cast<int>((t.r.array().abs() > t.bound).count());
  const bool too_many = t.outside > t.allowed_outside;
  const bool too_far = t.max_abs_r > t.strong_bound;
  t.pass = !too_many && !too_far;
  t.verdict = fmt::format(
      "{}: {} of {} lags outside ±{:.3g} (at most {} allowed); max |r| = "
      "{:.3g} (limit {:.3g})",
      t.pass ? "pass" : "fail", t.outside, lags, t.bound, t.allowed_outside, t.max_abs_r,
      t.strong_bound);
  return t;
}

bool Constant(const Eigen::VectorXd& s) {
  return !((s.array() - s.mean()).matrix().squaredNorm() > 0);
}

// A constant residual (a perfect model) or input has no correlation to test: the test is
// reported as not run, with NaN correlations, and does not fail the model.
CorrelationTest Untested(std::string name, int first_lag, Eigen::Index samples,
                         const ResidualTestOptions& o, const std::string& why) {
  CorrelationTest t =
      Judge(std::move(name), first_lag, Eigen::VectorXd::Zero(o.max_lag + 1), samples, o);
  t.r.setConstant(std::numeric_limits<double>::quiet_NaN());
  t.max_abs_r = std::numeric_limits<double>::quiet_NaN();
  t.tested = false;
  t.pass = true;
  t.verdict = "not tested: " + why;
  return t;
}

void CheckLength(Eigen::Index n, const ResidualTestOptions& o) {
  if (n < 4 * (static_cast<Eigen::Index>(o.max_lag) + 1))
    throw InputError(
        fmt::format("residual tests: {} samples for {} lags: expected at least "
                    "4 (lags + 1) = {} samples (give fewer lags)",
                    n, o.max_lag, 4 * (o.max_lag + 1)));
}

}  // namespace

void ResidualTestOptions::Validate() const {
  if (max_lag < 1 || max_lag > 1000)
    internal::FailOption("ResidualTestOptions", "max_lag", max_lag, "1 <= max_lag <= 1000");
  if (!(z > 0 && z <= 10)) internal::FailOption("ResidualTestOptions", "z", z, "0 < z <= 10");
  CheckProbability(lag_probability, "lag_probability");
  CheckProbability(test_level, "test_level");
}

double NormalQuantile(double q) {
  if (!(q > 0 && q < 1)) internal::FailOption("NormalQuantile", "q", q, "0 < q < 1");
  // Φ(x) = erfc(-x / sqrt 2) / 2 is increasing; bisect on [-40, 40].
  double lo = -40, hi = 40;
  while (hi - lo > 1e-12) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < q ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

int AllowedLagsOutside(int lags, double p, double level) {
  if (lags < 1) internal::FailOption("AllowedLagsOutside", "lags", lags, "lags >= 1");
  if (!(p > 0 && p < 1)) internal::FailOption("AllowedLagsOutside", "p", p, "0 < p < 1");
  if (!(level > 0 && level < 1))
    internal::FailOption("AllowedLagsOutside", "level", level, "0 < level < 1");
  // P(X = j) by the recurrence P(j) = P(j - 1) (n - j + 1) / j p / (1 - p), from (1 - p)^n.
  double pj = std::pow(1.0 - p, lags), cdf = pj;
  int k = 0;
  while (1.0 - cdf > level && k < lags) {
    ++k;
    pj *= static_cast<double>(lags - k + 1) / k * p / (1.0 - p);
    cdf += pj;
  }
  return k;
}

CorrelationTest AutocorrelationTest(const Eigen::VectorXd& e, const ResidualTestOptions& options) {
  options.Validate();
  CheckLength(e.size(), options);
  if (e.allFinite() && Constant(e))
    return Untested("autocorrelation", 1, e.size(), options, "the residual is constant");
  return Judge("autocorrelation", 1, NormalisedAutocorrelation(e, options.max_lag), e.size(),
               options);
}

CorrelationTest CrossCorrelationTest(const Eigen::VectorXd& e, const Eigen::VectorXd& u,
                                     const ResidualTestOptions& options) {
  options.Validate();
  CheckLength(e.size(), options);
  if (e.allFinite() && u.allFinite() && e.size() == u.size() && (Constant(e) || Constant(u)))
    return Untested("cross-correlation with u", 0, e.size(), options,
                    Constant(e) ? "the residual is constant" : "u is constant");
  return Judge("cross-correlation with u", 0, NormalisedCrossCorrelation(e, u, options.max_lag),
               e.size(), options);
}

}  // namespace sysid
