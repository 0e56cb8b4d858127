// The virtual piezo stage: a simulated ultrasonic-motor stage (PBA PLS8 + Nanomotion HR-8 as in
// the paper) that is deliberately richer than the rough model of model.hpp, and the paper's
// data-collection procedures (pulse test, tracking sets, test waveforms) that run on it.
// Two plant models (VelocitySourcePlant, ActuatorDelayPlant) share the rig, driver and CVODE:
//
// VELOCITY SOURCE (model "velocity-source", the default's; docs/virtual_stage.md). An ultrasonic
// motor's fingertips push with a force that droops linearly with speed, from the stall force at
// rest to zero at the no-load speed v_f(u): per unit mass p (v_f(u) - v).
//   DAC:     u_dac as below; driver: u_s = clip(u_dac(t - transport_delay_s), +-saturation_v),
//            first-order envelope lag  T_l u_d' = u_s - u_d   (lag_time_constant_s, 0.1 ms)
//   motor:   v_f(u_d) = 0 for -dz_b <= u_d <= dz_f (the fingertip preload: below these
//            voltages the fingers do not slide on the belt and hold the stage), else piecewise
//            linear through (dz_f, 0), the speed-map knots and (-dz_b, 0), extrapolated linearly
//   motion:  x' = v,  v' = p (v_f(u_d) - v) - F_r      (p = motor.pole_per_s [1/s])
//   rail:    Karnopp stick-slip: sliding F_r = sgn(v) g(v), g(v) = Fc + (Fs - Fc) exp(-(v/vs)^2);
//            stuck (v = 0) while |p v_f(u_d)| <= Fs, then it breaks away in the sign of v_f;
//            a sliding stage that reaches v = 0 sticks again unless |p v_f| > Fs.
//   Steady sliding: p (v_f(u) - v) = g(v), so the speed map is calibrated as
//   v_f(u_i) = v_i + g(v_i) / p through the paper's ten pulse points (u_i, v_i).
//   Start and stop differ: from rest the stage starts when |v_f| > Fs / p; sliding, it stops
//   when v_f falls to ~Fc / p (start/stop hysteresis of the rail's static friction).
//   Optional drive hysteresis (drive.hysteresis, DriveHysteresis below): the lag's input is the
//   piezoceramic's effective voltage u_h = H[u_s] (asymmetric play operators with
//   rate-dependent weights, per control sample) instead of u_s; preset
//   "drive-hysteresis-static" (without the creep below).
//   Optional creep (drive.creep, DriveCreep below): shares of that voltage and of the
//   hysteresis' lag relax with a time constant (the ceramic's domain relaxation); the default
//   stage, preset "drive-hysteresis", has both; preset "velocity-source" neither.
//
// ACTUATOR DELAY (model "actuator-delay", the preset of libsysid <= 0.x; kept because on it the
// paper's feedforward does NOT help: its multi-ms transport delay makes the stage respond later
// than the rough model, so no viscous delay tau > 0 fits, and its delay + lag eat the phase
// margin of the paper's PI gains). Plant (all forces per unit mass, [m/s^2]):
//   DAC:     u_dac = 16-bit quantisation of the command over +-dac_range_v, held for one sample
//   driver:  u_d(t) = u_dac(t - transport_delay_s), clipped to +-saturation_v,
//            dead zone: u_z = u_d - dz sgn(u_d) for |u_d| > dz, else 0,
//            static characteristic u_m = M(u_z) (piecewise linear through drive_map knots),
//            first-order lag  T w' = u_m - w
//   motion:  x' = v,  v' = a3 w - F,   F = s0 z + s1 z' + s2(v) v            (LuGre friction)
//            z' = v - s0 |v| z / g(v),  g(v) = Fc + (Fs - Fc) exp(-(v / vs)^2)
//            with (Fc, Fs, vs, s2) taken from the forward branch for v > 0, the backward for v < 0.
//   In steady sliding the friction is g(v) + s2 v, so a constant voltage u gives
//   a3 M(|u| - dz) = g(v) + s2 |v|: the rough model's a1 ~ s2 and a2 ~ Fc + a3 dz.
//
// Rig (both): the encoder reads round((x + n) / q) q with n ~ N(0, position_noise_m^2) (seeded),
// q = encoder_resolution_m; travel limits are hard end stops; exceeding max_velocity_mps is
// reported (not clipped).
//
// Determinism: the noise comes from std::mt19937_64 (whose output the standard fixes) through an
// Irwin-Hall transform (sum of 12 uniforms - 6: only additions, so identical on every IEEE-754
// machine); no std::*_distribution is used.
#ifndef SYSID_STAGE_HPP_
#define SYSID_STAGE_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "sysid/io.hpp"
#include "sysid/serialize.hpp"
#include "sysid/signal.hpp"

