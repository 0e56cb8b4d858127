// The output-error refinement's standard errors, s^2 (J^T J)^-1 at the optimum, against the
// spread of the refined parameters over many noise seeds (Monte-Carlo).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "identify/simulated_recording.hpp"
#include "sysid/delay.hpp"
#include "sysid/input.hpp"
#include "sysid/simulate.hpp"
#include "support/standard_error_tally.hpp"

// About 100 refinements of ~50 simulations each (20 s on one core): hidden from the default
// run ("[.slow]") and registered in CTest with the label "slow" (tests/CMakeLists.txt).
TEST_CASE("refinement: standard errors match the Monte-Carlo spread over noise seeds",
          "[delay][refine][uncertainty][.slow]") {
  // Short pulses (never settled: the transient carries a1, a3 and tau) on a stage with
  // direction-dependent friction; the recorded velocity is the simulated one plus white
  // N(0, sigma^2) noise, the output-error model's own noise assumption.
  const auto truth = sysid::test::MakeModel(20.0, 25.0, 1.0, 1.5, 4.0, 0.002);
  sysid::PulseTrainSpec spec;
  spec.amplitudes_v = {0.8, -0.9, 1.2, -1.3, 1.6, -1.7};
  spec.on_s = 0.1;
  spec.off_s = 0.15;
  spec.repeats = 1;
  spec.start_s = 0.05;
  const auto input = sysid::MakePulseTrain(spec);
  const double rate = 1000.0, duration = spec.duration_s() + 0.05;
  const auto n = static_cast<size_t>(std::round(duration * rate)) + 1;
  std::vector<double> tk(n), uk(n);
  for (size_t k = 0; k < n; ++k) {
    tk[k] = static_cast<double>(k) / rate;
    uk[k] = input.Value(tk[k]);
  }
  sysid::SimulationOptions so;
  so.t_end_s = tk.back();
  so.output_times_s = tk;
  so.rtol = 1e-10;
  so.atol = 1e-13;
  const auto sim = sysid::Simulate(truth, sysid::PiecewiseConstantInput(tk, uk), so);
  REQUIRE(sim.summary.IsSolutionUsable());
  const auto& tr = sim.trajectory;
  const double sigma_v = 2e-3;  // [m/s] about 1 % of the fastest pulse's speed
  sysid::RefineOptions ro;
  ro.detection.min_duration_s = 0.05;
  ro.threads = 2;
  // Seeds: each refinement is ~50 simulations of the record (the agreement required is the
  // tally's, 4 / sqrt(2 (N - 1))).
  const int seeds = 100;
  std::mt19937 rng(31);
  std::normal_distribution<double> noise(0.0, sigma_v);
  const size_t np = 6;
  sysid::test::StandardErrorTally tally({"a1p", "a1n", "a2p", "a2n", "a3", "tau"});
  for (int s = 0; s < seeds; ++s) {
    sysid::Recording rec;
    rec.source = "mc";
    rec.names = {"t", "u", "v"};
    rec.data.resize(tr.t_s.size(), 3);
    for (Eigen::Index k = 0; k < tr.t_s.size(); ++k)
      rec.data.row(k) << tr.t_s[k], tr.u_v[k], tr.v_mps[k] + noise(rng);
    const auto r = sysid::RefineOutputError(truth, {rec}, ro);
    REQUIRE(r.names.size() == np);
    const double p[] = {r.model.a1p, r.model.a1n, r.model.a2p, r.model.a2n, r.model.a3,
                        r.model.tau_s};
    for (size_t i = 0; i < np; ++i) tally.Add(i, p[i], r.std_error[static_cast<Eigen::Index>(i)]);
  }
  tally.CheckAgreement();
}
