// The one CVODE wrapper (core/cvode_solver.hpp): integration against a closed form, counters
// across restarts, and the one readable error path its users (simulate, stage) share.
#include <sunmatrix/sunmatrix_dense.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <string>

#include "core/cvode_solver.hpp"
#include "sysid/error.hpp"

namespace sysid {
namespace {

using internal::CvodeSolver;

// y' = -k y, k = 2 [1/s]: y(t) = y0 exp(-k t).
int Decay(double, N_Vector y, N_Vector ydot, void*) {
  N_VGetArrayPointer(ydot)[0] = -2.0 * N_VGetArrayPointer(y)[0];
  return 0;
}

int DecayJacobian(double, N_Vector, N_Vector, SUNMatrix J, void*, N_Vector, N_Vector, N_Vector) {
  SM_ELEMENT_D(J, 0, 0) = -2.0;
  return 0;
}

int Broken(double, N_Vector, N_Vector, void*) { return -1; }  // unrecoverable failure

TEST_CASE("CvodeSolver integrates y' = -2 y to its closed form, Adams and BDF", "[core][cvode]") {
  for (auto method : {CvodeSolver::Method::kAdams, CvodeSolver::Method::kBdf}) {
    const double y0 = 3.0;
    CvodeSolver cv(1, method, Decay, nullptr, 0.0, &y0, "test");
    cv.SetTolerances(1e-10, 1e-12);
    if (method == CvodeSolver::Method::kBdf) cv.SetJacobian(DecayJacobian);
    double t = 0;
    REQUIRE(cv.Advance(0.5, &t, CV_NORMAL) == CV_SUCCESS);
    CHECK(cv.state()[0] == Approx(3.0 * std::exp(-1.0)).epsilon(1e-8));
    const long steps_before = cv.Counters().steps;
    CHECK(steps_before > 0);
    // A restart (from the current state) continues the solution; counters keep adding up.
    cv.ReInit(t);
    REQUIRE(cv.Advance(1.0, &t, CV_NORMAL) == CV_SUCCESS);
    CHECK(cv.state()[0] == Approx(3.0 * std::exp(-2.0)).epsilon(1e-8));
    CHECK(cv.Counters().steps > steps_before);
    CHECK(cv.Counters().rhs_evaluations >= cv.Counters().steps);
  }
}

TEST_CASE("CvodeSolver's Nordsieck array is the step's Taylor polynomial", "[core][cvode]") {
  const double y0 = 3.0;
  CvodeSolver cv(1, CvodeSolver::Method::kAdams, Decay, nullptr, 0.0, &y0, "test");
  cv.SetTolerances(1e-12, 1e-14);
  int highest = 0;
  for (int step = 0; step < 60; ++step) {
    double t = 0, tn = 0, h = 0;
    int q = 0;
    REQUIRE(cv.Advance(10.0, &t, CV_ONE_STEP) == CV_SUCCESS);
    CVodeGetCurrentTime(cv.mem(), &tn);
    CVodeGetLastStep(cv.mem(), &h);
    CVodeGetLastOrder(cv.mem(), &q);
    highest = std::max(highest, q);
    const double* const* z = cv.Nordsieck(q);
    REQUIRE(z != nullptr);
    // z_0 is the state after a plain step; z_k = h^k / k! y^(k)(tn), which CVodeGetDky forms
    // from the same vectors: k! z_k h^-k.
    CHECK(z[0][0] == cv.state()[0]);
    double factorial = 1, power = 1;
    for (int k = 1; k <= q; ++k) {
      factorial *= k;
      power *= h;
      const double dky = cv.Dky(tn, k)[0];
      CHECK(factorial * z[k][0] / power == Approx(dky).epsilon(1e-14));
    }
    // Inside the step the polynomial is the solution, to the tolerance.
    const double theta = -0.5, ts = tn + theta * h;
    double poly = 0;
    for (int k = q; k >= 0; --k) poly = poly * theta + z[k][0];
    CHECK(poly == Approx(3.0 * std::exp(-2.0 * ts)).epsilon(1e-9));
  }
  CHECK(highest >= 4);  // the vectors were found again as the order climbed
}

TEST_CASE("CvodeSolver failures read as one sentence with the flag's name", "[core][cvode]") {
  const double y0 = 1.0;
  CvodeSolver cv(1, CvodeSolver::Method::kAdams, Decay, nullptr, 0.0, &y0, "my integrator",
                 "try a smaller t");
  cv.SetTolerances(1e-12, 1e-14);
  cv.SetMaxNumSteps(3);
  double t = 0;
  const int flag = cv.Advance(100.0, &t, CV_NORMAL);
  REQUIRE(flag == CV_TOO_MUCH_WORK);
  CHECK(CvodeSolver::FlagName(flag) == "CV_TOO_MUCH_WORK");
  const std::string text = cv.Describe(flag, "CVode");
  CHECK_THAT(text, Catch::StartsWith("CVODE failed at t = ") && Catch::Contains(" s: too much work") &&
                       Catch::Contains("(CV_TOO_MUCH_WORK) in CVode: "));
  CHECK_THROWS_AS(cv.Check(flag, "CVode"), NumericalError);
  CHECK_THROWS_WITH(cv.Check(flag, "CVode"), Catch::StartsWith("my integrator: CVODE failed at t = ") &&
                                                 !Catch::Contains(".;") &&
                                                 Catch::EndsWith("; try a smaller t"));
  CHECK_NOTHROW(cv.Check(CV_SUCCESS, "CVode"));

  CvodeSolver broken(1, CvodeSolver::Method::kBdf, Broken, nullptr, 0.0, &y0, "broken");
  broken.SetTolerances(1e-8, 1e-10);
  const int rhs_flag = broken.Advance(1.0, &t, CV_NORMAL);
  REQUIRE(rhs_flag < 0);
  CHECK_THAT(broken.Describe(rhs_flag, "CVode"), Catch::Contains("right-hand side failed") &&
                                                     Catch::Contains("(CV_RHSFUNC_FAIL)"));
}

}  // namespace
}  // namespace sysid
