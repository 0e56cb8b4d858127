// The pipeline's report: report.md with tables and plots, the model files and CSV tables.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "core/json_text.hpp"
#include "paper/measures.hpp"
#include "report/report_sections.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/pipeline.hpp"
#include "sysid/report.hpp"
#include "sysid/simulate.hpp"

namespace sysid {
namespace {
namespace fs = std::filesystem;

std::string F(double v, int digits = 5) { return fmt::format("{:.{}g}", v, digits); }

// Reference numbers (e.g. the paper's) to set beside ours; all keys optional.
struct Reference {
  std::string label = "reference";
  nlohmann::json j;
  bool has(const char* key) const { return j.contains(key); }
  bool contains_tau() const { return j.contains("model") && j["model"].contains("tau"); }
};

std::optional<Reference> LoadReference(const std::string& path) {
  if (path.empty()) return std::nullopt;
  Reference ref;
  ref.j = internal::ParseJsonText(ReadFile(path), path);  // positioned errors, duplicate keys
  ref.label = ref.j.value("label", std::string("reference"));
  return ref;
}

class ReportWriter {
 public:
  ReportWriter(const PipelineResult& r, const std::string& dir)
      : r_(r), dir_(dir), ref_(LoadReference(r.options.reference_path)) {}

  std::vector<std::string> Write() {
    fs::create_directories(dir_);
    md_ = "# libsysid pipeline report\n\n";
    const std::string sets =
        r_.inputs.PulsesOnly()
            ? std::string(" alone (no training or test set), ")
            : ", training set `" + fs::path(r_.inputs.training).filename().string() +
                  "`, test set `" + fs::path(r_.inputs.test).filename().string() + "`, ";
    md_ += "Inputs: `" + r_.inputs.root + "` — " + std::to_string(r_.inputs.pulses.size()) +
           " pulse recording(s)" + sets + std::to_string(r_.inputs.waveforms.size()) +
           " test waveform(s)" +
           (r_.inputs.loops.empty()
                ? std::string()
                : ", " + std::to_string(r_.inputs.loops.size()) + " voltage-loop sweep(s)") +
           "." + internal::MappingSentence(r_.inputs) + "\n";
    if (ref_) md_ += "Reference numbers (" + ref_->label + ") are set beside ours.\n";
    Model();
    Delay();
    if (r_.skipped.empty()) {
      Dominance();
      Neural();
      Comparison();
    } else {
      Skipped();
    }
    Render(internal::ValidationSection(r_));
    Tracking();
    Margins();
    ModelTracking();
    Facts();
    Loops();
    Timing();
    DrawPlots();
    WriteFileAtomically(Path("report.md"), md_);
    return notes_;
  }

 private:
  std::string Path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

  // Plots are queued and drawn together at the end (DrawPlots): each is a gnuplot process, and
  // drawn one after another they were most of the report's time. report.md keeps a marker where
  // each plot's line goes.
  void Plot(const std::string& file, PlotSpec spec, const std::string& caption) {
    DrawMeasuredLast(spec);
    colours_.Apply(spec);  // one colour per label across the report's plots
    md_ += PlotMarker(plots_.size());
    plots_.push_back({file, std::move(spec), caption, {}});
  }

  static std::string PlotMarker(std::size_t i) { return fmt::format("\x1f{}\x1f", i); }

