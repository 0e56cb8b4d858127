// sysid dominance --model M.json [--json] [-o TABLE.csv] REC.csv...
// Ranks the inverse model's input variables by the size of the terms they generate.
#include "sysid/dominance.hpp"

#include <fmt/format.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/common.hpp"
#include "cli/field_flag.hpp"
#include "cli/output_file.hpp"
#include "cli/motion_flags.hpp"
#include "cli/registry.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"

namespace sysid::cli {
namespace {

struct DominanceCli {
  std::string model;
  std::vector<std::string> recordings;
  std::vector<std::string> candidates;
  DominanceOptions options;  // the flags' defaults are the library's
  bool json = false;
  bool verbose = false;
  std::string output;
  MotionFlags motion;
};

CandidateTerm ParseCandidate(const std::string& spec) {
  // NAME=COLUMN*GAIN or NAME=COLUMN
  const size_t eq = spec.find('=');
  if (eq == std::string::npos || eq == 0)
    throw OptionsError("--candidate '" + spec + "': expected NAME=COLUMN or NAME=COLUMN*GAIN");
  CandidateTerm c;
  c.variable = spec.substr(0, eq);
  std::string rest = spec.substr(eq + 1);
  const size_t star = rest.find('*');
  if (star != std::string::npos) {
    const std::string g = rest.substr(star + 1);
    size_t used = 0;
    try {
      c.gain = std::stod(g, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != g.size() || g.empty())
      throw OptionsError("--candidate '" + spec + "': gain '" + g + "' is not a number");
    rest = rest.substr(0, star);
  }
  c.column = rest;
  return c;
}

void RunDominance(const DominanceCli& o) {
  const FrictionModel model = ReadModel(o.model);
  DominanceOptions d = o.options;
  o.motion.ApplyTo(d.motion);
  for (const auto& c : o.candidates) d.candidates.push_back(ParseCandidate(c));
  const std::vector<Recording> recs = o.motion.ReadRecordings(o.recordings);
  const DominanceSummary s = AnalyzeDominanceBatch(model, recs, d);
  if (!o.output.empty()) WriteFileAtomically(o.output, DominanceTableCsv(s));
  if (o.json) {
    std::cout << ToJson(s);
    return;
  }
  for (const auto& r : s.results) std::cout << (o.verbose ? r.FullReport() : r.BriefReport());
  if (s.results.size() > 1) {
    std::cout << fmt::format("\n{} recordings: dominant {} ", s.results.size(), s.dominant);
    for (const auto& [k, c] : s.dominant_counts) std::cout << fmt::format("[{}: {}] ", k, c);
    std::cout << fmt::format("margin min {:.3g}, median {:.3g}\n", s.min_margin, s.median_margin);
    const auto unclear = std::count_if(s.results.begin(), s.results.end(), [](const auto& r) {
      return r.margin < kClearDominanceMargin;
    });
    if (unclear > 0)
      std::cout << fmt::format(
          "{} of {} recordings have no clear dominant variable (margin < {:g})\n", unclear,
          s.results.size(), kClearDominanceMargin);
  }
}

void AddDominanceCommand(CLI::App& app) {
  auto o = std::make_shared<DominanceCli>();
  CLI::App* cmd = app.add_subcommand(
      "dominance",
      "Rank the inverse model's input variables (acceleration, velocity, ...) by the size of "
      "the terms of a3 u = x'' + a1 v(t-tau) + a2 sgn(v) they generate over the moving part "
      "[m/s^2]; batch over many recordings in parallel");
  AddModelAndRecordings(cmd, o->model, "model file (JSON: a1p, a1n, a2p, a2n, a3, tau)",
                        o->recordings);
  DominanceOptions& d = o->options;
  // Each --candidate is parsed into a CandidateTerm appended to `candidates` when the command runs.
  BindField(cmd,
            cmd->add_option("--candidate", o->candidates,
                            "further candidate variable NAME=COLUMN*GAIN: term GAIN*COLUMN "
                            "[m/s^2]")
                ->type_name("NAME=COL*GAIN"),
            d, d.candidates);
  AddFieldOption(cmd, "--min-speed", d, d.min_speed_mps, "moving part: |v| >= this [m/s]");
  AddFieldOption(cmd, "--negligible", d, d.negligible_ratio,
                 "a variable with rms <= this x the top's is negligible [dimensionless]");
  BindField(cmd,
            AddThreadsOption(cmd, d.threads,
                             "recordings analysed in parallel [count]; 0 = all cores"),
            d, d.threads);
  AddVerboseFlag(cmd, o->verbose);
  cmd->add_flag("--json", o->json,
                "print {ranking: [{variable, rms, peak, ratio_to_top}], dominant, summary, "
                "recordings} (rms, peak in m/s^2)");
  AddOutputOption(cmd, o->output, "write the per-recording table as CSV");
  GuardOutputFiles(cmd, {{&o->output, "-o"}});
  o->motion.Add(cmd, "filter for v and x'' from x",
                ToString(DominanceOptions{}.motion.derivative.method));
  o->motion.Bind(cmd, d, d.motion);
  cmd->callback([o] { RunDominance(*o); });
}

const bool kRegistered = RegisterCommand(50, &AddDominanceCommand);

}  // namespace
}  // namespace sysid::cli
