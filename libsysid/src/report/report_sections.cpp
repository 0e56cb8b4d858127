// The report's networks figure pair and F8's loop tables (report_sections.hpp).
#include "report/report_sections.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "paper/facts_results.hpp"
#include "paper/measures.hpp"
#include "paper/paper_numbers.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_irreducible.hpp"

namespace sysid::internal {
namespace {

std::string G(double v, int digits = 4) {
  return std::isnan(v) ? std::string("-") : fmt::format("{:.{}g}", v, digits);
}

std::string Join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (const auto& x : v) out += (out.empty() ? "" : sep) + x;
  return out;
}

// F8's note without its "not met: " lead (the verdict is already in bold).
std::string FailedParts(const std::string& note) {
  const std::string lead = "not met: ";
  return note.rfind(lead, 0) == 0 ? note.substr(lead.size()) : note;
}

}  // namespace

std::string MappingSentence(const PipelineInputs& inputs) {
  const SourceMapping& m = inputs.mapping;
  if (m.empty()) return "";
  std::string flags;
  if (!m.variables.empty()) {
    std::vector<std::string> parts;
    for (const auto& [column, spec] : m.variables) parts.push_back(column + "=" + spec);
    flags += " --var " + Join(parts, ",");
  }
  if (m.rate_hz > 0) flags += fmt::format(" --rate {}", m.rate_hz);
  if (!m.scales.empty()) {
    std::vector<std::string> parts;
    for (const auto& [column, factor] : m.scales)
      parts.push_back(fmt::format("{}={}", column, factor));  // shortest round-trip text
    flags += " --scale " + Join(parts, ",");
  }
  if (m.t_start_s) flags += fmt::format(" --t-start {}", *m.t_start_s);
  if (m.t_end_s) flags += fmt::format(" --t-end {}", *m.t_end_s);
  return " Read with `" + flags.substr(1) + "`.";
}

std::string NetworkLabel(const PipelineResult& r) {
  return fmt::format("NN inverse ({}), H = {}", Join(r.nn_inputs, ", "), r.network.hidden_size());
}

ReportSection NetworkFigurePair(const PipelineResult& r, NetworkMses* mses) {
  ReportSection s;
  if (!r.typical) return s;
  const NeuralNetwork& typical = r.typical->network;
  const NeuralNetwork& dominant = r.network;
  NetworkMses m;
  std::string csv = "network,inputs,hidden,set,mse_v2\n";
  // Per set (training, test): the least MSE any model on (v, a) and on the dominant inputs can
  // reach there (sysid irreducible): what the networks' MSEs are to be read against.
  std::array<std::pair<double, double>, 2> floors{};
  for (const PipelineFigures::NetworkSet& n : r.figures.networks) {
    const std::string& set = n.set;
    const double mt = n.typical_mse, md = n.dominant_mse;
    floors[set == "training" ? 0 : 1] = {n.typical_floor_mse, n.dominant_floor_mse};
    (set == "training" ? m.typical_train : m.typical_test) = mt;
    (set == "training" ? m.dominant_train : m.dominant_test) = md;
    csv += fmt::format("typical,v a,{},{},{:.9g}\n", typical.hidden_size(), set, mt);
    csv += fmt::format("dominant,{},{},{},{:.9g}\n", Join(r.nn_inputs, " "),
                       dominant.hidden_size(), set, md);
    // Against the row index, as the paper's figures: the set is segments in random order, and
    // the index keeps them side by side without the gaps a time axis could show.
    Eigen::VectorXd k(n.targets_v.size());
    for (Eigen::Index i = 0; i < k.size(); ++i) k[i] = static_cast<double>(i);
    PlotSpec spec{fmt::format("networks against the {} set", set),
                  "sample index [1]",
                  "u [V]",
                  {{fmt::format("typical NN (v, a), H = {}", typical.hidden_size()), k,
                    n.typical_v, "lines"},
                   {NetworkLabel(r), k, n.dominant_v, "lines"},
                   {"measured", k, n.targets_v, "lines"}},
                  false,
                  1400,
                  500};
    // The data's range plus a quarter each way: a network that strays far outside (a typical
    // network extrapolating in a) is cut at the frame instead of flattening the data.
    const double lo = n.targets_v.minCoeff(), hi = n.targets_v.maxCoeff(), pad = 0.25 * (hi - lo);
    spec.y_min = lo - pad;
    spec.y_max = hi + pad;
    s.plots.push_back({fmt::format("network_{}.png", set), spec,
                       fmt::format("network outputs against the {} set (y: the data's range "
                                   "+-25 %)", set)});
  }
  const bool contrast = m.typical_test >= 2 * m.typical_train && m.dominant_test < m.typical_test;
  s.markdown = fmt::format(
      "\n### The paper's figure pair: each network against the training and the test set\n\n"
      "Each network's output and the data u on every row of the training set and of the test "
      "set (the paper's figures of the typical network, \"fits the training set, test very "
      "poor\", and of the dominant one). The four MSEs in one table, computed as the facts' F7 "
      "(every row of each set; the typical network trained on every n-th training row, n = "
      "{}):\n\n",
      r.options.typical_stride);
  s.markdown += MarkdownTable(
      {"network", "training MSE [V²]", "test MSE [V²]",
       "least MSE on its inputs, training / test [V²]", "paper (training / test)"},
      {{fmt::format("typical (v, a), H = {}", typical.hidden_size()), G(m.typical_train),
        G(m.typical_test), fmt::format("{} / {}", G(floors[0].first), G(floors[1].first)),
        "fits training; test very poor"},
       {fmt::format("dominant ({}), H = {}", Join(r.nn_inputs, ", "), dominant.hidden_size()),
        G(m.dominant_train), G(m.dominant_test),
        fmt::format("{} / {}", G(floors[0].second), G(floors[1].second)),
        fmt::format("{:.3f} / {:.3f}", paper::kDominantTrainMseV2,
                    paper::kDominantTestMseV2)}});
  s.markdown +=
      "\nThe least MSE is estimated from the data alone (`sysid irreducible`: the variance of u "
      "among each row's 10 nearest neighbours in the network's standardised inputs): a network "
      "near it has learnt what its inputs determine; the rest is what they do not.\n";
  s.markdown += fmt::format(
      "\nF7's contrast (typical test ≥ 2 × typical training and dominant test < typical test): "
      "**{}** (typical test / training {:.3g}).\n",
      contrast ? "yes, as in the paper" : "no", m.typical_test / m.typical_train);
  // When the stage's physics gives no contrast the report says so, and where the search for a
  // drive that would is recorded.
  if (!contrast)
    s.markdown +=
        "\nThe paper's headline (the typical network overfits, the dominant one generalises) "
        "needs a drive whose voltage depends on the motion's history in a way the acceleration "
        "encodes differently on the training and the test waveforms. No drive tried on the twin "
        "does it without breaking another fact: docs/virtual_stage.md lists 124 candidates "
        "(\"Drive hysteresis\", \"Creep\", \"F8 with F5\"), with the facts each meets. The "
        "default stage is the closest to the paper among them (the preset `drive-hysteresis`, "
        "candidate P2): the ceramic's asymmetric play operators whose lag partly creeps out, so "
        "that the voltage-velocity loop is asymmetric, reaches into the pulse region and widens "
        "with the rate (F8), with every other required fact met at the default seed.\n";
  if (!contrast)
    s.markdown += fmt::format(
        "\nOn these recordings no model of u on the dominant inputs can go below {} V² on the "
        "test set ({:.3g} × the paper's {:.3f} V²): the rows where the stage rests while u "
        "crosses the dead band decide the MSE, whatever the network (docs/virtual_stage.md, "
        "\"F7: what the data allow\").\n",
        G(floors[1].second), floors[1].second / paper::kDominantTestMseV2,
        paper::kDominantTestMseV2);
  s.files.emplace_back("network_mse.csv", csv);
  if (mses) *mses = m;
  return s;
}

