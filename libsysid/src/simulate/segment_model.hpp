// The friction model as CVODE sees it on one segment: friction mode and viscous branch frozen.
//
// Freezing them is what makes the right-hand side smooth inside a segment (CVODE's high-order
// methods need that); the root functions watch for the instants where the frozen choice stops
// being right, and the simulator (simulator.cpp) then picks the next mode from the right-hand
// limit. One SegmentModel per Simulate call carries everything the callbacks need (no
// globals: concurrent simulations are thread-safe).
#ifndef SYSID_SRC_SIMULATE_SEGMENT_MODEL_HPP_
#define SYSID_SRC_SIMULATE_SEGMENT_MODEL_HPP_

#include <nvector/nvector_serial.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <algorithm>
#include <cmath>

#include "simulate/delay_history.hpp"
#include "sysid/input.hpp"
#include "sysid/model.hpp"
#include "sysid/simulate.hpp"

namespace sysid::internal {

/// v = 0 while sliding, F - a2p and F + a2n while stuck, v(t - tau) against the a1 branch.
constexpr int kNumRoots = 4;

struct SegmentModel {
  const FrictionModel& model;
  const InputSignal& input;
  double tau;
  DelayHistory history;
  int mode = 0;    // friction mode: +1 sliding forward, -1 backward, 0 stuck
  int branch = 0;  // sign of v(t - tau) on this segment: selects a1 (0: v(t - tau) = 0)
  double a1 = 0;   // [1/s] the frozen viscous coefficient
  double a2 = 0;   // [m/s^2] signed Coulomb term: a2p (mode +1), -a2n (mode -1)
  // The segment's input. CVODE evaluates f at the segment's end point, where a right-continuous
  // u has already jumped: inside a segment u is read at most just left of its end.
  bool u_held = false;       // u constant on the segment (zero-order hold): u_seg
  double u_seg = 0;          // [V]
  double t_last_inside = 0;  // [s] largest double below the segment's end

  SegmentModel(const FrictionModel& m, const InputSignal& in, const SimulationOptions& o)
      : model(m), input(in), tau(m.tau_s), history(o.t0_s, o.history_v_mps, o.v0_mps) {}

  /// v(t - tau); with tau = 0 that is the current velocity.
  double DelayedV(double t, double v) const { return tau > 0 ? history.Value(t - tau) : v; }

  /// Driving force per mass F = a3 u(t) - a1 v(t - tau) [m/s^2], a1 by the actual sign (not
  /// the frozen branch: used to decide a mode at an instant, where the right-hand limit counts).
  double Force(double t, double v) const {
    const double vd = DelayedV(t, v);
    return model.a3 * input.Value(t) - (vd > 0 ? model.a1p : model.a1n) * vd;
  }

  /// The stick–slip rule at v = 0.
  int Decide(double force) const {
    if (force > model.a2p) return 1;
    if (force < -model.a2n) return -1;
    return 0;
  }

  /// u inside the current segment (left limit at its end).
  double SegmentU(double t) const {
    return u_held ? u_seg : input.Value(std::min(t, t_last_inside));
  }

  /// v' in the frozen mode and branch.
  double Acceleration(double t, double v) const {
    if (mode == 0) return 0.0;
    return model.a3 * SegmentU(t) - a1 * DelayedV(t, v) - a2;
  }

  /// Fixes a1 and a2 from the mode and branch for the coming segment.
  void Freeze() {
    a1 = branch < 0 ? model.a1n : model.a1p;
    a2 = mode > 0 ? model.a2p : (mode < 0 ? -model.a2n : 0.0);
  }

  static int Rhs(double t, N_Vector y, N_Vector ydot, void* self) {
    const auto* p = static_cast<const SegmentModel*>(self);
    const double* yv = N_VGetArrayPointer(y);
    double* d = N_VGetArrayPointer(ydot);
    // Stuck: x' = v = 0 exactly, not the solver's v (which may carry round-off).
    d[0] = p->mode == 0 ? 0.0 : yv[1];
    d[1] = p->Acceleration(t, yv[1]);
    return std::isfinite(d[1]) ? 0 : -1;
  }

  static int Roots(double t, N_Vector y, double* g, void* self) {
    const auto* p = static_cast<const SegmentModel*>(self);
    const double v = N_VGetArrayPointer(y)[1];
    const double vd = p->DelayedV(t, v);
    const double force = p->model.a3 * p->SegmentU(t) - p->a1 * vd;
    // Inactive functions are a nonzero constant: CVODE then never reports them.
    g[0] = p->mode != 0 ? v : 1.0;
    g[1] = p->mode == 0 ? force - p->model.a2p : 1.0;
    g[2] = p->mode == 0 ? force + p->model.a2n : 1.0;
    g[3] = p->branch != 0 ? vd : 1.0;
    return 0;
  }

  static int Jacobian(double, N_Vector, N_Vector, SUNMatrix J, void* self, N_Vector, N_Vector,
                      N_Vector) {
    const auto* p = static_cast<const SegmentModel*>(self);
    SUNMatZero(J);
    if (p->mode != 0) {
      SM_ELEMENT_D(J, 0, 1) = 1.0;
      // Only with tau = 0 does v' depend on the current v; otherwise v(t - tau) is history.
      SM_ELEMENT_D(J, 1, 1) = p->tau > 0 ? 0.0 : -p->a1;
    }
    return 0;
  }
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIMULATE_SEGMENT_MODEL_HPP_
