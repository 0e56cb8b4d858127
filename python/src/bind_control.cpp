// PI position control with feedforward on the virtual stage (sysid/control.hpp) and the inverse
// models as feedforward (sysid/compare.hpp): the tracking experiment of `sysid track`.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "bind_common.hpp"
#include "bind_fields.hpp"
#include "sysid/compare.hpp"
#include "sysid/control.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"
#include "sysid/pipeline.hpp"
#include "sysid/stage.hpp"

namespace sysid::python {
namespace {

/// One closed-loop run on a fresh virtual stage seeded with `seed` (every scheme of a
/// comparison sees the same plant and noise), playing `u_ff_v` [V] sample by sample.
py::tuple TrackStage(const StageParameters& stage, const PositionReference& reference,
                     PiOptions pi, const std::optional<Eigen::VectorXd>& u_ff_v,
                     std::uint64_t seed) {
  if (u_ff_v && u_ff_v->size() != reference.t_s.size())
    throw InputError("track: the feedforward has " + std::to_string(u_ff_v->size()) +
                     " values, the reference " + std::to_string(reference.t_s.size()));
  pi.sample_time_s = stage.sample_time_s();
  TrackingResult result;
  std::string limits;
  {
    py::gil_scoped_release release;
    VirtualStage plant(stage, seed);
    result = RunClosedLoop(plant, reference, pi,
                           u_ff_v ? SampledFeedforward(*u_ff_v) : Feedforward{});
    limits = plant.status().Describe();
  }
  return py::make_tuple(result, limits);
}

}  // namespace

// Long function: a pybind11 registration table, one entry per bound type and field in the
// header's order; split, it would only scatter the table.
void BindControl(py::module_& m) {
  py::module_ s = m.attr("stage").cast<py::module_>();

  py::enum_<AntiWindup>(s, "AntiWindup")
      .value("none", AntiWindup::kNone)
      .value("conditional_integration", AntiWindup::kConditionalIntegration);
  py::class_<PiOptions> pi(s, "PiOptions", "Discrete PI position controller (paper's gains).");
  AddKeywordInit(pi);
  AddOptionsJson(pi, &PiOptionsFromJson);
  DefFields(pi);
  pi.def("validate", &PiOptions::Validate)
      .def_static("for_actuator_delay_stage", &PiOptions::ForActuatorDelayStage);

  py::class_<SmoothProfileOptions> profile(s, "SmoothProfileOptions");
  AddKeywordInit(profile);
  AddOptionsJson(profile, &SmoothProfileOptionsFromJson);
  DefFields(profile);
  profile.def("validate", &SmoothProfileOptions::Validate);

  py::class_<PositionReference>(s, "PositionReference")
      .def_readonly("t_s", &PositionReference::t_s)
      .def_readonly("x_m", &PositionReference::x_m)
      .def_readonly("v_mps", &PositionReference::v_mps)
      .def_readonly("a_mps2", &PositionReference::a_mps2)
      .def_readonly("description", &PositionReference::description);
  s.def("smooth_profile", &MakeSmoothProfile, py::arg("options") = SmoothProfileOptions{},
        "The minimum-jerk back-and-forth profile of the tracking experiment.");
  s.def(
      "reference_from_positions",
      [](const py::object& t_s, const py::object& x_m) {
        const Eigen::VectorXd t = RealVector(t_s, "t_s"), x = RealVector(x_m, "x_m");
        CheckSameLength("reference_from_positions", "t_s", t.size(), "x_m", x.size());
        return ReferenceFromPositions(t, x);
      },
      py::arg("t_s"), py::arg("x_m"));

  py::class_<TrackingResult> tracking(s, "TrackingResult");
  constexpr const char* kTrace = "a trace of the run; the JSON holds its metrics only";
  DefReadOnlyFields(tracking)
      .Stored("t_s", &TrackingResult::t_s, kTrace)
      .Stored("x_ref_m", &TrackingResult::x_ref_m, kTrace)
      .Stored("x_m", &TrackingResult::x_m, kTrace)
      .Stored("e_m", &TrackingResult::e_m, kTrace)
      .Stored("u_v", &TrackingResult::u_v, kTrace)
      .Stored("u_ff_v", &TrackingResult::u_ff_v, kTrace);
  tracking.def("brief_report", &TrackingResult::BriefReport)
      .def("to_json", py::overload_cast<const TrackingResult&, int>(&ToJson),
           py::arg("indent") = 2, "the metrics as `sysid track --json` lists them")
      .def_static("from_json", &TrackingResultFromJson, py::arg("text"),
                  py::arg("source") = "json", "the metrics back (the traces stay empty)");
  py::class_<TrackingRow> tracking_row(s, "TrackingRow");
  DefReadOnlyFields(tracking_row)
      .Stored("result", &TrackingRow::result,
              "the whole run (its traces too); the row's file keys are two of its metrics");

  // The pipeline's run summary (`sysid pipeline --json`), read back from its JSON.
  py::class_<PipelineResult> pipeline(m, "PipelineResult",
                                      "A pipeline run's summary: see "
                                      "sysid::PipelineResultFromJson for what the JSON carries.");
  constexpr const char* kSummaryKey = "a key ToJson(PipelineResult) writes beside the fields";
  DefReadOnlyFields(pipeline)
      .PickleByJson([](const PipelineResult& r) { return ToJson(r, -1); },
                    [](const std::string& text) { return PipelineResultFromJson(text, "pickle"); })
      .Derived(
          "dominant", [](const PipelineResult& r) { return r.dominance.dominant; }, kSummaryKey)
      .Stored("nn_inputs", &PipelineResult::nn_inputs, kSummaryKey)
      .Stored("network", &PipelineResult::network, kSummaryKey)
      .Stored("network_test_mse", &PipelineResult::network_test_mse, kSummaryKey)
      .Derived(
          "typical_train_mse",
          [](const PipelineResult& r) -> std::optional<double> {
            if (!r.typical) return std::nullopt;
            return r.typical->train_mse;
          },
          kSummaryKey)
      .Stored("typical_test_mse", &PipelineResult::typical_test_mse, kSummaryKey)
      .Derived(
          "tuned_pi",
          [](const PipelineResult& r) -> std::optional<PiOptions> {
            if (!r.tuning) return std::nullopt;
            return r.tuning->pi;
          },
          "the PI gains tuned on the model (a pulse-only run), else None")
      .Derived(
          "margins",
          [](const PipelineResult& r) -> std::optional<py::dict> {
            if (!r.margins) return std::nullopt;
            py::dict out;
            for (const auto& [name, a1, m] : r.margins->directions) {
              py::dict d;
              d["crossover_rad_s"] = m.crossover_rad_s;
              d["phase_margin_deg"] = m.phase_margin_deg;
              d["gain_margin"] = m.gain_margin;
              d["stable"] = m.Stable();
              out[py::str(name)] = d;
            }
            return out;
          },
          "the PI gains' margins on the final model per direction (None without tracking)")
      .Derived(
          "facts_required_met",
          [](const PipelineResult& r) -> std::optional<bool> {
            if (!r.facts) return std::nullopt;
            return r.facts->RequiredMet();
          },
          kSummaryKey);
  pipeline
      .def("to_json", py::overload_cast<const PipelineResult&, int>(&ToJson),
           py::arg("indent") = 2)
      .def_static("from_json", &PipelineResultFromJson, py::arg("text"),
                  py::arg("source") = "json");
  s.def(
      "track_stage",
      [](const StageParameters& stage, const PositionReference& reference, const PiOptions& pi,
         const py::object& u_ff_v, std::uint64_t seed) {
        std::optional<Eigen::VectorXd> u_ff;
        if (!u_ff_v.is_none()) u_ff = RealVector(u_ff_v, "u_ff_v");
        return TrackStage(stage, reference, pi, u_ff, seed);
      },
      py::arg("parameters"), py::arg("reference"), py::arg("pi"), py::arg("u_ff_v"),
      py::arg("seed"));
  s.def(
      "track_scheme",
      [](const StageParameters& stage, const PositionReference& reference, const PiOptions& pi,
         const std::string& scheme, const std::optional<FrictionModel>& model,
         const std::optional<NeuralNetwork>& network, std::uint64_t seed) {
        // The loop `sysid track` runs (TrackSchemes): the inverse stepped inside it.
        InverseModels models;
        if (model) models.model = &*model;
        if (network) models.network = &*network;
        const FeedforwardScheme ff = ParseFeedforwardScheme(scheme);
        std::vector<SchemeTracking> runs;
        {
          py::gil_scoped_release release;
          runs = TrackSchemes(stage, seed, reference, pi, {ff}, models);
        }
        return py::make_tuple(runs[0].result, runs[0].stage_limits);
      },
      py::arg("parameters"), py::arg("reference"), py::arg("pi"), py::arg("scheme"),
      py::arg("model"), py::arg("network"), py::arg("seed"));

  m.def(
      "pi_margins_json",
      [](const FrictionModel& model, const PiOptions& pi, double extra_delay_s) {
        return ToJson(AnalyzePiMargins(model, pi, extra_delay_s));
      },
      py::arg("model"), py::arg("pi"), py::arg("extra_delay_s") = 0.0,
      "The PI loop's gain and phase margins on the model, per direction, as `sysid margins "
      "--json` prints them.");
  m.def(
      "tune_pi_json",
      [](const FrictionModel& model, const std::string& plant, double loop_rate_hz,
         double phase_margin_deg, double gain_margin_db, double corner_ratio, double extra_delay_s,
         double u_max_v) {
        PiTuningOptions o;
        o.loop_rate_hz = loop_rate_hz;
        o.phase_margin_deg = phase_margin_deg;
        o.gain_margin_db = gain_margin_db;
        o.crossover_per_integral_corner = corner_ratio;
        o.extra_delay_s = extra_delay_s;
        o.u_max_v = u_max_v;
        const PiTuningResult r = TunePi(model, o);
        return TunePiToJson(plant, r, SimulatePiBehaviour(model, r.pi));
      },
      py::arg("model"), py::arg("plant"), py::arg("loop_rate_hz"), py::arg("phase_margin_deg"),
      py::arg("gain_margin_db"), py::arg("crossover_per_integral_corner"), py::arg("extra_delay_s"),
      py::arg("u_max_v"),
      "PI gains for the model meeting the margins, as `sysid tune-pi --json` prints them.");
  // The library checks that v and a are equally long (InputError naming v_mps and a_mps2).
  m.def(
      "analytic_inverse",
      [](const FrictionModel& model, double dt_s, const py::object& v_mps,
         const py::object& a_mps2) {
        return AnalyticInverse(model, dt_s, RealVector(v_mps, "v_mps"),
                               RealVector(a_mps2, "a_mps2"));
      },
      py::arg("model"), py::arg("dt_s"), py::arg("v_mps"), py::arg("a_mps2"),
      "u [V] of the analytic inverse with v(t - tau) interpolated.");
  m.def(
      "network_inverse",
      [](const NeuralNetwork& n, const py::object& v_mps, const py::object& a_mps2) {
        return NetworkInverse(n, RealVector(v_mps, "v_mps"), RealVector(a_mps2, "a_mps2"));
      },
      py::arg("network"), py::arg("v_mps"), py::arg("a_mps2"),
      "u [V] of a network on v [m/s] (and a [m/s^2]).");
}

}  // namespace sysid::python
