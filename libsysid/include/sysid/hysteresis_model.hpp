// The common face of the hysteresis models (the paper's rivals, docs/hysteresis.md): each maps a
// sampled input u (voltage [V] or force [N]) to an output y (displacement [m]) and, where the
// model allows, back. Prandtl–Ishlinskii models live in sysid/hysteresis.hpp, Bouc–Wen models in
// sysid/hysteresis_bouc_wen.hpp; both implement this interface so that the CLI
// (`sysid hysteresis`), the comparison tables and Python treat them alike.
#ifndef SYSID_HYSTERESIS_MODEL_HPP_
#define SYSID_HYSTERESIS_MODEL_HPP_

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "sysid/serialize.hpp"

namespace sysid {

/// One fitted parameter with its unit and standard error (NaN when the fit gives none).
struct HysteresisParameter {
  std::string name;       ///< e.g. "w3", "alpha"
  std::string unit;       ///< SI unit, "1" for a pure number
  double value = 0;
  double std_error = 0;   ///< NaN when unknown (not estimated, or the normal matrix is singular)
  /// An entry of a model file's or a fit's "parameters" table, in file order
  /// (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(name));
    a->Visit(SYSID_NVP(unit));
    a->Visit(SYSID_NVP(value).NaNAsNull());
    a->Visit(SYSID_NVP(std_error).NaNAsNull());
  }
};

/// What a fit did, for every model alike (the Ceres-style summary).
struct HysteresisFitSummary {
  std::string kind;                 ///< the model's kind() string
  int samples = 0;                  ///< training samples used
  double fit_time_s = 0;            ///< [s] wall time of the fit
  double training_rms = 0;          ///< RMS of y_model - y on the training samples, in y's unit
  bool converged = true;
  std::string message;              ///< why the fit stopped; warnings (ill-conditioning, bounds)
  /// `hysteresis fit --json`'s keys before the model's parameters (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(kind));
    a->Visit(SYSID_NVP(samples).Minimum(0));
    a->Visit(SYSID_NVP(fit_time_s).Minimum(0));
    a->Visit(SYSID_NVP(training_rms).Renamed("training_rms_m").NaNAsNull());
    a->Visit(SYSID_NVP(converged));
    a->Visit(SYSID_NVP(message));
  }
};

/// A model's inverse run causally, one sample at a time, as a real-time controller runs it:
/// Step(x_ref at sample k) -> u_k from the reference so far, no allocation and no
/// exception on finite input. The concrete steppers (PiInverseStepper, BoucWenInverseStepper in
/// sysid/hysteresis_stepper.hpp; OperatorNetworkInverseStepper in sysid/nn_stepper.hpp) say
/// more; HysteresisModel::InverseStepper makes the one of a model of any kind, so that a loop
/// holding a HysteresisModel can step its inverse.
class HysteresisInverseStepper {
 public:
  virtual ~HysteresisInverseStepper() = default;
  /// Back to the model's initial state: the next step is the first sample.
  virtual void Reset() = 0;
  /// u_k [V] such that the model's output at sample k follows x_ref_m [m].
  virtual double Step(double x_ref_m) = 0;
  /// Whether the last step's reference was outside the model's reach (non-finite included): the
  /// output is then held at the range's end, and the model's Invert refuses that sample.
  virtual bool out_of_range() const = 0;
};

/// A hysteresis model y = H[u]. Implementations are immutable after construction (thread-safe
/// to simulate from several threads).
class HysteresisModel {
 public:
  virtual ~HysteresisModel() = default;
  /// "pi", "gpi", "rdpi", "bouc-wen", "bouc-wen-piezo" or "nn-operators" (the CLI's --model).
  virtual std::string kind() const = 0;
  /// y [m] for the samples u, spaced dt_s [s] apart, from the model's initial state.
  virtual Eigen::VectorXd Simulate(const Eigen::VectorXd& u, double dt_s) const = 0;
  /// y [m] over one period of a periodic input in its periodic steady state: `u_period` is one
  /// period of u (the input is u_period repeated forever), the result the last simulated period
  /// once two successive periods agree to `tolerance` [m] (max |Δy|). The default simulates
  /// 2, 4, 8, ... periods from the initial state, up to `max_periods` (then NumericalError
  /// saying how far the last two periods still differ); models with a cheaper way override it.
  virtual Eigen::VectorXd SimulatePeriodic(const Eigen::VectorXd& u_period, double dt_s,
                                           double tolerance = 1e-12, int max_periods = 256) const;
  /// Whether Invert is available for this model (and these parameters).
  virtual bool invertible() const = 0;
  /// u such that Simulate(u) follows y_desired [m]; throws NumericalError with the reason when
  /// the model cannot be inverted, InputError (naming the sample) when y_desired leaves the
  /// model's range.
  virtual Eigen::VectorXd Invert(const Eigen::VectorXd& y_desired, double dt_s) const = 0;
  /// The inverse as a causal stepper at sample time dt_s [s]; Invert is a loop over it (and
  /// raises its errors from out_of_range()), except nn-operators, whose Invert evaluates the
  /// same features in one batch (a few ulp apart). Throws NumericalError as Invert does when
  /// the model cannot be inverted (at dt_s).
  virtual std::unique_ptr<HysteresisInverseStepper> InverseStepper(double dt_s) const = 0;
  /// Every parameter, in a fixed order, with its unit and standard error.
  virtual std::vector<HysteresisParameter> parameters() const = 0;
  /// The model file's JSON text ({"kind": ..., ...}); ReadHysteresisModel reads it back.
  virtual std::string ToJson(int indent = 2) const = 0;
};

}  // namespace sysid

#endif  // SYSID_HYSTERESIS_MODEL_HPP_
