// PI gains for an identified friction model (`sysid tune-pi`), the gains' behaviour on the
// model, and the limit-cycle check of a tracking run.
//
// The design: the loop of sysid/control.hpp's RoughModelPiLoop, per direction (a1p, a1n, the
// delay tau, the sample-and-hold's half sample, an extra actuator delay). For a candidate
// crossover w the integral corner is put at Ki / Kp = w / N (N = crossover_per_integral_corner:
// the PI law's phase lag at w is atan(1 / N), 11.3 deg for N = 5) and Kp makes the faster
// direction's |L(j w)| = 1 (the slower direction crosses lower). The tuner scans w on a log
// grid from 0.1 rad/s to the Nyquist frequency, keeps the highest w at which both directions
// meet the phase margin and the gain margin (RoughModelPiMargins, the margins `sysid margins`
// prints), and bisects between it and the next grid point that fails. Without the corner rule
// the crossover grows as Ki -> 0 (pure P control), which leaves the friction's offset
// a2 / (a3 Kp) in the steady state: the rule keeps the integral action in proportion.
#ifndef SYSID_CONTROL_TUNING_HPP_
#define SYSID_CONTROL_TUNING_HPP_

#include <string>

#include "sysid/control.hpp"
#include "sysid/model.hpp"

namespace sysid {

struct PiTuningOptions {
  double loop_rate_hz = 1000;       ///< [Hz] the controller's rate, Ts = 1 / rate, in (0, 1e7]
  double phase_margin_deg = 45;     ///< [deg] target phase margin, in (0, 90)
  double gain_margin_db = 6;        ///< [dB] target gain margin, in [0, 40]
  double crossover_per_integral_corner = 5;  ///< N = w_c / (Ki / Kp), in [1, 1000]
  double extra_delay_s = 0;         ///< [s] actuator delay beyond the sample-and-hold, [0, 10]
  double u_max_v = 10;              ///< [V] the PI output's saturation (for PiOptions), > 0
  void Validate() const;  ///< OptionsError naming the field and the rule
  /// The margins the gains must meet, as a tuning result writes them ("targets").
  template <class Archive>
  void SerializeTargets(Archive* a) {
    a->Visit(SYSID_NVP(phase_margin_deg).Required());
    a->Visit(SYSID_NVP(gain_margin_db).Required());
    a->Visit(SYSID_NVP(crossover_per_integral_corner).Required());
  }
};

struct PiTuningResult {
  PiOptions pi;              ///< the tuned gains, sample_time_s = 1 / loop_rate_hz, u_max_v
  PiMarginsReport margins;   ///< AnalyzePiMargins of the gains: what `sysid margins` prints
  double design_crossover_rad_s = 0;  ///< [rad/s] w: the faster direction's crossover
  int evaluations = 0;       ///< candidate w tried
  PiTuningOptions options;   ///< the options TunePi was given
  /// The fields, in file order (sysid/serialize.hpp): of the PI's, all but the anti-windup
  /// (always on); of the options, the targets, as one object. The evaluations are not written.
  template <class Archive>
  void Serialize(Archive* a) {
    FieldSlice<Archive> gains(a, 0, 4);
    pi.Serialize(&gains);
    Targets targets{&options};
    a->Visit(NameValue<Targets>("targets", &targets).Required());
    a->Visit(SYSID_NVP(design_crossover_rad_s).Required());
    a->Visit(SYSID_NVP(margins).Required());
  }

 private:
  // The options' targets as a described object of their own (they are not the options'
  // first fields).
  struct Targets {
    PiTuningOptions* options;
    template <class Archive>
    void Serialize(Archive* a) {
      options->SerializeTargets(a);
    }
  };
};

/// The tuned gains; throws NumericalError when no candidate w meets both margins in both
/// directions (e.g. a delay that leaves less phase than the target at any crossover), and
/// OptionsError for invalid options or model.
PiTuningResult TunePi(const FrictionModel& model, const PiTuningOptions& options = {});

/// The tuned result as JSON: {"kp_v_per_m", "ki_v_per_m_s", "sample_time_s", "u_max_v",
/// "targets": {"phase_margin_deg", "gain_margin_db", "crossover_per_integral_corner"},
/// "design_crossover_rad_s", "margins": ToJson(PiMarginsReport)}.
std::string ToJson(const PiTuningResult& result, int indent = 2);

// ---- Behaviour of gains on the model plant --------------------------------------------------

/// A reference that holds its last position for `hold_s` [s] after `reference` ends (v = a = 0
/// there): the tail where a loop that has settled is at rest and one that limit-cycles is not.
PositionReference AppendHold(const PositionReference& reference, double hold_s);

/// The limit-cycle check of a run whose reference ends with a hold (AppendHold): over the last
/// `window_s` [s] the error's peak-to-peak; a settled loop (the stage stuck, the integral
/// still) leaves it near the sensor's noise, a limit cycle (the integral winding the stage
/// across its target and back: stick-slip hunting) at least one breakaway's travel. Limit
/// cycle when the peak-to-peak exceeds threshold_m [m].
struct LimitCycleCheck {
  double window_s = 0;                ///< [s]
  double threshold_m = 0;             ///< [m]
  double error_peak_to_peak_m = 0;    ///< [m] max e - min e over the window
  double control_peak_to_peak_v = 0;  ///< [V] max u - min u over the window
  bool limit_cycle = false;           ///< error_peak_to_peak_m > threshold_m
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(window_s).Minimum(0).Required());
    a->Visit(SYSID_NVP(threshold_m).Minimum(0).Required());
    a->Visit(SYSID_NVP(error_peak_to_peak_m).Minimum(0).Required());
    a->Visit(SYSID_NVP(control_peak_to_peak_v).Minimum(0).Required());
    a->Visit(SYSID_NVP(limit_cycle).Required());
  }
};
/// window_s > 0 and no longer than the run; threshold_m > 0 (OptionsError otherwise).
LimitCycleCheck CheckLimitCycle(const TrackingResult& run, double window_s, double threshold_m);
/// {"window_s", "threshold_m", "error_peak_to_peak_m", "control_peak_to_peak_v", "limit_cycle"}.
std::string ToJson(const LimitCycleCheck& check, int indent = 2);

