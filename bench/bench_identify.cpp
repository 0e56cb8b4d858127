// Identification throughput and delay-tuning speed.
//
//   bench_identify [--pulse-recordings 1000] [--p4 PATH/p4_measured.csv] [--repeats 3]
// 1) Pulse identification: IdentifyFromPulses on each of N simulated 4-pulse recordings (4 s at
//    1 kHz, encoder quantum 0.1 um, seeded noise), one thread; prints recordings per second.
// 2) Delay tuning on the SciPy peer's data (p4_measured.csv: t,u,v_meas,v_true; paper model,
//    tau_true = 3.5 ms): TuneDelay with the velocity column v_meas; prints tau, simulations and
//    the median wall time. bench/run_identify.sh runs the peer beside it and prints the ratio.
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "sysid/delay.hpp"
#include "sysid/identify.hpp"
#include "sysid/input.hpp"
#include "sysid/io.hpp"
#include "sysid/simulate.hpp"

namespace {

double Seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A 4-pulse rig recording of `m` (zero-order hold of the sampled input, as a DAC).
sysid::Recording PulseRecording(const sysid::FrictionModel& m, unsigned seed) {
  sysid::PulseTrainSpec spec;
  spec.amplitudes_v = {1.3, -1.8, 2.0, -2.5};
  spec.repeats = 1;
  spec.start_s = 0.0;
  const auto input = sysid::MakePulseTrain(spec);
  const int n = 4001;
  std::vector<double> t(n), u(n);
  for (int k = 0; k < n; ++k) {
    t[static_cast<size_t>(k)] = k * 1e-3;
    u[static_cast<size_t>(k)] = input.Value(k * 1e-3);
  }
  sysid::SimulationOptions o;
  o.t_end_s = t.back();
  o.output_times_s = t;
  const auto r = sysid::Simulate(m, sysid::PiecewiseConstantInput(t, u), o);
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 5e-8);
  sysid::Recording rec;
  rec.source = fmt::format("sim{}", seed);
  rec.names = {"t", "u", "x"};
  rec.data.resize(n, 3);
  for (int k = 0; k < n; ++k) {
    rec.data(k, 0) = t[static_cast<size_t>(k)];
    rec.data(k, 1) = u[static_cast<size_t>(k)];
    rec.data(k, 2) = 1e-7 * std::round((r.trajectory.x_m[k] + noise(rng)) / 1e-7);
  }
  return rec;
}

}  // namespace

int main(int argc, char** argv) {
  int recordings = 1000;
  int repeats = 3;
  std::string p4 = "/work/shared/bench/peers/p4_measured.csv";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--pulse-recordings" && i + 1 < argc)
      recordings = std::atoi(argv[++i]);
    else if (a == "--p4" && i + 1 < argc)
      p4 = argv[++i];
    else if (a == "--repeats" && i + 1 < argc)
      repeats = std::atoi(argv[++i]);
  }
  // 1) Pulse identification throughput. Ten stages (the paper's and scaled variants), each
  //    recorded with different noise.
  std::vector<sysid::Recording> recs;
  std::vector<sysid::FrictionModel> truths;
  for (int i = 0; i < recordings; ++i) {
    sysid::FrictionModel m = sysid::FrictionModel::Paper();
    const double s = 0.8 + 0.04 * (i % 10);
    m.a1p *= s;
    m.a1n *= s;
    if (i < 10) {
      recs.push_back(PulseRecording(m, static_cast<unsigned>(i)));
    } else {
      sysid::Recording r = recs[static_cast<size_t>(i % 10)];
      std::mt19937 rng(static_cast<unsigned>(i));
      std::uniform_int_distribution<int> flip(-1, 1);
      for (Eigen::Index k = 0; k < r.rows(); ++k) r.data(k, 2) += 1e-7 * flip(rng);
      recs.push_back(std::move(r));
    }
    truths.push_back(m);
  }
  sysid::PulseIdentificationOptions po;
  double worst_a1 = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (size_t i = 0; i < recs.size(); ++i) {
    const auto r = sysid::IdentifyFromPulses({recs[i]}, po);
    worst_a1 = std::max(worst_a1, std::abs(r.model.a1p / truths[i].a1p - 1));
  }
  const double t_pulse = Seconds(t0);
  fmt::print(
      "pulse identification: {} recordings (4 pulses, 4001 samples each) in {:.3f} s = "
      "{:.0f} recordings/s (one thread); worst |a1p error| {:.3g} %\n",
      recs.size(), t_pulse, recs.size() / t_pulse, 100 * worst_a1);
  // 2) Delay tuning on the peer's data.
  sysid::ReadOptions ro;
  ro.any_of_columns = {"v_meas"};
  const auto rec = sysid::ReadRecording(p4, ro);
  sysid::DelayTuningOptions d;
  d.motion.velocity_column = "v_meas";
  d.x_tolerance_s = 1e-6;  // the peer's xatol
  sysid::DelayTuningResult res;
  // The median wall time [s] of `repeats` tunings with d as it is; res holds the last.
  auto median_wall = [&] {
    std::vector<double> walls;
    for (int k = 0; k < repeats; ++k) {
      const auto t1 = std::chrono::steady_clock::now();
      res = sysid::TuneDelay(sysid::FrictionModel::Paper(), {rec}, d);
      walls.push_back(Seconds(t1));
    }
    std::sort(walls.begin(), walls.end());
    return walls[walls.size() / 2];
  };
  double wall_s = median_wall();
  fmt::print(
      "delay tuning (sysid): tau = {:.4f} ms (true 3.5 ms, error {:.2f} us), {} "
      "evaluations, {} segment simulations, median wall {:.4f} s\n",
      1e3 * res.tau_s, 1e6 * (res.tau_s - 0.0035), res.evaluations, res.simulations,
      wall_s);
  fmt::print("SYSID_DELAY_WALL_S={:.6f}\n", wall_s);
  // The same without reusing the simulations of repeated pulses (every piece simulated).
  d.segments.reuse_identical_segments = false;
  wall_s = median_wall();
  fmt::print(
      "delay tuning (sysid, no reuse of repeated pulses): tau = {:.4f} ms, {} segment "
      "simulations, median wall {:.4f} s\n",
      1e3 * res.tau_s, res.simulations, wall_s);
  fmt::print("SYSID_DELAY_NOREUSE_WALL_S={:.6f}\n", wall_s);
  return 0;
}
