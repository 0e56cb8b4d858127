// Hysteresis models (sysid/hysteresis_model.hpp, sysid/compare_hysteresis.hpp): fit by kind,
// simulate, invert, read model files. python/sysid/hysteresis.py wraps them.
#include <fmt/format.h>

#include <cmath>
#include <memory>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/compare.hpp"
#include "sysid/compare_hysteresis.hpp"
#include "sysid/compare_stack.hpp"
#include "sysid/hysteresis_model.hpp"

namespace sysid::python {
namespace {

using SignalMap = Eigen::VectorXd (HysteresisModel::*)(const Eigen::VectorXd&, double) const;

// simulate and invert: one signal through the package's conversion, dt_s checked, the GIL
// released for the model's work.
Eigen::VectorXd MapSignal(const HysteresisModel& model, SignalMap map, const py::object& values,
                          const char* arg, double dt_s, const char* where) {
  const Eigen::VectorXd v = RealVector(values, arg);
  CheckTimeStep(where, dt_s);
  py::gil_scoped_release release;
  return (model.*map)(v, dt_s);
}

}  // namespace

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindHysteresis(py::module_& m) {
  py::class_<HysteresisParameter> parameter(m, "HysteresisParameter");
  DefReadOnlyFields(parameter);
  parameter.def("__repr__", [](const HysteresisParameter& p) {
        // %.4g, not std::to_string's %f, which prints a 2.264e-6 m/V weight as 0.000002.
        const std::string error =
            std::isfinite(p.std_error) ? fmt::format(" ± {:.2g}", p.std_error) : "";
        return fmt::format("HysteresisParameter({}={:.6g}{} {})", p.name, p.value, error, p.unit);
      });
  py::class_<HysteresisFitSummary> fit_summary(m, "HysteresisFitSummary");
  DefReadOnlyFields(fit_summary);
  py::class_<HysteresisModel, std::shared_ptr<HysteresisModel>>(m, "HysteresisModel")
      .def_property_readonly("kind", &HysteresisModel::kind)
      .def_property_readonly("invertible", &HysteresisModel::invertible)
      .def(
          "simulate",
          [](const HysteresisModel& model, const py::object& u_v, double dt_s) {
            return MapSignal(model, &HysteresisModel::Simulate, u_v, "u_v", dt_s,
                             "HysteresisModel.simulate");
          },
          py::arg("u_v"), py::arg("dt_s"), "x [m] for the inputs u [V] spaced dt_s [s].")
      .def(
          "simulate_periodic",
          [](const HysteresisModel& model, const py::object& u_period_v, double dt_s,
             double tolerance, int max_periods) {
            const Eigen::VectorXd u = RealVector(u_period_v, "u_period_v");
            CheckTimeStep("HysteresisModel.simulate_periodic", dt_s);
            py::gil_scoped_release release;
            return model.SimulatePeriodic(u, dt_s, tolerance, max_periods);
          },
          py::arg("u_period_v"), py::arg("dt_s"), py::arg("tolerance") = 1e-12,
          py::arg("max_periods") = 256,
          "x [m] over one period of the periodic steady state for one period of u [V].")
      .def(
          "invert",
          [](const HysteresisModel& model, const py::object& x_m, double dt_s) {
            return MapSignal(model, &HysteresisModel::Invert, x_m, "x_m", dt_s,
                             "HysteresisModel.invert");
          },
          py::arg("x_m"), py::arg("dt_s"), "u [V] that makes the model follow x [m].")
      .def_property_readonly("parameters", &HysteresisModel::parameters)
      .def("to_json", &HysteresisModel::ToJson, py::arg("indent") = 2)
      .def("__repr__", [](const HysteresisModel& model) {
        const auto parameters = model.parameters();
        return fmt::format("<HysteresisModel kind={}, {} parameters, {}invertible>", model.kind(),
                           parameters.size(), model.invertible() ? "" : "not ");
      });
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
  // `sysid compare --hysteresis` on one recording: each (label, model)'s inverse on the
  // recording's x, scored against its u on the trimmed samples (sysid.hysteresis.compare).
  m.def(
      "compare_hysteresis_inverses",
      [](const Recording& recording,
         const std::vector<std::pair<std::string, std::shared_ptr<HysteresisModel>>>& models,
         int trim_samples) {
        std::vector<NamedHysteresisModel> named;
        for (const auto& [label, model] : models) named.push_back({label, model.get()});
        CompareOptions o;
        o.trim_samples = trim_samples;
        InverseComparison c;
        {
          py::gil_scoped_release release;
          c = CompareInverseModels(recording, nullptr, nullptr, named, o);
        }
        py::list rows;
        for (const auto& h : c.hysteresis) {
          py::dict row;
          row["label"] = h.label;
          row["kind"] = h.kind;
          row["rmse_v"] = h.errors.rmse_v;
          row["peak_error_v"] = h.errors.peak_error_v;
          row["nrmse_range"] = h.errors.nrmse_range;
          row["r2"] = h.errors.r2;
          row["u_v"] = h.u_v;
          rows.append(row);
        }
        return py::make_tuple(c.t_s, c.u_measured_v, rows);
      },
      py::arg("recording"), py::arg("models"), py::arg("trim_samples") = 5);
  // The stack model table's row (sysid/compare_stack.hpp): fit on the first train_fraction of
  // each recording, score the rest (sysid.batch over models x recordings).
  m.def("stack_model_specs", [] {
    py::list out;
    for (const auto& s : StackModelSpecs()) {
      py::dict d;
      d["label"] = s.label;
      d["kind"] = s.kind;
      d["operators"] = s.options.operators;
      d["hidden"] = s.options.network.hidden;
      out.append(d);
    }
    return out;
  });
  m.def(
      "fit_and_score_hysteresis",
      [](const std::vector<Recording>& recordings, const std::string& kind,
         const std::string& label, int operators, bool offset, int degree, int hidden,
         int epochs, std::uint64_t seed, double train_fraction, int threads) {
        HysteresisModelSpec spec;
        spec.label = label.empty() ? kind : label;
        spec.kind = kind;
        spec.options.operators = operators;
        spec.options.pi.offset = offset;
        spec.options.pi.polynomial_degree = degree;
        spec.options.network.hidden = hidden;
        spec.options.network.max_epochs = epochs;
        spec.options.network.seed = seed;
        spec.options.bouc_wen.threads = threads;
        HysteresisSplitScore s;
        {
          py::gil_scoped_release release;
          s = FitAndScoreHysteresis(spec, recordings, train_fraction);
        }
        py::dict row;
        row["model"] = s.label;
        row["kind"] = s.kind;
        row["parameters"] = s.parameters;
        row["fit_time_s"] = s.fit_time_s;
        row["train_samples"] = s.train_samples;
        row["test_samples"] = s.test_samples;
        row["forward_rms_m"] = s.forward_rms_m;
        row["forward_nrmse_std"] = s.forward_nrmse_std;
        row["inverse_rms_v"] = s.inverse_rms_v;
        row["inverse_nrmse_std"] = s.inverse_nrmse_std;
        row["inverse_error"] = s.inverse_error;
        row["fit_error"] = s.error;
        return row;
      },
      py::arg("recordings"), py::arg("kind"), py::arg("label") = "", py::arg("operators") = 10,
      py::arg("offset") = true, py::arg("degree") = 3, py::arg("hidden") = 10,
      py::arg("epochs") = 300, py::arg("seed") = 1, py::arg("train_fraction") = 0.4,
      py::arg("threads") = 1);
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
