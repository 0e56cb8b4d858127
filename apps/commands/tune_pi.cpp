// sysid tune-pi --model M.json [--loop-rate HZ] [--phase-margin DEG] [--gain-margin DB]
//               [--corner-ratio N] [--extra-delay S] [--u-max V] [--step M] [--sine-amplitude M]
//               [--sine-freq HZ] [--json]
// PI gains for an identified friction model meeting phase and gain margins in both directions
// with the highest crossover, their margins, and their step and sine on the model
// (libsysid: TunePi, SimulatePiBehaviour in sysid/control_tuning.hpp).
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "cli/registry.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct TunePiCli {
  std::string model_path;
  PiTuningOptions tuning;
  PiBehaviourOptions behaviour;
  bool json = false;
};

std::string OrNone(double v, const char* f) {
  return std::isnan(v) ? std::string("none") : fmt::format(fmt::runtime(f), v);
}

void RunTunePi(const TunePiCli& o) {
  const FrictionModel model = ReadModel(o.model_path);
  PiTuningResult r;
  try {
    r = TunePi(model, o.tuning);
  } catch (const OptionsError& e) {
    RethrowWithFlag(e, {{"loop_rate_hz", "--loop-rate"},
                        {"phase_margin_deg", "--phase-margin"},
                        {"gain_margin_db", "--gain-margin"},
                        {"crossover_per_integral_corner", "--corner-ratio"}});
  }
  Progress("tune-pi: step and sine on the model");
  PiBehaviour b;
  try {
    b = SimulatePiBehaviour(model, r.pi, o.behaviour);
  } catch (const OptionsError& e) {
    RethrowWithFlag(e, {{"step_m", "--step"},
                        {"sine_amplitude_m", "--sine-amplitude"},
                        {"sine_frequency_hz", "--sine-freq"}});
  }
  ProgressDone();
  if (o.json) {
    std::cout << TunePiToJson(o.model_path, r, b) << '\n';
    return;
  }
  std::cout << fmt::format(
      "plant: {} (a3 = {:g} m/(s^2 V), tau = {:g} s) at {:g} Hz; targets: phase margin {:g} "
      "deg, gain margin {:g} dB, crossover = {:g} x Ki/Kp\n"
      "PI Kp = {:.5g} V/m, Ki = {:.5g} V/(m s)\n\n",
      o.model_path, model.a3, model.tau_s, o.tuning.loop_rate_hz, o.tuning.phase_margin_deg,
      o.tuning.gain_margin_db, o.tuning.crossover_per_integral_corner, r.pi.kp_v_per_m,
      r.pi.ki_v_per_m_s);
  Table margins({"direction", "a1 [1/s]", "crossover [Hz]", "phase margin [deg]",
                 "gain margin [dB]", "stable"});
  for (const auto& [name, a1, m] : r.margins.directions)
    margins.AddRow({name, Num(a1), OrNone(m.CrossoverHz(), "{:.4g}"),
                    OrNone(m.phase_margin_deg, "{:.2f}"),
                    OrNone(m.GainMarginDb(), "{:.2f}"), m.Stable() ? "yes" : "no"});
  Table behaviour({"on the model", "result"});
  behaviour.AddRow({fmt::format("step {:g} mm: overshoot", 1e3 * b.step.step_m),
                    fmt::format("{:.3g} %", 100 * b.step.overshoot)});
  behaviour.AddRow({"rise 10-90 % [ms]", OrNone(1e3 * b.step.rise_time_s, "{:.4g}")});
  behaviour.AddRow({"settling to 2 % [ms]", OrNone(1e3 * b.step.settling_time_s, "{:.4g}")});
  behaviour.AddRow({"final error [um]", Num(1e6 * b.step.final_error_m, 4)});
  behaviour.AddRow({"step: max |u| [V], saturated samples",
                    fmt::format("{:.4g}, {}", b.step.max_abs_u_v, b.step.saturated_samples)});
  behaviour.AddRow({fmt::format("sine {:g} mm at {:g} Hz: RMS e [um]", 1e3 * b.sine.amplitude_m,
                                b.sine.frequency_hz),
                    Num(1e6 * b.sine.run.rms_error_m, 4)});
  behaviour.AddRow({"sine: max |e| [um]", Num(1e6 * b.sine.run.max_error_m, 4)});
  behaviour.AddRow(
      {"sine: max |u| [V], saturated samples",
       fmt::format("{:.4g}, {}", b.sine.run.max_abs_u_v, b.sine.run.saturated_samples)});
  behaviour.AddRow({fmt::format("hold after the sine: e peak-to-peak [um] (last {:g} s)",
                                b.sine.limit_cycle.window_s),
                    fmt::format("{:.4g} ({})", 1e6 * b.sine.limit_cycle.error_peak_to_peak_m,
                                b.sine.limit_cycle.limit_cycle ? "limit cycle" : "settled")});
  std::cout << margins.Render() << '\n' << behaviour.Render()
            << "\nMargins: the linear loop around steady sliding (sysid margins). Step and sine: "
               "the model simulated with stick-slip, PI alone.\n";
}

void AddTunePiCommand(CLI::App& app) {
  auto o = std::make_shared<TunePiCli>();
  CLI::App* cmd = app.add_subcommand(
      "tune-pi",
      "PI gains for an identified friction model: the highest crossover at which both "
      "directions (a1p, a1n, with tau and the sample-and-hold) meet the phase and gain margins, "
      "the integral corner Ki/Kp a fixed fraction of the crossover; prints the margins and the "
      "gains' step and sine on the model");
  cmd->add_option("--model", o->model_path, "friction model JSON (sysid identify -o)")
      ->required()
      ->check(CLI::ExistingFile)
      ->type_name("M.json");
  cmd->add_option("--loop-rate", o->tuning.loop_rate_hz, "controller sample rate [Hz]")
      ->check(FiniteRange(1e-3, 1e7))
      ->capture_default_str();
  cmd->add_option("--phase-margin", o->tuning.phase_margin_deg, "target phase margin [deg]")
      ->capture_default_str();
  cmd->add_option("--gain-margin", o->tuning.gain_margin_db, "target gain margin [dB]")
      ->capture_default_str();
  cmd->add_option("--corner-ratio", o->tuning.crossover_per_integral_corner,
                  "crossover / (Ki/Kp): the integral corner this far below the crossover")
      ->capture_default_str();
  cmd->add_option("--extra-delay", o->tuning.extra_delay_s,
                  "actuator delay beyond the sample-and-hold [s]")
      ->check(FiniteRange(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--u-max", o->tuning.u_max_v, "output saturation [V] of the step and sine runs")
      ->check(PositiveNumber())
      ->capture_default_str();
  cmd->add_option("--step", o->behaviour.step_m, "step height of the step run [m]")
      ->capture_default_str();
  cmd->add_option("--sine-amplitude", o->behaviour.sine_amplitude_m,
                  "amplitude of the sine run [m]")
      ->capture_default_str();
  cmd->add_option("--sine-freq", o->behaviour.sine_frequency_hz, "frequency of the sine run [Hz]")
      ->capture_default_str();
  cmd->add_flag("--json", o->json,
                "print {\"plant\", \"tuning\": {\"kp_v_per_m\", \"ki_v_per_m_s\", ..., "
                "\"margins\"}, \"behaviour\": {\"step\", \"sine\"}}");
  cmd->callback([o] { RunTunePi(*o); });
}

const bool kRegistered = RegisterCommand(83, &AddTunePiCommand);

}  // namespace
}  // namespace sysid::cli