namespace sysid {

/// The driver both plants share (file section "drive"): its input clip, transport delay and
/// envelope lag.
struct DriverSettings {
  double saturation_v = 10.0;           ///< [V] driver input clip, > 0 and above the dead zones
  double transport_delay_s = 0.0;       ///< [s] in [0, 1], any multiple of the sample time
  double lag_time_constant_s = 0.0003;  ///< [s] T > 0, first-order lag of the drive
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(saturation_v));
    a->Visit(SYSID_NVP(transport_delay_s));
    a->Visit(SYSID_NVP(lag_time_constant_s));
  }
  /// Throws OptionsError "StageParameters::FIELD = VALUE. Violated constraint: RULE".
  void Validate() const;
};

/// The rig both plants share (file section "rig"): rates, DAC, encoder, end stops.
struct RigSettings {
  /// [Hz] control rate: the DAC hold, the encoder's reads and the controller's loop, > 0
  /// (file: rig.control_rate_hz, or rig.sample_rate_hz, which sets both rates)
  double sample_rate_hz = 1000;
  /// [Hz] the rate of the recordings the procedures return (pulse test, tracking sets,
  /// waveforms, triangle): every n-th control sample, n = sample_rate_hz / record_rate_hz an
  /// integer (plain sampling, as a real-time logger's downsampling keeps every n-th value: no
  /// anti-alias filter, whose delay would shift the delay fact). 0: the control rate.
  /// File: rig.record_rate_hz.
  double record_rate_hz = 0;
  int dac_bits = 16;                   ///< DAC resolution over +-dac_range_v, 1..32
  double dac_range_v = 10.0;           ///< [V] DAC output range +-dac_range_v, > 0
  double encoder_resolution_m = 1e-7;  ///< [m] q in [1e-15, the travel]
  double position_noise_m = 3e-8;      ///< [m] standard deviation of the reading noise, >= 0
  double travel_min_m = -0.0575;       ///< [m] lower end stop
  double travel_max_m = 0.0575;        ///< [m] upper end stop, > travel_min_m
  double max_velocity_mps = 0.23;      ///< [m/s] rated speed, > 0; exceeding it is reported
  double initial_position_m = 0.0;     ///< [m] position at t = 0, inside the travel
  /// The fields, in file order (sysid/serialize.hpp; the file writes the two rates as one
  /// sample_rate_hz when they are equal).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(sample_rate_hz));
    a->Visit(SYSID_NVP(record_rate_hz));
    a->Visit(SYSID_NVP(dac_bits));
    a->Visit(SYSID_NVP(dac_range_v));
    a->Visit(SYSID_NVP(encoder_resolution_m));
    a->Visit(SYSID_NVP(position_noise_m));
    a->Visit(SYSID_NVP(travel_min_m));
    a->Visit(SYSID_NVP(travel_max_m));
    a->Visit(SYSID_NVP(max_velocity_mps));
    a->Visit(SYSID_NVP(initial_position_m));
  }
  /// Throws OptionsError "StageParameters::FIELD = VALUE. Violated constraint: RULE".
  void Validate() const;
  /// [s] 1 / sample_rate_hz, the control period.
  double sample_time_s() const { return 1.0 / sample_rate_hz; }
  /// [Hz] the recordings' rate: record_rate_hz, or sample_rate_hz when that is 0.
  double RecordRateHz() const { return record_rate_hz > 0 ? record_rate_hz : sample_rate_hz; }
  /// Control samples per recorded sample, sample_rate_hz / RecordRateHz() (>= 1).
  long RecordStride() const;
};

/// The integrator both plants share (SUNDIALS CVODE, BDF; file section "integrator").
struct IntegratorSettings {
  double relative_tolerance = 1e-7;     ///< CVODE rtol, in (0, 1e-2]
  double position_tolerance_m = 1e-10;  ///< [m] CVODE atol of x and z (v, w scaled by 1/Ts), > 0
  /// The integrator's work budget per control sample: CVODE steps plus stick-slip and end-stop
  /// switches. A sample that needs more ends the run with NumericalError naming the time and
  /// the state (a stage that cannot be integrated fails, it never hangs). In [10, 1e8].
  /// Written to the file only when not the default.
  int max_steps_per_sample = kDefaultMaxStepsPerSample;
  static constexpr int kDefaultMaxStepsPerSample = 20000;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(relative_tolerance));
    a->Visit(SYSID_NVP(position_tolerance_m));
    a->Visit(SYSID_NVP(max_steps_per_sample));
  }
  /// Throws OptionsError "StageParameters::FIELD = VALUE. Violated constraint: RULE".
  void Validate() const;
};

