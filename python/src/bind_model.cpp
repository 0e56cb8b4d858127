// The friction model and its JSON files (sysid/model.hpp), inputs (sysid/input.hpp) and the
// simulator (sysid/simulate.hpp).
#include <fmt/format.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/input.hpp"
#include "sysid/io.hpp"
#include "sysid/model.hpp"
#include "sysid/simulate.hpp"

namespace sysid::python {
namespace {

std::shared_ptr<InputSignal> TableInput(const py::object& t_s, const py::object& u_v,
                                        const std::string& hold, const std::string& source) {
  const Eigen::VectorXd t = RealVector(t_s, "t_s"), u = RealVector(u_v, "u_v");
  CheckSameLength("table_input", "t_s", t.size(), "u_v", u.size());
  return std::shared_ptr<InputSignal>(MakeTableInput(std::vector<double>(t.begin(), t.end()),
                                                     std::vector<double>(u.begin(), u.end()),
                                                     ParseInputHold(hold), source));
}

}  // namespace

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindModel(py::module_& m) {
  py::class_<FrictionModel> model(
      m, "Model",
      "The rough friction model x'' = -a1 v(t - tau) - a2 sgn(v) + a3 u with direction-dependent "
      "a1p, a1n [1/s], a2p, a2n [m/s^2], gain a3 [m/(s^2 V)] and delay tau_s [s].");
  AddKeywordInit(model);
  model.def_readwrite("a1p", &FrictionModel::a1p)
      .def_readwrite("a1n", &FrictionModel::a1n)
      .def_readwrite("a2p", &FrictionModel::a2p)
      .def_readwrite("a2n", &FrictionModel::a2n)
      .def_readwrite("a3", &FrictionModel::a3)
      .def_readwrite("tau_s", &FrictionModel::tau_s)
      .def("validate", &FrictionModel::Validate)
      .def_static("paper", &FrictionModel::Paper, "The paper's identified model.")
      // Both methods check the model once per call, here and not in FrictionModel's methods:
      // those run per sample in C++ loops (AnalyticInverse, the comparisons), whose callers
      // validate once. Without it a3 = 0 would give inf and a NaN field NaN, as answers; with
      // it an invalid model is an OptionsError, as in analytic_inverse and every other consumer.
      .def("steady_velocity",
           [](const FrictionModel& f, const py::object& u) {
             f.Validate();
             return RealElementwise(u, "u_v", [&f](double x) { return f.SteadyVelocity(x); });
           },
           py::arg("u_v"),
           "Steady sliding velocity [m/s] under constant voltage(s) u_v [V] (+-inf where the "
           "force wins and that direction's a1 is 0). OptionsError for a model failing "
           "validate().")
      .def("inverse_voltage",
           [](const FrictionModel& f, const py::object& a, const py::object& vd,
              const py::object& v) {
             f.Validate();
             const auto a_ = RealArray(a, "a_mps2"), vd_ = RealArray(vd, "v_delayed_mps"),
                        v_ = RealArray(v, "v_mps");
             try {  // NumPy's broadcasting rule, with the library's error when it fails
               (void)py::module_::import("numpy").attr("broadcast")(a_, vd_, v_);
             } catch (const py::error_already_set&) {
               throw InputError(
                   "inverse_voltage: a_mps2, v_delayed_mps and v_mps of shapes " +
                   std::string(py::str(a_.attr("shape"))) + ", " +
                   std::string(py::str(vd_.attr("shape"))) + ", " +
                   std::string(py::str(v_.attr("shape"))) + " do not broadcast together");
             }
             return py::vectorize([&f](double x, double y, double z) {
               return f.InverseVoltage(x, y, z);
             })(a_, vd_, v_);
           },
           py::arg("a_mps2"),
           py::arg("v_delayed_mps"), py::arg("v_mps"),
           "The analytic inverse u [V]. OptionsError for a model failing validate().")
      .def_static("load", &ReadModel, py::arg("path"), "Reads a model JSON file (the CLI's).")
      .def("save", [](const FrictionModel& f, const std::string& path) { WriteModel(path, f); },
           py::arg("path"), "Writes the model JSON file atomically.")
      .def_static("from_json", &ParseModel, py::arg("text"), py::arg("source") = "json")
      .def("to_json", &ModelToJson, py::arg("indent") = 2)
      .def("__eq__", [](const FrictionModel& a, const FrictionModel& b) {
        return a.a1p == b.a1p && a.a1n == b.a1n && a.a2p == b.a2p && a.a2n == b.a2n &&
               a.a3 == b.a3 && a.tau_s == b.tau_s;
      });

  // ---- Inputs ----
  py::class_<InputSignal, std::shared_ptr<InputSignal>>(m, "InputSignal",
                                                        "An input voltage u(t) [V].")
      .def("value",
           [](const InputSignal& s, const py::object& t) {
             return RealElementwise(t, "t_s", [&s](double x) { return s.Value(x); });
           },
           py::arg("t_s"))
      .def("edges", &InputSignal::Edges, py::arg("t0_s"), py::arg("t1_s"));
  m.def("table_input", &TableInput, py::arg("t_s"), py::arg("u_v"), py::arg("hold") = "zoh",
        py::arg("source") = "table",
        "An input from a table of (t [s], u [V]); hold 'zoh' or 'linear'.");
  py::class_<SineComponent>(m, "SineComponent")
      .def(py::init<double, double, double>(), py::arg("amplitude_v"), py::arg("frequency_hz"),
           py::arg("phase_rad") = 0.0)
      .def_readwrite("amplitude_v", &SineComponent::amplitude_v)
      .def_readwrite("frequency_hz", &SineComponent::frequency_hz)
      .def_readwrite("phase_rad", &SineComponent::phase_rad);
  m.def(
      "sines_input",
      [](std::vector<SineComponent> c, double offset_v) -> std::shared_ptr<InputSignal> {
        return std::make_shared<SumOfSinesInput>(std::move(c), offset_v);
      },
      py::arg("components"), py::arg("offset_v") = 0.0);
  py::class_<PulseTrainSpec> pulses(m, "PulseTrainSpec");
  AddKeywordInit(pulses);
  pulses.def_readwrite("amplitudes_v", &PulseTrainSpec::amplitudes_v)
      .def_readwrite("on_s", &PulseTrainSpec::on_s)
      .def_readwrite("off_s", &PulseTrainSpec::off_s)
      .def_readwrite("repeats", &PulseTrainSpec::repeats)
      .def_readwrite("start_s", &PulseTrainSpec::start_s)
      .def_property_readonly("duration_s", &PulseTrainSpec::duration_s);
  m.def(
      "pulse_train",
      [](const PulseTrainSpec& spec) -> std::shared_ptr<InputSignal> {
        return std::make_shared<PiecewiseConstantInput>(MakePulseTrain(spec));
      },
      py::arg("spec"));
  m.def("waveform_names", &NamedWaveformNames);
  m.def(
      "waveform",
      [](const std::string& name) {
        const NamedWaveform w = MakeNamedWaveform(name);
        return py::make_tuple(std::const_pointer_cast<InputSignal>(w.signal), w.duration_s);
      },
      py::arg("name"), "(input, natural duration [s]) of a named test waveform of the paper.");

  // ---- Simulation ----
  py::enum_<IntegratorMethod>(m, "IntegratorMethod")
      .value("adams", IntegratorMethod::kAdams)
      .value("bdf", IntegratorMethod::kBdf)
      .def(py::init(&ParseIntegratorMethod));
  py::implicitly_convertible<py::str, IntegratorMethod>();

  py::class_<SimulationOptions> sim(m, "SimulationOptions");
  AddKeywordInit(sim);
  DefFields(sim);
  sim.def("validate", &SimulationOptions::Validate);

  py::class_<Trajectory>(m, "Trajectory")
      .def_readonly("t_s", &Trajectory::t_s)
      .def_readonly("u_v", &Trajectory::u_v)
      .def_readonly("x_m", &Trajectory::x_m)
      .def_readonly("v_mps", &Trajectory::v_mps)
      .def_readonly("a_mps2", &Trajectory::a_mps2);
  py::class_<SimulationEvent> event(m, "SimulationEvent");
  DefReadOnlyFields(event);
  event.def("__repr__", [](const SimulationEvent& e) {
        return fmt::format("<SimulationEvent {} at {} s>", ToString(e.kind), e.t_s);
      });
  py::class_<SimulationSummary> summary(m, "SimulationSummary");
  DefReadOnlyFields(summary);
  summary.def("is_solution_usable", &SimulationSummary::IsSolutionUsable)
      .def("brief_report", &SimulationSummary::BriefReport);
  py::class_<SimulationResult>(m, "SimulationResult")
      .def_readonly("trajectory", &SimulationResult::trajectory)
      .def_readonly("events", &SimulationResult::events)
      .def_readonly("summary", &SimulationResult::summary)
      .def_property_readonly("termination",
                             [](const SimulationResult& r) {
                               return ToString(r.summary.termination);
                             })
      .def_property_readonly("message",
                             [](const SimulationResult& r) { return r.summary.message; })
      .def("brief_report", [](const SimulationResult& r) { return r.summary.BriefReport(); })
      .def(
          "to_recording",
          [](const SimulationResult& r, const std::string& source) {
            return TrajectoryRecording(r.trajectory, source);
          },
          py::arg("source") = "simulation", "Columns t, u, x, v, a.");
  m.def("simulate_input", &Simulate, py::arg("model"), py::arg("input"), py::arg("options"),
        ReleaseGil());
}

}  // namespace sysid::python
