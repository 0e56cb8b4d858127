// Table inputs: zero-order hold and linear interpolation of (t, u) rows.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/input.hpp"
#include "sysid/io.hpp"

namespace sysid {
namespace {

void ValidateTable(const std::vector<double>& t, const std::vector<double>& u,
                   const std::string& source) {
  if (t.empty()) throw InputError(source + ": input table has no rows");
  if (t.size() != u.size())
    throw InputError(source + ": input table has " + std::to_string(t.size()) + " times but " +
                     std::to_string(u.size()) + " values");
  for (size_t k = 0; k < t.size(); ++k) {
    if (!std::isfinite(t[k]) || !std::isfinite(u[k]))
      throw InputError(source + ": row " + std::to_string(k + 1) +
                       ": t and u must be finite numbers");
    if (k > 0 && !(t[k] > t[k - 1]))
      throw InputError(source + ": row " + std::to_string(k + 1) + ": t = " + std::to_string(t[k]) +
                       " s is not greater than the previous row's " + std::to_string(t[k - 1]) +
                       " s (time must increase strictly)");
  }
}

/// Index k of the row with t_k <= t < t_{k+1} (0 before the table, last after it).
size_t RowAt(const std::vector<double>& t, double t_s) {
  const auto it = std::upper_bound(t.begin(), t.end(), t_s);
  return it == t.begin() ? 0 : static_cast<size_t>(it - t.begin()) - 1;
}

}  // namespace

double InputSignal::MaxStepHint() const { return std::numeric_limits<double>::infinity(); }

PiecewiseConstantInput::PiecewiseConstantInput(std::vector<double> t_s, std::vector<double> u_v)
    : t_(std::move(t_s)), u_(std::move(u_v)) {
  ValidateTable(t_, u_, "PiecewiseConstantInput");
}

double PiecewiseConstantInput::Value(double t_s) const { return u_[RowAt(t_, t_s)]; }

std::vector<double> PiecewiseConstantInput::Edges(double t0_s, double t1_s) const {
  std::vector<double> edges;
  // The first row is no edge (its value also holds before it); equal neighbours are none either.
  for (size_t k = 1; k < t_.size(); ++k)
    if (t_[k] > t0_s && t_[k] <= t1_s && u_[k] != u_[k - 1]) edges.push_back(t_[k]);
  return edges;
}

PiecewiseLinearInput::PiecewiseLinearInput(std::vector<double> t_s, std::vector<double> u_v)
    : t_(std::move(t_s)), u_(std::move(u_v)) {
  ValidateTable(t_, u_, "PiecewiseLinearInput");
}

double PiecewiseLinearInput::Value(double t_s) const {
  if (t_s <= t_.front()) return u_.front();
  if (t_s >= t_.back()) return u_.back();
  const size_t k = RowAt(t_, t_s);
  const double w = (t_s - t_[k]) / (t_[k + 1] - t_[k]);
  return u_[k] + w * (u_[k + 1] - u_[k]);
}

std::vector<double> PiecewiseLinearInput::Edges(double t0_s, double t1_s) const {
  std::vector<double> edges;
  const size_t n = t_.size();
  // u' jumps at a knot where the slopes on either side differ (constant outside the table).
  auto slope = [&](size_t k) {  // slope on [t_{k-1}, t_k]; 0 outside
    return (k == 0 || k >= n) ? 0.0 : (u_[k] - u_[k - 1]) / (t_[k] - t_[k - 1]);
  };
  for (size_t k = 0; k < n; ++k)
    if (t_[k] > t0_s && t_[k] <= t1_s && slope(k) != slope(k + 1)) edges.push_back(t_[k]);
  return edges;
}

InputHold ParseInputHold(const std::string& name) {
  if (name == "zoh") return InputHold::kZeroOrder;
  if (name == "linear") return InputHold::kLinear;
  internal::FailOption("", "hold", "'" + name + "'", "one of zoh, linear");
}

std::unique_ptr<InputSignal> MakeTableInput(std::vector<double> t_s, std::vector<double> u_v,
                                            InputHold hold, const std::string& source) {
  ValidateTable(t_s, u_v, source);
  if (hold == InputHold::kLinear)
    return std::make_unique<PiecewiseLinearInput>(std::move(t_s), std::move(u_v));
  return std::make_unique<PiecewiseConstantInput>(std::move(t_s), std::move(u_v));
}

namespace {
std::unique_ptr<InputSignal> ReadTable(const std::string& path, InputHold hold, double* end_s,
                                       const SourceMapping& mapping) {
  ReadOptions options;
  options.mapping = mapping;
  options.required_columns = {"t", "u"};
  options.any_of_columns = {};
  const Recording rec = ReadRecording(path, options);
  const auto t = rec.column("t");
  const auto u = rec.column("u");
  auto table = MakeTableInput(std::vector<double>(t.data(), t.data() + t.size()),
                              std::vector<double>(u.data(), u.data() + u.size()), hold, path);
  if (end_s != nullptr) *end_s = t[t.size() - 1];
  return table;
}
}  // namespace

std::unique_ptr<InputSignal> ReadInputTable(const std::string& path, InputHold hold,
                                            const SourceMapping& mapping) {
  return ReadTable(path, hold, nullptr, mapping);
}

NamedWaveform ReadInputWaveform(const std::string& path, InputHold hold,
                                const SourceMapping& mapping) {
  NamedWaveform w;
  w.name = path;
  w.signal = ReadTable(path, hold, &w.duration_s, mapping);
  w.description = path + (hold == InputHold::kLinear ? " (linear)" : " (zoh)");
  return w;
}

}  // namespace sysid
