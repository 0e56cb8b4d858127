// Fitting a Prandtl–Ishlinskii model: linear least squares in the coefficients with p0, w_i,
// q_i >= 0. Ceres (a bounded trust region) finds the active set on the QR-reduced problem
// (P residuals instead of N); a Lawson–Hanson pass started from Ceres' point then makes the
// free-set solution exact and checks the KKT conditions, because a trust-region solver stops at
// a tolerance and the standard errors need the exact free set. Columns are scaled to unit norm.
#include <ceres/ceres.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/option_rule.hpp"
#include "pi_terms.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace sysid {
namespace {

// [bytes] The regression matrix (N x P doubles) must fit in this.
constexpr double kRegressionMemoryLimitBytes = 4e9;

// r = R x - qtb with the constant Jacobian R (P x P).
class ReducedCost final : public ceres::CostFunction {
 public:
  ReducedCost(const Eigen::MatrixXd& R, const Eigen::VectorXd& qtb) : R_(R), qtb_(qtb) {
    set_num_residuals(static_cast<int>(R.rows()));
    mutable_parameter_block_sizes()->push_back(static_cast<int32_t>(R.cols()));
  }
  bool Evaluate(double const* const* x, double* residuals, double** jacobians) const override {
    const Eigen::Map<const Eigen::VectorXd> theta(x[0], R_.cols());
    Eigen::Map<Eigen::VectorXd>(residuals, R_.rows()) = R_ * theta - qtb_;
    if (jacobians && jacobians[0])
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
          jacobians[0], R_.rows(), R_.cols()) = R_;
    return true;
  }

 private:
  const Eigen::MatrixXd& R_;
  const Eigen::VectorXd& qtb_;
};

Eigen::MatrixXd Columns(const Eigen::MatrixXd& R, const std::vector<int>& cols) {
  Eigen::MatrixXd out(R.rows(), static_cast<Eigen::Index>(cols.size()));
  for (size_t c = 0; c < cols.size(); ++c) out.col(static_cast<Eigen::Index>(c)) = R.col(cols[c]);
  return out;
}

// Least squares on the columns `free` of R; the others 0.
Eigen::VectorXd FreeSolve(const Eigen::MatrixXd& R, const Eigen::VectorXd& qtb,
                          const std::vector<int>& free) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(R.cols());
  if (free.empty()) return x;
  const Eigen::VectorXd xf = Columns(R, free).colPivHouseholderQr().solve(qtb);
  for (size_t c = 0; c < free.size(); ++c) x[free[c]] = xf[static_cast<Eigen::Index>(c)];
  return x;
}

// Lawson–Hanson from the feasible point x (bounded[j]: x_j >= 0). Returns false when it does
// not settle within its iteration budget (then x is Ceres' point, unchanged).
bool LawsonHanson(const Eigen::MatrixXd& R, const Eigen::VectorXd& qtb,
                  const std::vector<bool>& bounded, const std::vector<bool>& fixed,
                  Eigen::VectorXd* x_io) {
  const int P = static_cast<int>(R.cols());
  Eigen::VectorXd x = *x_io;
  std::vector<bool> in_free(static_cast<size_t>(P));
  for (int j = 0; j < P; ++j)
    in_free[static_cast<size_t>(j)] = !fixed[static_cast<size_t>(j)] &&
                                      (!bounded[static_cast<size_t>(j)] || x[j] > 0);
  const double gradient_tolerance = 1e-10 * std::max(1.0, (R.transpose() * qtb).cwiseAbs().maxCoeff());
  for (int outer = 0; outer < 3 * P + 10; ++outer) {
    // Inner loop: move to the free-set optimum, stopping at the boundary of the feasible set.
    for (int inner = 0; inner <= P; ++inner) {
      std::vector<int> free;
      for (int j = 0; j < P; ++j)
        if (in_free[static_cast<size_t>(j)]) free.push_back(j);
      const Eigen::VectorXd z = FreeSolve(R, qtb, free);
      double alpha = 1;
      int blocking = -1;
      for (int j : free)
        if (bounded[static_cast<size_t>(j)] && z[j] <= 0) {
          const double a = x[j] / (x[j] - z[j]);
          if (a < alpha) alpha = a, blocking = j;
        }
      x += alpha * (z - x);
      if (blocking < 0) break;
      for (int j : free)
        if (bounded[static_cast<size_t>(j)] && x[j] <= 1e-300) x[j] = 0, in_free[static_cast<size_t>(j)] = false;
    }
    // KKT: every held parameter's gradient of 1/2 |R x - qtb|^2 must be >= 0.
    const Eigen::VectorXd gradient = R.transpose() * (R * x - qtb);
    int release = -1;
    double most_negative = -gradient_tolerance;
    for (int j = 0; j < P; ++j)
      if (!in_free[static_cast<size_t>(j)] && !fixed[static_cast<size_t>(j)] && gradient[j] < most_negative)
        most_negative = gradient[j], release = j;
    if (release < 0) {
      *x_io = x;
      return true;
    }
    in_free[static_cast<size_t>(release)] = true;
  }
  return false;
}

