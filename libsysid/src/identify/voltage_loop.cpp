// The voltage-velocity loop of a slow open-loop sweep (the paper's triangle test, its Fig. 3):
// the velocity on the way up and on the way down at given voltages, and where the stage starts
// and stops. A friction-dominated stage shows an asymmetric loop here; a static inverse (the
// analytic one, or a network on v alone) follows only one curve through it.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/json_text.hpp"
#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"

namespace sysid {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double Mean(const std::vector<double>& x) {
  if (x.empty()) return kNaN;
  double s = 0;
  for (double v : x) s += v;
  return s / static_cast<double>(x.size());
}

// Six levels per direction where the stage moves: evenly from just past the start voltage
// (2 % of the peak beyond it) to 95 % of the peak; from 50 % when it never starts.
std::vector<double> DefaultLevels(double peak, double start) {
  std::vector<double> levels;
  if (peak == 0) return levels;
  double lo = 0.5 * peak;
  if (std::isfinite(start) && std::abs(start + 0.02 * peak) < 0.95 * std::abs(peak))
    lo = start + 0.02 * peak;
  for (int i = 0; i < 6; ++i) levels.push_back(lo + (0.95 * peak - lo) * i / 5.0);
  return levels;
}

// Starts and stops: the voltage where |v| crosses the motion threshold, averaged per direction.
void FindStartsAndStops(const Eigen::VectorXd& u, const Eigen::VectorXd& v, double moving_mps,
                        VoltageLoop& loop) {
  std::vector<double> start[2], stop[2];  // [0] forward, [1] backward
  bool moving = std::abs(v[0]) > moving_mps;
  int direction = v[0] > 0 ? 0 : 1;
  for (Eigen::Index k = 1; k < u.size(); ++k) {
    const bool now = std::abs(v[k]) > moving_mps;
    if (now && !moving) {
      direction = v[k] > 0 ? 0 : 1;
      if ((u[k] > 0) == (direction == 0)) start[direction].push_back(u[k]);
    } else if (!now && moving) {
      stop[direction].push_back(u[k]);
    }
    moving = now;
  }
  loop.start_forward_v = Mean(start[0]);
  loop.start_backward_v = Mean(start[1]);
  loop.stop_forward_v = Mean(stop[0]);
  loop.stop_backward_v = Mean(stop[1]);
}

// The enclosed areas: sum of -v du per direction. A closed path of a static map encloses none;
// the steps near rest (|v| <= moving) are left out so that encoder noise at rest, whose sign is
// random, adds nothing.
void FindAreas(const Eigen::VectorXd& u, const Eigen::VectorXd& v, const VoltageLoopOptions& o,
               VoltageLoop& loop) {
  double area[2] = {0, 0}, lo[2] = {kNaN, kNaN}, hi[2] = {kNaN, kNaN};
  for (Eigen::Index k = 0; k + 1 < u.size(); ++k) {
    if (!(std::abs(v[k]) > o.moving_speed_mps && std::abs(v[k + 1]) > o.moving_speed_mps)) continue;
    if ((v[k] > 0) != (v[k + 1] > 0)) continue;
    const int d = v[k] > 0 ? 0 : 1;
    area[d] -= 0.5 * (v[k] + v[k + 1]) * (u[k + 1] - u[k]);
    lo[d] = std::isnan(lo[d]) ? std::min(u[k], u[k + 1]) : std::min({lo[d], u[k], u[k + 1]});
    hi[d] = std::isnan(hi[d]) ? std::max(u[k], u[k + 1]) : std::max({hi[d], u[k], u[k + 1]});
  }
  loop.area_forward_v_mps = area[0] / o.cycles;
  loop.area_backward_v_mps = area[1] / o.cycles;
  loop.span_forward_v = std::isnan(lo[0]) ? 0.0 : hi[0] - lo[0];
  loop.span_backward_v = std::isnan(lo[1]) ? 0.0 : hi[1] - lo[1];
}

}  // namespace

void VoltageLoopOptions::Validate() const {
  constexpr const char* kOwner = "VoltageLoopOptions";
  if (levels_v.size() > 1000)
    internal::FailOption(kOwner, "levels_v", fmt::format("{} values", levels_v.size()),
                         "at most 1000 levels");
  for (size_t i = 0; i < levels_v.size(); ++i)
    if (!std::isfinite(levels_v[i]) || levels_v[i] == 0)
      internal::FailOption(kOwner, fmt::format("levels_v[{}]", i), levels_v[i], "finite and != 0");
  if (half_window < 0 || half_window > 100000)
    internal::FailOption(kOwner, "half_window", half_window, "0 <= half_window <= 100000");
  if (!(moving_speed_mps > 0) || !std::isfinite(moving_speed_mps))
    internal::FailOption(kOwner, "moving_speed_mps", moving_speed_mps,
                         "moving_speed_mps > 0 [m/s]");
  if (cycles < 1 || cycles > 10000)
    internal::FailOption(kOwner, "cycles", cycles, "1 <= cycles <= 10000");
}

double VoltageLoop::MeanWidthForwardMps() const {
  return span_forward_v > 0 ? area_forward_v_mps / span_forward_v : kNaN;
}

