// The Bouc–Wen fit's standard errors, s^2 (J^T J)^-1 with J the benchmark chain's exact Jacobian
// (forward sensitivities), against the spread of the fitted parameters over many noise seeds
// (Monte-Carlo), as tests/delay/refine_monte_carlo_test.cpp checks refine's.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "core/portable_random.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/io.hpp"
#include "support/standard_error_tally.hpp"

namespace sysid {
namespace {

TEST_CASE("bouc-wen: standard errors from the exact Jacobian match the Monte-Carlo spread",
          "[hysteresis][bouc-wen][fit][uncertainty]") {
  // The benchmark's system on one period of a 1024-sample multisine at 750 Hz, the chain at 4x
  // (the recovery test's set-up, shorter), white noise of the benchmark's level; each fit from
  // the truth, one start (the spread is the noise's, not the starts').
  const MechanicalBoucWenParameters truth;
  BoucWenSimulationOptions sim;
  sim.integrator = BoucWenIntegrator::kBenchmarkChain;
  sim.upsampling = 4;
  const double dt = 1.0 / 750;
  const Eigen::Index n = 1024;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
  const double w0 = 2 * M_PI / (static_cast<double>(n) * dt);
  for (int l = 7; l <= 200; ++l)
    for (Eigen::Index i = 0; i < n; ++i)
      u[i] += 6.0 * std::cos(w0 * l * static_cast<double>(i) * dt + 2.39996 * l * l);
  const Eigen::VectorXd y = MechanicalBoucWen(truth, sim).Simulate(u, dt);
  BoucWenFitOptions o;
  o.simulation = sim;
  o.mechanical_initial = truth;
  o.mechanical_initial_given = true;
  o.starts = 1;
  o.threads = 1;
  const double sigma = 7.4e-6;  // [m]
  // The agreement required is the tally's, 4 / sqrt(2 (N - 1)).
  const int seeds = 100;
  internal::PortableRandom random(2041);
  const int free[] = {0, 1, 2, 3, 5, 6};  // m, c, k, alpha, gamma, delta (beta, nu fixed)
  test::StandardErrorTally tally({"m", "c", "k", "alpha", "beta", "gamma", "delta", "nu"});
  for (int s = 0; s < seeds; ++s) {
    Recording rec;
    rec.source = "mc";
    rec.names = {"t", "u", "x"};
    rec.data.resize(n, 3);
    for (Eigen::Index i = 0; i < n; ++i)
      rec.data.row(i) << static_cast<double>(i) * dt, u[i], y[i] + sigma * random.Normal();
    const auto model = FitBoucWen(BoucWenForm::kMechanical, {rec}, o);
    const auto ps = model->parameters();
    for (int i : free) {
      const auto& p = ps[static_cast<size_t>(i)];
      tally.Add(static_cast<size_t>(i), p.value, p.std_error);
    }
  }
  tally.CheckAgreement();
}

}  // namespace
}  // namespace sysid
