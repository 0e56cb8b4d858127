// sysid margins --model M.json [--kp KP] [--ki KI] [--rate HZ] [--extra-delay S] [--json]:
// the PI gains' linear gain and phase margins on an identified rough model, per direction
// (libsysid: RoughModelPiMargins in sysid/control.hpp).
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/pi_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/control.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct MarginsCli {
  std::string model_path;
  PiOptions pi;  // the flags' defaults are the library's (the paper's gains)
  double rate_hz = 1000;
  double extra_delay_s = 0;
  bool json = false;
};

void RunMargins(const MarginsCli& o) {
  PiOptions pi = o.pi;
  pi.sample_time_s = 1 / o.rate_hz;
  const PiMarginsReport r = AnalyzePiMargins(ReadModel(o.model_path), pi, o.extra_delay_s);
  if (o.json) {
    std::cout << ToJson(r) << '\n';
    return;
  }
  std::cout << fmt::format(
      "PI Kp = {:g} V/m, Ki = {:g} V/(m s) at {:g} Hz on a3 / (s (s + a1 e^(-s tau))), "
      "a3 = {:g} m/(s^2 V), tau = {:g} s, extra delay {:g} s\n\n",
      pi.kp_v_per_m, pi.ki_v_per_m_s, o.rate_hz, r.a3_mps2_per_v, r.tau_s, o.extra_delay_s);
  auto num = [](double v, const char* f) {
    return std::isnan(v) ? std::string("none") : fmt::format(fmt::runtime(f), v);
  };
  Table table({"direction", "a1 [1/s]", "crossover [rad/s]", "phase margin [deg]",
               "phase crossover [rad/s]", "gain margin", "stable"});
  for (const auto& [name, a1, m] : r.directions)
    table.AddRow({name, Num(a1), num(m.crossover_rad_s, "{:.4g}"),
                  num(m.phase_margin_deg, "{:.2f}"), num(m.phase_crossover_rad_s, "{:.4g}"),
                  num(m.gain_margin, "{:.3f}"), m.Stable() ? "yes" : "no"});
  std::cout << table.Render()
            << "\nLinear, around steady sliding: stick-slip, the dead zone and saturation are "
               "outside it.\n";
}

void AddMarginsCommand(CLI::App& app) {
  auto o = std::make_shared<MarginsCli>();
  CLI::App* cmd = app.add_subcommand(
      "margins",
      "Gain and phase margins of the PI position loop on an identified model, per direction: "
      "L = (Kp + Ki Ts / (1 - z^-1)) a3 e^(-s (Ts/2 + extra)) / (s (s + a1 e^(-s tau))), the "
      "linear loop around steady sliding (crossover [rad/s], phase margin [deg], gain margin)");
  cmd->add_option("--model", o->model_path, "friction model JSON (sysid identify -o)")
      ->required()
      ->check(CLI::ExistingFile)
      ->type_name("M.json");
  PiOptions& pi = o->pi;
  AddPiGainOptions(cmd, pi, "PI ");
  // The rate sets sample_time_s = 1 / rate when the command runs.
  BindField(cmd,
            cmd->add_option("--rate", o->rate_hz, "controller sample rate [Hz]")
                ->check(FiniteRange(1e-3, 1e7))
                ->capture_default_str(),
            pi, pi.sample_time_s);
  cmd->add_option("--extra-delay", o->extra_delay_s,
                  "actuator delay beyond the sample-and-hold, e.g. a driver lag [s]")
      ->check(FiniteRange(0.0, 10.0))
      ->capture_default_str();
  cmd->add_flag("--json", o->json,
                "print {\"kp_v_per_m\", \"ki_v_per_m_s\", \"sample_time_s\", \"extra_delay_s\", "
                "\"tau_s\", \"a3_mps2_per_v\", \"directions\": [{\"direction\", \"a1_per_s\", "
                "\"crossover_rad_s\", \"crossover_hz\", \"phase_margin_deg\", "
                "\"phase_crossover_rad_s\", \"gain_margin\", \"gain_margin_db\", \"stable\"}]}");
  cmd->callback([o] { RunMargins(*o); });
}

const bool kRegistered = RegisterCommand(82, &AddMarginsCommand);

}  // namespace
}  // namespace sysid::cli
