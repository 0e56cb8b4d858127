// The analytic friction inverse run causally, one sample at a time, as a real-time controller
// runs it: u_k = (a_k + a1 v(t_k - tau) + a2 sgn v_k) / a3 (sysid/model.hpp) from
// the reference's velocity v_k [m/s] and acceleration a_k [m/s^2] at sample k and the
// velocities before it. v(t_k - tau) comes from a DelayLine (sysid/signal.hpp): linear
// interpolation between the two neighbouring samples, v_0 held before the first sample, the
// same rule as DelaySignal. AnalyticInverse (sysid/compare.hpp) is a loop over this stepper.
#ifndef SYSID_MODEL_STEPPER_HPP_
#define SYSID_MODEL_STEPPER_HPP_

#include "sysid/model.hpp"
#include "sysid/signal.hpp"

namespace sysid {

class FrictionInverseStepper {
 public:
  /// Throws OptionsError for an invalid model (FrictionModel::Validate), unless
  /// 0 < dt_s < infinity, and when tau / dt + 2 > kMaxDelayLineSamples. `max_steps` as
  /// DelayLine's max_pushes (a batch's length; -1 for a controller that runs without end).
  FrictionInverseStepper(const FrictionModel& model, double dt_s, long long max_steps = -1);
  /// Back to rest: the next step is the first sample.
  void Reset() { line_.Reset(); }
  /// u_k [V] from v_k [m/s] and a_k [m/s^2]. No allocation, no exception; finite inputs can
  /// still give a non-finite u when the model's coefficients overflow (the caller checks).
  double Step(double v_mps, double a_mps2) {
    return model_.InverseVoltage(a_mps2, line_.Push(v_mps), v_mps);
  }
  const FrictionModel& model() const { return model_; }
  double dt_s() const { return dt_s_; }
  const DelayLine& delay_line() const { return line_; }

 private:
  FrictionModel model_;
  double dt_s_;
  DelayLine line_;
};

}  // namespace sysid

#endif  // SYSID_MODEL_STEPPER_HPP_