/// One direction's friction (LuGre steady state g(v) + s2 v).
struct FrictionBranch {
  double coulomb_mps2 = 0;           ///< [m/s^2] Fc, sliding friction level
  double static_mps2 = 0;            ///< [m/s^2] Fs >= Fc, breakaway level at v -> 0
  double stribeck_velocity_mps = 0;  ///< [m/s] vs > 0, width of the Stribeck dip
  double viscous_per_s = 0;          ///< [1/s] s2 >= 0, viscous coefficient
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(coulomb_mps2));
    a->Visit(SYSID_NVP(static_mps2));
    a->Visit(SYSID_NVP(stribeck_velocity_mps));
    a->Visit(SYSID_NVP(viscous_per_s));
  }
};

/// Which plant equations the virtual stage integrates (see the top of this file).
enum class StageModel {
  kVelocitySource,  ///< "velocity-source": ultrasonic motor as a drooping velocity source
  kActuatorDelay,   ///< "actuator-delay": force actuator behind a transport delay, LuGre rail
};
std::string ToString(StageModel model);
/// "velocity-source" or "actuator-delay"; throws OptionsError naming both otherwise.
StageModel ParseStageModel(const std::string& text);

/// Rail friction of the velocity-source model (Karnopp stick-slip), per unit mass, both
/// directions alike.
struct RailFriction {
  double coulomb_mps2 = 0.6;            ///< [m/s^2] Fc > 0, sliding level
  double static_mps2 = 3.0;             ///< [m/s^2] Fs >= Fc, breakaway level
  double stribeck_velocity_mps = 0.01;  ///< [m/s] vs > 0, width of the Stribeck dip
  /// [s] T_m >= 0, frictional memory (Hess & Soom's frictional lag): while sliding, the
  /// friction is g(s) of a lagged slip speed s, T_m s' = |v| - s (s = 0 at rest); 0 = no
  /// memory, g(|v|). Steady sliding has s = |v|, so the steady law does not depend on T_m.
  double memory_time_s = 0.02;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(coulomb_mps2));
    a->Visit(SYSID_NVP(static_mps2));
    a->Visit(SYSID_NVP(stribeck_velocity_mps));
    a->Visit(SYSID_NVP(memory_time_s));
  }
  /// [m/s^2] g(|v|) = Fc + (Fs - Fc) exp(-(v / vs)^2), the sliding friction magnitude.
  double Sliding(double speed_mps) const;
  /// [m/s^2 / (m/s)] g'(s), the slope of Sliding at speed s >= 0.
  double SlidingSlope(double speed_mps) const;
};

/// The velocity-source motor: force per unit mass p (v_f(u_d) - v).
struct MotorParameters {
  double pole_per_s = 300;             ///< [1/s] p > 0, stall force / no-load speed per volt
  double dead_zone_forward_v = 1.15;   ///< [V] dz_f >= 0: v_f = 0 for 0 <= u_d <= dz_f
  double dead_zone_backward_v = 1.65;  ///< [V] dz_b >= 0: v_f = 0 for -dz_b <= u_d <= 0
  std::vector<double> speed_map_in_v;  ///< [V] knots, increasing, all outside [-dz_b, dz_f]
  std::vector<double> speed_map_out_mps;  ///< [m/s] v_f at the knots (sign of the knot)
  /// [m/s^2] L >= 0: the fingertips' thrust saturates at the contact's friction limit,
  /// T(y) = L tanh(y / L) of the linear droop y = p (v_f - v); 0: no limit (T(y) = y).
  double thrust_limit_mps2 = 0;
  /// The fields, in file order (sysid/serialize.hpp; the file leaves out a thrust limit of 0).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(pole_per_s));
    a->Visit(SYSID_NVP(dead_zone_forward_v));
    a->Visit(SYSID_NVP(dead_zone_backward_v));
    a->Visit(SYSID_NVP(speed_map_in_v));
    a->Visit(SYSID_NVP(speed_map_out_mps));
    a->Visit(SYSID_NVP(thrust_limit_mps2));
  }
  /// T(y) and its slope dT/dy.
  double Thrust(double y) const;
  double ThrustSlope(double y) const;
  /// The droop y at which T(y) = f (|f| < L when limited).
  double DroopForThrust(double f) const;
};

