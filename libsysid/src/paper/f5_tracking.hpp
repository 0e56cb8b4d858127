// Private: F5, the tracking table: max |e| of PI > PI + analytic inverse > PI + NN inverse at
// both frequencies, each within a factor 3 of the paper's table.
#ifndef SYSID_SRC_PAPER_F5_TRACKING_HPP_
#define SYSID_SRC_PAPER_F5_TRACKING_HPP_

#include <vector>

#include "paper/experiments.hpp"

namespace sysid::paper {

constexpr double kTrackingFactor = 3;  ///< each max |e| within this factor of the paper's

struct TrackingFact {
  /// Max |e| [m] of each scheme, the stage's and the paper's (NaN at a frequency the paper did
  /// not measure).
  struct Row {
    double frequency_hz = 0;                                        ///< [Hz]
    double none_m = 0, analytic_m = 0, nn_m = 0;                    ///< [m]
    double paper_none_m = 0, paper_analytic_m = 0, paper_nn_m = 0;  ///< [m]
  };
  /// The NN row with dominant networks from several initial weights
  /// (FactsOptions::network_initializations > 1).
  struct Spread {
    double frequency_hz = 0;             ///< [Hz]
    std::vector<double> nn_max_error_m;  ///< [m] per network, the first the NN row's
    long beats_analytic = 0;             ///< networks with max |e| below the analytic's
  };
  std::vector<Row> rows;       ///< in FactsOptions::track_frequencies_hz order
  std::vector<Spread> spread;  ///< empty with one network
  bool met = false;            ///< the first network's rows: the paper reports one network
};

/// Within kTrackingFactor of the paper's value, both ways.
bool WithinTrackingFactor(double stage_m, double paper_m);
/// none > analytic > nn, and each WithinTrackingFactor of the paper's.
bool TrackingOrderMet(double none_m, double analytic_m, double nn_m, double paper_none_m,
                      double paper_analytic_m, double paper_nn_m);

TrackingFact CheckTracking(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F5_TRACKING_HPP_
