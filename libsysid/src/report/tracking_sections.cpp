// The report's section 6: PI tracking with feedforward on the stage, the gains' loop margins on
// the identified model, and (pulses alone) the gains tuned for the model with the loop on it.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "report/report_sections.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/io_csv_table.hpp"

namespace sysid::internal {
namespace {
namespace fs = std::filesystem;

// A feedforward scheme under its model's label in every other plot ("none": PI alone).
std::string SchemeLabel(const PipelineResult& r, const std::string& scheme) {
  if (scheme == "analytic") return "analytic inverse";
  if (scheme == "nn") return NetworkLabel(r);
  return scheme == "none" ? "no feedforward" : scheme;
}

// One sentence when PI alone rings in motion at frequency f (the pipeline's
// figures.tracking_ringing): why the plots show a band.
std::string RingingSentence(const PipelineResult& r, double f) {
  for (const PipelineFigures::Ringing& m : r.figures.tracking_ringing) {
    if (m.frequency_hz != f) continue;
    // Below 10 kHz the loop rate is what rings it (docs/virtual_stage.md, "Loop rate": the
    // 1 kHz loop at 80 Hz); at 10 kHz the 0.3 ms lag still rings, at 132 Hz.
    const char* cure = m.sample_rate_hz < 1e4
                           ? "a faster loop (rig.control_rate_hz, e.g. 10 kHz) quiets it"
                           : "at this rate the driver's envelope lag sets that margin "
                             "(drive.lag_time_constant_s: 0.3 ms rings, 0.1 ms is quiet)";
    return fmt::format(
        " PI alone rings while the stage moves (RMS of e minus its 50 ms moving average "
        "{:.3g} um at {:.3g} Hz, above F4's 5 um), so every error plot carries a band at that "
        "frequency: at this stage's {:g} Hz loop rate the paper's gains leave the loop almost "
        "no phase margin in motion; {} (docs/virtual_stage.md, \"Loop rate\").",
        1e6 * m.rms_m, m.ringing_hz, m.sample_rate_hz, cure);
  }
  return {};
}

// The rows' metrics as CSV (tracking.csv, model_tracking.csv).
std::string TrackingCsv(const std::vector<TrackingRow>& rows) {
  CsvTable csv({"frequency_hz", "ff", "max_error_m", "rms_error_m", "rms_u_v"});
  for (const auto& t : rows)
    csv.Shortest(t.frequency_hz)
        .Text(t.scheme)
        .Number(t.result.max_error_m)
        .Number(t.result.rms_error_m)
        .Number(t.result.rms_u_v)
        .EndRow();
  return csv.str();
}

// The linear loop's margins per direction of sliding.
std::string MarginsTable(const PiMarginsReport& m) {
  auto num = [](double v, int digits) {
    return std::isnan(v) ? std::string("none") : Sig(v, digits);
  };
  std::vector<std::vector<std::string>> rows;
  for (const auto& [name, a1, l] : m.directions)
    rows.push_back({name, Sig(a1), num(l.crossover_rad_s, 4), num(l.phase_margin_deg, 3),
                    num(l.gain_margin, 3), l.Stable() ? "yes" : "**no**"});
  return MarkdownTable(
      {"direction", "a1 [1/s]", "crossover [rad/s]", "phase margin [deg]", "gain margin", "stable"},
      rows);
}

// The reference's max error [mm] at frequency f for `scheme`, or "".
std::string ReferenceMaxError(const PipelineReference& ref, double f, const std::string& scheme) {
  std::string v;
  for (const auto& e : *ref.tracking_max_error_mm)
    if (std::abs(e.frequency_hz - f) < 1e-9 && e.scheme == scheme) v = Sig(e.max_error_mm, 5);
  return v;
}

// Under the plot of frequency f: whether the paper's ordering (PI > PI + analytic > PI + NN)
// holds, and why the plots ring when they do.
std::string OrderingLine(const PipelineResult& r, double f) {
  double e[3] = {0, 0, 0};
  for (const auto& t : r.tracking)
    if (t.frequency_hz == f)
      e[t.scheme == "none" ? 0 : (t.scheme == "analytic" ? 1 : 2)] = t.result.max_error_m;
  const bool with_nn = r.skipped.empty();
  const bool ordered = e[0] > e[1] && (!with_nn || e[1] > e[2]);
  return fmt::format("\n- {} Hz: {}", f,
                     !with_nn  ? fmt::format("max error {:.4g} mm with PI alone, {:.4g} mm with "
                                              "the analytic feedforward (no network: pulses "
                                              "alone).",
                                             1e3 * e[0], 1e3 * e[1])
                     : ordered ? "the paper's ordering holds (PI > PI + analytic > PI + NN)."
                               : fmt::format("**the paper's ordering does not hold** (max "
                                             "errors {:.4g}, {:.4g}, {:.4g} mm for none, "
                                             "analytic, NN).",
                                             1e3 * e[0], 1e3 * e[1], 1e3 * e[2])) +
         RingingSentence(r, f);
}

// The error traces at frequency f, one per scheme.
PlotSpec ErrorPlot(const PipelineResult& r, const std::vector<TrackingRow>& rows, double f,
                   const std::string& title) {
  PlotSpec spec{title, "t [s]", "e [mm]", {}, false, 1100, 450};
  for (const auto& t : rows)
    if (t.frequency_hz == f)
      spec.series.push_back({SchemeLabel(r, t.scheme), t.result.t_s, 1e3 * t.result.e_m, "lines"});
  return spec;
}

}  // namespace

ReportSection TrackingSection(const PipelineResult& r) {
  ReportSection s;
  if (r.tracking.empty()) return s;
  s.markdown = "\n## 6. PI position control with feedforward\n\n";
  s.markdown += fmt::format(
      "Plant: the virtual stage of `{}`. Discrete PI at the stage's sample rate, Kp = {} V/m, "
      "Ki = {} V/(m s), saturation ±{} V with conditional-integration anti-windup; smooth "
      "back-and-forth profile of {} mm.\n\n",
      fs::path(r.inputs.stage).filename().string(), r.options.pi.kp_v_per_m,
      r.options.pi.ki_v_per_m_s, r.options.pi.u_max_v, 1e3 * r.options.track_amplitude_m);
  const PipelineReference* ref =
      r.reference && r.reference->tracking_max_error_mm ? &*r.reference : nullptr;
  std::vector<std::string> header{"frequency [Hz]", "feedforward", "max \\|e\\| [mm]", "RMS e [mm]",
                                  "RMS u [V]"};
  if (ref) header.push_back(ref->label + " max \\|e\\| [mm]");
  std::vector<std::vector<std::string>> rows;
  for (const auto& t : r.tracking) {
    std::vector<std::string> row{Sig(t.frequency_hz, 3), t.scheme,
                                 Sig(1e3 * t.result.max_error_m, 4),
                                 Sig(1e3 * t.result.rms_error_m, 4), Sig(t.result.rms_u_v, 4)};
    if (ref) row.push_back(ReferenceMaxError(*ref, t.frequency_hz, t.scheme));
    rows.push_back(row);
  }
  s.markdown += MarkdownTable(header, rows);
  s.files.emplace_back("tracking.csv", TrackingCsv(r.tracking));
  // The paper's ordering: PI worst, analytic better, NN best at every frequency.
  for (double f : r.options.track_frequencies_hz) {
    s.markdown += OrderingLine(r, f);
    s.AddPlot(fmt::format("tracking_{}hz.png", f),
              ErrorPlot(r, r.tracking, f,
                        fmt::format("tracking error at {} Hz: PI with feedforward from each "
                                    "inverse model",
                                    f)),
              fmt::format("tracking error {} Hz", f));
  }
  s.markdown += "\n";
  return s;
}

ReportSection MarginsSection(const PipelineResult& r) {
  ReportSection s;
  if (!r.margins) return s;
  const PiMarginsReport& m = *r.margins;
  s.markdown = r.tracking.empty() ? "\n## 6. PI gains on the identified model\n\n"
                                  : "\n### Loop margins of these gains on the identified model\n\n";
  s.markdown += fmt::format(
      "`sysid margins`: Kp = {} V/m, Ki = {} V/(m s) at {} Hz on a3 / (s (s + a1 "
      "e^(-s tau))) (a3 = {}, tau = {} ms), the sample-and-hold as half a sample of delay; a "
      "linear view of steady sliding (stick-slip, dead zone and saturation are outside "
      "it).\n\n",
      m.pi.kp_v_per_m, m.pi.ki_v_per_m_s, Sig(1 / m.pi.sample_time_s), Sig(m.a3_mps2_per_v),
      Sig(1e3 * m.tau_s, 3));
  s.markdown += MarginsTable(m);
  s.files.emplace_back("margins.json", ToJson(m) + "\n");
  if (!m.forward().Stable() || !m.backward().Stable())
    s.markdown +=
        "\nThe linearised loop of this model is unstable with these gains. The delayed "
        "viscous term fits the pulses' large-signal response rather than the stage's "
        "small-signal one, so read this as a warning, not a verdict: look for ringing "
        "while the stage slides (in the tracking runs, or on the rig); at rest friction "
        "may hold it quiet.\n";
  return s;
}

ReportSection ModelTrackingSection(const PipelineResult& r) {
  ReportSection s;
  if (!r.tuning && r.model_tracking.empty()) return s;
  s.markdown = "\n### PI gains tuned for the identified model, the loop on the model\n\n";
  if (r.tuning) {
    const PiTuningResult& t = *r.tuning;
    s.markdown += fmt::format(
        "`sysid tune-pi`: Kp = {} V/m, Ki = {} V/(m s) at {} Hz, the highest crossover at "
        "which both directions keep a 45 deg phase margin and a 6 dB gain margin "
        "(tuned_pi.json):\n\n",
        Sig(t.pi.kp_v_per_m), Sig(t.pi.ki_v_per_m_s), Sig(1 / t.pi.sample_time_s));
    s.markdown += MarginsTable(t.margins);
    s.files.emplace_back("tuned_pi.json", ToJson(t) + "\n");
  }
  if (r.model_tracking.empty()) return s;
  const PiOptions& pi = r.tuning ? r.tuning->pi : r.margins->pi;
  s.markdown += fmt::format(
      "\nPlant: the identified model (`model.json`) simulated with stick-slip at {} Hz "
      "(`sysid track --plant model.json`), from rest, exact position; Kp = {} V/m, Ki = {} "
      "V/(m s){}; smooth back-and-forth profile of {} mm. The analytic feedforward is the "
      "plant's own inverse, so this is the loop's best case; on the rig the model's error adds "
      "to it.\n\n",
      Sig(1 / pi.sample_time_s), Sig(pi.kp_v_per_m), Sig(pi.ki_v_per_m_s),
      r.tuning ? " (tuned)" : " (given: no tuned gains)", Sig(1e3 * r.options.track_amplitude_m));
  std::vector<std::vector<std::string>> rows;
  for (const auto& t : r.model_tracking)
    rows.push_back({Sig(t.frequency_hz, 3), t.scheme, Sig(1e3 * t.result.max_error_m, 4),
                    Sig(1e3 * t.result.rms_error_m, 4), Sig(t.result.rms_u_v, 4)});
  s.markdown += MarkdownTable(
      {"frequency [Hz]", "feedforward", "max \\|e\\| [mm]", "RMS e [mm]", "RMS u [V]"}, rows);
  s.files.emplace_back("model_tracking.csv", TrackingCsv(r.model_tracking));
  for (double f : r.options.track_frequencies_hz)
    s.AddPlot(fmt::format("model_tracking_{}hz.png", f),
              ErrorPlot(r, r.model_tracking, f,
                        fmt::format("tracking error at {} Hz on the identified model", f)),
              fmt::format("tracking error {} Hz on the model", f));
  s.markdown += "\n";
  return s;
}

}  // namespace sysid::internal