  void DrawPlots() {
    std::atomic<std::size_t> next{0};
    auto worker = [&] {
      for (std::size_t i = next++; i < plots_.size(); i = next++) {
        try {
          plots_[i].outcome = WritePlot(Path(plots_[i].file), plots_[i].spec);
        } catch (const std::exception& e) {  // a worker thread must not throw
          plots_[i].outcome = {false, "plot " + plots_[i].file + " failed: " + e.what()};
        }
      }
    };
    const unsigned cores = std::max(1U, std::thread::hardware_concurrency());
    const std::size_t n = std::min<std::size_t>(
        plots_.size(), r_.options.threads > 0 ? static_cast<unsigned>(r_.options.threads) : cores);
    std::vector<std::thread> pool;
    for (std::size_t t = 1; t < n; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    std::vector<std::pair<std::string, PlotSpec>> index;
    for (const PendingPlot& p : plots_) index.emplace_back(p.file, p.spec);
    WriteFileAtomically(Path("plots.json"), PlotIndexJson(index));
    for (std::size_t i = 0; i < plots_.size(); ++i) {
      const PendingPlot& p = plots_[i];
      const std::string line = p.outcome.written
                                   ? "\n![" + p.caption + "](" + p.file + ")\n"
                                   : "\n*(plot `" + p.file + "` not drawn: " +
                                         p.outcome.message + ")*\n";
      if (!p.outcome.written) notes_.push_back(p.outcome.message);
      const std::string marker = PlotMarker(i);
      md_.replace(md_.find(marker), marker.size(), line);
    }
  }

  void Render(const internal::ReportSection& s) {
    md_ += s.markdown;
    for (const auto& p : s.plots) Plot(p.file, p.spec, p.caption);
    for (const auto& [name, text] : s.files) WriteFileAtomically(Path(name), text);
  }

  void Model() {
    const auto& p = r_.pulse;
    md_ += "\n## 1. Pulse-test identification\n\n";
    std::vector<std::vector<std::string>> rows;
    std::string csv = "source,t_start_s,duration_s,u_v,v_mps,v_stderr_mps,status,reason\n";
    for (const auto& e : p.pulses) {
      rows.push_back({fs::path(e.pulse.source).filename().string(), F(e.pulse.t_start_s, 4),
                      F(e.pulse.amplitude_v, 4), F(e.v_mps, 5), ToString(e.status), e.reason});
      csv += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{},\"{}\"\n", e.pulse.source,
                         e.pulse.t_start_s, e.pulse.duration_s, e.pulse.amplitude_v, e.v_mps,
                         e.v_stderr_mps, ToString(e.status), e.reason);
    }
    md_ += MarkdownTable(
        {"recording", "t start [s]", "u [V]", "steady v [m/s]", "status", "reason"}, rows);
    WriteFileAtomically(Path("pulses.csv"), csv);
    md_ += "\nLeast squares (column-pivoted QR), condition number " + F(p.fit.condition_number, 4) +
           ", relative residual " + F(p.fit.relative_error, 3) + ":\n\n";
    // The pulse method's estimates (a3 given, tau = 0) beside the final model after the delay
    // (and refinement), so that neither hides the other.
    std::vector<std::string> header{"parameter", "pulse LS", "std. error", "final model"};
    if (ref_ && ref_->has("model")) header.push_back(ref_->label);
    std::vector<std::vector<std::string>> prow;
    const std::vector<std::tuple<const char*, double, double>> values{
        {"a1p", p.model.a1p, r_.model.a1p}, {"a1n", p.model.a1n, r_.model.a1n},
        {"a2p", p.model.a2p, r_.model.a2p}, {"a2n", p.model.a2n, r_.model.a2n},
        {"a3", p.model.a3, r_.model.a3},    {"tau", p.model.tau_s, r_.model.tau_s}};
    for (const auto& [name, pulse_value, final_value] : values) {
      std::string se = "—";
      for (size_t i = 0; i < p.fit.names.size(); ++i)
        if (p.fit.names[i] == name) se = F(p.fit.std_error[static_cast<Eigen::Index>(i)], 3);
      std::vector<std::string> row{name, F(pulse_value, 7), se, F(final_value, 7)};
      if (ref_ && ref_->has("model"))
        row.push_back(ref_->j["model"].contains(name) ? F(ref_->j["model"][name].get<double>(), 7)
                                                      : "");
      prow.push_back(row);
    }
    md_ += MarkdownTable(header, prow);
    if (!p.a3_given) md_ += "\n**Warning:** " + DescribeA3(p.model.a3, false) + ".\n";
    md_ += "\nThe final model (" + std::string(p.a3_given ? "a3 given" : "a3 the default") +
           ", then the delay" +
           std::string(r_.refine ? " and the output-error refinement of all six parameters" : "") +
           ") is `model.json`.\n";
    WriteModel(Path("model.json"), r_.model);
  }

  void Delay() {
    if (!r_.delay) return;
    const auto& d = *r_.delay;
    md_ += "\n## 2. Delay of the viscous term\n\n";
    md_ += fmt::format(
        "NLopt (DIRECT-L then BOBYQA) over tau: **tau = {:.4g} ms**, cost {:.4g} m²/s² (RMS "
        "velocity error {:.3g} m/s), {} evaluations, {} simulations. {}\n",
        1e3 * d.tau_s, d.cost, d.rms_error_mps, d.evaluations, d.simulations, d.message);
    if (ref_ && ref_->contains_tau())
      md_ += fmt::format("\n{}: tau = {:.4g} ms.\n", ref_->label,
                         1e3 * ref_->j["model"]["tau"].get<double>());
    Eigen::VectorXd tau(static_cast<Eigen::Index>(d.curve.size())), cost(tau.size());
    for (size_t i = 0; i < d.curve.size(); ++i) {
      tau[static_cast<Eigen::Index>(i)] = 1e3 * d.curve[i].first;
      cost[static_cast<Eigen::Index>(i)] = d.curve[i].second;
    }
    Plot("delay_cost.png",
         {"delay fit: cost against tau",
          "tau [ms]",
          "cost [m^2/s^2]",
          {{"sum of squared velocity errors", tau, cost, "linespoints"}},
          true,
          900,
          500},
         "cost against tau");
    if (r_.refine) md_ += "\nOutput-error refinement (Ceres): " + r_.refine->BriefReport() + "\n";
    VelocityPlot();
  }

