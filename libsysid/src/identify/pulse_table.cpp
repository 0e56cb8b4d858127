// The paper's method on a table of (amplitude, steady-state velocity) pairs.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "identify/linear_fit.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"
#include "sysid/io.hpp"

namespace sysid {

void PulseFitOptions::Validate() const {
  // A model file requires a3 > 0 (FrictionModel::Validate): a negative gain would only write a
  // model that every other command rejects.
  if (!std::isfinite(a3) || !(a3 > 0))
    internal::FailOption("PulseFitOptions", "a3", a3, "a3 > 0 and finite [m/(s^2 V)]");
}

std::vector<PulsePoint> ReadPulseTable(const std::string& path, const SourceMapping& mapping) {
  ReadOptions ro;
  ro.mapping = mapping;
  ro.required_columns = {"u", "v"};
  ro.any_of_columns = {};
  const Recording rec = ReadRecording(path, ro);
  const auto u = rec.column("u");
  const auto v = rec.column("v");
  std::vector<PulsePoint> points;
  for (Eigen::Index k = 0; k < rec.rows(); ++k)
    points.push_back({u[k], v[k], fmt::format("{} row {}", path, k + 1)});
  return points;
}

PulseIdentificationResult FitPulseTable(const std::vector<PulsePoint>& points,
                                        const PulseFitOptions& options) {
  options.Validate();
  std::vector<PulsePoint> pos, neg;
  for (const auto& p : points) {
    if (!std::isfinite(p.u_v) || !std::isfinite(p.v_mps))
      throw InputError(p.label + ": u and v must be finite");
    if (p.u_v == 0)
      throw InputError(p.label + ": u = 0 V is not a pulse (amplitude must be non-zero)");
    if (p.v_mps == 0)
      throw InputError(p.label + fmt::format(": v = 0 m/s at u = {} V: a stuck stage gives no "
                                             "sliding equation; drop the row",
                                             p.u_v));
    if ((p.u_v > 0) != (p.v_mps > 0))
      throw InputError(
          p.label + fmt::format(": u = {} V and v = {} m/s have opposite signs", p.u_v, p.v_mps));
    (p.u_v > 0 ? pos : neg).push_back(p);
  }
  // Name what the data cannot identify before attempting the solve.
  std::vector<std::string> problems;
  auto check_side = [&](const std::vector<PulsePoint>& side, const char* a1, const char* a2,
                        const char* word) {
    if (side.empty()) {
      problems.push_back(fmt::format("{}, {}: no {} pulses", a1, a2, word));
      return;
    }
    // Equal amplitudes give equal steady states up to noise: what separates viscous from
    // Coulomb friction is the number of distinct amplitudes (1 mV apart), not of velocities.
    std::vector<double> amps;
    for (const auto& p : side) amps.push_back(std::abs(p.u_v));
    std::sort(amps.begin(), amps.end());
    int distinct = 1;
    for (size_t i = 1; i < amps.size(); ++i)
      if (amps[i] - amps[i - 1] > 1e-3) ++distinct;
    if (distinct < 2)
      problems.push_back(fmt::format(
          "{}, {}: the {} pulses have a single amplitude ({:.6g} V); at least two distinct "
          "amplitudes are needed to separate viscous and Coulomb friction",
          a1, a2, word, amps.front()));
  };
  check_side(pos, "a1p", "a2p", "positive");
  check_side(neg, "a1n", "a2n", "negative");
  if (!problems.empty()) {
    std::string msg = "cannot identify ";
    for (size_t i = 0; i < problems.size(); ++i) msg += (i ? "; " : "") + problems[i];
    throw NumericalError(msg);
  }
  PulseIdentificationResult r;
  const Eigen::Index n = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd X = Eigen::MatrixXd::Zero(n, 4);
  Eigen::VectorXd y(n);
  Eigen::Index row = 0;
  for (const auto* side : {&pos, &neg}) {
    const Eigen::Index c = side == &pos ? 0 : 2;
    for (const auto& p : *side) {
      X(row, c) = std::abs(p.v_mps);
      X(row, c + 1) = 1.0;
      y[row] = options.a3 * std::abs(p.u_v);
      r.points.push_back(p);
      ++row;
    }
  }
  auto outcome = internal::SolveLinearFit(X, y, {"a1p", "a2p", "a1n", "a2n"});
  if (!outcome.unidentified.empty()) {
    std::string names;
    for (const auto& s : outcome.unidentified) names += (names.empty() ? "" : ", ") + s;
    throw NumericalError(names +
                         ": not identifiable from these pulses (rank-deficient "
                         "regressor)");
  }
  r.fit = std::move(outcome.fit);
  r.model.a1p = r.fit.theta[0];
  r.model.a2p = r.fit.theta[1];
  r.model.a1n = r.fit.theta[2];
  r.model.a2n = r.fit.theta[3];
  r.model.a3 = options.a3;
  r.a3_given = options.a3_given;
  r.model.tau_s = 0;
  return r;
}

std::string DescribeA3(double a3, bool given) {
  return fmt::format("a3 = {:.6g} ({})", a3,
                     given ? "given"
                           : "default: the paper's HR-8 data sheet; give --a3 for your stage");
}

std::string PulseIdentificationResult::BriefReport() const {
  std::string s = fmt::format("pulse least squares: {} equations, rank {}, condition {:.4g}\n",
                              fit.rows, fit.rank, fit.condition_number);
  for (size_t i = 0; i < fit.names.size(); ++i)
    s += fmt::format("  {:<4} = {:.7g} +- {:.2g}\n", fit.names[i], fit.theta[Eigen::Index(i)],
                     fit.std_error[Eigen::Index(i)]);
  s += fmt::format("  {}\n  rms residual {:.4g} m/s^2\n", DescribeA3(model.a3, a3_given),
                   fit.rms_residual);
  return s;
}

}  // namespace sysid