// min ||R x - qtb|| with x_j >= 0 where bounded and x_j = 0 where fixed: Ceres from the clipped
// unconstrained solution, then the exact active set (Lawson-Hanson) from Ceres' point. `exact`
// says whether the active set settled; otherwise Ceres' point is kept and a note says so.
Eigen::VectorXd BoundedLeastSquares(const Eigen::MatrixXd& R, const Eigen::VectorXd& qtb,
                                    const std::vector<bool>& bounded,
                                    const std::vector<bool>& fixed, bool* exact,
                                    std::vector<std::string>* notes) {
  const int P = static_cast<int>(R.cols());
  // Start: the unconstrained solution with bounded parameters clipped to a small positive value.
  std::vector<int> all;
  for (int j = 0; j < P; ++j)
    if (!fixed[static_cast<size_t>(j)]) all.push_back(j);
  Eigen::VectorXd x = FreeSolve(R, qtb, all);
  const double x_floor = 1e-6 * std::max(1e-300, x.cwiseAbs().maxCoeff());
  for (int j = 0; j < P; ++j)
    if (bounded[static_cast<size_t>(j)] && !fixed[static_cast<size_t>(j)] && x[j] < x_floor) x[j] = x_floor;
  ceres::Problem problem;
  problem.AddResidualBlock(new ReducedCost(R, qtb), nullptr, x.data());
  for (int j = 0; j < P; ++j)
    if (bounded[static_cast<size_t>(j)] && !fixed[static_cast<size_t>(j)])
      problem.SetParameterLowerBound(x.data(), j, 0.0);
  std::vector<int> constant;
  for (int j = 0; j < P; ++j)
    if (fixed[static_cast<size_t>(j)]) constant.push_back(j);
  if (!constant.empty() && static_cast<int>(constant.size()) < P)
    problem.SetManifold(x.data(), new ceres::SubsetManifold(P, constant));
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = 500;
  so.function_tolerance = 1e-15;
  so.gradient_tolerance = 1e-15;
  so.parameter_tolerance = 1e-15;
  so.logging_type = ceres::SILENT;
  so.num_threads = 1;
  ceres::Solver::Summary cs;
  ceres::Solve(so, &problem, &cs);
  if (!cs.IsSolutionUsable())
    throw NumericalError("hysteresis fit: the bounded least squares failed: " + cs.message);
  *exact = LawsonHanson(R, qtb, bounded, fixed, &x);
  if (!*exact) notes->push_back("the active set did not settle: Ceres' point kept (" + cs.BriefReport() + ")");

  return x;
}

// Standard errors of the free parameters (sigma2 (Rf' Rf)^-1 in scaled units, back to the
// parameters' units by `scale`; NaN for the others) and the condition number of the free
// columns (NaN when none is free).
double StandardErrors(const Eigen::MatrixXd& R, const std::vector<int>& free,
                      const Eigen::VectorXd& scale, double sigma2, std::vector<double>* se) {
  se->assign(static_cast<size_t>(R.cols()), NAN);
  if (free.empty()) return NAN;
  const Eigen::MatrixXd Rf = Columns(R, free);
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Rf);
  const Eigen::VectorXd sv = svd.singularValues();
  if (sv[sv.size() - 1] > 0) {
    const Eigen::MatrixXd cov = sigma2 * (Rf.transpose() * Rf).inverse();
    for (size_t c = 0; c < free.size(); ++c)
      (*se)[static_cast<size_t>(free[c])] =
          std::sqrt(cov(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(c))) /
          scale[free[c]];
  }
  return sv[0] / sv[sv.size() - 1];
}

