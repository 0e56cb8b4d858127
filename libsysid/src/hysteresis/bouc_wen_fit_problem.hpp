// Private: the Bouc–Wen fit's least-squares problem, shared by its files — the recordings and
// the parameter vector (bouc_wen_fit_layout.cpp), the cost function and its Jacobians
// (bouc_wen_fit_cost.cpp), one Ceres solve and the fixed step's check (bouc_wen_fit_solve.cpp),
// and the fit's course (bouc_wen_fit.cpp).
#ifndef SYSID_SRC_HYSTERESIS_BOUC_WEN_FIT_PROBLEM_HPP_
#define SYSID_SRC_HYSTERESIS_BOUC_WEN_FIT_PROBLEM_HPP_

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/io.hpp"

namespace sysid::internal::bouc_wen_fit {

/// The mechanical form's parameters from the fit's full vector (m, c, k, alpha, beta, gamma,
/// delta, nu: the order of the layout's names).
MechanicalBoucWenParameters MechanicalParameters(const Eigen::VectorXd& p);
/// The piezo form's parameters from the fit's vector (d, alpha, beta, gamma, offset).
PiezoBoucWenParameters PiezoParameters(const Eigen::VectorXd& p);

struct Series {
  Eigen::VectorXd u, x;
  double dt_s;
  // The benchmark chain's upsampled input (internal::ChainInput) or the fixed step's
  // (internal::FixedStepInput), when the fit simulates by one of them: it does not depend on the
  // parameters, and recomputing it (for the chain an FFT of 20 n points) was a fifth of every
  // simulation. Empty otherwise.
  Eigen::VectorXd fine_u;
  // The CVODE simulations' input between samples (u, dt_s and the layout's input), when the fit
  // simulates by CVODE: a band-limited input's table (two inverse FFTs of n L points) is built
  // once here instead of at every simulation and CVODES pass. Null otherwise.
  std::shared_ptr<const SampledInput> input;
};

/// The parameters as one vector: mechanical m, c, k, alpha, beta, gamma, delta, nu; piezo d,
/// alpha, beta, gamma, offset.
struct Layout {
  BoucWenForm form;
  Eigen::VectorXd all;        // every parameter, fixed ones at their value
  std::vector<int> free;      // indices into all
  std::vector<double> scale;  // free parameter i = scale[i] * x[i]
  std::vector<double> lower;  // bounds on x (scaled), -inf when none
  std::vector<double> upper;
  BoucWenSimulationOptions sim;

  Eigen::VectorXd Full(const double* x) const {
    Eigen::VectorXd p = all;
    for (size_t i = 0; i < free.size(); ++i) p[free[i]] = scale[i] * x[i];
    return p;
  }
  std::unique_ptr<HysteresisModel> Model(const Eigen::VectorXd& p,
                                         std::vector<double> errors = {}) const;
  /// True when the fit simulates by CVODE (to its rtol, not to rounding): the mechanical form's
  /// CVODE, the piezo form's for a band-limited input (else its exact closed-form step).
  bool SimulatedByCvode() const {
    return sim.integrator == BoucWenIntegrator::kCvode &&
           (form == BoucWenForm::kMechanical || sim.input == InputInterpolation::kBandLimited);
  }
};

/// The free parameters, their scales and bounds, and the starting values (the options' or, for
/// the mechanical form, the linear fit of docs/hysteresis.md).
Layout MakeLayout(BoucWenForm form, const std::vector<Series>& data, const BoucWenFitOptions& o);

/// The recordings' inputs and sample times, as the fixed step's helpers take them.
SampledRecordings Inputs(const std::vector<Series>& data);

/// Series::input of every recording when the fit simulates by CVODE (after kAuto is resolved:
/// the layout's input); InputError naming the recording's source where CVODE refuses it.
void ShareCvodeInputs(const std::vector<Recording>& recordings, const Layout& layout,
                      std::vector<Series>* data);

/// What the fit computed: plain simulations, and passes with their sensitivities.
struct Work {
  long simulations = 0;
  long sensitivity_passes = 0;
};

/// Ceres evaluates one point up to three times: bounded problems take the trust-region step by
/// a projected line search, which asks for the gradient (the Jacobian) at the full step, then the
/// candidate's cost, then — the step accepted — residuals and Jacobian there again. The last
/// evaluation is kept and answered from: 13 simulations per iteration instead of 27, with
/// identical numbers (a simulation is a deterministic function of the parameters). The cache can
/// outlive its cost function: the final fit starts with the best start's, whose last evaluation
/// is usually its last point. The evaluation before the last is kept too when it had its
/// Jacobian: when Ceres' last candidate is not taken (rejected, or the function tolerance met
/// there), the point it returns is that one, and the standard errors (and the final fit after
/// the best start) ask for its Jacobian again: one exact pass less per solve.
struct EvaluationCache {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  std::vector<double> x;
  Eigen::VectorXd r;
  RowMajor j;
  bool ok = false;
  bool has_jacobian = false;
  std::vector<double> x_before;  // empty: none kept
  Eigen::VectorXd r_before;
  RowMajor j_before;
  bool before_has_jacobian = false;
};

/// y_model - x over every recording, stacked, in the scaled free parameters; the Jacobian by
/// forward sensitivities (the mechanical form: the chain's, the fixed step's or CVODES'; the
/// piezo form's closed-form step) or by central differences, the simulations in parallel.
class OutputError : public ceres::CostFunction {
 public:
  OutputError(const Layout* l, const std::vector<Series>* data, Eigen::Index n, int threads,
              BoucWenJacobian jacobian, Work* work, std::shared_ptr<EvaluationCache> cache);
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override;

