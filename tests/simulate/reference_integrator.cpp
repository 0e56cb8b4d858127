#include "reference_integrator.hpp"

#include <cmath>
#include <stdexcept>

namespace sysid::test {
namespace {

class Rk4MethodOfSteps {
 public:
  Rk4MethodOfSteps(const FrictionModel& m, const PiecewiseConstantInput& in, double h)
      : m_(m),
        in_(in),
        h_(h),
        D_(static_cast<long>(std::lround(m.tau_s / h))),
        size_(static_cast<size_t>(D_ + 2)),
        V_(size_),
        dR_(size_),
        dL_(size_) {
    if (D_ < 1 || std::abs(D_ * h - m.tau_s) > 1e-9 * h)
      throw std::invalid_argument("tau must be a positive multiple of h");
  }

  ReferenceTrajectory Run(double t_end, int sample_every) {
    ReferenceTrajectory out;
    const long n = std::lround(t_end / h_);
    double x = 0, v = 0;
    int mode = 0;
    for (long k = 0;; ++k) {
      const double t = k * h_;
      // Edges lie on the grid: u at the step midpoint is the value on the whole step, free of the
      // rounding of k * h near an edge.
      const double u = in_.Value(t + 0.5 * h_);
      if (mode == 0) {
        mode = Decide(Force(k, 0.0, u));
        if (mode != 0) out.event_t.push_back(t);
      }
      V(k) = v;
      if (k % sample_every == 0) {
        out.t.push_back(t);
        out.x.push_back(x);
        out.v.push_back(v);
      }
      if (k == n) break;
      dR(k) = Accel(k, 0.0, u, mode);
      double theta = 0;
      // Up to a few events inside one step (stop, then release or reverse).
      for (int guard = 0; guard < 4 && theta < 1; ++guard) {
        if (mode == 0) {
          if (Decide(Force(k, 1.0, u)) == 0) {
            theta = 1;
            break;
          }
          double lo = theta, hi = 1;
          for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (lo + hi);
            (Decide(Force(k, mid, u)) != 0 ? hi : lo) = mid;
          }
          theta = hi;
          mode = Decide(Force(k, theta, u));
          out.event_t.push_back((k + theta) * h_);
          continue;
        }
        double xn, vn;
        Partial(k, theta, 1.0, u, mode, x, v, &xn, &vn);
        if (mode * vn > 0) {
          x = xn;
          v = vn;
          theta = 1;
          break;
        }
        double lo = theta, hi = 1;
        for (int i = 0; i < 60; ++i) {
          const double mid = 0.5 * (lo + hi);
          Partial(k, theta, mid, u, mode, x, v, &xn, &vn);
          (mode * vn > 0 ? lo : hi) = mid;
        }
        Partial(k, theta, hi, u, mode, x, v, &xn, &vn);
        x = xn;
        v = 0;
        theta = hi;
        mode = Decide(Force(k, theta, u));
        out.event_t.push_back((k + theta) * h_);
      }
      dL(k + 1) = Accel(k, 1.0, u, mode);
    }
    return out;
  }

 private:
  double& V(long k) { return V_[static_cast<size_t>(k) % size_]; }
  double& dR(long k) { return dR_[static_cast<size_t>(k) % size_]; }
  double& dL(long k) { return dL_[static_cast<size_t>(k) % size_]; }

  /// v(t_k + theta h - tau) by cubic Hermite on grid interval [k - D, k - D + 1].
  double Delayed(long k, double th) {
    const long j = k - D_;
    if (j < 0) return 0.0;  // zero history
    const double v0 = V(j), v1 = V(j + 1);
    const double d0 = dR(j), d1 = dL(j + 1);
    const double t2 = th * th, t3 = t2 * th;
    return (2 * t3 - 3 * t2 + 1) * v0 + (t3 - 2 * t2 + th) * h_ * d0 + (-2 * t3 + 3 * t2) * v1 +
           (t3 - t2) * h_ * d1;
  }
  double Force(long k, double th, double u) {
    const double vd = Delayed(k, th);
    return m_.a3 * u - (vd > 0 ? m_.a1p : m_.a1n) * vd;
  }
  int Decide(double f) const { return f > m_.a2p ? 1 : (f < -m_.a2n ? -1 : 0); }
  double Accel(long k, double th, double u, int mode) {
    if (mode == 0) return 0.0;
    return Force(k, th, u) - (mode > 0 ? m_.a2p : -m_.a2n);
  }
  /// One RK4 step from theta0 to theta1 in a fixed mode (v' does not depend on v: Simpson).
  void Partial(long k, double th0, double th1, double u, int mode, double x, double v, double* xn,
               double* vn) {
    const double L = (th1 - th0) * h_;
    const double g0 = Accel(k, th0, u, mode), gm = Accel(k, 0.5 * (th0 + th1), u, mode),
                 g1 = Accel(k, th1, u, mode);
    *vn = v + L / 6 * (g0 + 4 * gm + g1);
    *xn = x + L * v + L * L / 6 * (g0 + 2 * gm);
  }

  const FrictionModel& m_;
  const PiecewiseConstantInput& in_;
  double h_;
  long D_;
  size_t size_;
  std::vector<double> V_, dR_, dL_;
};

}  // namespace

ReferenceTrajectory ReferenceRk4(const FrictionModel& model, const PiecewiseConstantInput& input,
                                 double t_end, double h, int sample_every) {
  return Rk4MethodOfSteps(model, input, h).Run(t_end, sample_every);
}

}  // namespace sysid::test
