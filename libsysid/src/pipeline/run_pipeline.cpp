#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/parallel_for.hpp"
#include "core/task_pool.hpp"
#include "nn/sweep_tasks.hpp"
#include "paper/measures.hpp"
#include "pipeline/timed_step.hpp"
#include "sysid/control_tuning.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"
#include "sysid/nn_irreducible.hpp"
#include "sysid/pipeline.hpp"
#include "sysid/signal.hpp"
#include "sysid/simulate.hpp"
#include "sysid/stage.hpp"

namespace sysid {
namespace {

std::vector<Recording> ReadAll(const std::vector<std::string>& paths, const ReadOptions& ro) {
  std::vector<Recording> out;
  out.reserve(paths.size());
  for (const auto& p : paths) out.push_back(ReadRecording(p, ro));
  return out;
}

// Dominance names variables; networks take recording columns.
std::string ColumnOf(const std::string& variable) {
  if (variable == "velocity") return "v";
  if (variable == "acceleration") return "a";
  return variable;
}

// v and a columns for the network data sets: recorded ones when present (made with the filter
// chosen at collection time), else derived with the default motion filter.
Recording WithDerivatives(const Recording& rec) {
  if (rec.has("v") && rec.has("a")) return rec;
  const MotionSignals m = ExtractMotion(rec);
  Recording out = rec;
  out.SetColumn("v", m.v_mps);
  out.SetColumn("a", m.a_mps2);
  return out;
}

// The first pulse recording's measured velocity beside the model simulated with tau = 0 and
// with its tau, at the tolerances the delay was fitted with.
void PulseVelocityTraces(const Recording& pulse, const FrictionModel& model,
                         const DelayTuningOptions& delay, PipelineFigures& f) {
  const MotionSignals m = ExtractMotion(pulse);
  const auto& t = m.t_s;
  std::vector<double> tt(t.data(), t.data() + t.size()),
      uu(m.u_v.data(), m.u_v.data() + m.u_v.size());
  const PiecewiseConstantInput input(tt, uu);
  SimulationOptions so;
  so.t0_s = t[0];
  so.t_end_s = t[t.size() - 1];
  so.output_times_s = tt;
  so.rtol = delay.sim_rtol;
  so.atol = delay.sim_atol;
  f.pulse_velocity.push_back({"measured", t, m.v_mps});
  FrictionModel no_delay = model;
  no_delay.tau_s = 0;
  for (const auto& [label, mdl] :
       {std::pair<std::string, FrictionModel>{"model, tau = 0", no_delay},
        {fmt::format("model, tau = {:.3g} ms", 1e3 * model.tau_s), model}}) {
    const SimulationResult sim = Simulate(mdl, input, so);
    if (!sim.summary.IsSolutionUsable()) {
      f.pulse_velocity_note = "velocity plot: simulation failed: " + sim.summary.message;
      return;
    }
    f.pulse_velocity.push_back({label, sim.trajectory.t_s, sim.trajectory.v_mps});
  }
}

// The paper's dominance figure: the acceleration term against the viscous term over time.
// PI alone's error at one tracking frequency: its ringing in motion when above F4's tolerance.
void RingingTrace(const TrackingRow& row, PipelineFigures& f) {
  const Eigen::VectorXd& t = row.result.t_s;
  if (t.size() < 2) return;
  SmoothProfileOptions p;
  p.frequency_hz = row.frequency_hz;
  p.sample_rate_hz = 1.0 / (t[1] - t[0]);
  p.cycles = static_cast<int>(
      std::lround(static_cast<double>(t.size() - 1) / p.sample_rate_hz * row.frequency_hz));
  const FactsOptions limits;
  // The ringing frequency (a long FFT) only where it rings.
  if (paper::MotionRippleOf(row.result.e_m, p, limits.motion_ripple_window_s, false).rms_m <=
      limits.motion_ripple_tolerance_m)
    return;
  const paper::MotionRipple m =
      paper::MotionRippleOf(row.result.e_m, p, limits.motion_ripple_window_s);
  f.tracking_ringing.push_back({row.frequency_hz, p.sample_rate_hz, m.rms_m, m.ringing_hz});
}

void DominanceTraces(const Recording& training, const FrictionModel& model, PipelineFigures& f) {
  const MotionSignals m = ExtractMotion(training);
  const Eigen::VectorXd vd = DelaySignal(m.v_mps, m.dt_s, model.tau_s);
  Eigen::VectorXd viscous(vd.size());
  for (Eigen::Index k = 0; k < vd.size(); ++k)
    viscous[k] = (vd[k] > 0 ? model.a1p : model.a1n) * vd[k];
  f.dominance_terms.push_back({"viscous term a1 v(t - tau)", m.t_s, viscous});
  f.dominance_terms.push_back({"acceleration term x'' = a", m.t_s, m.a_mps2});
}

PipelineFigures::NetworkSet NetworkTraces(const std::string& set, const Recording& rec,
                                          const NeuralNetwork& typical,
                                          const NeuralNetwork& dominant,
                                          const std::vector<std::string>& dominant_inputs) {
  const NeuralDataset va = MakeNeuralDataset(rec, {"v", "a"}, "u");
  const NeuralDataset dv = MakeNeuralDataset(rec, dominant_inputs, "u");
  PipelineFigures::NetworkSet s;
  s.set = set;
  s.targets_v = va.targets;
  s.typical_v = typical.EvaluateBatch(va.inputs);
  s.dominant_v = dominant.EvaluateBatch(dv.inputs);
  s.typical_mse = MeanSquaredError(typical, va);
  s.dominant_mse = MeanSquaredError(dominant, dv);
  s.typical_floor_mse = EstimateIrreducibleError(va).mse;
  s.dominant_floor_mse = EstimateIrreducibleError(dv).mse;
  return s;
}

// Pulse recordings alone: each cut at the fraction F of its duration, the first part to fit, the
// rest to validate on (F = 1: the whole recording to fit, nothing held out).
void SplitPulses(std::vector<Recording>& pulses, double fraction, std::vector<Recording>& held_out,
                 std::vector<std::string>& notes) {
  if (fraction >= 1) {
    notes.push_back(
        "pulse recordings alone, fitted whole (pulse_fit_fraction = 1): the model is "
        "validated on the waveforms only");
    return;
  }
  for (Recording& rec : pulses) {
    const auto t = rec.column("t");
    const double first = t[0], last = t[t.size() - 1];
    const double cut = first + fraction * (last - first);
    held_out.push_back(CropRecording(rec, cut, last));
    rec = CropRecording(rec, first, cut);
    notes.push_back(fmt::format(
        "pulse recordings alone: the model is identified on t = {:.6g} .. {:.6g} s of {} (the "
        "first {:g} %) and validated on t = {:.6g} .. {:.6g} s (its rows in the validation "
        "table)",
        first, cut, rec.source, 100 * fraction, cut, last));
  }
}

// What a pulse-only run leaves out, and the recordings that would enable it.
std::vector<std::string> SkippedWithoutTrackingSets() {
  const std::string sets =
      "a training set and a test set (training*.csv and test*.csv: closed-loop tracking "
      "recordings with t, u, x; sysid generate tracking makes them on the twin)";
  return {"dominance analysis: needs " + sets,
          "NN hidden-size sweep and the typical (v, a) network: need " + sets,
          "inverse-model comparison (analytic vs NN): needs " + sets + " and a network"};
}

// One run of the stage pipeline: the recordings, read once, and the steps in order, each timed.
struct PipelineRun {
  const PipelineInputs& inputs;
  const PipelineOptions& options;
  const PipelineProgress& progress;
  PipelineResult& r;
  const bool pulses_only;
  std::vector<Recording> pulses, held_out_pulses, waveforms;
  Recording training, test;

