// Prandtl–Ishlinskii inverses (pi, gpi, rdpi; sysid/hysteresis.hpp) run causally, one sample at
// a time, as a real-time controller runs them: Step(x_ref_k) -> u_k from the
// reference position at sample k and the play operators' state. pi: the closed-form inverse, a
// classical PI model of x - c (Kuhnen 2003); gpi, rdpi: a bisection to adjacent doubles on the
// step's monotone output (rdpi's rate is that of the inverse's own last two outputs).
// PrandtlIshlinskiiModel::Invert is a loop over this stepper. The piezo Bouc–Wen inverse
// (BoucWenInverseStepper) solves the model's exact step per sample; PiezoBoucWen::Invert loops
// over it.
#ifndef SYSID_HYSTERESIS_STEPPER_HPP_
#define SYSID_HYSTERESIS_STEPPER_HPP_

#include <vector>

#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"

namespace sysid {

/// Where the last step left the model's input range [lo, hi] (the training range widened by
/// range_margin): the output is then clamped to the range's end.
struct PiInverseSaturation {
  bool saturated = false;  ///< the last step's reference needs an input outside [lo, hi]
  bool above = false;      ///< gpi, rdpi: beyond the output at hi (else below the one at lo)
  double needed_u_v = 0;   ///< pi: the input the closed form gave (may be non-finite)
  double bound_output_m = 0;  ///< gpi, rdpi: the step's output at the violated end
};

class PiInverseStepper final : public HysteresisInverseStepper {
 public:
  /// Throws NumericalError when the model is not invertible (the reason names the parameter)
  /// or, rdpi, when the inverse's error gain (q_0 + ... + q_n) max|u| / (dt p0) >= 1; rdpi
  /// also OptionsError unless 0 < dt_s < infinity (pi, gpi do not use dt_s).
  PiInverseStepper(const PrandtlIshlinskiiModel& model, double dt_s);
  /// Back to the model's initial state.
  void Reset() override;
  /// u_k [V] such that the model's output at sample k is x_ref_m [m], clamped to [lo, hi]
  /// (saturation() says so). No allocation and no exception.
  double Step(double x_ref_m) override;
  bool out_of_range() const override { return saturation_.saturated; }
  const PiInverseSaturation& saturation() const { return saturation_; }
  double input_min_v() const { return lo_; }  ///< lo [V]
  double input_max_v() const { return hi_; }  ///< hi [V]
  /// pi: the inverse model's parameters (a classical PI in x - c); gpi, rdpi: the model's.
  const PiParameters& stepped_parameters() const { return p_; }
  /// The forward model's offset c [m] (pi subtracts it before its inverse model).
  double offset_m() const { return offset_m_; }
  /// The play states now [V] (pi: the inverse model's).
  const std::vector<double>& state() const { return z_; }

 private:
  bool closed_form_ = true;
  PiParameters p_;
  double offset_m_ = 0, dt_s_ = 0, lo_ = 0, hi_ = 0;
  std::vector<double> z0_, z_;
  double u1_ = 0, u2_ = 0;  // rdpi: u_{k-1}, u_{k-2}
  long long k_ = 0;
  PiInverseSaturation saturation_;
};

/// The piezo Bouc–Wen inverse (kind "bouc-wen-piezo", rate-independent): u_0 = (x_0 - c) / d
/// from h = 0, then per sample the u_k whose exact step from (u_{k-1}, h) gives x_ref,k: the
/// root bracketed by doubling a step from u_{k-1}, then bisected to adjacent doubles.
class BoucWenInverseStepper final : public HysteresisInverseStepper {
 public:
  /// Throws NumericalError when the model is not invertible (its loop is not monotone).
  explicit BoucWenInverseStepper(const PiezoBoucWen& model);
  void Reset() override;
  /// u_k [V]. No allocation, no exception: a reference out of the model's reach (no bracket
  /// in 200 doublings) holds u_{k-1} and out_of_reach() says so.
  double Step(double x_ref_m) override;
  bool out_of_reach() const { return out_of_reach_; }
  bool out_of_range() const override { return out_of_reach_; }

 private:
  PiezoBoucWenParameters p_;
  double u_prev_ = 0, h_ = 0;
  long long k_ = 0;
  bool out_of_reach_ = false;
};

}  // namespace sysid

#endif  // SYSID_HYSTERESIS_STEPPER_HPP_
