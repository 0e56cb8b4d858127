// sysid excite pulses|tracking|waveforms [...] [-o FILE]: the excitation or reference signals
// of a procedure alone, as CSV, to play on a real rig.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

namespace sysid::cli {
namespace {

struct ExciteOptions {
  std::string what;
  std::string output;
  double rate_hz = 1000;
  std::vector<double> amplitudes_v;
  double on_s = 0.4, rest_s = 0.3, lead_s = 0.1;
  std::string set = "training";
  int cycles = 2;
};

void RunExcite(const ExciteOptions& o) {
  Recording r;
  if (o.what == "pulses") {
    PulseProcedure p;
    if (!o.amplitudes_v.empty()) p.amplitudes_v = o.amplitudes_v;
    p.on_s = o.on_s;
    p.rest_s = o.rest_s;
    p.lead_s = o.lead_s;
    r = PulseExcitation(p, o.rate_hz);
  } else {
    TrackingProcedure t;
    t.lead_cycles = 0;
    t.kept_cycles = o.cycles;
    const auto waves = o.what == "waveforms" ? PaperTestWaveforms()
                       : o.set == "test"     ? TestGrid()
                                             : TrainingGrid();
    r = ReferenceSignals(waves, t, o.rate_hz);
  }
  r.metadata.emplace_back("sample_rate_hz", Num(o.rate_hz, 12));
  if (o.output.empty())
    std::cout << FormatRecording(r);
  else
    WriteRecording(o.output, r);
}

void AddExciteCommand(CLI::App& app) {
  auto o = std::make_shared<ExciteOptions>();
  CLI::App* cmd = app.add_subcommand(
      "excite",
      "Emit a procedure's excitation (pulses: t [s], u [V]) or position references (tracking, "
      "waveforms: t [s], waveform, x_ref [m], v_ref [m/s], a_ref [m/s^2]) as CSV, to play on "
      "a real stage");
  cmd->add_option("what", o->what, "pulses, tracking or waveforms")
      ->required()
      ->check(CLI::IsMember({"pulses", "tracking", "waveforms"}));
  AddOutputOption(cmd, o->output, "CSV file (default: standard output)");
  cmd->add_option("--rate", o->rate_hz, "sample rate [Hz] (default 1000)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--amplitudes", o->amplitudes_v,
                  "pulse amplitudes [V], in order (default: the paper's ten, alternating "
                  "direction)")
      ->delimiter(',');
  cmd->add_option("--on", o->on_s, "pulse length [s] (default 0.4)")->check(CLI::PositiveNumber);
  cmd->add_option("--rest", o->rest_s, "rest after each pulse [s] (default 0.3)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--lead", o->lead_s, "0 V before the first pulse [s] (default 0.1)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--set", o->set, "tracking grid: training or test (default training)")
      ->check(CLI::IsMember({"training", "test"}));
  cmd->add_option("--cycles", o->cycles, "reference cycles per waveform [1] (default 2)")
      ->check(CLI::PositiveNumber);
  cmd->callback([o] { RunExcite(*o); });
}

const bool kRegistered = RegisterCommand(41, &AddExciteCommand);

}  // namespace
}  // namespace sysid::cli