  // Measured velocity of the first pulse recording beside the model with tau = 0 and tuned.
  void VelocityPlot() {
    const auto& f = r_.figures;
    if (!f.pulse_velocity_note.empty()) {
      notes_.push_back(f.pulse_velocity_note);
      return;
    }
    if (f.pulse_velocity.empty()) return;
    PlotSpec spec{"pulse response: measured and simulated velocity",
                  "t [s]",
                  "v [m/s]",
                  {},
                  false,
                  1100,
                  500};
    for (const auto& t : f.pulse_velocity) spec.series.push_back({t.label, t.x, t.y, "lines"});
    Plot("pulse_velocity.png", spec, "measured vs simulated velocity");
  }

  void Dominance() {
    const auto& d = r_.dominance;
    md_ += "\n## 3. Dominant variable\n\n";
    std::vector<std::vector<std::string>> rows;
    for (const auto& res : d.results)
      for (const auto& v : res.ranking)
        rows.push_back({fs::path(res.source).filename().string(), v.name, F(v.rms, 4), F(v.peak, 4),
                        F(v.ratio_to_top, 3), F(v.ratio_bound, 3), v.negligible ? "yes" : "no"});
    md_ += MarkdownTable({"recording", "variable", "RMS term [m/s²]", "peak [m/s²]", "RMS / top",
                          "pointwise ratio to top (q99)", "negligible"},
                         rows);
    if (d.ranking.size() > 1)
      md_ += fmt::format(
          "\nPooled over the recordings: {}.",
          DominanceVerdict(d.ranking[0].name, d.ranking[1].name,
                           d.ranking[1].rms > 0 ? d.ranking[0].rms / d.ranking[1].rms : HUGE_VAL));
    md_ += "\nTop-ranked in most recordings: **" + d.dominant + "**; network inputs: ";
    for (const auto& c : r_.nn_inputs) md_ += "`" + c + "` ";
    md_ += "\n";
    for (const auto& res : d.results)
      md_ += fmt::format(
          "\n- `{}`: ratio of peaks max |x''| / max |a1 v(t-tau)| = {:.3g} (how the paper reads "
          "its bound); pointwise ratio |x''(t)| / |a1 v(t-tau)|: 99 % quantile {:.3g}, max {:.3g} "
          "(a different quantity) over {} moving samples.",
          fs::path(res.source).filename().string(), res.peak_ratio, res.pointwise_ratio_quantile,
          res.pointwise_ratio_max, res.moving_samples);
    if (ref_ && ref_->has("dominance_ratio_bound"))
      md_ += fmt::format("\n- {}: the bound (ratio of peaks, read off its figure) is O({:.1g}).",
                         ref_->label, ref_->j["dominance_ratio_bound"].get<double>());
    md_ += "\n";
    WriteFileAtomically(Path("dominance.csv"), DominanceTableCsv(d));
    // The paper's figure: the acceleration term against the viscous term over time.
    PlotSpec terms{"terms of a3 u = x'' + a1 v(t - tau) + a2 sgn v on the training set",
                   "t [s]",
                   "term [m/s^2]",
                   {},
                   false,
                   1100,
                   500};
    for (const auto& t : r_.figures.dominance_terms) terms.series.push_back({t.label, t.x, t.y, "lines"});
    Plot("dominance_terms.png",
         terms,
         "acceleration term vs viscous term");
  }

