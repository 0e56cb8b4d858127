// The fixed-step integrator of the mechanical form: the benchmark chain's Newmark/trapezoidal
// step at m steps per sample on the input between samples, without the chain's decimation. Second
// order (docs/benchmarks.md, "The default path: the fixed step"), with the chain's forward
// sensitivities; a fit chooses m by step doubling (docs/hysteresis.md, "Fixed step").
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "core/option_rule.hpp"
#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

namespace sysid::internal {

void CheckFixedStepWork(Eigen::Index rows, int substeps, InputInterpolation how, const char* kind) {
  const double steps = static_cast<double>(rows) * substeps;
  if (steps > kMaxSignalSamples)
    throw InputError(fmt::format(
        "{}: the fixed step on {} samples x {} steps per sample = {:.4g} steps, more than the "
        "{:.0e} it may integrate (sysid::kMaxSignalSamples); lower the substeps or shorten the "
        "recording",
        kind, rows, substeps, steps, kMaxSignalSamples));
  if (how == InputInterpolation::kBandLimited && FftWork(rows * substeps) > kMaxFftWork)
    throw InputError(fmt::format(
        "{}: the fixed step's band-limited input of {} samples x {} steps per sample costs {:.3g} "
        "FFT operations (the length times the sum of its prime factors), more than the {:.0e} "
        "allowed (kMaxFftWork); use the linear input, or a length with small prime factors",
        kind, rows, substeps, FftWork(rows * substeps), kMaxFftWork));
}

Eigen::VectorXd FixedStepInput(const Eigen::VectorXd& u, InputInterpolation how, int substeps) {
  const Eigen::Index n = u.size();
  if (how == InputInterpolation::kHold)
    internal::FailOption("BoucWenSimulationOptions", "input", "hold",
                         "the fixed-step integrator takes a linear or band-limited input (use "
                         "cvode for a held one)");
  if (n == 0) return u;
  const Eigen::Index nf = (n - 1) * substeps + 1;
  if (how == InputInterpolation::kBandLimited) return UpsampleBandLimited(u, substeps).head(nf);
  Eigen::VectorXd uf(nf);
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const double step = (u[k + 1] - u[k]) / substeps;
    for (int j = 0; j < substeps; ++j) uf[k * substeps + j] = u[k] + step * j;
  }
  uf[nf - 1] = u[n - 1];
  return uf;
}

Eigen::VectorXd FixedStepOutput(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& uf,
                                double dt_s, int substeps) {
  const Eigen::Index nf = uf.size();
  Eigen::VectorXd yf(nf);
  NewmarkState s;
  NewmarkBoucWen(p, uf.data(), nf, dt_s / substeps, &s, yf.data());
  const Eigen::Index n = nf > 0 ? (nf - 1) / substeps + 1 : 0;
  Eigen::VectorXd y(n);
  for (Eigen::Index k = 0; k < n; ++k) y[k] = yf[k * substeps];
  return y;
}

void FixedStepOutputSensitivity(const MechanicalBoucWenParameters& p, const Eigen::VectorXd& uf,
                                double dt_s, int substeps, bool with_nu, Eigen::VectorXd* y,
                                Eigen::MatrixXd* dy_dp) {
  NewmarkJacobian s;
  NewmarkSensitivity(p, uf, dt_s / substeps, substeps, with_nu, y, &s);
  *dy_dp = s.transpose();
}

double StepDoublingError(const Eigen::VectorXd& y_m, const Eigen::VectorXd& y_2m) {
  const double n = static_cast<double>(std::max<Eigen::Index>(y_m.size(), 1));
  return 4.0 / 3.0 * std::sqrt((y_m - y_2m).squaredNorm() / n);
}

Eigen::VectorXd FixedStepStacked(const MechanicalBoucWenParameters& p, const SampledRecordings& in,
                                 InputInterpolation how, int m) {
  Eigen::Index n = 0;
  for (const Eigen::VectorXd* u : in.u) {
    CheckFixedStepWork(u->size(), m, how, "bouc-wen");
    n += u->size();
  }
  Eigen::VectorXd y(n);
  Eigen::Index at = 0;
  for (size_t k = 0; k < in.u.size(); ++k) {
    const Eigen::VectorXd& u = *in.u[k];
    y.segment(at, u.size()) = FixedStepOutput(p, FixedStepInput(u, how, m), in.dt_s[k], m);
    at += u.size();
  }
  return y;
}

int ChooseFixedSteps(const MechanicalBoucWenParameters& p, const SampledRecordings& in,
                     InputInterpolation how, double tolerance_m, double* estimate_m) {
  auto simulate = [&](int m) {
    try {
      return FixedStepStacked(p, in, how, m);
    } catch (const NumericalError&) {
      return Eigen::VectorXd();  // Newton diverged: too coarse
    } catch (const InputError& e) {
      throw NumericalError(fmt::format(
          "bouc-wen: the fixed step did not reach its tolerance {:.3g} m (step doubling) before "
          "its work bound: {}; fit with --integrator cvode, or a larger --step-tolerance",
          tolerance_m, e.what()));
    }
  };
  Eigen::VectorXd coarse = simulate(2);
  double estimate = std::numeric_limits<double>::infinity();
  for (int m = 2; m <= 512; m *= 2) {
    const Eigen::VectorXd fine = simulate(2 * m);
    estimate = coarse.size() > 0 && fine.size() > 0 ? StepDoublingError(coarse, fine)
                                                    : std::numeric_limits<double>::infinity();
    if (estimate <= tolerance_m) {
      *estimate_m = estimate;
      return m;
    }
    coarse = fine;
  }
  throw NumericalError(fmt::format(
      "bouc-wen: the fixed step's step-doubling error at 512 steps per sample is {:.3g} m, above "
      "its tolerance {:.3g} m; fit with --integrator cvode, or a larger --step-tolerance",
      estimate, tolerance_m));
}

}  // namespace sysid::internal
