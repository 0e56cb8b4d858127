// Input voltages u(t) [V] for the simulator. Every input is right-continuous (a value given at
// time t applies from t on) and reports its own edges: the times where u or u' jumps, which
// the simulator hits exactly.
#ifndef SYSID_INPUT_HPP_
#define SYSID_INPUT_HPP_

#include <memory>
#include <string>
#include <vector>

namespace sysid {

class InputSignal {
 public:
  virtual ~InputSignal() = default;
  /// u(t) [V], right-continuous.
  virtual double Value(double t_s) const = 0;
  /// Times in (t0_s, t1_s] where u or its derivative is discontinuous, ascending.
  virtual std::vector<double> Edges(double t0_s, double t1_s) const = 0;
};

/// Zero-order hold of a table: u = u_k on [t_k, t_{k+1}); holds the last value after the end and
/// the first value before the start.
class PiecewiseConstantInput final : public InputSignal {
 public:
  PiecewiseConstantInput(std::vector<double> t_s, std::vector<double> u_v);
  double Value(double t_s) const override;
  std::vector<double> Edges(double t0_s, double t1_s) const override;
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
  double amplitude_v = 0;  ///< [V]
  double frequency_hz = 0; ///< [Hz]
  double phase_rad = 0;    ///< [rad]
};
class SumOfSinesInput final : public InputSignal {
 public:
  explicit SumOfSinesInput(std::vector<SineComponent> components, double offset_v = 0.0);
  double Value(double t_s) const override;
  std::vector<double> Edges(double, double) const override { return {}; }
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
  double start_s = 0.0;                         ///< [s]
  double duration_s() const;                    ///< [s] start_s + repeats * n * (on_s + off_s)
};
/// The pulse train as a zero-order-hold table.
PiecewiseConstantInput MakePulseTrain(const PulseTrainSpec& spec);

}  // namespace sysid

#endif  // SYSID_INPUT_HPP_
