// A model simulated free-run from a recording's u and scored on its outputs (validate.hpp).
#include <fmt/format.h>

#include <cmath>
#include <vector>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/input.hpp"
#include "sysid/simulate.hpp"
#include "sysid/validate.hpp"

namespace sysid {
namespace {

OutputValidation ScoreOutput(std::string output, std::string unit, Eigen::VectorXd measured,
                             Eigen::VectorXd simulated, const Eigen::VectorXd& u,
                             const ResidualTestOptions& options) {
  OutputValidation o;
  o.output = std::move(output);
  o.unit = std::move(unit);
  o.measured = std::move(measured);
  o.simulated = std::move(simulated);
  o.scores = ScoreFit(o.measured, o.simulated);
  const Eigen::VectorXd e = o.measured - o.simulated;
  o.autocorrelation = AutocorrelationTest(e, options);
  o.cross_correlation = CrossCorrelationTest(e, u, options);
  return o;
}

void RequireColumns(const Recording& rec, std::initializer_list<const char*> names) {
  for (const char* name : names)
    if (!rec.has(name))
      throw InputError(
          fmt::format("{}: no column '{}': validation simulates the model from u "
                      "and scores it on the measured output",
                      rec.source, name));
}

// Before the simulation, which may take seconds, and naming the recording.
void RequireSamples(const std::string& source, Eigen::Index n, const ResidualTestOptions& o) {
  if (n < 4 * (static_cast<Eigen::Index>(o.max_lag) + 1))
    throw InputError(
        fmt::format("{}: {} samples for {} lags: expected at least 4 (lags + 1) = "
                    "{} samples (give fewer lags)",
                    source, n, o.max_lag, 4 * (o.max_lag + 1)));
}

}  // namespace

void ValidationOptions::Validate() const {
  residual.Validate();
  motion.Validate();
  if (!(sim_rtol > 0 && sim_rtol < 1))
    internal::FailOption("ValidationOptions", "sim_rtol", sim_rtol, "0 < sim_rtol < 1");
  if (!(sim_atol > 0 && std::isfinite(sim_atol)))
    internal::FailOption("ValidationOptions", "sim_atol", sim_atol, "sim_atol > 0");
}

Validation ValidateFrictionModel(const Recording& recording, const FrictionModel& model,
                                 const ValidationOptions& options) {
  options.Validate();
  model.Validate();
  RequireColumns(recording, {"u"});
  const MotionSignals m = ExtractMotion(recording, options.motion);
  const Eigen::Index n = m.t_s.size();
  RequireSamples(recording.source, n, options.residual);
  const std::vector<double> t(m.t_s.data(), m.t_s.data() + n), u(m.u_v.data(), m.u_v.data() + n);
  const PiecewiseConstantInput input(t, u);
  SimulationOptions so;
  so.t0_s = t.front();
  so.t_end_s = t.back();
  so.output_times_s = t;
  so.x0_m = m.x_m.size() == n ? m.x_m[0] : 0.0;
  so.v0_mps = m.v_mps[0];
  so.history_v_mps = m.v_mps[0];
  so.rtol = options.sim_rtol;
  so.atol = options.sim_atol;
  const SimulationResult sim = Simulate(model, input, so);
  if (!sim.summary.IsSolutionUsable() || sim.trajectory.v_mps.size() != n)
    throw NumericalError(fmt::format("{}: the model's simulation failed at t = {:.6g} s: {}",
                                     recording.source, sim.summary.failure_time_s,
                                     sim.summary.message));
  Validation val;
  val.source = recording.source;
  val.model_kind = "friction";
  val.t_s = m.t_s;
  val.u_v = m.u_v;
  val.outputs.push_back(
      ScoreOutput("v", "m/s", m.v_mps, sim.trajectory.v_mps, m.u_v, options.residual));
  if (m.x_m.size() == n)
    val.outputs.push_back(
        ScoreOutput("x", "m", m.x_m, sim.trajectory.x_m, m.u_v, options.residual));
  return val;
}

Validation ValidateHysteresisModel(const Recording& recording, const HysteresisModel& model,
                                   const ValidationOptions& options) {
  options.Validate();
  RequireColumns(recording, {"t", "u", "x"});
  RequireSamples(recording.source, recording.rows(), options.residual);
  const double dt = RecordingStep(recording);
  Validation val;
  val.source = recording.source;
  val.model_kind = model.kind();
  val.t_s = recording.column("t");
  val.u_v = recording.column("u");
  Eigen::VectorXd x_model = model.Simulate(val.u_v, dt);
  val.outputs.push_back(
      ScoreOutput("x", "m", recording.column("x"), std::move(x_model), val.u_v, options.residual));
  return val;
}

}  // namespace sysid
