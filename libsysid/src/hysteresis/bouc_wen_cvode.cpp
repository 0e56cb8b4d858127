// The mechanical Bouc–Wen oscillator by CVODE, and its forward sensitivities by CVODES.
//
// State x = (y, v, z): y' = v, v' = (u - c v - k y - z) / m, z' = f(v, z). A sensitivity
// s = dx/dp obeys s' = (df/dx) s + df/dp with
//   df/dx = [[0, 1, 0], [-k/m, -c/m, -1/m], [0, f_v, f_z]],
// and df/dp from the equation of motion (m: -v'/m, c: -v/m, k: -y/m) and from z'
// (MechanicalRateParameterPartials). f is continuous where |z| and |v| switch sign, so the
// sensitivities need no jump there and its partials are those of the side the state is on.
#include <cmath>

#include "core/cvode_solver.hpp"
#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {

namespace {

struct MechanicalOde {
  const MechanicalBoucWenParameters* p;
  const SampledInput* input;
  Eigen::Index interval = 0;
  const std::vector<int>* which = nullptr;  // the sensitivities' parameters
  bool with_nu = false;
};

int MechanicalRhs(double t, N_Vector x, N_Vector dx, void* data) {
  const auto* ode = static_cast<const MechanicalOde*>(data);
  const double* s = N_VGetArrayPointer(x);
  double* d = N_VGetArrayPointer(dx);
  double u = 0, du = 0;
  ode->input->Evaluate(t, ode->interval, &u, &du);
  const auto& p = *ode->p;
  d[0] = s[1];
  d[1] = (u - p.c_n_s_per_m * s[1] - p.k_n_per_m * s[0] - s[2]) / p.m_kg;
  d[2] = MechanicalRate(p, s[1], s[2]).f;
  return std::isfinite(d[1]) && std::isfinite(d[2]) ? 0 : 1;  // > 0: CVODE retries smaller
}

int MechanicalSensitivityRhs(int count, double, N_Vector x, N_Vector dx, N_Vector* s,
                             N_Vector* ds, void* data, N_Vector, N_Vector) {
  const auto* ode = static_cast<const MechanicalOde*>(data);
  const auto& p = *ode->p;
  const double* xs = N_VGetArrayPointer(x);
  const double a = N_VGetArrayPointer(dx)[1];  // v'
  const double m = p.m_kg, c = p.c_n_s_per_m, k = p.k_n_per_m;
  const BoucWenRate r = MechanicalRate(p, xs[1], xs[2]);
  const MechanicalParameterVector fp =
      MechanicalRateParameterPartials(p, xs[1], xs[2], ode->with_nu);
  for (int i = 0; i < count; ++i) {
    const double* si = N_VGetArrayPointer(s[i]);
    double* dsi = N_VGetArrayPointer(ds[i]);
    const int q = (*ode->which)[static_cast<size_t>(i)];
    const double dv_dp = q == 0 ? -a / m : q == 1 ? -xs[1] / m : q == 2 ? -xs[0] / m : 0.0;
    dsi[0] = si[1];
    dsi[1] = (-k * si[0] - c * si[1] - si[2]) / m + dv_dp;
    dsi[2] = r.df_dv * si[1] + r.df_dz * si[2] + fp[q];
    if (!std::isfinite(dsi[1]) || !std::isfinite(dsi[2])) return 1;
  }
  return 0;
}

}  // namespace

void MechanicalCvode(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& u, double dt_s,
                     const BoucWenSimulationOptions& o, const std::vector<int>& which,
                     Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp) {
  MechanicalCvode(p, SampledInput(u, dt_s, o.input), o, which, y, dy_dp);
}

void MechanicalCvode(const MechanicalBoucWenParameters& p, const SampledInput& input,
                     const BoucWenSimulationOptions& o, const std::vector<int>& which,
                     Eigen::VectorXd* y, Eigen::MatrixXd* dy_dp) {
  const Eigen::VectorXd& u = input.samples();
  const double dt_s = input.dt_s();
  const Eigen::Index n = u.size();
  *y = Eigen::VectorXd::Zero(n);
  const int ns = static_cast<int>(which.size());
  if (ns > 0) *dy_dp = Eigen::MatrixXd::Zero(n, kMechanicalParameters);
  if (n == 0) return;
  MechanicalOde ode{&p, &input, 0, &which, false};
  for (int q : which) ode.with_nu = ode.with_nu || q == 7;
  const double x0[3] = {0, 0, 0};
  CvodeSolver solver(3, CvodeSolver::Method::kAdams, MechanicalRhs, &ode, 0, x0,
                     "bouc-wen simulation", "check the parameters, or loosen rtol");
  // Absolute tolerances from the static scales: y ~ max|u| / (k + alpha), z ~ max|u|.
  const double umax = std::max(u.cwiseAbs().maxCoeff(), 1e-300);
  const double ys = umax / (p.k_n_per_m + p.alpha_n_per_m);
  const double vs = ys * std::sqrt((p.k_n_per_m + p.alpha_n_per_m) / p.m_kg);
  const double atol[3] = {1e-3 * o.rtol * ys, 1e-3 * o.rtol * vs, 1e-3 * o.rtol * umax};
  solver.SetTolerances(o.rtol, atol);
  solver.SetMaxNumSteps(1000000);
  if (ns > 0) {
    // The parameters' magnitudes scale the sensitivities' tolerances (nu's from 1).
    const double values[kMechanicalParameters] = {
        p.m_kg,  p.c_n_s_per_m, p.k_n_per_m, p.alpha_n_per_m, p.beta_per_m,
        p.gamma, p.delta,       p.nu};
    std::vector<double> scales;
    for (int q : which) scales.push_back(std::max(std::abs(values[q]), 1e-300));
    solver.EnableSensitivities(ns, MechanicalSensitivityRhs, scales.data(), false);
  }
  const bool smooth = input.how() == InputInterpolation::kBandLimited;
  double t = 0;
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const double t_next = static_cast<double>(k + 1) * dt_s;
    ode.interval = k;
    if (!smooth) solver.SetStopTime(t_next);  // never step past a kink or a jump of u
    solver.Check(solver.Advance(t_next, &t, CV_NORMAL), "CVode");
    (*y)[k + 1] = solver.state()[0];
    if (ns > 0) solver.ReadSensitivities();
    for (int i = 0; i < ns; ++i) (*dy_dp)(k + 1, which[static_cast<size_t>(i)]) = solver.sensitivity(i)[0];
    // A held input jumps at every sample, a linear one's slope does: CVODE's multistep
    // history would carry the jump into the next interval, so it restarts there.
    if (!smooth) solver.ReInit(t_next);
  }
}

}  // namespace sysid::internal
