// 62 simulations written as hex floats (trajectories, events, every counter), to check that a
// change to the simulator or CVODE wrapper leaves results bit-identical: run it with the build
// before and after, then cmp the two files.
//   simulate_dump FILE
#include <cstdio>
#include <random>
#include "sysid/input.hpp"
#include "sysid/model.hpp"
#include "sysid/simulate.hpp"
using namespace sysid;
static void Dump(FILE* f, const char* name, const FrictionModel& m, const InputSignal& in,
                 const SimulationOptions& o) {
  SimulationResult r = Simulate(m, in, o);
  const auto& s = r.summary;
  std::fprintf(f, "case %s term=%d steps=%ld rhs=%ld roots=%ld events=%ld reinit=%ld flag=%s\n",
               name, (int)s.termination, s.steps, s.rhs_evaluations, s.root_evaluations, s.events,
               s.reinitialisations, s.cvode_flag.c_str());
  for (auto& e : r.events) std::fprintf(f, "ev %a %d\n", e.t_s, (int)e.kind);
  const auto& t = r.trajectory;
  for (Eigen::Index i = 0; i < t.t_s.size(); ++i)
    std::fprintf(f, "%a %a %a %a %a\n", t.t_s[i], t.u_v[i], t.x_m[i], t.v_mps[i], t.a_mps2[i]);
}
int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: simulate_dump FILE\n");
    return 1;
  }
  FILE* f = std::fopen(argv[1], "w");
  if (!f) {
    std::fprintf(stderr, "simulate_dump: cannot write %s\n", argv[1]);
    return 1;
  }
  const FrictionModel P = FrictionModel::Paper();
  char name[128];
  for (const auto& wn : NamedWaveformNames()) {
    NamedWaveform w = MakeNamedWaveform(wn);
    for (auto meth : {IntegratorMethod::kAdams, IntegratorMethod::kBdf})
      for (double rtol : {1e-10, 1e-7}) {
        SimulationOptions o;
        o.t_end_s = w.duration_s;
        o.method = meth;
        o.rtol = rtol;
        o.atol = rtol * 1e-2;
        std::snprintf(name, sizeof name, "%s-%s-%g", wn.c_str(), ToString(meth).c_str(), rtol);
        Dump(f, name, P, *w.signal, o);
      }
  }
  PiecewiseConstantInput pulses = MakePulseTrain({});
  {
    FrictionModel m = P; m.tau_s = 0;
    SimulationOptions o; o.t_end_s = 10;
    Dump(f, "tau0", m, pulses, o);
    o.method = IntegratorMethod::kBdf; Dump(f, "tau0-bdf", m, pulses, o);
  }
  {
    FrictionModel m = P; m.a1p = m.a1n = 0;
    SimulationOptions o; o.t_end_s = 10;
    Dump(f, "coulomb", m, pulses, o);
  }
  {
    SimulationOptions o; o.t_end_s = 3; o.history_v_mps = 0.01; o.v0_mps = 0.01;
    Dump(f, "history", P, pulses, o);
    o.history_v_mps = -0.005; o.v0_mps = 0.0; o.x0_m = 0.1; o.t0_s = 0.2;
    Dump(f, "history2", P, pulses, o);
  }
  {
    SimulationOptions o; o.t_end_s = 10; o.max_steps = 500;
    Dump(f, "budget", P, pulses, o);
  }
  {
    SimulationOptions o; o.t_end_s = 10;
    for (int k = 0; k < 3000; ++k) o.output_times_s.push_back(k * 3.3e-3 + 1e-4 * (k % 7));
    Dump(f, "explicit", P, pulses, o);
    o.output_times_s.clear(); o.dt_out_s = 1e-4;
    Dump(f, "fine", P, pulses, o);
    o.dt_out_s = 0.05; o.breakpoint_order = 5; Dump(f, "bp5", P, pulses, o);
    o.breakpoint_order = 1; Dump(f, "bp1", P, pulses, o);
    o.breakpoint_order = 2; o.max_order = 12; Dump(f, "q12", P, pulses, o);
    o.max_order = 2; Dump(f, "q2", P, pulses, o);
  }
  {
    SumOfSinesInput s({{1.5, 0.7, 0.1}, {0.8, 3.1, 1.0}}, 0.2);
    SimulationOptions o; o.t_end_s = 6;
    Dump(f, "sines", P, s, o);
    o.method = IntegratorMethod::kBdf; Dump(f, "sines-bdf", P, s, o);
  }
  {
    auto ramp = MakeTableInput({0, 1, 2, 3, 4, 5}, {0, 2.5, -1, -2.6, 1.9, 0}, InputHold::kLinear);
    SimulationOptions o; o.t_end_s = 5;
    Dump(f, "ramp", P, *ramp, o);
    auto zoh = MakeTableInput({0, 0.5, 1.3, 2.0, 2.05, 3}, {2.0, -2.2, 1.7, 0, 3, -1}, InputHold::kZeroOrder);
    Dump(f, "zoh", P, *zoh, o);
  }
  std::mt19937 rng(20240521);
  std::uniform_real_distribution<double> u(0.8, 1.2);
  for (int k = 0; k < 30; ++k) {  // as bench_simulate's batch, every fifth with BDF
    FrictionModel m = P;
    m.a1p *= u(rng); m.a1n *= u(rng); m.a2p *= u(rng); m.a2n *= u(rng); m.tau_s *= u(rng);
    SimulationOptions o; o.t_end_s = 10;
    if (k % 5 == 4) o.method = IntegratorMethod::kBdf;
    std::snprintf(name, sizeof name, "perturbed-%d", k);
    Dump(f, name, m, pulses, o);
  }
  std::fclose(f);
}
