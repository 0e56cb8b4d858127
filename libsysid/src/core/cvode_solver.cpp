#include "core/cvode_solver.hpp"

#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cstdio>
#include <cstdlib>
#include <utility>

#include "core/small_vector_ops.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {
namespace {

/// What a flag means, in words a user can act on (CVODE's names are terse).
const char* Reason(int flag) {
  switch (flag) {
    case CV_TOO_MUCH_WORK: return "too much work (the step budget ran out before the stop time)";
    case CV_TOO_MUCH_ACC: return "more accuracy requested than the machine precision allows";
    case CV_ERR_FAILURE: return "the error test failed repeatedly (the solution changes too fast)";
    case CV_CONV_FAILURE: return "the nonlinear solver failed to converge repeatedly";
    case CV_LINIT_FAIL: return "the linear solver could not be initialised";
    case CV_LSETUP_FAIL: return "the linear solver's setup failed";
    case CV_LSOLVE_FAIL: return "the linear solver failed";
    case CV_RHSFUNC_FAIL: return "the right-hand side failed (a non-finite value)";
    case CV_FIRST_RHSFUNC_ERR: return "the right-hand side failed at the first call";
    case CV_REPTD_RHSFUNC_ERR: return "the right-hand side failed repeatedly";
    case CV_UNREC_RHSFUNC_ERR: return "the right-hand side failed unrecoverably";
    case CV_RTFUNC_FAIL: return "a root function failed";
    case CV_MEM_FAIL: return "out of memory";
    case CV_ILL_INPUT: return "an input to CVODE is illegal";
    case CV_TOO_CLOSE: return "the output time is too close to the start time";
    default: return "CVODE error";
  }
}

/// What one N_VLinearCombination call was asked to form (see CvodeSolver::Nordsieck).
struct CombinationSeen {
  int nvec = 0;
  double c[16] = {};
  N_Vector x[16] = {};
};
// Set only around the one CVodeGetDky call that CvodeSolver::Nordsieck makes on its own work
// vector, in the calling thread: concurrent solvers never see each other's.
thread_local CombinationSeen* combination_seen = nullptr;

/// The serial linear combination, noting its operands while combination_seen is set.
int WatchedLinearCombination(int nvec, double* c, N_Vector* x, N_Vector z) {
  if (CombinationSeen* seen = combination_seen) {
    seen->nvec = nvec;
    for (int i = 0; i < nvec && i < 16; ++i) {
      seen->c[i] = c[i];
      seen->x[i] = x[i];
    }
  }
  return N_VLinearCombination_Serial(nvec, c, x, z);
}

std::string Seconds(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", t);
  return text;
}

}  // namespace

CvodeSolver::CvodeSolver(int states, Method method, CVRhsFn rhs, void* user_data, double t0,
                         const double* y0, std::string context, std::string hint)
    : method_(method), context_(std::move(context)), hint_(std::move(hint)) {
  // A constructor that throws runs no destructor: free what was made on the way.
  try {
    if (SUNContext_Create(nullptr, &ctx_) != 0) ctx_ = nullptr;
    if (ctx_) y_ = N_VNew_Serial(states, ctx_);
    if (!y_) Throw(CV_MEM_FAIL, "SUNContext_Create/N_VNew_Serial");
    // Fused vector operations: one call per linear combination instead of one per term
    // (CVODE's Nordsieck updates and CVodeGetDky are linear combinations of up to 13 vectors).
    Check(N_VEnableFusedOps_Serial(y_, SUNTRUE), "N_VEnableFusedOps_Serial");
    // CVODE's vectors are clones of y: 1 to 4 states get fixed-length operations.
    UseSmallVectorOps(y_);
    double* y = state();
    for (int i = 0; i < states; ++i) y[i] = y0[i];
    mem_ = CVodeCreate(method == Method::kBdf ? CV_BDF : CV_ADAMS, ctx_);
    if (!mem_) Throw(CV_MEM_FAIL, "CVodeCreate");
    Check(CVodeSetErrHandlerFn(mem_, &CvodeSolver::HandleError, this), "CVodeSetErrHandlerFn");
    Check(CVodeInit(mem_, rhs, t0, y_), "CVodeInit");
    Check(CVodeSetUserData(mem_, user_data), "CVodeSetUserData");
    if (method == Method::kBdf) {
      matrix_ = SUNDenseMatrix(states, states, ctx_);
      if (matrix_) linear_ = SUNLinSol_Dense(y_, matrix_, ctx_);
      if (!linear_) Throw(CV_MEM_FAIL, "SUNLinSol_Dense");
      Check(CVodeSetLinearSolver(mem_, linear_, matrix_), "CVodeSetLinearSolver");
    } else {
      // Adams is for nonstiff problems: fixed-point iteration needs no Jacobian.
      fixed_point_ = SUNNonlinSol_FixedPoint(y_, 0, ctx_);
      if (!fixed_point_) Throw(CV_MEM_FAIL, "SUNNonlinSol_FixedPoint");
      Check(CVodeSetNonlinearSolver(mem_, fixed_point_), "CVodeSetNonlinearSolver");
    }
  } catch (...) {
    Release();
    throw;
  }
}