double VoltageLoop::MeanWidthBackwardMps() const {
  return span_backward_v > 0 ? area_backward_v_mps / span_backward_v : kNaN;
}

double VoltageLoopLevel::WidthMps() const {
  return (level_v > 0 ? 1.0 : -1.0) * (v_falling_mps - v_rising_mps);
}

VoltageLoop AnalyzeVoltageLoop(const Recording& recording, const VoltageLoopOptions& options,
                               const MotionOptions& motion) {
  options.Validate();
  if (!recording.has("u"))
    throw InputError(recording.source + ": the voltage loop needs a u [V] column");
  const MotionSignals m = ExtractMotion(recording, motion);
  const Eigen::VectorXd u = recording.column("u");
  const Eigen::VectorXd& v = m.v_mps;
  const Eigen::Index n = u.size();
  // A window wider than the recording averages the same samples at every level (width 0).
  if (2 * static_cast<Eigen::Index>(options.half_window) + 1 > n)
    throw InputError(fmt::format("{}: half_window = {} samples: the window (2 x {} + 1) is wider "
                                 "than the recording's {} samples",
                                 recording.source, options.half_window, options.half_window, n));
  VoltageLoop loop;
  loop.source = recording.source;
  loop.peak_forward_v = std::max(u.maxCoeff(), 0.0);
  loop.peak_backward_v = std::min(u.minCoeff(), 0.0);
  FindStartsAndStops(u, v, options.moving_speed_mps, loop);
  FindAreas(u, v, options, loop);
  std::vector<double> levels = options.levels_v;
  if (levels.empty()) {
    levels = DefaultLevels(loop.peak_forward_v, loop.start_forward_v);
    for (double l : DefaultLevels(loop.peak_backward_v, loop.start_backward_v)) levels.push_back(l);
  }
  for (double level : levels) {
    std::vector<double> up, down;
    for (Eigen::Index k = 0; k + 1 < n; ++k) {
      const double a = u[k] - level, b = u[k + 1] - level;
      if ((a < 0) == (b < 0)) continue;
      // The sample nearer the level is the crossing; |u| rises when u moves away from 0.
      const Eigen::Index c = std::abs(a) <= std::abs(b) ? k : k + 1;
      const Eigen::Index lo = std::max<Eigen::Index>(c - options.half_window, 0),
                         hi = std::min<Eigen::Index>(c + options.half_window, n - 1);
      const double mean = v.segment(lo, hi - lo + 1).mean();
      ((level > 0) == (u[k + 1] > u[k]) ? up : down).push_back(mean);
    }
    VoltageLoopLevel l;
    l.level_v = level;
    l.v_rising_mps = Mean(up);
    l.v_falling_mps = Mean(down);
    l.rising_crossings = static_cast<int>(up.size());
    l.falling_crossings = static_cast<int>(down.size());
    loop.levels.push_back(l);
  }
  // The areas are per cycle: more cycles than the sweep crosses any level would divide them by
  // cycles that are not there (--cycles 10000 on one period).
  int most = 0;
  for (const auto& l : loop.levels) most = std::max({most, l.rising_crossings, l.falling_crossings});
  if (most > 0 && options.cycles > most)
    throw InputError(fmt::format("{}: cycles = {}, but the sweep crosses each level at most {} "
                                 "time(s) in one direction: it holds {} cycle(s)",
                                 recording.source, options.cycles, most, most));
  loop.u_v = u;
  loop.v_mps = v;
  return loop;
}

std::string ToJson(const VoltageLoop& loop, int indent) {
  using internal::NumberOrNull;
  nlohmann::ordered_json j;
  j["source"] = loop.source;
  j["peak_forward_v"] = loop.peak_forward_v;
  j["peak_backward_v"] = loop.peak_backward_v;
  j["start_forward_v"] = NumberOrNull(loop.start_forward_v);
  j["start_backward_v"] = NumberOrNull(loop.start_backward_v);
  j["stop_forward_v"] = NumberOrNull(loop.stop_forward_v);
  j["stop_backward_v"] = NumberOrNull(loop.stop_backward_v);
  j["area_forward_v_mps"] = loop.area_forward_v_mps;
  j["area_backward_v_mps"] = loop.area_backward_v_mps;
  j["span_forward_v"] = loop.span_forward_v;
  j["span_backward_v"] = loop.span_backward_v;
  j["mean_width_forward_mps"] = NumberOrNull(loop.MeanWidthForwardMps());
  j["mean_width_backward_mps"] = NumberOrNull(loop.MeanWidthBackwardMps());
  j["levels"] = nlohmann::ordered_json::array();
  for (const auto& l : loop.levels)
    j["levels"].push_back({{"level_v", l.level_v},
                           {"v_rising_mps", NumberOrNull(l.v_rising_mps)},
                           {"v_falling_mps", NumberOrNull(l.v_falling_mps)},
                           {"width_mps", NumberOrNull(l.WidthMps())},
                           {"rising_crossings", l.rising_crossings},
                           {"falling_crossings", l.falling_crossings}});
  return internal::DumpJson(j, indent);
}

}  // namespace sysid
