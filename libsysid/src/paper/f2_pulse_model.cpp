#include "paper/f2_pulse_model.hpp"

#include <cmath>

#include "paper/paper_numbers.hpp"

namespace sysid::paper {

bool PulseModelMet(const FrictionModel& s, const FrictionModel& p) {
  auto within = [](double a, double b) {
    return std::abs(a - b) <= kPulseModelTolerance * std::abs(b);
  };
  return within(s.a1p, p.a1p) && within(s.a1n, p.a1n) && within(s.a2p, p.a2p) &&
         within(s.a2n, p.a2n);
}

PulseModelFact CheckPulseModel(Experiments& experiments) {
  PulseModelFact f;
  f.stage = experiments.Pulses().identification.model;
  f.paper = PulseModel();
  f.met = PulseModelMet(f.stage, f.paper);
  return f;
}

}  // namespace sysid::paper