ReportSection LoopFactSection(const StageFacts& facts) {
  ReportSection s;
  const StageFact* f = facts.Find("F8");
  if (!f || !facts.results || !facts.results->f8) return s;
  const paper::VoltageLoopFact& loops = *facts.results->f8;
  const VoltageLoop& t = loops.triangle;
  s.markdown = fmt::format(
      "\n### F8 on the stage: the loop of the paper's section-3 tests\n\n"
      "`sysid stage facts --facts F8` (docs/virtual_stage.md, \"Stage facts\"): **{}**{}.\n\n"
      "Triangle (one period, open loop): starts forward at {} V, backward at {} V; width = "
      "v (\\|u\\| falling) − v (\\|u\\| rising); mean width = enclosed area / voltage span.\n\n",
      f->met ? "met" : "not met", f->met ? std::string() : ", " + FailedParts(f->note),
      G(t.start_forward_v), G(t.start_backward_v));
  std::vector<std::vector<std::string>> rows;
  std::string csv = "test,amplitude_v,frequency_hz,level_v,width_mps,mean_width_forward_mps,"
                    "mean_width_backward_mps,mean_width_mps\n";
  for (const auto& l : t.levels) {
    rows.push_back({fmt::format("{:+g}", l.level_v), G(1e3 * l.v_rising_mps),
                    G(1e3 * l.v_falling_mps), G(1e3 * l.WidthMps()),
                    G(100 * paper::LoopRelativeWidth(l), 3)});
    csv += fmt::format("triangle,,,{:g},{:.9g},{:.9g},{:.9g},{:.9g}\n", l.level_v, l.WidthMps(),
                       t.MeanWidthForwardMps(), t.MeanWidthBackwardMps(),
                       paper::LoopMeanWidth(t));
  }
  s.markdown += MarkdownTable({"u [V]", "v, \\|u\\| rising [mm/s]", "v, \\|u\\| falling [mm/s]",
                               "width [mm/s]", "width / \\|v\\| [%]"},
                              rows);
  s.markdown += "\nSinusoids u = A sin(2π f t − π/2) − 0.3 V (second period; mean width [mm/s]):\n\n";
  rows.clear();
  for (const auto* sweep : {&loops.frequency_sweep, &loops.amplitude_sweep})
    for (const auto& r : *sweep) {
      rows.push_back({G(r.amplitude_v), G(r.frequency_hz), G(r.loop.start_forward_v),
                      G(r.loop.start_backward_v), G(1e3 * r.loop.MeanWidthForwardMps()),
                      G(1e3 * r.loop.MeanWidthBackwardMps()), G(1e3 * r.mean_width_mps)});
      csv += fmt::format("sine,{:g},{:g},,,{:.9g},{:.9g},{:.9g}\n", r.amplitude_v, r.frequency_hz,
                         r.loop.MeanWidthForwardMps(), r.loop.MeanWidthBackwardMps(),
                         r.mean_width_mps);
    }
  s.markdown += MarkdownTable({"A [V]", "f [Hz]", "start forward [V]", "start backward [V]",
                               "forward", "backward", "both"},
                              rows);
  s.files.emplace_back("loop_fact.csv", csv);
  return s;
}

}  // namespace sysid::internal
