// The paper's printed numbers.
#include "paper/paper_numbers.hpp"

#include <cmath>

#include "sysid/stage.hpp"

namespace sysid::paper {

const std::vector<std::pair<double, double>>& PulseTable() {
  // The stage's copy of the paper's table (datasets/paper/pulse_table.csv).
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

FrictionModel PulseModel() {
  FrictionModel m = FrictionModel::Paper();
  m.tau_s = 0;
  return m;
}

double TrackingMaxErrorM(double frequency_hz, FeedforwardScheme scheme) {
  // The tracking table of "Prediction Performance in Feedforward Compensation" [mm].
  const bool half = std::abs(frequency_hz - 0.5) < 1e-9, one = std::abs(frequency_hz - 1.0) < 1e-9;
  if (!half && !one) return std::nan("");
  double mm = std::nan("");
  if (scheme == FeedforwardScheme::kNone) mm = half ? 0.10651 : 0.17156;
  if (scheme == FeedforwardScheme::kAnalytic) mm = half ? 0.03609 : 0.10579;
  if (scheme == FeedforwardScheme::kNetwork) mm = half ? 0.01779 : 0.07292;
  return 1e-3 * mm;
}

}  // namespace sysid::paper