// Scales A's columns to unit norm (the returned factors) and marks each parameter bounded
// (>= 0) or fixed at 0: a zero regressor (noted), the offset when not fitted, held terms.
Eigen::VectorXd ScaleColumns(const internal::PiLayout& layout, bool offset, Eigen::MatrixXd* A,
                             std::vector<bool>* bounded, std::vector<bool>* fixed,
                             std::vector<std::string>* notes) {
  const int P = layout.size();
  bounded->assign(static_cast<size_t>(P), false);
  fixed->assign(static_cast<size_t>(P), false);
  Eigen::VectorXd scale(P);
  for (int j = 0; j < P; ++j) {
    (*bounded)[static_cast<size_t>(j)] = layout.bounded(j);
    scale[j] = A->col(j).norm();
    if (!(scale[j] > 0)) {  // e.g. a rate column of recordings that never move
      scale[j] = 1;
      (*fixed)[static_cast<size_t>(j)] = true;
      notes->push_back(layout.name(j) + " fixed at 0 (its regressor is zero)");
    }
  }
  if (!offset) (*fixed)[static_cast<size_t>(layout.offset())] = true;
  for (int j = 0; j < P; ++j)
    if (layout.held(j)) (*fixed)[static_cast<size_t>(j)] = true;
  for (int j = 0; j < P; ++j)
    if ((*fixed)[static_cast<size_t>(j)]) A->col(j).setZero();
  A->array().rowwise() /= scale.transpose().array();
  return scale;
}

// The fit's one-line account: the active bounds, the conditioning, invertibility, the notes.
std::string FitMessage(const PrandtlIshlinskiiModel& model, const PiFitReport& rep,
                       const PiFitOptions& options, bool exact,
                       const std::vector<std::string>& active, int P, double condition,
                       const std::vector<std::string>& notes) {
  std::string message = fmt::format(
      "non-negative least squares ({}): {} of {} parameters at their bound 0{}; condition number "
      "of the regression (unit-norm columns) {:.3g}",
      exact ? "exact active set" : "Ceres' point", active.size(), P,
      active.empty() ? "" : " (" + fmt::format("{}", fmt::join(active, ", ")) + ")", condition);
  if (!model.invertible())
    message += "; not invertible: " + model.why_not_invertible();
  else if (rep.ill_conditioned_inverse)
    message += fmt::format("; ill-conditioned inverse: the loading slopes span a ratio {:.3g} > "
                           "{:.3g}, the inverse amplifies reference noise by up to that factor",
                           rep.inverse_gain_ratio, options.ill_conditioned_ratio);
  else
    message += fmt::format("; inverse gain ratio {:.3g}", rep.inverse_gain_ratio);
  for (const auto& note : notes) message += "; " + note;
  return message;
}

}  // namespace

void PiFitOptions::Validate() const {
  auto fail = [](const std::string& field, double value, const std::string& rule) {
    internal::FailOption("PiFitOptions", field, value, rule);
  };
  if (thresholds.empty() && (operators < 1 || operators > kMaxPlayOperators))
    fail("operators", operators, fmt::format("1 <= operators <= {} (kMaxPlayOperators)", kMaxPlayOperators));
  if (thresholds.size() > static_cast<size_t>(kMaxPlayOperators))
    fail("thresholds", static_cast<double>(thresholds.size()),
         fmt::format("at most {} thresholds (kMaxPlayOperators)", kMaxPlayOperators));
  for (size_t i = 0; i < thresholds.size(); ++i) {
    const std::string f = fmt::format("thresholds[{}]", i);
    if (!std::isfinite(thresholds[i]) || !(thresholds[i] > 0)) fail(f, thresholds[i], f + " > 0 [V], finite");
    if (i > 0 && !(thresholds[i] > thresholds[i - 1]))
      fail(f, thresholds[i], fmt::format("{} > thresholds[{}] = {} (strictly increasing)", f, i - 1,
                                         thresholds[i - 1]));
  }
  if (polynomial_degree < 3 || polynomial_degree > 5)
    fail("polynomial_degree", polynomial_degree, "3 <= polynomial_degree <= 5");
  if (!(ill_conditioned_ratio > 1)) fail("ill_conditioned_ratio", ill_conditioned_ratio, "> 1");
  if (!(range_margin >= 0 && range_margin <= 1)) fail("range_margin", range_margin, "in [0, 1]");
}

