// The operator-input network: play operators feeding the paper's tanh network, a forward and a
// directly identified inverse network (sysid/nn_operators.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/json_text.hpp"
#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/nn_operators.hpp"
#include "sysid/nn_stepper.hpp"

namespace sysid {
namespace {

std::vector<ScaledVariable> Inputs(const std::string& name, const std::string& unit, size_t m) {
  std::vector<ScaledVariable> in{{name, unit, -1, 1}};
  for (size_t i = 0; i < m; ++i) in.push_back({fmt::format("F{}[{}]", i + 1, name), unit, -1, 1});
  return in;
}

// Trains one side: `input` -> `target`, operators uniform over the input's range.
OperatorNetworkSide TrainSide(const std::vector<Eigen::VectorXd>& inputs,
                              const std::vector<Eigen::VectorXd>& targets, const std::string& in_name,
                              const std::string& in_unit, const std::string& out_name,
                              const std::string& out_unit, double initial_input,
                              const OperatorNetworkOptions& o, NeuralTrainingResult* result) {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  Eigen::Index n = 0;
  for (const auto& v : inputs) lo = std::min(lo, v.minCoeff()), hi = std::max(hi, v.maxCoeff()), n += v.size();
  OperatorNetworkSide side;
  if (o.operators > 0) side.thresholds = UniformThresholds(lo, hi, o.operators);
  side.initial_input = initial_input;
  NeuralDataset data;
  data.input_names.push_back(in_name);
  for (int i = 0; i < o.operators; ++i) data.input_names.push_back(fmt::format("F{}[{}]", i + 1, in_name));
  data.output_name = out_name;
  data.inputs.resize(n, 1 + o.operators);
  data.targets.resize(n);
  Eigen::Index row = 0;
  for (size_t r = 0; r < inputs.size(); ++r) {
    data.inputs.middleRows(row, inputs[r].size()) = side.Features(inputs[r]);
    data.targets.segment(row, inputs[r].size()) = targets[r];
    row += inputs[r].size();
  }
  data.source = in_name + " -> " + out_name;
  NeuralTrainingOptions t;
  t.hidden = o.hidden;
  t.max_epochs = o.max_epochs;
  t.restarts = o.restarts;
  t.seed = o.seed;
  t.threads = 1;  // identical results for any count; the machine is shared
  *result = TrainNeuralNetwork(data, nullptr, t);
  side.network = result->network;
  // Units for the file (TrainNeuralNetwork names the variables, not their units).
  std::vector<ScaledVariable> named = Inputs(in_name, in_unit, side.thresholds.size());
  for (size_t i = 0; i < named.size(); ++i) {
    named[i].min = side.network.inputs()[i].min;
    named[i].max = side.network.inputs()[i].max;
  }
  ScaledVariable out{out_name, out_unit, side.network.output().min, side.network.output().max};
  NeuralNetwork net(named, out, side.network.hidden_size());
  net.set_parameters(side.network.parameters());
  side.network = net;
  return side;
}

// Refuses, before anything is allocated, a fit whose memory passes kTrainingMemoryLimitBytes.
// The options' own bounds (operators <= kMaxPlayOperators, hidden <= 200) are not enough: the
// feature matrix grows with samples x operators and TrainNeuralNetwork's own limit is checked
// only after TrainSide has built it, so 200 operators on 2e6 samples would ask for two 3.2 GB
// matrices and end in std::bad_alloc (Python: MemoryError) instead of an OptionsError.
// Per side, sequentially: the dataset's N x (1 + m) features and its normalised copy, one
// recording's features while they are copied in, targets (twice), and TrainNeuralNetwork's
// estimate 16 P^2 + 8 N H; plus the u and x copies (2 N) held for both sides.
void CheckFitMemory(const std::vector<Recording>& recordings, const OperatorNetworkOptions& o) {
  Eigen::Index rows = 0, longest_rows = 0;
  for (const Recording& rec : recordings) {
    rows += rec.rows();
    longest_rows = std::max(longest_rows, rec.rows());
  }
  const double n = static_cast<double>(rows), longest = static_cast<double>(longest_rows);
  const double inputs = 1.0 + o.operators, hidden = o.hidden;
  const double weights = hidden * (inputs + 2) + 1;
  const double features = 8.0 * inputs * (2 * n + longest) + 16.0 * n;
  const double training = 16.0 * weights * weights + 8.0 * n * hidden;
  const double bytes = features + training + 16.0 * n;
  if (bytes <= kTrainingMemoryLimitBytes) return;
  // Name the option whose term dominates, so the CLI points at the flag to lower.
  const char* field = features >= training ? "operators" : "hidden";
  internal::FailOption(
      "OperatorNetworkOptions", field, field[0] == 'o' ? o.operators : o.hidden,
      fmt::format("the nn-operators fit with {} operators and {} hidden units ({} weights per "
                  "network) on {} samples needs about {:.3g} GB, above the limit of {:.3g} GB; "
                  "use fewer operators, hidden units or samples",
                  o.operators, o.hidden, static_cast<long long>(weights), rows, bytes * 1e-9,
                  kTrainingMemoryLimitBytes * 1e-9));
}

}  // namespace

void OperatorNetworkOptions::Validate() const {
  auto fail = [](const char* field, double v, const std::string& rule) {
    internal::FailOption("OperatorNetworkOptions", field, v, rule);
  };
  if (operators < 0 || operators > kMaxPlayOperators)
    fail("operators", operators, fmt::format("0 <= operators <= {} (kMaxPlayOperators)", kMaxPlayOperators));
  if (hidden < 1 || hidden > 200) fail("hidden", hidden, "1 <= hidden <= 200");
  if (max_epochs < 1 || max_epochs > 100000) fail("max_epochs", max_epochs, "1 <= max_epochs <= 100000");
  if (restarts < 1 || restarts > 100) fail("restarts", restarts, "1 <= restarts <= 100");
}

Eigen::MatrixXd OperatorNetworkSide::Features(const Eigen::VectorXd& input) const {
  const size_t m = thresholds.size();
  Eigen::MatrixXd X(input.size(), static_cast<Eigen::Index>(m) + 1);
  std::vector<double> z(m, initial_input);
  for (Eigen::Index k = 0; k < input.size(); ++k) {
    X(k, 0) = input[k];
    for (size_t i = 0; i < m; ++i)
      X(k, static_cast<Eigen::Index>(i) + 1) = z[i] = PlayStep(input[k], thresholds[i], z[i]);
  }
  return X;
}

Eigen::VectorXd OperatorNetworkSide::Evaluate(const Eigen::VectorXd& input) const {
  return network.EvaluateBatch(Features(input));
}

OperatorNetworkModel::OperatorNetworkModel(OperatorNetworkSide forward, OperatorNetworkSide inverse)
    : forward_(std::move(forward)), inverse_(std::move(inverse)) {
  constexpr const char* kOwner = "OperatorNetworkModel";
  for (const OperatorNetworkSide* s : {&forward_, &inverse_}) {
    const char* side = s == &forward_ ? "forward" : "inverse";
    if (s->thresholds.size() > static_cast<size_t>(kMaxPlayOperators))
      internal::FailOption(kOwner, std::string(side) + ".thresholds", s->thresholds.size(),
                           fmt::format("at most {} operators", kMaxPlayOperators));
    for (size_t i = 0; i < s->thresholds.size(); ++i)
      if (!std::isfinite(s->thresholds[i]) || !(s->thresholds[i] > 0) ||
          (i > 0 && !(s->thresholds[i] > s->thresholds[i - 1])))
        internal::FailOption(kOwner, fmt::format("{}.thresholds[{}]", side, i), s->thresholds[i],
                             "> 0 and strictly increasing");
    if (!std::isfinite(s->initial_input))
      internal::FailOption(kOwner, std::string(side) + ".initial_input", s->initial_input,
                           "finite");
    if (static_cast<size_t>(s->network.input_count()) != s->thresholds.size() + 1)
      internal::FailOption(kOwner, std::string(side) + ".network",
                           fmt::format("{} inputs", s->network.input_count()),
                           fmt::format("1 + {} operators", s->thresholds.size()));
    s->network.Validate();
  }
}

Eigen::VectorXd OperatorNetworkModel::Simulate(const Eigen::VectorXd& u, double) const {
  return forward_.Evaluate(u);
}

Eigen::VectorXd OperatorNetworkModel::Invert(const Eigen::VectorXd& y, double dt_s) const {
  const ScaledVariable& range = inverse_.network.inputs()[0];
  const double half = 0.5 * (range.max - range.min);
  for (Eigen::Index k = 0; k < y.size(); ++k) {
    // A NaN or inf reference (Python passes them; files cannot hold them) is not a value
    // "outside the range": say so, as the PI models do.
    if (!std::isfinite(y[k]))
      throw InputError(fmt::format("reference sample {}: x = {}: expected a finite number [m]", k,
                                   y[k]));
    if (!(y[k] >= range.min - half && y[k] <= range.max + half))
      throw InputError(fmt::format(
          "reference sample {} (t = {:.6g} s): x = {:.9g} m is outside the nn-operators model's "
          "range [{:.6g}, {:.6g}] m (the inverse network's training range widened by half its "
          "span)", k, static_cast<double>(k) * dt_s, y[k], range.min - half, range.max + half));
  }
  return inverse_.Evaluate(y);
}

std::unique_ptr<HysteresisInverseStepper> OperatorNetworkModel::InverseStepper(double) const {
  return std::make_unique<OperatorNetworkInverseStepper>(*this);
}

std::vector<HysteresisParameter> OperatorNetworkModel::parameters() const {
  std::vector<HysteresisParameter> out;
  for (const OperatorNetworkSide* s : {&forward_, &inverse_}) {
    const Eigen::VectorXd theta = s->network.parameters();
    const char* side = s == &forward_ ? "forward" : "inverse";
    for (Eigen::Index j = 0; j < theta.size(); ++j)
      out.push_back({fmt::format("{}.theta[{}]", side, j), "1", theta[j], NAN});
  }
  return out;
}

std::string OperatorNetworkModel::ToJson(int indent) const {
  nlohmann::ordered_json j;
  j["kind"] = kind();
  for (const OperatorNetworkSide* s : {&forward_, &inverse_}) {
    nlohmann::ordered_json side;
    side["thresholds"] = s->thresholds;
    side["initial_input"] = s->initial_input;
    side["network"] = nlohmann::ordered_json::parse(NeuralNetworkToJson(s->network, 0));
    j[s == &forward_ ? "forward" : "inverse"] = side;
  }
  return internal::DumpJson(j, indent);
}

std::unique_ptr<OperatorNetworkModel> OperatorNetworkFromJson(std::string_view text,
                                                              const std::string& source) {
  const internal::JsonDocument doc(text, source);
  const internal::JsonNode root = doc.Root();
  root.ExpectObject({"kind", "forward", "inverse"}, {"fit"});
  if (root.Get("kind").String() != "nn-operators") root.Get("kind").Expected("\"nn-operators\"");
  OperatorNetworkSide sides[2];
  const char* names[2] = {"forward", "inverse"};
  for (int s = 0; s < 2; ++s) {
    const internal::JsonNode node = root.Get(names[s]);
    node.ExpectObject({"thresholds", "initial_input", "network"});
    const internal::JsonNode th = node.Get("thresholds");
    th.ExpectArray();
    if (th.Size() > static_cast<size_t>(kMaxPlayOperators))
      th.Fail(fmt::format("{} operators, more than the bound {}", th.Size(), kMaxPlayOperators));
    sides[s].thresholds = th.Numbers();
    sides[s].initial_input = node.Get("initial_input").Number();
    sides[s].network = ParseNeuralNetwork(node.Get("network").json().dump(),
                                          fmt::format("{} ({}.network)", source, names[s]));
  }
  std::unique_ptr<OperatorNetworkModel> model;
  internal::ValidateOptions(doc, [&] {
    model = std::make_unique<OperatorNetworkModel>(sides[0], sides[1]);
  });
  return model;
}

std::unique_ptr<OperatorNetworkModel> FitOperatorNetwork(const std::vector<Recording>& recordings,
                                                         const OperatorNetworkOptions& options,
                                                         HysteresisFitSummary* summary) {
  options.Validate();
  const auto start = std::chrono::steady_clock::now();
  if (recordings.empty()) throw InputError("nn-operators fit: no recordings");
  CheckFitMemory(recordings, options);
  std::vector<Eigen::VectorXd> u, x;
  for (const Recording& rec : recordings) {
    u.emplace_back(rec.column("u"));
    x.emplace_back(rec.column("x"));
  }
  NeuralTrainingResult rf, ri;
  OperatorNetworkSide forward = TrainSide(u, x, "u", "V", "x", "m", 0.0, options, &rf);
  OperatorNetworkSide inverse = TrainSide(x, u, "x", "m", "u", "V", x.front()[0], options, &ri);
  auto model = std::make_unique<OperatorNetworkModel>(std::move(forward), std::move(inverse));
  if (summary) {
    Eigen::Index n = 0;
    double sse = 0;
    for (size_t r = 0; r < u.size(); ++r) {
      sse += (model->Simulate(u[r], 0) - x[r]).squaredNorm();
      n += u[r].size();
    }
    summary->kind = model->kind();
    summary->samples = static_cast<int>(n);
    summary->fit_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    summary->training_rms = std::sqrt(sse / static_cast<double>(n));
    summary->converged = rf.termination == Termination::kConverged && ri.termination == Termination::kConverged;
    summary->message = fmt::format("forward network: {} epochs, {}; inverse network: {} epochs, {} "
                                   "(inverse training MSE {:.3g} V^2)",
                                   rf.epochs, rf.message, ri.epochs, ri.message, ri.train_mse);
  }
  return model;
}

}  // namespace sysid
