// sysid/validate.hpp: a model simulated free-run on a recording and scored as MATLAB's compare
// and resid do (fit %, RMSE, nrmse_std, nrmse_range, residual correlations and their verdicts).
#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/validate.hpp"

namespace sysid::python {

void BindValidate(py::module_& m) {
  py::class_<FitScores> scores(m, "FitScores",
                              "fit % (MATLAB compare), RMSE and both NRMSEs, named");
  DefReadOnlyFields(scores);
  scores.def("__repr__", [](const FitScores& s) {
        return py::str("FitScores(fit_percent={!r}, rmse={!r}, nrmse_std={!r}, nrmse_range={!r})")
            .format(s.fit_percent, s.rmse, s.nrmse_std, s.nrmse_range);
      });
  m.def(
      "score_fit",
      [](const py::object& measured, const py::object& simulated) {
        return ScoreFit(RealVector(measured, "measured"), RealVector(simulated, "simulated"));
      },
      py::arg("measured"), py::arg("simulated"),
      "fit % = 100 (1 - |y - yhat| / |y - mean y|), RMSE, nrmse_std, nrmse_range");
  m.def(
      "normalised_autocorrelation",
      [](const py::object& e, int max_lag) {
        return NormalisedAutocorrelation(RealVector(e, "e"), max_lag);
      },
      py::arg("e"), py::arg("max_lag"), "r_e(k), k = 0..max_lag, means removed");
  m.def(
      "normalised_cross_correlation",
      [](const py::object& e, const py::object& u, int max_lag) {
        return NormalisedCrossCorrelation(RealVector(e, "e"), RealVector(u, "u"), max_lag);
      },
      py::arg("e"), py::arg("u"), py::arg("max_lag"),
      "r_eu(k) = corr(e_t, u_{t-k}), k = 0..max_lag, means removed");

  py::class_<CorrelationTest> correlation(m, "CorrelationTest");
  DefReadOnlyFields(correlation)
      .Derived(
          "passed", [](const CorrelationTest& t) { return t.pass; },
          "the field pass, whose name is a Python keyword (getattr(test, 'pass') reads it)");
  correlation.def("__repr__", [](const CorrelationTest& t) {
        return "<CorrelationTest " + t.name + ": " + t.verdict + ">";
      });
  py::class_<OutputValidation> output(m, "OutputValidation");
  constexpr const char* kSignal = "a signal of the run; the JSON holds its scores";
  DefReadOnlyFields(output)
      .Stored("measured", &OutputValidation::measured, kSignal)
      .Stored("simulated", &OutputValidation::simulated, kSignal);
  output.def("__repr__", [](const OutputValidation& o) {
        return py::str(
                   "<OutputValidation {}: fit {:.4g} %, autocorrelation {}, cross-correlation "
                   "{}>")
            .format(o.output, o.scores.fit_percent, o.autocorrelation.pass ? "pass" : "fail",
                    o.cross_correlation.pass ? "pass" : "fail");
      });
  py::class_<Validation> validation(m, "Validation");
  DefReadOnlyFields(validation)
      .Stored("t_s", &Validation::t_s, kSignal)
      .Stored("u_v", &Validation::u_v, kSignal);
  validation.def(
          "to_json", [](const Validation& v, int indent) { return ToJson(v, indent); },
          py::arg("indent") = 2)
      .def("__repr__", [](const Validation& v) {
        return "<Validation of a " + v.model_kind + " model on " + v.source + ", " +
               std::to_string(v.outputs.size()) + " output(s)>";
      });

  py::class_<ResidualTestOptions> residual(m, "ResidualTestOptions");
  AddKeywordInit(residual);
  DefFields(residual);
  residual.def("validate", &ResidualTestOptions::Validate);
  py::class_<ValidationOptions> options(m, "ValidationOptions");
  AddKeywordInit(options);
  DefFields(options);
  options.def("validate", &ValidationOptions::Validate);
  m.def("validate_friction", &ValidateFrictionModel, py::arg("recording"), py::arg("model"),
        py::arg("options") = ValidationOptions{}, ReleaseGil());
  m.def("validate_hysteresis", &ValidateHysteresisModel, py::arg("recording"), py::arg("model"),
        py::arg("options") = ValidationOptions{}, ReleaseGil());
}

}  // namespace sysid::python
