#include <algorithm>
#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "core/json_text.hpp"
#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/pipeline.hpp"

namespace sysid {
namespace fs = std::filesystem;

namespace {

bool StartsWith(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

// A recording the folder layout picks up: CSV, MAT or HDF5 by its extension (any case). The
// file's first bytes still decide how it is read (ReadRecording).
bool IsRecordingFile(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".csv" || ext == ".mat" || ext == ".h5" || ext == ".hdf5";
}

// Pulse recordings are the least a stage needs; the tracking sets come as a pair (pulses alone
// run the identification part, PipelineInputs::PulsesOnly).
void RequireComplete(const PipelineInputs& in) {
  std::string missing;
  if (in.pulses.empty()) missing += " pulse recordings (pulses*.csv|mat|h5),";
  if (!in.training.empty() && in.test.empty()) missing += " a test set (test*.csv|mat|h5),";
  if (in.training.empty() && !in.test.empty()) missing += " a training set (training*.csv|mat|h5),";
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
  const fs::path manifest = fs::path(dir) / "manifest.json";
  if (fs::exists(manifest, ec)) return FromManifest(manifest.string());
  if (ec && ec != std::errc::no_such_file_or_directory)
    throw InputError(manifest.string() + ": " + ec.message());
  PipelineInputs in;
  in.root = dir;
  std::vector<fs::path> files;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path& p = it->path();
    const bool used = IsRecordingFile(p) || p.filename() == "stage.json";
    std::error_code entry_ec;
    const bool regular = it->is_regular_file(entry_ec);
    // A link loop or a dangling link among the files the pipeline would read is an error
    // naming it; among other files it is ignored like any non-file.
    if (entry_ec && used)
      throw InputError(p.string() + ": cannot read: " + entry_ec.message() +
                       (entry_ec == std::errc::too_many_symbolic_link_levels
                            ? " (a symbolic link loop)"
                            : ""));
    if (regular) files.push_back(p);
  }
  if (ec) throw InputError(dir + ": cannot list the folder: " + ec.message());
  std::sort(files.begin(), files.end());  // deterministic order
  std::vector<std::string> recordings;
  for (size_t i = 0; i < files.size(); ++i) {
    const fs::path& p = files[i];
    const std::string name = p.filename().string();
    if (name == "stage.json") in.stage = p.string();
    if (!IsRecordingFile(p)) continue;
    // training.csv beside training.mat is one recording twice (a conversion left behind):
    // which one to use is the user's call, not the sort order's.
    for (size_t j = 0; j < i; ++j)
      if (IsRecordingFile(files[j]) && files[j].stem() == p.stem())
        throw InputError(dir + ": " + files[j].filename().string() + " and " + name +
                         " are the same recording in two formats; keep one, or name the files "
                         "in a manifest.json");
    recordings.push_back(p.string());
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
  // No trace of a stage's pulse test or tracking sets: a stack's recordings (t, u, x).
  if (in.pulses.empty() && in.training.empty() && in.test.empty() && !recordings.empty()) {
    PipelineInputs stack;
    stack.root = dir;
    stack.stack = recordings;
    return stack;
  }
  RequireComplete(in);
  return in;
}

PipelineInputs PipelineInputs::FromManifest(const std::string& path) {
  const std::string text = ReadFile(path);
  // Every complaint names FILE:LINE:COL of the key (internal::JsonDocument), exit 2.
  const internal::JsonDocument doc(text, path);
  const internal::JsonNode root = doc.Root();
  const fs::path base = fs::path(path).parent_path();
  auto resolve = [&](const internal::JsonNode& v) {
    return (base / v.String(/*non_empty=*/true)).string();
  };
  PipelineInputs in;
  in.root = path;
  if (root.json().is_object() && root.Has("stack")) {
    // A stack's manifest names its recordings and nothing of a stage's.
    root.ExpectObject({"stack"}, {"note"});
    const internal::JsonNode list = root.Get("stack");
    list.ExpectArray();
    for (size_t i = 0; i < list.Size(); ++i) in.stack.push_back(resolve(list.Element(i)));
    if (in.stack.empty()) list.Expected("a non-empty list of recordings (t, u, x)");
    return in;
  }
  root.ExpectObject({"pulses", "training", "test", "waveforms", "loops", "stage", "a3", "stack"},
                    {"note"});
  for (const char* key : {"pulses", "waveforms", "loops"}) {
    if (!root.Has(key)) continue;
    const internal::JsonNode list = root.Get(key);
    list.ExpectArray();
    auto& out = std::string(key) == "pulses" ? in.pulses
                : std::string(key) == "waveforms" ? in.waveforms
                                                  : in.loops;
    for (size_t i = 0; i < list.Size(); ++i) out.push_back(resolve(list.Element(i)));
  }
  if (root.Has("training")) in.training = resolve(root.Get("training"));
  if (root.Has("test")) in.test = resolve(root.Get("test"));
  if (root.Has("stage")) in.stage = resolve(root.Get("stage"));
  if (root.Has("a3")) in.a3 = root.Get("a3").Number(internal::NumberRule::Positive());
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
  auto fail = [](const std::string& field, double value, const std::string& rule) {
    internal::FailOption("PipelineOptions", field, value, rule);
  };
  if (!(a3 > 0)) fail("a3", a3, "a3 > 0");
  if (hidden_sizes.empty())
    internal::FailOption("PipelineOptions", "hidden_sizes", "{}", "at least one hidden size");
  if (threads < 0) fail("threads", threads, "threads >= 0 (0: all cores)");
  if (typical_hidden < 1) fail("typical_hidden", typical_hidden, "typical_hidden >= 1");
  if (typical_stride < 1) fail("typical_stride", typical_stride, "typical_stride >= 1");
  if (typical_max_epochs < 0)
    fail("typical_max_epochs", typical_max_epochs, "typical_max_epochs >= 0");
  if (!(pulse_fit_fraction > 0 && pulse_fit_fraction <= 1))
    fail("pulse_fit_fraction", pulse_fit_fraction, "0 < pulse_fit_fraction <= 1");
  for (size_t i = 0; i < track_frequencies_hz.size(); ++i)
    if (!(track_frequencies_hz[i] > 0))
      fail("track_frequencies_hz[" + std::to_string(i) + "]", track_frequencies_hz[i],
           "every frequency > 0");
  delay.Validate();
  training.Validate();
  pi.Validate();
}

}  // namespace sysid
