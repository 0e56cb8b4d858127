// Private: bounded derivative-free minimisation of a scalar function of the delay tau with
// NLopt: DIRECT-L over the whole interval (the cost is not smooth and may have local minima),
// then BOBYQA from the best point found, with a step of the coarse stage's resolution.
#ifndef SYSID_SRC_NUMERICS_BOUNDED_SEARCH_HPP_
#define SYSID_SRC_NUMERICS_BOUNDED_SEARCH_HPP_

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace sysid::internal {

struct ScalarSearchOptions {
  double lo = 0;                ///< lower bound
  double hi = 1;                ///< upper bound, > lo
  int coarse_evaluations = 20;  ///< DIRECT-L budget
  int max_evaluations = 60;     ///< total budget (coarse + refine)
  double x_tolerance = 1e-7;    ///< BOBYQA absolute tolerance on x
};

struct ScalarSearchResult {
  double x = 0;
  double f = 0;
  int evaluations = 0;
  bool converged = false;  ///< BOBYQA met x_tolerance (not the evaluation budget)
  std::string message;
  std::vector<std::pair<double, double>> evaluated;  ///< (x, f) in evaluation order
};

/// Minimises f over [lo, hi]. A non-finite f(x) is treated as +inf (so a failed simulation
/// steers the search away without aborting it).
ScalarSearchResult MinimizeScalar(const std::function<double(double)>& f,
                                  const ScalarSearchOptions& options);

}  // namespace sysid::internal

#endif  // SYSID_SRC_NUMERICS_BOUNDED_SEARCH_HPP_