std::unique_ptr<PrandtlIshlinskiiModel> FitPrandtlIshlinskii(
    const std::vector<Recording>& recordings, const PiFitOptions& options,
    HysteresisFitSummary* summary, PiFitReport* report) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  if (recordings.empty()) throw InputError("hysteresis fit: no recordings");
  Eigen::Index N = 0;
  double u_min = HUGE_VAL, u_max = -HUGE_VAL;
  std::vector<double> steps;
  for (const Recording& rec : recordings) {
    const auto u = rec.column("u");
    rec.column("x");
    steps.push_back(RecordingStep(rec));
    N += rec.rows();
    u_min = std::min(u_min, u.minCoeff());
    u_max = std::max(u_max, u.maxCoeff());
  }
  if (!(u_max > u_min))
    throw InputError(fmt::format("{}: column 'u' is constant ({} V): nothing to fit a hysteresis to",
                                 recordings.front().source, u_min));
  PiParameters p;
  p.form = options.form;
  p.thresholds = options.thresholds.empty() ? UniformThresholds(u_min, u_max, options.operators)
                                            : options.thresholds;
  const size_t n = p.thresholds.size();
  p.weights.assign(n, 0.0);
  p.polynomial.assign(options.form == PiForm::kPolynomial ? static_cast<size_t>(options.polynomial_degree) : 1, 0.0);
  if (options.form == PiForm::kRateDependent) p.rate_weights.assign(n + 1, 0.0);
  p.input_min_v = u_min;
  p.input_max_v = u_max;
  const internal::PiLayout layout = internal::LayoutOf(p);
  const int P = layout.size();
  if (static_cast<double>(N) * P * 8 > kRegressionMemoryLimitBytes)
    throw OptionsError(fmt::format("hysteresis fit: {} samples x {} parameters need a {:.3g} GB "
                                   "regression matrix, more than the limit {:.3g} GB: use fewer "
                                   "operators or samples",
                                   N, P, static_cast<double>(N) * P * 8e-9, kRegressionMemoryLimitBytes * 1e-9),
                       "operators");
  if (N <= P)
    throw InputError(fmt::format("hysteresis fit: {} samples for {} parameters: expected more "
                                 "samples than parameters", N, P));

  Eigen::MatrixXd A(N, P);
  Eigen::VectorXd b(N);
  Eigen::Index row = 0;
  for (size_t r = 0; r < recordings.size(); ++r) {
    const Eigen::VectorXd u = recordings[r].column("u");
    const Eigen::VectorXd x = recordings[r].column("x");
    internal::FillTerms(p, u, steps[r], row, &A);
    b.segment(row, u.size()) = x;
    row += u.size();
  }
  std::vector<bool> bounded, fixed;
  std::vector<std::string> notes;
  const Eigen::VectorXd scale = ScaleColumns(layout, options.offset, &A, &bounded, &fixed, &notes);
  Eigen::HouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::MatrixXd R = qr.matrixQR().topRows(P).triangularView<Eigen::Upper>();
  const Eigen::VectorXd qtb = (qr.householderQ().transpose() * b).head(P);

  bool exact = false;
  Eigen::VectorXd x = BoundedLeastSquares(R, qtb, bounded, fixed, &exact, &notes);
  std::vector<int> free;
  std::vector<std::string> active;
  for (int j = 0; j < P; ++j) {
    if (fixed[static_cast<size_t>(j)]) continue;
    if (bounded[static_cast<size_t>(j)] && !(x[j] > 0)) {
      active.push_back(layout.name(j));
      x[j] = 0;
    } else {
      free.push_back(j);
    }
  }
  const Eigen::VectorXd theta = x.cwiseQuotient(scale);
  internal::Unpack(theta, &p);
  // Residuals in metres: A is scaled, x is in scaled units.
  const double rss = (A * x - b).squaredNorm();
  const double dof = static_cast<double>(N) - static_cast<double>(free.size());
  const double sigma2 = rss / std::max(1.0, dof);
  std::vector<double> se;
  const double condition = StandardErrors(R, free, scale, sigma2, &se);
  if (!options.offset) se[static_cast<size_t>(layout.offset())] = NAN;
  auto model = std::make_unique<PrandtlIshlinskiiModel>(p, se, options.range_margin);
  PiFitReport rep;
  rep.active_constraints = active;
  rep.condition_number = condition;
  rep.inverse_gain_ratio = model->InverseGainRatio();
  rep.ill_conditioned_inverse = !(rep.inverse_gain_ratio <= options.ill_conditioned_ratio);
  rep.residual_std = std::sqrt(sigma2);
  const std::string message = FitMessage(*model, rep, options, exact, active, P, condition, notes);
  if (summary) {
    summary->kind = model->kind();
    summary->samples = static_cast<int>(N);
    summary->fit_time_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary->training_rms = std::sqrt(rss / static_cast<double>(N));
    summary->converged = exact;
    summary->message = message;
  }
  if (report) *report = rep;
  return model;
}

}  // namespace sysid
