// Identification (sysid/identify.hpp) and delay tuning (sysid/delay.hpp). Results keep the C++
// field names.
#include <fmt/format.h>

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/delay.hpp"
#include "sysid/dominance.hpp"
#include "sysid/error.hpp"
#include "sysid/identify.hpp"
#include "sysid/io.hpp"

namespace sysid::python {
namespace {

template <typename R>
void AddSolvedTermination(py::class_<R>& cls) {
  // Least squares either returns a solution or throws NumericalError: no other termination.
  cls.def_property_readonly("termination", [](const R&) { return "solved"; });
}

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindPulses(py::module_& m) {
  // ---- Pulses ----
  py::class_<PulseDetectionOptions> detection(m, "PulseDetectionOptions");
  AddKeywordInit(detection);
  AddOptionsJson(detection, &PulseDetectionOptionsFromJson);
  DefFields(detection);
  detection.def("validate", &PulseDetectionOptions::Validate);
  py::class_<PlateauOptions> plateau(m, "PlateauOptions");
  AddKeywordInit(plateau);
  AddOptionsJson(plateau, &PlateauOptionsFromJson);
  DefFields(plateau);
  plateau.def("validate", &PlateauOptions::Validate);
  py::class_<PulseFitOptions> fit_options(m, "PulseFitOptions");
  AddKeywordInit(fit_options);
  AddOptionsJson(fit_options, &PulseFitOptionsFromJson);
  DefFields(fit_options);
  // Setting a3 gives it (a3_given); the default is the paper's HR-8 value, which reports say.
  // a3_given is not a file field (a file gives a3 by naming it), so it is an attribute of its own.
  fit_options
      .def_property(
          "a3", [](const PulseFitOptions& o) { return o.a3; },
          [](PulseFitOptions& o, double a3) {
            o.a3 = a3;
            o.a3_given = true;
          })
      .def_readwrite("a3_given", &PulseFitOptions::a3_given)
      .def("validate", &PulseFitOptions::Validate);
  fit_options.attr("__fields__") = py::make_tuple("a3", "a3_given");
  py::class_<PulseIdentificationOptions> pulse_options(m, "PulseIdentificationOptions");
  AddKeywordInit(pulse_options);
  AddOptionsJson(pulse_options, &PulseIdentificationOptionsFromJson);
  DefFields(pulse_options);
  pulse_options.def("validate", &PulseIdentificationOptions::Validate);

  py::class_<Pulse>(m, "Pulse")
      .def_readonly("source", &Pulse::source)
      .def_readonly("first_row", &Pulse::first_row)
      .def_readonly("end_row", &Pulse::end_row)
      .def_readonly("t_start_s", &Pulse::t_start_s)
      .def_readonly("duration_s", &Pulse::duration_s)
      .def_readonly("amplitude_v", &Pulse::amplitude_v)
      .def_readonly("at_record_start", &Pulse::at_record_start)
      .def_readonly("at_record_end", &Pulse::at_record_end);
  m.def(
      "detect_pulses",
      [](const py::object& t_s, const py::object& u_v, const PulseDetectionOptions& options,
         const std::string& source) {
        const Eigen::VectorXd t = RealVector(t_s, "t_s"), u = RealVector(u_v, "u_v");
        // The library only asserts equal lengths (InternalError): from Python it is bad data.
        CheckSameLength("detect_pulses", "t_s", t.size(), "u_v", u.size());
        py::gil_scoped_release release;
        return DetectPulses(t, u, options, source);
      },
      py::arg("t_s"), py::arg("u_v"), py::arg("options") = PulseDetectionOptions{},
      py::arg("source") = "", "Pulses of u [V] sampled at t [s] (equally long 1-D arrays).");
  py::class_<PulseEstimate>(m, "PulseEstimate")
      .def_readonly("pulse", &PulseEstimate::pulse)
      .def_readonly("v_mps", &PulseEstimate::v_mps)
      .def_readonly("v_stderr_mps", &PulseEstimate::v_stderr_mps)
      .def_readonly("drift_mps", &PulseEstimate::drift_mps)
      .def_readonly("window_samples", &PulseEstimate::window_samples)
      .def_property_readonly("status", [](const PulseEstimate& p) { return ToString(p.status); })
      .def_readonly("reason", &PulseEstimate::reason)
      .def_property_readonly("usable", &PulseEstimate::usable);

  py::class_<LinearFit>(m, "LinearFit")
      .def_readonly("names", &LinearFit::names)
      .def_readonly("theta", &LinearFit::theta)
      .def_readonly("std_error", &LinearFit::std_error)
      .def_readonly("covariance", &LinearFit::covariance)
      .def_readonly("residuals", &LinearFit::residuals)
      .def_readonly("rows", &LinearFit::rows)
      .def_readonly("rank", &LinearFit::rank)
      .def_readonly("dof", &LinearFit::dof)
      .def_readonly("rms_residual", &LinearFit::rms_residual)
      .def_readonly("relative_error", &LinearFit::relative_error)
      .def_readonly("condition_number", &LinearFit::condition_number)
      .def_readonly("r_diagonal", &LinearFit::r_diagonal);
  py::class_<PulsePoint>(m, "PulsePoint")
      .def(py::init([](double u, double v, std::string label) {
             return PulsePoint{u, v, std::move(label)};
           }),
           py::arg("u_v"), py::arg("v_mps"), py::arg("label") = "")
      .def_readwrite("u_v", &PulsePoint::u_v)
      .def_readwrite("v_mps", &PulsePoint::v_mps)
      .def_readwrite("label", &PulsePoint::label);
  m.def(
      "read_pulse_table", [](const std::string& path) { return ReadPulseTable(path); },
      py::arg("path"));

  py::class_<PulseIdentificationResult> pulse_result(m, "PulseIdentificationResult");
  pulse_result.def_readonly("model", &PulseIdentificationResult::model)
      .def_readonly("a3_given", &PulseIdentificationResult::a3_given)
      .def_readonly("fit", &PulseIdentificationResult::fit)
      .def_readonly("points", &PulseIdentificationResult::points)
      .def_readonly("pulses", &PulseIdentificationResult::pulses)
      .def_property_readonly("message",
                             [](const PulseIdentificationResult& r) {
                               return fmt::format("{} equations, rank {}", r.fit.rows, r.fit.rank);
                             })
      .def("brief_report", &PulseIdentificationResult::BriefReport)
      .def("to_json", py::overload_cast<const PulseIdentificationResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid identify --json`'s text (a model file too)")
      .def_static("from_json", &PulseIdentificationResultFromJson, py::arg("text"),
                  py::arg("source") = "json");
  AddSolvedTermination(pulse_result);
  m.def("fit_pulse_table", &FitPulseTable, py::arg("points"),
        py::arg("options") = PulseFitOptions{});
  m.def("identify_pulses_recordings", &IdentifyFromPulses, py::arg("recordings"),
        py::arg("options") = PulseIdentificationOptions{}, ReleaseGil());

}

void BindVoltageLoop(py::module_& m) {
  // ---- The voltage-velocity loop (as `sysid loop --json`) ----
  m.def(
      "voltage_loop_json",
      [](const Recording& recording, const py::object& levels_v, int half_window,
         double moving_speed_mps, int cycles, const MotionOptions& motion) {
        VoltageLoopOptions o;
        const Eigen::VectorXd levels = RealVector(levels_v, "levels_v", /*allow_empty=*/true);
        o.levels_v.assign(levels.begin(), levels.end());
        o.half_window = half_window;
        o.moving_speed_mps = moving_speed_mps;
        o.cycles = cycles;
        return ToJson(AnalyzeVoltageLoop(recording, o, motion));
      },
      py::arg("recording"), py::arg("levels_v"), py::arg("half_window"),
      py::arg("moving_speed_mps"), py::arg("cycles"), py::arg("motion"));

}

void BindTrajectory(py::module_& m) {
  // ---- Trajectory ----
  py::class_<TrajectoryOptions> trajectory_options(m, "TrajectoryOptions");
  AddKeywordInit(trajectory_options);
  AddOptionsJson(trajectory_options, &TrajectoryOptionsFromJson);
  DefFields(trajectory_options);
  trajectory_options.def("validate", &TrajectoryOptions::Validate);
  py::class_<TrajectoryIdentificationResult> trajectory_result(m,
                                                              "TrajectoryIdentificationResult");
  trajectory_result
      .def("to_json", py::overload_cast<const TrajectoryIdentificationResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid identify --method trajectory --json`'s text")
      .def_static("from_json", &TrajectoryIdentificationResultFromJson, py::arg("text"),
                  py::arg("source") = "json")
      .def_readonly("model", &TrajectoryIdentificationResult::model)
      .def_readonly("fit", &TrajectoryIdentificationResult::fit)
      .def_readonly("names", &TrajectoryIdentificationResult::names)
      .def_readonly("estimate", &TrajectoryIdentificationResult::estimate)
      .def_readonly("std_error", &TrajectoryIdentificationResult::std_error)
      .def_readonly("covariance", &TrajectoryIdentificationResult::covariance)
      .def_readonly("offset_mps2", &TrajectoryIdentificationResult::offset_mps2)
      .def_readonly("samples_used", &TrajectoryIdentificationResult::samples_used)
      .def_readonly("relative_error", &TrajectoryIdentificationResult::relative_error)
      .def_readonly("tau_curve", &TrajectoryIdentificationResult::tau_curve)
      .def_property_readonly("message",
                             [](const TrajectoryIdentificationResult& r) {
                               return fmt::format("{} moving samples, relative error {:.4g}",
                                                  r.samples_used, r.relative_error);
                             })
      .def("brief_report", &TrajectoryIdentificationResult::BriefReport);
  AddSolvedTermination(trajectory_result);
  m.def("identify_trajectory_recordings", &IdentifyFromTrajectory, py::arg("recordings"),
        py::arg("options") = TrajectoryOptions{}, ReleaseGil());

}

void BindDelayTuning(py::module_& m) {
  // ---- Delay tuning ----
  py::class_<SegmentOptions> segments(m, "SegmentOptions");
  AddKeywordInit(segments);
  AddOptionsJson(segments, &SegmentOptionsFromJson);
  DefFields(segments);
  segments.def("validate", &SegmentOptions::Validate);
  py::class_<DelayTuningOptions> delay_options(m, "DelayTuningOptions");
  AddKeywordInit(delay_options);
  AddOptionsJson(delay_options, &DelayTuningOptionsFromJson);
  DefFields(delay_options);
  delay_options.def("validate", &DelayTuningOptions::Validate);
  py::class_<DelayTuningResult>(m, "DelayTuningResult")
      .def("to_json", py::overload_cast<const DelayTuningResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid tune-delay --json`'s text")
      .def_static("from_json", &DelayTuningResultFromJson, py::arg("text"),
                  py::arg("source") = "json")
      .def_readonly("warnings", &DelayTuningResult::warnings)
      .def_property_readonly("termination",
                             [](const DelayTuningResult& r) { return ToString(r.termination); })
      .def_readonly("message", &DelayTuningResult::message)
      .def_readonly("model", &DelayTuningResult::model)
      .def_readonly("tau_s", &DelayTuningResult::tau_s)
      .def_readonly("cost", &DelayTuningResult::cost)
      .def_readonly("rms_error_mps", &DelayTuningResult::rms_error_mps)
      .def_readonly("evaluations", &DelayTuningResult::evaluations)
      .def_readonly("simulations", &DelayTuningResult::simulations)
      .def_readonly("segments", &DelayTuningResult::segments)
      .def_readonly("samples", &DelayTuningResult::samples)
      .def_readonly("curve", &DelayTuningResult::curve)
      .def_readonly("wall_time_s", &DelayTuningResult::wall_time_s)
      .def("brief_report", &DelayTuningResult::BriefReport);
  m.def("tune_delay_recordings", &TuneDelay, py::arg("model"), py::arg("recordings"),
        py::arg("options") = DelayTuningOptions{}, ReleaseGil());

}

void BindRefinement(py::module_& m) {
  // ---- Refinement ----
  py::class_<RefineOptions> refine_options(m, "RefineOptions");
  AddKeywordInit(refine_options);
  AddOptionsJson(refine_options, &RefineOptionsFromJson);
  DefFields(refine_options);
  refine_options.def("validate", &RefineOptions::Validate);
  py::class_<RefineResult>(m, "RefineResult")
      .def("to_json", py::overload_cast<const RefineResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid refine --json`'s text (a model file too)")
      .def_static("from_json", &RefineResultFromJson, py::arg("text"), py::arg("source") = "json")
      .def_readonly("initial", &RefineResult::initial)
      .def_readonly("model", &RefineResult::model)
      .def_readonly("names", &RefineResult::names)
      .def_readonly("std_error", &RefineResult::std_error)
      .def_readonly("initial_cost", &RefineResult::initial_cost)
      .def_readonly("final_cost", &RefineResult::final_cost)
      .def_readonly("rms_error_mps", &RefineResult::rms_error_mps)
      .def_readonly("iterations", &RefineResult::iterations)
      .def_readonly("simulations", &RefineResult::simulations)
      .def_property_readonly("termination",
                             [](const RefineResult& r) { return ToString(r.termination); })
      .def_readonly("message", &RefineResult::message)
      .def_readonly("warnings", &RefineResult::warnings)
      .def_readonly("wall_time_s", &RefineResult::wall_time_s)
      .def("brief_report", &RefineResult::BriefReport);
  m.def("refine_recordings", &RefineOutputError, py::arg("initial"), py::arg("recordings"),
        py::arg("options") = RefineOptions{}, ReleaseGil());

}

}  // namespace

void BindIdentify(py::module_& m) {
  BindPulses(m);
  BindVoltageLoop(m);
  BindTrajectory(m);
  BindDelayTuning(m);
  BindRefinement(m);
}

}  // namespace sysid::python
