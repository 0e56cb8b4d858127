// sysid excite pulses|tracking|waveforms [...] [-o FILE|DIR]: the excitation or reference
// signals of a procedure alone, as CSV, to play on a real rig.
#include <filesystem>
#include <iostream>
#include <optional>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/output_folder.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/stage.hpp"

namespace sysid::cli {
namespace {

struct ExciteOptions {
  std::string what;
  std::string output;
  bool force = false;
  double rate_hz = StageParameters{}.rig.sample_rate_hz;
  std::vector<double> amplitudes_v;  // empty: the procedure's (the paper's ten)
  PulseProcedure pulses;             // on, rest, lead: the flags' defaults are the library's
  std::string set = "training";
  int cycles = 2;
  bool json = false;
};

// --json: one entry per signal written (or, without -o, the signal that would go to stdout).
nlohmann::ordered_json Describe(const Recording& r, const std::string& path,
                                const std::string& waveform) {
  nlohmann::ordered_json f;
  f["path"] = path.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(path);
  if (!waveform.empty()) f["waveform"] = waveform;
  f.update(nlohmann::ordered_json::parse(RecordingShapeToJson(r)));
  return f;
}

void RunExcite(const ExciteOptions& o) {
  // References with -o DIR (no .csv ending): one file per waveform in a new folder, under the
  // same folder rule as pipeline; checked before any work.
  const bool per_waveform = o.what != "pulses" && !o.output.empty() && !EndsWithCsv(o.output);
  std::optional<OutputFolder> folder;
  if (per_waveform) folder.emplace(o.output, o.force, std::vector<std::string>{}, "excite");
  if (!per_waveform) CheckOutputFile(o.output, o.force);
  nlohmann::ordered_json summary;
  summary["what"] = o.what;
  if (o.what == "tracking") summary["set"] = o.set;
  summary["sample_rate_hz"] = o.rate_hz;
  summary["files"] = nlohmann::ordered_json::array();
  auto finish = [&] {
    size_t total = 0;
    for (const auto& f : summary["files"]) total += f["samples"].get<size_t>();
    summary["total_samples"] = total;
    PrintJson(summary);
  };
  Recording r;
  if (o.what == "pulses") {
    PulseProcedure p = o.pulses;
    if (!o.amplitudes_v.empty()) p.amplitudes_v = o.amplitudes_v;
    r = PulseExcitation(p, o.rate_hz);
  } else {
    TrackingProcedure t;
    t.lead_cycles = 0;
    t.kept_cycles = o.cycles;
    const auto waves = o.what == "waveforms" ? PaperTestWaveforms()
                       : o.set == "test"     ? TestGrid()
                                             : TrainingGrid();
    if (per_waveform) {
      folder->Write([&](const std::filesystem::path& dir) {
        for (const auto& w : waves) {
          Recording one = ReferenceSignals({w}, t, o.rate_hz);
          one.metadata.emplace_back("waveform_name", w.name);
          one.metadata.emplace_back("sample_rate_hz", Num(o.rate_hz, 12));
          const std::string name = "waveform_" + w.name + ".csv";
          WriteRecording((dir / name).string(), one);
          summary["files"].push_back(Describe(one, (folder->path() / name).string(), w.name));
        }
      });
      if (o.json) return finish();
      std::cout << "wrote " << waves.size() << " references to " << folder->path().string()
                << "/waveform_<name>.csv\n";
      return;
    }
    r = ReferenceSignals(waves, t, o.rate_hz);
  }
  r.metadata.emplace_back("sample_rate_hz", Num(o.rate_hz, 12));
  if (!o.output.empty()) WriteRecording(o.output, r);
  if (o.json) {
    summary["files"].push_back(Describe(r, o.output, ""));
    return finish();
  }
  if (o.output.empty()) std::cout << FormatRecording(r);
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
  AddOutputOption(cmd, o->output,
                  "CSV file (default: standard output); for tracking and waveforms a name "
                  "without .csv is a new folder with one waveform_<name>.csv per waveform")
      ->type_name("FILE|DIR");
  cmd->add_flag("--force", o->force,
                "replace a folder an earlier sysid excite wrote (one holding .sysid-output), "
                "or an existing -o FILE that sysid did not write");
  cmd->add_option("--rate", o->rate_hz, "sample rate [Hz]")
      ->check(PositiveNumber())
      ->capture_default_str();
  PulseProcedure& pulses = o->pulses;
  // Given, the amplitudes replace the procedure's when the command runs.
  BindField(cmd,
            cmd->add_option("--amplitudes", o->amplitudes_v,
                            "pulse amplitudes [V], in order (default: the paper's ten, "
                            "alternating direction)")
                ->delimiter(','),
            pulses, pulses.amplitudes_v);
  AddFieldOption(cmd, "--on", pulses, pulses.on_s, "pulse length [s]")->check(PositiveNumber());
  AddFieldOption(cmd, "--rest", pulses, pulses.rest_s, "rest after each pulse [s]")
      ->check(NonNegativeNumber());
  AddFieldOption(cmd, "--lead", pulses, pulses.lead_s, "0 V before the first pulse [s]")
      ->check(NonNegativeNumber());
  cmd->add_option("--set", o->set, "tracking grid: training or test")
      ->check(CLI::IsMember({"training", "test"}))
      ->capture_default_str();
  cmd->add_option("--cycles", o->cycles, "reference cycles per waveform [1]")
      ->check(PositiveNumber())
      ->capture_default_str();
  cmd->add_flag("--json", o->json,
                "print one JSON object: what, sample_rate_hz, files (path, waveform, samples, "
                "duration_s, columns, units), total_samples; without -o nothing is written and "
                "path is null");
  cmd->callback([o] { RunExcite(*o); });
}

const bool kRegistered = RegisterCommand(41, &AddExciteCommand);

}  // namespace
}  // namespace sysid::cli