  PipelineRun(const PipelineInputs& in, const PipelineOptions& opt, const PipelineProgress& prog,
              PipelineResult& result)
      : inputs(in), options(opt), progress(prog), r(result), pulses_only(in.PulsesOnly()) {}

  template <typename Body>
  void step(const std::string& name, Body&& body) {
    internal::TimedStep(r, progress, name, body);
  }

  // `track` of each scheme on the smooth profile at each tracking frequency, sampled at
  // `rate_hz`. Every (frequency, scheme) run is independent (the trackers reset the plant
  // before each scheme), so they run side by side (--threads), the lowest frequency's first
  // (its profile lasts longest: `cycles` periods); their rows are appended to `rows` in
  // frequency, then scheme order.
  template <typename Track>
  void TrackAtEachFrequency(double rate_hz, const std::vector<FeedforwardScheme>& schemes,
                            std::vector<TrackingRow>* rows, const Track& track) {
    const auto& freqs = options.track_frequencies_hz;
    std::vector<std::size_t> by_length(freqs.size());
    std::iota(by_length.begin(), by_length.end(), std::size_t{0});
    std::stable_sort(by_length.begin(), by_length.end(),
                     [&](std::size_t a, std::size_t b) { return freqs[a] < freqs[b]; });
    const std::size_t S = schemes.size();
    std::vector<SchemeTracking> runs(freqs.size() * S);
    internal::ParallelFor(static_cast<long>(runs.size()), options.threads, [&](long item) {
      const std::size_t f = by_length[static_cast<std::size_t>(item) / S];
      const std::size_t s = static_cast<std::size_t>(item) % S;
      SmoothProfileOptions p;
      p.frequency_hz = freqs[f];
      p.amplitude_m = options.track_amplitude_m;
      p.sample_rate_hz = rate_hz;
      std::vector<SchemeTracking> one = track(MakeSmoothProfile(p), schemes[s]);
      runs[f * S + s] = std::move(one.at(0));
    });
    for (std::size_t f = 0; f < freqs.size(); ++f)
      for (std::size_t s = 0; s < S; ++s)
        rows->push_back({freqs[f], ToString(runs[f * S + s].scheme), runs[f * S + s].result});
  }

