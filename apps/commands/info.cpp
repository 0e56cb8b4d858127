// sysid info FILE.csv|FILE.mat|FILE.h5 [--json] [--jitter-tolerance R] [--var ...]: summary of
// a recording, or the variables of a MAT/HDF5 file when no mapping is given.
#include <fmt/format.h>

#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/motion.hpp"

namespace sysid::cli {
namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
  MotionOptions motion;  // its sampling check (max_relative_jitter) only: info derives nothing
  RecordingFlags recording;
};

// One table cell or line from file data: ForTerminal's escapes, and line breaks too (a MAT or
// HDF5 variable name may hold an escape sequence or a newline).
std::string Cell(std::string_view s) {
  std::string out;
  for (const char c : ForTerminal(s)) out += c == '\n' ? std::string("\\x0A") : std::string(1, c);
  return out;
}

// A MAT/HDF5 file without a mapping: its variables, so the user can write one.
void ListFileVariables(const InfoOptions& o) {
  const std::vector<VariableInfo> vars = ListVariables(o.path);
  if (o.json) {
    std::cout << VariableListToJson(o.path, vars);
    return;
  }
  std::cout << fmt::format("file        {} ({})\nvariables   {}\n\n", Cell(o.path),
                           DescribeFileFormat(o.path), vars.size());
  Table table({"variable", "class", "dims", "length", "min", "max"});
  for (const auto& v : vars) {
    std::string dims;
    for (const auto d : v.dims) dims += (dims.empty() ? "" : " x ") + std::to_string(d);
    if (v.complex) dims += " complex";
    const bool range = v.numeric_vector && v.length > 0;
    table.AddRow({Cell(v.name), Cell(v.type), dims,
                  v.numeric_vector ? std::to_string(v.length) : "",
                  range ? Num(v.min) : "", range ? Num(v.max) : ""});
  }
  std::cout << table.Render();
}

void RunInfo(const InfoOptions& o) {
  const ReadOptions ro = o.recording.Apply({});
  if (ro.mapping.empty() && DetectFileFormat(o.path) != FileFormat::kText) {
    ListFileVariables(o);
    return;
  }
  const Recording rec = ReadRecording(o.path, ro);  // its source is o.path
  for (const auto& w : UnitSanityWarnings(rec)) std::cerr << "sysid info: warning: " << w << '\n';
  const std::string text = RecordingSummaryToJson(rec, o.motion.max_relative_jitter);
  if (o.json) {
    std::cout << text;
    return;
  }
  const auto j = nlohmann::json::parse(text);
  // JSON writes a number that is not finite as null: printed as "-", never a type error.
  const auto number = [](const nlohmann::json& v) {
    return v.is_number() ? v.get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  std::cout << fmt::format("file        {}\nrows        {}\nduration    {:.6g} s\n", Cell(o.path),
                           rec.rows(), number(j["duration_s"]));
  if (j.contains("sampling")) {
    const auto& s = j["sampling"];
    std::cout << fmt::format("sample rate {:.6g} Hz (max jitter {:.3g} s, {:.3g} %)\n",
                             number(j["sample_rate_hz"]), number(s["max_jitter_s"]),
                             100 * number(s["max_relative_jitter"]));
    if (s.contains("warning")) std::cout << "warning     " << s["warning"].get<std::string>() << '\n';
  }
  for (const auto& [k, v] : rec.metadata) std::cout << fmt::format("# {}: {}\n", k, v);
  Table table({"column", "min", "max", "mean"});
  for (const auto& name : rec.names) {
    const auto& c = j["column_stats"][name];
    table.AddRow({Cell(name), Num(number(c["min"])), Num(number(c["max"])),
                  Num(number(c["mean"]))});
  }
  std::cout << '\n' << table.Render();
}

void AddInfoCommand(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Summarise a recording: rows, columns, duration, sampling rate and jitter, "
      "metadata, per-column ranges (SI units); for a MAT or HDF5 file without --var, list its "
      "variables (name, class, dims, length, min, max)");
  cmd->add_option("file", o->path,
                  "recording CSV (columns t [s], u [V], x [m] or v [m/s]), or a MAT/HDF5 file")
      ->required()
      ->type_name("FILE");
  cmd->add_flag("--json", o->json,
                "print one JSON object (rows, columns, duration_s, sample_rate_hz, sampling, "
                "column_stats, metadata)");
  AddFieldOption(cmd, "--jitter-tolerance", o->motion, o->motion.max_relative_jitter,
                 "relative sampling jitter above which sampling is reported irregular "
                 "[dimensionless]")
      ->check(PositiveNumber());
  o->recording.Add(cmd);
  cmd->callback([o] { RunInfo(*o); });
}

const bool kRegistered = RegisterCommand(10, &AddInfoCommand);

}  // namespace
}  // namespace sysid::cli
