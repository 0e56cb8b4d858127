// sysid/validate.hpp: a model simulated free-run on a recording and scored as MATLAB's compare
// and resid do (fit %, RMSE, nrmse_std, nrmse_range, residual correlations and their verdicts).
#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/validate.hpp"

namespace sysid::python {

void BindValidate(py::module_& m) {
  py::class_<FitScores>(m, "FitScores", "fit % (MATLAB compare), RMSE and both NRMSEs, named")
      .def_readonly("fit_percent", &FitScores::fit_percent)
      .def_readonly("rmse", &FitScores::rmse)
      .def_readonly("nrmse_std", &FitScores::nrmse_std)
      .def_readonly("nrmse_range", &FitScores::nrmse_range)
      .def("__repr__", [](const FitScores& s) {
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

  py::class_<CorrelationTest>(m, "CorrelationTest")
      .def_readonly("name", &CorrelationTest::name)
      .def_readonly("lags", &CorrelationTest::lags)
      .def_readonly("r", &CorrelationTest::r)
      .def_readonly("bound", &CorrelationTest::bound)
      .def_readonly("strong_bound", &CorrelationTest::strong_bound)
      .def_readonly("outside", &CorrelationTest::outside)
      .def_readonly("allowed_outside", &CorrelationTest::allowed_outside)
      .def_readonly("max_abs_r", &CorrelationTest::max_abs_r)
      .def_readonly("tested", &CorrelationTest::tested)
      .def_readonly("passed", &CorrelationTest::pass)
      .def_readonly("verdict", &CorrelationTest::verdict)
      .def("__repr__", [](const CorrelationTest& t) {
        return "<CorrelationTest " + t.name + ": " + t.verdict + ">";
      });
  py::class_<OutputValidation>(m, "OutputValidation")
      .def_readonly("output", &OutputValidation::output)
      .def_readonly("unit", &OutputValidation::unit)
      .def_readonly("measured", &OutputValidation::measured)
      .def_readonly("simulated", &OutputValidation::simulated)
      .def_readonly("scores", &OutputValidation::scores)
      .def_readonly("autocorrelation", &OutputValidation::autocorrelation)
      .def_readonly("cross_correlation", &OutputValidation::cross_correlation)
      .def("__repr__", [](const OutputValidation& o) {
        return py::str(
                   "<OutputValidation {}: fit {:.4g} %, autocorrelation {}, cross-correlation "
                   "{}>")
            .format(o.output, o.scores.fit_percent, o.autocorrelation.pass ? "pass" : "fail",
                    o.cross_correlation.pass ? "pass" : "fail");
      });
  py::class_<Validation>(m, "Validation")
      .def_readonly("source", &Validation::source)
      .def_readonly("model_kind", &Validation::model_kind)
      .def_readonly("t_s", &Validation::t_s)
      .def_readonly("u_v", &Validation::u_v)
      .def_readonly("outputs", &Validation::outputs)
      .def(
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
