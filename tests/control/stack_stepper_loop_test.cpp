// The stack's loop steps the hysteresis inverse inside the loop (issue #39): each model kind's
// inverse stepper, called once per sample with x_ref,k, against the same loop playing back the
// batch inverse Invert(x_ref) computed over the whole reference first. Invert is a loop over the
// same stepper (pi, gpi, rdpi, bouc-wen-piezo), so the tracking errors agree bit for bit;
// nn-operators' Invert evaluates its network in one batch (Eigen's summation order, a few ulp
// from the stepper's), so to rounding. The playback shifted by one sample must be far outside
// that agreement (the check sees a one-sample lag); a reference out of a model's reach stops
// the loop with Invert's own error.
#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "sysid/compare_hysteresis.hpp"
#include "sysid/control.hpp"
#include "sysid/error.hpp"
#include "sysid/stack.hpp"

using sysid::FeedforwardScheme;

namespace {

double MaxAbsDiff(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

// PI alone tracking 22 um sines at 2, 10 and 40 Hz: the recordings the models are fitted on.
std::vector<sysid::Recording> Training(const sysid::StackParameters& stack) {
  std::vector<sysid::Recording> training;
  for (double f : {2.0, 10.0, 40.0}) {
    sysid::StackReferenceOptions o;
    o.frequency_hz = f;
    o.stroke_m = 22e-6;
    o.cycles = 1;
    o.sample_rate_hz = stack.rig.control_rate_hz;
    const auto runs =
        sysid::TrackStackSchemes(stack, 2, sysid::MakeStackReference(o),
                                 sysid::StackPiOptions(stack), {FeedforwardScheme::kNone}, {});
    training.push_back(sysid::TrackingRecording(runs[0].result, "none"));
  }
  return training;
}

sysid::PositionReference Reference(const sysid::StackParameters& stack,
                                   sysid::StackWaveform waveform, double stroke_m) {
  sysid::StackReferenceOptions o;
  o.waveform = waveform;
  o.frequency_hz = 10;
  o.stroke_m = stroke_m;
  o.cycles = 1;
  o.sample_rate_hz = stack.rig.control_rate_hz;
  return sysid::MakeStackReference(o);
}

// The loop with a precomputed feedforward played back, on a fresh stack of the same seed.
sysid::TrackingResult Playback(const sysid::StackParameters& stack,
                               const sysid::PositionReference& ref, const Eigen::VectorXd& u_ff) {
  sysid::PiezoStack plant(stack, 3);
  return sysid::RunClosedLoop([&plant](double u) { return plant.Step(u); },
                              plant.measured_position_m(), ref, sysid::StackPiOptions(stack),
                              sysid::SampledFeedforward(u_ff));
}

}  // namespace

TEST_CASE("hysteresis inverse stepped inside the stack's loop equals the batch playback",
          "[control][stack]") {
  // Fitted on the default stack (10 kHz). rdpi's inverse feeds its errors back through the rate
  // term with a gain of 2.6 at 0.1 ms (the library refuses it), so it runs on the stack at
  // 2.5 kHz (gain 0.66).
  const sysid::StackParameters fast = sysid::StackParameters::Default();
  sysid::StackParameters slow = fast;
  slow.rig.control_rate_hz = 2500;
  const std::vector<sysid::Recording> training = Training(fast);
  sysid::HysteresisFitOptions fit;
  fit.operators = 10;
  fit.network.hidden = 5;
  fit.network.max_epochs = 30;
  struct Case {
    const char* kind;
    const sysid::StackParameters* stack;
    int operators;       // PI family and nn-operators (bouc-wen-piezo has none)
    double tolerance_m;  // of the tracking errors' agreement
  };
  for (const Case& c : {Case{"pi", &fast, 10, 0.0}, Case{"gpi", &fast, 10, 0.0},
                        Case{"rdpi", &slow, 10, 0.0}, Case{"bouc-wen-piezo", &fast, 10, 0.0},
                        // a few ulp of u (~1e-14 V) at the stack's ~3e-7 m/V: far below 1e-15 m
                        Case{"nn-operators", &fast, 3, 1e-15}}) {
    const sysid::StackParameters& stack = *c.stack;
    fit.operators = c.operators;
    const auto model = sysid::FitHysteresis(c.kind, training, fit);
    for (auto waveform : {sysid::StackWaveform::kSine, sysid::StackWaveform::kTriangle}) {
      const sysid::PositionReference ref = Reference(stack, waveform, 20e-6);
      const auto runs = sysid::TrackStackSchemes(stack, 3, ref, sysid::StackPiOptions(stack),
                                                 {FeedforwardScheme::kHysteresis},
                                                 {nullptr, nullptr, model.get()});
      REQUIRE(runs.size() == 1);
      const sysid::TrackingResult& in_loop = runs[0].result;
      const Eigen::VectorXd u = model->Invert(ref.x_m, stack.sample_time_s());
      const sysid::TrackingResult batch = Playback(stack, ref, u);
      // The same inverse one sample late: what a loop stepping x_ref,k-1 would give.
      Eigen::VectorXd late(u.size());
      late[0] = u[0];
      late.tail(u.size() - 1) = u.head(u.size() - 1);
      const sysid::TrackingResult lagged = Playback(stack, ref, late);
      const double de = MaxAbsDiff(in_loop.e_m, batch.e_m);
      const double de_lag = MaxAbsDiff(lagged.e_m, batch.e_m);
      INFO(c.kind << ", " << sysid::ToString(waveform) << ": max |e| in the loop "
                  << in_loop.max_error_m << " m, batch " << batch.max_error_m
                  << " m; max |e_loop - e_batch| = " << de << " m, one sample late " << de_lag
                  << " m");
      CHECK(in_loop.u_ff_v.cwiseAbs().maxCoeff() > 10);  // the inverse did feed the loop [V]
      CHECK(MaxAbsDiff(in_loop.u_ff_v, u) <= (c.tolerance_m > 0 ? 1e-12 : 0.0));
      CHECK(de <= c.tolerance_m);
      CHECK(in_loop.u_v.size() == batch.u_v.size());
      // A one-sample lag moves the errors by far more than the agreement allows.
      CHECK(de_lag > 1e-9);
    }
  }
}

TEST_CASE("a reference out of the model's reach stops the stack's loop with Invert's error",
          "[control][stack]") {
  const sysid::StackParameters stack = sysid::StackParameters::Default();
  sysid::HysteresisFitOptions fit;
  fit.network.hidden = 5;
  fit.network.max_epochs = 30;
  fit.operators = 3;
  const std::vector<sysid::Recording> training = Training(stack);
  const sysid::PositionReference far = Reference(stack, sysid::StackWaveform::kSine, 40e-6);
  for (const char* kind : {"pi", "gpi", "nn-operators"}) {
    const auto model = sysid::FitHysteresis(kind, training, fit);
    std::string batch_error;
    try {
      model->Invert(far.x_m, stack.sample_time_s());
    } catch (const sysid::InputError& e) {
      batch_error = e.what();
    }
    INFO(kind << ": Invert says: " << batch_error);
    REQUIRE_THAT(batch_error, Catch::Contains("is outside the " + std::string(kind)));
    CHECK_THROWS_WITH(
        sysid::TrackStackSchemes(stack, 3, far, sysid::StackPiOptions(stack),
                                 {FeedforwardScheme::kHysteresis}, {nullptr, nullptr, model.get()}),
        batch_error);
  }
  // Not invertible: refused before the loop runs, with the model's reason.
  sysid::PiParameters p;
  p.form = sysid::PiForm::kClassical;
  p.thresholds = {1.0};
  p.weights = {-2e-7};
  p.polynomial = {1e-7};
  p.input_min_v = 0;
  p.input_max_v = 100;
  const sysid::PrandtlIshlinskiiModel bad(p);
  REQUIRE_FALSE(bad.invertible());
  CHECK_THROWS_AS(
      sysid::TrackStackSchemes(stack, 3, far, sysid::StackPiOptions(stack),
                               {FeedforwardScheme::kHysteresis}, {nullptr, nullptr, &bad}),
      sysid::NumericalError);
  CHECK_THROWS_WITH(
      sysid::TrackStackSchemes(stack, 3, far, sysid::StackPiOptions(stack),
                               {FeedforwardScheme::kHysteresis}, {nullptr, nullptr, &bad}),
      Catch::Contains("pi model not invertible: "));
}
