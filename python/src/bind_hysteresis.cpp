// Hysteresis models (sysid/hysteresis_model.hpp, sysid/compare_hysteresis.hpp): fit by kind,
// simulate, invert, read model files. python/sysid/hysteresis.py wraps them.
#include <memory>

#include "bind_common.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/hysteresis_model.hpp"

namespace sysid::python {

void BindHysteresis(py::module_& m) {
  py::class_<HysteresisParameter>(m, "HysteresisParameter")
      .def_readonly("name", &HysteresisParameter::name)
      .def_readonly("unit", &HysteresisParameter::unit)
      .def_readonly("value", &HysteresisParameter::value)
      .def_readonly("std_error", &HysteresisParameter::std_error)
      .def("__repr__", [](const HysteresisParameter& p) {
        return "HysteresisParameter(" + p.name + "=" + std::to_string(p.value) + " " + p.unit + ")";
      });
  py::class_<HysteresisFitSummary>(m, "HysteresisFitSummary")
      .def_readonly("kind", &HysteresisFitSummary::kind)
      .def_readonly("samples", &HysteresisFitSummary::samples)
      .def_readonly("fit_time_s", &HysteresisFitSummary::fit_time_s)
      .def_readonly("training_rms", &HysteresisFitSummary::training_rms)
      .def_readonly("converged", &HysteresisFitSummary::converged)
      .def_readonly("message", &HysteresisFitSummary::message);
  py::class_<HysteresisModel, std::shared_ptr<HysteresisModel>>(m, "HysteresisModel")
      .def_property_readonly("kind", &HysteresisModel::kind)
      .def_property_readonly("invertible", &HysteresisModel::invertible)
      .def("simulate", &HysteresisModel::Simulate, py::arg("u_v"), py::arg("dt_s"), ReleaseGil())
      .def("simulate_periodic", &HysteresisModel::SimulatePeriodic, py::arg("u_period_v"),
           py::arg("dt_s"), py::arg("tolerance") = 1e-12, py::arg("max_periods") = 256, ReleaseGil())
      .def("invert", &HysteresisModel::Invert, py::arg("x_m"), py::arg("dt_s"), ReleaseGil())
      .def_property_readonly("parameters", &HysteresisModel::parameters)
      .def("to_json", &HysteresisModel::ToJson, py::arg("indent") = 2);
  m.def("hysteresis_kinds", &HysteresisKinds);
  m.def(
      "fit_hysteresis",
      [](const std::string& kind, const std::vector<Recording>& recordings, int operators,
         bool offset, int degree, int hidden, int epochs, std::uint64_t seed) {
        HysteresisFitOptions o;
        o.operators = operators;
        o.pi.offset = offset;
        o.pi.polynomial_degree = degree;
        o.network.hidden = hidden;
        o.network.max_epochs = epochs;
        o.network.seed = seed;
        HysteresisFitSummary s;
        std::shared_ptr<HysteresisModel> model;
        {
          py::gil_scoped_release release;
          model = FitHysteresis(kind, recordings, o, &s);
        }
        return py::make_tuple(model, s);
      },
      py::arg("kind"), py::arg("recordings"), py::arg("operators") = 10, py::arg("offset") = true,
      py::arg("degree") = 3, py::arg("hidden") = 10, py::arg("epochs") = 300, py::arg("seed") = 1);
  m.def("read_hysteresis_model",
        [](const std::string& path) { return std::shared_ptr<HysteresisModel>(ReadHysteresisModel(path)); },
        py::arg("path"));
  m.def("hysteresis_model_from_json",
        [](const std::string& text, const std::string& source) {
          return std::shared_ptr<HysteresisModel>(HysteresisModelFromJson(text, source));
        },
        py::arg("text"), py::arg("source") = "json");
}

}  // namespace sysid::python
