// A downstream program (docs/api.md): identify the paper's pulse table, simulate the pulse
// train with the identified model, compare a plateau with its closed form.
#include <sysid/identify.hpp>
#include <sysid/report.hpp>
#include <sysid/simulate.hpp>

#include <cmath>
#include <cstdio>

int main(int argc, char** argv) {
  if (argc < 2) return 2;
  // 1. The paper's pulse table: a1p, a1n, a2p, a2n by least squares with a3 = 6.
  const auto fit = sysid::FitPulseTable(sysid::ReadPulseTable(argv[1]));
  sysid::FrictionModel model = fit.model;
  model.tau_s = 0.0035;  // [s] the paper's delay of the viscous term
  std::printf("a1p=%.4f a1n=%.4f a2p=%.4f a2n=%.4f\n", model.a1p, model.a1n, model.a2p,
              model.a2n);

  // 2. Simulate the paper's pulse train (+1.6 V / -2.3 V, 0.4 s on, 0.6 s off).
  const sysid::PiecewiseConstantInput input = sysid::MakePulseTrain({});
  sysid::SimulationOptions options;
  options.t_end_s = 2.0;  // [s]
  const sysid::SimulationResult sim = sysid::Simulate(model, input, options);
  if (!sim.summary.IsSolutionUsable()) {  // numerical trouble is reported, not thrown
    std::fprintf(stderr, "%s\n", sim.summary.message.c_str());
    return 3;
  }

  // 3. The plateau of the first pulse is the closed-form steady state (a3 u - a2p) / a1p.
  const double v = sim.trajectory.v_mps[390], ref = model.SteadyVelocity(1.6);
  std::printf("v(0.39 s) = %.6f m/s, closed form %.6f m/s\n", v, ref);
  // 4. The report target links too: a markdown table of the result.
  std::printf("%s", sysid::MarkdownTable({"v [m/s]", "closed form [m/s]"},
                                         {{std::to_string(v), std::to_string(ref)}}).c_str());
  return std::abs(v - ref) < 1e-6 ? 0 : 1;  // settled to 1e-6 m/s after 0.39 s (e^-40)
}
