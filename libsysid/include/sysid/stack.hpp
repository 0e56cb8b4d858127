// The virtual piezo stack (docs/piezo_stack.md): a simulated piezoelectric stack actuator on
// which each hysteresis model's inverse can be tried as feedforward to a PI position loop
// (`sysid track --plant piezo-stack`). The plant is the cascade of Croft, Shed & Devasia
// (ASME J. Dyn. Syst. Meas. Control 123(1), 2001): hysteresis, then creep, then vibration.
//
//   DAC:        u_k = the command clipped to [voltage_min_v, voltage_max_v] and quantised to
//               dac_bits over that range, held for one control period Ts (zero-order hold)
//   hysteresis: rate-dependent Prandtl–Ishlinskii (sysid/hysteresis.hpp, form rdpi; Ang, Khosla
//               & Riviere, IEEE/ASME T-Mech 12(2) 2007) on the DAC samples:
//                 y_k = (p0 + q0 rho_k) u_k + sum_i (w_i + q_i rho_k) F_ri[u]_k,
//                 rho_k = |u_{k-1} - u_{k-2}| / Ts  [V/s]   (0 for k < 2),
//               the operators at rest at 0 V. Exact on the samples: u is piecewise constant, and
//               a play operator's output depends only on the input's successive values, so y
//               is piecewise constant too — there is nothing between samples to integrate.
//   creep:      m Kelvin–Voigt elements driven by y (Croft et al. 2001; the creep rate ~1 % of the
//               last move per decade of time, Jung & Gweon, Rev. Sci. Instrum. 71(4) 2000):
//                 tau_j c_j' = kappa_j y - c_j,      so a step of y gives
//                 c_j(t) = kappa_j y (1 - exp(-t / tau_j))
//   mechanics:  x'' + 2 zeta w_n x' + w_n^2 x = w_n^2 (y + sum_j c_j),   w_n = 2 pi f_n
//   sensor:     the reading round((x + n) / q) q, n ~ N(0, sensor_noise_m^2) (seeded, the
//               stage's portable generator), q = sensor_resolution_m
// x, x', c_j are integrated by CVODE (Adams; core/cvode_solver), restarted at every sample
// because y jumps there, or (integrator.method "exact") by the ODE's exact zero-order-hold
// discretisation: the ODE is linear and its input y is held over each sample. All states start
// at 0 (the stack at rest at 0 V).
#ifndef SYSID_STACK_HPP_
#define SYSID_STACK_HPP_

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sysid/hysteresis.hpp"
#include "sysid/serialize.hpp"

namespace sysid {

/// The most creep elements and play operators a stack file may hold.
inline constexpr int kMaxCreepElements = 16;

/// The stack's rate-dependent Prandtl–Ishlinskii hysteresis (file section "hysteresis").
struct StackHysteresis {
  double linear_gain_m_per_v = 0;       ///< [m/V] p0 > 0, the slope right after a reversal
  std::vector<double> thresholds_v;     ///< [V] r_i, 0 < r_1 < ... < r_n, n <= kMaxPlayOperators
  std::vector<double> weights_m_per_v;  ///< [m/V] w_i >= 0, one per threshold
  /// [m s/V^2] q_0 .. q_n >= 0 (n + 1 values): how the slopes grow with the input rate; all 0
  /// makes the hysteresis rate-independent (a classical PI).
  std::vector<double> rate_weights_m_s_per_v2;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(linear_gain_m_per_v));
    a->Visit(SYSID_NVP(thresholds_v));
    a->Visit(SYSID_NVP(weights_m_per_v));
    a->Visit(SYSID_NVP(rate_weights_m_s_per_v2));
  }
};

/// The stack's creep: Kelvin–Voigt elements (file section "creep"); both lists equally long
/// (0 .. kMaxCreepElements; empty: no creep).
struct StackCreep {
  std::vector<double> time_constants_s;  ///< [s] tau_j > 0
  std::vector<double> fractions;         ///< [1] kappa_j >= 0, the element's share of a step
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(time_constants_s));
    a->Visit(SYSID_NVP(fractions));
  }
};

