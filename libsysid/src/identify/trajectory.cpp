// Trajectory (inverse-model) least squares: u = (1/a3) x'' + (a1/a3) v(t - tau) + (a2/a3) sgn v.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "identify/linear_fit.hpp"
#include "numerics/bounded_search.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"
#include "sysid/signal.hpp"

namespace sysid {

MotionOptions TrajectoryOptions::DefaultMotion() {
  MotionOptions m;
  m.derivative.method = DerivativeMethod::kButterworthCentral;
  return m;
}

void TrajectoryOptions::Validate() const {
  motion.Validate();
  auto rule = [](const char* field, double value, const char* what) {
    internal::FailOption("TrajectoryOptions", field, value, what);
  };
  if (!(tau_s >= 0) || !std::isfinite(tau_s)) rule("tau_s", tau_s, "tau_s >= 0 [s]");
  if (!(tau_min_s >= 0) || !std::isfinite(tau_min_s))
    rule("tau_min_s", tau_min_s, "tau_min_s >= 0 [s]");
  if (!(tau_max_s > tau_min_s) || !std::isfinite(tau_max_s))
    rule("tau_max_s", tau_max_s, "tau_max_s > tau_min_s [s]");
  if (decimation < 1) rule("decimation", decimation, "decimation >= 1");
  if (!(min_speed_mps > 0) || !std::isfinite(min_speed_mps))
    rule("min_speed_mps", min_speed_mps, "min_speed_mps > 0 [m/s]");
  if (trim_samples < 0) rule("trim_samples", trim_samples, "trim_samples >= 0");
}

namespace {

struct Regression {
  Eigen::MatrixXd X;
  Eigen::VectorXd y;
  Eigen::Index positive = 0, negative = 0;
};

Regression Build(const std::vector<MotionSignals>& motions, const TrajectoryOptions& o,
                 double tau_s) {
  const Eigen::Index p = o.symmetric_viscous ? 4 : 5;
  Regression r;
  Eigen::Index total = 0;
  std::vector<std::array<Eigen::VectorXd, 4>> signals;  // u, a, v, v_delayed
  for (const auto& m : motions) {
    Eigen::VectorXd vd = DelaySignal(m.v_mps, m.dt_s, tau_s, DelayStart::kNaN);
    std::array<Eigen::VectorXd, 4> s{m.u_v, m.a_mps2, m.v_mps, vd};
    if (o.decimation > 1) {
      // The samples before the delay's start are not data: hold the first real value for the
      // anti-alias filter, the rows are dropped below anyway.
      const Eigen::Index skip = static_cast<Eigen::Index>(std::ceil(tau_s / m.dt_s));
      for (Eigen::Index k = 0; k < std::min(skip, vd.size()); ++k)
        s[3][k] = vd[std::min(skip, vd.size() - 1)];
      for (auto& x : s) x = Decimate(x, m.dt_s, o.decimation);
      const Eigen::Index keep = s[0].size();
      for (Eigen::Index k = 0; k * o.decimation < std::min(skip, vd.size()) && k < keep; ++k)
        s[3][k] = std::numeric_limits<double>::quiet_NaN();
    }
    total += s[0].size();
    signals.push_back(std::move(s));
  }
  r.X.resize(total, p);
  r.y.resize(total);
  Eigen::Index row = 0;
  for (const auto& s : signals) {
    const Eigen::Index n = s[0].size();
    const Eigen::Index trim = std::max<Eigen::Index>(0, o.trim_samples / o.decimation);
    for (Eigen::Index k = trim; k < n - trim; ++k) {
      const double v = s[2][k], vd = s[3][k];
      // Stuck or reversing samples obey static friction, not the sliding equation.
      if (!std::isfinite(vd) || std::abs(v) < o.min_speed_mps || std::abs(vd) < o.min_speed_mps)
        continue;
      const double pos = v > 0 ? 1.0 : 0.0, neg = v < 0 ? 1.0 : 0.0;
      Eigen::Index c = 0;
      r.X(row, c++) = s[1][k];
      if (o.symmetric_viscous) {
        r.X(row, c++) = vd;
      } else {
        r.X(row, c++) = vd > 0 ? vd : 0.0;
        r.X(row, c++) = vd < 0 ? vd : 0.0;
      }
      if (o.offset) {
        r.X(row, c++) = pos - neg;
        r.X(row, c++) = 1.0;
      } else {
        r.X(row, c++) = pos;
        r.X(row, c++) = -neg;
      }
      r.y[row] = s[0][k];
      (v > 0 ? r.positive : r.negative) += 1;
      ++row;
    }
  }
  r.X.conservativeResize(row, p);
  r.y.conservativeResize(row);
  return r;
}

// Physical parameter of each column; the column's coefficient is (parameter / a3), and the
// first column's is 1 / a3.
std::vector<std::string> ColumnParameters(const TrajectoryOptions& o) {
  std::vector<std::string> names{"a3"};
  if (o.symmetric_viscous) {
    names.push_back("a1");
  } else {
    names.insert(names.end(), {"a1p", "a1n"});
  }
  if (o.offset) {
    names.insert(names.end(), {"a2", "c0"});
  } else {
    names.insert(names.end(), {"a2p", "a2n"});
  }
  return names;
}

std::vector<std::string> ThetaNames(const TrajectoryOptions& o) {
  std::vector<std::string> names;
  for (const auto& n : ColumnParameters(o)) names.push_back(n == "a3" ? "1/a3" : n + "/a3");
  return names;
}

}  // namespace

TrajectoryIdentificationResult IdentifyFromTrajectory(const std::vector<Recording>& recordings,
                                                      const TrajectoryOptions& options) {
  options.Validate();
  if (recordings.empty()) throw OptionsError("IdentifyFromTrajectory: no recordings given");
  std::vector<MotionSignals> motions;
  for (const auto& rec : recordings) motions.push_back(ExtractMotion(rec, options.motion));
  TrajectoryIdentificationResult result;
  result.derivative = options.motion.derivative.method;
  double tau = options.tau_s;
  if (options.tune_delay) {
    internal::ScalarSearchOptions so;
    so.lo = options.tau_min_s;
    so.hi = options.tau_max_s;
    so.x_tolerance = 1e-3 * motions.front().dt_s;  // far below what the data can resolve
    const auto search = internal::MinimizeScalar(
        [&](double t) {
          const Regression r = Build(motions, options, t);
          if (r.X.rows() <= r.X.cols()) return std::numeric_limits<double>::infinity();
          auto out = internal::SolveLinearFit(r.X, r.y, ThetaNames(options));
          if (!out.unidentified.empty()) return std::numeric_limits<double>::infinity();
          return out.fit.residuals.squaredNorm();
        },
        so);
    tau = search.x;
    result.tau_curve = search.evaluated;
    std::sort(result.tau_curve.begin(), result.tau_curve.end());
  }
  const Regression reg = Build(motions, options, tau);
  std::vector<std::string> missing;
  if (reg.positive == 0) missing.push_back(options.offset ? "a1p" : "a1p, a2p");
  if (reg.negative == 0) missing.push_back(options.offset ? "a1n" : "a1n, a2n");
  if (!missing.empty())
    throw NumericalError(fmt::format(
        "{}: no moving samples with {} (|v| >= min_speed_mps = {} m/s)",
        missing.size() == 2 ? missing[0] + ", " + missing[1] : missing[0],
        missing.size() == 2 ? "v > 0 or v < 0" : (reg.positive == 0 ? "v > 0" : "v < 0"),
        options.min_speed_mps));
  if (reg.X.rows() <= reg.X.cols())
    throw NumericalError(fmt::format("only {} moving samples: not enough for {} parameters",
                                     reg.X.rows(), reg.X.cols()));
  auto outcome = internal::SolveLinearFit(reg.X, reg.y, ThetaNames(options));
  if (!outcome.unidentified.empty()) {
    std::string names;
    for (auto s : outcome.unidentified) {
      if (s.size() > 3 && s.compare(s.size() - 3, 3, "/a3") == 0) s.resize(s.size() - 3);
      if (s == "1") s = "a3";
      names += (names.empty() ? "" : ", ") + s;
    }
    throw NumericalError(names +
                         ": not identifiable from these recordings (rank-deficient "
                         "regressor: too little excitation)");
  }
  LinearFit& f = outcome.fit;
  const Eigen::VectorXd& th = f.theta;
  if (!(th[0] > 0))
    throw NumericalError(
        fmt::format("a3: the fitted 1/a3 = {:.4g} V s^2/m is not positive: "
                    "the acceleration does not explain the voltage (too little "
                    "excitation or a wrong sign convention)",
                    th[0]));
  // Physical parameters p_i = theta_i / theta_0 and a3 = 1 / theta_0; delta-method covariance.
  const Eigen::Index p = th.size();
  Eigen::VectorXd phys(p);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(p, p);
  phys[0] = 1 / th[0];
  G(0, 0) = -1 / (th[0] * th[0]);
  for (Eigen::Index i = 1; i < p; ++i) {
    phys[i] = th[i] / th[0];
    G(i, 0) = -th[i] / (th[0] * th[0]);
    G(i, i) = 1 / th[0];
  }
  result.names = ColumnParameters(options);
  result.estimate = phys;
  result.covariance = G * f.covariance * G.transpose();
  result.std_error = result.covariance.diagonal().cwiseSqrt();
  auto get = [&](const char* name) {
    for (size_t i = 0; i < result.names.size(); ++i)
      if (result.names[i] == name) return phys[static_cast<Eigen::Index>(i)];
    return std::numeric_limits<double>::quiet_NaN();
  };
  FrictionModel& m = result.model;
  m.a3 = phys[0];
  m.a1p = options.symmetric_viscous ? get("a1") : get("a1p");
  m.a1n = options.symmetric_viscous ? get("a1") : get("a1n");
  if (options.offset) {
    result.offset_mps2 = get("c0");
    // v > 0: a3 u = ... + a2 + c0; v < 0: a3 u = ... - a2 + c0 = ... - (a2 - c0).
    m.a2p = get("a2") + get("c0");
    m.a2n = get("a2") - get("c0");
  } else {
    m.a2p = get("a2p");
    m.a2n = get("a2n");
  }
  m.tau_s = tau;
  result.samples_used = f.rows;
  result.relative_error = f.relative_error;
  result.fit = std::move(f);
  return result;
}

std::string TrajectoryIdentificationResult::BriefReport() const {
  std::string s = fmt::format(
      "trajectory least squares: {} moving samples, condition {:.4g}, relative error {:.4g}\n",
      samples_used, fit.condition_number, relative_error);
  for (size_t i = 0; i < names.size(); ++i)
    s += fmt::format("  {:<4} = {:.7g} +- {:.2g}\n", names[i], estimate[Eigen::Index(i)],
                     std_error[Eigen::Index(i)]);
  s += fmt::format("  tau  = {:.6g} s\n", model.tau_s);
  return s;
}

}  // namespace sysid
