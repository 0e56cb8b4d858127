// JSON of the identification options (every field; each key optional when read) and results:
// the model file's object with a "diagnostics" object, the form `sysid identify --json` prints
// and `-o` writes (docs/cli.md). The readers take that text back (any model file reader also
// accepts it: "diagnostics" rides along).
#include "identify/identify_json.hpp"

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "model/model_json.hpp"
#include "signal/signal_json.hpp"
#include "sysid/identify.hpp"
#include "sysid/model.hpp"

namespace sysid {

nlohmann::ordered_json internal::JsonForm<PulseStatus>::Write(const PulseStatus& status) {
  return ToString(status);
}

void internal::JsonForm<PulseStatus>::Read(const JsonNode& node, PulseStatus& status) {
  status = internal::ReadName(
      node,
      {PulseStatus::kOk, PulseStatus::kUnsettled, PulseStatus::kStuck,
       PulseStatus::kWrongDirection, PulseStatus::kVelocityLimit, PulseStatus::kTravelLimit,
       PulseStatus::kTooFewSamples},
      [](PulseStatus s) { return ToString(s); }, "a pulse status");
}

namespace {

using internal::JsonNode;
using Json = nlohmann::ordered_json;

// The keys a result's JSON adds around its described fields.
constexpr char kDiagnostics[] = "diagnostics";
constexpr char kMethod[] = "method";
constexpr char kParameters[] = "parameters";
constexpr char kOrder[] = "covariance_order";
constexpr char kCovariance[] = "covariance";
constexpr char kEquations[] = "equations";
constexpr char kResidual[] = "residual_mps2";
constexpr char kLinearFit[] = "linear_fit";
// The a3 the pulse fit was given [m/(s^2 V)] (the model's: steady states cannot separate it).
constexpr char kA3Given[] = "a3_given";

// Estimates with standard errors by name, and their covariance.
Json Parameters(const std::vector<std::string>& names, const Eigen::VectorXd& est,
                const Eigen::VectorXd& se, const Eigen::MatrixXd& cov) {
  Json p = Json::object();
  for (size_t i = 0; i < names.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    p[names[i]] = {{"estimate", est[k]}, {"std_error", internal::NumberOrNull(se[k])}};
  }
  return {{kParameters, p}, {kOrder, names}, {kCovariance, internal::MatrixJson(cov)}};
}

void ReadParameters(const JsonNode& d, std::vector<std::string>& names, Eigen::VectorXd& est,
                    Eigen::VectorXd& se, Eigen::MatrixXd& cov) {
  const JsonNode order = d.Get(kOrder);
  order.ExpectArray();
  names.clear();
  for (size_t i = 0; i < order.Size(); ++i) names.push_back(order.Element(i).String(true));
  const auto n = static_cast<Eigen::Index>(names.size());
  est.resize(n);
  se.resize(n);
  const JsonNode p = d.Get(kParameters);
  p.ExpectObject(names);
  for (Eigen::Index k = 0; k < n; ++k) {
    const JsonNode e = p.Get(names[static_cast<size_t>(k)]);
    e.ExpectObject({"estimate", "std_error"});
    est[k] = e.Get("estimate").Number();
    se[k] = e.Get("std_error").NumberOrNaN();
  }
  cov = internal::MatrixFromJson(d.Get(kCovariance), names.size(), names.size());
}

// The pulse fit's equations: each point with its residual [m/s^2].
Json Equations(const std::vector<PulsePoint>& points, const Eigen::VectorXd& residuals) {
  Json eq = Json::array();
  for (size_t i = 0; i < points.size(); ++i) {
    Json e = internal::WriteFields(points[i]);
    e[kResidual] = residuals[static_cast<Eigen::Index>(i)];
    eq.push_back(e);
  }
  return eq;
}

void ReadEquations(const JsonNode& eq, std::vector<PulsePoint>& points,
                   Eigen::VectorXd& residuals) {
  eq.ExpectArray();
  points.assign(eq.Size(), PulsePoint{});
  residuals.resize(static_cast<Eigen::Index>(eq.Size()));
  for (size_t i = 0; i < eq.Size(); ++i) {
    const JsonNode e = eq.Element(i);
    internal::ReadFields(e, points[i], {kResidual});
    residuals[static_cast<Eigen::Index>(i)] = e.Get(kResidual).NumberOrNaN();
  }
}

// The trajectory fit in u-space: its statistics, then the coefficients by name.
struct TrajectoryFit {
  LinearFit* fit;
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(NameValue<LinearFit>("fit", fit).Inline());
    a->Visit(NameValue<std::vector<std::string>>("theta_names", &fit->names));
    a->Visit(NameValue<Eigen::VectorXd>("theta", &fit->theta));
  }
};

// A result's text: the model file's object, then the diagnostics of `method`.
std::string ResultText(const FrictionModel& model, const char* method, const Json& fields,
                       int indent) {
  Json j = internal::ModelJson(model);
  Json d = {{kMethod, method}};
  d.update(fields);
  j[kDiagnostics] = d;
  return internal::DumpJson(j, indent);
}

// The model (checked as a model file) and the "diagnostics" object of `method`, whose keys are
// read by the caller.
JsonNode Diagnostics(const internal::JsonDocument& doc, const char* method, FrictionModel& model) {
  model = internal::ModelFromJson(doc, doc.Root(), {kDiagnostics});
  const JsonNode d = doc.Root().Get(kDiagnostics);
  if (d.Get(kMethod).String() != method) d.Get(kMethod).Expected(std::string("\"") + method + "\"");
  return d;
}

}  // namespace

