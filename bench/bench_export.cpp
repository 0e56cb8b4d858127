// ns per step of the library's streaming inverse (the stepper `sysid export` writes as C), for
// bench/run_export.sh beside the exported C's: the same vectors' inputs, cycled, CPU time.
//   bench_export friction|nn|pi MODEL INPUTS.txt STEPS [DT]
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "bench_clock.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/hysteresis_stepper.hpp"
#include "sysid/model.hpp"
#include "sysid/model_stepper.hpp"
#include "sysid/nn.hpp"
#include "sysid/nn_stepper.hpp"

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: bench_export friction|nn|pi MODEL INPUTS.txt STEPS [DT]\n");
    return 2;
  }
  const std::string kind = argv[1];
  const long steps = std::atol(argv[4]);
  const double dt_s = argc > 5 ? std::atof(argv[5]) : 0.0;
  const int inputs = kind == "pi" ? 1 : 2;
  std::vector<double> x;
  std::ifstream in(argv[3]);
  for (double value; in >> value;) x.push_back(value);
  const long rows = static_cast<long>(x.size()) / inputs;
  if (rows == 0 || steps <= 0) return 2;
  double sum = 0, t0 = 0, t1 = 0;
  if (kind == "friction") {
    sysid::FrictionInverseStepper stepper(sysid::ReadModel(argv[2]), dt_s);
    t0 = sysid::bench::CpuSeconds();
    for (long k = 0; k < steps; ++k) {
      const double* row = &x[static_cast<size_t>((k % rows) * 2)];
      sum += stepper.Step(row[0], row[1]);
    }
    t1 = sysid::bench::CpuSeconds();
  } else if (kind == "nn") {
    sysid::NetworkStepper stepper(sysid::ReadNeuralNetwork(argv[2]));
    t0 = sysid::bench::CpuSeconds();
    for (long k = 0; k < steps; ++k) sum += stepper.Step(&x[static_cast<size_t>((k % rows) * 2)]);
    t1 = sysid::bench::CpuSeconds();
  } else {
    const auto model = sysid::ReadHysteresisModel(argv[2]);
    const auto* pi = dynamic_cast<const sysid::PrandtlIshlinskiiModel*>(model.get());
    if (pi == nullptr) return 2;
    sysid::PiInverseStepper stepper(*pi, dt_s);
    t0 = sysid::bench::CpuSeconds();
    for (long k = 0; k < steps; ++k) sum += stepper.Step(x[static_cast<size_t>(k % rows)]);
    t1 = sysid::bench::CpuSeconds();
  }
  std::printf("%.2f ns/step (checksum %.6g)\n", 1e9 * (t1 - t0) / static_cast<double>(steps), sum);
  return 0;
}
