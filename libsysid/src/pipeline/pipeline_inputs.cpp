#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/pipeline.hpp"

namespace sysid {
namespace fs = std::filesystem;

namespace {

bool StartsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

void RequireComplete(const PipelineInputs& in) {
  std::string missing;
  if (in.pulses.empty()) missing += " pulse recordings (pulses*.csv),";
  if (in.training.empty()) missing += " a training set (training*.csv),";
  if (in.test.empty()) missing += " a test set (test*.csv),";
  if (!missing.empty()) {
    missing.pop_back();
    throw InputError(in.root + ": missing" + missing +
                     "; see 'sysid pipeline --help' for the layout or use a manifest.json");
  }
}

}  // namespace

PipelineInputs PipelineInputs::FromDirectory(const std::string& dir) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) throw InputError(dir + ": not a folder");
  if (fs::exists(fs::path(dir) / "manifest.json"))
    return FromManifest((fs::path(dir) / "manifest.json").string());
  PipelineInputs in;
  in.root = dir;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());  // deterministic order
  for (const auto& p : files) {
    const std::string name = p.filename().string();
    if (p.extension() == ".json" && name == "stage.json") in.stage = p.string();
    if (p.extension() != ".csv") continue;
    if (StartsWith(name, "pulses"))
      in.pulses.push_back(p.string());
    else if (StartsWith(name, "train"))
      in.training = p.string();
    else if (StartsWith(name, "test"))
      in.test = p.string();
    else if (StartsWith(name, "waveform"))
      in.waveforms.push_back(p.string());
    else if (StartsWith(name, "loop"))
      in.loops.push_back(p.string());
  }
  RequireComplete(in);
  return in;
}

PipelineInputs PipelineInputs::FromManifest(const std::string& path) {
  const std::string text = ReadFile(path);
  const nlohmann::json j = internal::ParseJsonText(text, path);
  if (!j.is_object()) throw InputError(path + ": expected a JSON object");
  const fs::path base = fs::path(path).parent_path();
  auto resolve = [&](const nlohmann::json& v, const char* key) {
    if (!v.is_string()) throw InputError(path + ": key '" + key + "': expected a file name");
    return (base / v.get<std::string>()).string();
  };
  PipelineInputs in;
  in.root = path;
  for (const auto& [key, v] : j.items()) {
    if (key == "pulses" || key == "waveforms" || key == "loops") {
      if (!v.is_array()) throw InputError(path + ": key '" + key + "': expected a list");
      auto& list = key == "pulses" ? in.pulses : (key == "waveforms" ? in.waveforms : in.loops);
      for (const auto& f : v) list.push_back(resolve(f, key.c_str()));
    } else if (key == "training") {
      in.training = resolve(v, "training");
    } else if (key == "test") {
      in.test = resolve(v, "test");
    } else if (key == "stage") {
      in.stage = resolve(v, "stage");
    } else if (key == "a3") {
      if (!v.is_number()) throw InputError(path + ": key 'a3': expected a number [m/(s^2 V)]");
      in.a3 = v.get<double>();
    } else if (key != "note" && key[0] != '_') {
      throw InputError(path + ": unknown key '" + key +
                       "' (expected pulses, training, test, waveforms, loops, stage, a3)");
    }
  }
  RequireComplete(in);
  return in;
}

NeuralTrainingOptions PipelineOptions::DefaultTraining() {
  NeuralTrainingOptions t;
  t.max_epochs = 100;
  t.solve_output_layer = true;
  return t;
}

void PipelineOptions::Validate() const {
  auto fail = [](const std::string& field, const std::string& rule) {
    throw OptionsError("PipelineOptions::" + field + ". Violated constraint: " + rule);
  };
  if (!(a3 > 0)) fail("a3 = " + std::to_string(a3), "a3 > 0");
  if (hidden_sizes.empty()) fail("hidden_sizes = {}", "at least one hidden size");
  if (threads < 0) fail("threads = " + std::to_string(threads), "threads >= 0 (0: all cores)");
  if (typical_hidden < 1) fail("typical_hidden", "typical_hidden >= 1");
  if (typical_stride < 1) fail("typical_stride", "typical_stride >= 1");
  if (typical_max_epochs < 0) fail("typical_max_epochs", "typical_max_epochs >= 0");
  for (double f : track_frequencies_hz)
    if (!(f > 0)) fail("track_frequencies_hz", "every frequency > 0");
  delay.Validate();
  training.Validate();
  pi.Validate();
}

}  // namespace sysid
