// Dominant-variable analysis: sizes of the inverse model's terms from measured signals.
#include "sysid/dominance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <map>
#include <thread>

#include "core/json_text.hpp"
#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/io_csv_table.hpp"
#include "sysid/io_output.hpp"

namespace sysid {

void DominanceOptions::Validate() const {
  motion.Validate();
  auto rule = [](const std::string& field, double value, const char* what) {
    internal::FailOption("DominanceOptions", field, value, what);
  };
  if (!(min_speed_mps >= 0) || !std::isfinite(min_speed_mps))
    rule("min_speed_mps", min_speed_mps, "min_speed_mps >= 0 [m/s]");
  if (!(negligible_ratio > 0 && negligible_ratio < 1))
    rule("negligible_ratio", negligible_ratio, "0 < negligible_ratio < 1");
  if (!(bound_quantile >= 0 && bound_quantile <= 1))
    rule("bound_quantile", bound_quantile, "0 <= bound_quantile <= 1");
  if (threads < 0) rule("threads", threads, "threads >= 0");
  for (size_t i = 0; i < candidates.size(); ++i) {
    const auto& c = candidates[i];
    if (c.variable.empty() || c.column.empty())
      throw OptionsError(
          fmt::format("DominanceOptions::candidates[{}]: variable and column "
                      "must be named",
                      i));
    if (!std::isfinite(c.gain)) rule(fmt::format("candidates[{}].gain", i), c.gain, "finite");
    if (c.variable == "acceleration" || c.variable == "velocity")
      internal::FailOption("DominanceOptions", fmt::format("candidates[{}].variable", i),
                           "'" + c.variable + "'", "a name other than acceleration and velocity");
  }
}

namespace {

using ConstVectorRef = Eigen::Ref<const Eigen::VectorXd>;

// The q-quantile of `values`, which it reorders.
double Quantile(std::vector<double>& values, double q) {
  if (values.empty()) return 0.0;
  const size_t k = static_cast<size_t>(std::ceil(q * static_cast<double>(values.size() - 1)));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

// Pointwise |num| / |den| over samples where the denominator is non-zero; `r` is scratch.
void RatioStats(const ConstVectorRef& num, const ConstVectorRef& den, double q,
                std::vector<double>& r, double* bound, double* max) {
  r.clear();
  for (Eigen::Index k = 0; k < num.size(); ++k)
    if (den[k] != 0) r.push_back(std::abs(num[k]) / std::abs(den[k]));
  *max = r.empty() ? 0.0 : *std::max_element(r.begin(), r.end());
  *bound = Quantile(r, q);
}

TermStats Stats(const std::string& name, const ConstVectorRef& term) {
  TermStats s;
  s.name = name;
  s.rms = std::sqrt(term.squaredNorm() / static_cast<double>(term.size()));
  s.peak = term.cwiseAbs().maxCoeff();
  // A term of finite factors can overflow (a candidate gain of 1e308 times u), and an inf RMS
  // would rank first: said instead.
  if (!std::isfinite(s.rms))
    throw NumericalError(fmt::format("dominance: term '{}' is not finite (rms {}, peak {}): a "
                                     "gain or signal out of range overflows it",
                                     name, s.rms, s.peak));
  return s;
}

// Makes `v` hold at least n values, keeping its storage when it already does: the terms live
// in the first n (a prefix), so recordings with different moving-sample counts share storage.
void Reserve(Eigen::VectorXd& v, Eigen::Index n) {
  if (v.size() < n) v.resize(n);
}

}  // namespace

DominanceResult AnalyzeDominance(const FrictionModel& model, const Recording& recording,
                                 const DominanceOptions& options) {
  DominanceWorkspace workspace;
  return AnalyzeDominance(model, recording, options, &workspace);
}

DominanceResult AnalyzeDominance(const FrictionModel& model, const Recording& recording,
                                 const DominanceOptions& options, DominanceWorkspace* workspace) {
  options.Validate();
  model.Validate();
  DominanceWorkspace& w = *workspace;
  ExtractMotion(recording, options.motion, &w.motion);
  const MotionSignals& m = w.motion;
  DelaySignal(m.v_mps, m.dt_s, model.tau_s, DelayStart::kNaN, &w.delayed_v_mps);
  const Eigen::VectorXd& vd = w.delayed_v_mps;
  std::vector<Eigen::Index>& rows = w.moving;
  rows.clear();
  for (Eigen::Index k = 0; k < m.v_mps.size(); ++k)
    if (std::isfinite(vd[k]) && std::abs(m.v_mps[k]) >= options.min_speed_mps) rows.push_back(k);
  DominanceResult r;
  r.source = recording.source;
  r.samples = m.v_mps.size();
  r.moving_samples = static_cast<Eigen::Index>(rows.size());
  if (rows.empty())
    throw NumericalError(
        fmt::format("{}: the stage never moves (|v| < min_speed_mps = {} m/s "
                    "everywhere): no sliding samples to compare terms on",
                    recording.source, options.min_speed_mps));
  const Eigen::Index n = r.moving_samples;
  for (Eigen::VectorXd* v : {&w.acceleration, &w.viscous, &w.coulomb, &w.velocity}) Reserve(*v, n);
  auto ta = w.acceleration.head(n), tv = w.viscous.head(n), tc = w.coulomb.head(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index k = rows[static_cast<size_t>(i)];
    const double v = m.v_mps[k], d = vd[k];
    ta[i] = m.a_mps2[k];
    tv[i] = (d > 0 ? model.a1p : model.a1n) * d;
    tc[i] = v > 0 ? model.a2p : -model.a2n;
  }
  auto velocity = w.velocity.head(n);
  velocity = tv + tc;
  r.terms = {Stats("acceleration", ta), Stats("viscous", tv), Stats("coulomb", tc)};
  std::vector<std::pair<std::string, ConstVectorRef>> variables{{"acceleration", ta},
                                                                {"velocity", velocity}};
  if (w.candidates.size() < options.candidates.size())
    w.candidates.resize(options.candidates.size());
  for (size_t j = 0; j < options.candidates.size(); ++j) {
    const auto& c = options.candidates[j];
    if (!recording.has(c.column))
      throw InputError(
          fmt::format("{}: candidate '{}' needs column '{}', which the recording "
                      "does not have",
                      recording.source, c.variable, c.column));
    const auto col = recording.column(c.column);
    Reserve(w.candidates[j], n);
    auto t = w.candidates[j].head(n);
    for (Eigen::Index i = 0; i < n; ++i) t[i] = c.gain * col[rows[static_cast<size_t>(i)]];
    r.terms.push_back(Stats(c.variable, t));
    variables.emplace_back(c.variable, t);
  }
  std::vector<size_t> order(variables.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::vector<TermStats> stats;
  for (const auto& [name, t] : variables) stats.push_back(Stats(name, t));
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return stats[a].rms > stats[b].rms; });
  const ConstVectorRef& top = variables[order[0]].second;
  const double top_rms = stats[order[0]].rms;
  for (size_t i : order) {
    TermStats s = stats[i];
    s.ratio_to_top = top_rms > 0 ? s.rms / top_rms : 0.0;
    RatioStats(variables[i].second, top, options.bound_quantile, w.ratios, &s.ratio_bound,
               &s.ratio_max);
    s.negligible = i != order[0] && s.ratio_to_top <= options.negligible_ratio;
    r.ranking.push_back(s);
  }
  for (auto& t : r.terms) t.ratio_to_top = top_rms > 0 ? t.rms / top_rms : 0.0;
  r.dominant = r.ranking[0].name;
  r.margin = r.ranking.size() > 1 && r.ranking[1].rms > 0 ? r.ranking[0].rms / r.ranking[1].rms
                                                          : std::numeric_limits<double>::infinity();
  RatioStats(ta, tv, options.bound_quantile, w.ratios, &r.pointwise_ratio_quantile,
             &r.pointwise_ratio_max);
  const double peak_v = tv.cwiseAbs().maxCoeff();
  r.peak_ratio =
      peak_v > 0 ? ta.cwiseAbs().maxCoeff() / peak_v : std::numeric_limits<double>::infinity();
  return r;
}

DominanceSummary AnalyzeDominanceBatch(const FrictionModel& model,
                                       const std::vector<Recording>& recordings,
                                       const DominanceOptions& options) {
  options.Validate();
  model.Validate();
  DominanceSummary s;
  const size_t n = recordings.size();
  s.results.resize(n);
  std::vector<std::exception_ptr> errors(n);
  std::atomic<size_t> next{0};
  auto work = [&] {
    DominanceWorkspace workspace;  // one per thread, reused over its recordings
    for (size_t i = next++; i < n; i = next++) {
      try {
        s.results[i] = AnalyzeDominance(model, recordings[i], options, &workspace);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const size_t threads =
      std::min<size_t>(n, options.threads > 0 ? static_cast<size_t>(options.threads) : hw);
  std::vector<std::thread> pool;
  for (size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& t : pool) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
  std::map<std::string, int> counts;
  std::vector<double> margins;
  for (const auto& r : s.results) {
    ++counts[r.dominant];
    margins.push_back(r.margin);
  }
  for (const auto& [k, c] : counts) s.dominant_counts.emplace_back(k, c);
  std::stable_sort(s.dominant_counts.begin(), s.dominant_counts.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  if (!s.dominant_counts.empty()) s.dominant = s.dominant_counts[0].first;
  if (!margins.empty()) {
    s.min_margin = *std::min_element(margins.begin(), margins.end());
    std::sort(margins.begin(), margins.end());
    const size_t h = margins.size() / 2;
    s.median_margin = margins.size() % 2 ? margins[h] : 0.5 * (margins[h - 1] + margins[h]);
  }
  s.ranking = PooledRanking(s, options.negligible_ratio);
  s.negligible_ratio = options.negligible_ratio;
  s.min_speed_mps = options.min_speed_mps;
  return s;
}

std::string DominanceTableCsv(const DominanceSummary& summary) {
  // First the mark of a file sysid wrote (a later -o replaces only such files).
  CsvTable csv({"source", "rank", "variable", "rms", "peak", "ratio_to_top", "ratio_bound",
                "ratio_max", "negligible", "dominant", "margin", "moving_samples"},
               GeneratorLine() +
                   "# dominance of the inverse-model terms; rms and peak in [m/s^2], ratios "
                   "dimensionless\n");
  for (const auto& r : summary.results) {
    int rank = 0;
    for (const auto& s : r.ranking)
      csv.Text(r.source).Integer(++rank).Text(s.name).Number(s.rms).Number(s.peak)
          .Number(s.ratio_to_top).Number(s.ratio_bound).Number(s.ratio_max)
          .Integer(s.negligible ? 1 : 0).Integer(r.dominant == s.name ? 1 : 0).Number(r.margin)
          .Integer(static_cast<long long>(r.moving_samples)).EndRow();
  }
  return csv.str();
}

std::string DominanceVerdict(const std::string& top, const std::string& second, double margin) {
  if (second.empty() || margin >= kClearDominanceMargin)
    return std::isfinite(margin) ? fmt::format("dominant variable {} (margin {:.3g})", top, margin)
                                 : fmt::format("dominant variable {} (the only candidate)", top);
  return fmt::format("no clear dominant variable: {} leads {} by a margin of {:.3g} (< {:g})", top,
                     second, margin, kClearDominanceMargin);
}

std::string DominanceResult::BriefReport() const {
  std::string s =
      fmt::format("{}: {}, {} of {} samples moving\n", source,
                  DominanceVerdict(dominant, ranking.size() > 1 ? ranking[1].name : "", margin),
                  moving_samples, samples);
  for (const auto& t : ranking)
    s += fmt::format("  {:<14} rms {:.4g} m/s^2  peak {:.4g} m/s^2  ratio {:.3g}{}\n", t.name,
                     t.rms, t.peak, t.ratio_to_top, t.negligible ? "  (negligible)" : "");
  s += fmt::format(
      "  max |x''| / max |a1 v(t-tau)| (ratio of peaks) {:.3g}; pointwise |x''(t)| / |a1 v(t-tau)|:"
      " quantile {:.3g}, max {:.3g}\n",
      peak_ratio, pointwise_ratio_quantile, pointwise_ratio_max);
  return s;
}

std::vector<TermStats> PooledRanking(const DominanceSummary& summary, double negligible_ratio) {
  std::map<std::string, std::pair<double, double>> pooled;  // name -> (sum of squares, peak)
  Eigen::Index moving = 0;
  for (const auto& r : summary.results) {
    moving += r.moving_samples;
    for (const auto& t : r.ranking) {
      auto& p = pooled[t.name];
      p.first += t.rms * t.rms * static_cast<double>(r.moving_samples);
      p.second = std::max(p.second, t.peak);
    }
  }
  std::vector<TermStats> ranking;
  for (const auto& [name, p] : pooled) {
    TermStats t;
    t.name = name;
    t.rms = std::sqrt(p.first / static_cast<double>(moving));
    t.peak = p.second;
    ranking.push_back(t);
  }
  std::sort(ranking.begin(), ranking.end(),
            [](const TermStats& a, const TermStats& b) { return a.rms > b.rms; });
  for (auto& t : ranking) {
    t.ratio_to_top = t.rms / ranking[0].rms;
    t.negligible = &t != &ranking[0] && t.ratio_to_top <= negligible_ratio;
  }
  return ranking;
}

}  // namespace sysid
