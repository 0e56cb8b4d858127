// The simulator's outputs: the requested sample times, the trajectory they fill, and the
// polynomial of the last accepted step that the samples inside that step are read from.
#ifndef SYSID_SRC_SIMULATE_OUTPUT_SAMPLER_HPP_
#define SYSID_SRC_SIMULATE_OUTPUT_SAMPLER_HPP_

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sysid/simulate.hpp"

namespace sysid::internal {

/// Largest CVODE order (Adams); the Taylor coefficient arrays are sized for it.
constexpr int kMaxOrder = 12;

/// One accepted step as a polynomial in theta = (t - tn) / hu: x(t) = sum_k x[k] theta^k, same
/// for v. It is the step's own interpolant (CVODE's Nordsieck array, the polynomial its error
/// control certified), used both for the delay history and for the outputs inside the step.
struct StepPolynomial {
  int order = 0;
  double tn = 0, hu = 1;  // [s] step end and length
  double x[kMaxOrder + 1] = {};
  double v[kMaxOrder + 1] = {};

  /// x and v at ts (Horner).
  void Evaluate(double ts, double* xs, double* vs) const {
    const double theta = (ts - tn) / hu;
    double xa = x[order], va = v[order];
    for (int k = order - 1; k >= 0; --k) {
      xa = xa * theta + x[k];
      va = va * theta + v[k];
    }
    *xs = xa;
    *vs = va;
  }
};

/// The output grid (explicit times, or t0 + k dt_out up to t_end) and the trajectory, filled
/// in time order as the run reaches each sample.
class OutputSampler {
 public:
  OutputSampler(const SimulationOptions& o, Trajectory* trajectory)
      : times_(Times(o)), tr_(*trajectory) {
    const auto n = static_cast<Eigen::Index>(times_.size());
    tr_.t_s.resize(n);
    tr_.u_v.resize(n);
    tr_.x_m.resize(n);
    tr_.v_mps.resize(n);
    tr_.a_mps2.resize(n);
  }

  /// True while samples are left; next() is then the next sample time.
  bool pending() const { return next_ < times_.size(); }
  double next() const { return times_[next_]; }

  /// Stores the next sample (labelled t_label: a snap onto a stop may have moved the time by
  /// less than TimeEps).
  void Add(double t_label, double u, double x, double v, double a) {
    const auto i = static_cast<Eigen::Index>(next_++);
    tr_.t_s[i] = t_label;
    tr_.u_v[i] = u;
    tr_.x_m[i] = x;
    tr_.v_mps[i] = v;
    tr_.a_mps2[i] = a;
  }

  /// After a failure: keep the samples reached, and only those.
  void KeepReached() {
    if (!pending()) return;
    const auto n = static_cast<Eigen::Index>(next_);
    tr_.t_s.conservativeResize(n);
    tr_.u_v.conservativeResize(n);
    tr_.x_m.conservativeResize(n);
    tr_.v_mps.conservativeResize(n);
    tr_.a_mps2.conservativeResize(n);
  }

 private:
  static std::vector<double> Times(const SimulationOptions& o) {
    if (!o.output_times_s.empty()) return o.output_times_s;
    const auto n =
        static_cast<long>(std::floor((o.t_end_s - o.t0_s) / o.dt_out_s * (1 + 1e-12)));
    std::vector<double> t(static_cast<std::size_t>(n + 1));
    for (long k = 0; k <= n; ++k)
      t[static_cast<std::size_t>(k)] =
          std::min(o.t0_s + static_cast<double>(k) * o.dt_out_s, o.t_end_s);
    return t;
  }

  std::vector<double> times_;
  Trajectory& tr_;
  std::size_t next_ = 0;
};

}  // namespace sysid::internal

#endif  // SYSID_SRC_SIMULATE_OUTPUT_SAMPLER_HPP_
