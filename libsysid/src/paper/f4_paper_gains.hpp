// Private: F4, the paper's PI gains (Kp 19000 V/m, Ki 660000 V/(m s)) on the 0.5 and 1 Hz
// smooth profiles, PI alone: no limit cycle (ripple at rest within
// FactsOptions::ripple_tolerance_m, no sample with u clipped at +-u_max) and quiet in motion
// (MotionRippleOf's RMS within FactsOptions::motion_ripple_tolerance_m).
#ifndef SYSID_SRC_PAPER_F4_PAPER_GAINS_HPP_
#define SYSID_SRC_PAPER_F4_PAPER_GAINS_HPP_

#include <vector>

#include "paper/experiments.hpp"

namespace sysid::paper {

struct PaperGainsFact {
  struct Row {
    double frequency_hz = 0;     ///< [Hz]
    double ripple_m = 0;         ///< [m] RippleAmplitude
    double motion_ripple_m = 0;  ///< [m] MotionRippleOf's RMS
    double ringing_hz = 0;       ///< [Hz] its periodogram peak
    long clipped_samples = 0;    ///< samples with |u| clipped at u_max
    double max_abs_u_v = 0;      ///< [V]
    bool quiet = false;          ///< motion_ripple_m within its tolerance
  };
  std::vector<Row> rows;  ///< in FactsOptions::track_frequencies_hz order
  bool met = false;
};

/// No limit cycle and quiet in motion: ripple_m <= ripple_tolerance_m, no clipped sample and
/// motion_ripple_m <= motion_ripple_tolerance_m.
bool PaperGainsMet(const PaperGainsFact::Row& row, const FactsOptions& options);

PaperGainsFact CheckPaperGains(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F4_PAPER_GAINS_HPP_