  void Neural() {
    const auto& s = r_.sweep;
    md_ += "\n## 4. Inverse neural network: hidden-size sweep\n\n";
    const bool paper_sweep = ref_ && ref_->has("sweep");
    std::vector<std::string> header{"H", "epochs", "training MSE [V²]", "test MSE [V²]", "stop"};
    if (paper_sweep) {
      header.push_back(ref_->label + " epochs");
      header.push_back(ref_->label + " training MSE");
      header.push_back(ref_->label + " test MSE");
    }
    std::vector<std::vector<std::string>> rows;
    std::string csv = "hidden,epochs,train_mse,test_mse,stop\n";
    for (size_t i = 0; i < s.rows.size(); ++i) {
      const auto& row = s.rows[i];
      std::vector<std::string> cells{
          std::to_string(row.hidden) + (static_cast<int>(i) == s.chosen ? " (chosen)" : ""),
          std::to_string(row.epochs), F(row.train_mse), F(row.test_mse), ToString(row.stop)};
      if (paper_sweep) {
        std::vector<std::string> extra{"", "", ""};
        for (const auto& p : ref_->j["sweep"])
          if (p.value("hidden", -1) == row.hidden)
            extra = {std::to_string(p.value("epochs", 0)), F(p.value("train_mse", 0.0)),
                     F(p.value("test_mse", 0.0))};
        cells.insert(cells.end(), extra.begin(), extra.end());
      }
      rows.push_back(cells);
      csv += fmt::format("{},{},{:.9g},{:.9g},{}\n", row.hidden, row.epochs, row.train_mse,
                         row.test_mse, ToString(row.stop));
    }
    md_ += MarkdownTable(header, rows);
    md_ += "\nRule: " + s.rule + ". The chosen network is `nn.json`.\n";
    WriteFileAtomically(Path("sweep.csv"), csv);
    WriteNeuralNetwork(Path("nn.json"), r_.network);
    Eigen::VectorXd h(static_cast<Eigen::Index>(s.rows.size())), tr(h.size()), te(h.size());
    for (size_t i = 0; i < s.rows.size(); ++i) {
      h[static_cast<Eigen::Index>(i)] = s.rows[i].hidden;
      tr[static_cast<Eigen::Index>(i)] = s.rows[i].train_mse;
      te[static_cast<Eigen::Index>(i)] = s.rows[i].test_mse;
    }
    Plot("sweep.png",
         {"hidden-size sweep",
          "hidden units H [1]",
          "MSE [V^2]",
          {{"training", h, tr, "linespoints"}, {"test", h, te, "linespoints"}},
          false,
          900,
          500},
         "training and test MSE against H");
    if (!r_.typical) return;
    const auto& t = *r_.typical;
    md_ += "\n### Typical (v, a) network vs dominant-variable network\n\n";
    md_ += MarkdownTable(
        {"network", "inputs", "H", "epochs", "training MSE [V²]", "test MSE [V²]"},
        {{"typical", "v, a", std::to_string(t.network.hidden_size()), std::to_string(t.epochs),
          F(t.train_mse), F(r_.typical_test_mse)},
         {"dominant", Join(r_.nn_inputs), std::to_string(r_.network.hidden_size()),
          std::to_string(s.rows[static_cast<size_t>(s.chosen)].epochs),
          F(s.rows[static_cast<size_t>(s.chosen)].train_mse), F(r_.network_test_mse)}});
    const double train_dom = s.rows[static_cast<size_t>(s.chosen)].train_mse;
    const bool overfits = t.train_mse <= train_dom && r_.typical_test_mse > r_.network_test_mse;
    md_ += overfits
               ? "\nAs in the paper, the typical network fits the training set at least as well "
                 "and the test set worse: it overfits.\n"
               : fmt::format(
                     "\n**Not the paper's outcome:** the typical network's training MSE is {} "
                     "and its test MSE {} against the dominant network's {} and {}. With "
                     "encoder-quantised acceleration as an input, 120 units and the pipeline's "
                     "epoch budget ({} epochs on every n-th training sample, n = {}), this data "
                     "does not "
                     "reproduce the overfitting; see docs/neural.md.\n",
                     F(t.train_mse), F(r_.typical_test_mse), F(train_dom), F(r_.network_test_mse),
                     r_.options.typical_max_epochs, r_.options.typical_stride);
    WriteNeuralNetwork(Path("nn_typical.json"), t.network);
    Render(internal::NetworkFigurePair(r_));
  }

  void Comparison() {
    md_ += "\n## 5. Analytic vs NN inverse model\n\n";
    std::vector<std::vector<std::string>> rows;
    std::string csv = "recording,model,rmse_v,peak_error_v,nrmse_range\n";
    for (const auto& c : r_.comparisons) {
      const std::string name = fs::path(c.source).stem().string();
      rows.push_back({name, F(c.analytic.rmse_v, 4), F(c.nn.rmse_v, 4),
                      F(c.analytic.peak_error_v, 4), F(c.nn.peak_error_v, 4),
                      F(c.analytic.nrmse_range, 3), F(c.nn.nrmse_range, 3)});
      const std::string field = internal::CsvField(name);  // one row, whatever the name holds
      csv += fmt::format("{},analytic,{:.9g},{:.9g},{:.9g}\n{},nn,{:.9g},{:.9g},{:.9g}\n", field,
                         c.analytic.rmse_v, c.analytic.peak_error_v, c.analytic.nrmse_range, field,
                         c.nn.rmse_v, c.nn.peak_error_v, c.nn.nrmse_range);
      WriteRecording(Path("compare_" + name + ".csv"), c.AsRecording());
    }
    md_ += MarkdownTable({"recording", "RMSE analytic [V]", "RMSE NN [V]", "peak analytic [V]",
                          "peak NN [V]", "nrmse_range analytic", "nrmse_range NN"},
                         rows);
    WriteFileAtomically(Path("comparison.csv"), csv);
    for (const auto& c : r_.comparisons) {
      const std::string name = fs::path(c.source).stem().string();
      Plot("compare_" + name + ".png",
           {"inverse models on " + name,
            "t [s]",
            "u [V]",
            {{"analytic inverse", c.t_s, c.u_analytic_v, "lines"},
             {internal::NetworkLabel(r_), c.t_s, c.u_nn_v, "lines"},
             {"measured", c.t_s, c.u_measured_v, "lines"}},
            false,
            1100,
            450},
           name);
    }
  }

