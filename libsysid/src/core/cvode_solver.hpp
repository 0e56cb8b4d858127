// The one SUNDIALS CVODE wrapper: an integrator with everything it owns, and one way of turning
// CVODE's negative return flags into readable errors.
//
// Both CVODE users (the simulator, simulate/, and the virtual stage, stage/) need the same
// machinery: a SUNContext per integrator (no globals, so concurrent runs are thread-safe), a
// serial state vector, the CVODE memory, and the nonlinear solver that suits the method —
// fixed-point iteration for Adams (nonstiff: no Jacobian), Newton with a dense direct linear
// solver and the caller's analytic Jacobian for BDF. Owning them in one RAII object frees them
// on every path, exceptions included. CVODE's messages are captured (never printed to stderr)
// and every failure reads the same way:
//   "CVODE failed at t = 1.40716 s: too much work (CV_TOO_MUCH_WORK) in CVode: <CVODE's text>".
#ifndef SYSID_SRC_CORE_CVODE_SOLVER_HPP_
#define SYSID_SRC_CORE_CVODE_SOLVER_HPP_

#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>

#include <string>
#include <vector>

namespace sysid::internal {

/// CVODE's counters summed over re-initialisations (CVodeReInit zeroes CVODE's own).
struct CvodeCounters {
  long steps = 0;
  long rhs_evaluations = 0;  ///< f calls, those for difference-quotient Jacobians included
  long root_evaluations = 0;
};

class CvodeSolver {
 public:
  enum class Method {
    kAdams,  ///< Adams–Moulton, fixed-point iteration (nonstiff)
    kBdf,    ///< BDF, Newton with a dense linear solver (stiff); give SetJacobian
  };

  /// An integrator of `states` equations y' = rhs(t, y) from y(t0) = y0. `user_data` reaches
  /// rhs, the roots and the Jacobian. `context` starts every error message ("virtual stage");
  /// `hint` ends it (what the user can change), may be empty.
  CvodeSolver(int states, Method method, CVRhsFn rhs, void* user_data, double t0,
              const double* y0, std::string context, std::string hint = {});
  ~CvodeSolver();
  CvodeSolver(const CvodeSolver&) = delete;
  CvodeSolver& operator=(const CvodeSolver&) = delete;

  /// The state vector: CVode writes the solution here, ReInit restarts from it.
  N_Vector y() const { return y_; }
  double* state() const { return N_VGetArrayPointer(y_); }
  /// CVODE memory, for the Get functions (CVodeGetDky, CVodeGetLastStep, ...).
  void* mem() const { return mem_; }
  Method method() const { return method_; }

  void SetTolerances(double rtol, double atol);
  /// Absolute tolerance per state (`atol` has `states` entries).
  void SetTolerances(double rtol, const double* atol);
  void SetJacobian(CVLsJacFn jacobian);
  /// `count` root functions g; 0 switches root finding off.
  void SetRoots(int count, CVRootFn g);
  void SetRootDirections(int* directions);
  void SetMaxOrder(int order);
  void SetMaxStep(double h_s);
  void SetMaxNumSteps(long steps);
  void SetInitStep(double h_s);
  void SetStopTime(double t_s);
  /// Forward sensitivities (CVODES) of `count` parameters, from zero: the staggered corrector
  /// (the state's own corrector and steps come first and are unchanged, then the sensitivities'
  /// linear system by fixed-point iteration) with `rhs` giving every sensitivity's right-hand side
  /// at once. Tolerances: CVODES' estimate from the state's, scaled by `scales` (`count` typical
  /// parameter magnitudes). `error_control` false keeps the sensitivities out of the local error
  /// test (the state's steps alone). Adams only (fixed point needs no Jacobian).
  void EnableSensitivities(int count, CVSensRhsFn rhs, const double* scales, bool error_control);
  /// The sensitivities at the last Advance's t (CVodeGetSens: interpolated as the state is),
  /// into sensitivity(i).
  void ReadSensitivities();
  const double* sensitivity(int i) const { return N_VGetArrayPointer(sens_[i]); }
  /// Restarts at t from state() (after a discontinuity): CVODE forgets its history; the
  /// sensitivities restart from their values at t (read here).
  void ReInit(double t_s);
  /// One CVode call. Returns its flag; a negative flag is the caller's to handle (Check or
  /// Describe), so a caller that reports failures without throwing can.
  int Advance(double t_out_s, double* t_reached_s, int task) {
    return CVode(mem_, t_out_s, y_, t_reached_s, task);
  }

