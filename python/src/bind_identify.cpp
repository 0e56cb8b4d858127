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
void AddSolvedTermination(ReadOnlyFields<R>& fields) {
  fields.Derived(
      "termination", [](const R&) { return "solved"; },
      "least squares either returns a solution or throws NumericalError: no other termination");
}

constexpr const char* kFitArrays = "the fit's arrays; its file holds the estimates by name";

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

  py::class_<Pulse> pulse(m, "Pulse");
  constexpr const char* kRows = "the pulse's place in its recording; a file gives its times";
  DefReadOnlyFields(pulse)
      .Stored("first_row", &Pulse::first_row, kRows)
      .Stored("end_row", &Pulse::end_row, kRows)
      .Stored("at_record_start", &Pulse::at_record_start, kRows)
      .Stored("at_record_end", &Pulse::at_record_end, kRows);
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
  py::class_<PulseEstimate> estimate(m, "PulseEstimate");
  DefReadOnlyFields(estimate)
      .Stored("window_samples", &PulseEstimate::window_samples,
              "the plateau window's length; the file gives the estimate and its error")
      .Derived("usable", &PulseEstimate::usable, "whether the status is ok");

  py::class_<LinearFit> linear_fit(m, "LinearFit");
  DefReadOnlyFields(linear_fit)
      .Stored("names", &LinearFit::names, kFitArrays)
      .Stored("theta", &LinearFit::theta, kFitArrays)
      .Stored("std_error", &LinearFit::std_error, kFitArrays)
      .Stored("covariance", &LinearFit::covariance, kFitArrays)
      .Stored("residuals", &LinearFit::residuals, kFitArrays);
  // An input (a pulse table's row): read-write, constructed from its three values.
  py::class_<PulsePoint> point(m, "PulsePoint");
  point.def(py::init([](double u, double v, std::string label) {
              return PulsePoint{u, v, std::move(label)};
            }),
            py::arg("u_v") = 0.0, py::arg("v_mps") = 0.0, py::arg("label") = "");
  DefFields(point);
  m.def(
      "read_pulse_table", [](const std::string& path) { return ReadPulseTable(path); },
      py::arg("path"));

  py::class_<PulseIdentificationResult> pulse_result(m, "PulseIdentificationResult");
  ReadOnlyFields<PulseIdentificationResult> pulse_fields = DefReadOnlyFields(pulse_result);
  constexpr const char* kModelFile = "written by the model file's writer around the fields";
  pulse_fields.Stored("model", &PulseIdentificationResult::model, kModelFile)
      .Stored("a3_given", &PulseIdentificationResult::a3_given, kModelFile)
      .Stored("points", &PulseIdentificationResult::points, kModelFile)
      .Derived(
          "message",
          [](const PulseIdentificationResult& r) {
            return fmt::format("{} equations, rank {}", r.fit.rows, r.fit.rank);
          },
          "the fit's size in words");
  AddSolvedTermination(pulse_fields);
  pulse_result.def("brief_report", &PulseIdentificationResult::BriefReport)
      .def("to_json", py::overload_cast<const PulseIdentificationResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid identify --json`'s text (a model file too)")
      .def_static("from_json", &PulseIdentificationResultFromJson, py::arg("text"),
                  py::arg("source") = "json");
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
  using TrajectoryResult = TrajectoryIdentificationResult;
  ReadOnlyFields<TrajectoryResult> trajectory_fields = DefReadOnlyFields(trajectory_result);
  trajectory_fields
      .Stored("model", &TrajectoryResult::model, "the model file's part of the result's JSON")
      .Stored("fit", &TrajectoryResult::fit, "written as \"linear_fit\" by the result's JSON")
      .Stored("names", &TrajectoryResult::names, kFitArrays)
      .Stored("estimate", &TrajectoryResult::estimate, kFitArrays)
      .Stored("std_error", &TrajectoryResult::std_error, kFitArrays)
      .Stored("covariance", &TrajectoryResult::covariance, kFitArrays)
      .Derived(
          "message",
          [](const TrajectoryResult& r) {
            return fmt::format("{} moving samples, relative error {:.4g}", r.samples_used,
                               r.relative_error);
          },
          "the fit's size and error in words");
  AddSolvedTermination(trajectory_fields);
  trajectory_result
      .def("to_json", py::overload_cast<const TrajectoryResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid identify --method trajectory --json`'s text")
      .def_static("from_json", &TrajectoryIdentificationResultFromJson, py::arg("text"),
                  py::arg("source") = "json")
      .def("brief_report", &TrajectoryResult::BriefReport);
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
  py::class_<DelayTuningResult> delay_result(m, "DelayTuningResult");
  DefReadOnlyFields(delay_result);
  delay_result
      .def("to_json", py::overload_cast<const DelayTuningResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid tune-delay --json`'s text")
      .def_static("from_json", &DelayTuningResultFromJson, py::arg("text"),
                  py::arg("source") = "json")
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
  py::class_<RefineResult> refine_result(m, "RefineResult");
  constexpr const char* kRefineFile = "the model file's part of the result's JSON";
  DefReadOnlyFields(refine_result)
      .Stored("initial", &RefineResult::initial, kRefineFile)
      .Stored("model", &RefineResult::model, kRefineFile)
      .Stored("names", &RefineResult::names, kRefineFile)
      .Stored("std_error", &RefineResult::std_error, kRefineFile)
      .Stored("wall_time_s", &RefineResult::wall_time_s,
              "not in the file, which stays identical run to run");
  refine_result
      .def("to_json", py::overload_cast<const RefineResult&, int>(&ToJson),
           py::arg("indent") = 2, "`sysid refine --json`'s text (a model file too)")
      .def_static("from_json", &RefineResultFromJson, py::arg("text"), py::arg("source") = "json")
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