  // A pulse-only run: what it did not do, and which recordings would make it.
  void Skipped() {
    md_ +=
        "\n## 3-5. Dominance, networks, inverse comparison: skipped\n\n"
        "Pulse recordings alone identify the rough model; the steps below need more:\n\n";
    for (const auto& s : r_.skipped) md_ += "- " + s + "\n";
  }

  void Tracking() {
    if (r_.tracking.empty()) return;
    md_ += "\n## 6. PI position control with feedforward\n\n";
    md_ += fmt::format(
        "Plant: the virtual stage of `{}`. Discrete PI at the stage's sample rate, Kp = {} V/m, "
        "Ki = {} V/(m s), saturation ±{} V with conditional-integration anti-windup; smooth "
        "back-and-forth profile of {} mm.\n\n",
        fs::path(r_.inputs.stage).filename().string(), r_.options.pi.kp_v_per_m,
        r_.options.pi.ki_v_per_m_s, r_.options.pi.u_max_v, 1e3 * r_.options.track_amplitude_m);
    const bool paper = ref_ && ref_->has("tracking_max_error_mm");
    std::vector<std::string> header{"frequency [Hz]", "feedforward", "max \\|e\\| [mm]",
                                    "RMS e [mm]", "RMS u [V]"};
    if (paper) header.push_back(ref_->label + " max \\|e\\| [mm]");
    std::vector<std::vector<std::string>> rows;
    std::string csv = "frequency_hz,ff,max_error_m,rms_error_m,rms_u_v\n";
    for (const auto& t : r_.tracking) {
      std::vector<std::string> row{F(t.frequency_hz, 3), t.scheme, F(1e3 * t.result.max_error_m, 4),
                                   F(1e3 * t.result.rms_error_m, 4), F(t.result.rms_u_v, 4)};
      if (paper) {
        std::string v;
        for (const auto& [key, val] : ref_->j["tracking_max_error_mm"].items())
          if (std::abs(std::stod(key) - t.frequency_hz) < 1e-9 && val.contains(t.scheme))
            v = F(val[t.scheme].get<double>(), 5);
        row.push_back(v);
      }
      rows.push_back(row);
      csv += fmt::format("{},{},{:.9g},{:.9g},{:.9g}\n", t.frequency_hz, t.scheme,
                         t.result.max_error_m, t.result.rms_error_m, t.result.rms_u_v);
    }
    md_ += MarkdownTable(header, rows);
    WriteFileAtomically(Path("tracking.csv"), csv);
    // The paper's ordering: PI worst, analytic better, NN best at every frequency.
    for (double f : r_.options.track_frequencies_hz) {
      double e[3] = {0, 0, 0};
      PlotSpec spec{
          fmt::format("tracking error at {} Hz: PI with feedforward from each inverse model", f),
          "t [s]",
          "e [mm]",
          {},
          false,
          1100,
          450};
      for (const auto& t : r_.tracking) {
        if (t.frequency_hz != f) continue;
        const int i = t.scheme == "none" ? 0 : (t.scheme == "analytic" ? 1 : 2);
        e[i] = t.result.max_error_m;
        spec.series.push_back({SchemeLabel(t.scheme), t.result.t_s, 1e3 * t.result.e_m, "lines"});
      }
      const bool with_nn = r_.skipped.empty();
      const bool ordered = e[0] > e[1] && (!with_nn || e[1] > e[2]);
      md_ += fmt::format("\n- {} Hz: {}", f,
                         !with_nn ? fmt::format("max error {:.4g} mm with PI alone, {:.4g} mm with "
                                                "the analytic feedforward (no network: pulses "
                                                "alone).",
                                                1e3 * e[0], 1e3 * e[1])
                         : ordered ? "the paper's ordering holds (PI > PI + analytic > PI + NN)."
                                   : fmt::format("**the paper's ordering does not hold** (max "
                                                 "errors {:.4g}, {:.4g}, {:.4g} mm for none, "
                                                 "analytic, NN).",
                                                 1e3 * e[0], 1e3 * e[1], 1e3 * e[2]));
      md_ += RingingSentence(f);
      Plot(fmt::format("tracking_{}hz.png", f), spec, fmt::format("tracking error {} Hz", f));
    }
    md_ += "\n";
  }

