// The Bouc–Wen benchmark (Noël & Schoukens 2016) scored by its protocol, and the Bouc–Wen
// simulators' throughput. experiments/boucwen_benchmark.sh and bench/run_bouc_wen.sh run it.
//
//   bench_bouc_wen score TRAIN.csv TEST.csv [--threads T] [--starts S] [-o MODEL.json]
//     Fits the mechanical form on TRAIN (t, u, x) only, simulated by the benchmark chain;
//     simulates TEST's input alone in its periodic steady state; prints key=value lines:
//     "fit ..." (parameters, standard errors, fit time, training rms), "score model=... e_rms=..."
//     for the fitted model (chain, and CVODE with band-limited input) and the true system.
//   bench_bouc_wen fit-speed TRAIN.csv [--threads T] [--starts S] [--repeats R]
//                  [--jacobian sensitivities|central-differences] [--integrator chain|cvode]
//                  [--max-time S] [--start-rtol R]
//     What the benchmark fit costs: one chain simulation of TRAIN's u (true parameters) as the
//     fit ran it before (Simulate: the input upsampled on every call) against the fit's path now
//     (the upsampled input computed once, internal::ChainOutput), best CPU time of R, the outputs
//     compared bit for bit; one exact Jacobian (internal::ChainOutputSensitivity) against one
//     simulation, CPU; then the fit itself: CPU [s] (user + system of every thread), wall
//     [s], simulations. Prints "simulation ...", "jacobian ..." and "fit ..." lines. The
//     options after --repeats are this build's (a baseline binary is run without them).
//   bench_bouc_wen cvode-jacobian REC.csv [--input linear|hold|band-limited] [--rtol R]
//                  [--repeats R]
//     The CVODE path's Jacobian: one CVODE simulation of REC's u (true parameters) against one
//     pass of CVODES with the sensitivities of the fit's six default free parameters (m, c, k,
//     alpha, gamma, delta; internal::MechanicalCvode), best CPU of R; central differences cost 13
//     simulations. Prints a "cvode-jacobian ..." line (with a band-limited input: its table's grid
//     points per sample and error bound, 0 when the lines are summed), each pass building its own
//     input as a standalone simulation does; then a "cvode-jacobian-shared-input ..." line: the
//     input (a band-limited input's table) built once, best CPU of R, and the same two passes on
//     it as the fit runs them, their outputs compared with the others bit for bit (exit 1 if not);
//     with a band-limited input a "cvode-jacobian-auto-rule ..." line: the fit's --input auto
//     check of the table's bound (SampledInput::GridPerSample, no table) against building it.
//   bench_bouc_wen fixed-step REC.csv
//     The Newmark/trapezoidal step (the chain's) on the input linear between samples, 5 to 80
//     substeps per sample, against CVODE at rtol 1e-12 on REC's u (true parameters): max and
//     RMS error [m], CPU [s]; CVODE at the fit's rtol 1e-9 beside. Prints "fixed-step ..." lines.
//   bench_bouc_wen throughput REC.csv [--repeats R]
//     Samples per second of Simulate on REC's u (true parameters): the chain, CVODE with linear
//     and band-limited input, and the piezo form. Prints "throughput method=... samples_per_s=...".
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"
#include "sysid/io.hpp"

