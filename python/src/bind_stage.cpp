// The virtual piezo stage (sysid/stage.hpp): its parameter files, open-loop runs, the pulse test
// and the tracking experiment that generate the bundled datasets/virtual recordings.
#include <cstdint>
#include <string>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/stage.hpp"

namespace sysid::python {
namespace {

// pybind11 keeps the pointer: the text lives as long as the module.
const char* PresetDoc() {
  static const std::string doc =
      "A named preset (" + StageParameters::PresetNameList() + "); docs/virtual_stage.md.";
  return doc.c_str();
}

}  // namespace

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindStage(py::module_& m) {
  py::module_ s = m.def_submodule("stage", "The virtual piezo stage and its procedures.");

  // The settings both plants share, each a described struct (one attribute per field).
  py::class_<DriverSettings> driver(s, "DriverSettings",
                                    "The driver both plants share: clip, transport delay, lag.");
  AddKeywordInit(driver);
  DefFields(driver);
  driver.def("validate", &DriverSettings::Validate);
  py::class_<RigSettings> rig(s, "RigSettings",
                              "The rig both plants share: rates, DAC, encoder, end stops.");
  AddKeywordInit(rig);
  DefFields(rig);
  rig.def("validate", &RigSettings::Validate);
  py::class_<IntegratorSettings> integrator(
      s, "IntegratorSettings", "The integrator both plants share (CVODE tolerances, work budget).");
  AddKeywordInit(integrator);
  DefFields(integrator);
  integrator.def("validate", &IntegratorSettings::Validate);

  py::class_<StageParameters>(s, "StageParameters",
                              "Every parameter of the virtual stage (SI units); see "
                              "docs/virtual_stage.md. Edit through to_json / from_json.")
      .def(py::init(&StageParameters::Default))
      .def_static("default", &StageParameters::Default)
      .def_static("preset", &StageParameters::Preset, py::arg("name"), PresetDoc())
      .def_static("preset_names", &StageParameters::PresetNames,
                  "The names StageParameters.preset takes, \"virtual\" first.")
      .def_static("load", &ReadStageParameters, py::arg("path"))
      .def(
          "save",
          [](const StageParameters& p, const std::string& path) { WriteStageParameters(path, p); },
          py::arg("path"))
      .def_static("from_json", &ParseStageParameters, py::arg("text"), py::arg("source") = "json")
      .def("to_json", &StageParametersToJson)
      .def_readwrite("name", &StageParameters::name)
      .def_property_readonly(
          "model", [](const StageParameters& p) { return ToString(p.model()); },
          "The plant the stage holds: \"velocity-source\" or \"actuator-delay\".")
      // The actuator-delay plant's fields under their names from before the plants were split;
      // on a velocity-source stage they raise sysid.OptionsError (they are not its fields).
      .def_property(
          "gain_mps2_per_v",
          [](const StageParameters& p) { return p.actuator_delay().gain_mps2_per_v; },
          [](StageParameters& p, double v) { p.actuator_delay().gain_mps2_per_v = v; },
          "[m/(s^2 V)] a3 of the actuator-delay plant (OptionsError on a velocity-source stage)")
      .def_property(
          "dead_zone_v", [](const StageParameters& p) { return p.actuator_delay().dead_zone_v; },
          [](StageParameters& p, double v) { p.actuator_delay().dead_zone_v = v; },
          "[V] the actuator-delay plant's dead zone (OptionsError on a velocity-source stage)")
      .def_readwrite("driver", &StageParameters::driver)
      .def_readwrite("rig", &StageParameters::rig)
      .def_readwrite("integrator", &StageParameters::integrator)
      // Deprecated: the rig's fields under their names from before the shared settings were
      // split out (rig.position_noise_m, ...); kept for one release.
      .def_property(
          "position_noise_m", [](const StageParameters& p) { return p.rig.position_noise_m; },
          [](StageParameters& p, double v) { p.rig.position_noise_m = v; },
          "Deprecated: rig.position_noise_m")
      .def_property(
          "encoder_resolution_m",
          [](const StageParameters& p) { return p.rig.encoder_resolution_m; },
          [](StageParameters& p, double v) { p.rig.encoder_resolution_m = v; },
          "Deprecated: rig.encoder_resolution_m")
      .def_property(
          "sample_rate_hz", [](const StageParameters& p) { return p.rig.sample_rate_hz; },
          [](StageParameters& p, double v) { p.rig.sample_rate_hz = v; },
          "Deprecated: rig.sample_rate_hz")
      .def_property(
          "record_rate_hz", [](const StageParameters& p) { return p.rig.record_rate_hz; },
          [](StageParameters& p, double v) { p.rig.record_rate_hz = v; },
          "Deprecated: rig.record_rate_hz")
      .def_property_readonly("record_stride", &StageParameters::RecordStride)
      .def_property_readonly("sample_time_s", &StageParameters::sample_time_s)
      .def("validate", &StageParameters::Validate)
      .def(
          "steady_velocity",
          [](const StageParameters& p, const py::object& u) {
            return RealElementwise(u, "u_v", [&p](double x) { return p.SteadyVelocity(x); });
          },
          py::arg("u_v"));

  py::class_<StageStatus>(s, "StageStatus")
      .def_readonly("travel_limit_hit", &StageStatus::travel_limit_hit)
      .def_readonly("velocity_limit_exceeded", &StageStatus::velocity_limit_exceeded)
      .def_readonly("steps", &StageStatus::steps)
      .def("describe", &StageStatus::Describe);
  py::class_<StageRun>(s, "StageRun")
      .def_readonly("t_s", &StageRun::t_s)
      .def_readonly("u_v", &StageRun::u_v)
      .def_readonly("x_m", &StageRun::x_m)
      .def_readonly("x_true_m", &StageRun::x_true_m)
      .def_readonly("v_true_mps", &StageRun::v_true_mps)
      .def_readonly("status", &StageRun::status);
  s.def(
      "run_open_loop",
      [](const StageParameters& parameters, const py::object& u_v, std::uint64_t seed) {
        const Eigen::VectorXd u = RealVector(u_v, "u_v");
        py::gil_scoped_release release;
        return RunOpenLoop(parameters, u, seed);
      },
      py::arg("parameters"), py::arg("u_v"), py::arg("seed") = 1,
        "Drives a fresh stage with one command [V] per sample.");

  py::class_<PulseProcedure> pulse(s, "PulseProcedure");
  AddKeywordInit(pulse);
  AddOptionsJson(pulse, &PulseProcedureFromJson);
  DefFields(pulse);
  pulse.def("validate", &PulseProcedure::Validate);

  py::class_<VelocityWaveform::Term>(s, "WaveformTerm")
      .def_readwrite("omega_rad_s", &VelocityWaveform::Term::omega_rad_s)
      .def_readwrite("sin_mps", &VelocityWaveform::Term::sin_mps)
      .def_readwrite("cos_mps", &VelocityWaveform::Term::cos_mps);
  py::class_<VelocityWaveform>(s, "VelocityWaveform")
      .def_readwrite("name", &VelocityWaveform::name)
      .def_readwrite("terms", &VelocityWaveform::terms)
      .def_readwrite("period_s", &VelocityWaveform::period_s)
      .def("velocity",
           [](const VelocityWaveform& w, const py::object& t) {
             return RealElementwise(t, "t_s", [&w](double x) { return w.Velocity(x); });
           },
           py::arg("t_s"))
      .def("position",
           [](const VelocityWaveform& w, const py::object& t) {
             return RealElementwise(t, "t_s", [&w](double x) { return w.Position(x); });
           },
           py::arg("t_s"))
      .def_static("sine", &VelocityWaveform::Sine, py::arg("amplitude_m"),
                  py::arg("omega_rad_s"));
  s.def("paper_test_waveforms", &PaperTestWaveforms);
  s.def("training_grid", &TrainingGrid);
  s.def("test_grid", &TestGrid);

  py::class_<TrackingProcedure> tracking(s, "TrackingProcedure");
  AddKeywordInit(tracking);
  tracking.def_readwrite("kp_v_per_m", &TrackingProcedure::kp_v_per_m)
      .def_readwrite("lead_cycles", &TrackingProcedure::lead_cycles)
      .def_readwrite("kept_cycles", &TrackingProcedure::kept_cycles)
      .def_readwrite("tail_s", &TrackingProcedure::tail_s)
      .def_readwrite("derivative", &TrackingProcedure::derivative)
      .def("validate", &TrackingProcedure::Validate, py::arg("stage"));

  s.def("run_pulse_test", &RunPulseTest, py::arg("parameters"),
        py::arg("procedure") = PulseProcedure{}, py::arg("seed") = 1,
        py::arg("derivative") = DerivativeOptions{}, ReleaseGil(),
        "The paper's pulse test on the virtual stage: columns t, u, x, v, a.");
  s.def("track_waveform", &TrackWaveform, py::arg("parameters"), py::arg("waveform"),
        py::arg("procedure") = TrackingProcedure{}, py::arg("seed") = 1, ReleaseGil(),
        "One waveform tracked by the P controller: columns t, u, x, v, a, x_ref.");
  s.def("run_tracking_set", &RunTrackingSet, py::arg("parameters"), py::arg("grid"),
        py::arg("procedure") = TrackingProcedure{}, py::arg("seed") = 1,
        py::arg("set_name") = "tracking", ReleaseGil());
  s.def("derive_seed", &DeriveSeed, py::arg("seed"), py::arg("index"));
}

}  // namespace sysid::python