  /// Which root functions CVode's last CV_ROOT_RETURN found (+1 rising, -1 falling, 0 not).
  void GetRootInfo(int* found) const { Check(CVodeGetRootInfo(mem_, found), "CVodeGetRootInfo"); }
  /// The k-th derivative of the interpolating polynomial at t (inside the last step); points
  /// into a work vector that the next call overwrites.
  const double* Dky(double t_s, int k);
  /// The Nordsieck array after a step of order q: data of z_0 .. z_q, z_j = h^j / j! y^(j)(t_n)
  /// with h CVODE's current step (the last step's, until the next step starts), so the step's
  /// polynomial is y(t_n + theta h) = sum_j z_j theta^j. Reading it costs nothing, against q
  /// CVodeGetDky calls of up to q + 1 vectors each. CVODE has no getter for it (it lives in the
  /// private cvode_impl.h): the vectors are found by watching the linear combination that
  /// CVodeGetDky(t_n, 0) forms of them, once per order reached (CVODE allocates them once, so
  /// their addresses hold for the solver's life). nullptr when that combination does not look
  /// like z_q .. z_0 with coefficients 0 .. 0, 1 (another SUNDIALS): use Dky instead.
  const double* const* Nordsieck(int q);

  /// CVODE's counters since construction.
  CvodeCounters Counters() const;
  /// CVODE's current internal time (where it stopped, also on failure).
  double CurrentTime() const;

  /// CVODE's name of a flag ("CV_TOO_MUCH_WORK").
  static std::string FlagName(int flag);
  /// One sentence for a failed call: "CVODE failed at t = T s: <reason> (<FLAG>) in <call>:
  /// <CVODE's own message>" (without context and hint).
  std::string Describe(int flag, const char* call) const;
  /// Throws NumericalError("<context>: " + Describe(flag, call) + "; <hint>") if flag < 0.
  void Check(int flag, const char* call) const {
    if (flag < 0) Throw(flag, call);
  }
  [[noreturn]] void Throw(int flag, const char* call) const;

 private:
  static void HandleError(int code, const char* module, const char* function, char* message,
                          void* self);
  void Release();

  Method method_;
  std::string context_, hint_;
  std::string cvode_message_;  // the last error CVODE reported through HandleError
  CvodeCounters before_reinit_;
  SUNContext ctx_ = nullptr;
  N_Vector y_ = nullptr;
  N_Vector atol_ = nullptr;
  N_Vector work_ = nullptr;  // for Dky
  static constexpr int kMaxNordsieck = 13;        // CVODE's L_MAX: orders up to 12
  int nordsieck_order_ = -1;                      // z_0 .. z_order found; -2: not available
  const double* nordsieck_[kMaxNordsieck] = {};  // data of z_j
  void* mem_ = nullptr;
  SUNMatrix matrix_ = nullptr;
  SUNLinearSolver linear_ = nullptr;
  SUNNonlinearSolver fixed_point_ = nullptr;
  int sensitivities_ = 0;
  N_Vector* sens_ = nullptr;  // the sensitivities at the last Advance's t
  std::vector<double> sens_scales_;
  SUNNonlinearSolver sens_fixed_point_ = nullptr;
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_CORE_CVODE_SOLVER_HPP_