namespace {

using sysid::BoucWenIntegrator;
using sysid::InputInterpolation;

double Rms(const Eigen::VectorXd& e) {
  return std::sqrt(e.squaredNorm() / static_cast<double>(e.size()));
}

// `tolerance` [m]: periods agree to it in steady state (the chain is exact to rounding, CVODE
// to its rtol of ~1e-13 m here).
void Score(const char* name, const sysid::HysteresisModel& m, const Eigen::VectorXd& u,
           const Eigen::VectorXd& y, double dt, double tolerance) {
  const auto t0 = std::chrono::steady_clock::now();
  const Eigen::VectorXd ym = m.SimulatePeriodic(u, dt, tolerance, 64);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  fmt::print("score model={} e_rms={:.4e} max_error={:.4e} simulate_s={:.3f}\n", name, Rms(ym - y),
             (ym - y).cwiseAbs().maxCoeff(), s);
}

int ScoreCommand(const std::vector<std::string>& args) {
  std::string train, test, out;
  sysid::BoucWenFitOptions o;
  o.simulation.integrator = BoucWenIntegrator::kBenchmarkChain;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--threads" && i + 1 < args.size()) {
      o.threads = std::atoi(args[++i].c_str());
    } else if (args[i] == "--starts" && i + 1 < args.size()) {
      o.starts = std::atoi(args[++i].c_str());
    } else if (args[i] == "-o" && i + 1 < args.size()) {
      out = args[++i];
    } else if (train.empty()) {
      train = args[i];
    } else {
      test = args[i];
    }
  }
  if (train.empty() || test.empty()) {
    fmt::print(stderr,
               "usage: bench_bouc_wen score TRAIN.csv TEST.csv [--threads T] [--starts S] [-o "
               "MODEL.json]\n");
    return 1;
  }
  const sysid::Recording tr = sysid::ReadRecording(train);
  const sysid::Recording te = sysid::ReadRecording(test);
  const double dt = te.column("t")[1] - te.column("t")[0];
  sysid::HysteresisFitSummary summary;
  const std::clock_t cpu0 = std::clock();
  const auto model = sysid::FitBoucWen(sysid::BoucWenForm::kMechanical, {tr}, o, &summary);
  const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  fmt::print("fit samples={} fit_time_s={:.2f} cpu_s={:.2f} training_rms={:.4e} converged={}\n",
             summary.samples, summary.fit_time_s, cpu_s, summary.training_rms, summary.converged);
  fmt::print("fit_message {}\n", summary.message);
  for (const auto& p : model->parameters())
    fmt::print("parameter name={} value={:.8g} std_error={:.3g} unit={}\n", p.name, p.value,
               p.std_error, p.unit);
  if (!out.empty()) sysid::WriteFileAtomically(out, model->ToJson());
  const Eigen::VectorXd u = te.column("u"), y = te.column("x");
  Score("fitted-chain", *model, u, y, dt, 1e-13);
  const auto& fitted = dynamic_cast<const sysid::MechanicalBoucWen&>(*model);
  sysid::BoucWenSimulationOptions cv;
  cv.input = InputInterpolation::kBandLimited;
  cv.rtol = 1e-10;
  Score("fitted-cvode-band-limited", sysid::MechanicalBoucWen(fitted.values(), cv), u, y, dt,
        1e-10);
  sysid::BoucWenSimulationOptions chain;
  chain.integrator = BoucWenIntegrator::kBenchmarkChain;
  Score("true-chain", sysid::MechanicalBoucWen({}, chain), u, y, dt, 1e-13);
  Score("true-cvode-band-limited", sysid::MechanicalBoucWen({}, cv), u, y, dt, 1e-10);
  cv.input = InputInterpolation::kLinear;
  Score("true-cvode-linear", sysid::MechanicalBoucWen({}, cv), u, y, dt, 1e-10);
  return 0;
}

