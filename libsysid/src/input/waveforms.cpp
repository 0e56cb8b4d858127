// Smooth inputs, pulse trains and the paper's named test waveforms.
#include <fmt/format.h>
#include <fmt/ranges.h>

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

constexpr double kPi = 3.14159265358979323846;

void Require(bool ok, const char* owner, const std::string& field, double value,
             const std::string& rule) {
  if (!ok) internal::FailOption(owner, field, value, rule);
}

}  // namespace

SumOfSinesInput::SumOfSinesInput(std::vector<SineComponent> components, double offset_v)
    : components_(std::move(components)), offset_v_(offset_v) {
  Require(std::isfinite(offset_v_), "SumOfSinesInput", "offset_v", offset_v_, "finite");
  for (const auto& c : components_) {
    Require(std::isfinite(c.amplitude_v), "SineComponent", "amplitude_v", c.amplitude_v, "finite");
    Require(std::isfinite(c.frequency_hz) && c.frequency_hz >= 0, "SineComponent", "frequency_hz",
            c.frequency_hz, "finite and >= 0");
    Require(std::isfinite(c.phase_rad), "SineComponent", "phase_rad", c.phase_rad, "finite");
  }
}

double SumOfSinesInput::Value(double t_s) const {
  double u = offset_v_;
  for (const auto& c : components_)
    u += c.amplitude_v * std::sin(2 * kPi * c.frequency_hz * t_s + c.phase_rad);
  return u;
}

double SumOfSinesInput::MaxStepHint() const {
  double f_max = 0;
  for (const auto& c : components_)
    if (c.amplitude_v != 0) f_max = std::max(f_max, c.frequency_hz);
  // 20 steps per period: a threshold crossing of u cannot hide between two root checks.
  return f_max > 0 ? 1.0 / (20 * f_max) : std::numeric_limits<double>::infinity();
}

double PulseTrainSpec::duration_s() const {
  return start_s + repeats * static_cast<double>(amplitudes_v.size()) * (on_s + off_s);
}

PiecewiseConstantInput MakePulseTrain(const PulseTrainSpec& spec) {
  if (spec.amplitudes_v.empty())
    internal::FailOption("PulseTrainSpec", "amplitudes_v", "empty", "at least one amplitude");
  for (size_t i = 0; i < spec.amplitudes_v.size(); ++i)
    Require(std::isfinite(spec.amplitudes_v[i]), "PulseTrainSpec",
            fmt::format("amplitudes_v[{}]", i), spec.amplitudes_v[i], "finite");
  Require(std::isfinite(spec.on_s) && spec.on_s > 0, "PulseTrainSpec", "on_s", spec.on_s,
          "on_s > 0");
  Require(std::isfinite(spec.off_s) && spec.off_s >= 0, "PulseTrainSpec", "off_s", spec.off_s,
          "off_s >= 0");
  Require(spec.repeats >= 1, "PulseTrainSpec", "repeats", spec.repeats, "repeats >= 1");
  // The table has (1 or 2) x repeats x amplitudes rows: bounded by the signal limit before it is
  // allocated (repeats = 2e9 is a typo, not a request for 32 GB), as every generated signal is.
  const double rows =
      (spec.off_s > 0 ? 2.0 : 1.0) * spec.repeats * static_cast<double>(spec.amplitudes_v.size());
  Require(rows <= kMaxSignalSamples, "PulseTrainSpec", "repeats", spec.repeats,
          fmt::format("repeats x amplitudes x (2 with off_s > 0, else 1) <= {:.0f} table rows "
                      "(sysid::kMaxSignalSamples; asked for {:.0f})",
                      kMaxSignalSamples, rows));
  Require(std::isfinite(spec.start_s), "PulseTrainSpec", "start_s", spec.start_s, "finite");
  const double period = spec.on_s + spec.off_s;
  // A zero row before the start makes u = 0 there (a table holds its first value backwards).
  std::vector<double> t{spec.start_s - period}, u{0.0};
  const size_t n = spec.amplitudes_v.size();
  for (int r = 0; r < spec.repeats; ++r) {
    for (size_t i = 0; i < n; ++i) {
      // Multiplied, not accumulated, so that edges land on the decimal times of the spec.
      const double t_on = spec.start_s + static_cast<double>(r * n + i) * period;
      t.push_back(t_on);
      u.push_back(spec.amplitudes_v[i]);
      if (spec.off_s > 0) {
        t.push_back(t_on + spec.on_s);
        u.push_back(0.0);
      }
    }
  }
  if (spec.off_s == 0) {  // the train ends with the last pulse
    t.push_back(spec.duration_s());
    u.push_back(0.0);
  }
  return PiecewiseConstantInput(std::move(t), std::move(u));
}

