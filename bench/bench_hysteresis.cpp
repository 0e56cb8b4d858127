// Prandtl–Ishlinskii speed: the NNLS fit of a 20-operator PI (+ offset) on 1e5 samples, beside a
// baseline in the same run: the unconstrained least squares of the same regression (building
// the N x 22 matrix of play-operator outputs and its Householder QR, Eigen), so the ratio says
// what the bounds, the active-set pass and the standard errors cost on top. Also the simulate
// and closed-form inverse throughput [samples/s].
//
//   bench_hysteresis [--samples 100000] [--operators 20] [--repeats 3]
#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "sysid/hysteresis.hpp"

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  int samples = 100000, operators = 20, repeats = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--samples") samples = std::clamp(std::atoi(argv[i + 1]), 100, 20000000);
    else if (a == "--operators") operators = std::clamp(std::atoi(argv[i + 1]), 1, sysid::kMaxPlayOperators);
    else if (a == "--repeats") repeats = std::clamp(std::atoi(argv[i + 1]), 1, 100);
  }
  // The truth: a PI on [0, 3.6] V with decaying weights, a multi-tone input with minor loops.
  sysid::PiParameters p;
  p.thresholds = sysid::UniformThresholds(0, 3.6, operators);
  for (int i = 0; i < operators; ++i) p.weights.push_back(2e-6 * std::exp(-0.15 * i));
  p.polynomial = {3e-6};
  p.offset_m = -1e-4;
  p.input_min_v = 0;
  p.input_max_v = 3.6;
  const sysid::PrandtlIshlinskiiModel truth(p);
  const double dt = 5e-3;
  Eigen::VectorXd u(samples);
  for (int k = 0; k < samples; ++k) {
    const double t = k * dt;
    u[k] = 1.8 + 1.2 * std::sin(2 * M_PI * 0.5 * t) + 0.5 * std::sin(2 * M_PI * 2.3 * t);
  }
  Eigen::VectorXd x = truth.Simulate(u, dt);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0, 1e-7);
  for (int k = 0; k < samples; ++k) x[k] += noise(rng);
  sysid::Recording rec;
  rec.source = "bench";
  rec.names = {"t", "u", "x"};
  rec.data.resize(samples, 3);
  for (int k = 0; k < samples; ++k) rec.data.row(k) << k * dt, u[k], x[k];

  std::vector<double> fit_s, ls_s, sim_s, inv_s;
  sysid::HysteresisFitSummary summary;
  std::unique_ptr<sysid::PrandtlIshlinskiiModel> model;
  for (int r = 0; r < repeats; ++r) {
    auto t0 = std::chrono::steady_clock::now();
    sysid::PiFitOptions o;
    o.operators = operators;
    model = sysid::FitPrandtlIshlinskii({rec}, o, &summary);
    fit_s.push_back(Seconds(t0));
    // Baseline: the same regression matrix and an unconstrained Householder QR solve.
    t0 = std::chrono::steady_clock::now();
    Eigen::MatrixXd A(samples, operators + 2);
    A.col(0) = u;
    for (int i = 0; i < operators; ++i)
      A.col(1 + i) = sysid::PlayOperator(u, model->pi().thresholds[static_cast<size_t>(i)], 0.0);
    A.col(operators + 1).setOnes();
    const Eigen::VectorXd theta = A.householderQr().solve(x);
    ls_s.push_back(Seconds(t0));
    if (!std::isfinite(theta.sum())) return 3;
    t0 = std::chrono::steady_clock::now();
    const Eigen::VectorXd y = model->Simulate(u, dt);
    sim_s.push_back(Seconds(t0));
    t0 = std::chrono::steady_clock::now();
    const Eigen::VectorXd back = model->Invert(y, dt);
    inv_s.push_back(Seconds(t0));
    if ((back - u).cwiseAbs().maxCoeff() > 1e-9) return 3;
  }
  fmt::print("PI, {} operators + offset, {} samples, median of {} runs\n", operators, samples, repeats);
  fmt::print("  NNLS fit (Ceres + active-set pass + std errors): {:.4f} s  (training RMS {:.3g} m)\n",
             Median(fit_s), summary.training_rms);
  fmt::print("  baseline unconstrained QR least squares:           {:.4f} s\n", Median(ls_s));
  fmt::print("  ratio fit / baseline:                               {:.2f}\n", Median(fit_s) / Median(ls_s));
  fmt::print("  simulate: {:.3g} samples/s; closed-form inverse: {:.3g} samples/s\n",
             samples / Median(sim_s), samples / Median(inv_s));
  return 0;
}
