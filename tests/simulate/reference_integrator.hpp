// An independent tiny-step reference for the simulator tests: fixed-step classical RK4 method of
// steps on the grid t_k = t0 + k h, written for the tests only (it shares no code with
// libsysid's simulator).
//
// With tau = D h, the delayed term on step k is v on grid interval [k - D, k - D + 1], known
// before the step starts, so each RK4 step in a fixed friction mode is Simpson's rule on a known
// integrand; delayed values between grid points come from the cubic Hermite interpolant of the
// stored (v, v'_right, v'_left), error O(h^4). A zero of v inside a step (stop) or a threshold
// crossing of F while stuck (release) is located by bisection on the partial RK4 step, the new
// mode is chosen there and the rest of the step is integrated in it. Input edges must lie on the
// grid; u is piecewise constant. Zero history, x(t0) = 0, v(t0) = 0.
#ifndef SYSID_TESTS_SIMULATE_REFERENCE_INTEGRATOR_HPP_
#define SYSID_TESTS_SIMULATE_REFERENCE_INTEGRATOR_HPP_

#include <vector>

#include "sysid/input.hpp"
#include "sysid/model.hpp"

namespace sysid::test {

struct ReferenceTrajectory {
  std::vector<double> t, x, v;  ///< on the sample grid
  std::vector<double> event_t;  ///< stop and release times
};

/// Integrates from 0 to t_end with step h (tau / h and every edge / h integers); samples every
/// `sample_every` steps.
ReferenceTrajectory ReferenceRk4(const FrictionModel& model, const PiecewiseConstantInput& input,
                                 double t_end, double h, int sample_every);

}  // namespace sysid::test

#endif  // SYSID_TESTS_SIMULATE_REFERENCE_INTEGRATOR_HPP_