CvodeSolver::~CvodeSolver() { Release(); }

void CvodeSolver::Release() {
  if (mem_) CVodeFree(&mem_);
  if (sens_fixed_point_) SUNNonlinSolFree(sens_fixed_point_);
  if (sens_) N_VDestroyVectorArray(sens_, sensitivities_);
  sens_fixed_point_ = nullptr;
  sens_ = nullptr;
  if (fixed_point_) SUNNonlinSolFree(fixed_point_);
  if (linear_) SUNLinSolFree(linear_);
  if (matrix_) SUNMatDestroy(matrix_);
  if (work_) N_VDestroy(work_);
  if (atol_) N_VDestroy(atol_);
  if (y_) N_VDestroy(y_);
  if (ctx_) SUNContext_Free(&ctx_);
  fixed_point_ = nullptr;
  linear_ = nullptr;
  matrix_ = nullptr;
  work_ = atol_ = y_ = nullptr;
}

void CvodeSolver::SetTolerances(double rtol, double atol) {
  Check(CVodeSStolerances(mem_, rtol, atol), "CVodeSStolerances");
}

void CvodeSolver::SetTolerances(double rtol, const double* atol) {
  if (!atol_) atol_ = N_VClone(y_);
  if (!atol_) Throw(CV_MEM_FAIL, "N_VClone");
  double* a = N_VGetArrayPointer(atol_);
  for (sunindextype i = 0; i < N_VGetLength(atol_); ++i) a[i] = atol[i];
  Check(CVodeSVtolerances(mem_, rtol, atol_), "CVodeSVtolerances");
}

void CvodeSolver::SetJacobian(CVLsJacFn jacobian) {
  Check(CVodeSetJacFn(mem_, jacobian), "CVodeSetJacFn");
}

void CvodeSolver::SetRoots(int count, CVRootFn g) {
  Check(CVodeRootInit(mem_, count, count > 0 ? g : nullptr), "CVodeRootInit");
  // Callers switch root functions off by making them a nonzero constant: not worth a warning.
  if (count > 0) Check(CVodeSetNoInactiveRootWarn(mem_), "CVodeSetNoInactiveRootWarn");
}

void CvodeSolver::SetRootDirections(int* directions) {
  Check(CVodeSetRootDirection(mem_, directions), "CVodeSetRootDirection");
}

void CvodeSolver::SetMaxOrder(int order) { Check(CVodeSetMaxOrd(mem_, order), "CVodeSetMaxOrd"); }

void CvodeSolver::SetMaxStep(double h_s) { Check(CVodeSetMaxStep(mem_, h_s), "CVodeSetMaxStep"); }

void CvodeSolver::SetMaxNumSteps(long steps) {
  Check(CVodeSetMaxNumSteps(mem_, steps), "CVodeSetMaxNumSteps");
}

void CvodeSolver::SetInitStep(double h_s) { Check(CVodeSetInitStep(mem_, h_s), "CVodeSetInitStep"); }

void CvodeSolver::SetStopTime(double t_s) { Check(CVodeSetStopTime(mem_, t_s), "CVodeSetStopTime"); }

void CvodeSolver::ReInit(double t_s) {
  before_reinit_ = Counters();
  // The sensitivities at t_s from the history that the restart discards.
  if (sensitivities_ > 0) ReadSensitivities();
  Check(CVodeReInit(mem_, t_s, y_), "CVodeReInit");
  if (sensitivities_ > 0) Check(CVodeSensReInit(mem_, CV_STAGGERED, sens_), "CVodeSensReInit");
}

void CvodeSolver::EnableSensitivities(int count, CVSensRhsFn rhs, const double* scales,
                                      bool error_control) {
  if (method_ != Method::kAdams || sensitivities_ > 0 || count < 1)
    Throw(CV_ILL_INPUT, "EnableSensitivities");
  sens_ = N_VCloneVectorArray(count, y_);
  if (!sens_) Throw(CV_MEM_FAIL, "N_VCloneVectorArray");
  sensitivities_ = count;
  for (int i = 0; i < count; ++i) N_VConst(0.0, sens_[i]);
  sens_scales_.assign(scales, scales + count);
  Check(CVodeSensInit(mem_, count, CV_STAGGERED, rhs, sens_), "CVodeSensInit");
  Check(CVodeSetSensParams(mem_, nullptr, sens_scales_.data(), nullptr), "CVodeSetSensParams");
  Check(CVodeSensEEtolerances(mem_), "CVodeSensEEtolerances");
  Check(CVodeSetSensErrCon(mem_, error_control ? SUNTRUE : SUNFALSE), "CVodeSetSensErrCon");
  // CVODES defaults to Newton for the sensitivities, which needs a linear solver.
  sens_fixed_point_ = SUNNonlinSol_FixedPointSens(count, y_, 0, ctx_);
  if (!sens_fixed_point_) Throw(CV_MEM_FAIL, "SUNNonlinSol_FixedPointSens");
  Check(CVodeSetNonlinearSolverSensStg(mem_, sens_fixed_point_),
        "CVodeSetNonlinearSolverSensStg");
}

