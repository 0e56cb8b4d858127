// sysid generate pulses|tracking|waveforms|all [--stage STAGE.json] [--seed N] [--format csv|mat]
// [-o DIR]:
// runs the paper's data-collection procedures on the virtual stage and writes recordings.
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/stage.hpp"

namespace sysid::cli {
namespace {

struct GenerateOptions {
  std::string what;
  std::string stage_path;
  std::uint64_t seed = 1;
  std::string out_dir = ".";
  DerivativeOptions derivative_options = TrackingProcedure{}.derivative;  // the procedure's
  std::string derivative = ToString(derivative_options.method);  // parsed into it when run
  std::string format = "csv";  // csv or mat: the recordings' file format
  bool json = false;
  bool force = false;
};

// Refuses (exit 1) before any work when a file generate would replace in `dir` is not one it
// wrote: a user's own recording kept in the folder is never clobbered without --force.
void CheckGenerateTargets(const GenerateOptions& o, const std::vector<std::string>& names) {
  std::error_code ec;
  if (std::filesystem::exists(o.out_dir, ec) && !std::filesystem::is_directory(o.out_dir, ec))
    throw OptionsError(fmt::format("-o {}: exists and is not a folder: generate writes a folder "
                                   "of recordings; choose a folder name",
                                   o.out_dir));
  if (o.force) return;
  for (const auto& name : names) {
    const std::filesystem::path path = std::filesystem::path(o.out_dir) / name;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec) || WrittenBySysid(path)) continue;
    throw OptionsError(fmt::format(
        "-o {}: {} exists and was not written by sysid (it does not start with sysid's "
        "generator mark); refusing to replace it: choose another folder, move the file, or "
        "pass --force",
        o.out_dir, path.string()));
  }
}

void RunGenerate(const GenerateOptions& o) {
  const StageParameters stage =
      o.stage_path.empty() ? StageParameters::Default() : LoadStage(o.stage_path);
  TrackingProcedure tracking;
  tracking.derivative = o.derivative_options;
  tracking.derivative.method = ParseDerivativeMethod(o.derivative);
  tracking.Validate(stage);
  const bool all = o.what == "all";
  const bool mat = o.format == "mat";
  const std::string ext = mat ? ".mat" : ".csv";
  std::vector<std::string> names;
  if (all) names.push_back("stage.json");
  if (all || o.what == "pulses") names.push_back("pulses" + ext);
  if (all || o.what == "tracking") names.insert(names.end(), {"training" + ext, "test" + ext});
  if (all || o.what == "triangle") names.push_back("loop_triangle" + ext);
  if (all || o.what == "waveforms")
    for (const auto& w : PaperTestWaveforms()) names.push_back("waveform_" + w.name + ext);
  CheckGenerateTargets(o, names);
  // Everything is computed before anything is written: an error leaves no partial dataset.
  std::vector<std::pair<std::string, Recording>> files;
  if (all || o.what == "pulses") {
    Progress("generate: pulse test");
    files.emplace_back("pulses" + ext,
                       RunPulseTest(stage, PulseProcedure{}, o.seed, tracking.derivative));
  }
  if (all || o.what == "tracking") {
    Progress("generate: training set");
    files.emplace_back("training" + ext, RunTrackingSet(stage, TrainingGrid(), tracking,
                                                      DeriveSeed(o.seed, 1), "training"));
    Progress("generate: test set");
    files.emplace_back("test" + ext,
                       RunTrackingSet(stage, TestGrid(), tracking, DeriveSeed(o.seed, 2), "test"));
  }
  if (all || o.what == "triangle") {
    Progress("generate: triangle loop");
    files.emplace_back("loop_triangle" + ext, RunTriangleTest(stage, TriangleProcedure{},
                                                            DeriveSeed(o.seed, 3),
                                                            tracking.derivative));
  }
  if (all || o.what == "waveforms") {
    const auto waves = PaperTestWaveforms();
    for (size_t i = 0; i < waves.size(); ++i) {
      Progress("generate: waveform " + waves[i].name);
      files.emplace_back("waveform_" + waves[i].name + ext,
                         TrackWaveform(stage, waves[i], tracking, DeriveSeed(o.seed, 100 + i)));
    }
  }
  ProgressDone();
  std::error_code ec;
  std::filesystem::create_directories(o.out_dir, ec);
  if (ec) throw InputError(o.out_dir + ": cannot create folder: " + ec.message());
  nlohmann::ordered_json j;
  j["stage"] = stage.name;
  j["seed"] = o.seed;
  j["files"] = nlohmann::ordered_json::array();
  Table table({"file", "rows", "duration [s]", "limits"});
  if (all) {
    // The parameters beside the data they produced.
    const std::string path = (std::filesystem::path(o.out_dir) / "stage.json").string();
    WriteStageParameters(path, stage);
    j["files"].push_back({{"path", path}});
  }
  for (auto& [name, rec] : files) {
    const std::string path = (std::filesystem::path(o.out_dir) / name).string();
    if (mat)
      WriteRecordingMat(path, rec,
                        fmt::format("sysid generate: stage {}, procedure {}, seed {}",
                                    rec.meta("stage"), rec.meta("procedure"), rec.meta("seed")));
    else
      WriteRecording(path, rec);
    const double duration = rec.rows() > 0 ? rec.data(rec.rows() - 1, 0) - rec.data(0, 0) : 0;
    // The written file's shape as the library states it (as `excite --json` lists files).
    nlohmann::ordered_json f{{"path", path}, {"limits", rec.meta("limits", "none")}};
    f.update(nlohmann::ordered_json::parse(RecordingShapeToJson(rec)));
    j["files"].push_back(f);
    table.AddRow({path, std::to_string(rec.rows()), Num(duration, 5), rec.meta("limits")});
  }
  if (o.json)
    PrintJson(j);
  else
    std::cout << table.Render();
}

