// The virtual piezo stack's speed (docs/piezo_stack.md, "Speed"): open-loop samples per CPU
// second of the stack (rdpi hysteresis, 3 creep elements) with either integrator (CVODE
// restarted every sample; the exact zero-order-hold discretisation) against the virtual stage
// (velocity source, CVODE BDF with stick-slip) stepped at the same 10 kHz control rate for the
// same number of samples in the same process: the ratios are the stack's speed in units of the
// stage's, and the exact step's against CVODE's (with the largest difference of their x).
//   bench_stack [--samples N] [--repeats R]
#include <fmt/format.h>
#include <time.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "bench_clock.hpp"
#include "sysid/stack.hpp"
#include "sysid/stage.hpp"

namespace {

double CpuSeconds() { return sysid::bench::CpuSeconds(CLOCK_PROCESS_CPUTIME_ID); }

template <class Run>
double BestRate(long samples, int repeats, Run run) {
  double best = 0;
  for (int r = 0; r < repeats; ++r) {
    const double c0 = CpuSeconds();
    run();
    const double cpu = CpuSeconds() - c0;
    best = std::max(best, static_cast<double>(samples) / cpu);
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  long samples = 100000;
  int repeats = 3;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    if (flag == "--samples")
      samples = std::atol(argv[i + 1]);
    else if (flag == "--repeats")
      repeats = std::atoi(argv[i + 1]);
    else {
      fmt::print(stderr, "usage: bench_stack [--samples N] [--repeats R]\n");
      return 1;
    }
  }
  if (samples < 100 || samples > 100000000 || repeats < 1 || repeats > 100) {
    fmt::print(stderr, "bench_stack: --samples in [100, 1e8], --repeats in [1, 100]\n");
    return 1;
  }
  fmt::print("load average {}\n", sysid::bench::LoadAverage());
  const sysid::StackParameters stack = sysid::StackParameters::Default();
  const double rate = stack.rig.control_rate_hz;
  // A 10 Hz sine over most of the stack's drive, and a +-2 V 1 Hz sine on the stage (it slides,
  // reverses and sticks): each plant in its working regime.
  Eigen::VectorXd u_stack(samples), u_stage(samples);
  for (long k = 0; k < samples; ++k) {
    const double t = static_cast<double>(k) / rate;
    u_stack[k] = 50 - 45 * std::cos(2 * M_PI * 10 * t);
    u_stage[k] = 2.0 * std::sin(2 * M_PI * 1 * t);
  }
  sysid::StageParameters stage = sysid::StageParameters::Default();
  stage.rig.sample_rate_hz = rate;
  sysid::StackParameters exact = stack;
  exact.integrator.method = sysid::StackMethod::kExact;
  sysid::StackRun cvode_run, exact_run;
  const double stack_rate =
      BestRate(samples, repeats, [&] { cvode_run = sysid::RunStackOpenLoop(stack, u_stack, 1); });
  const double exact_rate =
      BestRate(samples, repeats, [&] { exact_run = sysid::RunStackOpenLoop(exact, u_stack, 1); });
  const double stage_rate =
      BestRate(samples, repeats, [&] { sysid::RunOpenLoop(stage, u_stage, 1); });
  fmt::print("stack cvode  {:.4g} samples/s ({} samples at {:g} Hz, best of {})\n", stack_rate,
             samples, rate, repeats);
  fmt::print(
      "stack exact  {:.4g} samples/s; max |x_exact - x_cvode| = {:.3g} m of max |x| {:.3g} m\n",
      exact_rate, (exact_run.x_true_m - cvode_run.x_true_m).cwiseAbs().maxCoeff(),
      cvode_run.x_true_m.cwiseAbs().maxCoeff());
  fmt::print("x_end exact {:.9e} m, cvode {:.9e} m (true x before the last sample)\n",
             exact_run.x_true_m[samples - 1], cvode_run.x_true_m[samples - 1]);
  fmt::print("stage        {:.4g} samples/s (same samples and rate)\n", stage_rate);
  fmt::print("ratio stack cvode/stage {:.2f}\n", stack_rate / stage_rate);
  fmt::print("ratio stack exact/stage {:.2f}\n", exact_rate / stage_rate);
  fmt::print("ratio stack exact/cvode {:.1f}\n", exact_rate / stack_rate);
  fmt::print("real time factor of the stack: cvode {:.1f}x, exact {:.0f}x\n", stack_rate / rate,
             exact_rate / rate);
  fmt::print("load average {}\n", sysid::bench::LoadAverage());
  return 0;
}
