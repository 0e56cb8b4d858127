// sysid hysteresis fit|simulate|invert: the hysteresis models (Prandtl–Ishlinskii family,
// Bouc–Wen, the operator-input network) fitted, simulated and inverted on recordings.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/fit_fraction_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/recording_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/dominance_candidates.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/io_output.hpp"

namespace sysid::cli {
namespace {

struct HysteresisCli {
  // fit
  std::string kind;
  std::vector<std::string> recordings;
  HysteresisFitOptions options;
  bool json = false;
  std::string output;
  // simulate / invert
  std::string model_path;
  std::string input;
  bool periodic = false;
  bool no_offset = false;
  // Bouc–Wen fits: auto | fixed-step | cvode | benchmark-chain (auto: docs/hysteresis.md).
  std::string integrator = "auto";
  // Bouc–Wen fits: auto | hold | linear | band-limited (auto: docs/hysteresis.md).
  std::string input_model = "auto";
  std::string jacobian = "sensitivities";  // Bouc–Wen fits: sensitivities | central-differences
  RecordingFlags recording;  // --var, --rate, --scale for every recording read
  FitFractionFlag fit_fraction;
};

// Bouc–Wen fits: the start, then one line per start (rewritten at each iteration) with its
// iteration, training RMS and elapsed time.
void AttachBoucWenProgress(HysteresisFitOptions& options, const std::string& kind,
                           const std::vector<Recording>& recs) {
  if (!ProgressEnabled() || (kind != "bouc-wen" && kind != "bouc-wen-piezo")) return;
  Eigen::Index rows = 0;
  for (const auto& r : recs) rows += r.rows();
  Progress(
      fmt::format("fitting {} to {} samples ({} starts)", kind, rows, options.bouc_wen.starts));
  ProgressDone();
  auto last_start = std::make_shared<int>(-1);
  options.bouc_wen.on_iteration = [=](const BoucWenFitProgress& p) {
    if (p.start != *last_start) ProgressDone();
    *last_start = p.start;
    const std::string which =
        p.start > 0 ? fmt::format("start {}/{}", p.start, p.starts) : std::string("final fit");
    Progress(fmt::format("{} {}: iteration {}, training RMS {:.6g} m, {:.1f} s", kind, which,
                         p.iteration, p.rms_m, p.elapsed_s));
  };
}

std::vector<Recording> ReadAll(const std::vector<std::string>& paths,
                               const RecordingFlags& flags) {
  ReadOptions ro = flags.Apply({});
  ro.required_columns = {"t", "u", "x"};
  ro.any_of_columns = {};
  std::vector<Recording> recs;
  for (const auto& p : paths) recs.push_back(ReadRecording(p, ro));
  return recs;
}

void PrintSummary(const HysteresisFitSummary& s, const HysteresisModel& model) {
  std::cout << fmt::format("{}: fitted on {} samples in {:.3g} s; training RMS {:.4g} m{}\n",
                           s.kind, s.samples, s.fit_time_s, s.training_rms,
                           s.converged ? "" : " (not converged)");
  if (!s.message.empty()) std::cout << s.message << "\n";
  const auto params = model.parameters();
  if (params.size() > 60) {
    std::cout << params.size() << " parameters (see the model file)\n";
    return;
  }
  Table t({"parameter", "value", "std error", "unit"});
  for (const auto& p : params)
    t.AddRow({p.name, Num(p.value), std::isnan(p.std_error) ? "-" : Num(p.std_error, 3), p.unit});
  std::cout << t.Render();
}

void RunFit(const HysteresisCli& o) {
  HysteresisFitOptions options = o.options;
  options.pi.offset = !o.no_offset;
  BoucWenSimulationOptions& sim = options.bouc_wen.simulation;
  // auto: the library's choice (BoucWenFitOptions: the mechanical form's fixed step, CVODE for
  // a held input; the input band-limited or linear from the recordings), shared with Python.
  sim.input = o.input_model == "hold"           ? InputInterpolation::kHold
              : o.input_model == "band-limited" ? InputInterpolation::kBandLimited
              : o.input_model == "linear"       ? InputInterpolation::kLinear
                                                : InputInterpolation::kAuto;
  sim.integrator = o.integrator == "benchmark-chain" ? BoucWenIntegrator::kBenchmarkChain
                   : o.integrator == "fixed-step"    ? BoucWenIntegrator::kFixedStep
                   : o.integrator == "cvode"         ? BoucWenIntegrator::kCvode
                                                     : BoucWenIntegrator::kAuto;
  if (o.kind != "bouc-wen" && sim.integrator != BoucWenIntegrator::kCvode &&
      sim.integrator != BoucWenIntegrator::kAuto)
    throw OptionsError("--integrator " + o.integrator +
                       ": only for --model bouc-wen (the mechanical form; bouc-wen-piezo takes "
                       "its exact closed-form step, or CVODE for a band-limited input)");
  if (sim.integrator == BoucWenIntegrator::kFixedStep && sim.input == InputInterpolation::kHold)
    throw OptionsError(
        "--integrator fixed-step: takes --input linear or band-limited (a held "
        "input: --integrator cvode)");
  try {
    options.Validate(o.kind);
  } catch (const OptionsError& e) {
    RethrowWithFlag(e, {{"operators", "--operators"}, {"kind", "--model"},
                        {"hidden", "--hidden"}, {"max_epochs", "--epochs"}});
  }
  try {
    options.pi.Validate();
  } catch (const OptionsError& e) {
    RethrowWithFlag(e, {{"polynomial_degree", "--degree"}}, "--thresholds");
  }
  options.bouc_wen.jacobian = o.jacobian == "central-differences"
                                  ? BoucWenJacobian::kCentralDifferences
                                  : BoucWenJacobian::kSensitivities;
  const std::vector<Recording> recs =
      o.fit_fraction.FitPart(ReadAll(o.recordings, o.recording), "hysteresis fit");
  AttachBoucWenProgress(options, o.kind, recs);
  HysteresisFitSummary s;
  std::unique_ptr<HysteresisModel> model;
  {
    // The progress line ends before the summary or the error is printed.
    struct EndProgress {
      ~EndProgress() { ProgressDone(); }
    } end_progress;
    try {
      model = FitHysteresis(o.kind, recs, options, &s);
    } catch (const OptionsError& e) {
      RethrowWithFlag(e, {{"operators", "--operators"},
                          {"kind", "--model"},
                          {"hidden", "--hidden"},
                          {"starts", "--starts"},
                          {"threads", "--threads"},
                          {"max_time_s", "--max-time"},
                          {"start_rtol", "--start-rtol"},
                          {"fixed_step_tolerance", "--step-tolerance"}});
    }
  }
  const std::string summary_json = HysteresisFitSummaryJson(s, *model, 2);
  nlohmann::ordered_json file = nlohmann::ordered_json::parse(model->ToJson(2));
  nlohmann::ordered_json fit = nlohmann::ordered_json::parse(summary_json);
  fit.erase("parameters");  // the model file holds them already
  fit["recordings"] = o.recordings;
  if (o.fit_fraction.fraction < 1) fit["fit_fraction"] = o.fit_fraction.fraction;
  file["fit"] = fit;
  WriteFileAtomically(o.output, WithGeneratorKey(file.dump(2) + "\n"));
  if (o.json) {
    std::cout << summary_json;
    return;
  }
  PrintSummary(s, *model);
  std::cout << "wrote " << o.output << "\n";
}

void RunSimulate(const HysteresisCli& o) {
  const auto model = ReadHysteresisModel(o.model_path);
  ReadOptions ro = o.recording.Apply({});
  ro.required_columns = {"t", "u"};
  ro.any_of_columns = {};
  const Recording rec = ReadRecording(o.input, ro);
  const double dt = RecordingStep(rec);
  const Eigen::VectorXd u = rec.column("u");
  Eigen::VectorXd y;
  try {
    y = o.periodic ? model->SimulatePeriodic(u, dt) : model->Simulate(u, dt);
  } catch (const InputError& e) {
    // The model's work on this recording is bounded (rows x upsampling, periods): the limit
    // belongs to the model file's settings.
    throw InputError(o.model_path + ": on " + o.input + ": " + e.what());
  } catch (const NumericalError& e) {
    throw NumericalError(o.model_path + ": on " + o.input + ": " + e.what());
  }
  Recording out;
  out.source = o.output;
  out.names = {"t", "u", "x_model"};
  out.metadata = {{"model", o.model_path}, {"kind", model->kind()}, {"input", o.input},
                  {"periodic", o.periodic ? "true" : "false"}};
  for (const auto& entry : ProvenanceOf(rec, {"t", "u"})) out.metadata.push_back(entry);
  out.data.resize(u.size(), 3);
  out.data.col(0) = rec.column("t");
  out.data.col(1) = u;
  out.data.col(2) = y;
  WriteRecording(o.output, out);
  std::cout << fmt::format("{}: simulated {} samples -> {}\n", model->kind(), u.size(), o.output);
}

void RunInvert(const HysteresisCli& o) {
  const auto model = ReadHysteresisModel(o.model_path);
  ReadOptions ro = o.recording.Apply({});
  ro.required_columns = {"t", "x"};
  ro.any_of_columns = {};
  const Recording ref = ReadRecording(o.input, ro);
  const double dt = RecordingStep(ref);
  if (!model->invertible()) {
    try {
      model->Invert(ref.column("x"), dt);
    } catch (const NumericalError& e) {
      throw InputError(o.model_path + ": " + e.what());
    }
    throw InputError(o.model_path + ": the " + model->kind() + " model is not invertible");
  }
  Eigen::VectorXd u;
  try {
    u = model->Invert(ref.column("x"), dt);
  } catch (const InputError& e) {
    throw InputError(o.input + ": " + e.what());
  } catch (const NumericalError& e) {
    throw NumericalError(o.model_path + ": " + e.what());
  }
  Recording out;
  out.source = o.output;
  out.names = {"t", "x", "u"};
  out.metadata = {{"model", o.model_path}, {"kind", model->kind()}, {"reference", o.input}};
  for (const auto& entry : ProvenanceOf(ref, {"t", "x"})) out.metadata.push_back(entry);
  out.data.resize(u.size(), 3);
  out.data.col(0) = ref.column("t");
  out.data.col(1) = ref.column("x");
  out.data.col(2) = u;
  WriteRecording(o.output, out);
  std::cout << fmt::format("{}: inverted {} samples -> {}\n", model->kind(), u.size(), o.output);
}

void RunDominance(const HysteresisCli& o, const CandidateRankingOptions& options) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const auto& path : o.recordings) {
    ReadOptions ro = o.recording.Apply({});
    ro.required_columns = {"t", "u", "x"};
    ro.any_of_columns = {};
    const CandidateRanking r = RankCandidates(ReadRecording(path, ro), options);
    if (!o.json) {
      std::cout << r.BriefReport();
      continue;
    }
    nlohmann::ordered_json j;
    j["source"] = r.source;
    j["dominant"] = r.dominant;
    j["margin"] = r.margin;
    j["r2"] = r.r2;
    j["residual_rms_v"] = r.residual_rms_v;
    for (const char* key : {"ranking", "terms"}) {
      nlohmann::ordered_json list = nlohmann::ordered_json::array();
      for (const auto& t : key[0] == 'r' ? r.ranking : r.terms)
        list.push_back({{"name", t.name}, {"rms_v", t.rms}, {"peak_v", t.peak},
                        {"ratio_to_top", t.ratio_to_top}, {"negligible", t.negligible}});
      j[key] = list;
    }
    all.push_back(j);
  }
  if (o.json) std::cout << all.dump(2) << "\n";
}

