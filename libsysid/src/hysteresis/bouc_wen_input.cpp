// The input of the CVODE simulations between its samples: held, linear or band-limited.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>

#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"

namespace sysid::internal {

void CheckSamples(const Eigen::VectorXd& v, double dt_s, const char* kind, const char* what) {
  if (!(dt_s > 0) || !std::isfinite(dt_s))
    throw OptionsError(fmt::format("{}: the sample time dt_s = {} must be > 0", kind, dt_s),
                       "dt_s");
  for (Eigen::Index i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i]))
      throw InputError(
          fmt::format("{}: {}[{}]: expected a finite number, found {}", kind, what, i, v[i]));
}

SampledInput::SampledInput(const Eigen::VectorXd& u, double dt_s, InputInterpolation how)
    : u_(u), dt_(dt_s), how_(how) {
  if (how_ != InputInterpolation::kBandLimited || u.size() < 2) return;
  const Eigen::Index n = u.size();
  CheckBandLimitedWork(n, "bouc-wen");
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(static_cast<size_t>(n)), x;
  for (Eigen::Index i = 0; i < n; ++i) in[static_cast<size_t>(i)] = u[i];
  fft.fwd(x, in);
  const double nd = static_cast<double>(n);
  mean_ = x[0].real() / nd;
  omega_ = 2 * M_PI / (nd * dt_s);
  double largest = 0;
  for (const auto& c : x) largest = std::max(largest, std::abs(c));
  const Eigen::Index top = n / 2;
  for (Eigen::Index j = 1; j <= top; ++j) {
    std::complex<double> c = x[static_cast<size_t>(j)] / nd;
    if (2 * j == n) c *= 0.5;  // the Nyquist line: half of it on each side
    // Lines below 1e-15 of the largest are rounding noise of the FFT.
    if (std::abs(c) * nd <= 1e-15 * largest) continue;
    lines_.push_back(static_cast<int>(j));
    coeff_.push_back(c);
  }
  // Each evaluation sums every kept line, and CVODE evaluates a few to hundreds of times a
  // sample: lines x samples is the work's scale (a rough 4000-sample input, 2000 lines: 9 s).
  const double work = static_cast<double>(lines_.size()) * nd;
  if (work > kMaxBandLimitedWork)
    throw InputError(fmt::format(
        "bouc-wen: the band-limited input of {} samples keeps {} spectral lines: {:.3g} "
        "line-samples, more than the {:.0e} a simulation may evaluate (kMaxBandLimitedWork); "
        "use the linear or held input, or a shorter recording",
        n, lines_.size(), work, kMaxBandLimitedWork));
}

void SampledInput::Evaluate(double t, Eigen::Index k, double* u, double* du) const {
  const Eigen::Index n = u_.size();
  if (how_ != InputInterpolation::kBandLimited || n < 2) {
    k = std::clamp<Eigen::Index>(k, 0, n - 1);
    if (how_ == InputInterpolation::kHold || k + 1 >= n) {
      *u = u_[k];
      *du = 0;
      return;
    }
    const double slope = (u_[k + 1] - u_[k]) / dt_;
    *u = u_[k] + slope * (t - static_cast<double>(k) * dt_);
    *du = slope;
    return;
  }
  if (lines_.empty()) {
    *u = mean_;
    *du = 0;
    return;
  }
  const std::complex<double> step = std::polar(1.0, omega_ * t);
  std::complex<double> p = std::polar(1.0, omega_ * lines_[0] * t);
  int at = lines_[0];
  double su = 0, sdu = 0;
  for (size_t j = 0; j < lines_.size(); ++j) {
    for (; at < lines_[j]; ++at) p *= step;
    const std::complex<double> cp = coeff_[j] * p;
    su += cp.real();
    sdu -= omega_ * lines_[j] * cp.imag();  // Re(i w l c p) = -w l Im(c p)
  }
  *u = mean_ + 2 * su;
  *du = 2 * sdu;
}

bool PeriodicBandLimited(const Eigen::VectorXd& u, double* wrap_step, double* high_fraction) {
  const Eigen::Index n = u.size();
  *wrap_step = *high_fraction = NAN;
  if (n < 8 || FftWork(n) > kMaxFftWork) return false;
  double largest_step = 0;
  for (Eigen::Index i = 0; i + 1 < n; ++i)
    largest_step = std::max(largest_step, std::abs(u[i + 1] - u[i]));
  *wrap_step = std::abs(u[0] - u[n - 1]);
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(static_cast<size_t>(n)), x;
  const double mean = u.mean();
  for (Eigen::Index i = 0; i < n; ++i) in[static_cast<size_t>(i)] = u[i] - mean;
  fft.fwd(x, in);
  // Parseval: the lines above n/4 (a quarter of the sampling rate) against all of them.
  double high = 0, all = 0;
  for (Eigen::Index j = 1; j < n; ++j) {
    const double power = std::norm(x[static_cast<size_t>(j)]);
    all += power;
    if (std::min(j, n - j) > n / 4) high += power;
  }
  if (!(all > 0)) return false;
  *high_fraction = high / all;
  return *wrap_step <= largest_step && *high_fraction <= kBandLimitedPower;
}

}  // namespace sysid::internal
