#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "core/option_rule.hpp"
#include "sysid/compare.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/model_stepper.hpp"
#include "sysid/motion.hpp"

namespace sysid {

PredictionErrors ComputePredictionErrors(const Eigen::VectorXd& measured,
                                         const Eigen::VectorXd& predicted) {
  SYSID_CHECK(measured.size() == predicted.size() && measured.size() >= 2,
              "sizes " + std::to_string(measured.size()) + ", " + std::to_string(predicted.size()));
  const Eigen::VectorXd e = predicted - measured;
  PredictionErrors r;
  r.rmse_v = std::sqrt(e.squaredNorm() / static_cast<double>(e.size()));
  r.peak_error_v = e.cwiseAbs().maxCoeff();
  const double range = measured.maxCoeff() - measured.minCoeff();
  r.nrmse_range = range > 0 ? r.rmse_v / range : std::numeric_limits<double>::quiet_NaN();
  const double sst = (measured.array() - measured.mean()).square().sum();
  r.r2 = sst > 0 ? 1.0 - e.squaredNorm() / sst : std::numeric_limits<double>::quiet_NaN();
  return r;
}

namespace {

/// The inverses pair v[k] with a[k]: a length mismatch is the caller's data error.
void CheckSameLength(const Eigen::VectorXd& v_mps, const Eigen::VectorXd& a_mps2,
                     const char* who) {
  if (v_mps.size() != a_mps2.size())
    throw InputError(std::string(who) + ": v_mps has " + std::to_string(v_mps.size()) +
                     " values, a_mps2 has " + std::to_string(a_mps2.size()) +
                     "; the two must be equally long (one value per sample)");
}

}  // namespace

Eigen::VectorXd AnalyticInverse(const FrictionModel& model, double dt_s,
                                const Eigen::VectorXd& v_mps, const Eigen::VectorXd& a_mps2) {
  // As every model consumer does: a3 = 0 would give u = inf, a NaN field NaN, without a word.
  model.Validate();
  CheckSameLength(v_mps, a_mps2, "AnalyticInverse");
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    internal::FailOption("AnalyticInverse", "dt_s", dt_s, "0 < dt_s < infinity");
  FrictionInverseStepper stepper(model, dt_s, static_cast<long long>(v_mps.size()));
  Eigen::VectorXd u(v_mps.size());
  for (Eigen::Index k = 0; k < u.size(); ++k) {
    u[k] = stepper.Step(v_mps[k], a_mps2[k]);
    // Finite parameters can still overflow (a3 = 1e-308 divides): said, never scored as inf.
    if (!std::isfinite(u[k]))
      throw NumericalError(fmt::format(
          "AnalyticInverse: u = {} V at sample {} (v = {:g} m/s, a = {:g} m/s^2): the model "
          "(a1p {:g}, a1n {:g}, a2p {:g}, a2n {:g}, a3 {:g}) overflows there",
          u[k], k, v_mps[k], a_mps2[k], model.a1p, model.a1n, model.a2p, model.a2n, model.a3));
  }
  return u;
}

namespace {

// The network's outputs, checked: weights of 1e308 in a file are finite, their sums are not.
Eigen::VectorXd CheckedNetworkOutput(Eigen::VectorXd u) {
  for (Eigen::Index k = 0; k < u.size(); ++k)
    if (!std::isfinite(u[k]))
      throw NumericalError(fmt::format(
          "NetworkInverse: u = {} V at sample {}: the network's output overflows (weights or "
          "ranges out of range)",
          u[k], k));
  return u;
}

}  // namespace

Eigen::VectorXd NetworkInverse(const NeuralNetwork& network, const Eigen::VectorXd& v_mps,
                               const Eigen::VectorXd& a_mps2, const Recording* recording) {
  CheckSameLength(v_mps, a_mps2, "NetworkInverse");
  Eigen::MatrixXd X(v_mps.size(), network.input_count());
  for (int i = 0; i < network.input_count(); ++i) {
    const std::string& name = network.inputs()[static_cast<size_t>(i)].name;
    if (name == "v") {
      X.col(i) = v_mps;
    } else if (name == "a") {
      X.col(i) = a_mps2;
    } else if (recording) {
      X.col(i) = recording->column(name);  // throws InputError naming the missing column
    } else {
      throw InputError("network input '" + name +
                       "' is neither v [m/s] nor a [m/s^2]; an inverse-model network takes "
                       "the velocity and/or acceleration");
    }
  }
  return CheckedNetworkOutput(network.EvaluateBatch(X));
}

Eigen::VectorXd HysteresisInverse(const HysteresisModel& model, const Recording& recording) {
  // column() names the source and the missing column
  return model.Invert(recording.column("x"), RecordingStep(recording));
}

std::string HysteresisInverseResult::TraceColumn() const {
  std::string name = "u_" + label;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_') ch = '_';
  return name;
}

void CompareOptions::Validate() const {
  if (trim_samples < 0)
    internal::FailOption("CompareOptions", "trim_samples", trim_samples, "trim_samples >= 0");
}

Recording InverseComparison::AsRecording() const {
  Recording rec;
  rec.source = source;
  rec.metadata = {{"content", "measured and predicted voltages of inverse models"},
                  {"units", "t [s], u [V], u_analytic [V], u_nn [V], u_* [V], v [m/s], a [m/s^2]"}};
  rec.SetColumn("t", t_s);
  rec.SetColumn("u", u_measured_v);
  if (has_analytic) rec.SetColumn("u_analytic", u_analytic_v);
  if (has_nn) rec.SetColumn("u_nn", u_nn_v);
  // Labels differ, but "pi:a-b" and "pi:a_b" give one column name: a later one gets a
  // suffix instead of replacing the first one's trace.
  for (const auto& h : hysteresis) {
    std::string name = h.TraceColumn();
    for (int k = 2; rec.has(name); ++k) name = h.TraceColumn() + "_" + std::to_string(k);
    rec.SetColumn(name, h.u_v);
  }
  rec.SetColumn("v", v_mps);
  rec.SetColumn("a", a_mps2);
  return rec;
}

InverseComparison CompareInverseModels(const Recording& recording, const FrictionModel& model,
                                       const NeuralNetwork* network,
                                       const CompareOptions& options) {
  return CompareInverseModels(recording, &model, network, {}, options);
}

InverseComparison CompareInverseModels(const Recording& recording, const FrictionModel* model,
                                       const NeuralNetwork* network,
                                       const std::vector<NamedHysteresisModel>& hysteresis,
                                       const CompareOptions& options) {
  options.Validate();
  if (!model && !network && hysteresis.empty())
    internal::FailOption("CompareInverseModels", "models", "none",
                         "a friction model, a network or at least one hysteresis model");
  if (model) model->Validate();
  InverseComparison c;
  c.source = recording.source;
  MotionOptions mo;
  mo.derivative = options.derivative;
  mo.prefer_velocity_column = options.use_recorded_columns;
  MotionSignals motion = ExtractMotion(recording, mo);
  c.motion_from = motion.velocity_from;
  const double dt = motion.dt_s;
  const Eigen::VectorXd t = std::move(motion.t_s), u = std::move(motion.u_v),
                        v = std::move(motion.v_mps), a = std::move(motion.a_mps2);
  const Eigen::Index n = t.size(), trim = options.trim_samples;
  if (n - 2 * trim < 2)
    throw InputError(recording.source + ": " + std::to_string(n) +
                     " rows leave too few samples after trimming " + std::to_string(trim) +
                     " at each end");
  const Eigen::Index m = n - 2 * trim;
  c.t_s = t.segment(trim, m);
  c.u_measured_v = u.segment(trim, m);
  c.v_mps = v.segment(trim, m);
  c.a_mps2 = a.segment(trim, m);
  if (recording.has("x") && recording.rows() == n) c.x_m = recording.column("x").segment(trim, m);
  c.has_analytic = model != nullptr;
  if (model) {
    c.u_analytic_v = AnalyticInverse(*model, dt, v, a).segment(trim, m);
    c.analytic = ComputePredictionErrors(c.u_measured_v, c.u_analytic_v);
  }
  if (network) {
    c.u_nn_v = NetworkInverse(*network, v, a, &recording).segment(trim, m);
    c.nn = ComputePredictionErrors(c.u_measured_v, c.u_nn_v);
    c.has_nn = true;
  }
  for (const auto& named : hysteresis) {
    SYSID_CHECK(named.model != nullptr, "hysteresis model '" + named.label + "' is null");
    // The inverse runs over the whole recording from the model's initial state (its state
    // needs the samples before the scored ones), then is scored on the trimmed samples.
    Eigen::VectorXd u_h;
    try {
      u_h = HysteresisInverse(*named.model, recording);
    } catch (const InputError& e) {
      throw InputError(recording.source + ": " + named.label + ": " + e.what());
    } catch (const NumericalError& e) {
      throw NumericalError(recording.source + ": " + named.label + ": " + e.what());
    }
    HysteresisInverseResult h;
    h.label = named.label;
    h.kind = named.model->kind();
    h.u_v = u_h.segment(trim, m);
    h.errors = ComputePredictionErrors(c.u_measured_v, h.u_v);
    c.hysteresis.push_back(std::move(h));
  }
  return c;
}

}  // namespace sysid
