// Private: F3, the delay of the viscous term: tune-delay on the pulse recording gives tau in
// [2.5, 4.5] ms (the paper's 3.5 ms) and RMS dv(tau) <= 0.8 RMS dv(0).
#ifndef SYSID_SRC_PAPER_F3_DELAY_HPP_
#define SYSID_SRC_PAPER_F3_DELAY_HPP_

#include "paper/experiments.hpp"

namespace sysid::paper {

constexpr double kDelayMinS = 2.5e-3;      ///< [s]
constexpr double kDelayMaxS = 4.5e-3;      ///< [s]
constexpr double kDelayMaxRmsRatio = 0.8;  ///< RMS dv(tau) / RMS dv(0)

struct DelayFact {
  double tau_s = 0;            ///< [s] the tuned delay
  double rms_at_tau_mps = 0;   ///< [m/s] RMS dv at tau
  double rms_at_zero_mps = 0;  ///< [m/s] RMS dv at tau = 0
  double rms_ratio = 0;        ///< rms_at_tau_mps / rms_at_zero_mps
  bool met = false;
};

/// kDelayMinS <= tau <= kDelayMaxS and rms_at_tau <= kDelayMaxRmsRatio rms_at_zero.
bool DelayMet(double tau_s, double rms_at_tau_mps, double rms_at_zero_mps);

DelayFact CheckDelay(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F3_DELAY_HPP_