int FitSpeedCommand(const std::vector<std::string>& args) {
  std::string train;
  sysid::BoucWenFitOptions o;
  o.simulation.integrator = BoucWenIntegrator::kBenchmarkChain;
  int repeats = 5;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--threads" && i + 1 < args.size())
      o.threads = std::atoi(args[++i].c_str());
    else if (args[i] == "--starts" && i + 1 < args.size())
      o.starts = std::atoi(args[++i].c_str());
    else if (args[i] == "--repeats" && i + 1 < args.size())
      repeats = std::max(1, std::atoi(args[++i].c_str()));
    else if (args[i] == "--jacobian" && i + 1 < args.size())
      o.jacobian = args[++i] == "central-differences" ? sysid::BoucWenJacobian::kCentralDifferences
                                                      : sysid::BoucWenJacobian::kSensitivities;
    else if (args[i] == "--integrator" && i + 1 < args.size())
      o.simulation.integrator =
          args[++i] == "cvode" ? BoucWenIntegrator::kCvode : BoucWenIntegrator::kBenchmarkChain;
    else if (args[i] == "--max-time" && i + 1 < args.size())
      o.max_time_s = std::atof(args[++i].c_str());
    else if (args[i] == "--start-rtol" && i + 1 < args.size())
      o.start_rtol = std::atof(args[++i].c_str());
    else
      train = args[i];
  }
  if (train.empty()) {
    fmt::print(stderr,
               "usage: bench_bouc_wen fit-speed TRAIN.csv [--threads T] [--starts S] [--repeats "
               "R] [--jacobian J] [--integrator I] [--max-time S] [--start-rtol R]\n");
    return 1;
  }
  const sysid::Recording tr = sysid::ReadRecording(train);
  const Eigen::VectorXd u = tr.column("u");
  const double dt = tr.column("t")[1] - tr.column("t")[0];
  sysid::BoucWenSimulationOptions chain_options = o.simulation;
  chain_options.integrator = BoucWenIntegrator::kBenchmarkChain;
  chain_options.input = InputInterpolation::kLinear;  // a model's (the chain ignores it)
  const sysid::MechanicalBoucWen truth({}, chain_options);
  const Eigen::VectorXd chain_u = sysid::internal::ChainInput(u, o.simulation.upsampling);
  auto best_of = [&](auto&& simulate, Eigen::VectorXd* y) {
    double best = 1e300;
    // CPU time (one thread here): the machine is shared, wall time is the load's.
    for (int r = 0; r < repeats; ++r) {
      const std::clock_t t0 = std::clock();
      *y = simulate();
      best = std::min(best, static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC);
    }
    return best;
  };
  Eigen::VectorXd y_old, y_new;
  const double t_old = best_of([&] { return truth.Simulate(u, dt); }, &y_old);
  const double t_new = best_of(
      [&] {
        return sysid::internal::ChainOutput(truth.values(), chain_u, u.size(), dt,
                                            o.simulation.upsampling);
      },
      &y_new);
  fmt::print(
      "simulation samples={} before_cpu_s={:.4f} now_cpu_s={:.4f} ratio={:.2f} identical={}\n",
      u.size(), t_old, t_new, t_old / t_new, y_old == y_new);
  {
    Eigen::VectorXd y;
    Eigen::MatrixXd dy;
    const double t_jac = best_of(
        [&] {
          sysid::internal::ChainOutputSensitivity(truth.values(), chain_u, u.size(), dt,
                                                  o.simulation.upsampling, false, &y, &dy);
          return y;
        },
        &y);
    fmt::print(
        "jacobian samples={} sensitivities_cpu_s={:.4f} simulation_cpu_s={:.4f} "
        "in_simulations={:.2f} central_differences_in_simulations=13\n",
        u.size(), t_jac, t_new, t_jac / t_new);
  }
  sysid::HysteresisFitSummary summary;
  const std::clock_t cpu0 = std::clock();
  const auto model = sysid::FitBoucWen(sysid::BoucWenForm::kMechanical, {tr}, o, &summary);
  const double cpu_s = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
  fmt::print("fit samples={} starts={} threads={} wall_s={:.2f} cpu_s={:.2f} training_rms={:.6e}\n",
             summary.samples, o.starts, o.threads, summary.fit_time_s, cpu_s, summary.training_rms);
  fmt::print("fit_message {}\n", summary.message);
  for (const auto& p : model->parameters())
    fmt::print("parameter name={} value={:.10g} std_error={:.3g}\n", p.name, p.value, p.std_error);
  return 0;
}