std::string ToJson(const PulseIdentificationResult& r, int indent) {
  Json d = {{kA3Given, r.model.a3}};
  d.update(Parameters(r.fit.names, r.fit.theta, r.fit.std_error, r.fit.covariance));
  d.update(internal::WriteFields(r));
  d[kEquations] = Equations(r.points, r.fit.residuals);
  return ResultText(r.model, "pulse", d, indent);
}

PulseIdentificationResult PulseIdentificationResultFromJson(std::string_view text,
                                                            const std::string& source_name) {
  PulseIdentificationResult r;
  const internal::JsonDocument doc(text, source_name);
  const JsonNode d = Diagnostics(doc, "pulse", r.model);
  internal::ReadFields(d, r, {kMethod, kA3Given, kParameters, kOrder, kCovariance, kEquations});
  ReadParameters(d, r.fit.names, r.fit.theta, r.fit.std_error, r.fit.covariance);
  ReadEquations(d.Get(kEquations), r.points, r.fit.residuals);
  return r;
}

std::string ToJson(const TrajectoryIdentificationResult& r, int indent) {
  Json d = internal::WriteFields(r);
  d.update(Parameters(r.names, r.estimate, r.std_error, r.covariance));
  d[kLinearFit] = internal::WriteFields(TrajectoryFit{const_cast<LinearFit*>(&r.fit)});
  return ResultText(r.model, "trajectory", d, indent);
}

TrajectoryIdentificationResult TrajectoryIdentificationResultFromJson(
    std::string_view text, const std::string& source_name) {
  TrajectoryIdentificationResult r;
  const internal::JsonDocument doc(text, source_name);
  const JsonNode d = Diagnostics(doc, "trajectory", r.model);
  internal::ReadFields(d, r, {kMethod, kParameters, kOrder, kCovariance, kLinearFit});
  ReadParameters(d, r.names, r.estimate, r.std_error, r.covariance);
  TrajectoryFit fit{&r.fit};
  internal::ReadFields(d.Get(kLinearFit), fit);
  return r;
}

// ---- Options ----

namespace {

// A file that names the fit's a3 gives it (PulseFitOptions::a3_given).
void ReadPulseFitOptions(const JsonNode& node, PulseFitOptions& o) {
  internal::ReadFields(node, o);
  if (node.Has("a3")) o.a3_given = true;
}

void ReadPulseIdentificationOptions(const JsonNode& node, PulseIdentificationOptions& o) {
  internal::ReadFields(node, o);
  if (node.Has("fit")) ReadPulseFitOptions(node.Get("fit"), o.fit);
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
