// Input voltages u(t) [V] for the simulator. Every input is right-continuous (a value given at
// time t applies from t on) and reports its own edges: the times where u or u' jumps, which
// the simulator hits exactly.
#ifndef SYSID_INPUT_HPP_
#define SYSID_INPUT_HPP_

#include <memory>
#include <string>
#include <vector>

#include "sysid/io.hpp"

namespace sysid {

class InputSignal {
 public:
  virtual ~InputSignal() = default;
  /// u(t) [V], right-continuous.
  virtual double Value(double t_s) const = 0;
  /// Times in (t0_s, t1_s] where u or its derivative is discontinuous, ascending.
  virtual std::vector<double> Edges(double t0_s, double t1_s) const = 0;
  /// [s] Largest integration step that still resolves u between its edges (a fraction of the
  /// shortest period of a smooth input), so that no threshold crossing of u falls between two
  /// steps unseen. +infinity when u is constant or linear between edges.
  virtual double MaxStepHint() const;
  /// True when u is constant between consecutive edges (a zero-order hold): the simulator then
  /// skips stuck stretches where the force cannot change.
  virtual bool ConstantBetweenEdges() const { return false; }
};

/// Zero-order hold of a table: u = u_k on [t_k, t_{k+1}); holds the last value after the end and
/// the first value before the start.
class PiecewiseConstantInput final : public InputSignal {
 public:
  PiecewiseConstantInput(std::vector<double> t_s, std::vector<double> u_v);
  double Value(double t_s) const override;
  std::vector<double> Edges(double t0_s, double t1_s) const override;
  bool ConstantBetweenEdges() const override { return true; }
  const std::vector<double>& times() const { return t_; }
  const std::vector<double>& values() const { return u_; }

 private:
  std::vector<double> t_, u_;
};

/// Linear interpolation of a table; constant outside it. Edges are the table's knots.
class PiecewiseLinearInput final : public InputSignal {
 public:
  PiecewiseLinearInput(std::vector<double> t_s, std::vector<double> u_v);
  double Value(double t_s) const override;
  std::vector<double> Edges(double t0_s, double t1_s) const override;

 private:
  std::vector<double> t_, u_;
};

/// u = offset + sum_i amplitude_i sin(2 pi f_i t + phase_i); smooth, no edges.
struct SineComponent {
  double amplitude_v = 0;   ///< [V]
  double frequency_hz = 0;  ///< [Hz]
  double phase_rad = 0;     ///< [rad]
};
class SumOfSinesInput final : public InputSignal {
 public:
  explicit SumOfSinesInput(std::vector<SineComponent> components, double offset_v = 0.0);
  double Value(double t_s) const override;
  std::vector<double> Edges(double, double) const override { return {}; }
  /// One twentieth of the shortest period.
  double MaxStepHint() const override;

 private:
  std::vector<SineComponent> components_;
  double offset_v_;
};

/// A pulse test: for each amplitude in turn, `amplitude` for on_s, then 0 for off_s; the whole
/// list repeated `repeats` times, starting at start_s (u = 0 before).
struct PulseTrainSpec {
  std::vector<double> amplitudes_v{1.6, -2.3};  ///< [V] in order
  double on_s = 0.4;                            ///< [s] pulse length
  double off_s = 0.6;                           ///< [s] rest after each pulse
  int repeats = 5;
  double start_s = 0.0;       ///< [s]
  double duration_s() const;  ///< [s] start_s + repeats * n * (on_s + off_s)
};
/// The pulse train as a zero-order-hold table. Throws OptionsError for a bad field, or when the
/// table would exceed kMaxSignalSamples rows (checked before allocating).
PiecewiseConstantInput MakePulseTrain(const PulseTrainSpec& spec);

/// How a table of (t, u) rows is held between its rows.
enum class InputHold {
  kZeroOrder,  ///< u_k holds on [t_k, t_{k+1}) ("zoh")
  kLinear,     ///< linear between rows ("linear")
};
/// Parses "zoh" / "linear"; throws OptionsError naming the accepted values.
InputHold ParseInputHold(const std::string& name);

/// An input table as a signal. `t_s` strictly increasing and finite, `u_v` finite, equally long
/// and non-empty; otherwise throws InputError naming `source`, the row and the rule.
std::unique_ptr<InputSignal> MakeTableInput(std::vector<double> t_s, std::vector<double> u_v,
                                            InputHold hold, const std::string& source = "table");
/// Reads an input table CSV with columns t [s] and u [V] (sysid::ReadRecording rules: other
/// columns are ignored). Throws InputError "FILE:LINE:COLUMN: ...".
std::unique_ptr<InputSignal> ReadInputTable(const std::string& path, InputHold hold,
                                            const SourceMapping& mapping = {});

/// A named test waveform of the paper, with its natural duration.
struct NamedWaveform {
  std::string name;         ///< e.g. "paper-pulses"
  std::string description;  ///< one line, with units
  double duration_s = 0;    ///< [s] natural length of the test
  std::shared_ptr<const InputSignal> signal;
};
/// The paper's test waveforms:
///  - "paper-pulses":  +1.6 V / -2.3 V pulses, 0.4 s on, 0.6 s off, 5 repeats (10 s);
///  - "paper-ladder":  pulses of -1.8, 1.3, -2.0, 1.5, -2.1, 1.7, -2.5, 2.0 V, 0.4 s on,
///                     0.6 s off (8 s), the paper's second identification experiment;
///  - "paper-triangle": triangle of 6 s period with peaks +1.5 V and -2.1 V, 2 periods (12 s):
///                     knots (0, 0), (1.5, 1.5), (4.5, -2.1), (6, 0) V, repeated;
///  - "paper-sine":    u = 1.5 sin(pi/2 t - pi/2) - 0.3 V (0.25 Hz), 2 periods (8 s).
std::vector<std::string> NamedWaveformNames();
/// Throws OptionsError listing the known names when `name` is unknown.
NamedWaveform MakeNamedWaveform(const std::string& name);

/// An input table file (columns t [s], u [V], as ReadInputTable) with its natural length, the
/// last row's t; described as "PATH (zoh)" or "PATH (linear)".
NamedWaveform ReadInputWaveform(const std::string& path, InputHold hold,
                                const SourceMapping& mapping = {});
/// A pulse train with its natural length spec.duration_s(), described with its amplitudes and
/// timing.
NamedWaveform PulseTrainWaveform(const PulseTrainSpec& spec);

}  // namespace sysid

#endif  // SYSID_INPUT_HPP_
