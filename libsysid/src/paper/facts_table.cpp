// The facts' text: what `sysid stage facts` prints for each fact and the named numbers of its
// JSON, made from the typed results. The JSON's value names are the command's interface
// (experiments/stages/*.py read them): they stay as they are.
#include "paper/facts_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>

#include "paper/paper_numbers.hpp"

namespace sysid::paper {
namespace {

std::string Mm(double m) { return fmt::format("{:.4g}", 1e3 * m); }
std::string Pct(double r) { return fmt::format("{:.2g} %", 100 * r); }
std::string Sep(const std::string& text, const char* sep = ", ") { return text.empty() ? "" : sep; }

StageFact Describe(const PlateausFact& x) {
  StageFact f;
  f.id = "F1";
  f.fact = "pulse plateaus: steady velocity of the paper's ten 0.4 s pulses";
  f.paper = "ten plateaus, 33.93 to 85.19 mm/s (pulse table)";
  f.tolerance = fmt::format("each within {:g} % of the paper's", 100 * kPlateauTolerance);
  for (const auto& row : x.rows)
    f.values.emplace_back(fmt::format("v_mps at {:+g} V", row.u_v), row.v_mps);
  f.met = x.met;
  const double worst = x.worst_relative_deviation;
  f.virtual_value =
      fmt::format("worst {:+g} V: {} vs {} mm/s ({})", x.worst.u_v, Mm(x.worst.v_mps),
                  Mm(x.worst.paper_v_mps), std::isfinite(worst) ? Pct(worst) : "no plateau");
  f.values.emplace_back("worst_relative_deviation", worst);
  if (x.rows.size() != x.paper_pulses)
    f.note = fmt::format("{} usable pulses, the paper has {}", x.rows.size(), x.paper_pulses);
  return f;
}

StageFact Describe(const PulseModelFact& x) {
  StageFact f;
  f.id = "F2";
  f.fact = "pulse least squares (a3 = 6): a1p, a1n [1/s], a2p, a2n [m/s^2]";
  auto text = [](const FrictionModel& m) {
    return fmt::format("{:.4g}, {:.4g}, {:.4g}, {:.4g}", m.a1p, m.a1n, m.a2p, m.a2n);
  };
  f.paper = text(x.paper);
  f.virtual_value = text(x.stage);
  f.tolerance = fmt::format("each within {:g} %", 100 * kPulseModelTolerance);
  f.met = x.met;
  f.values = {{"a1p_per_s", x.stage.a1p},
              {"a1n_per_s", x.stage.a1n},
              {"a2p_mps2", x.stage.a2p},
              {"a2n_mps2", x.stage.a2n}};
  return f;
}

StageFact Describe(const DelayFact& x) {
  StageFact f;
  f.id = "F3";
  f.fact = "delay of the viscous term (tune-delay on the pulse recording)";
  f.paper = fmt::format("tau = {:g} ms", 1e3 * kTauS);
  f.virtual_value =
      fmt::format("tau = {:.3g} ms; RMS dv {} mm/s at tau, {} at 0 (ratio {:.3g})", 1e3 * x.tau_s,
                  Mm(x.rms_at_tau_mps), Mm(x.rms_at_zero_mps), x.rms_ratio);
  f.tolerance = fmt::format("{:g} <= tau <= {:g} ms and RMS(tau) <= {:g} RMS(0)", 1e3 * kDelayMinS,
                            1e3 * kDelayMaxS, kDelayMaxRmsRatio);
  f.met = x.met;
  f.values = {{"tau_s", x.tau_s},
              {"rms_at_tau_mps", x.rms_at_tau_mps},
              {"rms_at_zero_mps", x.rms_at_zero_mps},
              {"rms_ratio", x.rms_ratio}};
  if (!f.met && x.tau_s < kDelayMinS)
    f.note =
        "a stage that responds later than the rough model (actuator delay or lag) is best "
        "fitted with no delay: delaying the viscous term makes the model faster";
  return f;
}

StageFact Describe(const PaperGainsFact& x, const FactsOptions& o) {
  StageFact f;
  f.id = "F4";
  f.fact =
      fmt::format("paper's gains Kp {:g} V/m, Ki {:g} V/(m s): no limit cycle, quiet in motion",
                  o.pi.kp_v_per_m, o.pi.ki_v_per_m_s);
  f.paper = "stable, no oscillation";
  f.tolerance = fmt::format(
      "PI alone: ripple (half peak-to-peak of e over the last half of each dwell after cycle 1) "
      "<= {:g} um, no sample with |u| clipped at {:g} V, and in motion RMS of e minus its "
      "{:g} ms moving average after cycle 1, each stroke's breakaway transient left out, "
      "<= {:g} um",
      1e6 * o.ripple_tolerance_m, o.pi.u_max_v, 1e3 * o.motion_ripple_window_s,
      1e6 * o.motion_ripple_tolerance_m);
  f.met = x.met;
  std::string ringing;
  for (const auto& row : x.rows) {
    const double hz = row.frequency_hz;
    f.virtual_value += Sep(f.virtual_value, "; ") +
                       fmt::format(
                           "{:g} Hz: ripple {:.3g} um, in motion {:.3g} um, {} clipped "
                           "samples, max |u| {:.3g} V",
                           hz, 1e6 * row.ripple_m, 1e6 * row.motion_ripple_m, row.clipped_samples,
                           row.max_abs_u_v);
    f.values.emplace_back(fmt::format("ripple_m at {:g} Hz", hz), row.ripple_m);
    f.values.emplace_back(fmt::format("motion_ripple_m at {:g} Hz", hz), row.motion_ripple_m);
    f.values.emplace_back(fmt::format("ringing_hz at {:g} Hz", hz), row.ringing_hz);
    f.values.emplace_back(fmt::format("clipped_samples at {:g} Hz", hz),
                          static_cast<double>(row.clipped_samples));
    if (!row.quiet)
      ringing += fmt::format("{}{:g} Hz: {:.3g} um RMS ringing at {:.3g} Hz", Sep(ringing, "; "),
                             hz, 1e6 * row.motion_ripple_m, row.ringing_hz);
  }
  if (!f.met)
    f.note = ringing.empty() ? "the loop limit-cycles at the paper's gains on this stage"
                             : "the loop rings in motion at the paper's gains: " + ringing;
  return f;
}

// Where F5 fails at one frequency, precisely.
std::vector<std::string> TrackingShortfalls(const TrackingFact::Row& r) {
  std::vector<std::string> why;
  if (!(r.none_m > r.analytic_m))
    why.push_back(fmt::format("analytic {} >= PI {}", Mm(r.analytic_m), Mm(r.none_m)));
  if (!(r.analytic_m > r.nn_m))
    why.push_back(fmt::format("NN {} >= analytic {}", Mm(r.nn_m), Mm(r.analytic_m)));
  for (const auto& [name, s, p] :
       {std::tuple<const char*, double, double>{"PI", r.none_m, r.paper_none_m},
        {"analytic", r.analytic_m, r.paper_analytic_m},
        {"NN", r.nn_m, r.paper_nn_m}})
    if (!WithinTrackingFactor(s, p))
      why.push_back(fmt::format("{} {} mm is {:.3g} x the paper's", name, Mm(s), s / p));
  return why;
}

StageFact Describe(const TrackingFact& x) {
  StageFact f;
  f.id = "F5";
  f.fact = "tracking max error [mm]: PI / PI + analytic / PI + NN";
  f.tolerance =
      fmt::format("PI > analytic > NN at each frequency, each within a factor {:g} of the paper's",
                  kTrackingFactor);
  f.met = x.met;
  for (const auto& r : x.rows) {
    const double hz = r.frequency_hz;
    const std::string sep = Sep(f.paper, "; ");
    f.paper += sep + fmt::format("{:g} Hz: {} / {} / {}", hz, Mm(r.paper_none_m),
                                 Mm(r.paper_analytic_m), Mm(r.paper_nn_m));
    f.virtual_value +=
        sep + fmt::format("{:g} Hz: {} / {} / {}", hz, Mm(r.none_m), Mm(r.analytic_m), Mm(r.nn_m));
    f.values.emplace_back(fmt::format("max_error_m at {:g} Hz none", hz), r.none_m);
    f.values.emplace_back(fmt::format("max_error_m at {:g} Hz analytic", hz), r.analytic_m);
    f.values.emplace_back(fmt::format("max_error_m at {:g} Hz nn", hz), r.nn_m);
    for (const auto& w : TrackingShortfalls(r))
      f.note += fmt::format("{}{:g} Hz: {}", Sep(f.note, "; "), hz, w);
  }
  if (x.spread.empty()) return f;
  std::string text;
  for (const auto& s : x.spread) {
    for (std::size_t k = 0; k < s.nn_max_error_m.size(); ++k)
      f.values.emplace_back(
          fmt::format("max_error_m at {:g} Hz nn, initial weights {}", s.frequency_hz, k + 1),
          s.nn_max_error_m[k]);
    f.values.emplace_back(fmt::format("nn beats analytic at {:g} Hz, networks", s.frequency_hz),
                          static_cast<double>(s.beats_analytic));
    const auto [lo, hi] = std::minmax_element(s.nn_max_error_m.begin(), s.nn_max_error_m.end());
    text += fmt::format("{}{:g} Hz {} of {} ({} to {} mm)", Sep(text), s.frequency_hz,
                        s.beats_analytic, s.nn_max_error_m.size(), Mm(*lo), Mm(*hi));
  }
  f.virtual_value += "; NN beats analytic over initial weights: " + text;
  return f;
}

StageFact Describe(const DominanceFact& x) {
  StageFact f;
  f.id = "F6";
  f.fact = "dominance: u = 1.5 sin(pi/2 t - pi/2) - 0.3 V, bound of |x''| / |a1 x'|";
  f.paper = "O(10^-1)";
  f.virtual_value = fmt::format(
      "ratio of peaks {:.3g} (max |x''| {:.3g}, max |a1 x'| {:.3g} m/s^2); pointwise ratio: 99 % "
      "quantile {:.3g}",
      x.peak_ratio, x.peak_acceleration_mps2, x.peak_viscous_mps2, x.pointwise_ratio_q99);
  f.tolerance = fmt::format("ratio of peaks <= {:g}", kDominanceMaxRatio);
  f.met = x.met;
  f.values = {{"peak_ratio", x.peak_ratio},
              {"pointwise_ratio_q99", x.pointwise_ratio_q99},
              {"peak_acceleration_mps2", x.peak_acceleration_mps2},
              {"peak_viscous_mps2", x.peak_viscous_mps2},
              {"moving_samples", static_cast<double>(x.moving_samples)}};
  f.note =
      "the paper reads the bound from its figure of the two terms: the ratio of their "
      "peaks. The pointwise ratio's quantile is a different quantity (large where x' "
      "crosses small values)";
  return f;
}

StageFact Describe(const NetworksFact& x) {
  StageFact f;
  f.id = "F7";
  f.required = false;
  f.fact = fmt::format("typical (v, a) {}-unit vs dominant v {}-unit network MSE [V^2]",
                       x.typical_hidden, x.dominant_hidden);
  f.paper =
      fmt::format("typical: fits training, test very poor; dominant: train {:.3g}, test {:.2g}",
                  kDominantTrainMseV2, kDominantTestMseV2);
  f.virtual_value =
      fmt::format("typical: train {:.3g}, test {:.3g}; dominant: train {:.3g}, test {:.3g}",
                  x.typical.train_v2, x.typical.test_v2, x.dominant.train_v2, x.dominant.test_v2);
  f.tolerance =
      "reported; contrast: typical test >= 2 x typical train and dominant test < typical test";
  f.met = x.contrast;
  const SetCoverage& c = x.coverage;
  f.values = {
      {"typical_train_mse_v2", x.typical.train_v2},
      {"typical_test_mse_v2", x.typical.test_v2},
      {"dominant_train_mse_v2", x.dominant.train_v2},
      {"dominant_test_mse_v2", x.dominant.test_v2},
      {"training_max_abs_v_mps", c.training_max_abs_v_mps},
      {"training_max_abs_a_mps2", c.training_max_abs_a_mps2},
      {"test_max_abs_v_mps", c.test_max_abs_v_mps},
      {"test_max_abs_a_mps2", c.test_max_abs_a_mps2},
      {"test_rows_outside_training_box_fraction", c.test_rows_outside_training_box_fraction},
      {"training_a_noise_rms_mps2", c.training_a_noise_rms_mps2},
      {"training_a_rms_mps2", c.training_a_rms_mps2},
      {"training_rest_fraction", c.training_rest_fraction},
      {"training_u_variance_at_rest_v2", c.training_u_variance_at_rest_v2},
      {"dominant_train_moving_mse_v2", x.dominant_moving.train_v2},
      {"dominant_test_moving_mse_v2", x.dominant_moving.test_v2},
      {"typical_train_moving_mse_v2", x.typical_moving.train_v2},
      {"typical_test_moving_mse_v2", x.typical_moving.test_v2},
      {"train_irreducible_mse_v_v2", x.irreducible_v.train_v2},
      {"test_irreducible_mse_v_v2", x.irreducible_v.test_v2},
      {"train_irreducible_mse_va_v2", x.irreducible_va.train_v2},
      {"test_irreducible_mse_va_v2", x.irreducible_va.test_v2},
      {"collection_kp_v_per_m", x.collection_kp_v_per_m}};
  // The share of the dominant network's training MSE on the rows at rest.
  const double rest_share =
      1 - (1 - c.training_rest_fraction) * x.dominant_moving.train_v2 / x.dominant.train_v2;
  f.note = fmt::format(
      "{} (sets collected at Kp {:g} V/m): {:.3g} % of the test rows lie outside the training "
      "set's (v, a) box (|v| <= {:.3g} m/s, |a| <= {:.3g} m/s^2); acceleration noise RMS {:.3g} "
      "against RMS a {:.3g} m/s^2; "
      "{:.3g} % of the training rows are at rest (|v| < 1 mm/s) with u spread over the dead "
      "zone (variance {:.3g} V^2) and carry {:.3g} % of the dominant network's training MSE; on "
      "the moving rows the MSEs are typical {:.3g} / {:.3g}, dominant {:.3g} / {:.3g} V^2 "
      "(train / test); the least MSE any function of v can reach (k-NN estimate, sysid "
      "irreducible) is {:.3g} / {:.3g} V^2, of (v, a) {:.3g} / {:.3g} V^2",
      f.met ? "contrast" : "no contrast", x.collection_kp_v_per_m,
      100 * c.test_rows_outside_training_box_fraction, c.training_max_abs_v_mps,
      c.training_max_abs_a_mps2, c.training_a_noise_rms_mps2, c.training_a_rms_mps2,
      100 * c.training_rest_fraction, c.training_u_variance_at_rest_v2, 100 * rest_share,
      x.typical_moving.train_v2, x.typical_moving.test_v2, x.dominant_moving.train_v2,
      x.dominant_moving.test_v2, x.irreducible_v.train_v2, x.irreducible_v.test_v2,
      x.irreducible_va.train_v2, x.irreducible_va.test_v2);
  return f;
}

// F8 (c), (d): each sinusoid's mean width in the values, and "KEY WIDTH, ..." [mm/s] keyed by
// frequency or amplitude.
std::string SweepText(const std::vector<LoopSine>& runs, bool by_frequency, StageFact& f) {
  std::string text;
  for (const auto& r : runs) {
    const std::string key = by_frequency ? fmt::format("{:g} Hz", r.frequency_hz)
                                         : fmt::format("{:g} V", r.amplitude_v);
    text += fmt::format("{}{} {:.3g}", Sep(text), key, 1e3 * r.mean_width_mps);
    f.values.emplace_back(
        fmt::format("sine {:g} V {:g} Hz mean_width_mps", r.amplitude_v, r.frequency_hz),
        r.mean_width_mps);
  }
  return text;
}

StageFact Describe(const VoltageLoopFact& x, const FactsOptions& o) {
  StageFact f;
  f.id = "F8";
  f.fact =
      "voltage-velocity loop, open loop: (a) a loop on the triangle, (b) asymmetric, "
      "(c) wider at a higher rate, (d) changes with amplitude";
  f.paper = fmt::format(
      "(a) a hysteresis loop on the {:g} s triangle (Fig. 3), (b) direction-dependent (Fig. 3; "
      "pulse LS a2n / a2p = {:.3g}), (c), (d) shapes depend on the voltage's rate and "
      "amplitude (Figs. 4, 5: {:g} V at several f, 1 Hz at several A); no widths printed",
      o.loop_period_s, PulseModel().a2n / PulseModel().a2p, o.loop_sine_amplitude_v);
  const VoltageLoop& t = x.triangle;
  std::string a_text;
  for (std::size_t i = 0; i < t.levels.size(); ++i) {
    const VoltageLoopLevel& l = t.levels[i];
    const double rel = x.relative_widths[i];
    a_text += fmt::format("{}{:+g} V {:.3g} mm/s ({:.2g} %)", Sep(a_text), l.level_v,
                          1e3 * l.WidthMps(), 100 * rel);
    f.values.emplace_back(fmt::format("triangle width_mps at {:+g} V", l.level_v), l.WidthMps());
    f.values.emplace_back(fmt::format("triangle relative_width at {:+g} V", l.level_v), rel);
  }
  f.values.insert(f.values.end(), {{"triangle start_forward_v", t.start_forward_v},
                                   {"triangle start_backward_v", t.start_backward_v},
                                   {"triangle stop_forward_v", t.stop_forward_v},
                                   {"triangle stop_backward_v", t.stop_backward_v},
                                   {"triangle start_ratio", x.start_ratio},
                                   {"triangle mean_width_forward_mps", t.MeanWidthForwardMps()},
                                   {"triangle mean_width_backward_mps", t.MeanWidthBackwardMps()},
                                   {"triangle area_forward_v_mps", t.area_forward_v_mps},
                                   {"triangle area_backward_v_mps", t.area_backward_v_mps}});
  const std::string c_text = SweepText(x.frequency_sweep, true, f);
  const std::string d_text = SweepText(x.amplitude_sweep, false, f);
  f.values.insert(f.values.end(), {{"rate_ratio", x.rate_ratio},
                                   {"amplitude_change", x.amplitude_change},
                                   {"a_met", x.a_met ? 1.0 : 0.0},
                                   {"b_met", x.b_met ? 1.0 : 0.0},
                                   {"c_met", x.c_met ? 1.0 : 0.0},
                                   {"d_met", x.d_met ? 1.0 : 0.0}});
  f.virtual_value = fmt::format(
      "(a) width {}; (b) starts {:.3f} / {:.3f} V (ratio {:.3g}); (c) mean width [mm/s] {} "
      "(x {:.3g}); (d) at {:g} Hz {} ({:+.2g} %)",
      a_text, t.start_forward_v, t.start_backward_v, x.start_ratio, c_text, x.rate_ratio,
      o.loop_sine_frequency_hz, d_text, 100 * x.amplitude_change);
  f.tolerance = fmt::format(
      "(a) width >= {:g} % of |v| at each level; (b) start ratio >= {:g}; (c) highest f's mean "
      "width >= {:g} x lowest f's; (d) largest A's and smallest A's differ by >= {:g} %",
      100 * o.loop_min_relative_width, o.loop_min_start_ratio, o.loop_min_rate_ratio,
      100 * o.loop_min_amplitude_change);
  f.met = x.met;
  std::vector<std::string> failed;
  if (!x.a_met) failed.push_back("(a) the triangle's loop is thinner than stated at a level");
  if (!x.b_met) failed.push_back("(b) the directions start at similar voltages");
  if (!x.c_met) failed.push_back("(c) the loop does not widen enough with the rate");
  if (!x.d_met) failed.push_back("(d) the loop's mean width hardly changes with the amplitude");
  for (const auto& w : failed) f.note += (f.note.empty() ? "not met: " : "; ") + w;
  if (f.note.empty())
    f.note =
        "width = v (|u| falling) - v (|u| rising) at a level; mean width = enclosed area "
        "/ voltage span of the motion (`sysid loop`)";
  return f;
}

}  // namespace

std::vector<StageFact> FactsTable(const FactsResults& r, const FactsOptions& o) {
  std::vector<StageFact> rows;
  if (r.f1) rows.push_back(Describe(*r.f1));
  if (r.f2) rows.push_back(Describe(*r.f2));
  if (r.f3) rows.push_back(Describe(*r.f3));
  if (r.f4) rows.push_back(Describe(*r.f4, o));
  if (r.f5) rows.push_back(Describe(*r.f5));
  if (r.f6) rows.push_back(Describe(*r.f6));
  if (r.f7) rows.push_back(Describe(*r.f7));
  if (r.f8) rows.push_back(Describe(*r.f8, o));
  return rows;
}

}  // namespace sysid::paper