  // A feedforward scheme under its model's label in every other plot ("none": PI alone).
  std::string SchemeLabel(const std::string& scheme) const {
    if (scheme == "analytic") return "analytic inverse";
    if (scheme == "nn") return internal::NetworkLabel(r_);
    return scheme == "none" ? "no feedforward" : scheme;
  }

  // One sentence when PI alone rings in motion at frequency f (F4 in motion, > 5 um): why the
  // plots show a band.
  std::string RingingSentence(double f) const {
    for (const auto& t : r_.tracking) {
      if (t.frequency_hz != f || t.scheme != "none" || t.result.t_s.size() < 2) continue;
      SmoothProfileOptions p;
      p.frequency_hz = f;
      p.sample_rate_hz = 1.0 / (t.result.t_s[1] - t.result.t_s[0]);
      p.cycles = static_cast<int>(std::lround(static_cast<double>(t.result.t_s.size() - 1) /
                                              p.sample_rate_hz * f));
      const FactsOptions limits;
      // The ringing frequency (a long FFT) only when the sentence is written.
      if (paper::MotionRippleOf(t.result.e_m, p, limits.motion_ripple_window_s, false).rms_m <=
          limits.motion_ripple_tolerance_m)
        return {};
      const paper::MotionRipple m =
          paper::MotionRippleOf(t.result.e_m, p, limits.motion_ripple_window_s);
      // Below 10 kHz the loop rate is what rings it (docs/virtual_stage.md, "Loop rate": the
      // 1 kHz loop at 80 Hz); at 10 kHz the 0.3 ms lag still rings, at 132 Hz.
      const char* cure = p.sample_rate_hz < 1e4
                             ? "a faster loop (rig.control_rate_hz, e.g. 10 kHz) quiets it"
                             : "at this rate the driver's envelope lag sets that margin "
                               "(drive.lag_time_constant_s: 0.3 ms rings, 0.1 ms is quiet)";
      return fmt::format(
          " PI alone rings while the stage moves (RMS of e minus its 50 ms moving average "
          "{:.3g} um at {:.3g} Hz, above F4's 5 um), so every error plot carries a band at that "
          "frequency: at this stage's {:g} Hz loop rate the paper's gains leave the loop almost "
          "no phase margin in motion; {} (docs/virtual_stage.md, \"Loop rate\").",
          1e6 * m.rms_m, m.ringing_hz, p.sample_rate_hz, cure);
    }
    return {};
  }

  // The PI gains on the identified model: the linear loop around steady sliding.
  void Margins() {
    if (!r_.margins) return;
    const PiMarginsReport& m = *r_.margins;
    md_ += r_.tracking.empty() ? "\n## 6. PI gains on the identified model\n\n"
                               : "\n### Loop margins of these gains on the identified model\n\n";
    md_ += fmt::format(
        "`sysid margins`: Kp = {} V/m, Ki = {} V/(m s) at {} Hz on a3 / (s (s + a1 "
        "e^(-s tau))) (a3 = {}, tau = {} ms), the sample-and-hold as half a sample of delay; a "
        "linear view of steady sliding (stick-slip, dead zone and saturation are outside "
        "it).\n\n",
        m.pi.kp_v_per_m, m.pi.ki_v_per_m_s, F(1 / m.pi.sample_time_s), F(m.model.a3),
        F(1e3 * m.model.tau_s, 3));
    auto num = [](double v, int digits) {
      return std::isnan(v) ? std::string("none") : F(v, digits);
    };
    std::vector<std::vector<std::string>> rows;
    for (const auto& [name, a1, l] : m.Directions())
      rows.push_back({name, F(a1), num(l.crossover_rad_s, 4), num(l.phase_margin_deg, 3),
                      num(l.gain_margin, 3), l.Stable() ? "yes" : "**no**"});
    md_ += MarkdownTable({"direction", "a1 [1/s]", "crossover [rad/s]", "phase margin [deg]",
                          "gain margin", "stable"},
                         rows);
    WriteFileAtomically(Path("margins.json"), ToJson(m) + "\n");
    if (!m.forward.Stable() || !m.backward.Stable())
      md_ += "\nThe linearised loop of this model is unstable with these gains. The delayed "
             "viscous term fits the pulses' large-signal response rather than the stage's "
             "small-signal one, so read this as a warning, not a verdict: look for ringing "
             "while the stage slides (in the tracking runs, or on the rig); at rest friction "
             "may hold it quiet.\n";
  }

