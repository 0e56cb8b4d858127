#include "cli/input_flags.hpp"

#include "cli/common.hpp"
#include "sysid/error.hpp"

namespace sysid::cli {

void InputFlags::Add(CLI::App* cmd) {
  auto* input = cmd->add_option("--input", input_path, "input table CSV with columns t [s], u [V]")
                    ->type_name("U.csv");
  cmd->add_option("--hold", hold,
                  "how the table holds between rows: zoh (u_k on [t_k, t_k+1)) or linear")
      ->check(CLI::IsMember({"zoh", "linear"}))
      ->capture_default_str();
  auto* pulses_option =
      cmd->add_option("--pulses", pulses, "pulse-train amplitudes [V], in order, e.g. 1.6,-2.3")
          ->delimiter(',')
          ->excludes(input);
  cmd->add_option("--pulse-on", pulse_train.on_s, "pulse length [s]")
      ->check(PositiveNumber())
      ->capture_default_str();
  cmd->add_option("--pulse-off", pulse_train.off_s, "rest after each pulse [s]")
      ->check(NonNegativeNumber())
      ->capture_default_str();
  cmd->add_option("--pulse-repeats", pulse_train.repeats, "repeats of the amplitude list [count]")
      ->check(PositiveNumber())
      ->capture_default_str();
  cmd->add_option("--pulse-start", pulse_train.start_s, "time of the first pulse [s]")
      ->capture_default_str();
  recording.Add(cmd, /*window=*/false);
  std::string names;
  for (const auto& n : NamedWaveformNames()) names += (names.empty() ? "" : ", ") + n;
  cmd->add_option("--waveform", waveform, "a named test waveform of the paper: " + names)
      ->excludes(input)
      ->excludes(pulses_option);
}

NamedWaveform InputFlags::Choose() const {
  const int given = !input_path.empty() + !pulses.empty() + !waveform.empty();
  if (given != 1)
    throw OptionsError("give exactly one input: --input U.csv, --pulses A[,A...] or --waveform NAME");
  if (!input_path.empty())
    return ReadInputWaveform(input_path, ParseInputHold(hold), recording.Mapping());
  if (!pulses.empty()) {
    PulseTrainSpec spec = pulse_train;
    spec.amplitudes_v = pulses;
    return PulseTrainWaveform(spec);
  }
  NamedWaveform w = MakeNamedWaveform(waveform);
  w.description = w.name + ": " + w.description;
  return w;
}

}  // namespace sysid::cli