int CvodeJacobianCommand(const std::vector<std::string>& args) {
  std::string path;
  sysid::BoucWenSimulationOptions o;
  int repeats = 3;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--input" && i + 1 < args.size()) {
      const std::string& v = args[++i];
      o.input = v == "hold"           ? InputInterpolation::kHold
                : v == "band-limited" ? InputInterpolation::kBandLimited
                                      : InputInterpolation::kLinear;
    } else if (args[i] == "--rtol" && i + 1 < args.size()) {
      o.rtol = std::atof(args[++i].c_str());
    } else if (args[i] == "--repeats" && i + 1 < args.size()) {
      repeats = std::max(1, std::atoi(args[++i].c_str()));
    } else {
      path = args[i];
    }
  }
  if (path.empty()) {
    fmt::print(stderr, "usage: bench_bouc_wen cvode-jacobian REC.csv [--input I] [--rtol R]\n");
    return 1;
  }
  const sysid::Recording rec = sysid::ReadRecording(path);
  const Eigen::VectorXd u = rec.column("u");
  const double dt = rec.column("t")[1] - rec.column("t")[0];
  const sysid::MechanicalBoucWenParameters p;  // the benchmark's true system
  using sysid::internal::SampledInput;
  auto cpu_since = [](std::clock_t t0) {
    return static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  };
  // The input between samples (a band-limited input's table) built once, as the fit does.
  double table = 1e300;
  std::unique_ptr<SampledInput> input;
  for (int r = 0; r < repeats; ++r) {
    input.reset();
    const std::clock_t t0 = std::clock();
    input = std::make_unique<SampledInput>(u, dt, o.input);
    table = std::min(table, cpu_since(t0));
  }
  // The fit's --input auto rule: the table's size and bound without the table.
  double rule = 1e300;
  int rule_grid = 0;
  if (o.input == InputInterpolation::kBandLimited)
    for (int r = 0; r < repeats; ++r) {
      const std::clock_t t0 = std::clock();
      rule_grid = SampledInput::GridPerSample(u, dt);
      rule = std::min(rule, cpu_since(t0));
    }
  // One pass, best CPU of R: `shared` on the table built above, else building its own.
  Eigen::VectorXd y_own, y_shared;
  Eigen::MatrixXd dy_own, dy_shared;
  auto best_cpu = [&](const std::vector<int>& which, bool shared) {
    double best = 1e300;
    for (int r = 0; r < repeats; ++r) {
      Eigen::VectorXd& y = shared ? y_shared : y_own;
      Eigen::MatrixXd& dy = shared ? dy_shared : dy_own;
      const std::clock_t t0 = std::clock();
      if (shared)
        sysid::internal::MechanicalCvode(p, *input, o, which, &y, &dy);
      else
        sysid::internal::MechanicalCvode(p, u, dt, o, which, &y, &dy);
      best = std::min(best, cpu_since(t0));
    }
    return best;
  };
  const double simulation = best_cpu({}, false);
  const double shared_simulation = best_cpu({}, true);
  const bool simulation_same = y_own == y_shared;
  const std::vector<int> six = {0, 1, 2, 3, 5, 6};
  const double jacobian = best_cpu(six, false);
  const double shared_jacobian = best_cpu(six, true);
  const bool jacobian_same = y_own == y_shared && dy_own == dy_shared;
  fmt::print(
      "cvode-jacobian samples={} input={} rtol={:g} simulation_cpu_s={:.4f} "
      "sensitivities_cpu_s={:.4f} in_simulations={:.2f} central_differences_in_simulations=13 "
      "input_grid_per_sample={} input_grid_error_bound={:.3g}\n",
      u.size(), static_cast<int>(o.input), o.rtol, simulation, jacobian, jacobian / simulation,
      input->fine(), input->grid_error_bound());
  fmt::print(
      "cvode-jacobian-shared-input input_table_cpu_s={:.4f} simulation_cpu_s={:.4f} "
      "sensitivities_cpu_s={:.4f} sensitivities_ratio_own/shared={:.3f} identical={}\n",
      table, shared_simulation, shared_jacobian, jacobian / shared_jacobian,
      simulation_same && jacobian_same ? "yes" : "NO");
  const bool rule_same = rule_grid == input->fine();
  if (o.input == InputInterpolation::kBandLimited)
    fmt::print(
        "cvode-jacobian-auto-rule grid_rule_cpu_s={:.4f} grid_per_sample={} "
        "table_cpu_s={:.4f} ratio_table/rule={:.1f} agrees={}\n",
        rule, rule_grid, table, table / rule, rule_same ? "yes" : "NO");
  return simulation_same && jacobian_same && rule_same ? 0 : 1;
}

