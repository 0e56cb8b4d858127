#include "paper/f3_delay.hpp"

namespace sysid::paper {

bool DelayMet(double tau_s, double rms_at_tau_mps, double rms_at_zero_mps) {
  return tau_s >= kDelayMinS && tau_s <= kDelayMaxS &&
         rms_at_tau_mps <= kDelayMaxRmsRatio * rms_at_zero_mps;
}

DelayFact CheckDelay(Experiments& experiments) {
  const DelayExperiment& d = experiments.Delay();
  DelayFact f;
  f.tau_s = d.tuning.tau_s;
  f.rms_at_tau_mps = d.tuning.rms_error_mps;
  f.rms_at_zero_mps = d.rms_at_zero_mps;
  f.rms_ratio = f.rms_at_tau_mps / f.rms_at_zero_mps;
  f.met = DelayMet(f.tau_s, f.rms_at_tau_mps, f.rms_at_zero_mps);
  return f;
}

}  // namespace sysid::paper
