// The exported inverses inside the loops of the twins (issue #39, docs/deploy.md): loads
// NAME_init / NAME_step / NAME_state_size from a shared object built from `sysid export`'s C and
// runs RunClosedLoop with it as the per-sample feedforward, and again with the library's
// stepper on a second plant of the same seed. Exit 0 when the two tracking-error traces agree
// to 1e-12 m, 1 otherwise, 2 on bad arguments or a missing symbol. Prints both runs' max |e|
// and the library's own loop's (SchemeFeedforward), for the docs.
//   export_closed_loop stage MODEL.json LIB.so PREFIX DT   the analytic inverse (v, a) in the
//       default virtual stage's PI loop, the smooth profile; DT [s] the export's --dt, which
//       must be the stage's control period
//   export_closed_loop stack-model OUT.json                writes the PI inverse the stack test
//       exports: the default stack's hysteresis as a classical PI (rate weights dropped)
//   export_closed_loop stack MODEL.json LIB.so PREFIX DT   that PI inverse (x_ref) in the
//       default piezo stack's PI loop, the 10 Hz sine
#include <dlfcn.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "sysid/compare_hysteresis.hpp"
#include "sysid/control.hpp"
#include "sysid/hysteresis.hpp"
#include "sysid/hysteresis_stepper.hpp"
#include "sysid/model.hpp"
#include "sysid/model_stepper.hpp"
#include "sysid/stack.hpp"
#include "sysid/stage.hpp"

namespace {

using InitFn = void (*)(void*);
using StepFn2 = double (*)(void*, double, double);
using StepFn1 = double (*)(void*, double);
using SizeFn = unsigned long (*)(void);

double MaxAbsDiff(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return 1e300;
  return (a - b).cwiseAbs().maxCoeff();
}

sysid::PrandtlIshlinskiiModel StackInverseModel() {
  sysid::PiParameters p = sysid::StackParameters::Default().HysteresisPi();
  p.form = sysid::PiForm::kClassical;
  p.rate_weights.clear();
  return sysid::PrandtlIshlinskiiModel(p);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "stack-model" && argc == 3) {
    std::ofstream(argv[2]) << StackInverseModel().ToJson();
    return 0;
  }
  if ((mode != "stage" && mode != "stack") || argc != 6) {
    std::fprintf(stderr,
                 "usage: %s stage|stack MODEL.json LIB.so PREFIX DT | stack-model OUT.json\n",
                 argv[0]);
    return 2;
  }
  const std::string prefix = argv[4];
  void* lib = dlopen(argv[3], RTLD_NOW | RTLD_LOCAL);
  if (lib == nullptr) {
    std::fprintf(stderr, "%s: %s\n", argv[3], dlerror());
    return 2;
  }
  // POSIX: a data pointer from dlsym converts to a function pointer.
  void* const step_symbol = dlsym(lib, (prefix + "_step").c_str());
  const auto init = reinterpret_cast<InitFn>(dlsym(lib, (prefix + "_init").c_str()));
  const auto size = reinterpret_cast<SizeFn>(dlsym(lib, (prefix + "_state_size").c_str()));
  if (init == nullptr || step_symbol == nullptr || size == nullptr) {
    std::fprintf(stderr, "%s: no %s_init, %s_step or %s_state_size\n", argv[3], prefix.c_str(),
                 prefix.c_str(), prefix.c_str());
    return 2;
  }
  // The caller-owned state, aligned for doubles.
  std::vector<double> state((size() + sizeof(double) - 1) / sizeof(double) + 1);
  init(state.data());

  sysid::TrackingResult exported, library, scheme;
  double dt_s = 0;
  long samples = 0;
  if (mode == "stage") {
    const auto step = reinterpret_cast<StepFn2>(step_symbol);
    const sysid::FrictionModel model = sysid::ReadModel(argv[2]);
    const sysid::StageParameters stage = sysid::StageParameters::Default();
    dt_s = 1.0 / stage.rig.sample_rate_hz;
    if (std::stod(argv[5]) != dt_s) {
      std::fprintf(stderr, "the export's dt %s s is not the stage's control period %.17g s\n",
                   argv[5], dt_s);
      return 2;
    }
    const sysid::PositionReference reference =
        sysid::MakeStageProfile(stage, sysid::SmoothProfileOptions{});
    samples = static_cast<long>(reference.t_s.size());
    sysid::PiOptions pi;
    pi.sample_time_s = dt_s;
    sysid::VirtualStage exported_stage(stage, 1);
    exported = sysid::RunClosedLoop(
        exported_stage, reference, pi,
        [&](const sysid::ReferenceSample& r) { return step(state.data(), r.v_mps, r.a_mps2); });
    sysid::FrictionInverseStepper stepper(model, dt_s);
    sysid::VirtualStage library_stage(stage, 1);
    library = sysid::RunClosedLoop(
        library_stage, reference, pi,
        [&](const sysid::ReferenceSample& r) { return stepper.Step(r.v_mps, r.a_mps2); });
    sysid::InverseModels models;
    models.model = &model;
    sysid::VirtualStage scheme_stage(stage, 1);
    scheme = sysid::RunClosedLoop(
        scheme_stage, reference, pi,
        sysid::SchemeFeedforward(sysid::FeedforwardScheme::kAnalytic, reference, dt_s, models));
  } else {
    const auto step = reinterpret_cast<StepFn1>(step_symbol);
    const auto read = sysid::ReadHysteresisModel(argv[2]);
    const auto* model = dynamic_cast<const sysid::PrandtlIshlinskiiModel*>(read.get());
    if (model == nullptr) return 2;
    const sysid::StackParameters stack = sysid::StackParameters::Default();
    dt_s = stack.sample_time_s();
    if (std::stod(argv[5]) != dt_s) {
      std::fprintf(stderr, "the export's dt %s s is not the stack's control period %.17g s\n",
                   argv[5], dt_s);
      return 2;
    }
    const sysid::PositionReference reference =
        sysid::MakeStackReference(sysid::StackReferenceOptions{});
    samples = static_cast<long>(reference.t_s.size());
    const sysid::PiOptions pi = sysid::StackPiOptions(stack);
    // The hysteresis inverse takes x_ref,k: the loop hands the feedforward the reference at
    // each sample, in order.
    auto run = [&](const sysid::Feedforward& ff) {
      sysid::PiezoStack plant(stack, 1);
      return sysid::RunClosedLoop([&plant](double u) { return plant.Step(u); },
                                  plant.measured_position_m(), reference, pi, ff);
    };
    exported = run([&](const sysid::ReferenceSample& r) { return step(state.data(), r.x_m); });
    sysid::PiInverseStepper stepper(*model, dt_s);
    library = run([&](const sysid::ReferenceSample& r) { return stepper.Step(r.x_m); });
    sysid::InverseModels models;
    models.hysteresis = model;
    scheme = run(
        sysid::SchemeFeedforward(sysid::FeedforwardScheme::kHysteresis, reference, dt_s, models));
  }
  const double de = MaxAbsDiff(exported.e_m, library.e_m);
  std::printf(
      "%s closed loop, %ld samples at %g s: max |e| exported C %.6g m, library stepper "
      "%.6g m, library loop (SchemeFeedforward) %.6g m; max |e_C - e_stepper| = %.3g m (bound "
      "1e-12 m), max |e_stepper - e_loop| = %.3g m\n",
      mode.c_str(), samples, dt_s, exported.max_error_m, library.max_error_m, scheme.max_error_m,
      de, MaxAbsDiff(library.e_m, scheme.e_m));
  dlclose(lib);
  return de <= 1e-12 ? 0 : 1;
}