/// The piezoceramic fingers' rate-dependent, asymmetric hysteresis (velocity source only;
/// docs/virtual_stage.md, "Drive hysteresis"). It acts on the driver's clipped command u_k (one
/// value per control sample, held: the DAC's ZOH) before the envelope lag, which is the
/// fingers' resonant build-up and follows the ceramic's strain:
///   F_i,k = PlayStep(u_k - alpha r_i, r_i, F_i,k-1)   (asymmetric play: the band
///           [u - r_i (1 + alpha), u + r_i (1 - alpha)]; F_i = 0 at t = 0)
///   rate:  q_k = q_k-1 + b ((u_k - u_k-1) / Ts - q_k-1),  b = 1 - exp(-Ts / tau),  rho_k = |q_k|
///   u_h,k = u_k - sum_i c_i(rho_k) (u_k - F_i,k),  c_i(rho) = w_i + s_i min(rho, rho_sat)
/// with rho_sat = (1 - sum w) / sum s, so that sum c_i <= 1 (u_h non-decreasing in u_k). The
/// lag then gives T_l u_d' = u_h - u_d, and v_f(u_d) as without hysteresis. A held voltage
/// reached by a rise of at least 2 r_max (every pulse of the paper's table from 0 V) settles
/// at u_h = u - sum w_i r_i (1 + alpha); by a fall, u + sum w_i r_i (1 - alpha).
struct DriveHysteresis {
  std::vector<double> thresholds_v;  ///< r_i [V], 0 < r_1 < ... < r_n; empty: no hysteresis
  std::vector<double> weights;       ///< w_i [1] >= 0 at rest rate, sum w_i < 1
  std::vector<double> rate_weights_s_per_v;  ///< s_i [s/V] >= 0: weight per V/s of input rate
  double rate_time_constant_s = 0.01;  ///< [s] tau >= 0: the rate's relaxation (0: last step)
  double asymmetry = 0;  ///< alpha [1] in (-1, 1): rising bands (1 + alpha) r, falling (1 - alpha) r
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(thresholds_v));
    a->Visit(SYSID_NVP(weights));
    a->Visit(SYSID_NVP(rate_weights_s_per_v));
    a->Visit(SYSID_NVP(rate_time_constant_s));
    a->Visit(SYSID_NVP(asymmetry));
  }
  bool enabled() const { return !thresholds_v.empty(); }
  /// [V] sum w_i r_i (1 + alpha) (rising) or (1 - alpha) (falling): the held lag.
  double HeldLag(bool rising) const;
  /// [V/s] rho_sat, the rate above which the weights stop growing (infinity without s_i).
  double SaturationRate() const;
};

/// The piezoceramic's creep (domain relaxation; velocity source only; docs/virtual_stage.md,
/// "Creep: the loop's rate dependence"): one first-order relaxation with time constant T_c
/// acting on two shares, after the hysteresis. With s the clipped command, u_pi the
/// hysteresis' output (s without it) and D = s - u_pi the play operators' lag:
///   T_c z' = q - z,   q = k_v u_pi + k_l D,   u_h = (1 - k_v) u_pi + z     (z = 0 at t = 0)
/// k_v (voltage_share): that share of the voltage reaches the fingers late (strain creep after
///   a step; a pure lag of the voltage);
/// k_l (loop_share): that share of the play operators' lag creeps out while the voltage is
///   held (the pinned domain walls relax), so a slow sweep traces a loop (1 - k_l) as wide as
///   a fast one: the loop widens with the rate.
/// Held, z = q and u_h = u_pi + k_l D = s - (1 - k_l) D: the held lag is (1 - k_l) times the
/// hysteresis' (VelocitySourcePlant::HeldDriveLag). s and u_pi are held per control sample, so z
/// has the closed form q + (z_a - q) e^(-(t - t_a) / T_c) over each held piece: the envelope
/// lag sees that continuous u_h (no integrator state, z advanced exactly from piece to piece).
struct DriveCreep {
  double voltage_share = 0;      ///< k_v [1] in [0, 1): the voltage's share that arrives late
  double loop_share = 0;         ///< k_l [1] in [0, 1): the hysteresis lag's share that relaxes
  double time_constant_s = 0.1;  ///< T_c [s] in (0, 100]: the relaxation's time constant
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(voltage_share));
    a->Visit(SYSID_NVP(loop_share));
    a->Visit(SYSID_NVP(time_constant_s));
  }
  bool enabled() const { return voltage_share > 0 || loop_share > 0; }
};

