// The pipeline on a stack data set (no pulse test; recordings t, u, x): the hysteresis models
// fitted on the first part of every recording and scored on the rest (sysid/compare_stack.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/json_fields.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "pipeline/timed_step.hpp"
#include "sysid/pipeline.hpp"

namespace sysid {
namespace {

/// [V] The most a stack recording's |u| may reach: no piezo amplifier gives more.
constexpr double kMaxStackVoltage_v = 1e5;

// The hysteresis fits take powers and products of u and x (a polynomial of degree 3, Ceres'
// Jacobians): values near 1e150 overflowed into inf scores and a solver's failure dump in the
// report. A stack moves micrometres on at most a few hundred volts; far past that the
// recording is in another unit, or not a stack's.
void CheckStackRanges(const Recording& rec) {
  const Eigen::VectorXd x = rec.column("x"), u = rec.column("u");
  const double span = x.maxCoeff() - x.minCoeff(), peak = u.cwiseAbs().maxCoeff();
  if (!(span <= kMaxPlausibleTravel_m))
    throw InputError(fmt::format(
        "{}: column 'x' spans {:.6g} m, more than the {:g} m any stage or stack moves "
        "(sysid::kMaxPlausibleTravel_m): if x is in another unit, declare it with a "
        "'# units: x=um' line",
        rec.source, span, kMaxPlausibleTravel_m));
  if (!(peak <= kMaxStackVoltage_v))
    throw InputError(fmt::format(
        "{}: column 'u' reaches {:.6g} V, more than the {:g} V a piezo amplifier gives: "
        "expected the drive voltage in V",
        rec.source, peak, kMaxStackVoltage_v));
}

// The first recording's scored part, its first kStackFigureSamples samples: measured beside each
// model, forward and inverse (the report's two plots).
void StackTraces(const Recording& rec, const std::vector<HysteresisSplitScore>& models,
                 PipelineFigures& f) {
  const Eigen::Index k = TrainingPart(rec, kStackTrainFraction).rows();
  const Eigen::Index m = std::min<Eigen::Index>(rec.rows() - k, kStackFigureSamples);
  const Eigen::VectorXd t = rec.column("t").segment(k, m);
  f.stack_source = rec.source;
  f.stack_position.push_back({"measured", t, rec.column("x").segment(k, m)});
  f.stack_voltage.push_back({"measured", t, rec.column("u").segment(k, m)});
  for (size_t i = 0; i < models.size(); ++i) {
    const auto& s = models[i];
    // The table's row and model label: two rows may share a kind (both networks).
    const std::string label = fmt::format("{} {}", i + 1, s.label);
    if (!s.x_model.empty()) f.stack_position.push_back({label, t, s.x_model.front().segment(k, m)});
    if (!s.u_model.empty()) f.stack_voltage.push_back({label, t, s.u_model.front().segment(k, m)});
  }
}

}  // namespace

PipelineResult RunStackPipeline(const PipelineInputs& inputs, const PipelineOptions& options,
                                const PipelineProgress& progress) {
  SYSID_CHECK(inputs.IsStack(), "RunStackPipeline on a stage's inputs");
  options.Validate();
  PipelineResult r;
  r.inputs = inputs;
  r.options = options;
  auto step = [&](const std::string& name, auto&& body) {
    internal::TimedStep(r, progress, name, body);
  };
  std::vector<Recording> recs;
  step("read recordings", [&] {
    ReadOptions ro = inputs.Read();
    ro.required_columns = {"t", "u", "x"};
    ro.any_of_columns = {};
    for (const auto& path : inputs.stack) {
      recs.push_back(ReadRecording(path, ro));
      TrainingPart(recs.back(), kStackTrainFraction);  // InputError now if too short to split
      CheckStackRanges(recs.back());
    }
  });
  step("dominance of x, v, a (training parts)", [&] {
    for (const auto& rec : recs)
      r.stack_dominance.push_back(RankCandidates(TrainingPart(rec, kStackTrainFraction)));
  });
  for (const auto& spec : StackModelSpecs(options.threads)) {
    step("fit and score: " + spec.label, [&] {
      r.stack_models.push_back(FitAndScoreHysteresis(spec, recs, kStackTrainFraction));
      const auto& s = r.stack_models.back();
      if (!s.error.empty()) r.notes.push_back(s.label + ": no score: " + s.error);
    });
  }
  if (!r.stack_models.empty()) StackTraces(recs.front(), r.stack_models, r.figures);
  return r;
}

StackSummary StackSummaryOf(const PipelineResult& r) {
  StackSummary s;
  s.recordings = r.inputs.stack;
  s.train_fraction = kStackTrainFraction;
  s.split = fmt::format(
      "each model fitted on the first {:g} % of every recording's rows and scored on the rest; "
      "forward and inverse run over the whole recording from the model's initial state",
      100 * kStackTrainFraction);
  for (const auto& d : r.stack_dominance) s.dominance.push_back({d.source, d.dominant, d.margin, d.r2});
  s.models = r.stack_models;
  s.steps = r.step_seconds;
  return s;
}

std::string ToJson(const StackSummary& s, int indent) { return internal::FieldsToJson(s, indent); }

}  // namespace sysid
