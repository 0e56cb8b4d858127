#include <cmath>
#include <string>

#include "core/option_rule.hpp"
#include "sysid/error.hpp"
#include "sysid/model_stepper.hpp"

namespace sysid {

namespace {

double CheckedStep(double dt_s) {
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    internal::FailOption("FrictionInverseStepper", "dt_s", dt_s, "0 < dt_s < infinity");
  return dt_s;
}

const FrictionModel& Validated(const FrictionModel& model) {
  model.Validate();
  return model;
}

}  // namespace

FrictionInverseStepper::FrictionInverseStepper(const FrictionModel& model, double dt_s,
                                               long long max_steps)
    : model_(Validated(model)),
      dt_s_(CheckedStep(dt_s)),
      line_(dt_s, model.tau_s, max_steps) {}

}  // namespace sysid
