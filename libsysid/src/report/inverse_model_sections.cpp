// The report's sections 3 to 5: the dominant variable, the networks' hidden-size sweep and the
// analytic and network inverses compared; for pulses alone, what was skipped.
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "report/report_sections.hpp"
#include "sysid/io_csv_table.hpp"

namespace sysid::internal {
namespace {
namespace fs = std::filesystem;

// The typical (v, a) network's table and verdict beside the dominant one (nn_typical.json).
void AddTypicalNetwork(const PipelineResult& r, ReportSection& s) {
  const auto& t = *r.typical;
  const auto& chosen = r.sweep.rows[static_cast<size_t>(r.sweep.chosen)];
  s.markdown += "\n### Typical (v, a) network vs dominant-variable network\n\n";
  s.markdown += MarkdownTable(
      {"network", "inputs", "H", "epochs", "training MSE [V²]", "test MSE [V²]"},
      {{"typical", "v, a", std::to_string(t.network.hidden_size()), std::to_string(t.epochs),
        Sig(t.train_mse), Sig(r.typical_test_mse)},
       {"dominant", JoinWith(r.nn_inputs, ", "), std::to_string(r.network.hidden_size()),
        std::to_string(chosen.epochs), Sig(chosen.train_mse), Sig(r.network_test_mse)}});
  const double train_dom = chosen.train_mse;
  const bool overfits = t.train_mse <= train_dom && r.typical_test_mse > r.network_test_mse;
  s.markdown +=
      overfits
          ? "\nAs in the paper, the typical network fits the training set at least as well "
            "and the test set worse: it overfits.\n"
          : fmt::format(
                "\n**Not the paper's outcome:** the typical network's training MSE is {} "
                "and its test MSE {} against the dominant network's {} and {}. With "
                "encoder-quantised acceleration as an input, 120 units and the pipeline's "
                "epoch budget ({} epochs on every n-th training sample, n = {}), this data "
                "does not "
                "reproduce the overfitting; see docs/neural.md.\n",
                Sig(t.train_mse), Sig(r.typical_test_mse), Sig(train_dom), Sig(r.network_test_mse),
                r.options.typical_max_epochs, r.options.typical_stride);
  s.writes.emplace_back("nn_typical.json",
                        [&t](const std::string& path) { WriteNeuralNetwork(path, t.network); });
}

// The reference's epochs and MSEs at hidden size `hidden` (blank cells when it has none).
std::vector<std::string> ReferenceSweepCells(const PipelineReference& ref, int hidden) {
  std::vector<std::string> cells{"", "", ""};
  for (const auto& p : *ref.sweep)
    if (p.hidden == hidden) cells = {std::to_string(p.epochs), Sig(p.train_mse), Sig(p.test_mse)};
  return cells;
}

}  // namespace

ReportSection DominanceSection(const PipelineResult& r) {
  ReportSection s;
  const auto& d = r.dominance;
  s.markdown = "\n## 3. Dominant variable\n\n";
  std::vector<std::vector<std::string>> rows;
  for (const auto& res : d.results)
    for (const auto& v : res.ranking)
      rows.push_back({fs::path(res.source).filename().string(), v.name, Sig(v.rms, 4),
                      Sig(v.peak, 4), Sig(v.ratio_to_top, 3), Sig(v.ratio_bound, 3),
                      v.negligible ? "yes" : "no"});
  s.markdown += MarkdownTable({"recording", "variable", "RMS term [m/s²]", "peak [m/s²]",
                               "RMS / top", "pointwise ratio to top (q99)", "negligible"},
                              rows);
  if (d.ranking.size() > 1)
    s.markdown += fmt::format(
        "\nPooled over the recordings: {}.",
        DominanceVerdict(d.ranking[0].name, d.ranking[1].name,
                         d.ranking[1].rms > 0 ? d.ranking[0].rms / d.ranking[1].rms : HUGE_VAL));
  s.markdown += "\nTop-ranked in most recordings: **" + d.dominant + "**; network inputs: ";
  for (const auto& c : r.nn_inputs) s.markdown += "`" + c + "` ";
  s.markdown += "\n";
  for (const auto& res : d.results)
    s.markdown += fmt::format(
        "\n- `{}`: ratio of peaks max |x''| / max |a1 v(t-tau)| = {:.3g} (how the paper reads "
        "its bound); pointwise ratio |x''(t)| / |a1 v(t-tau)|: 99 % quantile {:.3g}, max {:.3g} "
        "(a different quantity) over {} moving samples.",
        fs::path(res.source).filename().string(), res.peak_ratio, res.pointwise_ratio_quantile,
        res.pointwise_ratio_max, res.moving_samples);
  if (r.reference && r.reference->dominance_ratio_bound)
    s.markdown +=
        fmt::format("\n- {}: the bound (ratio of peaks, read off its figure) is O({:.1g}).",
                    r.reference->label, *r.reference->dominance_ratio_bound);
  s.markdown += "\n";
  s.files.emplace_back("dominance.csv", DominanceTableCsv(d));
  // The paper's figure: the acceleration term against the viscous term over time.
  PlotSpec terms{"terms of a3 u = x'' + a1 v(t - tau) + a2 sgn v on the training set",
                 "t [s]",
                 "term [m/s^2]",
                 {},
                 false,
                 1100,
                 500};
  for (const auto& t : r.figures.dominance_terms)
    terms.series.push_back({t.label, t.x, t.y, "lines"});
  s.AddPlot("dominance_terms.png", terms, "acceleration term vs viscous term");
  return s;
}

ReportSection NetworkSection(const PipelineResult& r) {
  ReportSection s;
  const auto& sweep = r.sweep;
  s.markdown = "\n## 4. Inverse neural network: hidden-size sweep\n\n";
  const PipelineReference* ref = r.reference && r.reference->sweep ? &*r.reference : nullptr;
  std::vector<std::string> header{"H", "epochs", "training MSE [V²]", "test MSE [V²]", "stop"};
  if (ref) {
    header.push_back(ref->label + " epochs");
    header.push_back(ref->label + " training MSE");
    header.push_back(ref->label + " test MSE");
  }
  std::vector<std::vector<std::string>> rows;
  CsvTable csv({"hidden", "epochs", "train_mse", "test_mse", "stop"});
  for (size_t i = 0; i < sweep.rows.size(); ++i) {
    const auto& row = sweep.rows[i];
    std::vector<std::string> cells{
        std::to_string(row.hidden) + (static_cast<int>(i) == sweep.chosen ? " (chosen)" : ""),
        std::to_string(row.epochs), Sig(row.train_mse), Sig(row.test_mse), ToString(row.stop)};
    if (ref) {
      const std::vector<std::string> extra = ReferenceSweepCells(*ref, row.hidden);
      cells.insert(cells.end(), extra.begin(), extra.end());
    }
    rows.push_back(cells);
    csv.Integer(row.hidden)
        .Integer(row.epochs)
        .Number(row.train_mse)
        .Number(row.test_mse)
        .Text(ToString(row.stop))
        .EndRow();
  }
  s.markdown += MarkdownTable(header, rows);
  s.markdown += "\nRule: " + sweep.rule + ". The chosen network is `nn.json`.\n";
  s.files.emplace_back("sweep.csv", csv.str());
  s.writes.emplace_back("nn.json",
                        [&r](const std::string& path) { WriteNeuralNetwork(path, r.network); });
  Eigen::VectorXd h(static_cast<Eigen::Index>(sweep.rows.size())), tr(h.size()), te(h.size());
  for (size_t i = 0; i < sweep.rows.size(); ++i) {
    h[static_cast<Eigen::Index>(i)] = sweep.rows[i].hidden;
    tr[static_cast<Eigen::Index>(i)] = sweep.rows[i].train_mse;
    te[static_cast<Eigen::Index>(i)] = sweep.rows[i].test_mse;
  }
  s.AddPlot("sweep.png",
            {"hidden-size sweep",
             "hidden units H [1]",
             "MSE [V^2]",
             {{"training", h, tr, "linespoints"}, {"test", h, te, "linespoints"}},
             false,
             900,
             500},
            "training and test MSE against H");
  if (!r.typical) return s;
  AddTypicalNetwork(r, s);
  s.Append(NetworkFigurePair(r));
  return s;
}

ReportSection ComparisonSection(const PipelineResult& r) {
  ReportSection s;
  s.markdown = "\n## 5. Analytic vs NN inverse model\n\n";
  std::vector<std::vector<std::string>> rows;
  CsvTable csv({"recording", "model", "rmse_v", "peak_error_v", "nrmse_range"});
  for (const auto& c : r.comparisons) {
    const std::string name = fs::path(c.source).stem().string();
    rows.push_back({name, Sig(c.analytic.rmse_v, 4), Sig(c.nn.rmse_v, 4),
                    Sig(c.analytic.peak_error_v, 4), Sig(c.nn.peak_error_v, 4),
                    Sig(c.analytic.nrmse_range, 3), Sig(c.nn.nrmse_range, 3)});
    for (const auto& [model, e] :
         {std::pair<const char*, const PredictionErrors*>{"analytic", &c.analytic}, {"nn", &c.nn}})
      csv.Text(name)
          .Text(model)
          .Number(e->rmse_v)
          .Number(e->peak_error_v)
          .Number(e->nrmse_range)
          .EndRow();
    s.writes.emplace_back("compare_" + name + ".csv",
                          [&c](const std::string& path) { WriteRecording(path, c.AsRecording()); });
  }
  s.markdown += MarkdownTable({"recording", "RMSE analytic [V]", "RMSE NN [V]", "peak analytic [V]",
                               "peak NN [V]", "nrmse_range analytic", "nrmse_range NN"},
                              rows);
  s.files.emplace_back("comparison.csv", csv.str());
  for (const auto& c : r.comparisons) {
    const std::string name = fs::path(c.source).stem().string();
    s.AddPlot("compare_" + name + ".png",
              {"inverse models on " + name,
               "t [s]",
               "u [V]",
               {{"analytic inverse", c.t_s, c.u_analytic_v, "lines"},
                {NetworkLabel(r), c.t_s, c.u_nn_v, "lines"},
                {"measured", c.t_s, c.u_measured_v, "lines"}},
               false,
               1100,
               450},
              name);
  }
  return s;
}

ReportSection SkippedSection(const PipelineResult& r) {
  ReportSection s;
  s.markdown =
      "\n## 3-5. Dominance, networks, inverse comparison: skipped\n\n"
      "Pulse recordings alone identify the rough model; the steps below need more:\n\n";
  for (const auto& line : r.skipped) s.markdown += "- " + line + "\n";
  return s;
}

}  // namespace sysid::internal