/// The stack's second-order mechanics (file section "mechanics").
struct StackMechanics {
  double resonance_hz = 1000;   ///< [Hz] f_n > 0, below the control rate's Nyquist frequency
  double damping_ratio = 0.05;  ///< [1] zeta in [1e-4, 2]
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(resonance_hz));
    a->Visit(SYSID_NVP(damping_ratio));
  }
};

/// The rig around the stack (file section "rig").
struct StackRig {
  double control_rate_hz = 10000;      ///< [Hz] DAC hold, sensor reads and controller, (0, 1e6]
  double voltage_min_v = -20;          ///< [V] amplifier range, lower end
  double voltage_max_v = 120;          ///< [V] amplifier range, upper end, > voltage_min_v
  int dac_bits = 16;                   ///< DAC resolution over the amplifier range, 1..32
  double sensor_resolution_m = 1e-10;  ///< [m] q in [1e-20, 1e-3] (capacitive sensor)
  double sensor_noise_m = 1e-9;        ///< [m] standard deviation of the reading noise, [0, 1e-3]
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(control_rate_hz));
    a->Visit(SYSID_NVP(voltage_min_v));
    a->Visit(SYSID_NVP(voltage_max_v));
    a->Visit(SYSID_NVP(dac_bits));
    a->Visit(SYSID_NVP(sensor_resolution_m));
    a->Visit(SYSID_NVP(sensor_noise_m));
  }
};

/// How the linear ODE is advanced over a sample (file section "integrator").
enum class StackMethod {
  kCvode,  ///< "cvode": CVODE (Adams), restarted at every sample, tolerances below
  /// "exact": the zero-order-hold discretisation s_(k+1) = Phi s_k + Gamma y_k, Phi and Gamma
  /// from one matrix exponential of [[A, B], [0, 0]] Ts (Van Loan): exact for the held input,
  /// to rounding, at one small matrix-vector product per sample
  kExact,
};
std::string ToString(StackMethod method);
/// "cvode" or "exact"; OptionsError (field "integrator.method") otherwise.
StackMethod ParseStackMethod(const std::string& name);

struct StackIntegrator {
  StackMethod method = StackMethod::kCvode;
  double relative_tolerance = 1e-10;  ///< rtol in [1e-14, 1e-2]
  /// [m] atol of x and c_j (x' gets atol w_n), > 0: far below rtol x, because the creep
  /// states are ~1 % of x and their error adds up over the restarts at every sample
  double position_tolerance_m = 1e-20;
  /// The fields, in file order (sysid/serialize.hpp).
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(SYSID_NVP(method));
    a->Visit(SYSID_NVP(relative_tolerance));
    a->Visit(SYSID_NVP(position_tolerance_m));
  }
};

/// Every parameter of the virtual piezo stack, SI units; the file carries the unit in each key.
struct StackParameters {
  std::string name = "virtual piezo stack (30 um at 100 V, 1 kHz)";
  StackHysteresis hysteresis;
  StackCreep creep;
  StackMechanics mechanics;
  StackRig rig;
  StackIntegrator integrator;

  /// Throws OptionsError "StackParameters::SECTION.FIELD = VALUE. Violated constraint: RULE"
  /// (e.g. "hysteresis.thresholds_v[3]"), the field written as its file key.
  void Validate() const;
  /// The bundled stack (datasets/piezo_stack/stack.json; docs/piezo_stack.md says where each
  /// number comes from).
  static StackParameters Default();
  /// [s] 1 / control_rate_hz.
  double sample_time_s() const { return 1.0 / rig.control_rate_hz; }
  /// The hysteresis as a PI model's parameters (form rdpi, no offset, at rest at 0 V, input
  /// range the amplifier's): PrandtlIshlinskiiModel(HysteresisPi()).Simulate is the plant's
  /// hysteresis.
  PiParameters HysteresisPi() const;
  /// [m/V] the steepest slope of the static (rate-0) loading curve, p0 + sum w_i, times the
  /// creep's static gain 1 + sum kappa_j: the loop gain a PI design must stay stable at.
  double MaxStaticGain() const;
};