// `hysteresis fit`: its flags on the shared options o.
void AddFitSubcommand(CLI::App& h, const std::shared_ptr<HysteresisCli>& o) {
  CLI::App* fit = h.add_subcommand("fit", "Fit a model to recordings (columns t [s], u [V], x [m])");
  fit->add_option("--model", o->kind, "model kind")
      ->required()
      ->check(CLI::IsMember(HysteresisKinds()))
      ->type_name("KIND");
  fit->add_option("--operators", o->options.operators,
                  fmt::format("play operators (PI family: 1..{0}; nn-operators: 0..{0}, 0 = the "
                              "static network on u alone)", kMaxPlayOperators))
      ->capture_default_str();
  fit->add_option("--thresholds", o->options.pi.thresholds,
                  "PI family: the play operators' thresholds r_1 < ... < r_n [V], > 0 (default: "
                  "uniform over half the input range; --operators is then ignored)")
      ->delimiter(',')
      ->allow_extra_args(false)  // one comma list: the recordings that follow stay positionals
      ->type_name("R1,R2,...");
  fit->add_flag("--no-offset", o->no_offset,
                "PI family: no sensor-offset term c [m] (default: fitted)");
  fit->add_option("--degree", o->options.pi.polynomial_degree,
                  "gpi: degree of the input polynomial a1 u + a3 u^3 (+ a5 u^5), odd powers fitted (3..5)")
      ->capture_default_str();
  fit->add_option("--hidden", o->options.network.hidden, "nn-operators: tanh units")
      ->capture_default_str();
  fit->add_option("--epochs", o->options.network.max_epochs, "nn-operators: LM epochs per network")
      ->capture_default_str();
  AddSeedOption(fit, o->options.network.seed, "nn-operators: initialisation seed");
  fit->add_option("--integrator", o->integrator,
                  "bouc-wen, bouc-wen-piezo: how the fit simulates: auto (bouc-wen: fixed-step, "
                  "or cvode for --input hold; bouc-wen-piezo: its exact step), fixed-step "
                  "(bouc-wen: Newmark at m steps per sample, m chosen by step doubling and "
                  "checked against CVODE), cvode, or benchmark-chain (bouc-wen: the Bouc-Wen "
                  "benchmark's own generator); docs/hysteresis.md")
      ->check(CLI::IsMember({"auto", "fixed-step", "cvode", "benchmark-chain"}))
      ->capture_default_str();
  fit->add_option("--step-tolerance", o->options.bouc_wen.fixed_step_tolerance,
                  "bouc-wen with fixed-step: the integration error allowed, relative to the "
                  "output's RMS about its mean (0 < TOL <= 0.1)")
      ->type_name("TOL")
      ->capture_default_str();
  fit->add_option("--input", o->input_model,
                  "bouc-wen, bouc-wen-piezo: u between samples: auto (bouc-wen: band-limited when "
                  "every recording is whole periods of a band-limited signal, else linear; "
                  "bouc-wen-piezo: linear), hold, linear or band-limited (the record as one "
                  "period of a periodic input)")
      ->check(CLI::IsMember({"auto", "hold", "linear", "band-limited"}))
      ->capture_default_str();
  fit->add_option("--starts", o->options.bouc_wen.starts,
                  "bouc-wen, bouc-wen-piezo: starting points (1..64)")
      ->capture_default_str();
  fit->add_option("--start-rtol", o->options.bouc_wen.start_rtol,
                  "bouc-wen by CVODE with sensitivities: the CVODE relative tolerance of the "
                  "starts' iterations; the best start continues at the fit's 1e-9 (1e-9 <= R <= "
                  "1e-2; 1e-9: no screening)")
      ->type_name("R")
      ->capture_default_str();
  fit->add_option("--jacobian", o->jacobian,
                  "bouc-wen, bouc-wen-piezo: how the fit differentiates the simulation: "
                  "sensitivities (the fixed step's, the chain's or the piezo closed form's step "
                  "differentiated; bouc-wen by CVODE: CVODES' forward sensitivities; "
                  "bouc-wen-piezo by CVODE: central differences) or central-differences (2p+1 "
                  "simulations)")
      ->check(CLI::IsMember({"sensitivities", "central-differences"}))
      ->capture_default_str();
  fit->add_option("--max-time", o->options.bouc_wen.max_time_s,
                  "bouc-wen, bouc-wen-piezo: stop after SECONDS [s] of wall time with the best "
                  "parameters so far (the summary says so; not an error); 0 = no bound")
      ->check(CLI::NonNegativeNumber)
      ->type_name("SECONDS")
      ->capture_default_str();
  AddThreadsOption(fit, o->options.bouc_wen.threads,
                   "bouc-wen, bouc-wen-piezo: the Jacobian's simulations (central differences) "
                   "or the recordings' sensitivity passes in parallel; 0 = all cores");
  o->recording.Add(fit);
  o->fit_fraction.Add(fit);
  fit->add_option("recordings", o->recordings, "recording CSVs: t [s], u [V], x [m]")
      ->required()
      ->type_name("REC.csv");
  fit->add_flag("--json", o->json,
                "print {kind, samples, fit_time_s, training_rms_m, converged, message, "
                "parameters: [{name, unit, value, std_error}]}");
  AddOutputOption(fit, o->output, "write the model file (JSON)")->required();
  fit->callback([o] { RunFit(*o); });
  GuardOutputFiles(fit, {{&o->output, "-o"}});
}

