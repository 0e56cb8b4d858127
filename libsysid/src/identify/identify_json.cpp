// JSON of the identification options (every field; each key optional when read) and results: the model file's text (ModelToJson) with a "diagnostics"
// object, the form `sysid identify --json` prints and `-o` writes (docs/cli.md). The readers
// take that text back (any model file reader also accepts it: "diagnostics" rides along).
#include "identify/identify_json.hpp"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "model/model_json.hpp"
#include "motion/motion_json.hpp"
#include "sysid/identify.hpp"
#include "sysid/model.hpp"

namespace sysid {
namespace {

using internal::JsonNode;
using internal::NumberOrNull;
using Json = nlohmann::ordered_json;

// The model's keys first (a valid model file), the diagnostics after them.
Json ModelObject(const FrictionModel& m) { return Json::parse(ModelToJson(m, -1)); }

// Fit statistics shared by both methods.
Json FitStatistics(const LinearFit& f) {
  Json j;
  j["rows"] = f.rows;
  j["rank"] = f.rank;
  j["dof"] = f.dof;
  j["condition_number"] = f.condition_number;
  j["rms_residual"] = f.rms_residual;
  j["relative_error"] = f.relative_error;
  Json rd = Json::array();
  for (const auto& [name, value] : f.r_diagonal)
    rd.push_back({{"parameter", name}, {"abs_r", value}});
  j["r_diagonal"] = rd;
  return j;
}

void ReadFitStatistics(const JsonNode& d, LinearFit& f) {
  f.rows = d.Get("rows").Integer(0, std::numeric_limits<long>::max());
  f.rank = static_cast<int>(d.Get("rank").Integer(0, 1000));
  f.dof = static_cast<int>(d.Get("dof").Integer(-1000, std::numeric_limits<int>::max()));
  f.condition_number = d.Get("condition_number").NumberOrNaN();
  f.rms_residual = d.Get("rms_residual").NumberOrNaN();
  f.relative_error = d.Get("relative_error").NumberOrNaN();
  const JsonNode rd = d.Get("r_diagonal");
  rd.ExpectArray();
  for (size_t i = 0; i < rd.Size(); ++i) {
    const JsonNode e = rd.Element(i);
    e.ExpectObject({"parameter", "abs_r"});
    f.r_diagonal.emplace_back(e.Get("parameter").String(), e.Get("abs_r").NumberOrNaN());
  }
}

// Estimates with standard errors by name, and their covariance.
Json Parameters(const std::vector<std::string>& names, const Eigen::VectorXd& est,
                const Eigen::VectorXd& se, const Eigen::MatrixXd& cov) {
  Json p = Json::object();
  for (size_t i = 0; i < names.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    p[names[i]] = {{"estimate", est[k]}, {"std_error", NumberOrNull(se[k])}};
  }
  return {{"parameters", p}, {"covariance_order", names}, {"covariance", internal::MatrixJson(cov)}};
}

void ReadParameters(const JsonNode& d, std::vector<std::string>& names, Eigen::VectorXd& est,
                    Eigen::VectorXd& se, Eigen::MatrixXd& cov) {
  const JsonNode order = d.Get("covariance_order");
  order.ExpectArray();
  names.clear();
  for (size_t i = 0; i < order.Size(); ++i) names.push_back(order.Element(i).String(true));
  const auto n = static_cast<Eigen::Index>(names.size());
  est.resize(n);
  se.resize(n);
  const JsonNode p = d.Get("parameters");
  p.ExpectObject(names);
  for (Eigen::Index k = 0; k < n; ++k) {
    const JsonNode e = p.Get(names[static_cast<size_t>(k)]);
    e.ExpectObject({"estimate", "std_error"});
    est[k] = e.Get("estimate").Number();
    se[k] = e.Get("std_error").NumberOrNaN();
  }
  cov = internal::MatrixFromJson(d.Get("covariance"), names.size(), names.size());
}

PulseStatus PulseStatusFromJson(const JsonNode& node) {
  const std::string s = node.String();
  for (auto status : {PulseStatus::kOk, PulseStatus::kUnsettled, PulseStatus::kStuck,
                      PulseStatus::kWrongDirection, PulseStatus::kVelocityLimit,
                      PulseStatus::kTravelLimit, PulseStatus::kTooFewSamples})
    if (ToString(status) == s) return status;
  node.Expected(
      "a pulse status (ok, unsettled, stuck, wrong-direction, velocity-limit, "
      "travel-limit, too-few-samples)");
}

// The model (checked as a model file) and the "diagnostics" object of `method` with `keys`.
JsonNode Diagnostics(const internal::JsonDocument& doc, const std::string& method,
                     const std::vector<std::string>& keys, FrictionModel& model) {
  model = internal::ModelFromJson(doc, doc.Root(), {"units", "diagnostics"});
  const JsonNode d = doc.Root().Get("diagnostics");
  d.ExpectObject(keys);
  if (d.Get("method").String() != method) d.Get("method").Expected("\"" + method + "\"");
  return d;
}

}  // namespace

std::string ToJson(const PulseIdentificationResult& r, int indent) {
  Json j = ModelObject(r.model);
  Json d;
  d["method"] = "pulse";
  d["a3_given"] = r.model.a3;
  d.update(Parameters(r.fit.names, r.fit.theta, r.fit.std_error, r.fit.covariance));
  d.update(FitStatistics(r.fit));
  Json eq = Json::array();
  for (size_t i = 0; i < r.points.size(); ++i)
    eq.push_back({{"label", r.points[i].label},
                  {"u_v", r.points[i].u_v},
                  {"v_mps", r.points[i].v_mps},
                  {"residual_mps2", r.fit.residuals[static_cast<Eigen::Index>(i)]}});
  d["equations"] = eq;
  if (!r.pulses.empty()) {
    Json pulses = Json::array();
    for (const auto& e : r.pulses)
      pulses.push_back({{"source", e.pulse.source},
                        {"t_start_s", e.pulse.t_start_s},
                        {"duration_s", e.pulse.duration_s},
                        {"amplitude_v", e.pulse.amplitude_v},
                        {"v_mps", e.v_mps},
                        {"v_stderr_mps", NumberOrNull(e.v_stderr_mps)},
                        {"drift_mps", e.drift_mps},
                        {"status", ToString(e.status)},
                        {"reason", e.reason}});
    d["pulses"] = pulses;
  }
  j["diagnostics"] = d;
  return internal::DumpJson(j, indent);
}

PulseIdentificationResult PulseIdentificationResultFromJson(std::string_view text,
                                                            const std::string& source_name) {
  PulseIdentificationResult r;
  const internal::JsonDocument doc(text, source_name);
  const JsonNode d = Diagnostics(
      doc, "pulse",
      {"method", "a3_given", "parameters", "covariance_order", "covariance", "rows", "rank", "dof",
       "condition_number", "rms_residual", "relative_error", "r_diagonal", "equations", "pulses"},
      r.model);
  ReadParameters(d, r.fit.names, r.fit.theta, r.fit.std_error, r.fit.covariance);
  ReadFitStatistics(d, r.fit);
  const JsonNode eq = d.Get("equations");
  eq.ExpectArray();
  r.fit.residuals.resize(static_cast<Eigen::Index>(eq.Size()));
  for (size_t i = 0; i < eq.Size(); ++i) {
    const JsonNode e = eq.Element(i);
    e.ExpectObject({"label", "u_v", "v_mps", "residual_mps2"});
    r.points.push_back({e.Get("u_v").Number(), e.Get("v_mps").Number(), e.Get("label").String()});
    r.fit.residuals[static_cast<Eigen::Index>(i)] = e.Get("residual_mps2").NumberOrNaN();
  }
  if (d.Has("pulses")) {
    const JsonNode pulses = d.Get("pulses");
    pulses.ExpectArray();
    for (size_t i = 0; i < pulses.Size(); ++i) {
      const JsonNode p = pulses.Element(i);
      p.ExpectObject({"source", "t_start_s", "duration_s", "amplitude_v", "v_mps", "v_stderr_mps",
                      "drift_mps", "status", "reason"});
      PulseEstimate e;
      e.pulse.source = p.Get("source").String();
      e.pulse.t_start_s = p.Get("t_start_s").Number();
      e.pulse.duration_s = p.Get("duration_s").Number(internal::NumberRule::NonNegative());
      e.pulse.amplitude_v = p.Get("amplitude_v").Number();
      e.v_mps = p.Get("v_mps").NumberOrNaN();
      e.v_stderr_mps = p.Get("v_stderr_mps").NumberOrNaN();
      e.drift_mps = p.Get("drift_mps").NumberOrNaN();
      e.status = PulseStatusFromJson(p.Get("status"));
      e.reason = p.Get("reason").String();
      r.pulses.push_back(e);
    }
  }
  return r;
}

std::string ToJson(const TrajectoryIdentificationResult& r, int indent) {
  Json j = ModelObject(r.model);
  Json d;
  d["method"] = "trajectory";
  d["derivative"] = ToString(r.derivative);
  d.update(Parameters(r.names, r.estimate, r.std_error, r.covariance));
  d["offset_mps2"] = r.offset_mps2;
  d["samples_used"] = r.samples_used;
  d["linear_fit"] = FitStatistics(r.fit);
  d["linear_fit"]["theta_names"] = r.fit.names;
  d["linear_fit"]["theta"] = internal::VectorJson(r.fit.theta);
  d["relative_error"] = r.relative_error;
  if (!r.tau_curve.empty()) {
    Json c = Json::array();
    for (const auto& [t, f] : r.tau_curve) c.push_back({t, f});
    d["tau_curve"] = c;
  }
  j["diagnostics"] = d;
  return internal::DumpJson(j, indent);
}

TrajectoryIdentificationResult TrajectoryIdentificationResultFromJson(
    std::string_view text, const std::string& source_name) {
  TrajectoryIdentificationResult r;
  const internal::JsonDocument doc(text, source_name);
  const JsonNode d =
      Diagnostics(doc, "trajectory",
                  {"method", "derivative", "parameters", "covariance_order", "covariance",
                   "offset_mps2", "samples_used", "linear_fit", "relative_error", "tau_curve"},
                  r.model);
  try {
    r.derivative = ParseDerivativeMethod(d.Get("derivative").String());
  } catch (const std::exception&) {
    d.Get("derivative").Expected("central, butterworth or savgol");
  }
  ReadParameters(d, r.names, r.estimate, r.std_error, r.covariance);
  r.offset_mps2 = d.Get("offset_mps2").Number();
  r.samples_used = d.Get("samples_used").Integer(0, std::numeric_limits<long>::max());
  const JsonNode f = d.Get("linear_fit");
  f.ExpectObject({"rows", "rank", "dof", "condition_number", "rms_residual", "relative_error",
                  "r_diagonal", "theta_names", "theta"});
  ReadFitStatistics(f, r.fit);
  const JsonNode names = f.Get("theta_names");
  names.ExpectArray();
  for (size_t i = 0; i < names.Size(); ++i) r.fit.names.push_back(names.Element(i).String(true));
  r.fit.theta = internal::VectorFromJson(f.Get("theta"), r.fit.names.size());
  r.relative_error = d.Get("relative_error").NumberOrNaN();
  if (d.Has("tau_curve")) {
    const JsonNode c = d.Get("tau_curve");
    c.ExpectArray();
    for (size_t i = 0; i < c.Size(); ++i) {
      const auto tf = c.Element(i).Numbers(2);
      r.tau_curve.emplace_back(tf[0], tf[1]);
    }
  }
  return r;
}

// ---- Options ----


namespace {

void ReadPulseIdentificationOptions(const JsonNode& node, PulseIdentificationOptions& o) {
  internal::ReadFields(node, o);
  // A file that names the fit's a3 gives it (PulseFitOptions::a3_given).
  if (node.Has("fit") && node.Get("fit").Has("a3")) o.fit.a3_given = true;
}

void ReadPulseFitOptions(const JsonNode& node, PulseFitOptions& o) {
  internal::ReadFields(node, o);
  if (node.Has("a3")) o.a3_given = true;
}

}  // namespace

std::string ToJson(const PulseDetectionOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

PulseDetectionOptions PulseDetectionOptionsFromJson(std::string_view text,
                                                    const std::string& source_name) {
  return internal::FieldsFromJson<PulseDetectionOptions>(text, source_name);
}

std::string ToJson(const PlateauOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

PlateauOptions PlateauOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<PlateauOptions>(text, source_name);
}

std::string ToJson(const PulseFitOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

PulseFitOptions PulseFitOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::OptionsFromJson<PulseFitOptions>(text, source_name, ReadPulseFitOptions);
}

std::string ToJson(const PulseIdentificationOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

PulseIdentificationOptions PulseIdentificationOptionsFromJson(std::string_view text,
                                                              const std::string& source_name) {
  return internal::OptionsFromJson<PulseIdentificationOptions>(text, source_name,
                                                               ReadPulseIdentificationOptions);
}

std::string ToJson(const TrajectoryOptions& o, int indent) {
  return internal::FieldsToJson(o, indent);
}

TrajectoryOptions TrajectoryOptionsFromJson(std::string_view text, const std::string& source_name) {
  return internal::FieldsFromJson<TrajectoryOptions>(text, source_name);
}

}  // namespace sysid
