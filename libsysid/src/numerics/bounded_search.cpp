#include "numerics/bounded_search.hpp"

#include <nlopt.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "sysid/error.hpp"

namespace sysid::internal {
namespace {

struct Context {
  const std::function<double(double)>* f;
  ScalarSearchResult* result;
  std::exception_ptr error;
};

double Objective(unsigned, const double* x, double*, void* data) {
  auto* c = static_cast<Context*>(data);
  double value = std::numeric_limits<double>::max();
  // After a thrown error the run is over: skip the remaining (costly) evaluations until NLopt
  // returns and the error is rethrown.
  if (c->error) return value;
  try {
    value = (*c->f)(x[0]);
  } catch (...) {
    c->error = std::current_exception();
    return std::numeric_limits<double>::max();
  }
  if (!std::isfinite(value)) value = std::numeric_limits<double>::max();
  c->result->evaluated.emplace_back(x[0], value);
  ++c->result->evaluations;
  if (value < c->result->f || c->result->evaluations == 1) {
    c->result->f = value;
    c->result->x = x[0];
  }
  return value;
}

const char* Describe(nlopt_result r) {
  switch (r) {
    case NLOPT_SUCCESS:
      return "success";
    case NLOPT_STOPVAL_REACHED:
      return "stop value reached";
    case NLOPT_FTOL_REACHED:
      return "function tolerance reached";
    case NLOPT_XTOL_REACHED:
      return "x tolerance reached";
    case NLOPT_MAXEVAL_REACHED:
      return "evaluation budget exhausted";
    case NLOPT_MAXTIME_REACHED:
      return "time budget exhausted";
    case NLOPT_ROUNDOFF_LIMITED:
      return "round-off limited";
    case NLOPT_FORCED_STOP:
      return "forced stop";
    default:
      return "NLopt failure";
  }
}

}  // namespace

ScalarSearchResult MinimizeScalar(const std::function<double(double)>& f,
                                  const ScalarSearchOptions& o) {
  SYSID_CHECK(o.hi > o.lo, "search interval empty");
  ScalarSearchResult r;
  r.f = std::numeric_limits<double>::infinity();
  Context c{&f, &r, nullptr};
  auto run = [&](nlopt_algorithm alg, int budget, double x0, double step, double xtol) {
    nlopt_opt opt = nlopt_create(alg, 1);
    nlopt_set_lower_bounds1(opt, o.lo);
    nlopt_set_upper_bounds1(opt, o.hi);
    nlopt_set_min_objective(opt, &Objective, &c);
    nlopt_set_maxeval(opt, std::max(1, budget));
    if (xtol > 0) nlopt_set_xtol_abs1(opt, xtol);
    if (step > 0) nlopt_set_initial_step1(opt, step);
    double x = x0, fx = 0;
    const nlopt_result res = nlopt_optimize(opt, &x, &fx);
    nlopt_destroy(opt);
    if (c.error) std::rethrow_exception(c.error);
    return res;
  };
  // DIRECT-L divides the interval in thirds: its budget fixes the coarse resolution.
  run(NLOPT_GN_DIRECT_L, o.coarse_evaluations, 0.5 * (o.lo + o.hi), 0, 0);
  const double resolution = (o.hi - o.lo) / std::max(3, o.coarse_evaluations);
  const int left = o.max_evaluations - r.evaluations;
  if (left <= 0) {
    r.message = "coarse stage used the whole evaluation budget";
    return r;
  }
  const double x_start = r.x;
  // A step of the coarse resolution keeps BOBYQA inside the basin DIRECT found.
  const double step = std::min({resolution, std::max(x_start - o.lo, o.hi - x_start)});
  const nlopt_result res = run(NLOPT_LN_BOBYQA, left, x_start, step, o.x_tolerance);
  r.converged = res == NLOPT_XTOL_REACHED || res == NLOPT_FTOL_REACHED || res == NLOPT_SUCCESS;
  r.message = std::string("DIRECT-L then BOBYQA: ") + Describe(res);
  return r;
}

}  // namespace sysid::internal