void AddHysteresisCommand(CLI::App& app) {
  CLI::App* h = app.add_subcommand(
      "hysteresis",
      "Hysteresis models of an actuator's input u [V] to displacement x [m]: Prandtl-Ishlinskii "
      "(pi, asymmetric gpi, rate-dependent rdpi), Bouc-Wen and the operator-input network; fit, "
      "simulate, invert (docs/hysteresis.md)");
  h->require_subcommand(1);
  auto o = std::make_shared<HysteresisCli>();

  AddFitSubcommand(*h, o);

  CLI::App* sim = h->add_subcommand(
      "simulate", "Drive a model with a recording's u from the model's initial state; write t, u, x_model");
  sim->add_option("--model", o->model_path, "model file from `hysteresis fit`")->required()->type_name("H.json");
  o->recording.Add(sim);
  sim->add_option("recording", o->input, "CSV with t [s] and u [V]")->required()->type_name("REC.csv");
  sim->add_flag("--periodic", o->periodic,
                "u is one period of a periodic input: simulate to the periodic steady state and "
                "write the last period");
  AddOutputOption(sim, o->output, "write t, u, x_model (CSV)")->required();
  sim->callback([o] { RunSimulate(*o); });
  GuardOutputFiles(sim, {{&o->output, "-o"}});

  CLI::App* inv = h->add_subcommand(
      "invert", "The input u [V] that makes the model follow a reference x [m]; write t, x, u");
  inv->add_option("--model", o->model_path, "model file from `hysteresis fit`")->required()->type_name("H.json");
  o->recording.Add(inv);
  inv->add_option("reference", o->input, "CSV with t [s] and x [m]")->required()->type_name("REF.csv");
  AddOutputOption(inv, o->output, "write t, x, u (CSV)")->required();
  inv->callback([o] { RunInvert(*o); });
  GuardOutputFiles(inv, {{&o->output, "-o"}});

  auto rank = std::make_shared<CandidateRankingOptions>();
  CLI::App* dom = h->add_subcommand(
      "dominance",
      "Rank x, v and a (with play operators of x) by the RMS of their terms in a linear inverse "
      "model u ~ c + th_x x + th_v v + th_a a + sum th_i F_ri[x] [V]: which variable carries "
      "the input (a stack: x; the stage: v)");
  o->recording.Add(dom);
  dom->add_option("recordings", o->recordings, "recording CSVs: t [s], u [V], x [m]")
      ->required()
      ->type_name("REC.csv");
  dom->add_option("--operators", rank->operators, "play operators on x")
      ->check(CLI::Range(0, kMaxPlayOperators))
      ->capture_default_str();
  dom->add_flag("--json", o->json, "print [{source, dominant, margin, r2, residual_rms_v, ranking, terms}]");
  dom->callback([o, rank] { RunDominance(*o, *rank); });
}

const bool kRegistered = RegisterCommand(55, &AddHysteresisCommand);

}  // namespace
}  // namespace sysid::cli
