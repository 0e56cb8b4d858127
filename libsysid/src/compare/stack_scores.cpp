// Hysteresis models fitted on the first part of a stack's recordings, scored on the rest
// (sysid/compare_stack.hpp).
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "core/option_rule.hpp"
#include "sysid/compare_stack.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"

namespace sysid {

std::vector<HysteresisModelSpec> StackModelSpecs(int threads) {
  std::vector<HysteresisModelSpec> specs;
  auto add = [&](std::string label, std::string kind, int operators) {
    HysteresisModelSpec s;
    s.label = std::move(label);
    s.kind = std::move(kind);
    s.options.operators = operators;
    s.options.network.hidden = 10;
    s.options.bouc_wen.threads = threads;
    specs.push_back(std::move(s));
  };
  add("PI, 20 operators + offset", "pi", 20);
  add("asymmetric PI (cubic input function), 20 operators + offset", "gpi", 20);
  add("rate-dependent PI, 20 operators + offset", "rdpi", 20);
  add("Bouc–Wen, piezo form", "bouc-wen-piezo", 1);
  add("dominant-variable network (static, H = 10)", "nn-operators", 0);
  add("operator-input network (4 play operators, H = 10)", "nn-operators", 4);
  return specs;
}

Recording TrainingPart(const Recording& recording, double train_fraction) {
  if (!(train_fraction > 0 && train_fraction < 1))
    internal::FailOption("", "train_fraction", train_fraction, "0 < train_fraction < 1");
  const Eigen::Index n = recording.rows();
  const auto split = static_cast<Eigen::Index>(std::llround(train_fraction * static_cast<double>(n)));
  if (split < 2 || n - split < 2)
    throw InputError(fmt::format("{}: {} rows: the first {:g} % ({} rows) to fit and the rest "
                                 "({} rows) to score need at least 2 rows each",
                                 recording.source, n, 100 * train_fraction, split, n - split));
  Recording part = recording;
  part.data = recording.data.topRows(split);
  part.row_lines.clear();  // the rows changed (line_of's guard)
  part.row_lines_rows = 0;
  return part;
}

namespace {

// RMS of the pooled errors and the population std of the pooled measured values.
struct Pooled {
  double sum_e2 = 0, sum = 0, sum2 = 0;
  Eigen::Index n = 0;
  void Add(const Eigen::VectorXd& model, const Eigen::VectorXd& measured) {
    sum_e2 += (model - measured).squaredNorm();
    sum += measured.sum();
    sum2 += measured.squaredNorm();
    n += measured.size();
  }
  double Rms() const { return std::sqrt(sum_e2 / static_cast<double>(n)); }
  double NrmseStd() const {
    const double mean = sum / static_cast<double>(n);
    const double var = std::max(0.0, sum2 / static_cast<double>(n) - mean * mean);
    return var > 0 ? Rms() / std::sqrt(var) : std::numeric_limits<double>::quiet_NaN();
  }
};

}  // namespace

HysteresisSplitScore FitAndScoreHysteresis(const HysteresisModelSpec& spec,
                                           const std::vector<Recording>& recordings,
                                           double train_fraction) {
  if (recordings.empty()) throw InputError("FitAndScoreHysteresis: no recordings");
  spec.options.Validate(spec.kind);
  HysteresisSplitScore s;
  s.label = spec.label;
  s.kind = spec.kind;
  std::vector<Recording> train;
  std::vector<Eigen::Index> splits;
  for (const auto& rec : recordings) {
    for (const char* name : {"t", "u", "x"})
      (void)rec.column(name);  // InputError naming a missing column
    train.push_back(TrainingPart(rec, train_fraction));
    splits.push_back(train.back().rows());
    s.train_samples += train.back().rows();
    s.test_samples += rec.rows() - train.back().rows();
  }
  std::unique_ptr<HysteresisModel> fitted;
  try {
    fitted = FitHysteresis(spec.kind, train, spec.options, &s.summary);
  } catch (const NumericalError& e) {
    s.error = e.what();
    return s;
  }
  s.model = std::shared_ptr<const HysteresisModel>(std::move(fitted));
  s.fit_time_s = s.summary.fit_time_s;
  s.parameters = static_cast<int>(s.model->parameters().size());
  Pooled fwd, inv;
  try {
    for (size_t i = 0; i < recordings.size(); ++i) {
      const Recording& rec = recordings[i];
      const Eigen::Index k = splits[i], m = rec.rows() - k;
      s.x_model.push_back(s.model->Simulate(rec.column("u"), RecordingStep(rec)));
      fwd.Add(s.x_model.back().tail(m), rec.column("x").tail(m));
    }
  } catch (const NumericalError& e) {
    s.error = std::string("simulation: ") + e.what();
    s.x_model.clear();
    return s;
  }
  s.forward_rms_m = fwd.Rms();
  s.forward_nrmse_std = fwd.NrmseStd();
  try {
    for (size_t i = 0; i < recordings.size(); ++i) {
      const Recording& rec = recordings[i];
      const Eigen::Index k = splits[i], m = rec.rows() - k;
      s.u_model.push_back(s.model->Invert(rec.column("x"), RecordingStep(rec)));
      inv.Add(s.u_model.back().tail(m), rec.column("u").tail(m));
    }
    s.inverse_rms_v = inv.Rms();
    s.inverse_nrmse_std = inv.NrmseStd();
  } catch (const Error& e) {
    // Not invertible (NumericalError) or a measured x outside the model's range (InputError):
    // the model's reason, a row of the table rather than the end of the run.
    if (dynamic_cast<const NumericalError*>(&e) == nullptr &&
        dynamic_cast<const InputError*>(&e) == nullptr)
      throw;
    s.inverse_error = e.what();
    s.u_model.clear();
  }
  return s;
}

std::string ToJson(const HysteresisSplitScore& s, int indent) {
  return internal::FieldsToJson(s, indent);
}

}  // namespace sysid
