// Simulator speed: the paper's 10 s pulse train against the h = 1e-6 reference trajectory
// (p1_reference_1ms.csv), at several tolerances, and a batch of parameter sets across threads.
//   bench_simulate [--reference FILE] [--repeats N] [--batch N] [--threads N]
// Prints a table and, last, one "sysid_case ..." line per case and "sysid_seconds=<median wall
// time at the default tolerances>" for bench/run_simulate.sh to form ratios against the peer.
#include <fmt/format.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "bench_clock.hpp"
#include "sysid/input.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/simulate.hpp"

namespace {

double ThreadCpuSeconds() { return sysid::bench::CpuSeconds(); }

using sysid::bench::LoadAverage;

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string reference = "/work/shared/bench/peers/p1_reference_1ms.csv";
  int repeats = 7, batch = 1000, breakpoint_order = sysid::SimulationOptions{}.breakpoint_order;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--reference")
      reference = argv[i + 1];
    else if (a == "--repeats")
      repeats = std::atoi(argv[i + 1]);
    else if (a == "--batch")
      batch = std::atoi(argv[i + 1]);
    else if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--breakpoint-order")
      breakpoint_order = std::atoi(argv[i + 1]);
    else {
      fmt::print(stderr, "unknown option {}\n", a);
      return 1;
    }
  }
  sysid::ReadOptions ro;
  ro.required_columns = {"t", "u", "x", "v"};
  const sysid::Recording ref = sysid::ReadRecording(reference, ro);
  const auto t_ref = ref.column("t");
  const auto x_ref = ref.column("x");
  const auto v_ref = ref.column("v");

  const sysid::FrictionModel model = sysid::FrictionModel::Paper();
  const sysid::PiecewiseConstantInput input = sysid::MakePulseTrain({});
  sysid::SimulationOptions base;
  base.t_end_s = 10.0;
  base.breakpoint_order = breakpoint_order;
  base.output_times_s.assign(t_ref.data(), t_ref.data() + t_ref.size());

  fmt::print("load average before: {}\n", LoadAverage());
  fmt::print(
      "10 s paper pulse train (+1.6/-2.3 V, tau = 3.5 ms), vs h=1e-6 RK4 reference on "
      "the 1 ms grid ({} points); median of {}\n",
      t_ref.size(), repeats);
  fmt::print("{:<8} {:>8} {:>8} {:>10} {:>10} {:>8} {:>7} {:>7} {:>11} {:>11} {:>10}\n", "method",
             "rtol", "atol", "wall [s]", "cpu [s]", "steps", "rhs", "events", "max|dv|", "max|dx|",
             "reinits");
  double default_seconds = 0;
  std::string machine_lines;  // for bench/run_simulate.sh
  struct Case {
    sysid::IntegratorMethod method;
    double rtol, atol;
  };
  const sysid::SimulationOptions defaults;
  const std::vector<Case> cases = {{sysid::IntegratorMethod::kAdams, 1e-6, 1e-8},
                                   {sysid::IntegratorMethod::kAdams, 1e-8, 1e-10},
                                   {sysid::IntegratorMethod::kAdams, defaults.rtol, defaults.atol},
                                   {sysid::IntegratorMethod::kBdf, 1e-8, 1e-10},
                                   {sysid::IntegratorMethod::kBdf, defaults.rtol, defaults.atol}};
  for (const Case& c : cases) {
    sysid::SimulationOptions o = base;
    o.method = c.method;
    o.rtol = c.rtol;
    o.atol = c.atol;
    std::vector<double> walls, cpus;
    sysid::SimulationResult r;
    for (int k = 0; k < repeats; ++k) {
      const auto w0 = std::chrono::steady_clock::now();
      const double c0 = ThreadCpuSeconds();
      r = sysid::Simulate(model, input, o);
      cpus.push_back(ThreadCpuSeconds() - c0);
      walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
    }
    if (!r.summary.IsSolutionUsable()) {
      fmt::print("simulation failed: {}\n", r.summary.message);
      return 3;
    }
    const double dv = (r.trajectory.v_mps - v_ref).cwiseAbs().maxCoeff();
    const double dx = (r.trajectory.x_m - x_ref).cwiseAbs().maxCoeff();
    const double wall = Median(walls);
    const bool is_default = c.method == defaults.method && c.rtol == defaults.rtol;
    if (is_default) default_seconds = wall;
    machine_lines +=
        fmt::format("sysid_case method={} rtol={:g} wall={:.6g} cpu={:.6g} dv={:.3g}\n",
                    sysid::ToString(c.method), c.rtol, wall, Median(cpus), dv);
    fmt::print(
        "{:<8} {:>8.0e} {:>8.0e} {:>10.5f} {:>10.5f} {:>8} {:>7} {:>7} {:>11.2e} {:>11.2e} "
        "{:>10}{}\n",
        sysid::ToString(c.method), c.rtol, c.atol, wall, Median(cpus), r.summary.steps,
        r.summary.rhs_evaluations, r.summary.events, dv, dx, r.summary.reinitialisations,
        is_default ? "  <- defaults" : "");
  }

  // Batch: paper parameters perturbed by up to +-20 % (seeded), across threads.
  std::mt19937 rng(20240521);
  std::uniform_real_distribution<double> f(0.8, 1.2);
  std::vector<sysid::FrictionModel> models(static_cast<size_t>(batch), model);
  for (auto& m : models) {
    m.a1p *= f(rng);
    m.a1n *= f(rng);
    m.a2p *= f(rng);
    m.a2n *= f(rng);
    m.tau_s *= f(rng);
  }
  sysid::SimulationOptions bo;
  bo.t_end_s = 10.0;
  bo.dt_out_s = 1e-3;
  // Per thread: wall time and the thread's own CPU time (on a shared machine a thread may wait
  // for a core; simulations per CPU-second is the per-core rate, whatever the load).
  struct BatchRun {
    double wall_s, cpu_s;
  };
  auto run_batch = [&](int n_threads) {
    std::atomic<int> next{0}, failures{0};
    std::vector<double> cpu(static_cast<size_t>(n_threads), 0.0);
    const auto w0 = std::chrono::steady_clock::now();
    std::vector<std::thread> pool;
    for (int k = 0; k < n_threads; ++k)
      pool.emplace_back([&, k] {
        const double c0 = ThreadCpuSeconds();
        for (int i; (i = next++) < batch;)
          if (!sysid::Simulate(models[static_cast<size_t>(i)], input, bo).summary.IsSolutionUsable())
            ++failures;
        cpu[static_cast<size_t>(k)] = ThreadCpuSeconds() - c0;
      });
    for (auto& th : pool) th.join();
    BatchRun run{std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count(), 0.0};
    for (double c : cpu) run.cpu_s += c;
    fmt::print(
        "batch of {} parameter sets (10 s each, default tolerances), {} thread(s): {:.3f} s wall, "
        "{:.1f} simulations/s, {:.1f} per CPU-second, {} failures\n",
        batch, n_threads, run.wall_s, batch / run.wall_s, batch / run.cpu_s, failures.load());
    return run;
  };
  const BatchRun one = run_batch(1);
  if (threads > 1) {
    const BatchRun many = run_batch(threads);
    fmt::print("batch speed-up on {} threads: {:.2f}x by wall time (load average now: {})\n",
               threads, one.wall_s / many.wall_s, LoadAverage());
  }
  fmt::print("{}sysid_seconds={:.6g}\n", machine_lines, default_seconds);
  return 0;
}