 private:
  using RowMajor = EvaluationCache::RowMajor;
  static Eigen::Map<RowMajor> Jacobian(double* j, Eigen::Index n, int np) {
    return Eigen::Map<RowMajor>(j, n, np);
  }
  bool CentralDifferences(const double* x, bool have_residuals, double* residuals,
                          double* jacobian) const;
  bool ResidualsAndSensitivities(const double* x, double* residuals, double* jacobian) const;

  const Layout* l_;
  const std::vector<Series>* data_;
  bool sensitivities_ = false;
  int threads_;
  Work* work_;
  // The last point evaluated and what was computed there (Ceres evaluates serially).
  std::shared_ptr<EvaluationCache> c_;
};

/// The fit's clock and its bound, shared by the starts and the final fit.
struct FitClock {
  std::chrono::steady_clock::time_point start;
  double max_time_s = 0;  // 0: none
  double Elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  bool Bounded() const { return max_time_s > 0; }
  double Remaining() const { return std::max(0.0, max_time_s - Elapsed()); }
};

/// [standard errors] The Gauss–Newton step below which a CVODE-simulated fit with exact
/// Jacobians stops (the solve's NoiseFloorCallback): past it only CVODE's noise moves.
inline constexpr double kNoiseFloorStep = 0.05;

struct Solved {
  std::vector<double> x;
  ceres::Solver::Summary summary;
  bool timed_out = false;  // stopped by BoucWenFitOptions::max_time_s
  // The problem's cost function while the problem is kept (Solve's `keep`): its last
  // evaluation answers the standard errors' Jacobian at the optimum when it was there.
  const OutputError* cost = nullptr;
  std::shared_ptr<EvaluationCache> cache;  // the cost function's, kept after the problem
};

/// One Ceres solve of `iterations` at most from x (scaled), within the clock's bound; `start`
/// (0: the final fit) goes to the progress reports. With `keep` the problem is the caller's.
Solved Solve(const Layout& l, const std::vector<Series>& data, Eigen::Index n,
             std::vector<double> x, int iterations, const BoucWenFitOptions& o,
             const FitClock& clock, int start, Work* work, std::shared_ptr<EvaluationCache> cache,
             ceres::Problem** keep = nullptr);

/// The final model's fixed step against CVODE (rtol 1e-9, the same input): the RMS difference
/// [m] over every sample. Where CVODE refuses the input (its band-limited work bound), step
/// doubling at m instead; *how says which.
double FixedStepCheck(const MechanicalBoucWenParameters& p, const std::vector<Series>& data,
                      const BoucWenSimulationOptions& sim, std::string* how);

}  // namespace sysid::internal::bouc_wen_fit

#endif  // SYSID_SRC_HYSTERESIS_BOUC_WEN_FIT_PROBLEM_HPP_
