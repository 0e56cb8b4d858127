// sysid import --column NAME=FILE[:VARIABLE] ... [--rate HZ] [--scale COL=F] [--unit COL=UNIT]
//              [-o REC.csv]
// One CSV recording from columns of MAT, HDF5 and text files, with its provenance as metadata.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/output_file.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"

namespace sysid::cli {
namespace {

struct ImportCliOptions {
  std::vector<std::string> columns;  // NAME=FILE[:VARIABLE]
  double rate_hz = 0;
  std::vector<std::string> scales, units;
  std::string output;
};

// NAME=FILE[:VARIABLE]: FILE is the whole text when that is an existing file, else the shortest
// prefix before a ':' that is one (file names and variable specs may both hold ':').
ImportColumn ParseColumn(const std::string& text) {
  const size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw OptionsError(fmt::format("--column '{}': expected NAME=FILE[:VARIABLE]", text),
                       "--column");
  ImportColumn c;
  c.column = text.substr(0, eq);
  const std::string rest = text.substr(eq + 1);
  std::error_code ec;
  if (std::filesystem::is_regular_file(rest, ec)) {
    c.file = rest;
    return c;
  }
  for (size_t colon = rest.find(':'); colon != std::string::npos;
       colon = rest.find(':', colon + 1)) {
    if (std::filesystem::is_regular_file(rest.substr(0, colon), ec)) {
      c.file = rest.substr(0, colon);
      c.variable = rest.substr(colon + 1);
      return c;
    }
  }
  const size_t colon = rest.find(':');
  c.file = rest.substr(0, colon);  // does not exist: the reader says so
  if (colon != std::string::npos) c.variable = rest.substr(colon + 1);
  return c;
}

// An input named as -o is refused; whether an existing -o may be replaced is the rule of every
// command (cli::CheckOutputFile, run before this): a FIFO or a device is written through and
// never read.
void CheckOutputIsNoInput(const ImportCliOptions& o, const ImportOptions& io) {
  namespace fs = std::filesystem;
  std::error_code ec;
  for (const auto& c : io.columns)
    if (fs::exists(c.file, ec) && fs::exists(o.output, ec) && fs::equivalent(c.file, o.output, ec))
      throw OptionsError(fmt::format("-o {}: is an input (--column {})", o.output, c.column), "-o");
}

void RunImport(const ImportCliOptions& o) {
  ImportOptions io;
  for (const auto& c : o.columns) io.columns.push_back(ParseColumn(c));
  io.rate_hz = o.rate_hz;
  for (const auto& [column, factor] : ParseAssignments(o.scales, "--scale")) {
    const double f = ParseFlagNumber(factor, "--scale " + column);
    if (f == 0) throw OptionsError("--scale " + column + ": factor 0", "--scale");
    io.scales.emplace_back(column, f);
  }
  io.units = ParseAssignments(o.units, "--unit");
  if (!o.output.empty()) CheckOutputIsNoInput(o, io);
  Recording rec = ImportRecording(io);
  if (o.output.empty()) {
    std::cout << FormatRecording(rec);
    return;
  }
  WriteRecordingByExtension(o.output, rec);
  std::cout << fmt::format("wrote {} ({} rows, columns {})\n", o.output, rec.rows(),
                           fmt::join(rec.names, ","));
}

void AddImportCommand(CLI::App& app) {
  auto o = std::make_shared<ImportCliOptions>();
  CLI::App* cmd = app.add_subcommand(
      "import",
      "Build a CSV recording from columns of MAT (v4, v5, v7.3), HDF5 and text files, with "
      "the sources, scales and rate as '# key: value' metadata");
  cmd->add_option("--column", o->columns,
                  "COLUMN=FILE[:VARIABLE]: a MAT variable (data[:,k] for matrix column k, "
                  "1-based like MATLAB), an HDF5 dataset (/group/name), a ControlDesk signal "
                  "(Y(k).Name or Y(k).Data; without a t column t is the export's X.Data), or a text file's column (header name, or number 1.. for headerless "
                  "whitespace/CSV text); repeat per column")
      ->required()
      ->allow_extra_args(false)  // one value per flag, as --var and --scale everywhere
      ->type_name("COLUMN=FILE[:VAR]");
  cmd->add_option("--rate", o->rate_hz, "sample rate [Hz] when no t column is given: t = k / rate")
      ->check(PositiveNumber())
      ->type_name("HZ");
  cmd->add_option("--scale", o->scales, "factor to SI units, COLUMN=FACTOR[,...] (x=1e-6: um)")
      ->allow_extra_args(false)
      ->type_name("MAP");
  cmd->add_option("--unit", o->units,
                  "SI unit written as metadata, COLUMN=UNIT[,...] (default: t s, u V, x m, ...; "
                  "u=N for a force input)")
      ->allow_extra_args(false)
      ->type_name("MAP");
  AddOutputOption(cmd, o->output, "recording CSV (or .mat) to write; stdout when absent");
  GuardOutputFiles(cmd, {{&o->output, "-o"}});
  cmd->callback([o] { RunImport(*o); });
}

const bool kRegistered = RegisterCommand(11, &AddImportCommand);

}  // namespace
}  // namespace sysid::cli