  // Read the recordings; identify a1, a2 from the pulses, then the delay (and the refinement).
  void IdentifyModel() {
    step("read recordings", [&] {
      pulses = ReadAll(inputs.pulses, inputs.Read());
      if (!pulses_only) {
        training = WithDerivatives(ReadRecording(inputs.training, inputs.Read()));
        test = WithDerivatives(ReadRecording(inputs.test, inputs.Read()));
      }
      waveforms = ReadAll(inputs.waveforms, inputs.Read());
      if (pulses_only) {
        SplitPulses(pulses, options.pulse_fit_fraction, held_out_pulses, r.notes);
        r.skipped = SkippedWithoutTrackingSets();  // the report's section 3-5 lists them
      }
    });

    step("identify (pulse least squares)", [&] {
      PulseIdentificationOptions po;
      po.fit.a3 = inputs.a3.value_or(options.a3);
      po.fit.a3_given = inputs.a3.has_value() || options.a3_given;
      if (!po.fit.a3_given)
        r.notes.push_back("warning: " + DescribeA3(po.fit.a3, false) +
                          "; a1 and a2 scale with a3, so this model is the paper's stage's unless "
                          "a3 is right for yours");
      r.pulse = IdentifyFromPulses(pulses, po);
      r.model = r.pulse.model;
    });

    if (options.tune_delay) {
      step("tune delay (NLopt)", [&] {
        DelayTuningOptions d = options.delay;
        d.threads = options.threads;
        if (d.curve_points == 0) d.curve_points = 21;  // the report plots cost against tau
        r.delay = TuneDelay(r.model, pulses, d);
        if (!IsSolutionUsable(r.delay->termination)) {
          r.notes.push_back("delay tuning failed (" + r.delay->message + "); tau = 0 kept");
        } else {
          r.model = r.delay->model;
        }
      });
    }

    if (options.refine) {
      step("refine (Ceres output error)", [&] {
        r.refine = RefineOutputError(r.model, pulses);
        if (r.refine->termination == Termination::kConverged &&
            r.refine->final_cost <= r.refine->initial_cost) {
          r.model = r.refine->model;
        } else {
          r.notes.push_back("output-error refinement did not improve the fit (" +
                            r.refine->message + "); the pulse/delay model is kept");
        }
      });
    }
  }