/// The velocity-source plant's own parameters (model "velocity-source"; the top of this file).
/// The driver, rig and integrator are StageParameters' (shared with the actuator delay).
struct VelocitySourcePlant {
  MotorParameters motor;
  RailFriction rail;
  DriveHysteresis hysteresis;  ///< before the lag (file: drive.hysteresis, when enabled)
  DriveCreep creep;            ///< after the hysteresis (file: drive.creep, when enabled)
  /// The fields (sysid/serialize.hpp); the file writes motor and rail as sections and the
  /// hysteresis and creep inside "drive", each only when enabled.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(motor));
    a->Visit(SYSID_NVP(rail));
    a->Visit(SYSID_NVP(hysteresis));
    a->Visit(SYSID_NVP(creep));
  }

  /// Throws OptionsError "StageParameters::FIELD = VALUE. Violated constraint: RULE" (FIELD as
  /// the stage file's path: motor.pole_per_s, hysteresis.weights[2], ...).
  void Validate() const;
  /// The rules over the shared driver: the dead zones below its clip saturation_v (OptionsError
  /// as Validate).
  void ValidateWithDriver(const DriverSettings& driver) const;
  double NoLoadSpeed(double u_v) const;  ///< [m/s] v_f(u) of the motor (0 in the dead zone)
  /// [m/s] steady sliding velocity under a held voltage u_v [V] (clipped by the DAC and the
  /// driver) reached from 0 V: T(p (|v_f| - s)) = g(s) by bisection, 0 when |T(p v_f)| <= Fs;
  /// v_f read at u -+ HeldDriveLag.
  double SteadyVelocity(double u_v) const;
  /// [V] the drive's lag of a voltage held after a rise (rising) or a fall of at least 2 r_max
  /// from 0 V: the hysteresis' HeldLag, of which the creep's loop share has relaxed,
  /// (1 - k_l) HeldLag (0 without hysteresis).
  double HeldDriveLag(bool rising) const;
  /// Sets the speed map's knots so that a held voltage u_i settles at v_i for each
  /// (u_i [V], v_i [m/s]) (steady law T(p (v_f - v)) = g(|v|), so
  /// v_f(u_i) = v_i + sgn(v_i) T^-1(g(|v_i|)) / p), for the current pole, thrust limit and rail.
  /// With drive hysteresis the knot sits at the held u_h: u_i reached from 0 V by a rise
  /// (u_i > 0) or a fall (u_i < 0) of at least 2 r_max, u_i -+ HeldDriveLag.
  /// The presets call it with the paper's pulse table.
  void SetSpeedMapThrough(const std::vector<std::pair<double, double>>& steady_points);
};

/// The actuator-delay plant's own parameters (model "actuator-delay"; the top of this file).
struct ActuatorDelayPlant {
  double gain_mps2_per_v = 6.0;         ///< [m/(s^2 V)] a3, force per volt per unit mass
  double dead_zone_v = 0.15;            ///< [V] dz >= 0, below the driver's saturation_v
  std::vector<double> drive_map_in_v;   ///< [V] knots of M (after the dead zone), increasing
  std::vector<double> drive_map_out_v;  ///< [V] M at the knots, non-decreasing, M(0) = 0
  double bristle_stiffness_per_s2 = 1e6;  ///< [1/s^2] s0 > 0
  double bristle_damping_per_s = 1000;    ///< [1/s] s1 >= 0
  FrictionBranch forward;                 ///< branch for v > 0
  FrictionBranch backward;                ///< branch for v < 0 (all values positive)
  /// The fields (sysid/serialize.hpp); the file writes the force actuator's (gain, dead zone,
  /// map as map_in_v / map_out_v) in "drive" and the rest in "friction".
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(gain_mps2_per_v));
    a->Visit(SYSID_NVP(dead_zone_v));
    a->Visit(SYSID_NVP(drive_map_in_v));
    a->Visit(SYSID_NVP(drive_map_out_v));
    a->Visit(SYSID_NVP(bristle_stiffness_per_s2));
    a->Visit(SYSID_NVP(bristle_damping_per_s));
    a->Visit(SYSID_NVP(forward));
    a->Visit(SYSID_NVP(backward));
  }

  /// As VelocitySourcePlant::Validate.
  void Validate() const;
  /// The dead zone below the driver's clip saturation_v (OptionsError naming saturation_v).
  void ValidateWithDriver(const DriverSettings& driver) const;
  /// The static drive characteristic M(u) [V] (linear extrapolation beyond the end knots).
  double DriveMap(double u_v) const;
  /// [m/s] steady sliding velocity under a held voltage u_v [V] (clipped by the DAC and the
  /// driver): a3 M(|u| - dz) = g(v) + s2 |v| by bisection, 0 when a3 M <= Fs.
  double SteadyVelocity(double u_v) const;
};

/// Every parameter of the virtual stage, SI units: one plant (the velocity source or the
/// actuator delay, each with its own fields and Validate) over the settings both share: the
/// driver's clip, delay and lag, the rig (DAC, encoder, end stops, rates) and the integrator.
/// The JSON file carries the unit in each key.
struct StageParameters {
  std::string name = "virtual PLS8/HR-8 (velocity source)";
  /// The plant's own parameters; which one is held is the stage's model().
  std::variant<VelocitySourcePlant, ActuatorDelayPlant> plant;
  DriverSettings driver;
  RigSettings rig;
  IntegratorSettings integrator;

  StageModel model() const;  ///< which plant `plant` holds
  /// The plant's parameters; OptionsError naming the stage's model when it holds the other.
  VelocitySourcePlant& velocity_source();
  const VelocitySourcePlant& velocity_source() const;
  ActuatorDelayPlant& actuator_delay();
  const ActuatorDelayPlant& actuator_delay() const;

