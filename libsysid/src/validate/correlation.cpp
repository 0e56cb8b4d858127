// Normalised residual correlations by the direct O(N L) sum (validate.hpp): L is at most a
// thousand lags and N a recording, so the sum costs less than the simulation that made e.
#include <fmt/format.h>

#include <cmath>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/validate.hpp"

namespace sysid {
namespace {

void CheckLag(Eigen::Index n, int max_lag) {
  if (max_lag < 0 || max_lag >= n)
    internal::FailOption("", "max_lag", max_lag, fmt::format("0 <= max_lag < N = {}", n));
}

Eigen::VectorXd Centred(const Eigen::VectorXd& s, const char* name) {
  if (!s.allFinite())
    throw InputError(
        fmt::format("correlation: {} holds NaN or inf: expected finite samples", name));
  Eigen::VectorXd c = s.array() - s.mean();
  if (!(c.squaredNorm() > 0))
    throw InputError(
        fmt::format("correlation: {} is constant: its correlation is undefined", name));
  return c;
}

// sum_{t=k}^{N-1} a_t b_{t-k} for k = 0..max_lag.
Eigen::VectorXd LaggedProducts(const Eigen::VectorXd& a, const Eigen::VectorXd& b, int max_lag) {
  const Eigen::Index n = a.size();
  Eigen::VectorXd out(max_lag + 1);
  for (int k = 0; k <= max_lag; ++k) out[k] = a.tail(n - k).dot(b.head(n - k));
  return out;
}

}  // namespace

Eigen::VectorXd NormalisedAutocorrelation(const Eigen::VectorXd& e, int max_lag) {
  CheckLag(e.size(), max_lag);
  const Eigen::VectorXd c = Centred(e, "the residual");
  return LaggedProducts(c, c, max_lag) / c.squaredNorm();
}

Eigen::VectorXd NormalisedCrossCorrelation(const Eigen::VectorXd& e, const Eigen::VectorXd& u,
                                           int max_lag) {
  if (e.size() != u.size())
    throw InputError(
        fmt::format("correlation: the residual has {} samples, u {}: expected "
                    "equal lengths",
                    e.size(), u.size()));
  CheckLag(e.size(), max_lag);
  const Eigen::VectorXd ce = Centred(e, "the residual"), cu = Centred(u, "u");
  return LaggedProducts(ce, cu, max_lag) / std::sqrt(ce.squaredNorm() * cu.squaredNorm());
}

}  // namespace sysid