  // The sweep's networks and the typical one side by side in one pool, the largest first (the
  // typical network: several times the sweep's largest), each on the threads the others leave;
  // trained one step after the other, the end of each left a core idle.
  void TrainNetworks(const NeuralDataset& test_set) {
    internal::TaskPool pool(options.threads);
    const NeuralDataset train_set = MakeNeuralDataset(training, r.nn_inputs, "u");
    HiddenSweepOptions so;
    so.hidden_sizes = options.hidden_sizes;
    so.training = options.training;
    so.threads = options.threads;
    internal::nn::SweepTasks sweep(train_set, nullptr, &test_set, so);
    sweep.AddTo(&pool);
    NeuralDataset train_va, test_va;
    NeuralTrainingOptions t = options.training;
    if (options.typical) {
      train_va =
          SubsampleRows(MakeNeuralDataset(training, {"v", "a"}, "u"), options.typical_stride);
      test_va = MakeNeuralDataset(test, {"v", "a"}, "u");
      t.hidden = options.typical_hidden;
      t.max_epochs = options.typical_max_epochs;
      const double cost = internal::nn::TrainingCost(
          t, static_cast<int>(train_va.input_names.size()), static_cast<size_t>(train_va.size()));
      pool.Add(cost, [&](const internal::ThreadsNow& threads_now) {
        NeuralTrainingOptions own = t;
        own.threads_now = threads_now;
        r.typical = TrainNeuralNetwork(train_va, nullptr, own);
        r.typical_test_mse = MeanSquaredError(r.typical->network, test_va);
      });
    }
    pool.Run();
    r.sweep = sweep.Finish();
    const auto chosen = static_cast<size_t>(r.sweep.chosen);
    r.network = r.sweep.runs[chosen].network;
    r.network_test_mse = r.sweep.rows[chosen].test_mse;
  }

  // The dominant variable, the hidden-size sweep, the typical network, the inverse comparison.
  void InverseNetworks() {
    step("dominance analysis", [&] {
      DominanceOptions dopt;
      dopt.threads = options.threads;
      r.dominance = AnalyzeDominanceBatch(r.model, {training, test}, dopt);
      // The paper's rule: the network takes the dominant variable only; the ranking of the others
      // is in the report. A caller may name the inputs instead.
      r.nn_inputs = options.nn_inputs.empty()
                        ? std::vector<std::string>{ColumnOf(r.dominance.dominant)}
                        : options.nn_inputs;
    });

    const NeuralDataset test_set = MakeNeuralDataset(test, r.nn_inputs, "u");
    step(options.typical ? "NN hidden-size sweep and typical (v, a) network (LM)"
                         : "NN hidden-size sweep (LM)",
         [&] { TrainNetworks(test_set); });

    step("compare inverse models", [&] {
      r.comparisons.push_back(CompareInverseModels(test, r.model, &r.network));
      for (const auto& w : waveforms)
        r.comparisons.push_back(CompareInverseModels(w, r.model, &r.network));
    });
  }

  // The model on every held-out recording, the figures' traces, the voltage-velocity loops.
  void ValidateModel() {
    step("validate the model on held-out recordings", [&] {
      std::vector<const Recording*> held_out;
      if (!pulses_only) held_out = {&training, &test};
      for (const auto& p : held_out_pulses) held_out.push_back(&p);
      for (const auto& w : waveforms) held_out.push_back(&w);
      // Recordings side by side (--threads), their results and notes kept in recording order.
      std::vector<std::optional<Validation>> scored(held_out.size());
      std::vector<std::string> failed(held_out.size());
      internal::ParallelFor(static_cast<long>(held_out.size()), options.threads, [&](long i) {
        const auto k = static_cast<std::size_t>(i);
        try {
          scored[k] = ValidateFrictionModel(*held_out[k], r.model);
        } catch (const NumericalError& e) {
          failed[k] = "validation of " + held_out[k]->source + " skipped: " + e.what();
        }
      });
      for (std::size_t k = 0; k < held_out.size(); ++k) {
        if (scored[k]) r.validations.push_back(std::move(*scored[k]));
        if (!failed[k].empty()) r.notes.push_back(failed[k]);
      }
    });

    step("figure traces (pulse simulation, network outputs)", [&] {
      PulseVelocityTraces(pulses.front(), r.model, options.delay, r.figures);
      if (!pulses_only) DominanceTraces(training, r.model, r.figures);
      if (r.typical)
        for (const auto& [set, rec] :
             {std::pair<std::string, const Recording*>{"training", &training}, {"test", &test}})
          r.figures.networks.push_back(
              NetworkTraces(set, *rec, r.typical->network, r.network, r.nn_inputs));
    });

    if (!inputs.loops.empty()) {
      step("voltage-velocity loop", [&] {
        for (const auto& path : inputs.loops)
          r.loops.push_back(AnalyzeVoltageLoop(ReadRecording(path, inputs.Read())));
      });
    }
  }

