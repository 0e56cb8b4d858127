// sysid info FILE.csv [--json] [--jitter-tolerance R]: summary of a recording.
#include <fmt/format.h>

#include <iostream>
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
  const Recording rec = ReadRecording(o.path);
  const auto t = rec.column("t");
  nlohmann::ordered_json j;
  j["file"] = o.path;
  j["rows"] = rec.rows();
  j["columns"] = rec.names;
  j["duration_s"] = t[t.size() - 1] - t[0];
  j["t_start_s"] = t[0];
  if (rec.rows() >= 2) {
    const SamplingReport s = AnalyzeSampling(t, o.jitter_tolerance);
    j["sample_rate_hz"] = s.sample_rate_hz;
    j["sampling"] = {
        {"nominal_dt_s", s.nominal_dt_s},         {"max_jitter_s", s.max_jitter_s},
        {"rms_jitter_s", s.rms_jitter_s},         {"max_relative_jitter", s.max_relative_jitter},
        {"jitter_tolerance", o.jitter_tolerance}, {"irregular", s.irregular}};
    if (s.irregular)
      j["sampling"]["warning"] = fmt::format(
          "irregular sampling: interval at row {} deviates {:.3g} % from the nominal {:.6g} s; "
          "resample with 'sysid derive --resample HZ' or sysid::Resample",
          s.worst_index + 2, 100 * s.max_relative_jitter, s.nominal_dt_s);
  } else {
    j["sample_rate_hz"] = nullptr;
  }
  nlohmann::ordered_json stats = nlohmann::ordered_json::object();
  for (size_t c = 0; c < rec.names.size(); ++c) {
    const auto col = rec.data.col(static_cast<Eigen::Index>(c));
    stats[rec.names[c]] = {{"min", col.minCoeff()}, {"max", col.maxCoeff()}, {"mean", col.mean()}};
  }
  j["column_stats"] = stats;
  nlohmann::ordered_json meta = nlohmann::ordered_json::object();
  for (const auto& [k, v] : rec.metadata) meta[k] = v;
  j["metadata"] = meta;
  if (o.json) {
    std::cout << j.dump(2) << '\n';
    return;
  }
  std::cout << fmt::format("file        {}\nrows        {}\nduration    {:.6g} s\n", o.path,
                           rec.rows(), j["duration_s"].get<double>());
  if (rec.rows() >= 2) {
    std::cout << fmt::format("sample rate {:.6g} Hz (max jitter {:.3g} s, {:.3g} %)\n",
                             j["sample_rate_hz"].get<double>(),
                             j["sampling"]["max_jitter_s"].get<double>(),
                             100 * j["sampling"]["max_relative_jitter"].get<double>());
    if (j["sampling"].contains("warning"))
      std::cout << "warning     " << j["sampling"]["warning"].get<std::string>() << '\n';
  }
  for (const auto& [k, v] : rec.metadata) std::cout << fmt::format("# {}: {}\n", k, v);
  Table table({"column", "min", "max", "mean"});
  for (const auto& name : rec.names) {
    const auto& s = stats[name];
    table.AddRow({name, Num(s["min"].get<double>()), Num(s["max"].get<double>()),
                  Num(s["mean"].get<double>())});
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
