#include "paper/f1_plateaus.hpp"

#include <cmath>
#include <limits>

#include "paper/paper_numbers.hpp"

namespace sysid::paper {

bool PlateausMet(const std::vector<double>& stage_mps, const std::vector<double>& paper_mps) {
  if (stage_mps.size() != paper_mps.size() || stage_mps.empty()) return false;
  for (std::size_t i = 0; i < stage_mps.size(); ++i)
    if (!(std::abs(stage_mps[i] - paper_mps[i]) <= kPlateauTolerance * std::abs(paper_mps[i])))
      return false;
  return true;
}

PlateausFact CheckPlateaus(Experiments& experiments) {
  PlateausFact f;
  f.paper_pulses = PulseTable().size();
  std::vector<double> stage_v, paper_v;
  for (const Plateau& p : experiments.Pulses().plateaus) {
    PlateausFact::Row row{p.u_v, p.v_mps, std::nan("")};
    for (const auto& [pu, pv] : PulseTable())
      if (std::abs(pu - p.u_v) < 1e-6) row.paper_v_mps = pv;
    f.rows.push_back(row);
    stage_v.push_back(row.v_mps);
    paper_v.push_back(row.paper_v_mps);
    const double dev = std::abs(row.v_mps - row.paper_v_mps) / std::abs(row.paper_v_mps);
    if (!(dev <= f.worst_relative_deviation)) {  // NaN (no plateau, no table entry) is worst
      f.worst_relative_deviation = std::isnan(dev) ? std::numeric_limits<double>::infinity() : dev;
      f.worst = row;
    }
  }
  f.met = f.rows.size() == f.paper_pulses && PlateausMet(stage_v, paper_v);
  return f;
}

}  // namespace sysid::paper