  // The PI loop: margins, gains tuned on the model (pulses alone), tracking, the paper's facts.
  void CloseTheLoop() {
    if (options.track) {
      step("loop margins of the PI gains", [&] {
        PiOptions pi = options.pi;
        pi.sample_time_s = inputs.stage.empty()
                               ? AnalyzeSampling(pulses.front().column("t")).nominal_dt_s
                               : ReadStageParameters(inputs.stage).sample_time_s();
        r.margins = AnalyzePiMargins(r.model, pi);
      });
    }

    // Pulses alone: no network to compare, so the loop is closed on the identified model itself,
    // with gains tuned for it (the paper's gains are often unstable on a user's model).
    if (options.track && pulses_only) {
      step("tune PI gains on the identified model", [&] {
        PiTuningOptions to;
        to.loop_rate_hz = 1 / r.margins->pi.sample_time_s;
        to.u_max_v = options.pi.u_max_v;
        try {
          r.tuning = TunePi(r.model, to);
        } catch (const NumericalError& e) {
          r.notes.push_back(std::string("PI tuning found no gains: ") + e.what() +
                            "; the model-plant tracking runs the given gains");
        }
      });
      step("PI tracking on the identified model", [&] {
        const PiOptions pi = r.tuning ? r.tuning->pi : r.margins->pi;
        TrackAtEachFrequency(
            1 / pi.sample_time_s, {FeedforwardScheme::kNone, FeedforwardScheme::kAnalytic},
            &r.model_tracking, [&](const PositionReference& ref, FeedforwardScheme scheme) {
              return TrackModelSchemes(r.model, pi.sample_time_s, ref, pi, {scheme},
                                       {&r.model, nullptr});
            });
      });
    }

    if (options.track && !inputs.stage.empty()) {
      step("PI tracking with feedforward", [&] {
        const StageParameters stage = ReadStageParameters(inputs.stage);
        std::vector<FeedforwardScheme> schemes{FeedforwardScheme::kNone,
                                               FeedforwardScheme::kAnalytic};
        if (!pulses_only) schemes.push_back(FeedforwardScheme::kNetwork);
        TrackAtEachFrequency(stage.rig.sample_rate_hz, schemes, &r.tracking,
                             [&](const PositionReference& ref, FeedforwardScheme scheme) {
                               return TrackSchemes(stage, 1, ref, options.pi, {scheme},
                                                   {&r.model, pulses_only ? nullptr : &r.network});
                             });
        for (const TrackingRow& row : r.tracking)
          if (row.scheme == "none") RingingTrace(row, r.figures);
      });
    } else if (options.track) {
      r.notes.push_back("no stage file: the tracking experiment was skipped");
    }

    if (options.facts && !inputs.stage.empty()) {
      step("paper facts on the stage (F1-F8)", [&] {
        FactsOptions fo = options.facts_options;
        fo.threads = options.threads;
        r.facts = RunStageFacts(ReadStageParameters(inputs.stage), fo);
      });
    } else if (options.facts) {
      r.notes.push_back("no stage file: the paper's facts were not checked");
    }
  }
};

}  // namespace

PipelineResult RunPipeline(const PipelineInputs& inputs, const PipelineOptions& options,
                           const PipelineProgress& progress) {
  if (inputs.IsStack()) return RunStackPipeline(inputs, options, progress);
  options.Validate();
  PipelineResult r;
  r.inputs = inputs;
  r.options = options;
  if (!options.reference_path.empty()) r.reference = ReadPipelineReference(options.reference_path);
  PipelineRun run(inputs, options, progress, r);
  run.IdentifyModel();
  if (!run.pulses_only) run.InverseNetworks();
  run.ValidateModel();
  run.CloseTheLoop();
  return r;
}

}  // namespace sysid