  /// Throws OptionsError "StageParameters::FIELD = VALUE. Violated constraint: RULE".
  /// Checks the driver, the rig and the integrator, then the plant (its own Validate) and the
  /// plant over the driver (ValidateWithDriver: its dead zones below the clip).
  void Validate() const;
  /// The calibrated virtual stage (identical to datasets/virtual/stage.json): the preset
  /// "drive-hysteresis", VelocitySource() plus the ceramic's asymmetric play operators whose
  /// lag partly creeps out (docs/virtual_stage.md, "F8 with F5").
  static StageParameters Default();
  /// The velocity-source stage without drive hysteresis:
  /// a 10 kHz control loop recorded at 1 kHz with a 0.1 ms driver lag (docs/virtual_stage.md,
  /// "Loop rate"). The member defaults are the 1 kHz loop with a 0.3 ms lag:
  /// Preset("virtual-1khz").
  static StageParameters VelocitySource();
  /// The stage of libsysid before the velocity-source model (transport delay + lag + LuGre):
  /// the stage on which the paper's feedforward does not help (docs/virtual_stage.md).
  static StageParameters ActuatorDelay();
  /// A named preset: "virtual" or "drive-hysteresis" (= Default()), "velocity-source"
  /// (= VelocitySource()), "virtual-1khz"
  /// (VelocitySource() at the member defaults' 1 kHz loop and 0.3 ms lag), "actuator-delay",
  /// "drive-hysteresis-static" (VelocitySource() plus the ceramic's asymmetric hysteresis with
  /// wider operators and no creep).
  /// Throws OptionsError listing the names otherwise.
  static StageParameters Preset(const std::string& name);
  /// True when `name` is one of Preset's names.
  static bool IsPresetName(const std::string& name);
  /// Preset's names, "virtual" first.
  static const std::vector<std::string>& PresetNames();
  /// PresetNames() for messages: "virtual (= drive-hysteresis), velocity-source, …".
  static std::string PresetNameList();
  /// [s] rig.sample_time_s(), the control period.
  double sample_time_s() const { return rig.sample_time_s(); }
  /// [Hz] rig.RecordRateHz(), the recordings' rate.
  double RecordRateHz() const { return rig.RecordRateHz(); }
  /// rig.RecordStride(), control samples per recorded sample.
  long RecordStride() const { return rig.RecordStride(); }
  /// [m/s] steady sliding velocity under a constant voltage reached from rest (ignoring noise
  /// and limits): u_v clipped by the DAC's range and the driver, then the plant's
  /// SteadyVelocity.
  double SteadyVelocity(double u_v) const;
  /// Velocity source: sets the creep `c` and moves the dead zones and the speed map's knots by
  /// the change of HeldDriveLag, as SetDriveHysteresis does (the voltage share does not move
  /// them: a held voltage has relaxed). Throws OptionsError (Validate) as SetDriveHysteresis.
  void SetDriveCreep(const DriveCreep& c);
  /// Velocity source: sets drive hysteresis `h` and moves the dead zones and the speed map's
  /// knots by the change of the held lags (forward side by HeldDriveLag(true), backward by
  /// HeldDriveLag(false)), so that a voltage held after a rise from 0 V (forward) or a fall
  /// (backward) gives the same steady velocity as before: the pulse table stays. Throws
  /// OptionsError (Validate) when the moved dead zones or knots are not valid.
  void SetDriveHysteresis(const DriveHysteresis& h);
  /// The paper's pulse table: (amplitude [V], steady velocity [m/s]), ten pulses.
  static std::vector<std::pair<double, double>> PaperPulseTable();

 private:
  /// Moves the dead zones and knots by the change of HeldDriveLag from (forward, backward).
  void MoveForHeldLag(double forward_before, double backward_before);
};

/// Parses a stage file's JSON text; `source` names it in errors ("FILE:LINE:COLUMN: ...").
/// Unknown keys are errors. Throws InputError.
StageParameters ParseStageParameters(std::string_view json_text, const std::string& source);
StageParameters ReadStageParameters(const std::string& path);
/// JSON text with nested objects "drive", "friction", "rig", "integrator"; units in key names.
std::string StageParametersToJson(const StageParameters& parameters);
void WriteStageParameters(const std::string& path, const StageParameters& parameters);
/// A preset name (StageParameters::IsPresetName: virtual, velocity-source, virtual-1khz,
/// actuator-delay, drive-hysteresis, drive-hysteresis-static) or the path of a stage file.
StageParameters LoadStage(const std::string& preset_or_path);

/// The true (unmeasured) state of the plant.
struct StageState {
  double x_m = 0;    ///< [m] position
  double v_mps = 0;  ///< [m/s] velocity
  double z_m = 0;    ///< [m] LuGre bristle deflection (actuator delay; 0 for velocity source)
  double w_v = 0;    ///< [V] driver lag state (actuator delay: drive force / a3; velocity
                     ///  source: the lagged drive voltage u_d, after the drive's hysteresis)
  bool stuck = false;  ///< velocity source: held by the rail's static friction (v = 0)
  /// [m/s] velocity source: the rail's lagged slip speed s (rail.memory_time_s > 0), else |v|
  double slip_memory_mps = 0;
};