// The Newmark/trapezoidal step on the linearly interpolated input, m substeps per sample and no
// decimation, against CVODE at rtol 1e-12 (the reference) and at the fit's 1e-9: error and CPU.
int FixedStepCommand(const std::vector<std::string>& args) {
  if (args.empty()) {
    fmt::print(stderr, "usage: bench_bouc_wen fixed-step REC.csv\n");
    return 1;
  }
  const sysid::Recording rec = sysid::ReadRecording(args[0]);
  const Eigen::VectorXd u = rec.column("u");
  const double dt = rec.column("t")[1] - rec.column("t")[0];
  const sysid::MechanicalBoucWenParameters p;  // the benchmark's true system
  sysid::BoucWenSimulationOptions o;
  o.input = InputInterpolation::kLinear;
  auto cpu = [](std::clock_t t0) {
    return static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC;
  };
  o.rtol = 1e-12;
  std::clock_t t0 = std::clock();
  const Eigen::VectorXd ref = sysid::MechanicalBoucWen(p, o).Simulate(u, dt);
  fmt::print("fixed-step method=cvode-rtol1e-12 cpu_s={:.3f} rms_y_m={:.4g} (the reference)\n",
             cpu(t0), std::sqrt(ref.squaredNorm() / static_cast<double>(ref.size())));
  auto report = [&](const std::string& name, double cpu_s, const Eigen::VectorXd& y) {
    fmt::print("fixed-step method={} cpu_s={:.3f} max_error_m={:.3g} rms_error_m={:.3g}\n", name,
               cpu_s, (y - ref).cwiseAbs().maxCoeff(),
               std::sqrt((y - ref).squaredNorm() / static_cast<double>(y.size())));
  };
  o.rtol = 1e-9;
  t0 = std::clock();
  const Eigen::VectorXd cv = sysid::MechanicalBoucWen(p, o).Simulate(u, dt);
  report("cvode-rtol1e-9", cpu(t0), cv);
  const Eigen::Index n = u.size();
  for (int m : {5, 10, 20, 40, 80}) {
    t0 = std::clock();
    Eigen::VectorXd uf((n - 1) * m + 1), yf((n - 1) * m + 1), y(n);
    for (Eigen::Index k = 0; k + 1 < n; ++k)
      for (int j = 0; j < m; ++j) uf[k * m + j] = u[k] + (u[k + 1] - u[k]) * j / double(m);
    uf[(n - 1) * m] = u[n - 1];
    sysid::internal::NewmarkState state;
    sysid::internal::NewmarkBoucWen(p, uf.data(), uf.size(), dt / m, &state, yf.data());
    for (Eigen::Index k = 0; k < n; ++k) y[k] = yf[k * m];
    report(fmt::format("newmark-linear-x{}", m), cpu(t0), y);
  }
  return 0;
}

int ThroughputCommand(const std::vector<std::string>& args) {
  std::string path;
  int repeats = 3;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--repeats" && i + 1 < args.size())
      repeats = std::max(1, std::atoi(args[++i].c_str()));
    else
      path = args[i];
  }
  if (path.empty()) {
    fmt::print(stderr, "usage: bench_bouc_wen throughput REC.csv [--repeats R]\n");
    return 1;
  }
  const sysid::Recording rec = sysid::ReadRecording(path);
  const Eigen::VectorXd u = rec.column("u");
  const double dt = rec.column("t")[1] - rec.column("t")[0];
  auto time = [&](const char* name, const sysid::HysteresisModel& m, const Eigen::VectorXd& in) {
    double best = 1e300, sink = 0;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      sink += m.Simulate(in, dt)[in.size() - 1];
      best = std::min(best,
                      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    fmt::print("throughput method={} samples={} seconds={:.4f} samples_per_s={:.4g} y_end={:.6e}\n",
               name, in.size(), best, static_cast<double>(in.size()) / best, sink / repeats);
  };
  sysid::BoucWenSimulationOptions o;
  o.integrator = BoucWenIntegrator::kBenchmarkChain;
  time("chain-newmark-x20", sysid::MechanicalBoucWen({}, o), u);
  o = {};
  o.rtol = 1e-6;
  o.input = InputInterpolation::kLinear;
  time("cvode-linear-rtol1e-6", sysid::MechanicalBoucWen({}, o), u);
  o.input = InputInterpolation::kHold;
  time("cvode-hold-rtol1e-6", sysid::MechanicalBoucWen({}, o), u);
  sysid::PiezoBoucWenParameters pz;
  pz.d_m_per_v = 2e-7;
  pz.alpha = 0.3;
  pz.beta_per_v = 0.04;
  pz.gamma_per_v = 0.015;
  time("piezo-closed-form", sysid::PiezoBoucWen(pz), u);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + std::min(argc, 2), argv + argc);
  const std::string command = argc > 1 ? argv[1] : "";
  try {
    if (command == "score") return ScoreCommand(args);
    if (command == "throughput") return ThroughputCommand(args);
    if (command == "fit-speed") return FitSpeedCommand(args);
    if (command == "cvode-jacobian") return CvodeJacobianCommand(args);
    if (command == "fixed-step") return FixedStepCommand(args);
  } catch (const sysid::Error& e) {
    fmt::print(stderr, "bench_bouc_wen: {}\n", e.what());
    return 2;
  }
  fmt::print(stderr, "usage: bench_bouc_wen score|fit-speed|fixed-step|throughput ...\n");
  return 1;
}
