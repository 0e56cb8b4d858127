// sysid stage facts [--stage S.json] [--json] [--facts F1,F3] [--seed N | --seeds A-B]
// [--nn-inits K] [--reduced]:
// runs the paper's experiments on a virtual stage and prints, for each of the paper's facts
// F1-F8, the paper's value, the stage's, the tolerance and whether it is met
// (libsysid: sysid/stage_facts.hpp).
#include "sysid/stage_facts.hpp"

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/stage.hpp"

namespace sysid::cli {
namespace {

struct StageFactsCli {
  std::string stage_path;
  std::vector<std::string> facts;
  FactsOptions options;  // seed, threads: the flags' defaults are the library's
  std::string seeds;     // --seeds: a sweep instead of one seed
  bool reduced = false;
  bool json = false;
  bool markdown = false;
};

void RunStageFactsCommand(const StageFactsCli& o) {
  const StageParameters stage =
      o.stage_path.empty() ? StageParameters::Default() : LoadStage(o.stage_path);
  FactsOptions f = o.reduced ? FactsOptions::Reduced() : o.options;
  f.facts = o.facts;
  f.seed = o.options.seed;
  f.threads = o.options.threads;
  f.network_initializations = o.options.network_initializations;
  f.collection_kp_v_per_m = o.options.collection_kp_v_per_m;
  if (!o.seeds.empty()) {
    std::vector<std::uint64_t> seeds;
    try {
      seeds = ParseFactsSeeds(o.seeds);
    } catch (const OptionsError& e) {
      RethrowWithFlag(e, {{"seeds", "--seeds"}});
    }
    const FactsSeedSweep sweep = RunStageFactsOverSeeds(
        stage, seeds, f, [](const std::string& step) { Progress("stage facts: " + step); });
    ProgressDone();
    std::cout << (o.json ? sweep.ToJson() + "\n" : sweep.ToMarkdown());
    return;
  }
  const StageFacts r =
      RunStageFacts(stage, f, [](const std::string& step) { Progress("stage facts: " + step); });
  ProgressDone();
  if (o.json) {
    std::cout << r.ToJson() << '\n';
    return;
  }
  if (o.markdown) {
    std::cout << r.ToMarkdown();
    return;
  }
  // One block per fact: the texts are too long for one table row in a terminal.
  std::cout << "stage: " << r.stage_name << '\n';
  for (const auto& x : r.facts) {
    std::cout << '\n'
              << x.id << "  " << x.fact << "  ["
              << (x.met ? "met" : (x.required ? "NOT MET" : "not met, reported only")) << "]\n";
    std::cout << "    paper:     " << x.paper << '\n';
    std::cout << "    stage:     " << x.virtual_value << '\n';
    std::cout << "    tolerance: " << x.tolerance << '\n';
    if (!x.note.empty() && (!x.met || x.id == "F6"))
      std::cout << "    note:      " << x.note << '\n';
  }
  std::cout << '\n';
  std::string failed, run;
  for (const auto& x : r.facts) {
    run += (run.empty() ? "" : ", ") + x.id;
    if (x.required && !x.met) failed += (failed.empty() ? "" : ", ") + x.id;
  }
  const std::string scope = o.facts.empty() ? "" : " (of the facts run: " + run + ")";
  std::cout << (failed.empty() ? "every required fact is met" + scope
                               : "required facts not met: " + failed + scope)
            << '\n';
}

void AddStageCommand(CLI::App& app) {
  CLI::App* stage = app.add_subcommand("stage", "Virtual-stage checks against the paper");
  stage->require_subcommand(1);
  auto o = std::make_shared<StageFactsCli>();
  CLI::App* cmd = stage->add_subcommand(
      "facts",
      "Run the paper's experiments on a stage (pulse test, delay tuning, PI tracking at the "
      "paper's gains with none/analytic/NN feedforward, the sinusoidal dominance test, the "
      "typical and dominant networks, the open-loop voltage-velocity loops) and print, for each "
      "fact F1-F8, the paper's value, the stage's, the tolerance and met / not met. F1-F6 and F8 "
      "are required, F7 is reported. Exit 0 "
      "whether or not the facts are met (read \"met\" / \"required_met\" in the JSON)");
  cmd->add_option("--stage", o->stage_path,
                  std::string("stage parameter file (JSON) or a preset: ") + cli::kStagePresets)
      ->type_name("S.json|PRESET");
  FactsOptions& f = o->options;
  // Copied into facts when the command runs (over FactsOptions::Reduced() with --reduced).
  BindField(cmd,
            cmd->add_option("--facts", o->facts,
                            "only these facts (and what they need), e.g. F1,F3")
                ->delimiter(',')
                ->check(CLI::IsMember({"F1", "F2", "F3", "F4", "F5", "F6", "F7", "F8"}))
                ->type_name("ID,..."),
            f, f.facts);
  auto* seed = BindField(
      cmd, AddSeedOption(cmd, f.seed, "noise seed of every experiment [integer]"), f, f.seed);
  cmd->add_option("--seeds", o->seeds,
                  "run the facts at each of these seeds (A-B or A,B,...; at most 1000) and "
                  "print, per fact, the seeds at which it is met (Markdown, or --json)")
      ->excludes(seed)
      ->type_name("A-B|A,B,...");
  BindField(cmd,
            AddThreadsOption(cmd, f.threads,
                             "threads for delay tuning; 0 = all cores (the networks train on "
                             "one thread: repeatable)"),
            f, f.threads);
  AddFieldOption(cmd, "--nn-inits", f, f.network_initializations,
                 "F5: also train the dominant network from this many initial weights and "
                 "report each one's tracking error and how many beat the analytic inverse "
                 "(the verdict stays the first network's)")
      ->check(CLI::Range(1, 100));
  AddFieldOption(cmd, "--collect-kp", f, f.collection_kp_v_per_m,
                 "[V/m] P gain of the controller that collects the networks' training and test "
                 "sets (F5's NN, F7); the paper does not print it")
      ->check(FiniteRange(1.0, 1e6));
  cmd->add_flag("--reduced", o->reduced,
                "small networks and short training, for tests (F5's NN row and F7 are then not "
                "the paper's experiment)");
  cmd->add_flag("--json", o->json,
                "print {\"stage\", \"facts\": [{\"id\", \"fact\", \"paper\", \"virtual\", "
                "\"tolerance\", \"met\", \"required\", \"note\", \"values\"}], \"required_met\"}");
  cmd->add_flag("--markdown", o->markdown, "print the table as Markdown");
  cmd->callback([o] { RunStageFactsCommand(*o); });
}

const bool kRegistered = RegisterCommand(45, &AddStageCommand);

}  // namespace
}  // namespace sysid::cli