/// `base` with its hysteresis replaced by an identified Prandtl–Ishlinskii model's (kind pi or
/// rdpi: p0 = the model's a_1, its thresholds and weights, rdpi's rate weights; pi: rate
/// weights 0), the creep, mechanics and rig kept: the model ahead of the stack's mechanics, the
/// plant of `sysid track --plant H.json`. The stack starts at rest at 0 V with the operators
/// at rest; the model's offset c (a sensor offset) and initial state are not the plant's.
/// Throws OptionsError naming the kind for gpi (its input polynomial has no stack form) and
/// naming the parameter when the model's values are not a stack's (e.g. a negative weight).
StackParameters StackWithHysteresis(const StackParameters& base, const PiParameters& model,
                                    const std::string& model_name);

/// "piezo-stack" (and "stack"): the names `--plant` takes for StackParameters::Default().
bool IsStackPresetName(const std::string& name);

/// Parses a stack file's JSON text ({"plant": "piezo-stack", "name", "hysteresis", "creep",
/// "mechanics", "rig", "integrator"}): every key but "plant" optional (left out: Default()'s
/// value), unknown keys are errors, Validate() errors positioned. Throws InputError
/// "SOURCE:LINE:COL: hysteresis.thresholds_v[3]: expected ..., found ...".
StackParameters ParseStackParameters(std::string_view json_text, const std::string& source);
StackParameters ReadStackParameters(const std::string& path);
/// Every key, units in the names.
std::string StackParametersToJson(const StackParameters& parameters);
/// True when the JSON text names "plant": "piezo-stack" at its top (a stack file rather than a
/// stage file); false for anything else, invalid JSON included (its reader reports that).
bool IsStackFileText(std::string_view json_text);
/// A preset name (IsStackPresetName) or the path of a stack file.
StackParameters LoadStack(const std::string& preset_or_path);

/// The true (unmeasured) state.
struct StackState {
  double x_m = 0;               ///< [m] displacement
  double v_mps = 0;             ///< [m/s] its rate
  double hysteresis_m = 0;      ///< [m] y of the last sample
  std::vector<double> creep_m;  ///< [m] c_j
};

/// The plant, one control sample at a time: at t_k the sensor has read measured_position_m();
/// Step(u) holds the DAC at u for Ts and returns the reading at t_{k+1}. Throws NumericalError
/// (CVODE's flag and time) when the integration fails.
class PiezoStack {
 public:
  explicit PiezoStack(const StackParameters& parameters, std::uint64_t seed = 1);
  ~PiezoStack();
  PiezoStack(PiezoStack&&) noexcept;
  PiezoStack& operator=(PiezoStack&&) noexcept;
  PiezoStack(const PiezoStack&) = delete;
  PiezoStack& operator=(const PiezoStack&) = delete;

  double Step(double u_command_v);
  double measured_position_m() const;  ///< [m]
  double time_s() const;               ///< [s] k Ts
  StackState state() const;
  const StackParameters& parameters() const;
  /// [V] what the DAC outputs for a command (clipped, quantised).
  double DacOutput(double u_command_v) const;
  /// Samples whose command the DAC clipped so far.
  long clipped_samples() const;
  /// "none", or "amplifier range clipped N samples (first at t = T s)".
  std::string DescribeLimits() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

/// An open-loop run of a fresh stack: row k is (t_k, u_k command, reading at t_k, true x).
struct StackRun {
  Eigen::VectorXd t_s, u_v, x_m, x_true_m;
  long clipped_samples = 0;
};
StackRun RunStackOpenLoop(const StackParameters& parameters, const Eigen::VectorXd& u_v,
                          std::uint64_t seed = 1);

}  // namespace sysid

#endif  // SYSID_STACK_HPP_
