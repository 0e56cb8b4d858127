// The export's options and default test inputs.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "c_text.hpp"
#include "core/option_rule.hpp"
#include "sysid/deploy.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/io.hpp"

namespace sysid {

using internal::CType;

std::string ToString(ExportPrecision precision) { return CType(precision); }

ExportPrecision ExportPrecisionFromString(const std::string& name) {
  if (name == "double") return ExportPrecision::kDouble;
  if (name == "float") return ExportPrecision::kFloat;
  internal::FailOption("ExportOptions", "precision", "\"" + name + "\"", "\"double\" or \"float\"");
}

void ExportOptions::Validate() const {
  static const char* const kKeywords[] = {
      "auto",     "break",  "case",     "char",   "const",    "continue", "default",
      "do",       "double", "else",     "enum",   "extern",   "float",    "for",
      "goto",     "if",     "inline",   "int",    "long",     "register", "restrict",
      "return",   "short",  "signed",   "sizeof", "static",   "struct",   "switch",
      "typedef",  "union",  "unsigned", "void",   "volatile", "while",    "_Bool",
      "_Complex", "_Imaginary"};
  auto fail = [&](const std::string& rule) {
    internal::FailOption("ExportOptions", "prefix", "\"" + prefix + "\"", rule);
  };
  if (prefix.empty() || prefix.size() > 40) fail("1 to 40 characters");
  if (!(std::isalpha(static_cast<unsigned char>(prefix[0]))))
    fail("a C identifier starting with a letter (names starting with '_' are reserved)");
  for (char c : prefix)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
      fail("a C identifier: letters, digits and '_' only");
  for (const char* k : kKeywords)
    if (prefix == k) fail("not a C99 keyword");
}

ExportVectors DefaultFrictionVectors(double dt_s) {
  const int n = 2000;
  ExportVectors v;
  v.source = "default waveform";
  v.inputs.resize(n, 2);
  // Two periods of the slowest sine over the n samples, whatever dt is, so that v takes both
  // signs; a = dv/dt exactly.
  const double f0 = 1.0 / (0.5 * n * dt_s);
  const double w[3] = {2 * M_PI * f0, 2 * M_PI * 2 * f0, 2 * M_PI * 4 * f0};
  for (int k = 0; k < n; ++k) {
    const double t = k * dt_s;
    // A rest (v = 0) over the middle tenth, so the stop and both restarts are in the vectors.
    const bool rest = k >= 9 * n / 20 && k < 11 * n / 20;
    double vel = 0, acc = 0;
    for (int j = 0; j < 3; ++j) {
      vel += 2e-3 / (j + 1) * std::sin(w[j] * t + j);
      acc += 2e-3 / (j + 1) * w[j] * std::cos(w[j] * t + j);
    }
    v.inputs(k, 0) = rest ? 0.0 : vel;
    v.inputs(k, 1) = rest ? 0.0 : acc;
  }
  return v;
}

ExportVectors DefaultNetworkVectors(const NeuralNetwork& network) {
  const int n = 2000, inputs = network.input_count();
  ExportVectors v;
  v.source = "default waveform";
  v.inputs.resize(n, inputs);
  for (int i = 0; i < inputs; ++i) {
    const ScaledVariable& in = network.inputs()[static_cast<size_t>(i)];
    const double mid = 0.5 * (in.min + in.max), half = 0.6 * (in.max - in.min);
    for (int k = 0; k < n; ++k)
      v.inputs(k, i) = mid + half * std::sin(2 * M_PI * k / (397.0 + 101.0 * i) + i);
  }
  return v;
}

ExportVectors DefaultPiVectors(const PrandtlIshlinskiiModel& model, double dt_s) {
  const int n = 2000;
  const PiParameters& p = model.pi();
  const double mid = 0.5 * (p.input_min_v + p.input_max_v);
  const double half = 0.45 * (p.input_max_v - p.input_min_v);
  Eigen::VectorXd u(n);
  for (int k = 0; k < n; ++k)
    u[k] = mid + half * std::sin(2 * M_PI * k / 400.0) * (0.6 + 0.4 * std::cos(k / 300.0));
  ExportVectors v;
  v.source = "default waveform";
  v.inputs = model.Simulate(u, dt_s);
  return v;
}

ExportVectors DefaultOperatorNetworkVectors(const OperatorNetworkModel& model) {
  const int n = 2000;
  const ScaledVariable& in = model.inverse().network.inputs()[0];
  const double mid = 0.5 * (in.min + in.max), half = 0.6 * (in.max - in.min);
  ExportVectors v;
  v.source = "default waveform";
  v.inputs.resize(n, 1);
  for (int k = 0; k < n; ++k)
    v.inputs(k, 0) = mid + half * std::sin(2 * M_PI * k / 400.0) * (0.6 + 0.4 * std::cos(k / 300.0));
  return v;
}

std::vector<std::string> WriteExportFiles(const ExportResult& result, const std::string& prefix,
                                          const std::string& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw InputError(dir + ": cannot create the folder: " + error.message());
  const std::filesystem::path folder(dir);
  const std::pair<std::string, const std::string*> files[] = {
      {prefix + ".h", &result.header},
      {prefix + ".c", &result.source},
      {prefix + "_check.c", &result.check},
      {prefix + "_vectors.csv", &result.vectors_csv},
      {prefix + "_README.md", &result.readme}};
  std::vector<std::string> written;
  for (const auto& [name, text] : files) {
    written.push_back((folder / name).string());
    WriteFileAtomically(written.back(), *text);
  }
  return written;
}

}  // namespace sysid