/// Limits reached so far, and integrator work.
struct StageStatus {
  bool travel_limit_hit = false;         ///< an end stop was reached
  double first_travel_hit_s = -1;        ///< [s] when, or -1
  bool velocity_limit_exceeded = false;  ///< |v| > max_velocity_mps at some sample
  double first_velocity_exceed_s = -1;   ///< [s] when, or -1
  long steps = 0;                        ///< CVODE steps
  long reinitialisations = 0;            ///< CVODE restarts (DAC/delay edges, end stops)
  /// "none", or e.g. "travel limit hit at t = 1.234 s; velocity limit exceeded at t = ...".
  std::string Describe() const;
};

/// The plant, steppable one sample at a time. At time t_k the encoder has read
/// measured_position_m(); Step(u) holds the DAC at u for one sample period and returns the
/// reading at t_{k+1}. Throws NumericalError (with the CVODE flag and time) if integration fails.
class VirtualStage {
 public:
  explicit VirtualStage(const StageParameters& parameters, std::uint64_t seed = 1);
  ~VirtualStage();
  VirtualStage(VirtualStage&&) noexcept;
  VirtualStage& operator=(VirtualStage&&) noexcept;
  VirtualStage(const VirtualStage&) = delete;
  VirtualStage& operator=(const VirtualStage&) = delete;

  /// Applies the command `u_command_v` [V] for one sample; returns the new reading [m].
  double Step(double u_command_v);
  /// [m] encoder reading at the current sample time.
  double measured_position_m() const;
  double time_s() const;      ///< [s] current sample time k / sample_rate_hz
  long sample_index() const;  ///< k
  StageState state() const;
  StageStatus status() const;
  const StageParameters& parameters() const;
  /// [V] what the DAC really outputs for a command (16-bit quantised, clipped).
  double DacOutput(double u_command_v) const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// An open-loop run: row k is (t_k, u_k, reading at t_k) with u_k applied on [t_k, t_{k+1}).
struct StageRun {
  Eigen::VectorXd t_s;         ///< [s]
  Eigen::VectorXd u_v;         ///< [V] command
  Eigen::VectorXd x_m;         ///< [m] encoder reading
  Eigen::VectorXd x_true_m;    ///< [m] true position
  Eigen::VectorXd v_true_mps;  ///< [m/s] true velocity
  StageStatus status;
};

/// Drives a fresh stage with the command sequence `u_v` (one value per sample).
StageRun RunOpenLoop(const StageParameters& parameters, const Eigen::VectorXd& u_v,
                     std::uint64_t seed = 1);

// ---- Procedures ------------------------------------------------------------------------

/// The paper's pulse test: each amplitude for on_s, then 0 for rest_s; lead_s of 0 V first.
struct PulseProcedure {
  /// [V] alternating directions so the stage stays inside its travel (the paper's amplitudes).
  std::vector<double> amplitudes_v{-1.8, 1.3, -2.0, 1.5, -2.1, 1.6, -2.3, 1.7, -2.5, 2.0};
  double on_s = 0.4;      ///< [s] pulse length, > 0
  double rest_s = 0.3;    ///< [s] 0 V after each pulse, >= 0
  double lead_s = 0.1;    ///< [s] 0 V before the first pulse, >= 0
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(amplitudes_v));
    a->Visit(SYSID_NVP(on_s));
    a->Visit(SYSID_NVP(rest_s));
    a->Visit(SYSID_NVP(lead_s));
  }
  void Validate() const;  ///< throws OptionsError naming the field and the rule
  /// The command, one value per sample at `sample_rate_hz`.
  Eigen::VectorXd Voltage(double sample_rate_hz) const;
  /// [s] start time of pulse i.
  double PulseStart(std::size_t i) const;
};
/// The procedure as JSON ({"amplitudes_v", "on_s", "rest_s", "lead_s"}) and back: every key
/// optional, validated, InputError "SOURCE:LINE:COL: NAME: expected ..., found ..." otherwise.
std::string ToJson(const PulseProcedure& procedure, int indent = 2);
PulseProcedure PulseProcedureFromJson(std::string_view text, const std::string& source_name);

/// A velocity reference v(t) = sum_i (s_i sin w_i t + c_i cos w_i t) [m/s]; the position
/// reference is its integral from x(0) = 0: x(t) = sum_i (s_i (1 - cos w_i t) + c_i sin w_i t)/w_i.
struct VelocityWaveform {
  struct Term {
    double omega_rad_s = 1;  ///< [rad/s] > 0
    double sin_mps = 0;      ///< [m/s] s_i
    double cos_mps = 0;      ///< [m/s] c_i
  };
  std::string name;
  std::vector<Term> terms;
  double period_s = 0;                    ///< [s] common period (one "cycle")
  double Velocity(double t_s) const;      ///< [m/s]
  double Position(double t_s) const;      ///< [m]
  double Acceleration(double t_s) const;  ///< [m/s^2]
  double PeakVelocity() const;            ///< [m/s] sum |s_i| + |c_i| (an upper bound)
  /// v = amplitude_m omega sin(omega t): x = amplitude_m (1 - cos omega t), one grid pair.
  static VelocityWaveform Sine(double amplitude_m, double omega_rad_s);
};

