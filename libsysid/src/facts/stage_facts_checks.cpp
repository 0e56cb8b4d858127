// The paper's numbers, the facts' criteria on plain numbers, and the result's JSON / Markdown.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <nlohmann/json.hpp>
#include <string>
#include <unsupported/Eigen/FFT>
#include <vector>

#include "sysid/error.hpp"
#include "sysid/stage_facts.hpp"

namespace sysid {

// ---- The paper's printed numbers ------------------------------------------------------------

const std::vector<std::pair<double, double>>& PaperFacts::PulseTable() {
  // The stage's copy of the paper's table (datasets/paper/pulse_table.csv), in the pulse order
  // of PulseProcedure's default amplitudes.
  static const std::vector<std::pair<double, double>> table = [] {
    const auto paper = StageParameters::PaperPulseTable();
    std::vector<std::pair<double, double>> ordered;
    for (double u : PulseProcedure{}.amplitudes_v)
      for (const auto& row : paper)
        if (row.first == u) ordered.push_back(row);
    return ordered;
  }();
  return table;
}

FrictionModel PaperFacts::PulseModel() {
  FrictionModel m = FrictionModel::Paper();
  m.tau_s = 0;
  return m;
}

double PaperFacts::TrackingMaxErrorM(double frequency_hz, const std::string& scheme) {
  // The tracking table of "Prediction Performance in Feedforward Compensation" [mm].
  const bool half = std::abs(frequency_hz - 0.5) < 1e-9, one = std::abs(frequency_hz - 1.0) < 1e-9;
  if (!half && !one) return std::nan("");
  double mm = std::nan("");
  if (scheme == "none") mm = half ? 0.10651 : 0.17156;
  if (scheme == "analytic") mm = half ? 0.03609 : 0.10579;
  if (scheme == "nn") mm = half ? 0.01779 : 0.07292;
  return 1e-3 * mm;
}

// ---- Criteria -------------------------------------------------------------------------------

namespace facts {

bool PlateausMet(const std::vector<double>& stage_mps, const std::vector<double>& paper_mps) {
  if (stage_mps.size() != paper_mps.size() || stage_mps.empty()) return false;
  for (size_t i = 0; i < stage_mps.size(); ++i)
    if (!(std::abs(stage_mps[i] - paper_mps[i]) <= 0.02 * std::abs(paper_mps[i]))) return false;
  return true;
}

bool PulseModelMet(const FrictionModel& s, const FrictionModel& p) {
  auto within = [](double a, double b) { return std::abs(a - b) <= 0.05 * std::abs(b); };
  return within(s.a1p, p.a1p) && within(s.a1n, p.a1n) && within(s.a2p, p.a2p) &&
         within(s.a2n, p.a2n);
}

bool DelayMet(double tau_s, double rms_at_tau_mps, double rms_at_zero_mps) {
  return tau_s >= 2.5e-3 && tau_s <= 4.5e-3 && rms_at_tau_mps <= 0.8 * rms_at_zero_mps;
}

double RippleAmplitude(const Eigen::VectorXd& e_m, const SmoothProfileOptions& p) {
  const double period = 1.0 / p.frequency_hz, dwell = p.dwell_fraction * period;
  const double tm = 0.5 * period - dwell;
  double ripple = 0;
  for (int c = 1; c < p.cycles; ++c) {
    for (const double start : {c * period, c * period + dwell + tm}) {
      // The last half of the dwell: [start + dwell/2, start + dwell).
      const auto k0 =
          static_cast<Eigen::Index>(std::ceil((start + 0.5 * dwell) * p.sample_rate_hz));
      const auto k1 = std::min<Eigen::Index>(
          e_m.size(), static_cast<Eigen::Index>(std::ceil((start + dwell) * p.sample_rate_hz)));
      if (k1 - k0 < 1) continue;
      const Eigen::VectorXd w = e_m.segment(k0, k1 - k0);
      ripple = std::max(ripple, 0.5 * (w.maxCoeff() - w.minCoeff()));
    }
  }
  return ripple;
}

MotionRipple MotionRippleOf(const Eigen::VectorXd& e_m, const SmoothProfileOptions& p,
                            double window_s, bool ringing_frequency) {
  if (!(window_s > 0) || !std::isfinite(window_s))
    throw OptionsError(fmt::format(
        "MotionRippleOf: window_s = {:g}. Violated constraint: window_s > 0", window_s));
  const Eigen::Index n = e_m.size();
  const auto half = static_cast<Eigen::Index>(std::llround(0.5 * window_s * p.sample_rate_hz));
  // After the first cycle, and only where the whole window lies inside the run.
  const Eigen::Index first = std::max(
      half, static_cast<Eigen::Index>(std::ceil(p.sample_rate_hz / p.frequency_hz - 1e-9)));
  const Eigen::Index last = n - half;  // exclusive
  MotionRipple out;
  if (last - first < 1) return out;
  // Centred moving sums from prefix sums (long double: e spans ~1e-4 m over ~1e5 samples).
  std::vector<long double> prefix(static_cast<std::size_t>(n) + 1, 0.0L);
  for (Eigen::Index k = 0; k < n; ++k)
    prefix[static_cast<std::size_t>(k) + 1] = prefix[static_cast<std::size_t>(k)] + e_m[k];
  const auto width = static_cast<long double>(2 * half + 1);
  // Each stroke's breakaway transient is left out: from the reference leaving a dwell to one
  // window after the largest |e| in the stroke's first half. A PI on a dead-zone stage winds
  // up while the stage sticks and overshoots at breakaway; that hump is the tracking error F5
  // measures (the paper's "greatest at the onset of motion"), not a ring, and counting it
  // would fail the paper's own PI row (docs/virtual_stage.md, "F4 in motion at 1 Hz").
  std::vector<bool> left_out(static_cast<std::size_t>(n), false);
  const double period = 1.0 / p.frequency_hz, dwell = p.dwell_fraction * period;
  const double stroke = 0.5 * period - dwell;
  const auto window = static_cast<Eigen::Index>(std::llround(window_s * p.sample_rate_hz));
  for (int c = 0; c < p.cycles; ++c)
    for (const double start : {c * period + dwell, c * period + 2 * dwell + stroke}) {
      const auto k0 = static_cast<Eigen::Index>(std::ceil(start * p.sample_rate_hz - 1e-9));
      const auto k1 = std::min<Eigen::Index>(
          n, static_cast<Eigen::Index>(std::ceil((start + 0.5 * stroke) * p.sample_rate_hz)));
      if (k0 >= k1) continue;
      Eigen::Index peak = 0;
      e_m.segment(k0, k1 - k0).cwiseAbs().maxCoeff(&peak);
      for (Eigen::Index k = k0; k <= std::min(n - 1, k0 + peak + window); ++k)
        left_out[static_cast<std::size_t>(k)] = true;
    }
  std::vector<double> residual(static_cast<std::size_t>(last - first), 0.0);
  double sum2 = 0;
  for (Eigen::Index k = first; k < last; ++k) {
    if (left_out[static_cast<std::size_t>(k)]) {
      ++out.breakaway_samples;
      continue;  // its residual stays 0 in the periodogram below
    }
    const long double mean = (prefix[static_cast<std::size_t>(k + half + 1)] -
                              prefix[static_cast<std::size_t>(k - half)]) / width;
    const double r = e_m[k] - static_cast<double>(mean);
    residual[static_cast<std::size_t>(k - first)] = r;
    sum2 += r * r;
    ++out.samples;
  }
  if (out.samples < 1) return out;
  out.rms_m = std::sqrt(sum2 / static_cast<double>(out.samples));
  if (!ringing_frequency || residual.size() < 4) return out;
  // The ringing frequency: the largest bin of the Hann-windowed periodogram (DC left out).
  const std::size_t m = residual.size();
  for (std::size_t k = 0; k < m; ++k)
    residual[k] *= 0.5 - 0.5 * std::cos(2 * 3.14159265358979323846 * static_cast<double>(k) / static_cast<double>(m - 1));
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, residual);
  std::size_t peak = 1;
  for (std::size_t k = 2; k <= m / 2; ++k)
    if (std::norm(spectrum[k]) > std::norm(spectrum[peak])) peak = k;
  out.ringing_hz = static_cast<double>(peak) * p.sample_rate_hz / static_cast<double>(m);
  return out;
}

bool TrackingOrderMet(double none_m, double analytic_m, double nn_m, double paper_none_m,
                      double paper_analytic_m, double paper_nn_m) {
  auto within3 = [](double s, double p) { return s <= 3 * p && s >= p / 3; };
  return none_m > analytic_m && analytic_m > nn_m && within3(none_m, paper_none_m) &&
         within3(analytic_m, paper_analytic_m) && within3(nn_m, paper_nn_m);
}

bool DominanceMet(double peak_ratio) { return peak_ratio <= 0.3; }

bool NetworkContrast(double typical_train, double typical_test, double dominant_test) {
  return typical_test >= 2 * typical_train && dominant_test < typical_test;
}

double LoopMeanWidth(const VoltageLoop& loop) {
  const double span = loop.span_forward_v + loop.span_backward_v;
  return span > 0 ? (loop.area_forward_v_mps + loop.area_backward_v_mps) / span : std::nan("");
}

double LoopRelativeWidth(const VoltageLoopLevel& level) {
  const double mean = 0.5 * (std::abs(level.v_rising_mps) + std::abs(level.v_falling_mps));
  return mean > 0 ? level.WidthMps() / mean : std::nan("");
}

double StartRatio(const VoltageLoop& loop) {
  const double f = std::abs(loop.start_forward_v), b = std::abs(loop.start_backward_v);
  if (!(f > 0) || !(b > 0)) return std::nan("");
  return std::max(f, b) / std::min(f, b);
}

bool LoopWidthMet(const std::vector<double>& relative_widths, double min_fraction) {
  return !relative_widths.empty() &&
         std::all_of(relative_widths.begin(), relative_widths.end(),
                     [&](double w) { return w >= min_fraction; });
}

bool LoopRateMet(const std::vector<double>& widths, double min_ratio) {
  if (widths.size() < 2) return false;
  const double first = widths.front(), last = widths.back();
  return first > 0 && std::isfinite(last) && last >= min_ratio * first;
}

bool LoopAmplitudeMet(const std::vector<double>& widths, double min_change) {
  if (widths.size() < 2) return false;
  const double first = widths.front(), last = widths.back();
  if (!std::isfinite(first) || !std::isfinite(last) || first == 0 || last == 0) return false;
  return std::abs(last - first) >= min_change * std::min(std::abs(first), std::abs(last));
}

}  // namespace facts

