// Private: F1, the pulse plateaus: the steady velocity of each of the paper's ten 0.4 s pulses
// within 2 % of the paper's pulse table.
#ifndef SYSID_SRC_PAPER_F1_PLATEAUS_HPP_
#define SYSID_SRC_PAPER_F1_PLATEAUS_HPP_

#include <cstddef>
#include <vector>

#include "paper/experiments.hpp"

namespace sysid::paper {

constexpr double kPlateauTolerance = 0.02;  ///< relative

struct PlateausFact {
  struct Row {
    double u_v = 0;          ///< [V] pulse amplitude
    double v_mps = 0;        ///< [m/s] NaN: no plateau
    double paper_v_mps = 0;  ///< [m/s] NaN: the amplitude is not in the paper's table
  };
  std::vector<Row> rows;         ///< in pulse order
  std::size_t paper_pulses = 0;  ///< pulses in the paper's table
  /// |v - v_paper| / |v_paper| of the worst row; infinite when a row has no plateau, -1 with no
  /// rows.
  double worst_relative_deviation = -1;
  Row worst;  ///< that row
  bool met = false;
};

/// Every |v - v_paper| <= kPlateauTolerance |v_paper|; `stage` and `paper` in the same order.
bool PlateausMet(const std::vector<double>& stage_mps, const std::vector<double>& paper_mps);

PlateausFact CheckPlateaus(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F1_PLATEAUS_HPP_