/// The paper's six test waveforms: four sinusoids v = 0.016625 sin 1.9t, 0.0525 sin 6t,
/// 0.030875 sin 1.9t, 0.0975 sin 6t; triangle-like 0.8/pi^2 [cos 2 pi t + cos(6 pi t)/9];
/// square-like 0.248/pi [cos 6t - cos(18t)/3 + cos(30t)/5] (all m/s).
std::vector<VelocityWaveform> PaperTestWaveforms();
/// Training grid: position amplitudes {5, 10, 20} mm x omega {1.5, 3, 6, 10} rad/s, kept when
/// the peak velocity A omega <= 0.16 m/s (11 pairs; 70 % of the rated speed, and 2A inside the
/// travel). Test grid: the paper's four sinusoids (amplitudes 8.75 and 16.25 mm at 1.9 and
/// 6 rad/s), a different grid.
std::vector<VelocityWaveform> TrainingGrid();
std::vector<VelocityWaveform> TestGrid();

/// Tracking with a proportional position controller u = kp (x_ref - x_measured).
struct TrackingProcedure {
  double kp_v_per_m = 1000;      ///< [V/m] > 0, the data-collection P gain
  int lead_cycles = 1;           ///< reference cycles run before the kept ones, >= 0
  int kept_cycles = 1;           ///< cycles kept per waveform, >= 1
  double tail_s = 0.05;          ///< [s] run past the kept cycles so the derivative filter has
                                 ///  samples on both sides of the cut, >= 0
  DerivativeOptions derivative;  ///< how v and a come from x
  void Validate(const StageParameters& stage) const;
};

/// One waveform tracked: columns t, u, x, v, a (and x_ref) of the kept cycles, t from 0.
Recording TrackWaveform(const StageParameters& stage, const VelocityWaveform& waveform,
                        const TrackingProcedure& procedure, std::uint64_t seed);

/// Runs every waveform of `grid` (each from rest at x = 0), cuts the kept cycles at the
/// reference's cycle boundaries (x_ref = 0 and v_ref equal on both sides: no jumps) and
/// concatenates them in a random order fixed by `seed`. Columns t, u, x, v, a.
Recording RunTrackingSet(const StageParameters& stage, const std::vector<VelocityWaveform>& grid,
                         const TrackingProcedure& procedure, std::uint64_t seed,
                         const std::string& set_name);

/// Runs the pulse test; columns t, u, x, v, a.
Recording RunPulseTest(const StageParameters& stage, const PulseProcedure& procedure,
                       std::uint64_t seed, const DerivativeOptions& derivative = {});

/// The paper's section-3/4 voltage-velocity check: an open-loop triangle voltage of period
/// period_s rising from 0 to peak_forward_v, back through 0 to -peak_backward_v and back to 0
/// (four straight quarters), repeated `cycles` times. Shows the stage's asymmetric
/// voltage-velocity loop (the paper's Fig. 7: 6 s, +1.5 V / -2.1 V).
struct TriangleProcedure {
  double period_s = 6.0;         ///< [s] > 0
  double peak_forward_v = 1.5;   ///< [V] >= 0
  double peak_backward_v = 2.1;  ///< [V] >= 0 (magnitude of the negative peak)
  int cycles = 1;                ///< >= 1
  void Validate() const;
  Eigen::VectorXd Voltage(double sample_rate_hz) const;  ///< one value per sample
};
/// Runs the triangle test; columns t, u, x, v, a.
Recording RunTriangleTest(const StageParameters& stage, const TriangleProcedure& procedure,
                          std::uint64_t seed, const DerivativeOptions& derivative = {});

/// The excitation alone (for a real rig): columns t, u.
Recording PulseExcitation(const PulseProcedure& procedure, double sample_rate_hz);
/// The references alone: waveforms back to back, columns t, waveform (index), x_ref, v_ref, a_ref.
Recording ReferenceSignals(const std::vector<VelocityWaveform>& waveforms,
                           const TrackingProcedure& procedure, double sample_rate_hz);

/// A sub-seed for stream `index` of a run seeded with `seed` (SplitMix64), so every waveform
/// has its own noise stream and reordering the grid does not change the others.
std::uint64_t DeriveSeed(std::uint64_t seed, std::uint64_t index);

}  // namespace sysid

#endif  // SYSID_STAGE_HPP_
