// The exported analytic inverse inside the twin's PI loop (issue #39, docs/deploy.md): loads
// NAME_init / NAME_step / NAME_state_size from a shared object built from `sysid export`'s C,
// runs RunClosedLoop on the virtual stage with it as the per-sample feedforward, and again with
// the library's FrictionInverseStepper on a second stage of the same seed. Exit 0 when the two
// tracking-error traces agree to 1e-12 m, 1 otherwise, 2 on bad arguments or a missing symbol.
// Prints both runs' max |e| and the playback feedforward's (SchemeFeedforward), for the docs.
//   export_closed_loop MODEL.json LIB.so PREFIX DT   (DT [s]: the export's --dt, which must be the
//   default virtual stage's control period)
#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "sysid/control.hpp"
#include "sysid/model.hpp"
#include "sysid/model_stepper.hpp"
#include "sysid/stage.hpp"

namespace {

using InitFn = void (*)(void*);
using StepFn = double (*)(void*, double, double);
using SizeFn = unsigned long (*)(void);

double MaxAbsDiff(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return 1e300;
  return (a - b).cwiseAbs().maxCoeff();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s MODEL.json LIB.so PREFIX DT\n", argv[0]);
    return 2;
  }
  const std::string prefix = argv[3];
  void* lib = dlopen(argv[2], RTLD_NOW | RTLD_LOCAL);
  if (lib == nullptr) {
    std::fprintf(stderr, "%s: %s\n", argv[2], dlerror());
    return 2;
  }
  // POSIX: a data pointer from dlsym converts to a function pointer.
  const auto init = reinterpret_cast<InitFn>(dlsym(lib, (prefix + "_init").c_str()));
  const auto step = reinterpret_cast<StepFn>(dlsym(lib, (prefix + "_step").c_str()));
  const auto size = reinterpret_cast<SizeFn>(dlsym(lib, (prefix + "_state_size").c_str()));
  if (init == nullptr || step == nullptr || size == nullptr) {
    std::fprintf(stderr, "%s: no %s_init, %s_step or %s_state_size\n", argv[2], prefix.c_str(),
                 prefix.c_str(), prefix.c_str());
    return 2;
  }
  // The caller-owned state, aligned for doubles.
  std::vector<double> state((size() + sizeof(double) - 1) / sizeof(double) + 1);
  init(state.data());

  const sysid::FrictionModel model = sysid::ReadModel(argv[1]);
  const sysid::StageParameters stage_parameters = sysid::StageParameters::Default();
  const double dt_s = 1.0 / stage_parameters.sample_rate_hz;
  if (std::stod(argv[4]) != dt_s) {
    std::fprintf(stderr, "the export's dt %s s is not the stage's control period %.17g s\n",
                 argv[4], dt_s);
    return 2;
  }
  const sysid::PositionReference reference =
      sysid::MakeStageProfile(stage_parameters, sysid::SmoothProfileOptions{});
  sysid::PiOptions pi;
  pi.sample_time_s = dt_s;

  sysid::VirtualStage exported_stage(stage_parameters, 1);
  const sysid::TrackingResult exported = sysid::RunClosedLoop(
      exported_stage, reference, pi,
      [&](double v_mps, double a_mps2) { return step(state.data(), v_mps, a_mps2); });

  sysid::FrictionInverseStepper stepper(model, dt_s);
  sysid::VirtualStage library_stage(stage_parameters, 1);
  const sysid::TrackingResult library = sysid::RunClosedLoop(
      library_stage, reference, pi,
      [&](double v_mps, double a_mps2) { return stepper.Step(v_mps, a_mps2); });

  sysid::InverseModels models;
  models.model = &model;
  sysid::VirtualStage playback_stage(stage_parameters, 1);
  const sysid::TrackingResult playback = sysid::RunClosedLoop(
      playback_stage, reference, pi,
      sysid::SchemeFeedforward(sysid::FeedforwardScheme::kAnalytic, reference, dt_s, models));

  const double de = MaxAbsDiff(exported.e_m, library.e_m);
  std::printf("closed loop, %ld samples at %g s: max |e| exported C %.6g m, library stepper "
              "%.6g m, playback %.6g m; max |e_C - e_stepper| = %.3g m (bound 1e-12 m), "
              "max |e_stepper - e_playback| = %.3g m\n",
              static_cast<long>(reference.t_s.size()), dt_s, exported.max_error_m,
              library.max_error_m, playback.max_error_m, de,
              MaxAbsDiff(library.e_m, playback.e_m));
  dlclose(lib);
  return de <= 1e-12 ? 0 : 1;
}
