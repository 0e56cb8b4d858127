// The input of the CVODE simulations between its samples: held, linear or band-limited.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <unsupported/Eigen/FFT>

#include "hysteresis/bouc_wen_internal.hpp"
#include "sysid/error.hpp"
#include "sysid/io.hpp"

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

SampledInput::SampledInput(const Eigen::VectorXd& u, double dt_s, InputInterpolation how,
                           double max_line_work, double max_table_values)
    : u_(u), dt_(dt_s), how_(how) {
  if (how_ != InputInterpolation::kBandLimited || u.size() < 2) return;
  CheckBandLimitedWork(u.size(), "bouc-wen");
  s_ = Spectrum(u, dt_s);
  fine_ = Grid(s_, u.size(), dt_s, max_line_work, max_table_values, &grid_error_bound_);
  if (fine_ > 0) Tabulate();
}

int SampledInput::GridPerSample(const Eigen::VectorXd& u, double dt_s, double max_line_work,
                                double max_table_values) {
  if (u.size() < 2) return 0;
  CheckBandLimitedWork(u.size(), "bouc-wen");
  double bound = 0;
  return Grid(Spectrum(u, dt_s), u.size(), dt_s, max_line_work, max_table_values, &bound);
}

SampledInput::Lines SampledInput::Spectrum(const Eigen::VectorXd& u, double dt_s) {
  const Eigen::Index n = u.size();
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> in(static_cast<size_t>(n)), x;
  for (Eigen::Index i = 0; i < n; ++i) in[static_cast<size_t>(i)] = u[i];
  fft.fwd(x, in);
  const double nd = static_cast<double>(n);
  Lines s;
  s.mean = x[0].real() / nd;
  s.omega = 2 * M_PI / (nd * dt_s);
  double largest = 0;
  for (const auto& c : x) largest = std::max(largest, std::abs(c));
  const Eigen::Index top = n / 2;
  for (Eigen::Index j = 1; j <= top; ++j) {
    std::complex<double> c = x[static_cast<size_t>(j)] / nd;
    if (2 * j == n) c *= 0.5;  // the Nyquist line: half of it on each side
    // Lines below 1e-15 of the largest are rounding noise of the FFT.
    if (std::abs(c) * nd <= 1e-15 * largest) continue;
    s.line.push_back(static_cast<int>(j));
    s.coeff.push_back(c);
  }
  return s;
}

// The grid: the smallest power of two L of points per sample whose Hermite bound is within
// kBandLimitedGridTolerance A.
int SampledInput::Grid(const Lines& s, Eigen::Index n, double dt_s, double max_line_work,
                       double max_table_values, double* bound_out) {
  *bound_out = 0;
  // Each evaluation of the sum costs every kept line, and CVODE evaluates a few to hundreds of
  // times a sample: lines x samples is the work's scale (4000 samples, 2000 lines: 9 s).
  const double work = static_cast<double>(s.line.size()) * static_cast<double>(n);
  if (s.line.empty() || work <= max_line_work) return 0;
  // A = sum |2 c_j| and |u^(6)| <= M6 = sum |2 c_j| w_j^6: the lines' own weights, so that
  // rounding-level lines near the Nyquist frequency do not refine the grid.
  double amplitude = 0, m6 = 0;
  for (size_t j = 0; j < s.line.size(); ++j) {
    const double a = 2 * std::abs(s.coeff[j]);
    amplitude += a;
    m6 += a * std::pow(s.omega * s.line[j], 6);
  }
  auto bound = [&](int points) { return std::pow(dt_s / points, 6) * m6 / 46080; };
  int L = 2;
  while (L < kMaxGridPerSample && bound(L) > kBandLimitedGridTolerance * amplitude) L *= 2;
  const double points = static_cast<double>(n) * L;
  if (3 * points > max_table_values || FftWork(n * L) > kMaxFftWork)
    throw InputError(fmt::format(
        "bouc-wen: the band-limited input of {} samples ({} spectral lines) would be tabulated "
        "at {} points a sample: 3 values (u, u', u'') at {:.4g} points, more than the {:.0e} a "
        "simulation may hold (kMaxSignalSamples), or an FFT of more than {:.0e} operations "
        "(kMaxFftWork); use the linear or held input, or a shorter recording",
        n, s.line.size(), L, points, max_table_values, kMaxFftWork));
  *bound_out = bound(L);
  return L;
}