struct PiBehaviourOptions {
  double step_m = 1e-3;             ///< [m] the step's height, != 0
  double step_duration_s = 1;       ///< [s] > 0, the run after the step
  double sine_amplitude_m = 1e-3;   ///< [m] x_ref = A sin(2 pi f t), > 0
  double sine_frequency_hz = 1;     ///< [Hz] > 0
  int sine_cycles = 2;              ///< >= 1, then a hold of one period (limit-cycle check)
  /// [m] > 0 (CheckLimitCycle): 50 counts of the twin's 0.1 um encoder, far above its noise
  /// (0.03 um) and far below a stick-slip hunt (mm on the actuator-delay stage)
  double limit_cycle_threshold_m = 5e-6;
  void Validate() const;
};

/// The step of the gains on the model plant: x_ref from 0 to step_m at the first sample.
struct PiStepResponse {
  double step_m = 0;           ///< [m]
  double overshoot = 0;        ///< [1] (max x - step) / step, >= 0
  double rise_time_s = 0;      ///< [s] 10 % to 90 % of the step (NaN if never reached)
  double settling_time_s = 0;  ///< [s] last exit from +-2 % of the step (NaN if outside at the end)
  double final_error_m = 0;    ///< [m] e at the end of the step run
  long saturated_samples = 0;  ///< samples where the PI output was clipped
  double max_abs_u_v = 0;      ///< [V] max |u|
  /// The fields, in file order (sysid/serialize.hpp): a time never reached is null.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(step_m).Required());
    a->Visit(SYSID_NVP(overshoot).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(rise_time_s).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(settling_time_s).NaNAsNull().Minimum(0).Required());
    a->Visit(SYSID_NVP(final_error_m).Required());
    a->Visit(
        SYSID_NVP(saturated_samples).Minimum(0).Maximum(static_cast<double>(1L << 40)).Required());
    a->Visit(SYSID_NVP(max_abs_u_v).Minimum(0).Required());
  }
};

/// The sine of the gains on the model plant, x_ref = A sin(2 pi f t), then a hold of one
/// period.
struct PiSineResponse {
  double amplitude_m = 0;       ///< [m] A
  double frequency_hz = 0;      ///< [Hz] f
  TrackingResult run;           ///< the sine run with its hold (metrics over the whole run)
  LimitCycleCheck limit_cycle;  ///< over the second half of the hold
  /// The fields, in file order (sysid/serialize.hpp): the run's metrics beside A and f.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(amplitude_m).Required());
    a->Visit(SYSID_NVP(frequency_hz).ExclusiveMinimum(0).Required());
    a->Visit(SYSID_NVP(run).Inline());
    a->Visit(SYSID_NVP(limit_cycle).Required());
  }
};

/// Step and sine of the gains on the model plant (TrackModelSchemes' plant, no feedforward).
struct PiBehaviour {
  PiStepResponse step;
  PiSineResponse sine;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(step).Required());
    a->Visit(SYSID_NVP(sine).Required());
  }
};
PiBehaviour SimulatePiBehaviour(const FrictionModel& model, const PiOptions& pi,
                                const PiBehaviourOptions& options = {});
/// {"step": {"step_m", "overshoot", "rise_time_s", "settling_time_s", "final_error_m",
/// "saturated_samples", "max_abs_u_v"}, "sine": {"amplitude_m", "frequency_hz", the run's
/// metrics, "limit_cycle": {...}}}: the described fields; NaN as null.
std::string ToJson(const PiBehaviour& behaviour, int indent = 2);
/// `sysid tune-pi --json`: the plant's name, the tuning and the gains' behaviour on it.
struct TunePiSummary {
  std::string plant;  ///< the model file's path, as given
  PiTuningResult tuning;
  PiBehaviour behaviour;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(plant).Required());
    a->Visit(SYSID_NVP(tuning).Required());
    a->Visit(SYSID_NVP(behaviour).Required());
  }
};
/// {"plant", "tuning": ToJson(result), "behaviour": ToJson(behaviour)}: a TunePiSummary.
std::string TunePiToJson(const std::string& plant, const PiTuningResult& result,
                         const PiBehaviour& behaviour, int indent = 2);

}  // namespace sysid

#endif  // SYSID_CONTROL_TUNING_HPP_