void AddGenerateCommand(CLI::App& app) {
  auto o = std::make_shared<GenerateOptions>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Run the paper's data-collection procedures on the virtual stage and write recordings "
      "(t [s], u [V], x [m], v [m/s], a [m/s^2]) with '#' metadata: pulses -> pulses.csv, "
      "tracking -> training.csv + test.csv, waveforms -> waveform_<name>.csv, triangle -> "
      "loop_triangle.csv (open-loop 6 s triangle, +1.5 / -2.1 V: the voltage-velocity loop), "
      "all -> every one plus stage.json; --format mat writes each recording as NAME.mat "
      "instead");
  cmd->add_option("what", o->what,
                  "which procedure: pulses, tracking, waveforms, triangle or all")
      ->required()
      ->check(CLI::IsMember({"pulses", "tracking", "waveforms", "triangle", "all"}));
  cmd->add_option("--stage", o->stage_path,
                  std::string("stage parameter file (JSON, SI units in the keys) or a preset: ") +
                      cli::kStagePresets + "; datasets/virtual/stage.json is the default's file")
      ->type_name("STAGE.json|PRESET");
  AddSeedOption(cmd, o->seed, "noise seed [integer]; the same seed gives byte-identical files");
  cmd->add_option("-o,--output", o->out_dir,
                  "output folder, created if missing; files of the same names are replaced only "
                  "when generate wrote them (their '#' metadata or MAT header says so) or with "
                  "--force")
      ->type_name("DIR")
      ->capture_default_str();
  cmd->add_option("--format", o->format,
                  "file format of the recordings: csv (with the '#' metadata) or mat (MAT v5, "
                  "one double column vector per column, same base names; the metadata is not "
                  "kept, the header names generate, the stage, the procedure and the seed)")
      ->check(CLI::IsMember({"csv", "mat"}))
      ->capture_default_str();
  cmd->add_flag("--force", o->force,
                "replace files of the same names in the folder that generate did not write "
                "(a user's own pulses.csv)");
  BindField(cmd,
            cmd->add_option("--derivative", o->derivative,
                            "how v [m/s] and a [m/s^2] come from x [m]: central (as the "
                            "paper), butterworth or savgol")
                ->check(CLI::IsMember({"central", "butterworth", "savgol"}))
                ->capture_default_str(),
            o->derivative_options, o->derivative_options.method);
  cmd->add_flag("--json", o->json,
                "print one JSON object: stage, seed, files (path, limits, samples, "
                "duration_s, columns, units)");
  cmd->callback([o] { RunGenerate(*o); });
}

const bool kRegistered = RegisterCommand(40, &AddGenerateCommand);

}  // namespace
}  // namespace sysid::cli
