#include "cli/recording_flags.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "cli/common.hpp"
#include "sysid/error.hpp"

namespace sysid::cli {

void RecordingFlags::Add(CLI::App* cmd, bool window) {
  cmd->add_option("--var", vars,
                  "column mapping COLUMN=VARIABLE[,...] for MAT/HDF5 files or renamed CSV "
                  "columns: t=time,u=/group/volts,x=data[:,2] (matrix column k 1-based, like "
                  "MATLAB; a dSPACE ControlDesk signal by its Y(k).Name, quoted or not, or "
                  "Y(k).Data, its time "
                  "X.Data); one value per flag, repeatable")
      ->allow_extra_args(false)  // the recordings that follow stay positionals
      ->type_name("MAP");
  cmd->add_option("--rate", rate_hz,
                  "sample rate [Hz] of recordings without a time column: t = k / rate")
      ->check(PositiveNumber())
      ->type_name("HZ");
  cmd->add_option("--scale", scales,
                  "factor to SI units per column, COLUMN=FACTOR[,...]: x=1e-6 for a sensor in um; "
                  "one value per flag, repeatable")
      ->allow_extra_args(false)
      ->type_name("MAP");
  if (!window) return;
  cmd->add_option("--t-start", t_start_s,
                  "keep only t >= S [s] of every recording read (t as recorded, not shifted to "
                  "0); an error when S lies outside the recording")
      ->type_name("S");
  cmd->add_option("--t-end", t_end_s,
                  "keep only t <= S [s] of every recording read; an error when S lies outside "
                  "the recording or the window holds fewer than 2 samples")
      ->type_name("S");
}

std::vector<std::pair<std::string, std::string>> ProvenanceOf(
    const Recording& rec, const std::vector<std::string>& columns) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [key, value] : rec.metadata) {
    bool keep = key == "sample_rate_hz" || key == "crop_s";
    for (const auto& c : columns) keep = keep || key == "source." + c || key == "scale." + c;
    if (keep) out.emplace_back(key, value);
  }
  return out;
}

std::vector<std::pair<std::string, std::string>> ParseAssignments(
    const std::vector<std::string>& items, const std::string& flag) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& item : items) {
    int depth = 0;
    size_t start = 0;
    for (size_t i = 0; i <= item.size(); ++i) {
      if (i < item.size() && item[i] == '[') ++depth;
      if (i < item.size() && item[i] == ']') --depth;
      if (i < item.size() && !(item[i] == ',' && depth == 0)) continue;
      const std::string part = item.substr(start, i - start);
      start = i + 1;
      const size_t eq = part.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == part.size())
        throw OptionsError(fmt::format("{} '{}': expected COLUMN=VALUE", flag, part), flag);
      out.emplace_back(part.substr(0, eq), part.substr(eq + 1));
    }
  }
  for (size_t i = 0; i < out.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (out[i].first == out[j].first)
        throw OptionsError(fmt::format("{}: column '{}' given twice", flag, out[i].first), flag);
  return out;
}

double ParseFlagNumber(const std::string& text, const std::string& flag) {
  double v = 0;
  const char* b = text.data();
  const char* e = text.data() + text.size();
  if (b != e && *b == '+') ++b;
  const auto [ptr, ec] = std::from_chars(b, e, v);
  if (text.empty() || ec != std::errc() || ptr != e || !std::isfinite(v))
    throw OptionsError(fmt::format("{}: expected a finite number, found '{}'", flag, text), flag);
  return v;
}

SourceMapping RecordingFlags::Mapping() const {
  SourceMapping m;
  m.variables = ParseAssignments(vars, "--var");
  m.rate_hz = rate_hz;
  for (const auto& [bound, flag] : {std::pair{t_start_s, "--t-start"}, {t_end_s, "--t-end"}})
    if (bound && !std::isfinite(*bound))
      throw OptionsError(fmt::format("{} {}: expected a finite time [s]", flag, *bound), flag);
  if (t_start_s && t_end_s && !(*t_start_s < *t_end_s))
    throw OptionsError(fmt::format("--t-start {} --t-end {}: expected the start before the end",
                                   *t_start_s, *t_end_s),
                       "--t-start");
  m.t_start_s = t_start_s;
  m.t_end_s = t_end_s;
  for (const auto& [column, factor] : ParseAssignments(scales, "--scale")) {
    const double f = ParseFlagNumber(factor, "--scale " + column);
    if (f == 0) throw OptionsError("--scale " + column + ": factor 0", "--scale");
    m.scales.emplace_back(column, f);
  }
  return m;
}

ReadOptions RecordingFlags::Apply(ReadOptions options) const {
  options.mapping = Mapping();
  return options;
}

}  // namespace sysid::cli
