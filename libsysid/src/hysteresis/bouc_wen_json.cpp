// Bouc–Wen model files and the options' rules.
#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "core/json_fields.hpp"
#include "core/json_text.hpp"
#include "hysteresis/hysteresis_json.hpp"
#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis_bouc_wen.hpp"

namespace sysid {

namespace {

[[noreturn]] void Violated(const char* type, const char* field, double value, const char* rule) {
  internal::FailOption(type, field, value, rule);
}

const char* ToString(BoucWenIntegrator i) {
  switch (i) {
    case BoucWenIntegrator::kCvode:
      return "cvode";
    case BoucWenIntegrator::kBenchmarkChain:
      return "benchmark-chain";
    case BoucWenIntegrator::kFixedStep:
      return "fixed-step";
    case BoucWenIntegrator::kAuto:
      return "auto";
  }
  return "?";
}
const char* ToString(InputInterpolation i) {
  switch (i) {
    case InputInterpolation::kHold:
      return "hold";
    case InputInterpolation::kLinear:
      return "linear";
    case InputInterpolation::kBandLimited:
      return "band-limited";
    case InputInterpolation::kAuto:
      return "auto";
  }
  return "?";
}

template <class Parameters>
nlohmann::ordered_json ModelJson(const char* kind, const Parameters& p,
                                 const std::vector<HysteresisParameter>& ps,
                                 const BoucWenSimulationOptions& o, const char* note) {
  // The described parameters and simulation, framed by the kind, the standard errors (when the
  // fit gave any) and units of parameters(), and the equations.
  nlohmann::ordered_json j, errors, units;
  j["kind"] = kind;
  bool any_error = false;
  for (const auto& q : ps) {
    errors[q.name] = internal::NumberOrNull(q.std_error);
    units[q.name] = q.unit;
    any_error = any_error || std::isfinite(q.std_error);
  }
  j["parameters"] = internal::WriteFields(p);
  if (any_error) j["std_errors"] = errors;
  j["units"] = units;
  j["simulation"] = internal::WriteFields(o);
  j["note"] = note;
  return j;
}

BoucWenSimulationOptions SimulationFromJson(const internal::JsonDocument& doc,
                                            const internal::JsonNode& node) {
  BoucWenSimulationOptions o;
  internal::ReadFields(node, o);
  internal::ValidateOptions(
      doc, [&] { o.Validate(); }, node.pointer());
  return o;
}

// The standard errors, in parameters() order; empty when the file has none.
std::vector<double> ErrorsFromJson(const internal::JsonNode& root,
                                   const std::vector<std::string>& names) {
  if (!root.Has("std_errors")) return {};
  const auto node = root.Get("std_errors");
  node.ExpectObject(names);
  std::vector<double> e(names.size(), NAN);
  for (size_t i = 0; i < names.size(); ++i)
    if (node.Has(names[i]))
      e[i] = node.Get(names[i]).NumberOrNaN(internal::NumberRule::NonNegative());
  return e;
}

}  // namespace

namespace internal {

nlohmann::ordered_json JsonForm<BoucWenIntegrator>::Write(const BoucWenIntegrator& integrator) {
  return ToString(integrator);
}
void JsonForm<BoucWenIntegrator>::Read(const JsonNode& node, BoucWenIntegrator& integrator) {
  integrator = ReadName(node,
                        {BoucWenIntegrator::kCvode, BoucWenIntegrator::kBenchmarkChain,
                         BoucWenIntegrator::kFixedStep},
                        [](BoucWenIntegrator i) { return ToString(i); });
}

nlohmann::ordered_json JsonForm<InputInterpolation>::Write(const InputInterpolation& input) {
  return ToString(input);
}
void JsonForm<InputInterpolation>::Read(const JsonNode& node, InputInterpolation& input) {
  input = ReadName(
      node, {InputInterpolation::kHold, InputInterpolation::kLinear, InputInterpolation::kBandLimited},
      [](InputInterpolation i) { return ToString(i); });
}

}  // namespace internal

BoucWenSimulationOptions AutoBoucWenSimulation() {
  BoucWenSimulationOptions o;
  o.integrator = BoucWenIntegrator::kAuto;
  o.input = InputInterpolation::kAuto;
  return o;
}

namespace internal {

void CheckModelSimulation(const BoucWenSimulationOptions& o) {
  o.Validate();
  if (o.integrator == BoucWenIntegrator::kAuto)
    FailOption("BoucWenSimulationOptions", "integrator", "auto",
               "auto is a fit's choice (BoucWenFitOptions); a model takes cvode, "
               "benchmark-chain or fixed-step");
  if (o.input == InputInterpolation::kAuto)
    FailOption("BoucWenSimulationOptions", "input", "auto",
               "auto is a fit's choice (BoucWenFitOptions); a model takes hold, linear or "
               "band-limited");
}

}  // namespace internal

void BoucWenSimulationOptions::Validate() const {
  if (!(rtol > 0 && rtol <= 1e-2))
    Violated("BoucWenSimulationOptions", "rtol", rtol, "0 < rtol <= 1e-2");
  if (upsampling < 1 || upsampling > 1000)
    Violated("BoucWenSimulationOptions", "upsampling", upsampling, "1 <= upsampling <= 1000");
  if (integrator == BoucWenIntegrator::kFixedStep && input == InputInterpolation::kHold)
    internal::FailOption("BoucWenSimulationOptions", "input", "hold",
                         "the fixed-step integrator takes a linear or band-limited input (use "
                         "cvode for a held one)");
}

void MechanicalBoucWenParameters::Validate() const {
  const char* t = "MechanicalBoucWenParameters";
  auto finite = [](double v) { return std::isfinite(v); };
  if (!(m_kg > 0) || !finite(m_kg)) Violated(t, "m_kg", m_kg, "m_kg > 0");
  if (!(c_n_s_per_m >= 0) || !finite(c_n_s_per_m))
    Violated(t, "c_n_s_per_m", c_n_s_per_m, "c_n_s_per_m >= 0");
  if (!(k_n_per_m >= 0) || !finite(k_n_per_m))
    Violated(t, "k_n_per_m", k_n_per_m, "k_n_per_m >= 0");
  if (!(alpha_n_per_m > 0) || !finite(alpha_n_per_m))
    Violated(t, "alpha_n_per_m", alpha_n_per_m, "alpha_n_per_m > 0");
  if (!(beta_per_m > 0) || !finite(beta_per_m))
    Violated(t, "beta_per_m", beta_per_m, "beta_per_m > 0");
  if (!finite(gamma)) Violated(t, "gamma", gamma, "a finite gamma");
  if (!finite(delta)) Violated(t, "delta", delta, "a finite delta");
  if (!(nu >= 1 && nu <= 10)) Violated(t, "nu", nu, "1 <= nu <= 10");
}

void PiezoBoucWenParameters::Validate() const {
  const char* t = "PiezoBoucWenParameters";
  if (!(d_m_per_v > 0) || !std::isfinite(d_m_per_v))
    Violated(t, "d_m_per_v", d_m_per_v, "d_m_per_v > 0");
  if (!std::isfinite(alpha)) Violated(t, "alpha", alpha, "a finite alpha");
  if (!std::isfinite(beta_per_v)) Violated(t, "beta_per_v", beta_per_v, "a finite beta_per_v");
  if (!std::isfinite(gamma_per_v)) Violated(t, "gamma_per_v", gamma_per_v, "a finite gamma_per_v");
  if (!std::isfinite(offset_m)) Violated(t, "offset_m", offset_m, "a finite offset_m");
}

std::string MechanicalBoucWen::ToJson(int indent) const {
  return ModelJson("bouc-wen", p_, parameters(), options_,
                   "m y'' + c y' + k y + z = u, z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + "
                   "delta y' |z|^nu); u [N], y [m], z [N]")
             .dump(indent) +
         "\n";
}

std::string PiezoBoucWen::ToJson(int indent) const {
  return ModelJson("bouc-wen-piezo", p_, parameters(), options_,
                   "y = d u - h + offset, h' = alpha d u' - beta |u'| h - gamma u' |h|; u [V], "
                   "y [m], h [m]")
             .dump(indent) +
         "\n";
}

std::unique_ptr<HysteresisModel> BoucWenModelFromJson(const std::string& text,
                                                      const std::string& source) {
  const internal::JsonDocument doc(text, source);
  const auto root = doc.Root();
  root.ExpectObject({"kind", "parameters", "std_errors", "units", "simulation"}, {"note", "fit"});
  const auto kind_node = root.Get("kind");
  const std::string kind = kind_node.String();
  if (kind != "bouc-wen" && kind != "bouc-wen-piezo")
    kind_node.Expected("\"bouc-wen\" or \"bouc-wen-piezo\"");
  BoucWenSimulationOptions sim;
  if (root.Has("simulation")) sim = SimulationFromJson(doc, root.Get("simulation"));
  const auto ps = root.Get("parameters");
  // The fields' ranges are the parameters' Validate() rules, so a bad value is reported at its
  // place in the file.
  if (kind == "bouc-wen") {
    MechanicalBoucWenParameters p;
    internal::ReadFields(ps, p);
    return std::make_unique<MechanicalBoucWen>(p, sim,
                                               ErrorsFromJson(root, internal::FieldNamesOf(p)));
  }
  PiezoBoucWenParameters p;
  internal::ReadFields(ps, p);
  if (sim.integrator != BoucWenIntegrator::kCvode && root.Has("simulation"))
    root.Get("simulation")
        .Get("integrator")
        .Expected("\"cvode\" (the chain and the fixed step are the mechanical form's)");
  return std::make_unique<PiezoBoucWen>(p, sim, ErrorsFromJson(root, internal::FieldNamesOf(p)));
}
}  // namespace sysid