  // Pulses alone: gains tuned for the identified model (sysid tune-pi) and the loop closed on the
  // model itself (sysid track --plant M.json), with and without the analytic feedforward.
  void ModelTracking() {
    if (!r_.tuning && r_.model_tracking.empty()) return;
    md_ += "\n### PI gains tuned for the identified model, the loop on the model\n\n";
    if (r_.tuning) {
      const PiTuningResult& t = *r_.tuning;
      md_ += fmt::format(
          "`sysid tune-pi`: Kp = {} V/m, Ki = {} V/(m s) at {} Hz, the highest crossover at "
          "which both directions keep a 45 deg phase margin and a 6 dB gain margin "
          "(tuned_pi.json):\n\n",
          F(t.pi.kp_v_per_m), F(t.pi.ki_v_per_m_s), F(1 / t.pi.sample_time_s));
      std::vector<std::vector<std::string>> rows;
      auto num = [](double v, int digits) {
        return std::isnan(v) ? std::string("none") : F(v, digits);
      };
      for (const auto& [name, a1, l] : t.margins.Directions())
        rows.push_back({name, F(a1), num(l.crossover_rad_s, 4), num(l.phase_margin_deg, 3),
                        num(l.gain_margin, 3), l.Stable() ? "yes" : "**no**"});
      md_ += MarkdownTable({"direction", "a1 [1/s]", "crossover [rad/s]", "phase margin [deg]",
                            "gain margin", "stable"},
                           rows);
      PiTuningOptions to;
      to.loop_rate_hz = 1 / t.pi.sample_time_s;
      to.u_max_v = t.pi.u_max_v;
      WriteFileAtomically(Path("tuned_pi.json"), ToJson(t, to) + "\n");
    }
    if (r_.model_tracking.empty()) return;
    const PiOptions& pi = r_.tuning ? r_.tuning->pi : r_.margins->pi;
    md_ += fmt::format(
        "\nPlant: the identified model (`model.json`) simulated with stick-slip at {} Hz "
        "(`sysid track --plant model.json`), from rest, exact position; Kp = {} V/m, Ki = {} "
        "V/(m s){}; smooth back-and-forth profile of {} mm. The analytic feedforward is the "
        "plant's own inverse, so this is the loop's best case; on the rig the model's error adds "
        "to it.\n\n",
        F(1 / pi.sample_time_s), F(pi.kp_v_per_m), F(pi.ki_v_per_m_s),
        r_.tuning ? " (tuned)" : " (given: no tuned gains)", F(1e3 * r_.options.track_amplitude_m));
    std::vector<std::vector<std::string>> rows;
    std::string csv = "frequency_hz,ff,max_error_m,rms_error_m,rms_u_v\n";
    for (const auto& t : r_.model_tracking) {
      rows.push_back({F(t.frequency_hz, 3), t.scheme, F(1e3 * t.result.max_error_m, 4),
                      F(1e3 * t.result.rms_error_m, 4), F(t.result.rms_u_v, 4)});
      csv += fmt::format("{},{},{:.9g},{:.9g},{:.9g}\n", t.frequency_hz, t.scheme,
                         t.result.max_error_m, t.result.rms_error_m, t.result.rms_u_v);
    }
    md_ += MarkdownTable(
        {"frequency [Hz]", "feedforward", "max \\|e\\| [mm]", "RMS e [mm]", "RMS u [V]"}, rows);
    WriteFileAtomically(Path("model_tracking.csv"), csv);
    for (double f : r_.options.track_frequencies_hz) {
      PlotSpec spec{fmt::format("tracking error at {} Hz on the identified model", f),
                    "t [s]",
                    "e [mm]",
                    {},
                    false,
                    1100,
                    450};
      for (const auto& t : r_.model_tracking)
        if (t.frequency_hz == f)
          spec.series.push_back({SchemeLabel(t.scheme), t.result.t_s, 1e3 * t.result.e_m, "lines"});
      Plot(fmt::format("model_tracking_{}hz.png", f), spec,
           fmt::format("tracking error {} Hz on the model", f));
    }
    md_ += "\n";
  }