void CvodeSolver::ReadSensitivities() {
  double t = 0;
  Check(CVodeGetSens(mem_, &t, sens_), "CVodeGetSens");
}

const double* CvodeSolver::Dky(double t_s, int k) {
  if (!work_) work_ = N_VClone(y_);
  if (!work_) Throw(CV_MEM_FAIL, "N_VClone");
  Check(CVodeGetDky(mem_, t_s, k, work_), "CVodeGetDky");
  return N_VGetArrayPointer(work_);
}

const double* const* CvodeSolver::Nordsieck(int q) {
  if (q <= nordsieck_order_) return nordsieck_;
  if (nordsieck_order_ == -2 || q >= kMaxNordsieck) return nullptr;
  if (!work_) work_ = N_VClone(y_);
  if (!work_) Throw(CV_MEM_FAIL, "N_VClone");
  // N_VLinearCombination dispatches on its output vector: only work_ is watched.
  work_->ops->nvlinearcombination = &WatchedLinearCombination;
  double tn = 0;
  Check(CVodeGetCurrentTime(mem_, &tn), "CVodeGetCurrentTime");
  CombinationSeen seen;
  combination_seen = &seen;
  const int flag = CVodeGetDky(mem_, tn, 0, work_);
  combination_seen = nullptr;
  Check(flag, "CVodeGetDky");
  // At theta = 0 the combination is z_q .. z_1 times 0 and z_0 times 1, giving z_0.
  bool ok = seen.nvec == q + 1 && seen.c[q] == 1.0;
  for (int i = 0; ok && i < q; ++i) ok = seen.c[i] == 0.0 && seen.x[i] != seen.x[q];
  if (ok) {
    const double* z0 = N_VGetArrayPointer(seen.x[q]);
    const double* dky = N_VGetArrayPointer(work_);
    for (sunindextype i = 0; ok && i < N_VGetLength(work_); ++i) ok = z0[i] == dky[i];
  }
  if (!ok) {
    nordsieck_order_ = -2;
    return nullptr;
  }
  for (int j = 0; j <= q; ++j) nordsieck_[j] = N_VGetArrayPointer(seen.x[q - j]);
  nordsieck_order_ = q;
  return nordsieck_;
}

CvodeCounters CvodeSolver::Counters() const {
  long steps = 0, fe = 0, fe_jacobian = 0, ge = 0;
  CVodeGetNumSteps(mem_, &steps);
  CVodeGetNumRhsEvals(mem_, &fe);
  CVodeGetNumGEvals(mem_, &ge);
  if (method_ == Method::kBdf) CVodeGetNumLinRhsEvals(mem_, &fe_jacobian);
  CvodeCounters c = before_reinit_;
  c.steps += steps;
  c.rhs_evaluations += fe + fe_jacobian;
  c.root_evaluations += ge;
  return c;
}

double CvodeSolver::CurrentTime() const {
  double t = 0;
  if (mem_) CVodeGetCurrentTime(mem_, &t);
  return t;
}

std::string CvodeSolver::FlagName(int flag) {
  char* name = CVodeGetReturnFlagName(flag);  // allocated by CVODE: ours to free
  std::string result = name ? name : "CV_UNKNOWN";
  std::free(name);
  return result;
}

std::string CvodeSolver::Describe(int flag, const char* call) const {
  std::string text = "CVODE failed";
  if (mem_) text += " at t = " + Seconds(CurrentTime()) + " s";
  text += std::string(": ") + Reason(flag) + " (" + FlagName(flag) + ") in " + call;
  if (!cvode_message_.empty()) text += ": " + cvode_message_;
  return text;
}

void CvodeSolver::Throw(int flag, const char* call) const {
  std::string text = context_ + ": " + Describe(flag, call);
  if (!hint_.empty()) text += "; " + hint_;
  throw NumericalError(text);
}

void CvodeSolver::HandleError(int code, const char* module, const char* function, char* message,
                              void* self) {
  if (code >= 0) return;  // warnings (e.g. t + h = t) do not stop a run
  std::string text = std::string(module) + "::" + function + ": " + message;
  if (!text.empty() && text.back() == '.') text.pop_back();  // it goes inside our sentence
  static_cast<CvodeSolver*>(self)->cvode_message_ = std::move(text);
}

}  // namespace sysid::internal
