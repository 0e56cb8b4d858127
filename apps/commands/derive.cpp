// sysid derive REC.csv [--method central|butterworth|savgol] [--cutoff HZ] [--order N]
//                      [--window N] [--decimate K] [--resample HZ] [-o OUT.csv] [--json]
// Velocity v [m/s] and acceleration a [m/s^2] from the position x [m] of a recording.
#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_containers.hpp"
#include "sysid/motion.hpp"
#include "sysid/signal.hpp"

namespace sysid::cli {
namespace {

struct DeriveCliOptions {
  std::string path;
  std::string output;
  std::string method;  // set from derivative.method
  DerivativeOptions derivative;  // the flags' defaults are the library's
  std::optional<int> order;      // the method's order field when given
  int decimate = 1;
  std::optional<double> resample_hz;
  MotionOptions motion;  // its sampling check (max_relative_jitter) only: the filter is above
  bool json = false;
  RecordingFlags recording;
};

void RunDerive(const DeriveCliOptions& o) {
  DerivativeOptions opt = o.derivative;
  opt.method = ParseDerivativeMethod(o.method);
  if (o.order && opt.method == DerivativeMethod::kSavitzkyGolay) opt.savgol_order = *o.order;
  if (o.order && opt.method != DerivativeMethod::kSavitzkyGolay) opt.butterworth_order = *o.order;
  if (o.decimate < 1)
    throw OptionsError("", "--decimate", std::to_string(o.decimate), "--decimate >= 1");

  Recording rec =
      ReadRecording(o.path, o.recording.Apply(ReadOptions{{"t", "u", "x"}, {}, true, {}}));
  if (rec.rows() < 2)
    throw InputError(fmt::format("{}: {} row; derive needs a sampled signal", o.path, rec.rows()));
  if (o.resample_hz) {
    try {
      rec = Resample(rec, *o.resample_hz);
    } catch (const OptionsError& e) {
      RethrowWithFlag(e, {{"rate_hz", "--resample"}});
    }
  }
  double dt_s = UniformSampleInterval(rec, o.motion.max_relative_jitter);
  try {
    dt_s = AddDerivatives(rec, dt_s, opt, o.decimate);
  } catch (const OptionsError& e) {
    RethrowWithFlag(e,
                    {{"cutoff_hz", "--cutoff"},
                     {"butterworth_order", "--order"},
                     {"savgol_order", "--order"},
                     {"savgol_window", "--window"},
                     {"factor", "--decimate"},
                     {"decimate", "--decimate"}},
                    "--method");
  } catch (const InputError& e) {
    throw InputError(o.path + ": " + e.what());
  }
  std::string settings = DescribeDerivative(opt, o.decimate);
  if (o.resample_hz) settings += fmt::format(" resample_hz={}", *o.resample_hz);
  rec.metadata.emplace_back("derive", settings);

  if (!o.output.empty()) WriteRecordingByExtension(o.output, rec);
  if (o.json) {
    // The library's summary with the command's files in front.
    nlohmann::ordered_json j;
    j["file"] = o.path;
    if (!o.output.empty()) j["output"] = o.output;
    j.update(nlohmann::ordered_json::parse(DerivedRecordingToJson(rec, dt_s, opt)));
    PrintJson(j);
  } else if (o.output.empty()) {
    std::cout << FormatRecording(rec);
  } else {
    std::cout << fmt::format("{}: {} rows at {:.6g} Hz, {} -> {}\n", o.path, rec.rows(), 1.0 / dt_s,
                             settings, o.output);
  }
}

void AddDeriveCommand(CLI::App& app) {
  auto o = std::make_shared<DeriveCliOptions>();
  o->method = ToString(o->derivative.method);
  CLI::App* cmd = app.add_subcommand(
      "derive",
      "Velocity v [m/s] and acceleration a [m/s^2] from the position x [m] of a recording: "
      "central differences, zero-phase Butterworth + central differences, or Savitzky-Golay; "
      "optional anti-aliased decimation. Writes t, u, x, the other columns, v, a");
  cmd->add_option("file", o->path, "recording CSV: columns t [s], u [V], x [m]")
      ->required()
      ->type_name("REC.csv");
  AddOutputOption(cmd, o->output,
                  "write the recording with v [m/s] and a [m/s^2] added (replaced if present) "
                  "to FILE (MAT v5 when it ends in .mat); without -o the CSV goes to stdout");
  GuardOutputFiles(cmd, {{&o->output, "-o"}});
  // --method is parsed into method, and --order into the method's order, when the command runs.
  DerivativeOptions& d = o->derivative;
  BindField(cmd,
            cmd->add_option("--method", o->method,
                            "central: (x[k+1]-x[k-1])/(2 dt), as the paper; butterworth: "
                            "zero-phase Butterworth low-pass of x then central differences; "
                            "savgol: Savitzky-Golay fit derivative")
                ->check(CLI::IsMember({"central", "butterworth", "savgol"}))
                ->capture_default_str(),
            d, d.method);
  AddFieldOption(cmd, "--cutoff", d, d.cutoff_hz,
                 "butterworth: cut-off frequency [Hz], 0 < HZ < Nyquist of the (decimated) "
                 "rate")
      ->type_name("HZ");
  CLI::Option* order =
      cmd->add_option("--order", o->order,
                      fmt::format("butterworth: filter order [1, {}]; savgol: polynomial order "
                                  "[2, min({}, window - 1)] [dimensionless]",
                                  kMaxButterworthOrder, kMaxSavitzkyGolayOrder))
          ->type_name("N")
          ->default_str(fmt::format("{} (butterworth), {} (savgol)", d.butterworth_order,
                                    d.savgol_order));
  BindField(cmd, order, d, d.butterworth_order);
  BindField(cmd, order, d, d.savgol_order);
  AddFieldOption(cmd, "--window", d, d.savgol_window,
                 fmt::format("savgol: window length [samples], odd, in [3, {}] (at 1 kHz, 21 "
                             "samples = 20 ms)",
                             kMaxSavitzkyGolayWindow))
      ->type_name("N");
  cmd->add_option("--decimate", o->decimate,
                  fmt::format("keep every K-th sample after a zero-phase order-{} Butterworth "
                              "anti-alias low-pass at {} x the new Nyquist frequency (all "
                              "columns but t) [samples, >= 1]",
                              kDecimateButterworthOrder, kDecimateCutoffFraction))
      ->type_name("K")
      ->capture_default_str();
  cmd->add_option("--resample", o->resample_hz,
                  "first resample every column onto a uniform grid at HZ [Hz] by linear "
                  "interpolation (for irregular time stamps)")
      ->type_name("HZ")
      ->check(PositiveNumber());
  AddFieldOption(cmd, "--jitter-tolerance", o->motion, o->motion.max_relative_jitter,
                 "relative sampling jitter above which the recording is rejected as irregular "
                 "[dimensionless]")
      ->check(PositiveNumber());
  cmd->add_flag("--json", o->json,
                "print one JSON object (file, output, method, settings, rows, columns, dt_s, "
                "sample_rate_hz, v_mps and a_mps2 min/max/rms) instead of the CSV or a summary");
  o->recording.Add(cmd);
  cmd->callback([o] { RunDerive(*o); });
}

const bool kRegistered = RegisterCommand(15, &AddDeriveCommand);

}  // namespace
}  // namespace sysid::cli
