// The closed-loop virtual stage's speed against its loop rate (issue #26): the paper's PI gains,
// PI alone, on the smooth 10 mm profile, at control rates of 0.1 to 20 kHz. For each rate and
// two lengths (1 and 2 cycles) it prints simulated seconds per CPU second and CVODE steps per
// sample; the ratio of the two lengths' speeds shows whether the cost is linear in simulated
// time (1.0 = linear), and every rate's speed is also given as a ratio against the 1 kHz run
// of the same process (the baseline, same machine, same load).
// With --stage (a preset or a stage file, e.g. drive-hysteresis) it also times that stage at its
// own control rate, against the 1 kHz preset virtual-1khz and against the same stage without its
// drive hysteresis (issue #28: the operators' cost and the dynamics they change).
//   bench_stage_rates [--freq HZ] [--rates 100,1000,5000,10000,20000] [--repeats N]
//                     [--stage PRESET|FILE]
#include <fmt/format.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bench_clock.hpp"
#include "sysid/control.hpp"
#include "sysid/stage.hpp"

namespace {

double CpuSeconds() { return sysid::bench::CpuSeconds(CLOCK_PROCESS_CPUTIME_ID); }

using sysid::bench::LoadAverage;

struct Run {
  double simulated_s = 0, cpu_s = 0, steps_per_sample = 0, max_error_m = 0;
};

// The fastest of `repeats` runs (CPU time: the least disturbed by the machine's other load).
Run MeasureStage(const sysid::StageParameters& stage, double freq_hz, int cycles, int repeats) {
  const double rate_hz = stage.rig.sample_rate_hz;
  sysid::SmoothProfileOptions p;
  p.frequency_hz = freq_hz;
  p.cycles = cycles;
  const sysid::PositionReference ref = sysid::MakeStageProfile(stage, p);
  Run best;
  for (int r = 0; r < repeats; ++r) {
    sysid::VirtualStage plant(stage, 1);
    const double c0 = CpuSeconds();
    const sysid::TrackingResult t = sysid::RunClosedLoop(plant, ref);
    const double cpu = CpuSeconds() - c0;
    if (r == 0 || cpu < best.cpu_s) {
      best.cpu_s = cpu;
      best.simulated_s = static_cast<double>(ref.t_s.size()) / rate_hz;
      best.steps_per_sample =
          static_cast<double>(plant.status().steps) / static_cast<double>(ref.t_s.size());
      best.max_error_m = t.max_error_m;
    }
  }
  return best;
}

// The 1 kHz preset (0.3 ms lag, one rate for control and records) at each rate: the rows of
// docs/benchmarks.md were measured on it when it was the default; the default's own 1 kHz
// records could not follow a loop slower than 1 kHz.
Run Measure(double rate_hz, double freq_hz, int cycles, int repeats) {
  sysid::StageParameters stage = sysid::StageParameters::Preset("virtual-1khz");
  stage.rig.sample_rate_hz = rate_hz;
  return MeasureStage(stage, freq_hz, cycles, repeats);
}

std::vector<double> ParseList(const std::string& text) {
  std::vector<double> out;
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) out.push_back(std::atof(item.c_str()));
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  double freq = 0.5;
  int repeats = 3;
  std::vector<double> rates{100, 1000, 5000, 10000, 20000};
  std::string stage_name;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--freq")
      freq = std::atof(argv[i + 1]);
    else if (a == "--rates")
      rates = ParseList(argv[i + 1]);
    else if (a == "--stage")
      stage_name = argv[i + 1];
    else if (a == "--repeats")
      repeats = std::max(1, std::atoi(argv[i + 1]));
    else {
      fmt::print(stderr, "unknown option {}\n", a);
      return 1;
    }
  }
  fmt::print("closed-loop virtual stage (preset virtual-1khz, paper's PI gains, PI alone), "
             "{:g} Hz profile; best of {} runs; load average before: {}\n",
             freq, repeats, LoadAverage());
  const Run base = Measure(1000, freq, 2, repeats);
  const double base_speed = base.simulated_s / base.cpu_s;
  fmt::print("| loop rate [kHz] | simulated s per CPU s, 1 cycle | 2 cycles | linearity (2 / 1) "
             "| vs 1 kHz | CVODE steps per sample | max \\|e\\| [mm] |\n|---|---|---|---|---|---|---|\n");
  for (double rate : rates) {
    const Run one = Measure(rate, freq, 1, repeats), two = Measure(rate, freq, 2, repeats);
    const double s1 = one.simulated_s / one.cpu_s, s2 = two.simulated_s / two.cpu_s;
    fmt::print("| {:g} | {:.3g} | {:.3g} | {:.2f} | {:.3f} | {:.2f} | {:.4f} |\n", rate / 1000, s1,
               s2, s2 / s1, s2 / base_speed, two.steps_per_sample, 1e3 * two.max_error_m);
  }
  if (!stage_name.empty()) {
    const sysid::StageParameters stage = sysid::LoadStage(stage_name);
    sysid::StageParameters plain = stage;
    plain.SetDriveHysteresis({});  // the dead zones and knots back where they were
    const Run with = MeasureStage(stage, freq, 2, repeats);
    const Run without = MeasureStage(plain, freq, 2, repeats);
    const double sw = with.simulated_s / with.cpu_s, so = without.simulated_s / without.cpu_s;
    fmt::print(
        "\n{} ({:g} kHz loop), 2 cycles: {:.3g} simulated s per CPU s, {:.2f} CVODE steps "
        "per sample; vs virtual-1khz at 1 kHz {:.3f}; without its drive hysteresis "
        "{:.3g} simulated s per CPU s (with / without {:.3f})\n",
        stage_name, stage.rig.sample_rate_hz / 1000, sw, with.steps_per_sample, sw / base_speed, so,
        sw / so);
  }
  fmt::print("load average after: {}\n", LoadAverage());
  return 0;
}