// ---- Output ---------------------------------------------------------------------------------

const StageFact* StageFacts::Find(const std::string& id) const {
  for (const auto& f : facts)
    if (f.id == id) return &f;
  return nullptr;
}

bool StageFacts::RequiredMet() const {
  return std::all_of(facts.begin(), facts.end(),
                     [](const StageFact& f) { return !f.required || f.met; });
}

std::string StageFacts::ToJson() const {
  nlohmann::ordered_json j;
  j["stage"] = stage_name;
  j["facts"] = nlohmann::ordered_json::array();
  for (const auto& f : facts) {
    nlohmann::ordered_json o;
    o["id"] = f.id;
    o["fact"] = f.fact;
    o["paper"] = f.paper;
    o["virtual"] = f.virtual_value;
    o["tolerance"] = f.tolerance;
    o["met"] = f.met;
    o["required"] = f.required;
    o["note"] = f.note;
    nlohmann::ordered_json values = nlohmann::ordered_json::object();
    for (const auto& [name, value] : f.values) {
      if (std::isfinite(value))
        values[name] = value;
      else
        values[name] = nullptr;
    }
    o["values"] = values;
    j["facts"].push_back(o);
  }
  j["required_met"] = RequiredMet();
  return j.dump(2);
}

std::string StageFacts::ToMarkdown() const {
  auto cell = [](std::string s) {
    for (size_t p = s.find('|'); p != std::string::npos; p = s.find('|', p + 2))
      s.replace(p, 1, "\\|");
    return s;
  };
  std::string md = "| id | fact | paper | stage | tolerance | met |\n|---|---|---|---|---|---|\n";
  for (const auto& f : facts)
    md += fmt::format("| {} | {} | {} | {} | {} | {} |\n", f.id, cell(f.fact), cell(f.paper),
                      cell(f.virtual_value), cell(f.tolerance),
                      f.met ? "yes" : (f.required ? "**no**" : "no (reported only)"));
  return md;
}

}  // namespace sysid