std::vector<std::string> NamedWaveformNames() {
  return {"paper-pulses", "paper-ladder", "paper-triangle", "paper-sine"};
}

NamedWaveform MakeNamedWaveform(const std::string& name) {
  NamedWaveform w;
  w.name = name;
  if (name == "paper-pulses") {
    PulseTrainSpec spec;  // the defaults are the paper's test
    w.description = "+1.6 V / -2.3 V pulses, 0.4 s on, 0.6 s off, 5 repeats";
    w.duration_s = spec.duration_s();
    w.signal = std::make_shared<PiecewiseConstantInput>(MakePulseTrain(spec));
  } else if (name == "paper-ladder") {
    PulseTrainSpec spec;
    spec.amplitudes_v = {-1.8, 1.3, -2.0, 1.5, -2.1, 1.7, -2.5, 2.0};
    spec.repeats = 1;
    w.description = "pulses of -1.8, 1.3, -2.0, 1.5, -2.1, 1.7, -2.5, 2.0 V, 0.4 s on, 0.6 s off";
    w.duration_s = spec.duration_s();
    w.signal = std::make_shared<PiecewiseConstantInput>(MakePulseTrain(spec));
  } else if (name == "paper-triangle") {
    std::vector<double> t, u;
    const int periods = 2;
    for (int p = 0; p < periods; ++p) {
      const double t0 = 6.0 * p;
      for (auto [dt, value] : {std::pair{0.0, 0.0}, {1.5, 1.5}, {4.5, -2.1}}) {
        t.push_back(t0 + dt);
        u.push_back(value);
      }
    }
    t.push_back(6.0 * periods);
    u.push_back(0.0);
    w.description = "triangle, 6 s period, peaks +1.5 V and -2.1 V, 2 periods";
    w.duration_s = 6.0 * periods;
    w.signal = std::make_shared<PiecewiseLinearInput>(std::move(t), std::move(u));
  } else if (name == "paper-sine") {
    w.description = "u = 1.5 sin(pi/2 t - pi/2) - 0.3 V (0.25 Hz), 2 periods";
    w.duration_s = 8.0;
    w.signal =
        std::make_shared<SumOfSinesInput>(std::vector<SineComponent>{{1.5, 0.25, -kPi / 2}}, -0.3);
  } else {
    std::string known;
    for (const auto& n : NamedWaveformNames()) known += (known.empty() ? "" : ", ") + n;
    internal::FailOption("", "waveform", "'" + name + "'", "one of " + known);
  }
  return w;
}

NamedWaveform PulseTrainWaveform(const PulseTrainSpec& spec) {
  NamedWaveform w;
  w.name = "pulses";
  w.signal = std::make_shared<PiecewiseConstantInput>(MakePulseTrain(spec));
  w.duration_s = spec.duration_s();
  w.description = fmt::format("pulses {} V, {} s on, {} s off, {} repeats",
                              fmt::join(spec.amplitudes_v, "/"), spec.on_s, spec.off_s,
                              spec.repeats);
  return w;
}

}  // namespace sysid