// u, u' and u'' at the n L points of one period are inverse FFTs of the lines placed at their
// harmonic numbers (with their conjugates at n L - l, so the transforms are real): one transform
// gives u + i u', a second u''.
void SampledInput::Tabulate() {
  const Eigen::Index N = u_.size() * fine_;
  std::vector<std::complex<double>> first(static_cast<size_t>(N)), second(first.size()), out;
  const std::complex<double> i(0, 1);
  for (size_t j = 0; j < s_.line.size(); ++j) {
    const auto l = static_cast<size_t>(s_.line[j]);
    const double w = s_.omega * s_.line[j];
    const std::complex<double> c = s_.coeff[j], dc = i * w * c, d2c = -w * w * c;
    // 2 Re(a e^(i w l t)) is the pair (a at l, conj(a) at N - l); u and u' share a transform
    // as its real and imaginary parts.
    first[l] += c + i * dc;
    first[static_cast<size_t>(N) - l] += std::conj(c) + i * std::conj(dc);
    second[l] += d2c;
    second[static_cast<size_t>(N) - l] += std::conj(d2c);
  }
  Eigen::FFT<double> fft;
  fft.SetFlag(Eigen::FFT<double>::Unscaled);
  grid_.resize(static_cast<size_t>(3 * N));
  fft.inv(out, first);
  for (Eigen::Index m = 0; m < N; ++m) {
    grid_[static_cast<size_t>(3 * m)] = s_.mean + out[static_cast<size_t>(m)].real();
    grid_[static_cast<size_t>(3 * m + 1)] = out[static_cast<size_t>(m)].imag();
  }
  fft.inv(out, second);
  for (Eigen::Index m = 0; m < N; ++m)
    grid_[static_cast<size_t>(3 * m + 2)] = out[static_cast<size_t>(m)].real();
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
  if (s_.line.empty()) {
    *u = s_.mean;
    *du = 0;
    return;
  }
  if (fine_ > 0) {
    // Quintic Hermite between grid points m and m + 1 (one period, wrapped), at x in [0, 1].
    const Eigen::Index N = n * fine_;
    const double h = dt_ / fine_;
    const double pos = t / h;
    const double base = std::floor(pos);
    const double x = pos - base;
    Eigen::Index m = static_cast<Eigen::Index>(base) % N;
    if (m < 0) m += N;
    const double* a = &grid_[static_cast<size_t>(3 * m)];
    const double* b = &grid_[static_cast<size_t>(3 * ((m + 1) % N))];
    const double x2 = x * x, x3 = x2 * x, x4 = x3 * x, x5 = x4 * x;
    const double h0 = 1 - 10 * x3 + 15 * x4 - 6 * x5, h5 = 1 - h0;
    const double h1 = x - 6 * x3 + 8 * x4 - 3 * x5, h4 = -4 * x3 + 7 * x4 - 3 * x5;
    const double h2 = 0.5 * (x2 - 3 * x3 + 3 * x4 - x5), h3 = 0.5 * (x3 - 2 * x4 + x5);
    const double g0 = -30 * x2 + 60 * x3 - 30 * x4;  // dh0/dx; dh5/dx = -g0
    const double g1 = 1 - 18 * x2 + 32 * x3 - 15 * x4, g4 = -12 * x2 + 28 * x3 - 15 * x4;
    const double g2 = 0.5 * (2 * x - 9 * x2 + 12 * x3 - 5 * x4), g3 = 0.5 * (3 * x2 - 8 * x3 + 5 * x4);
    *u = a[0] * h0 + b[0] * h5 + h * (a[1] * h1 + b[1] * h4) + h * h * (a[2] * h2 + b[2] * h3);
    *du = (a[0] - b[0]) * g0 / h + a[1] * g1 + b[1] * g4 + h * (a[2] * g2 + b[2] * g3);
    return;
  }
  const std::complex<double> step = std::polar(1.0, s_.omega * t);
  std::complex<double> p = std::polar(1.0, s_.omega * s_.line[0] * t);
  int at = s_.line[0];
  double su = 0, sdu = 0;
  for (size_t j = 0; j < s_.line.size(); ++j) {
    for (; at < s_.line[j]; ++at) p *= step;
    const std::complex<double> cp = s_.coeff[j] * p;
    su += cp.real();
    sdu -= s_.omega * s_.line[j] * cp.imag();  // Re(i w l c p) = -w l Im(c p)
  }
  *u = s_.mean + 2 * su;
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
