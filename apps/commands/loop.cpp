// sysid loop REC.csv [--levels 1.2,-1.75] [--cycles N] [--json]: the voltage-velocity loop of
// an open-loop sweep (the paper's triangle test, or its sinusoids; libsysid: AnalyzeVoltageLoop
// in identify.hpp): the loop at levels, the starts and stops, the enclosed areas and mean widths.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/motion_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/identify.hpp"

namespace sysid::cli {
namespace {

struct LoopCli {
  std::string path;
  VoltageLoopOptions loop;  // the flags' defaults are the library's
  MotionFlags motion;
  MotionOptions motion_options;  // the flags' fields; the rest the library's defaults
  bool json = false;
};

std::string MmOrDash(double v_mps) {
  return std::isnan(v_mps) ? std::string("-") : fmt::format("{:.2f}", 1e3 * v_mps);
}

std::string VOrDash(double u_v) {
  return std::isnan(u_v) ? std::string("never") : fmt::format("{:.3f} V", u_v);
}

void RunLoop(const LoopCli& o) {
  MotionOptions motion = o.motion_options;
  o.motion.ApplyTo(motion);
  const Recording rec = o.motion.ReadRecordings({o.path}).front();
  const VoltageLoop loop = AnalyzeVoltageLoop(rec, o.loop, motion);
  if (o.json) {
    std::cout << ToJson(loop) << '\n';
    return;
  }
  std::cout << fmt::format(
      "{}: u from {:.3f} to {:.3f} V\nstarts forward at {}, backward at {}; stops forward at "
      "{}, backward at {}\n\n",
      o.path, loop.peak_backward_v, loop.peak_forward_v, VOrDash(loop.start_forward_v),
      VOrDash(loop.start_backward_v), VOrDash(loop.stop_forward_v), VOrDash(loop.stop_backward_v));
  Table table({"u [V]", "v, |u| rising [mm/s]", "v, |u| falling [mm/s]", "width [mm/s]",
               "crossings up / down"});
  for (const auto& l : loop.levels)
    table.AddRow({fmt::format("{:+.3f}", l.level_v), MmOrDash(l.v_rising_mps),
                  MmOrDash(l.v_falling_mps), MmOrDash(l.WidthMps()),
                  fmt::format("{} / {}", l.rising_crossings, l.falling_crossings)});
  std::cout << table.Render();
  std::cout << fmt::format(
      "\nenclosed area per period [mV m/s] (mean width [mm/s] = area / span of u while moving): "
      "forward {:.4g} over {:.3f} V ({}), backward {:.4g} over {:.3f} V ({})\n",
      1e3 * loop.area_forward_v_mps, loop.span_forward_v, MmOrDash(loop.MeanWidthForwardMps()),
      1e3 * loop.area_backward_v_mps, loop.span_backward_v,
      MmOrDash(loop.MeanWidthBackwardMps()));
}

void AddLoopCommand(CLI::App& app) {
  auto o = std::make_shared<LoopCli>();
  CLI::App* cmd = app.add_subcommand(
      "loop",
      "The voltage-velocity loop of a slow open-loop sweep (the paper's triangle test, e.g. "
      "sysid generate triangle): velocity [mm/s] where |u| passes each level going up and "
      "going down, the loop's width, the voltages where the stage starts and stops, and the "
      "area the loop encloses per direction (its mean width = area / voltage span)");
  cmd->add_option("file", o->path, "recording CSV: t [s], u [V], x [m] (or a velocity column)")
      ->required()
      ->type_name("REC.csv");
  cmd->add_option("--levels", o->loop.levels_v,
                  "signed voltages to read the loop at [V]; default: six per direction, from 50 "
                  "to 95 % of the peak")
      ->delimiter(',')
      ->type_name("U,...");
  cmd->add_option("--half-window", o->loop.half_window,
                  "velocity at a crossing: mean over +-N samples")
      ->check(CLI::Range(0, 100000))
      ->capture_default_str();
  cmd->add_option("--cycles", o->loop.cycles,
                  "whole periods of u in the recording: the enclosed areas are per period")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  cmd->add_option("--moving-speed", o->loop.moving_speed_mps,
                  "|v| above this is motion, for the start and stop voltages [m/s]")
      ->check(PositiveNumber())
      ->capture_default_str();
  o->motion.Add(cmd, "how v is obtained from x", "central");
  o->motion.Bind(cmd, o->motion_options, o->motion_options);
  cmd->add_flag("--json", o->json,
                "print {\"source\", \"peak_forward_v\", \"peak_backward_v\", \"start_forward_v\", "
                "\"start_backward_v\", \"stop_forward_v\", \"stop_backward_v\", \"area_forward_v_mps\", "
                "\"area_backward_v_mps\", \"span_forward_v\", \"span_backward_v\", "
                "\"mean_width_forward_mps\", \"mean_width_backward_mps\", \"levels\": "
                "[{\"level_v\", \"v_rising_mps\", \"v_falling_mps\", \"width_mps\", "
                "\"rising_crossings\", \"falling_crossings\"}]}");
  cmd->callback([o] { RunLoop(*o); });
}

const bool kRegistered = RegisterCommand(16, &AddLoopCommand);

}  // namespace
}  // namespace sysid::cli
