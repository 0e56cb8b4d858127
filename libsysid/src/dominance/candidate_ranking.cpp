// Dominance over richer candidates: a linear inverse model in x, v, a and play operators of x,
// its terms sized by RMS (sysid/dominance_candidates.hpp).
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "core/option_rule.hpp"
#include "sysid/dominance_candidates.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace sysid {

void CandidateRankingOptions::Validate() const {
  motion.Validate();
  if (operators < 0 || operators > kMaxPlayOperators)
    internal::FailOption(
        "CandidateRankingOptions", "operators", operators,
        fmt::format("0 <= operators <= {} (kMaxPlayOperators)", kMaxPlayOperators));
  if (!(negligible_ratio >= 0 && negligible_ratio < 1))
    internal::FailOption("CandidateRankingOptions", "negligible_ratio", negligible_ratio,
                         "in [0, 1)");
}

CandidateRanking RankCandidates(const Recording& recording, const CandidateRankingOptions& o) {
  o.Validate();
  if (!recording.has("x"))
    throw InputError(recording.source + ": column 'x' [m] is required to rank x, v and a");
  MotionOptions motion = o.motion;
  motion.prefer_velocity_column = false;
  const MotionSignals s = ExtractMotion(recording, motion);
  const Eigen::Index n = s.u_v.size();
  const int m = o.operators;
  // Nothing to rank when either side does not vary: the fit would divide by zero (R^2 NaN) and
  // still name a winner.
  if (!(s.u_v.maxCoeff() > s.u_v.minCoeff()))
    throw InputError(fmt::format("{}: column 'u' is constant ({} V): no input to explain",
                                 recording.source, s.u_v[0]));
  if (!(s.x_m.maxCoeff() > s.x_m.minCoeff()))
    throw InputError(fmt::format("{}: column 'x' is constant ({} m): the stage does not move, "
                                 "so x, v and a explain nothing",
                                 recording.source, s.x_m[0]));
  // Columns: x, F1..Fm, v, a (centred: the offset c takes the means).
  Eigen::MatrixXd X(n, 3 + m);
  std::vector<std::string> names{"x"};
  X.col(0) = s.x_m;
  if (m > 0) {
    const std::vector<double> r = UniformThresholds(s.x_m.minCoeff(), s.x_m.maxCoeff(), m);
    for (int i = 0; i < m; ++i) {
      X.col(1 + i) = PlayOperator(s.x_m, r[static_cast<size_t>(i)], s.x_m[0]);
      names.push_back(fmt::format("F{}[x]", i + 1));
    }
  }
  X.col(1 + m) = s.v_mps;
  X.col(2 + m) = s.a_mps2;
  names.push_back("v");
  names.push_back("a");
  const Eigen::RowVectorXd mean = X.colwise().mean();
  X.rowwise() -= mean;
  const Eigen::VectorXd u = s.u_v.array() - s.u_v.mean();
  // Unit-norm columns for the solve; a zero column (x constant) gets a zero coefficient.
  Eigen::VectorXd scale = X.colwise().norm().transpose();
  for (Eigen::Index j = 0; j < scale.size(); ++j)
    if (!(scale[j] > 0)) scale[j] = HUGE_VAL;
  const Eigen::MatrixXd Xs = X * scale.cwiseInverse().asDiagonal();
  const Eigen::VectorXd theta = Xs.colPivHouseholderQr().solve(u).cwiseQuotient(scale);
  CandidateRanking out;
  out.source = recording.source;
  const Eigen::VectorXd fit = X * theta;
  out.residual_rms_v = std::sqrt((u - fit).squaredNorm() / static_cast<double>(n));
  out.r2 = 1 - (u - fit).squaredNorm() / u.squaredNorm();
  // Finite data can still overflow (values near 1e300 square to inf): said, not ranked.
  if (!theta.allFinite() || !std::isfinite(out.r2) || !std::isfinite(out.residual_rms_v))
    throw NumericalError(fmt::format(
        "{}: the linear inverse model's fit is not finite (R^2 {}, residual {} V): values out "
        "of range (u up to {:g} V, x up to {:g} m)",
        recording.source, out.r2, out.residual_rms_v, s.u_v.cwiseAbs().maxCoeff(),
        s.x_m.cwiseAbs().maxCoeff()));
  auto stats = [&](const std::string& name, const Eigen::VectorXd& term) {
    TermStats t;
    t.name = name;
    t.rms = std::sqrt(term.squaredNorm() / static_cast<double>(n));
    t.peak = term.cwiseAbs().maxCoeff();
    return t;
  };
  for (int j = 0; j < 3 + m; ++j) out.terms.push_back(stats(names[static_cast<size_t>(j)], theta[j] * X.col(j)));
  out.ranking.push_back(stats("x", X.leftCols(1 + m) * theta.head(1 + m)));
  out.ranking.push_back(stats("v", theta[1 + m] * X.col(1 + m)));
  out.ranking.push_back(stats("a", theta[2 + m] * X.col(2 + m)));
  std::stable_sort(out.ranking.begin(), out.ranking.end(),
                   [](const TermStats& a, const TermStats& b) { return a.rms > b.rms; });
  const double top = out.ranking[0].rms;
  for (auto* list : {&out.ranking, &out.terms})
    for (auto& t : *list) {
      t.ratio_to_top = top > 0 ? t.rms / top : 0;
      t.negligible = t.ratio_to_top <= o.negligible_ratio;
    }
  out.ranking[0].negligible = false;
  out.dominant = out.ranking[0].name;
  out.margin = out.ranking[1].rms > 0 ? top / out.ranking[1].rms : HUGE_VAL;
  return out;
}

std::string CandidateRanking::BriefReport() const {
  std::string s =
      fmt::format("{}: {}; linear model R^2 {:.3f}, residual {:.3g} V\n", source,
                  DominanceVerdict(dominant, ranking.size() > 1 ? ranking[1].name : "", margin), r2,
                  residual_rms_v);
  for (const auto& t : ranking)
    s += fmt::format("  {:<3} rms {:.4g} V  ratio {:.3g}{}\n", t.name, t.rms, t.ratio_to_top,
                     t.negligible ? "  (negligible)" : "");
  return s;
}

}  // namespace sysid
