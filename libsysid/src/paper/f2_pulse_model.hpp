// Private: F2, the pulse least squares (a3 = 6, tau = 0): a1p, a1n, a2p, a2n each within 5 %
// of the paper's 104.0154, 117.1441, 3.1023, 6.8216.
#ifndef SYSID_SRC_PAPER_F2_PULSE_MODEL_HPP_
#define SYSID_SRC_PAPER_F2_PULSE_MODEL_HPP_

#include "paper/experiments.hpp"

namespace sysid::paper {

constexpr double kPulseModelTolerance = 0.05;  ///< relative

struct PulseModelFact {
  FrictionModel stage;  ///< the stage's pulse least squares
  FrictionModel paper;  ///< PulseModel()
  bool met = false;
};

/// a1p, a1n, a2p, a2n of `stage` each within kPulseModelTolerance of `paper`'s.
bool PulseModelMet(const FrictionModel& stage, const FrictionModel& paper);

PulseModelFact CheckPulseModel(Experiments& experiments);

}  // namespace sysid::paper

#endif  // SYSID_SRC_PAPER_F2_PULSE_MODEL_HPP_