  // The slow open-loop sweeps: the voltage-velocity loop (the paper's Fig. 3 test).
  void Loops() {
    const internal::ReportSection fact =
        r_.facts ? internal::LoopFactSection(*r_.facts) : internal::ReportSection{};
    if (r_.loops.empty() && fact.markdown.empty()) return;
    md_ += "\n## 8. Voltage-velocity loop (slow open-loop sweep)\n\n";
    md_ += "The paper's triangle test (its Fig. 3: an asymmetric loop). Velocity where |u| "
           "passes each level going up and going down (mean of ±10 samples; `sysid loop`); "
           "width = how much faster the stage runs on the way down. A static inverse (the "
           "analytic one, a network on v alone) follows one curve through the loop.\n";
    std::string csv = "source,level_v,v_rising_mps,v_falling_mps,width_mps\n";
    for (std::size_t i = 0; i < r_.loops.size(); ++i) {
      const VoltageLoop& l = r_.loops[i];
      const std::string name = fs::path(l.source).filename().string();
      auto volts = [](double u) { return std::isnan(u) ? std::string("never") : F(u, 4) + " V"; };
      md_ += fmt::format(
          "\n`{}`: u from {} to {} V; starts forward at {}, backward at {}; stops forward at "
          "{}, backward at {}.\n\n",
          name, F(l.peak_backward_v, 4), F(l.peak_forward_v, 4), volts(l.start_forward_v),
          volts(l.start_backward_v), volts(l.stop_forward_v), volts(l.stop_backward_v));
      auto mm = [](double v) {
        return std::isnan(v) ? std::string("-") : fmt::format("{:.2f}", 1e3 * v);
      };
      std::vector<std::vector<std::string>> rows;
      for (const auto& lv : l.levels) {
        rows.push_back({F(lv.level_v, 4), mm(lv.v_rising_mps), mm(lv.v_falling_mps),
                        mm(lv.WidthMps())});
        csv += fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g}\n", name, lv.level_v, lv.v_rising_mps,
                           lv.v_falling_mps, lv.WidthMps());
      }
      md_ += MarkdownTable({"u [V]", "v, \\|u\\| rising [mm/s]", "v, \\|u\\| falling [mm/s]",
                            "width [mm/s]"},
                           rows);
      PlotSpec spec{"voltage-velocity loop: " + name, "u [V]", "v [mm/s]", {}, false, 900, 600};
      spec.series.push_back({name, l.u_v, 1e3 * l.v_mps, "lines"});
      Plot(fmt::format("loop_{}.png", i + 1), spec, "voltage-velocity loop " + name);
      WriteFileAtomically(Path(fmt::format("loop_{}.json", i + 1)), ToJson(l) + "\n");
    }
    if (!r_.loops.empty()) WriteFileAtomically(Path("loops.csv"), csv);
    Render(fact);
  }

  void Facts() {
    if (!r_.facts) return;
    md_ += "\n## 7. The paper's facts on the stage (`sysid stage facts`)\n\n";
    md_ +=
        "Each fact of the paper measured on this stage by the paper's own experiment "
        "(docs/virtual_stage.md, \"Stage facts\"). F1-F6 and F8 are required of a stage that "
        "stands in for the paper's; F7 is reported (its figure pair is in section 4, F8's loop "
        "numbers in section 8).\n\n";
    md_ += r_.facts->ToMarkdown();
    std::string failed;
    for (const auto& f : r_.facts->facts)
      if (f.required && !f.met) failed += (failed.empty() ? "" : ", ") + f.id;
    md_ += failed.empty() ? "\nEvery required fact is met.\n"
                          : "\n**Not met on this stage: " + failed +
                                ".** Numbers downstream of these facts describe this stage, not "
                                "the paper's.\n";
    for (const auto& f : r_.facts->facts)
      if (!f.met && !f.note.empty()) md_ += "- " + f.id + ": " + f.note + "\n";
    WriteFileAtomically(Path("facts.json"), r_.facts->ToJson() + "\n");
  }

  void Timing() {
    // Wall times go to stderr and `pipeline --json`, never into the report: the same inputs
    // and seed give a byte-identical report folder.
    md_ += "\n## Run\n\nSteps:";
    for (const auto& [name, s] : r_.step_seconds) {
      (void)s;
      md_ += " " + name + ";";
    }
    md_ += " wall times are printed on stderr and in `sysid pipeline --json`.\n";
    if (!r_.notes.empty()) {
      md_ += "\nNotes:\n";
      for (const auto& n : r_.notes) md_ += "- " + n + "\n";
    }
  }

  static std::string Join(const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s;
  }

  struct PendingPlot {
    std::string file;
    PlotSpec spec;
    std::string caption;
    PlotOutcome outcome;
  };

  const PipelineResult& r_;
  std::string dir_;
  std::vector<PendingPlot> plots_;
  PlotColours colours_;
  std::optional<Reference> ref_;
  std::string md_;
  std::vector<std::string> notes_;
};

}  // namespace

std::vector<std::string> WritePipelineReport(const PipelineResult& result,
                                             const std::string& out_dir) {
  if (result.inputs.IsStack()) return WriteStackReport(result, out_dir);  // stack_report.cpp
  return ReportWriter(result, out_dir).Write();
}

}  // namespace sysid
