// sysid info FILE.csv [--json] [--jitter-tolerance R]: summary of a recording.
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "cli/registry.hpp"
#include "sysid/io.hpp"
#include "sysid/motion.hpp"

namespace sysid::cli {
namespace {

struct InfoOptions {
  std::string path;
  bool json = false;
  double jitter_tolerance = MotionOptions{}.max_relative_jitter;
};

void RunInfo(const InfoOptions& o) {
  const Recording rec = ReadRecording(o.path);  // its source is o.path
  for (const auto& w : UnitSanityWarnings(rec)) std::cerr << "sysid info: warning: " << w << '\n';
  const std::string text = RecordingSummaryToJson(rec, o.jitter_tolerance);
  if (o.json) {
    std::cout << text;
    return;
  }
  const auto j = nlohmann::json::parse(text);
  std::cout << fmt::format("file        {}\nrows        {}\nduration    {:.6g} s\n", o.path,
                           rec.rows(), j["duration_s"].get<double>());
  if (j.contains("sampling")) {
    const auto& s = j["sampling"];
    std::cout << fmt::format("sample rate {:.6g} Hz (max jitter {:.3g} s, {:.3g} %)\n",
                             j["sample_rate_hz"].get<double>(), s["max_jitter_s"].get<double>(),
                             100 * s["max_relative_jitter"].get<double>());
    if (s.contains("warning")) std::cout << "warning     " << s["warning"].get<std::string>() << '\n';
  }
  for (const auto& [k, v] : rec.metadata) std::cout << fmt::format("# {}: {}\n", k, v);
  Table table({"column", "min", "max", "mean"});
  for (const auto& name : rec.names) {
    const auto& c = j["column_stats"][name];
    table.AddRow({name, Num(c["min"].get<double>()), Num(c["max"].get<double>()),
                  Num(c["mean"].get<double>())});
  }
  std::cout << '\n' << table.Render();
}

void AddInfoCommand(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Summarise a recording: rows, columns, duration, sampling rate and jitter, "
      "metadata, per-column ranges (SI units)");
  cmd->add_option("file", o->path, "recording CSV: columns t [s], u [V], x [m] or v [m/s]")
      ->required()
      ->type_name("FILE.csv");
  cmd->add_flag("--json", o->json,
                "print one JSON object (rows, columns, duration_s, sample_rate_hz, sampling, "
                "column_stats, metadata)");
  cmd->add_option("--jitter-tolerance", o->jitter_tolerance,
                  "relative sampling jitter above which sampling is reported irregular "
                  "[dimensionless]")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->callback([o] { RunInfo(*o); });
}

const bool kRegistered = RegisterCommand(10, &AddInfoCommand);

}  // namespace
}  // namespace sysid::cli
